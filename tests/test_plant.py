# SPDX-License-Identifier: BSD-2-Clause
"""The plant FMU alone (pmdplant, fmu_src/plant, modelDescription/plant.csv): its
interface as the table declares it in FMI 2 and 3, the motor's physics against
closed-form solutions, its fixed-step integration and determinism, the encoder,
the outputs that change only in doStep, FMU states and the refusals of bad
calls with a message."""

import csv
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

import pmdfmu

TABLE = Path(__file__).resolve().parent.parent / "modelDescription" / "plant.csv"
ROWS = list(csv.DictReader(open(TABLE, newline="")))
START = {r["name"]: float(r["start"]) for r in ROWS if r["start"]}
FULL_SCALE = 32768  # 2^15 counts of the chip's motor command (docs/servo.md)


def plant_fmu(fmi_version: int) -> Path:
    return pmdfmu.default_fmu(fmi_version).with_name(f"pmdplant-fmi{fmi_version}.fmu")


class Plant:
    """One pmdplant instance through FMPy, variables by name; the FMU's log
    messages in `messages`."""

    def __init__(self, fmi_version=2, start=None, start_time=0.0, initialize=True):
        self.fmi_version = fmi_version
        path = plant_fmu(fmi_version)
        md = read_model_description(path)
        self.variables = {v.name: v for v in md.modelVariables}
        self.unzipdir = extract(path)
        self.messages = []
        kwargs = dict(guid=md.guid, unzipDirectory=self.unzipdir, modelIdentifier="pmdplant", instanceName="plant")
        if fmi_version == 2:
            self.fmu = FMU2Slave(**kwargs)
            self._callbacks = fmi2CallbackFunctions()
            self._callbacks.logger = fmi2CallbackLoggerTYPE(
                lambda env, name, status, category, message: self.messages.append(message.decode().replace("%%", "%"))
            )
            self.fmu.instantiate(callbacks=self._callbacks)
            self.fmu.setupExperiment(startTime=start_time)
        else:
            self.fmu = FMU3Slave(**kwargs)
            self.fmu.instantiate(
                logMessage=lambda env, status, category, message: self.messages.append(message.decode())
            )
        self.time = start_time
        for name, value in (start or {}).items():
            self.set(name, value)
        if initialize:
            self.enter()
            self.exit()

    def enter(self):
        if self.fmi_version == 2:
            self.fmu.enterInitializationMode()
        else:
            self.fmu.enterInitializationMode(startTime=self.time)

    def exit(self):
        self.fmu.exitInitializationMode()

    def set(self, name, value):
        v = self.variables[name]
        getattr(self.fmu, "set" + v.type)([v.valueReference], [value])

    def get(self, name):
        v = self.variables[name]
        return getattr(self.fmu, "get" + v.type)([v.valueReference])[0]

    def outputs(self):
        return {n: self.get(n) for n, v in self.variables.items() if v.causality == "output"}

    def step(self, h, count=1):
        for _ in range(count):
            self.fmu.doStep(self.time, h)
            self.time += h
        return self

    def state(self) -> bytes:
        if self.fmi_version == 2:
            s = self.fmu.getFMUstate()
            data = bytes(self.fmu.serializeFMUstate(s))
            self.fmu.freeFMUstate(s)
        else:
            s = self.fmu.getFMUState()
            data = bytes(self.fmu.serializeFMUState(s))
            self.fmu.freeFMUState(s)
        return data

    def restore(self, data: bytes):
        if self.fmi_version == 2:
            s = self.fmu.deSerializeFMUstate(data)
            self.fmu.setFMUstate(s)
            self.fmu.freeFMUstate(s)
        else:
            s = self.fmu.deserializeFMUState(data)
            self.fmu.setFMUState(s)
            self.fmu.freeFMUState(s)

    def close(self):
        self.fmu.freeInstance()
        shutil.rmtree(self.unzipdir, ignore_errors=True)


@pytest.fixture(params=[2, 3], ids=["fmi2", "fmi3"])
def fmi_version(request):
    return request.param


@pytest.fixture
def plants():
    """Plant(...) that closes each instance it made."""
    made = []

    def make(*args, **kwargs):
        made.append(Plant(*args, **kwargs))
        return made[-1]

    yield make
    for p in made:
        p.close()


def motor(p=START):
    """The motor's constants: inertia J, damping c (back-EMF through the
    armature and viscous friction), torque per volt, counts per radian."""
    J = p["rotorInertia"] + p["loadInertia"]
    c = p["torqueConstant"] ** 2 / p["armatureResistance"] + p["viscousFriction"]
    return J, c, p["torqueConstant"] / p["armatureResistance"], 4 * p["encoderLines"] / (2 * math.pi)


# ---- the interface -------------------------------------------------------------------


def test_both_model_descriptions_validate_and_declare_the_table(fmi_version):
    assert validate_fmu(str(plant_fmu(fmi_version))) == []
    md = read_model_description(plant_fmu(fmi_version))
    declared = {v.name: v for v in md.modelVariables}
    for r in ROWS:
        if fmi_version == 2 and not r["type"]:
            assert r["name"] not in declared  # time: FMI 2's independent variable is implicit
            continue
        v = declared.pop(r["name"])
        assert v.valueReference == int(r["vr"])
        assert v.type == (r["type"] if fmi_version == 2 else r["fmi3Type"])
        assert (v.causality, v.variability) == (r["causality"], r["variability"])
        assert (v.unit or "") == r["unit"]
        if r["start"]:
            assert float(v.start) == float(r["start"])
    assert not declared
    assert md.coSimulation.modelIdentifier == "pmdplant"
    assert md.coSimulation.canHandleVariableCommunicationStepSize
    assert md.coSimulation.canGetAndSetFMUstate and md.coSimulation.canSerializeFMUstate
    if fmi_version == 3:
        assert float(md.coSimulation.fixedInternalStepSize) == START["internalStep"]
    units = {u.name for u in md.unitDefinitions}
    assert {r["unit"] for r in ROWS if r["unit"]} <= units


@pytest.mark.slow
def test_fmu_manipulation_toolboxs_checker_passes(fmi_version):
    """fmutool -check (fmu-manipulation-toolbox, pyproject's test extra): outside CI a missing
    package skips, in CI it fails."""
    try:
        import fmu_manipulation_toolbox  # noqa: F401
    except ImportError as e:
        if os.environ.get("CI"):
            raise
        pytest.skip(f"fmu-manipulation-toolbox not installed ({e}): pip install '.[test]'")
    out = subprocess.run(
        [sys.executable, "-m", "fmu_manipulation_toolbox", "-input", str(plant_fmu(fmi_version)), "-check"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    log = out.stdout + out.stderr
    assert out.returncode == 0, log
    assert f"This FMU seems to be compliant with FMI-{fmi_version}.0." in log
    assert f"No semantic error against the FMI-{fmi_version} standard." in log
    assert not re.search(r"^(ERROR|WARNING)", log, re.M), log


def test_no_output_depends_on_an_input_without_a_step(fmi_version):
    """encoderCount, angle, speed, current and voltage change only in doStep, and the
    model structure says so: dependencies="" for every output, and in initialization only
    the parameters the table names. So chip + plant is no algebraic loop."""
    with zipfile.ZipFile(plant_fmu(fmi_version)) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    structure = root.find("ModelStructure")
    if fmi_version == 2:
        names = [sv.get("name") for sv in root.find("ModelVariables")]
        outputs = {names[int(u.get("index")) - 1]: u.get("dependencies") for u in structure.find("Outputs")}
        initial = {
            names[int(u.get("index")) - 1]: sorted(names[int(i) - 1] for i in u.get("dependencies").split())
            for u in structure.find("InitialUnknowns")
        }
    else:
        by_vr = {v.get("valueReference"): v.get("name") for v in root.find("ModelVariables")}
        outputs = {by_vr[u.get("valueReference")]: u.get("dependencies") for u in structure.iter("Output")}
        initial = {
            by_vr[u.get("valueReference")]: sorted(by_vr[i] for i in u.get("dependencies").split())
            for u in structure.iter("InitialUnknown")
        }
    table_outputs = [r for r in ROWS if r["causality"] == "output"]
    assert outputs == {r["name"]: "" for r in table_outputs}
    assert initial == {r["name"]: sorted(r["initialDependencies"].split()) for r in table_outputs}
    assert initial["encoderCount"] == ["encoderLines", "initialAngle"]


def test_inputs_move_no_output_until_the_step(plants, fmi_version):
    p = plants(fmi_version, initialize=False)
    p.enter()
    before = p.outputs()
    p.set("motorCommand", 20000)
    p.set("loadTorque", 0.5)
    assert p.outputs() == before  # initialization: no feedthrough
    p.exit()
    p.step(1e-4, 10)
    before = p.outputs()
    p.set("motorCommand", -20000)
    p.set("loadTorque", -0.5)
    assert p.outputs() == before  # step mode: no feedthrough
    p.step(1e-4)
    assert p.outputs() != before


def test_outputs_in_initialization_follow_the_parameters_they_declare(plants, fmi_version):
    p = plants(fmi_version, initialize=False)
    p.enter()
    cpr = 4 * START["encoderLines"]
    p.set("initialAngle", 2 * math.pi * 2.25 / cpr)  # two and a quarter counts
    p.set("initialSpeed", 3.0)
    assert (p.get("angle"), p.get("speed"), p.get("encoderCount")) == (2 * math.pi * 2.25 / cpr, 3.0, 2)
    p.set("encoderLines", 2 * int(START["encoderLines"]))
    assert p.get("encoderCount") == 4
    assert (p.get("current"), p.get("voltage")) == (0.0, 0.0)  # no step yet


# ---- the physics -----------------------------------------------------------------------


def test_steady_speed_and_current_are_the_closed_form_ones(plants, fmi_version):
    """J dw/dt = k V/R + loadTorque - c w - Tc: at full scale the speed settles at
    (k V/R - Tc) / c, the current at (V - k w) / R, which balances friction; the
    fixed point of the implicit step is exactly that speed."""
    J, c, k_over_R, _ = motor()
    p = plants(fmi_version, {"motorOutput": 1.0})
    p.step(1e-3, 1000)  # 1 s, over 30 time constants
    w = (k_over_R * START["supplyVoltage"] - START["coulombFriction"]) / c
    assert p.get("speed") == pytest.approx(w, rel=1e-12)
    current = (START["supplyVoltage"] - START["torqueConstant"] * p.get("speed")) / START["armatureResistance"]
    assert p.get("current") == pytest.approx(current, rel=1e-12)
    assert START["torqueConstant"] * p.get("current") == pytest.approx(
        START["viscousFriction"] * w + START["coulombFriction"], rel=1e-9
    )
    assert p.get("voltage") == START["supplyVoltage"]


def test_a_load_torque_shifts_the_steady_speed(plants):
    J, c, k_over_R, _ = motor()
    p = plants(2, {"motorCommand": FULL_SCALE // 2, "loadTorque": -0.05})
    p.step(1e-3, 1000)
    V = START["supplyVoltage"] * (FULL_SCALE // 2) / FULL_SCALE
    assert p.get("speed") == pytest.approx((k_over_R * V - 0.05 - START["coulombFriction"]) / c, rel=1e-12)


def test_spin_up_follows_the_exponential_within_the_implicit_eulers_error(plants):
    """w(t) = w_ss (1 - exp(-t/tau)), tau = J/c. Backward Euler with step h errs by
    at most about w_ss h / (2 e tau); halving the internal step halves the error."""
    J, c, k_over_R, _ = motor()
    tau = J / c
    w_ss = (k_over_R * START["supplyVoltage"] - START["coulombFriction"]) / c
    errors = []
    for h in (START["internalStep"], START["internalStep"] / 2):
        p = plants(2, {"motorOutput": 1.0, "internalStep": h})
        worst = 0.0
        for n in range(1, 301):  # 0.03 s, one time constant
            p.step(1e-4)
            worst = max(worst, abs(p.get("speed") - w_ss * (1 - math.exp(-n * 1e-4 / tau))))
        assert worst <= w_ss * h / (2 * math.e * tau) * 1.05
        errors.append(worst)
    assert errors[1] == pytest.approx(errors[0] / 2, rel=0.02)


def test_coulomb_friction_holds_the_shaft_below_breakaway_and_stops_it_without_chatter(plants, fmi_version):
    J, c, k_over_R, _ = motor()
    breakaway = START["coulombFriction"] / (k_over_R * START["supplyVoltage"]) * FULL_SCALE
    p = plants(fmi_version, {"motorCommand": math.floor(breakaway)})
    p.step(1e-4, 100)
    assert (p.get("speed"), p.get("angle"), p.get("encoderCount")) == (0.0, 0.0, 0)
    p.fmu.terminate()
    # spinning at w0, no drive: J dw/dt = -c w - Tc stops the shaft at tau ln(1 + c w0 / Tc) and it stays
    w0 = 300.0
    q = plants(fmi_version, {"initialSpeed": w0})
    stop = J / c * math.log(1 + c * w0 / START["coulombFriction"])
    speeds = []
    for _ in range(2000):
        q.step(1e-4)
        speeds.append(q.get("speed"))
    first_zero = speeds.index(0.0) + 1
    assert abs(first_zero * 1e-4 - stop) <= 2e-4
    assert all(s > 0 for s in speeds[: first_zero - 1]) and set(speeds[first_zero - 1 :]) == {0.0}


def test_the_amplifier_scales_the_command_and_minus_32768_is_minus_full_scale(plants):
    p = plants(2, {"motorCommand": 16384})
    p.step(1e-4)
    assert p.get("voltage") == START["supplyVoltage"] * 16384 / FULL_SCALE
    p.set("motorCommand", -32768)
    p.step(1e-4)
    assert p.get("voltage") == -START["supplyVoltage"]


def test_the_encoder_counts_4_per_line_floors_and_wraps_at_32_bits(plants, fmi_version):
    cpr = 4 * START["encoderLines"]
    cases = [
        (0.0, 0),
        (-1e-9, -1),
        (2 * math.pi * 0.5 / cpr, 0),
        (2 * math.pi * 1.5 / cpr, 1),
        (2 * math.pi * (cpr + 0.5) / cpr, cpr),
        (-2 * math.pi * (cpr + 0.5) / cpr, -cpr - 1),
        (2 * math.pi * (2**31 + 5.5) / cpr, -(2**31) + 5),
        (2 * math.pi * (-(2**31) - 1.5) / cpr, 2**31 - 2),
    ]
    for angle, count in cases:
        p = plants(fmi_version, {"initialAngle": angle})
        assert p.get("encoderCount") == count, angle
        p.step(1e-4)  # at rest: the same count after a step
        assert p.get("encoderCount") == count, angle


# ---- integration steps and determinism ----------------------------------------------------


def run(fmi_version, steps, start_time=0.0, plants=None):
    """Outputs after each of the given communication steps, a drive that reverses."""
    p = plants(fmi_version, {"motorCommand": 12000}, start_time=start_time)
    out = []
    for i, h in enumerate(steps):
        if i == len(steps) // 2:
            p.set("motorCommand", -9000)
        p.step(h)
        out.append(p.outputs())
    return out


def test_results_are_the_same_in_both_fmi_versions_and_for_any_start_time(plants):
    steps = [1e-4] * 400
    a = run(2, steps, plants=plants)
    assert run(3, steps, plants=plants) == a
    assert run(2, steps, start_time=12.5, plants=plants) == a


def test_a_step_advances_by_whole_internal_steps_so_splits_on_the_grid_agree(plants, fmi_version):
    fine = run(fmi_version, [1e-4] * 400, plants=plants)
    coarse = run(fmi_version, [2e-4] * 200, plants=plants)
    assert coarse == fine[1::2]
    mixed = run(fmi_version, [1e-4, 3e-4] * 100, plants=plants)  # 3e-4 / 1e-5 is 29.999999999999996
    assert mixed[1::2] == fine[3::4]


def test_a_rest_shorter_than_an_internal_step_is_one_shorter_step(plants):
    """1.5e-5 with internal steps of 1e-5: one whole step and one of the 5e-6 left,
    each the implicit step (J + h c) w' = J w + h (k V/R - Tc)."""
    J, c, k_over_R, _ = motor()
    drive = k_over_R * START["supplyVoltage"] - START["coulombFriction"]
    p = plants(2, {"motorOutput": 1.0})
    p.step(1.5e-5)
    w, angle = 0.0, 0.0
    for h in (1e-5, 1.5e-5 - 1e-5):
        w = (J * w + h * drive) / (J + h * c)
        angle += h * w
    assert p.get("speed") == pytest.approx(w, rel=1e-14)
    assert p.get("angle") == pytest.approx(angle, rel=1e-14)


def test_fmu_states_restore_the_run_bit_for_bit(plants, fmi_version):
    p = plants(fmi_version, {"motorCommand": 12000, "loadInertia": 3e-5})
    p.step(1e-4, 50)
    saved, t = p.state(), p.time
    p.step(1e-4, 50)
    after = p.outputs()
    p.set("motorCommand", 0)
    p.step(1e-4, 20)
    p.restore(saved)
    p.time = t
    p.step(1e-4, 50)
    assert p.outputs() == after
    other = plants(fmi_version)  # a state carries the parameters too
    other.restore(saved)
    other.time = t
    other.step(1e-4, 50)
    assert other.outputs() == after


@pytest.mark.parametrize(
    "corrupt, message",
    [
        (lambda b: b[:-1], "bytes"),
        (lambda b: b"x" + b[1:], "not a state of this FMU"),
        (lambda b: b[:-8] + np.float64(np.nan).tobytes(), "is not in"),
    ],
)
def test_a_forged_state_is_refused_with_a_message(plants, fmi_version, corrupt, message):
    p = plants(fmi_version, {"motorCommand": 12000})
    p.step(1e-4, 10)
    good = p.state()
    with pytest.raises(FMICallException):
        p.restore(corrupt(good))
    assert any(message in m for m in p.messages), p.messages
    p.restore(good)


# ---- refusals -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda p: p.set("motorCommand", 40000), "motorCommand = 40000 is not in -32768 .. 32767"),
        (lambda p: p.set("encoderCount", 3), "encoderCount is an output and cannot be set"),
        (lambda p: p.set("armatureResistance", 1.0), "armatureResistance, a parameter, cannot be set in step mode"),
        (lambda p: p.set("loadTorque", float("nan")), "loadTorque = nan is not in"),
        (lambda p: p.fmu.setReal([999], [1.0]), "no variable has value reference 999"),
        (lambda p: p.fmu.setReal([20], [1.0]), "value reference 20 (motorCommand) is of type Integer"),
        (lambda p: p.fmu.doStep(1.0, 1e-4), "communication point 1 is not the current time 0"),
        (lambda p: p.fmu.doStep(0.0, 0.0), "the step size must be finite and > 0"),
        (lambda p: p.fmu.doStep(0.0, 1e6), "internal steps"),
        (lambda p: p.fmu.getBoolean([1]), "no variable of this type has value reference 1"),
        (lambda p: p.fmu.setDebugLogging(True, ["nonsense"]), 'unknown log category "nonsense"'),
    ],
)
def test_fmi2_refuses_bad_calls_naming_what_and_why(plants, call, message):
    p = plants(2)
    before = p.state()
    with pytest.raises(FMICallException):
        call(p)
    assert any(message in m for m in p.messages), p.messages
    assert p.state() == before


def test_parameters_out_of_range_are_refused_before_initialization(plants, fmi_version):
    p = plants(fmi_version, initialize=False)
    for name, value in [
        ("armatureResistance", 0.0),
        ("rotorInertia", 0.0),
        ("internalStep", 0.0),
        ("supplyVoltage", -1.0),
        ("encoderLines", 0),
    ]:
        with pytest.raises(FMICallException):
            p.set(name, value)
        assert any(m.startswith(f"fmi{fmi_version}Set") and f"{name} = " in m for m in p.messages), name
    p.enter()
    p.exit()
    p.step(1e-4)
    assert p.get("speed") == 0.0


def test_a_step_that_would_leave_doubles_range_is_refused_and_changes_nothing(plants, fmi_version):
    p = plants(
        fmi_version,
        {
            "initialSpeed": 1.7e308,
            "loadTorque": 1e300,
            "rotorInertia": 1e-12,
            "loadInertia": 0.0,
            "torqueConstant": 0.0,
            "viscousFriction": 0.0,
        },
    )
    before = p.outputs()
    with pytest.raises(FMICallException):
        p.fmu.doStep(0.0, 1e-4)
    assert any("leaves the motor's state not finite" in m for m in p.messages), p.messages
    assert p.outputs() == before


def test_calls_out_of_their_state_are_refused(plants, fmi_version):
    p = plants(fmi_version, initialize=False)
    with pytest.raises(FMICallException):
        p.get("speed")
    with pytest.raises(FMICallException):
        p.fmu.doStep(0.0, 1e-4)
    assert any("not allowed in the instantiated state" in m for m in p.messages)


def test_reset_brings_back_the_start_values(plants, fmi_version):
    p = plants(fmi_version, {"motorCommand": 5000, "loadInertia": 1e-4})
    p.step(1e-4, 10)
    p.fmu.reset()
    p.time = 0.0
    if fmi_version == 2:
        p.fmu.setupExperiment(startTime=0.0)
    p.enter()
    assert p.get("loadInertia") == START["loadInertia"] and p.get("motorCommand") == 0
    assert (p.get("angle"), p.get("speed")) == (0.0, 0.0)


# ---- docs/systems.md -------------------------------------------------------------------------

DOC = TABLE.parent.parent / "docs" / "systems.md"


def test_the_docs_variable_table_is_plant_csv():
    rows = re.findall(r"^\| `(\w+)` \| (\w+) \|([^|]*)\|([^|]*)\|", DOC.read_text(), re.M)
    documented = {name: (causality, unit.strip(), start.strip()) for name, causality, unit, start in rows}
    assert documented == {
        r["name"]: (r["causality"], r["unit"], r["start"]) for r in ROWS if r["causality"] != "independent"
    }


def test_the_docs_counts_and_cycles_follow_from_the_start_values():
    """docs/systems.md's table of the start values in the chip's counts and 1e-4 s cycles."""
    J, c, k_over_R, counts_per_rad = motor()
    cycle = 1e-4
    acceleration = k_over_R * START["supplyVoltage"] / J
    no_load = (k_over_R * START["supplyVoltage"] - START["coulombFriction"]) / c
    text = DOC.read_text()
    for fact in (
        f"{acceleration:.0f} rad/s², a_full = {acceleration * counts_per_rad * cycle**2:.3f} counts/cycle²",
        f"{J / c:.4f} s, tau = {J / c / cycle:.0f} cycles",
        f"{no_load:.0f} rad/s ({no_load * 60 / (2 * math.pi):.0f} rpm), "
        f"{no_load * counts_per_rad * cycle:.0f} counts/cycle",
        f"{START['coulombFriction'] / (k_over_R * START['supplyVoltage']) * FULL_SCALE:.0f} counts",
        f"{10 / counts_per_rad / cycle:.1f} rad/s ({10 / counts_per_rad / cycle * 60 / (2 * math.pi):.0f} rpm)",
        f"Kvff = 32768 / (a_full tau) = {32768 / (acceleration * counts_per_rad * cycle**2 * J / c / cycle):.0f}",
        f"Kaff = 32768 / a_full = {32768 / (acceleration * counts_per_rad * cycle**2):.0f}",
        f"4 Kd a_full / 32768 = {4 * 4000 * acceleration * counts_per_rad * cycle**2 / 32768:.2f}",
    ):
        assert fact in text, fact


def test_the_real_motor_output_drives_as_the_integer_command_does(plants, fmi_version):
    """motorOutput (a fraction of full scale, the chip's axisN.motorOutput: motorCommand / 2^15) and
    motorCommand / 32768 are one input: the chip's two outputs of one command give the same shaft, bit
    for bit, whatever the command; the sum saturates at -1 .. 1."""
    for command in (-32768, -12345, -1, 1, 364, 16383, 32767):
        by_word = plants(fmi_version, {"motorCommand": command}).step(1e-4, 50)
        by_fraction = plants(fmi_version, {"motorOutput": command / FULL_SCALE}).step(1e-4, 50)
        assert by_fraction.outputs() == by_word.outputs(), command
    both = plants(fmi_version, {"motorOutput": 1.0, "motorCommand": 32767}).step(1e-4, 1)
    assert both.get("voltage") == START["supplyVoltage"]
    both = plants(fmi_version, {"motorOutput": -1.0, "motorCommand": -32768}).step(1e-4, 1)
    assert both.get("voltage") == -START["supplyVoltage"]


def test_the_plant_declares_the_chips_cycle_as_its_step_and_default_fmu_finds_it(fmi_version):
    assert pmdfmu.default_fmu(fmi_version, "plant") == plant_fmu(fmi_version)
    md = read_model_description(str(pmdfmu.default_fmu(fmi_version, "plant")))
    assert md.defaultExperiment.stepSize == "0.0001"
    assert {v.name: (v.type, v.unit, v.min, v.max) for v in md.modelVariables}["motorOutput"] == (
        "Real" if fmi_version == 2 else "Float64",
        "1",
        "-1",
        "1",
    )
    if fmi_version == 3:
        assert float(md.coSimulation.fixedInternalStepSize) == START["internalStep"]


def test_the_cli_prints_the_plants_path(capsys):
    from pmdfmu.cli import main

    assert main(["path", "plant", "--fmi", "3"]) == 0
    assert capsys.readouterr().out.strip() == str(pmdfmu.default_fmu(3, "plant"))
    assert pmdfmu.default_fmu("plant") == pmdfmu.default_fmu(2, "plant")
