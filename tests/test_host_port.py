# SPDX-License-Identifier: BSD-2-Clause
"""The native host port (native/host_port.c, pmdfmu.host_port): the Axis methods, Chip.batch and
Chip.wait_for pinned bit for bit to the Python path they replace (tests/stepwise.py: StepwiseChip
sends through FMPy, wait_for_stepwise polls in Python): the same replies and errors, the same host
clock and cycles, the same chip (get_state's bytes)."""

import pytest
from stepwise import StepwiseChip, send_stepwise, wait_for_stepwise

import pmdfmu
from pmdfmu import PMDError

MOVE = [
    ("SetProfileMode", 0),
    ("SetPosition", -40000),
    ("SetVelocity", 0x30000),
    ("SetAcceleration", 0x800),
    ("SetDeceleration", 0x800),
    ("Update",),
]


def script(chip):
    """A host program's commands: sets, gets of one and two words, a chip-wide command, either reading
    of a 32-bit argument, a refused command; what each returned or raised."""
    ax, out = chip.axis(pmdfmu.PMDAxis2), []
    for name, *args in MOVE + [("SetVelocity", 0xFFFFFFFF), ("GetVelocity",), ("SetVelocity", 0x30000)]:
        out.append(getattr(ax, name)(*args))
    chip.run(7)
    for name in (
        "GetPosition",
        "GetCommandedPosition",
        "GetActivityStatus",
        "GetEventStatus",
        "GetTime",
        "GetBufferStart",
    ):
        try:
            out.append(getattr(ax, name)(*([0] if name == "GetBufferStart" else [])))
        except PMDError as e:
            out.append(("PMDError", e.code))
    try:
        ax.SetBufferLength(2, 0)  # a length the chip refuses
    except PMDError as e:
        out.append(("PMDError", e.code))
    out.append(chip.batch([pmdfmu.chip.instruction_word(pmdfmu.chip.COMMANDS["GetTime"].opcode, 0)]))
    return out


@pytest.mark.parametrize("host", [None, "parallel16", "serial"])
@pytest.mark.parametrize("version", [2, 3])
def test_commands_equal_the_python_path_bit_for_bit(version, host):
    with pmdfmu.Chip(version, host_interface=host) as fast, StepwiseChip(version, host_interface=host) as slow:
        assert fast._fast is not None and slow._fast is None
        assert script(fast) == script(slow)
        assert (fast.host_time_ns, fast.cycles) == (slow.host_time_ns, slow.cycles)
        assert fast.get_state() == slow.get_state()


@pytest.mark.parametrize("version", [2, 3])
def test_a_batch_equals_send_stepwise(version):
    with pmdfmu.Chip(version) as a, pmdfmu.Chip(version) as b:
        words = [pmdfmu.chip.instruction_word(pmdfmu.chip.COMMANDS[n].opcode, 1) for n in ("GetPosition", "GetTime")]
        error, reply = a.batch(words)
        assert (error, list(reply)) == send_stepwise(b, words)
        assert a.get_state() == b.get_state()


@pytest.mark.parametrize("host", [None, "parallel16", "serial"])
@pytest.mark.parametrize("version", [2, 3])
def test_wait_for_motion_complete_equals_a_python_polling_loop(version, host):
    mask = pmdfmu.PMDEventMotionCompleteMask
    with pmdfmu.Chip(version, host_interface=host) as fast, StepwiseChip(version, host_interface=host) as slow:
        for chip in (fast, slow):
            ax = chip.axis(1)
            for name, *args in MOVE:
                getattr(ax, name)(*args)
            ax.ResetEventStatus(0)
        status = fast.wait_for_motion_complete(1)
        assert status is not None and status & mask
        assert status == wait_for_stepwise(slow, mask, 1)
        assert (fast.host_time_ns, fast.cycles) == (slow.host_time_ns, slow.cycles)
        assert fast.cycles > 100
        assert fast.get_state() == slow.get_state()


@pytest.mark.parametrize("version", [2, 3])
def test_wait_for_times_out_as_the_python_loop(version):
    mask = pmdfmu.PMDEventMotionCompleteMask
    with pmdfmu.Chip(version, host_interface="serial") as fast, StepwiseChip(version, host_interface="serial") as slow:
        for chip in (fast, slow):
            for name, *args in MOVE:
                getattr(chip.axis(0), name)(*args)
            chip.axis(0).ResetEventStatus(0)
        assert fast.wait_for(mask, 0, timeout=0.01) is None
        assert wait_for_stepwise(slow, mask, 0, timeout=0.01) is None
        assert (fast.host_time_ns, fast.cycles) == (slow.host_time_ns, slow.cycles)
        assert fast.get_state() == slow.get_state()


def test_the_slow_path_still_checks_and_raises(any_chip):
    ax = any_chip.axis(0)
    with pytest.raises(ValueError, match="SetVelocity: velocity = 2.5 is not an integer"):
        ax.SetVelocity(2.5)
    with pytest.raises(TypeError, match="SetVelocity"):
        ax.SetVelocity()
    assert ax.SetVelocity(velocity=5) is None and ax.GetVelocity() == 5
    with pytest.raises(ValueError):
        any_chip.wait_for(0)
