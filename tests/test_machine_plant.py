# SPDX-License-Identifier: BSD-2-Clause
"""A machine's servo = "plant" (docs/machine.md): the pmdplant motor stepped inside the chip FMU
every cycle, its encoder count the axis's actual position. The reference is the systems example's
Gauss-Seidel FMPy master (examples/systems/systems.py), chip FMU and plant FMU side by side: the
same run, bit for bit."""

import sys
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu.cli import main

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT / "examples" / "systems")]
import systems  # noqa: E402  examples/systems/systems.py

PLANT = '[axis1]\nservo = "plant"\n'
RECORD = ["axis1.commandedPosition", "axis1.motorCommand", "axis1.eventStatus", "axis1.actualPosition"]
# the chip's column -> the master's: after cycle k the machine's motor has stepped with the cycle's
# command, so the chip's actual position input is the plant's encoder count after step k
MASTER = {
    "axis1.commandedPosition": "chip.axis1.commandedPosition",
    "axis1.motorCommand": "chip.axis1.motorCommand",
    "axis1.eventStatus": "chip.axis1.eventStatus",
    "axis1.actualPosition": "plant.encoderCount",
}
# the motor of docs/systems.md's hunting example (a_full ~ 1), with floats in TOML's forms
LIGHT = {"loadInertia": 7.2e-6, "coulombFriction": 0.003, "supplyVoltage": 24.0, "internalStep": 2e-5}
LIGHT_TOML = (
    PLANT + "[axis1.plant]\nloadInertia = 7.2e-6\ncoulombFriction = 0.003  # N.m\nsupplyVoltage = 24\n"
    "internalStep = 2E-5\n"
)


def master(fmi_version, plant=None):
    values = {**systems.parameters(), "plant": plant or {}}  # the machine's plant turns the Integer command
    return systems.run_master("gauss-seidel", fmi_version, log=lambda *a: None, values=values, motor="motorCommand")


def in_chip(fmi_version, machine, cycles, pieces=1):
    with pmdfmu.Chip(fmi_version=fmi_version, script=systems.script_value(), machine=machine) as chip:
        runs = [chip.run(cycles // pieces, record=RECORD) for _ in range(pieces)]
    return np.concatenate(runs)


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_the_closed_loop_move_equals_the_gauss_seidel_master_bit_for_bit(fmi_version):
    ref = master(fmi_version)
    got = in_chip(fmi_version, PLANT, len(ref))
    for ours, theirs in MASTER.items():
        assert np.array_equal(got[ours], ref[theirs]), ours
    # a real move: it follows, settles and reports motion complete where the master does
    assert got["axis1.actualPosition"][-1] == 10_000 and systems.motion_complete(ref) == 1530
    assert np.max(np.abs(ref["chip.axis1.commandedPosition"][1:] - got["axis1.actualPosition"][:-1])) > 0


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_the_plant_tables_parameters_act_as_the_plant_fmus_and_steps_do_not_matter(fmi_version):
    ref = master(fmi_version, LIGHT)
    got = in_chip(fmi_version, LIGHT_TOML, len(ref), pieces=3)
    for ours, theirs in MASTER.items():
        assert np.array_equal(got[ours], ref[theirs]), ours
    assert not np.array_equal(got["axis1.motorCommand"], in_chip(fmi_version, PLANT, len(ref))["axis1.motorCommand"])


def test_the_jacobi_master_is_a_cycle_behind_and_differs():
    """The machine is Gauss-Seidel's order (the plant steps with the command of the cycle just run);
    a Jacobi master gives the plant the command one cycle older, another run."""
    ref = systems.run_master("jacobi", 2, log=lambda *a: None, motor="motorCommand")
    got = in_chip(2, PLANT, len(ref))
    assert not np.array_equal(got["axis1.actualPosition"], ref["plant.encoderCount"])


def test_a_coasting_motor_turns_in_one_long_step_as_cycle_by_cycle():
    """An axis with a plant is never quiet nor fast-forwarded: its motor turns, motor off, every cycle."""
    machine = PLANT + "[axis1.plant]\ninitialSpeed = 50.0\n"
    with pmdfmu.Chip(machine=machine) as one, pmdfmu.Chip(machine=machine) as many:
        long = one.run(4000, record=["axis1.actualPosition"])["axis1.actualPosition"]
        short = np.concatenate(
            [many.run(1, record=["axis1.actualPosition"])["axis1.actualPosition"] for _ in range(4000)]
        )
        assert np.array_equal(long, short)
        assert long[0] > 0 and long[-1] == long[-2] > 1000  # friction stops it: 50 rad/s coasts ~1500 counts
        assert one.axis(0).GetActualPosition() == long[-1]


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_an_fmu_state_holds_the_motors_shaft_and_refuses_another_motor(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, script=systems.script_value(), machine=PLANT) as chip:
        chip.run(700)  # accelerating: the shaft turns
        saved = chip.get_state()
        first = chip.run(1500, record=RECORD)
        chip.set_state(saved)
        assert np.array_equal(chip.run(1500, record=RECORD), first)
        with pmdfmu.Chip(fmi_version=fmi_version, script=systems.script_value(), machine=PLANT) as same:
            same.set_state(saved)
            assert np.array_equal(same.run(1500, record=RECORD), first)
        other = PLANT + "[axis1.plant]\nloadInertia = 1.3e-5\n"
        with pmdfmu.Chip(fmi_version=fmi_version, script=systems.script_value(), machine=other) as heavier:
            with pytest.raises(Exception, match="machineDigest"):
                heavier.set_state(saved)


def test_a_chip_reset_leaves_the_motor_turning():
    machine = PLANT + "[axis1.plant]\ninitialSpeed = 50.0\n"
    with pmdfmu.Chip(machine=machine) as chip:
        chip.run(100)
        before = chip.axis(0).GetActualPosition()
        chip.axis(0).Reset()
        chip.run(100)
        assert chip.axis(0).GetActualPosition() > before > 0


BAD = [
    ('[axis1.plant]\nloadInertia = 1e-5\n[axis1]\nservo = "ideal"\n', 1, 'does not say servo = "plant"'),
    (PLANT + "[axis1.plant]\nmass = 3.0\n", 4, "unknown key 'mass' in [axis1.plant]"),
    (PLANT + "[axis1.plant]\nmotorCommand = 3\n", 4, "unknown key 'motorCommand'"),
    (PLANT + "[axis1.plant]\nrotorInertia = 0.0\n", 4, "rotorInertia = 0 is outside 1e-12 .. inf"),
    (PLANT + "[axis1.plant]\nencoderLines = 4000.0\n", 4, "encoderLines is a whole number"),
    (PLANT + "[axis1.plant]\nencoderLines = 0x200001\n", 4, "encoderLines = 2097153 is outside 1 .. 1048576"),
    (PLANT + "[axis1.plant]\ninternalStep = 1e-7\n", 4, "internalStep = 1e-07 is outside 1e-06 .. 1"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = inf\n", 4, "a motor's parameter is a finite number"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = 1e999\n", 4, "is not a finite double"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = .5\n", 4, "a value is an integer"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = 5.\n", 4, "digits on both sides"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = 05.0\n", 4, "leading zero"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = 1_.5\n", 4, "an underscore must stand between two digits"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = 1e\n", 4, "an exponent without digits"),
    (PLANT + '[axis1.plant]\nsupplyVoltage = "24"\n', 4, "supplyVoltage is a number"),
    (PLANT + "[axis1.plant]\nsupplyVoltage = 24\nsupplyVoltage = 12\n", 5, "given twice in [axis1.plant]"),
    (PLANT + "[axis1.plant]\n[axis1.plant]\n", 4, "[axis1.plant] is given twice (first at line 3)"),
    (PLANT + "[axis1.motor]\n", 3, "[axis1.plant] .. [axis4.plant]"),
    ("[axis1]\nhome = [0, 1.5]\n", 2, "a floating-point number: positions are whole counts"),
    ('[axis1]\nservo = "plants"\n', 2, 'the servo is "ideal" (the commanded position) or "plant"'),
]


@pytest.mark.parametrize("text,line,reason", BAD, ids=[b[2][:30] for b in BAD])
def test_a_bad_plant_table_is_refused_with_file_line_reason(tmp_path, text, line, reason, capsys):
    path = tmp_path / "m.toml"
    path.write_text(text)
    with pytest.raises(pmdfmu.FMUError) as e:
        pmdfmu.Chip(machine=path)
    assert f"{path}:{line}: " in str(e.value) and reason in str(e.value)
    assert main(["machine", "--check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"pmdfmu machine: {path}:{line}: ") and reason in err


def test_machine_check_prints_the_motor(tmp_path, capsys):
    path = tmp_path / "m.toml"
    path.write_text(LIGHT_TOML)
    assert main(["machine", "--check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "axis1 (PMDAxis1): plant servo (the pmdplant motor: supplyVoltage 24 armatureResistance 2" in out
    assert "loadInertia 7.2e-06" in out and "encoderLines 4000" in out
