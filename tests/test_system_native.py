# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu.System (python/pmdfmu/system.py, native/system.c): the chip and the plant stepped together
natively, pinned bit for bit to examples/systems' FMPy master (run_master), Gauss-Seidel and Jacobi,
FMI 2 and FMI 3; a run in pieces equals one run."""

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


def test_a_run_in_pieces_equals_one_run():
    whole = native_run("gauss-seidel", 2, 600)
    with chip(2) as c, pmdfmu.System(c) as system:
        parts = np.concatenate(
            [system.run(250, record=OUTPUTS), system.run(0, record=OUTPUTS), system.run(350, record=OUTPUTS)]
        )
        assert c.cycles == 600
    assert np.array_equal(parts, whole)


def test_bad_wiring_and_algorithm_are_refused():
    with pmdfmu.Chip(2, loopback=False) as chip:
        with pytest.raises(ValueError, match="algorithm"):
            pmdfmu.System(chip, algorithm="newton")
        with pytest.raises(ValueError, match="wiring"):
            pmdfmu.System(chip, wiring={"motor.x": "plant.motorCommand"})
        with pmdfmu.System(chip) as system, pytest.raises(ValueError, match="no scalar variable"):
            system.run(1, record=["plant.nothing"])
