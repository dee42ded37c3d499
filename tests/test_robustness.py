# SPDX-License-Identifier: BSD-2-Clause
"""Every class of bad input of docs/robustness.md: instance A gets it
while it runs a busy profile; instance B runs the same profile untouched. A
refused FMI call leaves A's FMU state byte for byte as it was; a refused chip
command is not executed: A's next 400 cycles equal B's. B never notices."""

import math

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from scenarios import BUSY_OUTPUTS, busy_chip
from states import op, snapshot, vr


# (row of docs/robustness.md, action on chip A); FMI-level refusals raise FMICallException
FMI_CALLS = {
    "unknown value reference": lambda c: c.fmu.getInteger([7777]),
    "wrong type": lambda c: c.fmu.getReal([vr(c, "axis1.commandedPosition")]),
    "an output set": lambda c: c.fmu.setInteger([vr(c, "host.ack")], [3]),
    "a fixed parameter after initialization": lambda c: c.fmu.setReal([vr(c, "cycleTime")], [1e-3]),
    "a host word out of 16 bits": lambda c: c.fmu.setInteger([vr(c, "host.word[1]")], [65536]),
    "a word count over 64": lambda c: c.fmu.setInteger([vr(c, "host.wordCount")], [65]),
    "a memory write address below 0": lambda c: c.fmu.setInteger([vr(c, "memory.address")], [-1]),
    "a NaN step size": lambda c: c.fmu.doStep(c.time, math.nan),
    "a negative step size": lambda c: c.fmu.doStep(c.time, -1e-4),
    "a zero step size": lambda c: c.fmu.doStep(c.time, 0.0),
    "an infinite step size": lambda c: c.fmu.doStep(c.time, math.inf),
    "a huge step size": lambda c: c.fmu.doStep(c.time, 1e300),
    "a step not at the last communication point": lambda c: c.fmu.doStep(c.time + 1.0, 1e-4),
    "SetupExperiment after initialization": lambda c: c.fmu.setupExperiment(startTime=0.0),
    "EnterInitializationMode twice": lambda c: c.fmu.enterInitializationMode(),
    "NULL value arrays": lambda c: (
        c.fmu._functions["fmi2GetInteger"](c.fmu.component, None, 3, None) == 3
        and (_ for _ in ()).throw(FMICallException("fmi2GetInteger", 3))
    ),
    "an unknown log category": lambda c: c.fmu.setDebugLogging(True, ["nonsense"]),
    "a truncated state blob": lambda c: c.fmu.deserializeFMUState(snapshot(c)[:-100]),
    "a corrupted state blob": lambda c: c.fmu.deserializeFMUState(snapshot(c)[:200] + b"\x55" + snapshot(c)[201:]),
    "a foreign state blob": lambda c: c.fmu.deserializeFMUState(b"FOREIGN!" + bytes(400)),
    "an unsupported function": lambda c: (
        c.fmu._functions["fmi2CancelStep"](c.fmu.component) == 3
        and (_ for _ in ()).throw(FMICallException("fmi2CancelStep", 3))
    ),
}

# refused chip commands: (row, batch of words, expected host I/O error)
CHIP_COMMANDS = {
    "an unknown opcode": ([0x02], 0x02),
    "a bad axis": ([op("SetPosition", 5), 0, 100], 0x03),
    "a truncated batch (wrong word count)": ([op("SetPosition"), 0], 0x04),
    "a bad buffer ID": ([op("SetBufferStart"), 40, 0, 0x300], 0x04),
    "an index out of range": ([op("SetBufferReadIndex"), 2, 0, 99], 0x07),
    "a block leaving the memory": ([op("SetBufferLength"), 2, 0x7000, 0], 0x07),
    "an absurd value": ([op("SetStopMode"), 9], 0x04),
    "a negative value": ([op("SetAcceleration"), 0x8000, 0], 0x0B),
    "unused bits set": ([op("SetBreakpoint"), 0, 0xFFFF], 0x04),
    "a reply past host.reply[64]": ([op("GetTime")] * 33, 0x04),
}


@pytest.fixture
def pair():
    with pmdfmu.Chip() as a, pmdfmu.Chip() as b:
        for chip in (a, b):
            busy_chip(chip)
            chip.run(150)
            chip.axis(0).GetHostIOError()  # 1 since reset: read, so the next error shows
        yield a, b


@pytest.mark.parametrize("row", FMI_CALLS)
def test_a_refused_fmi_call_changes_nothing_and_the_other_instance_goes_on(pair, row):
    a, b = pair
    before = snapshot(a)
    with pytest.raises(FMICallException):
        FMI_CALLS[row](a)
    assert snapshot(a) == before
    assert any(m.status == "Error" for m in a.messages) or row in ("NULL value arrays", "an unsupported function")
    assert np.array_equal(a.run(400, record=BUSY_OUTPUTS), b.run(400, record=BUSY_OUTPUTS))


@pytest.mark.parametrize("row", CHIP_COMMANDS)
def test_a_refused_chip_command_is_not_executed_and_the_other_instance_goes_on(pair, row):
    a, b = pair
    words, code = CHIP_COMMANDS[row]
    error, _ = a.batch(words)
    assert error == code
    assert a.axis(0).GetHostIOError() == code
    assert a.axis(0).GetEventStatus() & pmdfmu.PMDEventInstructionErrorMask  # the chip's answer ...
    ra, rb = a.run(400, record=BUSY_OUTPUTS), b.run(400, record=BUSY_OUTPUTS)
    ra["axis1.eventStatus"] &= ~np.uint16(pmdfmu.PMDEventInstructionErrorMask)  # ... and all it changed
    assert np.array_equal(ra, rb)


def test_a_refused_memory_write_writes_nothing(pair):
    a, b = pair
    with pytest.raises(FMICallException):
        a.fmu.setInteger(
            [vr(a, "memory.data[1]"), vr(a, "memory.address"), vr(a, "memory.count"), vr(a, "memory.strobe")],
            [12345, 0x3FFF, 5, a.get("memory.strobe") + 1],
        )
    assert np.array_equal(a.run(400, record=BUSY_OUTPUTS), b.run(400, record=BUSY_OUTPUTS))
    a.axis(0).SetBufferStart(9, 0x3FFF)
    a.axis(0).SetBufferLength(9, 1)
    assert a.axis(0).ReadBuffer(9) == 0
