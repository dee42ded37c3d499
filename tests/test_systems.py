# SPDX-License-Identifier: BSD-2-Clause
"""Chip + plant as a system (docs/systems.md): the servo loop of
examples/systems/SystemStructure.ssd closed through the plant FMU, as an SSP run by
FMPy's SSP support and by libcosim, as a container FMU run by FMPy, and by a plain
FMPy master stepping Gauss-Seidel or Jacobi.

Every master but the Gauss-Seidel one is Jacobi: each component steps on the
values its inputs had after the step before, so the plant turns the chip's
command one cycle later than in Gauss-Seidel, where the plant steps after the
chip with the command of the same cycle (as examples/closed_loop.py does). The
Jacobi runs are equal bit for bit whatever the master, FMI 2 or 3; the
Gauss-Seidel run differs from them; each is pinned, and both settle the move."""

import csv
import functools
import os
import re
import subprocess
import sys
import zipfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.ssp.ssd import read_ssd
from fmpy.validation import validate_fmu

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT / "examples" / "systems"), str(ROOT / "examples")]
import closed_loop  # noqa: E402  examples/closed_loop.py: docs/servo.md's suggested gains
import systems  # noqa: E402  examples/systems/systems.py

pytestmark = pytest.mark.slow  # tests/README.md: compiles programs or runs the CLI; -m "not slow" leaves it out

JACOBI = ("jacobi", "fmpy-ssp", "libcosim", "container")
# What each algorithm makes of the move: motion complete after this step, the largest
# following error in counts (commanded position minus the encoder count the cycle sampled)
PINNED = {"gauss-seidel": dict(complete=1530, following=5), "jacobi": dict(complete=1530, following=7)}


def libcosim():
    """libcosimpy; outside CI a missing one skips, in CI (pyproject's test extra) it fails."""
    try:
        import libcosimpy  # noqa: F401
    except (ImportError, OSError) as e:
        if os.environ.get("CI"):
            raise
        pytest.skip(f"libcosimpy not installed ({e}): pip install '.[test]'")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    out = tmp_path_factory.mktemp("systems")
    return {
        "ssp": systems.build_ssp(out / "servoLoop.ssp"),
        "container": systems.build_container(out / "servoLoop.fmu"),
    }


@pytest.fixture(scope="module")
def runs(built):
    """run(master, fmi_version=2) -> (result, log messages), each run once."""

    @functools.lru_cache(maxsize=None)
    def run(master, fmi_version=2):
        messages = []
        log = lambda instance, status, message: messages.append((instance, status, message))  # noqa: E731
        if master in ("gauss-seidel", "jacobi"):
            result = systems.run_master(master, fmi_version, log=log)
        elif master == "container":
            result = systems.run_container(built["container"], log=log)
        elif master == "fmpy-ssp":
            result = systems.run_fmpy_ssp(built["ssp"])
        else:
            libcosim()
            result = systems.run_libcosim(built["ssp"])
        return result, messages

    return run


# ---- the system's files ----------------------------------------------------------------


def test_the_ssp_holds_the_ssd_the_fmus_and_the_chips_parameter_values(built):
    ssd = read_ssd(str(built["ssp"]))  # FMPy validates the .ssd and .ssv against the SSP schemas
    components = {c.name: c for c in ssd.system.elements}
    assert {n: c.source for n, c in components.items()} == {
        "chip": "resources/move.fmu",
        "plant": "resources/pmdplant.fmu",
    }
    # the obvious wiring: Real to Real, a fraction of full scale
    assert [(c.startElement, c.startConnector, c.endElement, c.endConnector) for c in ssd.system.connections] == [
        ("chip", "axis1.motorOutput", "plant", "motorOutput"),
        ("plant", "encoderCount", "chip", "axis1.actualPosition"),
    ]
    (values,) = components["chip"].parameterBindings[0].parameterValues
    assert {p.name: (p.type, p.value) for p in values.parameters} == {"loopback": ("Boolean", "false")}
    with zipfile.ZipFile(built["ssp"]) as z:
        for source in ("resources/move.fmu", "resources/pmdplant.fmu"):
            assert z.read(source) == systems.fmu_of(source, 2).read_bytes()
    # the profile travels inside the chip's FMU: no String to set
    chip = read_model_description(str(systems.fmu_of("resources/move.fmu", 2)))
    assert chip.modelName == "PMDMotionProcessor.move"
    assert next(v.start for v in chip.modelVariables if v.name == "script") == "profile/move.script"
    with zipfile.ZipFile(systems.fmu_of("resources/move.fmu", 2)) as z:
        assert z.read("resources/profile/move.script") == systems.SCRIPT.read_bytes()


def test_the_integer_wire_of_a_16_bit_bus_is_the_other_motor_wire():
    system = systems.read_system(motor="motorCommand")
    assert [(a.path, b.path) for a, b in system.connections] == [
        ("chip.axis1.motorCommand", "plant.motorCommand"),
        ("plant.encoderCount", "chip.axis1.actualPosition"),
    ]
    assert [c.path for c in system.outputs] == [c.path for c in systems.read_system().outputs]
    with pytest.raises(ValueError, match="motor: motorOutput or motorCommand"):
        systems.read_system(motor="voltage")


def test_fmpys_ssp_master_sets_a_false_boolean_true_so_run_fmpy_ssp_sets_booleans_itself():
    """docs/tools.md, FMPy: fmpy.ssp.simulation.set_value compares the SSV's text with 0.0. This test
    fails when FMPy sets "false" as false; then the workaround and its paragraph can go."""
    from types import SimpleNamespace

    from fmpy.ssp import simulation

    set_to = []
    component = SimpleNamespace(
        variables={"loopback": SimpleNamespace(type="Boolean", valueReference=7)},
        fmu=SimpleNamespace(setBoolean=lambda vrs, values: set_to.extend(values)),
    )
    simulation.set_value(component, "loopback", "false")
    with systems._fmpy_ssp_parameters():
        simulation.set_value(component, "loopback", "false")
    assert set_to == [True, False]


def test_the_container_fmu_validates_and_needs_no_parameter_set(built):
    assert validate_fmu(str(built["container"])) == []

    md = read_model_description(str(built["container"]))
    starts = {v.name: v.start for v in md.modelVariables if v.causality == "parameter"}
    assert starts == {"chip.loopback": "false"}
    assert {v.name for v in md.modelVariables if v.causality == "output"} == {
        c.path for c in systems.read_system().outputs
    }


def test_the_profile_is_docs_servo_mds_suggested_set_up_and_move():
    calls = dict(re.findall(r"^Set(\w+)\(Axis1, ([^)]+)\);", systems.SCRIPT.read_text(), re.M))
    assert {name: int(calls[name]) for name in closed_loop.GAINS} == closed_loop.GAINS
    assert (int(calls["Position"]), float(calls["Velocity"]), float(calls["Acceleration"])) == tuple(
        closed_loop.MOVE.values()
    )
    assert (calls["SettleWindow"], calls["SettleTime"], calls["PositionErrorLimit"]) == ("5", "20", "1000")


def dependencies(fmu: Path, element: str):
    """output name -> the inputs it depends on without a step, as the model description
    declares them (no dependencies attribute: every input, as FMI says)."""
    with zipfile.ZipFile(fmu) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    variables = list(root.find("ModelVariables"))
    inputs = {v.get("name") for v in variables if v.get("causality") == "input"}
    if root.get("fmiVersion") == "2.0":
        unknowns = root.find(f"ModelStructure/{'Outputs' if element == 'Output' else 'InitialUnknowns'}")
        name_of = {str(i): v.get("name") for i, v in enumerate(variables, start=1)}
        key = "index"
    else:
        unknowns = root.find("ModelStructure").iter(element)
        name_of = {v.get("valueReference"): v.get("name") for v in variables}
        key = "valueReference"
    return {
        name_of[u.get(key)]: inputs
        if u.get("dependencies") is None
        else {name_of[d] for d in u.get("dependencies").split()} & inputs
        for u in unknowns
    }


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("element", ["Output", "InitialUnknown"])
def test_the_declared_dependencies_close_no_loop_through_the_connections(fmi_version, element):
    """What OMSimulator and fmu-manipulation-toolbox check: follow each connection
    and each declared output-on-input dependency; no path leads back to where it
    started, in step mode or in initialization, because the plant's encoder count
    depends on no input."""
    system = systems.read_system()
    edges = {}
    for name, source in system.components.items():
        for output, inputs in dependencies(systems.fmu_of(source, fmi_version), element).items():
            for i in inputs:
                edges.setdefault(f"{name}.{i}", set()).add(f"{name}.{output}")
    for a, b in system.connections:
        edges.setdefault(a.path, set()).add(b.path)
    assert dependencies(systems.fmu_of("pmdplant.fmu", fmi_version), element)["encoderCount"] == set()

    def reaches(node, target, seen):
        return any(
            n == target or (n not in seen and not seen.add(n) and reaches(n, target, seen)) for n in edges.get(node, ())
        )

    loops = [node for node in edges if reaches(node, node, set())]
    assert not loops, loops


# ---- the runs -------------------------------------------------------------------------------


@pytest.mark.parametrize("master, fmi_version", [("fmpy-ssp", 2), ("libcosim", 2), ("container", 3), ("jacobi", 3)])
def test_every_jacobi_master_gives_the_same_run_bit_for_bit(runs, master, fmi_version):
    """FMPy's SSP master (FMI 2), libcosim (FMI 2), the container FMU (FMI 3 inside)
    and the plain master stepping Jacobi (FMI 2, 3): the same outputs after every step."""
    reference, _ = runs("jacobi", 2)
    result, _ = runs(master, fmi_version)
    assert result.dtype.names == reference.dtype.names
    for name in reference.dtype.names:
        assert np.array_equal(result[name], reference[name]), name


def test_gauss_seidel_is_the_same_in_both_fmi_versions_and_differs_from_jacobi(runs):
    gs, _ = runs("gauss-seidel", 2)
    gs3, _ = runs("gauss-seidel", 3)
    jacobi, _ = runs("jacobi", 2)
    for name in gs.dtype.names:
        assert np.array_equal(gs3[name], gs[name]), name
    # the trajectory does not depend on the loop; what the motor did does
    assert np.array_equal(gs["chip.axis1.commandedPosition"], jacobi["chip.axis1.commandedPosition"])
    assert not np.array_equal(gs["plant.encoderCount"], jacobi["plant.encoderCount"])


@pytest.mark.parametrize("algorithm", ["gauss-seidel", "jacobi"])
def test_which_command_the_plant_turns_in_each_step(runs, algorithm):
    """The plant's voltage in a step is supplyVoltage times the chip's motorOutput it had
    (motorCommand / 32768): Gauss-Seidel's the chip's of the same step, Jacobi's the one
    of the step before (0 in the first step: the chip's command after initialization)."""
    result, _ = runs(algorithm)
    output = result["chip.axis1.motorOutput"]
    assert np.array_equal(output, result["chip.axis1.motorCommand"] / 32768)
    applied = output if algorithm == "gauss-seidel" else np.concatenate([[0.0], output[:-1]])
    assert np.array_equal(result["plant.voltage"], 24.0 * applied)


@pytest.mark.parametrize("algorithm", ["gauss-seidel", "jacobi"])
def test_the_move_settles_in_the_settle_window_in_both_algorithms(runs, algorithm):
    result, _ = runs(algorithm)
    following = systems.following_error(result)
    assert systems.motion_complete(result) == PINNED[algorithm]["complete"]
    assert np.abs(following).max() == PINNED[algorithm]["following"]
    assert result["chip.axis1.commandedPosition"][-1] == result["plant.encoderCount"][-1] == 10_000
    settled = PINNED[algorithm]["complete"]
    assert np.abs(following[settled - 20 :]).max() <= 5  # the settle window, from the settle time on
    assert np.abs(result["chip.axis1.motorCommand"][-500:]).max() < 100  # at rest the friction holds: a quiet motor
    assert result["plant.speed"][-1] == 0.0


def test_the_loop_runs_without_a_warning_in_fmpy(runs, capfd):
    """The FMUs log nothing (no refused call, no algebraic loop) in the plain master
    and the container; FMPy's SSP master prints what they would log."""
    for master, fmi_version in (("gauss-seidel", 2), ("jacobi", 3), ("container", 3)):
        assert runs(master, fmi_version)[1] == []
    runs.cache_clear()
    runs("fmpy-ssp")
    out = capfd.readouterr()
    assert (out.out, out.err) == ("", "")


def test_the_loop_initializes_and_runs_without_a_warning_in_libcosim(runs, capfd):
    """libcosim logs no algebraic loop and no warning; its error lines are at most the FMI
    Library's complaint about the chip's FMI 2 `time` (docs/tools.md, libcosim)."""
    libcosim()
    runs.cache_clear()
    runs("libcosim")
    err = capfd.readouterr().err.splitlines()
    assert not [line for line in err if "loop" in line.lower() or "[warning]" in line]
    assert {re.sub(r"^.*\[error\]\s*", "", line) for line in err if "[error]" in line} <= {
        "[FMI Library: FMI2XML] Start attribute is required for this causality, variability and initial combination"
    }


def test_the_example_runs_as_a_user_would(tmp_path):
    env = dict(os.environ)  # the pmdfmu the suite runs (installed, or PYTHONPATH + PMDFMU_FMU_DIR)
    out = subprocess.run(
        [
            sys.executable,
            str(ROOT / "examples" / "systems" / "systems.py"),
            "run",
            "gauss-seidel",
            "--csv",
            str(tmp_path / "run.csv"),
        ],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    assert out.stdout == (
        "gauss-seidel: 3000 cycles; motion complete after cycle 1530; encoder 10000 counts "
        "(commanded 10000); largest following error 5 counts\n"
    )
    rows = list(csv.DictReader(open(tmp_path / "run.csv", newline="")))
    assert len(rows) == 3000 and rows[-1]["plant.encoderCount"] == "10000"
    out = subprocess.run(
        [
            sys.executable,
            str(ROOT / "examples" / "systems" / "systems.py"),
            "ssp",
            "--out",
            str(tmp_path / "servoLoop.ssp"),
        ],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    assert zipfile.ZipFile(tmp_path / "servoLoop.ssp").namelist()[0] == "SystemStructure.ssd"


def test_with_the_example_motors_acceleration_only_gauss_seidel_settles(runs):
    """Why the plant's load inertia is what it is (docs/systems.md): with loadInertia 7.2e-6
    the plant accelerates about 1 count/cycle^2 at full scale, as examples/closed_loop.py's
    motor; the suggested gains' derivative loop is then near its edge, and a Jacobi master's
    extra cycle of delay makes the loop hunt at full scale and never complete the motion."""
    values = {**systems.parameters(), "plant": {"loadInertia": 7.2e-6}}
    gs = systems.run_master("gauss-seidel", values=values)
    jacobi = systems.run_master("jacobi", values=values)
    assert systems.motion_complete(gs) == 1530
    assert systems.motion_complete(jacobi) is None
    assert np.abs(jacobi["chip.axis1.motorCommand"][-500:]).max() == 32767
