# SPDX-License-Identifier: BSD-2-Clause
"""The harness never rounds or masks what the user passes: a value
that does not fit is refused with a ValueError naming it, before anything reaches the
FMU; the in-range boundary values do exactly what they say, through FMI 2 and FMI 3."""

import math
import re
from decimal import Decimal
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu.chip import COMMANDS, RECORDED
from stepwise import run_stepwise

SET_POSITION = COMMANDS["SetPosition"].opcode
GET_POSITION = COMMANDS["GetPosition"].opcode


def refused(chip, call, *patterns):
    """call() raises ValueError whose message holds each pattern, and the chip is unchanged."""
    before = chip.get_state()
    with pytest.raises(ValueError) as info:
        call()
    for p in patterns:
        assert re.search(p, str(info.value)), (p, str(info.value))
    assert chip.get_state() == before
    return str(info.value)


def same_effect(chip, *calls):
    """Each call, from the same starting state, leaves the chip in the same state."""
    start = chip.get_state()
    states = []
    for call in calls:
        chip.set_state(start)
        call()
        states.append(chip.get_state())
    assert all(s == states[0] for s in states[1:])


# ---- batch: host words are 16 bits ----


def test_a_batch_word_beyond_16_bits_is_refused_by_both_fmi_versions(any_chip):
    chip = any_chip
    refused(chip, lambda: chip.batch([0x10010]), r"word 0\b", "65552", "0x10010", r"0 \.\. 0xFFFF", "nothing was sent")
    refused(chip, lambda: chip.batch([SET_POSITION, 1, 0x10000]), r"word 2\b", "65536")
    refused(chip, lambda: chip.batch([SET_POSITION, -32769, 0]), r"word 1\b", "-32769", "-0x8000")
    refused(chip, lambda: chip.batch([SET_POSITION, 1.0, 0]), r"word 1\b", "not an integer")


def test_batch_words_0xffff_and_minus_1_send_the_same_word(any_chip):
    chip = any_chip
    same_effect(
        chip,
        lambda: chip.batch([SET_POSITION, 0xFFFF, 0xFFFF]),
        lambda: chip.batch([SET_POSITION, -1, -1]),
        lambda: chip.batch([SET_POSITION, 0xFFFF, -1]),
    )
    assert chip.batch([GET_POSITION]) == (0, [0xFFFF, 0xFFFF])
    chip.batch([SET_POSITION, -32768, 0x8000])  # both halves 0x8000
    held = chip.get("host.word")[:3] if chip.fmi_version == 3 else [chip.get(f"host.word[{i}]") for i in (1, 2, 3)]
    assert held == [SET_POSITION, 0x8000, 0x8000]  # the FMU holds the 16-bit words
    assert chip.batch([GET_POSITION]) == (0, [0x8000, 0x8000])


# ---- write_memory: 32-bit words inside the memory ----


def test_a_memory_word_beyond_32_bits_is_refused(any_chip):
    chip = any_chip
    refused(
        chip,
        lambda: chip.write_memory(0x300, [1, 2, 2**40 + 5]),
        r"words\[2\]",
        str(2**40 + 5),
        "-2147483648 .. 4294967295",
        "nothing was written",
    )
    refused(chip, lambda: chip.write_memory(0x300, [2**32]), r"words\[0\]", "4294967296")
    refused(chip, lambda: chip.write_memory(0x300, [0, -(2**31) - 1]), r"words\[1\]", "-2147483649")
    refused(chip, lambda: chip.write_memory(0x300, [2**70]), r"words\[0\]")
    refused(chip, lambda: chip.write_memory(0x300, [7, 2.5]), r"words\[1\] = 2.5 is not an integer")


def test_a_memory_write_at_a_negative_address_or_leaving_the_memory_is_refused_whole(any_chip):
    chip = any_chip
    size = chip.get("memorySize")
    refused(chip, lambda: chip.write_memory(-1, [5]), "address -1", "memorySize", "nothing was written")
    refused(chip, lambda: chip.write_memory(2**32 - 1, [5, 6]), f"address {2**32 - 1}")
    refused(chip, lambda: chip.write_memory(2**40, [5]), f"address {2**40}")
    # 100 words at size - 70: the first strobe's 64 would fit, the rest not: nothing is written
    refused(
        chip,
        lambda: chip.write_memory(size - 70, list(range(100))),
        f"100 words at address {size - 70}",
        f"{size}-word memory",
    )
    chip.write_memory(size - 1, [9])  # the last word is still writable


def test_memory_words_minus_1_and_0xffffffff_store_the_same_word(any_chip):
    chip = any_chip
    ax = chip.axis(0)
    ax.SetBufferStart(2, 0x300)
    ax.SetBufferLength(2, 4)
    same_effect(
        chip,
        lambda: chip.write_memory(0x300, [-1, -(2**31), 2**31 - 1, 0]),
        lambda: chip.write_memory(0x300, [0xFFFFFFFF, 0x80000000, 0x7FFFFFFF, 0]),
    )
    assert [ax.ReadBuffer(2) for _ in range(4)] == [-1, -(2**31), 2**31 - 1, 0]  # ReadBuffer is signed


# ---- C-Motion calls: each argument fits its field ----


def test_a_command_argument_that_does_not_fit_its_field_is_refused(any_chip):
    chip = any_chip
    ax = chip.axis(1)
    message = refused(
        chip, lambda: ax.SetPosition(2**32), "SetPosition", "position", "4294967296", "-2147483648 .. 4294967295"
    )
    assert "32 bits" in message
    refused(chip, lambda: ax.SetPosition(-(2**31) - 1), "SetPosition", "position")
    refused(chip, lambda: ax.SetProfileMode(0x10000), "SetProfileMode", "mode", "16 bits", "-32768 .. 65535")
    refused(chip, lambda: ax.SetBreakpoint(0, 16, 0, 0), "SetBreakpoint", "sourceAxis", "4-bit field", r"0 \.\. 15")
    refused(chip, lambda: ax.SetBreakpoint(0, -1, 0, 0), "SetBreakpoint", "sourceAxis", r"0 \.\. 15")
    refused(chip, lambda: ax.SetPosition(1000.5), "SetPosition", "position", "not an integer")
    refused(chip, lambda: ax.SetPosition(1000.0), "SetPosition", "position", "not an integer")
    refused(chip, lambda: ax.SetVelocity(2.75), "SetVelocity", "velocity", "16.16", r"fixed_16_16\(2.75\)")
    refused(chip, lambda: ax.SetJerk(0.0075), "SetJerk", "jerk", r"fixed_0_32\(0.0075\)")
    refused(chip, lambda: chip.command(4, "SetPosition", [5]), "axis 4", "0..3")
    with pytest.raises(ValueError, match="axis 4"):
        chip.axis(4)


def test_command_arguments_in_either_reading_of_their_bits_send_the_same_words(any_chip):
    chip = any_chip
    ax = chip.axis(0)
    same_effect(chip, lambda: ax.SetPosition(-1), lambda: ax.SetPosition(0xFFFFFFFF))
    ax.SetPosition(0xFFFFFFFF)
    assert ax.GetPosition() == -1
    same_effect(chip, lambda: ax.SetAcceleration(pmdfmu.fixed_16_16(1.5)), lambda: ax.SetAcceleration(0x18000))
    ax.SetVelocity(pmdfmu.fixed_16_16(-1.95))  # an unsigned word for a signed argument
    assert ax.GetVelocity() == pmdfmu.signed(0xFFFE0CCD)


# ---- set: FMU variables take the word of their width ----


def test_a_variable_value_that_does_not_fit_is_refused(any_chip):
    chip = any_chip
    refused(chip, lambda: chip.set("axis1.actualPosition", 2**32), "axis1.actualPosition", "32 bits")
    refused(chip, lambda: chip.set("axis1.actualPosition", 1.5), "axis1.actualPosition", "not an integer")
    chip.set("axis1.actualPosition", 0xFFFFFFFF)
    assert chip.get("axis1.actualPosition") == -1
    chip.set("axis1.actualPosition", -(2**31))
    assert chip.get("axis1.actualPosition") == -(2**31)


@pytest.mark.parametrize("cycles", [2.5, 0.9, 3.0, "3"])
def test_a_cycle_count_that_is_no_integer_is_refused(any_chip, cycles):
    """The attacker's finding: Chip.run(2.5) ran 2 cycles and run(0.9) one, silently; with record= it
    raised numpy's TypeError, and System.run ctypes' ArgumentError."""
    refused(any_chip, lambda: any_chip.run(cycles), "run: cycles", "not an integer")
    refused(any_chip, lambda: any_chip.run(cycles, record=["axis1.commandedPosition"]), "not an integer")
    with pmdfmu.System(any_chip) as loop:
        refused(any_chip, lambda: loop.run(cycles), "run: cycles", "not an integer")


WRAPS = 2**64 / 1e9 + 1e-3  # s: 2^64 ns + 1 ms, which the native loop's int64 ns read as 1 ms


@pytest.mark.parametrize("timeout", [-0.5, -1e-9, math.nan, math.inf, WRAPS])
def test_a_timeout_that_is_negative_not_finite_or_past_the_host_clock_is_refused(any_chip, timeout):
    """The attacker's finding: wait_for(mask, timeout=-0.5) polled for ever (a negative limit is the native
    loop's "no limit"), a timeout of 2^64 ns + 1 ms timed out after 1 ms, and NaN raised Fraction's bare
    "cannot convert NaN to integer ratio"."""
    refused(any_chip, lambda: any_chip.wait_for(0x0800, 0, timeout=timeout), "wait_for: timeout")
    refused(any_chip, lambda: any_chip.wait_for_motion_complete(0, timeout=timeout), "wait_for: timeout")
    if timeout != WRAPS:  # a long wait, not refused
        refused(any_chip, lambda: any_chip.wait_for_interrupt(timeout), "wait_for_interrupt: timeout")
        refused(any_chip, lambda: any_chip.wait(timeout), "wait: seconds = ")


def test_a_timeout_given_as_text_is_refused_and_one_of_any_number_type_is_taken(any_chip):
    """A string was read by Fraction ("1/3" s); a numpy float32, a number a user holds from an array, was
    "no finite number of seconds"."""
    for timeout in ("0.5", "1/3"):
        refused(any_chip, lambda t=timeout: any_chip.wait_for(0x0800, 0, timeout=t), "wait_for: timeout")
        refused(any_chip, lambda t=timeout: any_chip.wait(t), "wait: seconds = ")
    assert any_chip.host_time_ns == 0
    any_chip.wait(np.float32(0.5))
    any_chip.wait(Decimal("0.25"))
    assert any_chip.host_time_ns == 750_000_000


def test_a_boolean_real_or_string_value_of_another_kind_is_refused(any_chip):
    """The attacker's finding: FMI 3 set a Boolean input to Python's truth value of anything (0.5, "no",
    5: True; None: False) and FMI 2 took 5 and -1 as true; a Real took a string with ctypes' TypeError
    naming no variable, a String an int with AttributeError."""
    chip = any_chip
    for value in (0.5, "no", None, 5, -1):
        refused(chip, lambda v=value: chip.set("axis1.positiveLimit", v), "set: axis1.positiveLimit", "not a Boolean")
    for value in (True, 1, 0, False):
        chip.set("axis1.positiveLimit", value)
        assert chip.get("axis1.positiveLimit") == bool(value)
    refused(chip, lambda: chip.set("record.columns", 5), "set: record.columns = 5 is not a str")
    for value in ("x", True):  # True was taken as 1 s
        with pytest.raises(ValueError, match=f"cycleTime = {value!r} is not a number"):
            pmdfmu.Chip(chip.fmi_version, cycleTime=value)
    refused(chip, lambda: chip.set("record.columns", b"x" * 1000), r"is not a str", r"\(1003 characters\)")
    with pytest.raises(ValueError, match=r"cycleTime = 1000.*\(401 characters\) is not a number a double holds"):
        pmdfmu.Chip(chip.fmi_version, cycleTime=10**400)
    with pytest.raises(ValueError, match="set: loopback = 'no' is not a Boolean"):
        pmdfmu.Chip(chip.fmi_version, loopback="no")
    refused(chip, lambda: chip.set("analog[2]", 1.0), r"analog\[2\]", "not an integer")


def test_a_string_variable_takes_a_path_as_its_text(any_chip):
    """set's check takes a path for a String (`a path, or the text itself`): FMPy, which encodes a str,
    raised AttributeError ("'PosixPath' object has no attribute 'encode'")."""
    any_chip.set("record.columns", Path("axis1.commandedPosition"))
    assert any_chip.get("record.columns") == "axis1.commandedPosition"


# ---- fixed point through the chip ----


def test_from_fixed_refuses_what_a_get_call_cannot_return(any_chip):
    ax = any_chip.axis(0)
    ax.SetVelocity(pmdfmu.fixed_16_16(-2.5))
    assert pmdfmu.from_fixed(ax.GetVelocity(), "16.16") == pmdfmu.from_fixed(pmdfmu.fixed_16_16(-2.5), "16.16")
    with pytest.raises(ValueError, match="4294967296"):
        pmdfmu.from_fixed(2**32, "16.16")


# ---- bulk recording (FMI 3): never past record.data ----


def test_a_sample_time_change_inside_a_bulk_recording_is_recorded_and_the_chip_runs_on(tmp_path):
    script = tmp_path / "slower.script"
    script.write_text("@10\nSetSampleTime(Axis1, 200)\n")
    with pmdfmu.Chip(fmi_version=3, script=script) as chip, pmdfmu.Chip(fmi_version=3, script=script) as stepping:
        rows = chip.run(100, record=RECORDED)
        assert rows.tobytes() == run_stepwise(stepping, 100, RECORDED).tobytes()
        # the harness follows the chip's new grid: the next run records the next cycles
        assert chip.cycle_time == pytest.approx(200e-6)
        rows = chip.run(5, record=["axis1.commandedPosition"])
        assert list(rows["cycle"]) == [100, 101, 102, 103, 104]


def test_a_bulk_recording_reads_only_the_rows_record_data_holds():
    """If record.data holds fewer bytes than asked (here a cut in the middle of a row),
    the rows are counted from its size, and the run is refused."""
    with pmdfmu.Chip(fmi_version=3) as chip:
        real = chip.fmu.fmi3GetBinary

        def short(*args):
            status = real(*args)
            args[3][0] = 4 * (1 + len(RECORDED)) * 3 + 5  # 3 cycles and part of a fourth
            return status

        chip.fmu.fmi3GetBinary = short
        with pytest.raises(RuntimeError, match="holds 3 cycles, not 100"):
            chip.run(100, record=RECORDED)


# ---- an FMU refusal raised with the FMU's reason; a name that is no variable, with the nearest ----


@pytest.mark.parametrize("version", [2, 3])
def test_a_refused_parameter_raises_with_the_fmus_reason(version):
    """Chip(cycleTime=1.5e-6): the exception itself says what is wrong (1.5 us is inside 1 .. 65535 us but
    not whole), not only the FMI function and status; it is an FMUError and FMPy's FMICallException."""
    from fmpy.fmi1 import FMICallException

    with pytest.raises(pmdfmu.FMUError) as info:
        pmdfmu.Chip(fmi_version=version, cycleTime=1.5e-6)
    text = str(info.value)
    assert isinstance(info.value, FMICallException) and info.value.status == 3
    assert "cycleTime = 1.5e-06 s is not a whole number of microseconds" in text
    assert ("fmi3SetFloat64" if version == 3 else "fmi2SetReal") in text
    with pytest.raises(pmdfmu.FMUError, match="outside 1 us .. 65535 us"):
        pmdfmu.Chip(fmi_version=version, cycleTime=0.1)


@pytest.mark.parametrize("version", [2, 3])
def test_an_unknown_log_category_raises_with_the_fmus_reason_and_leaves_no_instance(version, monkeypatch):
    """Chip(log_categories=["bogus"]): FMUError naming the category and the FMU's categories; the instance
    made for it is freed, as for a refused parameter."""
    freed = []
    slave = pmdfmu.chip._Slave2 if version == 2 else pmdfmu.chip._Slave3
    real_free = slave.freeInstance
    monkeypatch.setattr(slave, "freeInstance", lambda self: freed.append(self) or real_free(self))
    with pytest.raises(pmdfmu.FMUError) as info:
        pmdfmu.Chip(fmi_version=version, log_categories=["bogus"])
    assert 'unknown log category "bogus" (the FMU\'s: errors, warnings' in str(info.value)
    assert len(freed) == 1


@pytest.mark.parametrize("version", [2, 3])
def test_a_refused_set_of_an_output_raises_with_the_fmus_reason(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        with pytest.raises(pmdfmu.FMUError, match=r"axis1.commandedPosition\) is an output and cannot be set"):
            chip.set("axis1.commandedPosition", 3)
        with pytest.raises(pmdfmu.FMUError, match="record.columns"):
            chip.set("record.columns", "axis1.nothing")
        assert chip.run(3, record=["axis1.commandedPosition"]).tolist() == [(0, 0), (1, 0), (2, 0)]


@pytest.mark.parametrize("version", [2, 3])
def test_a_name_that_is_no_variable_says_so_and_names_the_nearest(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        with pytest.raises(KeyError) as info:
            chip.get("axis5.position")
        assert str(info.value).startswith("get: 'axis5.position' is not a variable of the FMU: did you mean ")
        assert "axis4.position" in str(info.value)
        with pytest.raises(KeyError, match=r"'analog\[9\]' is not a variable of the FMU: did you mean analog\[8\]"):
            chip.set("analog[9]", 1)
        with pytest.raises(KeyError, match=r"'frobnicate' is not a variable of the FMU \(pmdfmu info lists them\)"):
            chip.get("frobnicate")
    with pytest.raises(KeyError, match="set: 'cycletime' is not a variable of the FMU: did you mean cycleTime?"):
        pmdfmu.Chip(fmi_version=version, cycletime=1e-4)


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_path_is_a_file_and_text_that_fails_says_it_was_read_as_text(version, tmp_path):
    """A Path is a file, never text: one holding a line feed (which the FMU would read as a script's text)
    is refused before the FMU sees it; a str holding one is text, and its error says why it was."""
    folder = tmp_path / "dir\nnew"
    folder.mkdir()
    (folder / "s.pmd").write_text("@0\nSetSampleTime(Axis1, 100);\n")
    with pytest.raises(ValueError, match="holds a line feed, and the FMU reads a script value holding one as"):
        pmdfmu.Chip(fmi_version=version, script=folder / "s.pmd")
    with pytest.raises(pmdfmu.FMUError) as info:
        pmdfmu.Chip(fmi_version=version, script=str(folder / "s.pmd"))
    assert "(script text):1:" in str(info.value)
    assert "(the value holds a line feed, so it was read as script text)" in str(info.value)
