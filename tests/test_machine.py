# SPDX-License-Identifier: BSD-2-Clause
"""The machine (docs/machine.md): switch and index inputs that follow each axis's actual position
every cycle, from a TOML file the FMU parses (its `machine` parameter), for the harness, the CLI and
the C library alike. Each capture, limit and sense test compares the chip with a reference of the
machine written here in Python from the file's meaning."""

import os
import shutil
import subprocess

import numpy as np
import pytest

import pmdfmu
from cmotion_build import ROOT, compile_program, generate
from pmdfmu import (
    PMDCaptureSourceHome,
    PMDCaptureSourceIndex,
    PMDEventCaptureReceivedMask,
    PMDEventInNegativeLimitMask,
    PMDEventInPositiveLimitMask,
    PMDExternalProfile,
    PMDSignalEncoderHomeMask,
    PMDSignalEncoderIndexMask,
    PMDTrapezoidal,
    PMDVelocityContouringProfile,
)
from pmdfmu.cli import main

STAGE = ROOT / "examples" / "machine" / "stage.toml"
HOME, POSITIVE, NEGATIVE, INDEX = (12_345, 12_845), 40_000, -40_000, 2_000  # stage.toml's meaning


# ---- the reference: the machine's inputs from the actual positions, cycle by cycle ----


def home_active(p, lo=HOME[0], hi=HOME[1]):
    return lo <= p <= hi


def index_active(before, now, period=INDEX):
    """A pulse at each multiple of period: active in the cycle that passes or reaches one."""
    low, high = (before + 1, now) if now > before else (now, before - 1) if now < before else (now, now)
    return (high // period) * period >= low


def first(flags):
    hits = np.flatnonzero(flags)
    return int(hits[0]) if len(hits) else None


def velocity_move(ax, velocity, acceleration=0x2000):
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetAcceleration(acceleration)
    ax.SetVelocity(velocity)
    ax.Update()


RECORD = ["axis1.commandedPosition", "axis1.eventStatus", "axis1.home", "axis1.index", "axis1.positiveLimit"]


# ---- capture ----


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_home_capture_latches_the_actual_position_of_the_cycle_the_switch_becomes_active(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, machine=STAGE) as chip:
        ax = chip.axis(0)
        ax.SetCaptureSource(PMDCaptureSourceHome)
        velocity_move(ax, 0x50000)
        rows = chip.run(6000, record=RECORD)
        position = rows["axis1.commandedPosition"]  # the ideal servo: actual = commanded
        k = first([home_active(p) for p in position])
        assert k is not None and position[k] >= HOME[0] and position[k - 1] < HOME[0]
        assert list(rows["axis1.home"]) == [home_active(p) for p in position]
        assert first(rows["axis1.eventStatus"] & PMDEventCaptureReceivedMask) == k
        assert ax.GetCaptureValue() == position[k]


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_index_capture_latches_the_cycle_that_passes_a_pulse_downward_too(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, machine=STAGE) as chip:
        ax = chip.axis(0)
        ax.SetCaptureSource(PMDCaptureSourceIndex)
        ax.SetActualPosition(-1)  # the stage stays at 0; the register says -1
        chip.run(2)
        ax.GetCaptureValue()  # at rest on the pulse at 0: captured; reading re-arms
        velocity_move(ax, -0x70000)  # 7 counts a cycle: pulses are passed, never landed on
        rows = chip.run(2000, record=RECORD)
        stage = rows["axis1.commandedPosition"].astype(np.int64) + 1
        before = np.concatenate([[0], stage[:-1]])
        expected = [index_active(b, n) for b, n in zip(before, stage)]
        assert list(rows["axis1.index"]) == expected
        k = first([e and b != 0 for e, b in zip(expected, before)])  # the first pulse passed after 0
        assert stage[k] <= -INDEX < stage[k - 1]
        assert ax.GetCaptureValue() == rows["axis1.commandedPosition"][k]


def wrapped_index_active(before, step, period):
    """index_active for a step that may take the 32-bit register past either end: the register's values
    passed, each as the int32 it is, a pulse at each of them that is a multiple of period (by brute force)."""
    values = range(before + 1, before + step + 1) if step > 0 else range(before + step, before)
    return any((((v + 2**31) % 2**32) - 2**31) % period == 0 for v in values)


@pytest.mark.parametrize("velocity", [0x7FFF0000, -0x7FFF0000], ids=["up", "down"])
def test_index_pulses_are_seen_as_the_stage_wraps_past_either_end_of_the_register(velocity, tmp_path):
    """32767 counts a cycle with a pulse every 3 counts (3 does not divide 2^32: the pulses lie otherwise
    on each side of the wrap): every cycle that passes one shows it, the cycles across the wrap too."""
    machine = "[axis1]\nindex = 3\n"
    with pmdfmu.Chip(machine=machine) as chip:
        ax = chip.axis(0)
        velocity_move(ax, velocity, acceleration=0x7FFF0000)
        chip.run(65_530)
        rows = chip.run(20, record=["axis1.commandedPosition", "axis1.index"])
        stage = rows["axis1.commandedPosition"].astype(np.int64)
        steps = [((int(n) - int(b) + 2**31) % 2**32) - 2**31 for b, n in zip(stage[:-1], stage[1:])]
        assert any(abs(int(n) - int(b)) > 2**31 for b, n in zip(stage[:-1], stage[1:]))  # the wrap is here
        expected = [wrapped_index_active(int(b), s, 3) for b, s in zip(stage[:-1], steps)]
        assert list(rows["axis1.index"][1:]) == expected


def test_a_chip_reset_restarts_the_counter_but_leaves_the_stage_on_its_switch():
    """Reset zeroes the actual position register; the ideal servo's stage does not move, so a home switch it
    stands on stays active (its count is the register minus the offset Reset leaves)."""
    with pmdfmu.Chip(machine="[axis1]\nhome = [100, 200]\n") as chip:
        ax = chip.axis(0)
        ax.SetProfileMode(PMDTrapezoidal)
        ax.SetPosition(150)
        ax.SetVelocity(0x10000)
        ax.SetAcceleration(0x1000)
        ax.Update()
        chip.run(3000)
        assert ax.GetActualPosition() == 150 and not ax.GetSignalStatus() & PMDSignalEncoderHomeMask
        ax.Reset()
        ax.GetHostIOError()  # the reset's error 1, read and so cleared
        chip.run(2)
        assert ax.GetActualPosition() == 0 and not ax.GetSignalStatus() & PMDSignalEncoderHomeMask


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_an_input_the_machine_drives_cannot_be_set_one_it_does_not_can(fmi_version):
    """axis1.home under a machine with a home switch: Error naming it, nothing changed (it would be taken
    back at the next cycle without a word); axis1.positiveLimit, which this machine leaves alone, is set."""
    with pmdfmu.Chip(fmi_version=fmi_version, machine="[axis1]\nhome = [100, 200]\n") as chip:
        chip.run(2)
        before = chip.axis(0).GetSignalStatus()
        with pytest.raises(pmdfmu.FMUError, match=r"axis1.home\) is driven every cycle by the machine"):
            chip.set("axis1.home", True)
        assert chip.axis(0).GetSignalStatus() == before
        chip.set("axis1.positiveLimit", True)
        chip.set("axis2.home", True)


def test_the_axis_index_input_captures_as_a_plant_drives_it():
    with pmdfmu.Chip() as chip:
        ax = chip.axis(1)
        ax.SetCaptureSource(PMDCaptureSourceIndex)
        ax.SetActualPosition(777)
        chip.run(3)
        assert ax.GetSignalStatus() & PMDSignalEncoderIndexMask  # idle reads 1
        chip.set("axis2.index", True)
        chip.run(1)
        assert not ax.GetSignalStatus() & PMDSignalEncoderIndexMask
        assert ax.GetEventStatus() & PMDEventCaptureReceivedMask and ax.GetCaptureValue() == 777


def test_a_machine_stops_an_external_profile_at_the_switch_edge_it_would_skip_over():
    """A long external segment is fast-forwarded without a machine; with one, the capture is the
    cycle the reference says, as if run cycle by cycle."""
    rows_in = [(0, 3 << 16, 0, 0, 100_000), (0, 0, 0, 0, 0)]
    for machine in (STAGE, None):
        with pmdfmu.Chip(**({"machine": machine} if machine else {})) as chip:
            ax = chip.axis(0)
            for f in range(5):
                ax.SetBufferStart(2 + f, 0x200 + 8 * f)
                ax.SetBufferLength(2 + f, 8)
                ax.SetBufferFunction(f, 2 + f)
                chip.write_memory(0x200 + 8 * f, [r[f] for r in rows_in])
            ax.SetCaptureSource(PMDCaptureSourceHome)
            ax.SetProfileMode(PMDExternalProfile)
            ax.Update()
            chip.run(50_000)  # one doStep
            if machine:
                assert ax.GetEventStatus() & PMDEventCaptureReceivedMask
                # 3 counts a cycle from 0 after the reading cycle: the first position at or past 12345
                assert ax.GetCaptureValue() == -(-HOME[0] // 3) * 3
            else:
                assert not ax.GetEventStatus() & PMDEventCaptureReceivedMask


# ---- limits ----


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_limit_switches_raise_the_chips_limit_events_where_the_machine_puts_them(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, machine=STAGE) as chip:
        ax = chip.axis(0)
        ax.SetProfileMode(PMDTrapezoidal)
        ax.SetPosition(100_000)
        ax.SetVelocity(20 << 16)
        ax.SetAcceleration(1 << 16)
        ax.SetDeceleration(1 << 16)
        ax.Update()
        rows = chip.run(4000, record=RECORD)
        position = rows["axis1.commandedPosition"]
        k = first(position >= POSITIVE)
        assert first(rows["axis1.eventStatus"] & PMDEventInPositiveLimitMask) == k
        assert first(rows["axis1.positiveLimit"]) == k
        assert (position[k:] == position[k]).all()  # stopped abruptly there
        # out of the limit the other way, into the negative one
        ax.ResetEventStatus(0)
        ax.SetPosition(-100_000)
        ax.Update()
        rows = chip.run(10_000, record=RECORD)
        position = rows["axis1.commandedPosition"]
        k = first(position <= NEGATIVE)
        assert first(rows["axis1.eventStatus"] & PMDEventInNegativeLimitMask) == k
        assert position[-1] == position[k] <= NEGATIVE


# ---- signal sense ----


def test_a_switch_wired_active_high_needs_its_signal_sense_bit():
    machine = "[axis1]\nhome = [100, 200]\nsignal_sense = 0x0008\n"
    with pmdfmu.Chip(machine=machine) as chip:
        ax = chip.axis(0)
        chip.run(1)
        assert not ax.GetSignalStatus() & PMDSignalEncoderHomeMask  # away from the flag, yet "active"
        ax.SetSignalSense(PMDSignalEncoderHomeMask)  # the host says how the switch is wired
        chip.run(1)
        assert ax.GetSignalStatus() & PMDSignalEncoderHomeMask
        ax.SetCaptureSource(PMDCaptureSourceHome)
        velocity_move(ax, 0x30000)
        rows = chip.run(300, record=RECORD)
        position = rows["axis1.commandedPosition"]
        k = first([home_active(p, 100, 200) for p in position])
        assert list(rows["axis1.home"]) == [not home_active(p, 100, 200) for p in position]  # the wire's level
        assert ax.GetCaptureValue() == position[k]


# ---- state ----


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_an_fmu_state_holds_the_machines_inputs_and_refuses_another_machine(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, machine=STAGE) as chip:
        ax = chip.axis(0)
        ax.SetCaptureSource(PMDCaptureSourceIndex)
        velocity_move(ax, 0x50000)
        chip.run(2410)  # the index input of this cycle is active
        saved = chip.get_state()
        first_run = chip.run(3000, record=RECORD)
        chip.set_state(saved)
        assert np.array_equal(chip.run(3000, record=RECORD), first_run)
        with pmdfmu.Chip(fmi_version=fmi_version, machine=STAGE) as same:
            same.set_state(saved)
            assert np.array_equal(same.run(3000, record=RECORD), first_run)
        with pmdfmu.Chip(fmi_version=fmi_version, machine="[axis1]\nhome = [0, 10]\n") as other:
            with pytest.raises(Exception, match="machineDigest"):
                other.set_state(saved)
        with pmdfmu.Chip(fmi_version=fmi_version) as none:
            with pytest.raises(Exception, match="machineDigest"):
                none.set_state(saved)


# ---- the file ----

BAD = [
    ("home = [1, 2]\n", 1, "'home' outside a table"),
    ("[axis5]\n", 1, "[axis5]: the tables are [axis1] .. [axis4]"),
    ("[axis1]\n[axis1]\n", 2, "[axis1] is given twice (first at line 1)"),
    ("[axis1]\nhome = [1, 2]\nhome = [3, 4]\n", 3, "'home' is given twice"),
    ("[axis1]\nhome = [5, 2]\n", 2, "lo is above hi"),
    ("[axis1]\nhome = 5\n", 2, "home = [lo, hi]"),
    ("[axis1]\n# fine\n\nindex = 1.5\n", 4, "a floating-point number"),
    ("[axis1]\nindex = 0\n", 2, "the counts between pulses are 1 .. 2^31-1"),
    ("[axis1]\npositive_limit = 3_000_000_000\n", 2, "is not a position"),
    ("[axis1]\npositive_limit = 1__0\n", 2, "an underscore must stand between two digits"),
    ("[axis1]\nnegative_limit = 010\n", 2, "leading zero"),
    ('[axis1]\nservo = "stepper"\n', 2, 'the servo is "ideal"'),
    ("[axis1]\nspeed = 3\n", 2, "unknown key 'speed'"),
    ("[axis1]\nhome = [1, 2\n", 2, "an array must close on its line"),
    ("[axis1]\nhome = {lo = 1}\n", 2, "an inline table"),
    ("[axis1]\nhome = [1, 2] x\n", 2, "text after the value"),
    ("[axis1]\nsignal_sense = 0x0100\n", 2, "signal_sense is a SignalSense mask"),
    ("[axis1]\npositive_limit = 5\nnegative_limit = 5\n", 3, "is not above negative_limit"),
    ("[axis1]\na.b = 1\n", 2, "a dotted key"),
    ("[axis1]\nhome = true\n", 2, "a value is an integer"),
    ("[[axis1]]\n", 1, "an array of tables"),
]


@pytest.mark.parametrize("text,line,reason", BAD, ids=[b[2][:30] for b in BAD])
def test_a_bad_machine_file_is_refused_with_file_line_reason(tmp_path, text, line, reason, capsys):
    path = tmp_path / "m.toml"
    path.write_text(text)
    with pytest.raises(pmdfmu.FMUError) as e:
        pmdfmu.Chip(machine=path)
    assert f"{path}:{line}: " in str(e.value) and reason in str(e.value)
    # the CLI: exit 2, one line, no traceback
    assert main(["machine", "--check", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith(f"pmdfmu machine: {path}:{line}: ") and reason in err


def test_machine_text_is_taken_as_the_script_is():
    with pytest.raises(pmdfmu.FMUError, match=r"\(machine text\):2: unknown key"):
        pmdfmu.Chip(machine="[axis2]\nhom = [1, 2]\n")


def test_the_toml_subset_takes_hex_underscores_comments_and_position_lists():
    text = '# a stage\n[axis3]  # third\nservo = "ideal"\nindex = [ -16, 1_000, +7, ]\nhome=[0b101,0o17]\n'
    with pmdfmu.Chip(machine=text, log_categories=["machine"]) as chip:
        meaning = "".join(m.message for m in chip.messages if m.category == "machine")
    assert "axis3 (PMDAxis3): ideal servo; home active at 5 .. 15; index pulse at -16, 1000, 7" in meaning


def test_machine_check_prints_what_the_file_means(capsys):
    assert main(["machine", "--check", str(STAGE)]) == 0
    out = capsys.readouterr().out
    assert "home active at 12345 .. 12845" in out and "index pulse every 2000 counts" in out
    assert "positive limit active at >= 40000" in out and "negative limit active at <= -40000" in out


def test_pmdfmu_run_takes_a_machine(tmp_path, capsys):
    script = tmp_path / "hunt.script"
    script.write_text(
        "@ 0\nSetCaptureSource(Axis1, PMDCaptureSourceHome);\nSetProfileMode(Axis1, PMDVelocityContouringProfile);\n"
        "SetAcceleration(Axis1, 0.125);\nSetVelocity(Axis1, 5.0);\nUpdate(Axis1);\n@ 3000\nNoOperation(Axis1);\n"
    )
    out = tmp_path / "o.csv"
    assert main(["run", str(script), "--machine", str(STAGE), "--csv", str(out)]) == 0
    header, *rows = out.read_text().splitlines()
    assert rows, header


def test_the_example_homes_against_the_stage():
    out = subprocess.run(
        [os.sys.executable, str(ROOT / "examples" / "machine_homing.py")], capture_output=True, text=True, check=True
    ).stdout
    assert "home switch captured at 12347 counts" in out
    assert "back at the switch: the origin now, actual position 0" in out
    assert "next index pulse captured at 1657 counts from the origin" in out


# ---- the C library ----


@pytest.fixture(scope="module")
def homing(tmp_path_factory):
    if not shutil.which("cc"):
        pytest.skip("no C compiler")
    tmp = tmp_path_factory.mktemp("machine-c")
    return compile_program(ROOT / "tests" / "c" / "machine_homing.c", tmp / "machine_homing", generate(tmp / "gen"))


def run_c(exe, *args, timeout=300, **env):
    env = {**os.environ, "PMDFMU_FMU": str(pmdfmu.default_fmu(2)), "PMDFMU_MACHINE": str(STAGE), **env}
    return subprocess.run([str(exe), *args], capture_output=True, text=True, env=env, timeout=timeout)


def test_a_c_motion_program_homes_against_the_machine_file_and_runs_to_completion(homing):
    out = run_c(homing)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [
        "R home captured 12347",
        "R back at 12347",
        "R origin 0",
        "R index captured 1657",
        "R positive limit 0x0029 27670",  # the stage's 40000 + its first overshoot, from the origin at 12347
    ]


def test_pmdfmu_max_cycles_ends_a_poll_that_never_finishes_naming_it(homing):
    out = run_c(homing, "forever", PMDFMU_MAX_CYCLES="200000")
    assert out.returncode == 124
    assert out.stdout.splitlines() == ["R home captured 12347"]
    assert out.stderr.startswith(
        "PMDFMU_MAX_CYCLES=200000: the chip has run 200000 cycles and the program is still waiting: "
        "its last command was PMDGetEventStatus on axis 0 (PMDAxis1), sent "
    )


VENDOR_POLL = """#include "c-motion.h"
int main(void)
{
    PMDAxisHandle hAxis;
    PMDuint16 status = 0;
    if (PMDSetupAxisInterface_Serial(&hAxis, PMDAxis1, 1) != PMD_ERR_OK)
        return 1;
    while (!(status & PMDEventMotionCompleteMask))
        PMDGetEventStatus(&hAxis, &status);
    return 0;
}
"""


def test_pmdfmu_max_cycles_says_it_once_to_a_program_opened_the_vendors_way(tmp_path):
    """Such an opening's transport lines go to stderr already: the limit's line came twice, once
    prefixed "pmdfmu: "."""
    if not shutil.which("cc"):
        pytest.skip("no C compiler")
    (tmp_path / "poll.c").write_text(VENDOR_POLL)
    exe = compile_program(tmp_path / "poll.c", tmp_path / "poll", generate(tmp_path / "gen"))
    out = run_c(exe, PMDFMU_MAX_CYCLES="300", PMDFMU_MACHINE="")
    assert out.returncode == 124
    assert out.stderr.splitlines() == [
        "PMDFMU_MAX_CYCLES=300: the chip has run 300 cycles and the program is still waiting: "
        f"its last command was PMDGetEventStatus on axis 0 (PMDAxis1), sent {out.stderr.split('sent ')[-1].split()[0]}"
        " times in a row"
    ]


@pytest.mark.parametrize("value", ["200k", "-5", "99999999999999999999", "0", " 7"])
def test_a_max_cycles_that_is_no_whole_number_opens_no_chip_and_says_so(homing, value):
    """The attacker's finding: "200k" was ignored (one line on stderr) and "-5" read by strtoull as
    2^64 - 5, so the program waited for ever without the guard the user had set."""
    out = run_c(homing, "forever", PMDFMU_MAX_CYCLES=value, timeout=60)
    assert out.returncode == 1 and out.stdout == "E PMDSetupAxisInterface_FMU 0x1205\n"  # PMD_ERR_OpeningPort
    assert f"PMDFMU_MAX_CYCLES={value} is not a whole number of cycles 1 .. 2^64-1: no chip opened" in out.stderr


def test_a_bad_machine_file_in_the_environment_is_named_on_stderr(homing, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[axis1]\nhome = [2, 1]\n")
    out = run_c(homing, PMDFMU_MACHINE=str(bad))
    assert out.returncode == 1
    assert f"{bad}:2: home = [2, 1]: lo is above hi" in out.stderr
