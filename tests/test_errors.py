# SPDX-License-Identifier: BSD-2-Clause
"""Bad input (CONTRACT 2.4): the chip answers a bad command with its host I/O
error code and does not execute it; a bad FMI call gets fmi2Error and a log
message naming the function, the value and the reason; nothing else changes."""

import math

import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

import pmdfmu
from pmdfmu import PMDBreakpointActivityStatus, PMDError, field_dp
from states import op


def errors(chip):
    return [m.message for m in chip.messages if m.status == "Error"]


# ---- the chip's answers ----------------------------------------------------------


def test_host_io_error_reads_1_after_reset_then_keeps_the_first_error(chip):
    ax = chip.axis(0)
    assert ax.GetHostIOError() == 0x01  # reset, until read
    assert ax.GetHostIOError() == 0
    with pytest.raises(PMDError):
        ax.SetBufferLength(40, 1)  # 0x04
    with pytest.raises(PMDError):
        ax.SetBufferReadIndex(2, 0)  # 0x07
    assert ax.GetHostIOError() == 0x04  # the first since the last read
    assert ax.GetHostIOError() == 0
    ax.Reset()
    assert ax.GetHostIOError() == 0x01


def test_refused_commands_set_the_instruction_error_event_bit(chip):
    ax = chip.axis(2)
    with pytest.raises(PMDError):
        ax.SetStopMode(3)
    assert ax.GetEventStatus() & pmdfmu.PMDEventInstructionErrorMask


def test_unknown_opcode_answers_0x02_and_ends_the_batch(chip):
    error, reply = chip.batch([0x0002, op("GetTime")])  # 0x02 is Magellan-only
    assert error == 0x02 and reply == []


# Magellan only: SetMotorType, its SetSampleTime, SetPositionLoop, SetUpdateMask
@pytest.mark.parametrize("opcode", [0x02, 0x3B, 0x67, 0xF9])
def test_unimplemented_opcodes_answer_invalid_instruction(chip, opcode):
    assert chip.batch([opcode])[0] == 0x02


def test_bad_axis_answers_0x03_and_the_batch_goes_on(chip):
    error, reply = chip.batch([op("SetPosition", axis=4), 0, 5, op("GetTime")])
    assert error == 0x03 and len(reply) == 2
    assert chip.axis(0).GetPosition() == 0


def test_truncated_batch_is_not_executed(chip):
    error, reply = chip.batch([op("SetPosition"), 0x0001])
    assert error == 0x04
    assert chip.axis(0).GetPosition() == 0


def test_a_failing_get_returns_no_words(chip):
    error, reply = chip.batch([op("GetBufferStart"), 99, op("GetTime")])
    assert error == 0x04 and reply == [0, 0]


def test_replies_past_host_reply_64_are_refused_not_dropped(chip):
    error, reply = chip.batch([op("GetTime")] * 33)
    assert error == 0x04 and len(reply) == 64


def test_unused_bits_of_a_packed_word_are_refused(chip):
    error, _ = chip.batch([op("SetBreakpoint"), 0, 0x10000 - 1])  # trigger 0xFF
    assert error == 0x04
    error, _ = chip.batch([op("SetBreakpoint"), 5, field_dp(0, "PMDBreakpointTrigger", PMDBreakpointActivityStatus)])
    assert error == 0x04


@pytest.mark.parametrize(
    "call,args,code",
    [
        ("SetBufferStart", (32, 0x200), 0x04),  # bad buffer ID
        ("SetBufferStart", (2, 0x4001), 0x07),  # start past memory
        ("SetBufferLength", (2, 0x4001), 0x07),  # start + length past memory
        ("SetBufferLength", (2, 0x40000000), 0x07),
        ("SetBufferWriteIndex", (2, 0), 0x07),  # index >= length 0
        ("SetBufferReadIndex", (2, 0), 0x07),
        ("WriteBuffer", (2, 1), 0x07),  # zero-length buffer
        ("ReadBuffer", (2,), 0x07),
        ("SetBufferFunction", (5, 2), 0x04),  # function 0..4
        ("SetBufferFunction", (0, 1), 0x04),  # 0 and 1 belong to the trace
        ("SetBufferFunction", (0, 32), 0x04),
        ("GetBufferFunction", (-1,), 0x04),
        ("SetAcceleration", (0x80000000,), 0x0B),  # negative in every mode
        ("SetDeceleration", (-1,), 0x0B),
        ("SetJerk", (0xFFFFFFFF,), 0x0B),
        ("SetStopMode", (3,), 0x04),
        ("SetProfileMode", (7,), 0x04),
        ("SetBreakpointValue", (2, 0), 0x04),
        ("MultiUpdate", (0x10,), 0x04),
    ],
)
def test_out_of_range_arguments_get_the_chips_code_and_change_nothing(chip, call, args, code):
    ax = chip.axis(0)
    ax.SetBufferStart(3, 0x100)
    before = [ax.GetBufferStart(b) for b in range(2, 4)] + [ax.GetBufferLength(b) for b in range(2, 4)]
    with pytest.raises(PMDError) as e:
        getattr(ax, call)(*args)
    assert e.value.code == code
    assert [ax.GetBufferStart(b) for b in range(2, 4)] + [ax.GetBufferLength(b) for b in range(2, 4)] == before


def test_start_at_the_end_of_memory_with_length_0_fits(chip):
    chip.axis(0).SetBufferStart(2, 0x4000)
    with pytest.raises(PMDError):
        chip.axis(0).SetBufferLength(2, 1)


def test_buffer_indexes_wrap_at_the_length_and_start_resets_them(chip):
    ax = chip.axis(0)
    ax.SetBufferStart(5, 0x300)
    ax.SetBufferLength(5, 3)
    for v in (11, 22, 33, 44):
        ax.WriteBuffer(5, v)
    assert ax.GetBufferWriteIndex(5) == 1
    assert [ax.ReadBuffer(5) for _ in range(4)] == [44, 22, 33, 44]
    assert ax.GetBufferReadIndex(5) == 1
    ax.SetBufferStart(5, 0x301)
    assert (ax.GetBufferReadIndex(5), ax.GetBufferWriteIndex(5)) == (0, 0)
    assert ax.ReadBuffer(5) == 22  # the memory itself is unchanged


# ---- bad FMI calls ------------------------------------------------------------------


def test_unknown_value_reference_is_an_error_naming_it(chip):
    with pytest.raises(FMICallException):
        chip.fmu.getInteger([9999])
    assert any("fmi2GetInteger" in m and "9999" in m for m in errors(chip))


def test_wrong_type_is_an_error_naming_the_variable(chip):
    vr = chip.variables["axis1.position"].valueReference
    with pytest.raises(FMICallException):
        chip.fmu.getInteger([vr])
    assert any("axis1.position" in m and "Real" in m for m in errors(chip))


def test_outputs_and_fixed_parameters_cannot_be_set(chip):
    with pytest.raises(FMICallException):
        chip.set("chipTime", 5)
    with pytest.raises(FMICallException):
        chip.set("memorySize", 100)
    assert any("output" in m for m in errors(chip)) and any("fixed parameter" in m for m in errors(chip))
    assert chip.get("memorySize") == 0x4000


def test_a_bad_value_in_a_set_call_sets_nothing(chip):
    vrs = [chip.variables[n].valueReference for n in ("host.word[1]", "host.word[2]", "host.wordCount")]
    with pytest.raises(FMICallException):
        chip.fmu.setInteger(vrs, [7, 70000, 2])
    assert chip.fmu.getInteger(vrs) == [0, 0, 0]
    assert any("host.word[2]" in m and "70000" in m for m in errors(chip))
    with pytest.raises(FMICallException):
        chip.set("host.wordCount", 65)


@pytest.mark.parametrize("h", [0.0, -1e-4, math.nan, math.inf, 1e300])
def test_absurd_step_sizes_are_errors_and_the_instance_goes_on(chip, h):
    with pytest.raises(FMICallException):
        chip.fmu.doStep(0.0, h)
    assert any(m.startswith("fmi2DoStep: ") for m in errors(chip))
    chip.run(3)
    assert chip.get("chipTime") == 2


def test_a_step_not_starting_at_the_last_communication_point_is_an_error(chip):
    chip.run(5)
    with pytest.raises(FMICallException):
        chip.fmu.doStep(1.0, 1e-4)
    assert any("not the current time" in m for m in errors(chip))
    chip.run(1)
    assert chip.get("chipTime") == 5


def test_memory_writes_leaving_the_memory_are_refused_whole(chip):
    vr = {
        n: chip.variables[n].valueReference
        for n in ("memory.address", "memory.count", "memory.strobe", "memory.data[1]", "memory.data[2]")
    }
    with pytest.raises(FMICallException):
        chip.fmu.setInteger(
            [vr["memory.data[1]"], vr["memory.data[2]"], vr["memory.address"], vr["memory.count"], vr["memory.strobe"]],
            [5, 6, 0x3FFF, 2, 1],
        )
    assert any("memory.strobe" in m and "refused" in m for m in errors(chip))
    ax = chip.axis(0)
    ax.SetBufferStart(2, 0x3FFF)
    ax.SetBufferLength(2, 1)
    assert ax.ReadBuffer(2) == 0
    chip.write_memory(0x3FFF, [9])
    assert ax.ReadBuffer(2) == 9


@pytest.fixture
def raw():
    path = str(pmdfmu.default_fmu())
    md = read_model_description(path)
    d = extract(path)
    messages = []
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier="PMDMotionProcessor", instanceName="raw")
    from fmpy.fmi2 import fmi2CallbackFunctions, fmi2CallbackLoggerTYPE

    callbacks = fmi2CallbackFunctions()
    callbacks.logger = fmi2CallbackLoggerTYPE(lambda env, name, status, cat, msg: messages.append(msg.decode()))
    fmu.instantiate(callbacks=callbacks)
    fmu.messages = messages
    yield fmu
    fmu.freeInstance()


def test_calls_in_the_wrong_state_are_errors(raw):
    with pytest.raises(FMICallException):
        raw.doStep(0.0, 1e-4)
    with pytest.raises(FMICallException):
        raw.exitInitializationMode()
    raw.setupExperiment(startTime=0.0)
    raw.enterInitializationMode()
    with pytest.raises(FMICallException):
        raw.setupExperiment(startTime=0.0)
    raw.exitInitializationMode()
    raw.doStep(0.0, 1e-4)
    assert any("fmi2DoStep: not allowed in instantiated" in m for m in raw.messages)


def test_null_arrays_are_errors(raw):
    raw.setupExperiment(startTime=0.0)
    raw.enterInitializationMode()
    raw.exitInitializationMode()
    assert raw._functions["fmi2GetInteger"](raw.component, None, 2, None) == 3
    assert raw._functions["fmi2SetReal"](raw.component, None, 1, None) == 3
    assert any("NULL" in m for m in raw.messages)
    assert raw._functions["fmi2GetInteger"](raw.component, None, 0, None) == 0  # nothing asked: fine


def test_unsupported_functions_say_so(raw):
    assert raw._functions["fmi2GetDirectionalDerivative"](raw.component, None, 0, None, 0, None, None) == 3
    assert raw._functions["fmi2CancelStep"](raw.component) == 3
    assert any("fmi2GetDirectionalDerivative: not supported" in m for m in raw.messages)
    assert any("fmi2CancelStep: not supported" in m for m in raw.messages)


def test_a_wrong_guid_is_refused(capfd):
    path = str(pmdfmu.default_fmu())
    fmu = FMU2Slave(
        guid="{00000000-0000-0000-0000-000000000000}",
        unzipDirectory=extract(path),
        modelIdentifier="PMDMotionProcessor",
        instanceName="wrong",
    )
    with pytest.raises(Exception, match="Failed to instantiate"):  # FMPy's own Exception for a NULL instance
        fmu.instantiate()
    out = capfd.readouterr().out
    assert "fmi2Instantiate: the GUID {00000000-0000-0000-0000-000000000000} does not match this binary's {" in out


@pytest.mark.parametrize("start", [math.nan, math.inf, 1e300])
def test_a_start_time_off_the_cycle_grid_is_refused(raw, start):
    """Found by fuzzing: a NaN or huge start time must not reach the cycle index."""
    with pytest.raises(FMICallException):
        raw.setupExperiment(startTime=start)  # refused where it arrives (no state holds it)
        raw.enterInitializationMode()
    assert any("fmi2SetupExperiment: time" in m and "2^53 cycles" in m for m in raw.messages)
