# SPDX-License-Identifier: BSD-2-Clause
"""The native host port (native/host_port.c, pmdfmu.host_port): the Axis methods, Chip.batch and
Chip.wait_for pinned bit for bit to the Python path they replace (tests/stepwise.py: StepwiseChip
sends through FMPy, wait_for_stepwise polls in Python): the same replies and errors, the same host
clock and cycles, the same chip (get_state's bytes)."""

import pytest
from stepwise import StepwiseChip, send_stepwise, wait_for_stepwise

import pmdfmu
from pmdfmu import PMDError
from pmdfmu.calls import COMMANDS, decode, encode, instruction_word

MOVE = [
    ("SetProfileMode", 0),
    ("SetPosition", -40000),
    ("SetVelocity", 0x30000),
    ("SetAcceleration", 0x800),
    ("SetDeceleration", 0x800),
    ("Update",),
]


class Sent:
    """An axis handle whose calls go as raw words through chip.send, encoded and decoded as C-Motion does."""

    def __init__(self, chip, number):
        self.chip, self.number = chip, number

    def __getattr__(self, name):
        command = COMMANDS[name]

        def call(*args):
            axis = 0 if command.scope == "chip" else self.number
            reply = self.chip.send(instruction_word(command.opcode, axis), *encode(command, args))
            values = decode(command.reply, reply)
            return None if not values else values[0] if len(values) == 1 else tuple(values)

        return call


def script(chip, sent=False):
    """A host program's commands: sets, gets of one and two words, a chip-wide command, either reading
    of a 32-bit argument, a refused command; what each returned or raised. sent: through chip.send."""
    ax, out = (Sent if sent else type(chip.axis(0)))(chip, pmdfmu.PMDAxis2), []
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
        "GetVersion",
    ):
        try:
            out.append(getattr(ax, name)(*([0] if name == "GetBufferStart" else [])))
        except PMDError as e:
            out.append(("PMDError", e.code))
    try:
        ax.SetBufferLength(2, 0)  # a length the chip refuses
    except PMDError as e:
        out.append(("PMDError", e.code, e.command))
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


@pytest.mark.parametrize("host", [None, "serial"])
@pytest.mark.parametrize("version", [2, 3])
def test_send_equals_the_axis_methods_and_the_python_path_bit_for_bit(version, host):
    """chip.send, a command's raw words: natively what the Axis method does, off it what batch does."""
    with (
        pmdfmu.Chip(version, host_interface=host) as methods,
        pmdfmu.Chip(version, host_interface=host) as sent,
        StepwiseChip(version, host_interface=host) as slow,
    ):
        expected = script(methods)
        assert script(sent, sent=True) == expected and script(slow, sent=True) == expected
        for chip in (sent, slow):
            assert (chip.host_time_ns, chip.cycles) == (methods.host_time_ns, methods.cycles)
            assert chip.get_state() == methods.get_state()


def test_send_checks_its_words_and_sends_an_unknown_opcode_for_the_chip_to_refuse(any_chip):
    get_position = instruction_word(COMMANDS["GetPosition"].opcode, 0)
    set_position = instruction_word(COMMANDS["SetPosition"].opcode, 0)
    assert any_chip.send(set_position, -1, -2) is not None  # two's complements: 0xFFFF, 0xFFFE
    assert any_chip.send(get_position) == (0xFFFF, 0xFFFE) and any_chip.axis(0).GetPosition() == -2
    with pytest.raises(ValueError, match=r"SetPosition \(opcode 0x10\) takes 2 data words, not 1; nothing was sent"):
        any_chip.send(set_position, 5)
    with pytest.raises(ValueError, match="send: data word 2 .*; nothing was sent"):
        any_chip.send(set_position, 0, 0x10000)
    with pytest.raises(ValueError, match="send: the instruction word"):
        any_chip.send(2.0)
    with pytest.raises(PMDError, match="instruction word 0x0001: host I/O error") as refused:
        any_chip.send(0x0001)
    assert refused.value.code == pmdfmu.PMD_ERR_InvalidInstruction


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
