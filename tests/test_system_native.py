# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu.System (python/pmdfmu/system.py, native/system.c): the chip and the plant stepped together
natively, pinned bit for bit to examples/systems' FMPy master (run_master), Gauss-Seidel and Jacobi,
FMI 2 and FMI 3; a run in pieces equals one run; a pmdfmu.Plant with its parameters equals the plant's
path with them."""

import sys
from pathlib import Path

import numpy as np
import pytest

import pmdfmu

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT / "examples" / "systems")]
import systems  # noqa: E402  examples/systems/systems.py

OUTPUTS = [c.path for c in systems.read_system().outputs]


# the .ssd's motor wire (Real) as pmdfmu.System's wiring; System's default is the Integer one
REAL = {"chip.axis1.motorOutput": "plant.motorOutput", "plant.encoderCount": "chip.axis1.actualPosition"}


def chip(version):
    """The chip as the system's: loopback off and the profile (examples/systems' is packed, the same
    compiled script)."""
    return pmdfmu.Chip(version, loopback=False, script=systems.script_value())


def native_run(algorithm, version, steps, wiring=None):
    with chip(version) as c, pmdfmu.System(c, algorithm=algorithm, wiring=wiring) as system:
        return system.run(steps, record=OUTPUTS)


@pytest.mark.parametrize("motor", ["motorOutput", "motorCommand"])
@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("algorithm", ["gauss-seidel", "jacobi"])
def test_the_system_equals_the_fmpy_master_bit_for_bit(algorithm, version, motor):
    master = systems.run_master(algorithm, version, log=lambda *a: None, motor=motor)
    rows = native_run(algorithm, version, len(master), wiring=REAL if motor == "motorOutput" else None)
    assert rows.dtype.names == master.dtype.names
    for name in master.dtype.names:
        assert np.array_equal(rows[name], master[name]), name
    assert systems.motion_complete(rows) is not None


@pytest.mark.parametrize("algorithm", ["gauss-seidel", "jacobi"])
def test_the_two_motor_wires_give_one_run(algorithm):
    """The plant takes the chip's Integer motor command and its Real motor output at the same 2^15 counts
    to full scale (docs/systems.md): over either wire the system runs alike, bit for bit."""
    assert np.array_equal(native_run(algorithm, 2, 3000), native_run(algorithm, 2, 3000, wiring=REAL))


def test_a_run_in_pieces_equals_one_run():
    whole = native_run("gauss-seidel", 2, 600)
    with chip(2) as c, pmdfmu.System(c) as system:
        parts = np.concatenate(
            [system.run(250, record=OUTPUTS), system.run(0, record=OUTPUTS), system.run(350, record=OUTPUTS)]
        )
        assert c.cycles == 600
    assert np.array_equal(parts, whole)


# plant parameters other than the build's start values: a heavier load, a coarser encoder, less friction
PLANT = {"loadInertia": 3e-5, "encoderLines": 1000, "coulombFriction": 0.002}


@pytest.mark.parametrize("version", [2, 3])
def test_a_plant_with_its_parameters_equals_its_path_with_them_and_the_fmpy_master(version):
    values = {**systems.parameters(), "plant": PLANT}
    # pmdfmu.System wires the Integer motor command unless told otherwise
    master = systems.run_master("gauss-seidel", version, log=lambda *a: None, values=values, motor="motorCommand")
    path = pmdfmu.default_fmu(version).with_name(f"pmdplant-fmi{version}.fmu")

    def run(*plant, **parameters):
        with chip(version) as c:
            with pmdfmu.System(c, *plant, **parameters) as system:
                return system.run(len(master), record=OUTPUTS)

    runs = [run(pmdfmu.Plant(**PLANT)), run(pmdfmu.Plant(path, **PLANT)), run(path, **PLANT), run(None, **PLANT)]
    for rows in runs:
        for name in master.dtype.names:
            assert np.array_equal(rows[name], master[name]), name
    # the parameters took effect: the build's plant turns otherwise
    assert not np.array_equal(
        native_run("gauss-seidel", version, len(master))["plant.encoderCount"], master["plant.encoderCount"]
    )


def test_a_plants_parameters_go_in_the_plant_or_as_keywords_and_are_its_variables():
    assert repr(pmdfmu.Plant("m.fmu", encoderLines=1000)) == "Plant('m.fmu', encoderLines=1000)"
    with pmdfmu.Chip(2, loopback=False) as chip:
        with pytest.raises(TypeError, match="not both"):
            pmdfmu.System(chip, pmdfmu.Plant(loadInertia=1e-5), encoderLines=1000)
        with pytest.raises(ValueError, match="'loadInertiaa' is no variable of pmdplant-fmi2.fmu"):
            pmdfmu.System(chip, pmdfmu.Plant(loadInertiaa=1e-5))


@pytest.mark.parametrize("version", [2, 3])
def test_a_plant_parameter_the_plant_refuses_raises_with_the_plants_reason(version):
    """The attacker's finding: Plant(loadInertia=-1) raised FMPy's bare "fmi2SetReal failed with status 3"
    and left the plant's instance allocated."""
    with pmdfmu.Chip(version, loopback=False) as c:
        with pytest.raises(pmdfmu.FMURefusal, match=r"loadInertia = -1 is not in 0 \.\. inf"):
            pmdfmu.System(c, pmdfmu.Plant(loadInertia=-1))
        with pmdfmu.System(c) as system:  # the chip goes on with a good plant
            assert len(system.run(3, record=["plant.angle"])) == 3


def test_bad_wiring_and_algorithm_are_refused():
    with pmdfmu.Chip(2, loopback=False) as chip:
        with pytest.raises(ValueError, match="algorithm"):
            pmdfmu.System(chip, algorithm="newton")
        with pytest.raises(ValueError, match="wiring"):
            pmdfmu.System(chip, wiring={"motor.x": "plant.motorCommand"})
        with pmdfmu.System(chip) as system, pytest.raises(ValueError, match="no scalar variable"):
            system.run(1, record=["plant.nothing"])


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize(
    "wiring,message",
    [
        ({"plant.angle": "chip.axis1.actualPosition"}, "does not fit a"),  # Real into Integer: truncated
        ({"chip.axis1.motorOutput": "plant.motorCommand"}, "does not fit a"),  # was TypeError from ctypes
        ({"chip.axis1.motorCommand": "plant.encoderCount"}, "from an output to an input"),
        ({"plant.encoderCount": "chip.memorySize"}, "from an output to an input"),
        ({"chip.axis1.motorCommand": "chip.axis1.actualPosition"}, "from one FMU to the other"),
        ({"plant.angle": "chip.record.columns"}, "a wire carries"),  # a String: was a bare KeyError
        (
            {"chip.axis1.motorCommand": "plant.motorCommand", "chip.axis2.motorCommand": "plant.motorCommand"},
            "plant.motorCommand is driven by both chip.axis1.motorCommand and chip.axis2.motorCommand",
        ),
    ],
)
def test_a_wire_that_would_change_or_lose_its_values_is_refused_before_anything_runs(version, wiring, message):
    """The attacker's finding: a Real output wired to an Integer input was truncated (and NaN or a huge
    value undefined) in native/system.c, a second wire into one input overwrote the first, and a wire into
    an output or a fixed parameter failed at its first set with FMPy's bare "status 3"."""
    with pmdfmu.Chip(version, loopback=False) as c:
        before = c.get_state()
        with pytest.raises(ValueError, match=message):
            pmdfmu.System(c, wiring=wiring)
        assert c.get_state() == before
