# SPDX-License-Identifier: BSD-2-Clause
"""Every command a Navigator accepts is accepted: the
command table is the Navigator set of the MC2440's C-Motion (pmd-reference S3),
each command runs through the harness and as raw host words, the hardware
registers keep what they are set to across their ranges and refuse the rest
with the documented code, Reset restores reference 4.2's values, the filter
group is double-buffered, only the Magellan's opcodes answer 0x02, and a
C-Motion initialization of the kind the seeds and the MC2440 application
describe runs without an error."""

import pytest

import pmdfmu
from pmdfmu import (
    COMMANDS,
    PMD_ERR_InvalidInstruction,
    PMD_ERR_InvalidParameter,
    PMDActivityInMotionMask,
    PMDActivityPhasingInitializedMask,
    PMDError,
    tables,
)
from pmdfmu.docs import hardware, out_of_scope
from states import command, op

REGISTERS = {r.name: r for r in tables.read_registers(pmdfmu.tables_dir() / "registers.csv")}
FIELD_RANGE = {"u16": (0, 0xFFFF), "i16": (-0x8000, 0x7FFF), "u32": (0, 0xFFFFFFFF), "i32": (-0x80000000, 0x7FFFFFFF)}

# The Navigator's opcodes: the PMDOP* enum of the MC2440's C-Motion (pmd-reference S3, UCtypes.h), transcribed.
NAVIGATOR = {
    0x00,
    0x06,
    0x07,
    0x0F,
    0x10,
    0x11,
    0x13,
    0x14,
    0x1A,
    0x1D,
    0x1E,
    0x25,
    0x26,
    0x27,
    0x2B,
    0x2C,
    0x2D,
    0x2F,
    0x31,
    0x34,
    0x36,
    0x37,
    0x38,
    0x39,
    0x3A,
    0x3E,
    0x47,
    0x4A,
    0x4B,
    0x4C,
    0x4D,
    0x50,
    0x51,
    0x52,
    0x54,
    0x56,
    0x58,
    0x59,
    0x5B,
    0x61,
    0x69,
    0x6A,
    0x6B,
    0x6E,
    0x72,
    0x75,
    0x76,
    0x77,
    0x7A,
    0x7B,
    0x7C,
    0x7D,
    *range(0x80, 0xCC),
    0xCE,
    0xCF,
    *range(0xD0, 0xF0),
    0xF2,
    0xF3,
    0xF5,
    0xF8,
}
# pmd-reference 1.2, "opcode gaps": the Magellan's opcodes the Navigator lacks
MAGELLAN_GAPS = {
    *range(0x02, 0x0E),
    0x1B,
    0x1C,
    *range(0x40, 0x4A),
    0x53,
    0x55,
    0x57,
    0x5A,
    0x5E,
    0x5F,
    *range(0x60, 0x69),
    0x6C,
    0x6D,
    0x71,
    0x73,
    0x74,
    0xF6,
    0xF7,
    *range(0xF9, 0xFD),
} - NAVIGATOR
# the commands out_of_scope.csv listed before the Navigator set was complete: the filter group's and the motor's (a4cb061), then the
# hardware's (all of which hardware.csv describes)
FILTER_OPCODES = {
    0x25,
    0x50,
    0x26,
    0x51,
    0x27,
    0x52,
    0x2B,
    0x54,
    0x93,
    0x94,
    0x9E,
    0x9F,
    0x95,
    0x96,
    0x9C,
    0x9D,
    0x77,
    0x69,
    0x3A,
    0x9A,
    0x9B,
    0x06,
    0x07,
    0x0F,
    0x2D,
}
HARDWARE_OPCODES = {
    0xE0,
    0x6E,
    0x6A,
    0x6B,
    0x87,
    0x88,
    0xED,
    0xEE,
    0x8B,
    0x8C,
    0x89,
    0x8A,
    0x82,
    0x83,
    0xEF,
    0xF8,
    0xDA,
    0xDB,
    0x8D,
    0x8E,
    0xBE,
    0xBF,
    0xDE,
    0xDF,
    0xCF,
    0xCE,
    0xF2,
    0xF3,
    0x2C,
    0x72,
    0x75,
    0x76,
    0x7A,
    0x7B,
    0x7C,
    0x7D,
    0xE2,
    0xE3,
    0xE4,
    0xE5,
    0xE6,
    0xE7,
    0xE8,
    0xE9,
    0xEA,
    0x84,
    0x85,
    0x86,
}
CHECKSUM = 0x12345678  # GetChecksum: what the MC2440 application's self-test expects (S3, PMDsetup.c)


def valid_args(c):
    """Arguments the command accepts on a chip whose buffers 0 (the trace's) and 2 hold 4 words."""
    special = {
        "SetSampleTime": (100,),
        "SetBufferFunction": (pmdfmu.PMDBufferFunctionPosition, 2),
        "SetTraceStart": (0, pmdfmu.PMDTraceConditionUpdate, 0, 0),
    }
    if c.name in special:
        return special[c.name]
    register = REGISTERS.get(c.name[3:]) if c.name.startswith("Set") else None
    return tuple(
        2 if f.name == "bufferID" else register.low if register and register.low is not None else 0 for f in c.args
    )


def ready(chip):
    chip.axis(0).SetBufferLength(0, 4)
    chip.axis(0).SetBufferLength(2, 4)
    chip.axis(0).GetHostIOError()


# ---- the tables -------------------------------------------------------------------------------------


def test_the_command_table_is_the_navigator_set():
    assert {c.opcode for c in COMMANDS.values()} == NAVIGATOR


def test_the_out_of_scope_table_holds_the_magellan_gaps_and_nothing_of_the_navigator():
    refused = {opcode for opcode, _, _ in out_of_scope()}
    assert MAGELLAN_GAPS <= refused
    assert not refused & NAVIGATOR
    assert FILTER_OPCODES | HARDWARE_OPCODES <= NAVIGATOR


def test_the_hardware_table_says_what_every_hardware_command_does_here():
    names = [name for _, commands, _ in hardware() for name in commands]
    assert len(names) == len(set(names)) and set(names) <= set(COMMANDS)
    assert {COMMANDS[n].opcode for n in names} == HARDWARE_OPCODES
    assert all(here for _, _, here in hardware())


# ---- every command is accepted ----------------------------------------------------------------------


def test_every_command_is_accepted_as_raw_host_words(any_chip):
    """Each executed (error 0) in a batch that goes on after it: its word counts are right."""
    failed = []
    for name, c in sorted(COMMANDS.items()):
        ready(any_chip)
        error, reply = any_chip.batch(command(name, *valid_args(c), axis=1) + [op("GetTime")])
        if error or len(reply) != c.reply_words + 2:
            failed.append((name, hex(error), len(reply)))
    assert not failed


def test_every_command_is_accepted_through_the_harness(chip):
    failed = []
    for name, c in sorted(COMMANDS.items()):
        ready(chip)
        try:
            result = getattr(chip.axis(2), name)(*valid_args(c))
        except PMDError as e:
            failed.append((name, e.code))
            continue
        shape = None if not c.reply else len(result) if len(c.reply) > 1 else 1
        if shape != (len(c.reply) or None):
            failed.append((name, result))
    assert not failed


@pytest.mark.parametrize("opcode", sorted(FILTER_OPCODES | HARDWARE_OPCODES))
def test_the_commands_refused_before_issue_13_are_executed(chip, opcode):
    name = next(c.name for c in COMMANDS.values() if c.opcode == opcode)
    error, reply = chip.batch(command(name, *valid_args(COMMANDS[name])) + [op("GetTime")])
    assert (error, len(reply)) == (0, COMMANDS[name].reply_words + 2), name


@pytest.mark.parametrize("opcode", sorted(op_ for op_, _, _ in out_of_scope()))
def test_a_magellan_opcode_answers_invalid_instruction_and_ends_the_batch(chip, opcode):
    chip.axis(0).GetHostIOError()
    error, reply = chip.batch([opcode, op("GetTime"), op("GetTime")])
    assert (error, reply) == (PMD_ERR_InvalidInstruction, [])
    assert chip.axis(0).GetHostIOError() == PMD_ERR_InvalidInstruction
    assert chip.axis(0).GetEventStatus() & pmdfmu.PMDEventInstructionErrorMask


# ---- the registers keep their whole range -----------------------------------------------------------

HARDWARE_REGISTERS = [
    name
    for _, commands, _ in hardware()
    for name in (n[3:] for n in commands if n.startswith("Set"))
    if name in REGISTERS
]


def span(r, kind):
    """Values across a register's range: both ends, their neighbours, the middle, every value of a small one."""
    low, high = (r.low, r.high) if r.low is not None else FIELD_RANGE[kind]
    if high - low < 16:
        return list(range(low, high + 1))
    return sorted({low, low + 1, (low + high) // 2, high - 1, high, low + 0x1234 % (high - low)})


@pytest.mark.parametrize("name", HARDWARE_REGISTERS)
def test_a_hardware_register_keeps_every_value_of_its_range_on_every_axis(chip, name):
    r = REGISTERS[name]
    axes = range(1) if COMMANDS["Set" + name].scope == "chip" else range(4)
    for value in span(r, COMMANDS["Set" + name].args[0].kind):
        for n in axes:
            getattr(chip.axis(n), "Set" + name)(value)
            assert getattr(chip.axis(n), "Get" + name)() == value, (name, n, value)


# Set, Get, a value other than the reset value, and the reset value (registers.csv's decisions, [L] where
# reference 4.2 gives none)
HARDWARE_ROUND_TRIPS = [
    ("SetOutputMode", "GetOutputMode", pmdfmu.PMDMotorOutputPWM5050Magnitude, pmdfmu.PMDMotorOutputDAC),
    ("SetStartVelocity", "GetStartVelocity", 0x18000, 0),
    ("SetAxisMode", "GetAxisMode", pmdfmu.PMDAxisOff, pmdfmu.PMDAxisOn),
    ("SetEncoderSource", "GetEncoderSource", pmdfmu.PMDEncoderSourceParallel, pmdfmu.PMDEncoderSourceIncremental),
    ("SetEncoderModulus", "GetEncoderModulus", 360, 0),
    ("SetActualPositionUnits", "GetActualPositionUnits", pmdfmu.PMDSteps, pmdfmu.PMDCounts),
    ("SetStepRange", "GetStepRange", 4, 1),
    (
        "SetCommutationMode",
        "GetCommutationMode",
        pmdfmu.PMDCommutationModeHallBased,
        pmdfmu.PMDCommutationModeSinusoidal,
    ),
    ("SetNumberPhases", "GetNumberPhases", 2, 3),
    ("SetPhaseInitializeMode", "GetPhaseInitializeMode", pmdfmu.PMDPhaseInitHallBased, pmdfmu.PMDPhaseInitAlgorithmic),
    ("SetPhaseInitializeTime", "GetPhaseInitializeTime", 1000, 0),
    ("SetPhasePrescale", "GetPhasePrescale", pmdfmu.PMDPhasePrescaleOn, pmdfmu.PMDPhasePrescaleOff),
    (
        "SetPhaseCorrectionMode",
        "GetPhaseCorrectionMode",
        pmdfmu.PMDPhaseCorrectionEnabled,
        pmdfmu.PMDPhaseCorrectionDisabled,
    ),
    ("SetPhaseCounts", "GetPhaseCounts", 2000, 0),
    ("SetPhaseOffset", "GetPhaseOffset", 500, 0),
    ("SetPhaseAngle", "GetPhaseAngle", 1234, 0),
    (
        "SetDiagnosticPortMode",
        "GetDiagnosticPortMode",
        pmdfmu.PMDDiagnosticPortModeFull,
        pmdfmu.PMDDiagnosticPortModeLimited,
    ),
    ("SetSynchronizationMode", "GetSynchronizationMode", pmdfmu.PMDSynchSlaveNode, pmdfmu.PMDSynchDisabled),
]


def test_the_round_trips_name_every_hardware_register():
    assert sorted(setter for setter, *_ in HARDWARE_ROUND_TRIPS) == sorted("Set" + n for n in HARDWARE_REGISTERS)


@pytest.mark.parametrize("setter,getter,value,reset", HARDWARE_ROUND_TRIPS)
def test_a_hardware_register_reads_back_and_resets_to_its_decided_value(any_chip, setter, getter, value, reset):
    ax = any_chip.axis(3)
    assert getattr(ax, getter)() == reset
    getattr(ax, setter)(value)
    assert getattr(ax, getter)() == value
    ax.Reset()
    assert getattr(ax, getter)() == reset


def refused(call, *args, code=PMD_ERR_InvalidParameter):
    with pytest.raises(PMDError) as e:
        call(*args)
    assert e.value.code == code


def test_axis_out_source_keeps_each_field_and_refuses_an_axis_or_register_it_lacks(chip):
    for n in range(4):
        ax = chip.axis(n)
        for source_axis in range(4):
            for register in range(4):
                bit = (5 * source_axis + 3 * register + n) % 16
                ax.SetAxisOutSource(source_axis, bit, register)
                assert ax.GetAxisOutSource() == (source_axis, bit, register)
        for bit in range(16):
            ax.SetAxisOutSource(n, bit, pmdfmu.PMDAxisOutSourceActivityStatus)
            assert ax.GetAxisOutSource() == (n, bit, pmdfmu.PMDAxisOutSourceActivityStatus)
    ax = chip.axis(1)
    ax.SetAxisOutSource(3, 9, pmdfmu.PMDAxisOutSourceSignalStatus)
    for args in [(4, 0, 0), (15, 0, 1), (0, 0, 4), (0, 15, 15)]:
        refused(ax.SetAxisOutSource, *args)
        assert ax.GetAxisOutSource() == (3, 9, pmdfmu.PMDAxisOutSourceSignalStatus)
    assert [chip.axis(n).GetAxisOutSource() for n in (0, 2, 3)] == [(0, 15, 2), (2, 15, 2), (3, 15, 2)]


SERIAL = ["baud", "parity", "stopBits", "protocol", "multiDropID"]
SERIAL_VALUES = {
    "baud": range(8),
    "parity": range(3),
    "stopBits": range(2),
    "protocol": (0, 2, 3),
    "multiDropID": range(32),
}


def test_serial_port_mode_keeps_each_field_across_its_values_and_is_chip_wide(chip):
    base = {
        "baud": pmdfmu.PMDSerialBaud19200,
        "parity": pmdfmu.PMDSerialParityOdd,
        "stopBits": 1,
        "protocol": pmdfmu.PMDSerialProtocolMultiDropUsingAddressBit,
        "multiDropID": 17,
    }
    for field in SERIAL:
        for value in SERIAL_VALUES[field]:
            mode = [value if f == field else base[f] for f in SERIAL]
            chip.axis(value % 4).SetSerialPortMode(*mode)
            assert all(chip.axis(n).GetSerialPortMode() == tuple(mode) for n in range(4))


@pytest.mark.parametrize("field,value", [("baud", 8), ("baud", 15), ("parity", 3), ("protocol", 1)])
def test_serial_port_mode_refuses_a_code_the_navigator_lacks(chip, field, value):
    ax = chip.axis(0)
    before = ax.GetSerialPortMode()
    mode = [value if f == field else 0 for f in SERIAL]
    refused(ax.SetSerialPortMode, *mode)
    assert ax.GetSerialPortMode() == before


def test_serial_port_mode_refuses_the_reserved_bits(chip):
    error, _ = chip.batch(command("SetSerialPortMode", 0, 0, 0, 0, 0)[:1] + [0x0200])
    assert error == PMD_ERR_InvalidParameter
    assert chip.axis(0).GetSerialPortMode() == (pmdfmu.PMDSerialBaud57600, 0, 0, 0, 0)


def test_encoder_to_step_ratio_keeps_both_words_on_its_axis(chip):
    for counts, steps in [(0, 0), (0xFFFF, 1), (4000, 12800), (0xFFFF, 0xFFFF), (1, 1)]:
        for n in range(4):
            chip.axis(n).SetEncoderToStepRatio(*((counts, steps) if n % 2 else (steps, counts)))
        for n in range(4):
            assert chip.axis(n).GetEncoderToStepRatio() == ((counts, steps) if n % 2 else (steps, counts))


def test_write_io_drives_the_io_output_of_its_address(any_chip):
    for address in range(16):
        any_chip.axis(address % 4).WriteIO(address, 0x1111 * address ^ 7)
    for address in range(16):
        assert any_chip.get(f"io.output[{address + 1}]") == 0x1111 * address ^ 7
    any_chip.axis(0).WriteIO(15, 0xFFFF)
    assert any_chip.get("io.output[16]") == 0xFFFF


def test_read_io_reads_the_io_input_of_its_address(any_chip):
    for address in range(16):
        any_chip.set(f"io.input[{address + 1}]", 0xF00F ^ address * 0x0101)
    for address in range(16):
        assert any_chip.axis(3).ReadIO(address) == 0xF00F ^ address * 0x0101


@pytest.mark.parametrize("call", ["WriteIO", "ReadIO"])
def test_an_address_the_io_bus_does_not_decode_is_refused_naming_the_bus_range(call):
    with pmdfmu.Chip(log_categories=["errors"]) as chip:
        chip.axis(0).WriteIO(0, 42)
        for address in (16, 0x100, 0xFFFF):
            chip.messages.clear()
            refused(getattr(chip.axis(0), call), *((address, 1) if call == "WriteIO" else (address,)))
            assert "0..15" in " ".join(m.message for m in chip.messages)
        assert [chip.get(f"io.output[{a + 1}]") for a in range(16)] == [42] + [0] * 15


def test_read_analog_reads_the_analog_input_of_its_channel(any_chip):
    for channel in range(8):
        any_chip.set(f"analog[{channel + 1}]", 0x2000 * channel + 0x1FF)
    for channel in range(8):
        assert any_chip.axis(channel % 4).ReadAnalog(channel) == 0x2000 * channel + 0x1FF
    refused(any_chip.axis(0).ReadAnalog, 8)
    refused(any_chip.axis(0).ReadAnalog, 0xFFFF)


def test_reset_clears_the_io_outputs_and_keeps_the_plant_inputs(chip):
    chip.set("analog[2]", 300)
    chip.set("io.input[5]", 0xABCD)
    chip.axis(0).WriteIO(3, 99)
    chip.axis(0).Reset()
    assert (chip.axis(0).ReadAnalog(1), chip.axis(0).ReadIO(4), chip.get("io.output[4]")) == (300, 0xABCD, 0)


def test_get_checksum_answers_the_value_a_navigator_self_test_expects(chip):
    assert chip.axis(2).GetChecksum() == CHECKSUM


def test_initialize_phase_completes_at_once_and_reset_clears_it(chip):
    ax = chip.axis(1)
    assert not ax.GetActivityStatus() & PMDActivityPhasingInitializedMask
    ax.InitializePhase()
    assert ax.GetActivityStatus() & PMDActivityPhasingInitializedMask
    assert chip.get("axis2.activityStatus") & PMDActivityPhasingInitializedMask
    assert not any(chip.axis(n).GetActivityStatus() & PMDActivityPhasingInitializedMask for n in (0, 2, 3))
    chip.run(10)
    assert ax.GetActivityStatus() & PMDActivityPhasingInitializedMask
    ax.Reset()
    assert not ax.GetActivityStatus() & PMDActivityPhasingInitializedMask


def test_the_phase_commands_are_the_motor_command_on_phase_a_and_0_on_b_and_c(chip):
    ax = chip.axis(3)
    ax.SetMotorMode(pmdfmu.PMDMotorOff)
    ax.SetMotorCommand(-1234)
    ax.Update()
    chip.run(2)
    assert ax.GetCurrentMotorCommand() == -1234
    assert [ax.GetPhaseCommand(p) for p in (pmdfmu.PMDPhaseA, pmdfmu.PMDPhaseB, pmdfmu.PMDPhaseC)] == [-1234, 0, 0]
    for phase in (3, 0xFFFF):
        refused(ax.GetPhaseCommand, phase)


def test_the_hardware_commands_do_not_disturb_a_move(chip):
    """Idle hardware: the commutation, encoder, step and port settings leave the trajectory as it was."""

    def move(c, configure):
        ax = c.axis(0)
        if configure:
            ax.SetCommutationMode(pmdfmu.PMDCommutationModeMicrostepping)
            ax.SetEncoderSource(pmdfmu.PMDEncoderSourceParallel)
            ax.SetActualPositionUnits(pmdfmu.PMDSteps)
            ax.SetEncoderToStepRatio(4000, 12800)
            ax.SetOutputMode(pmdfmu.PMDMotorOutputPWM5050Magnitude)
            ax.SetStartVelocity(0x8000)
            ax.SetSynchronizationMode(pmdfmu.PMDSynchMasterNode)
            ax.SetPhaseAngle(100)
        ax.SetPosition(2000)
        ax.SetVelocity(0x40000)
        ax.SetAcceleration(0x800)
        ax.Update()
        positions = []
        for _ in range(20):
            c.run(25)
            positions.append((ax.GetCommandedPosition(), ax.GetActualPosition(), ax.GetEventStatus()))
        return positions

    with pmdfmu.Chip() as plain:
        assert move(chip, True) == move(plain, False)
    assert chip.axis(0).GetPhaseAngle() == 100


# ---- reset values (reference 4.2) -------------------------------------------------------------------

# reference 4.2 (and 3.3 for the serial port), by Get command: the value after a Reset
RESET_4_2 = {
    "GetKp": 0,
    "GetKi": 0,
    "GetKd": 0,
    "GetKvff": 0,
    "GetKaff": 0,
    "GetIntegrationLimit": 0,
    "GetDerivativeTime": 1,
    "GetKout": 65535,
    "GetMotorLimit": 32767,
    "GetMotorBias": 0,
    "GetMotorCommand": 0,
    "GetPositionErrorLimit": 65535,
    "GetStartVelocity": 0,
    "GetEncoderModulus": 0,
    "GetCaptureSource": 0,
    "GetStepRange": 1,
    "GetEncoderToStepRatio": (1, 1),
    "GetAxisMode": pmdfmu.PMDAxisOn,
    "GetSettleTime": 0,
    "GetSettleWindow": 0,
    "GetTrackingWindow": 0,
    "GetMotionCompleteMode": 0,
    "GetGearMaster": (0, 0),
    "GetInterruptMask": 0,
    "GetSerialPortMode": (
        pmdfmu.PMDSerialBaud57600,
        pmdfmu.PMDSerialParityNone,
        pmdfmu.PMDSerial1StopBit,
        pmdfmu.PMDSerialProtocolPoint2Point,
        0,
    ),
}
CHANGED = {  # a value other than the reset value for each Set of RESET_4_2
    "SetKp": (5,),
    "SetKi": (6,),
    "SetKd": (7,),
    "SetKvff": (8,),
    "SetKaff": (9,),
    "SetIntegrationLimit": (1000,),
    "SetDerivativeTime": (4,),
    "SetKout": (100,),
    "SetMotorLimit": (20000,),
    "SetMotorBias": (-300,),
    "SetMotorCommand": (2000,),
    "SetPositionErrorLimit": (5,),
    "SetStartVelocity": (0x10000,),
    "SetEncoderModulus": (360,),
    "SetCaptureSource": (1,),
    "SetStepRange": (3,),
    "SetEncoderToStepRatio": (4000, 12800),
    "SetAxisMode": (pmdfmu.PMDAxisOff,),
    "SetSettleTime": (10,),
    "SetSettleWindow": (11,),
    "SetTrackingWindow": (12,),
    "SetMotionCompleteMode": (1,),
    "SetGearMaster": (1, 1),
    "SetInterruptMask": (0x10,),
    "SetSerialPortMode": (
        pmdfmu.PMDSerialBaud416667,
        pmdfmu.PMDSerialParityEven,
        pmdfmu.PMDSerial2StopBits,
        pmdfmu.PMDSerialProtocolMultiDropUsingIdleLineDetection,
        31,
    ),
}


def test_reset_restores_reference_4_2_on_every_axis(any_chip):
    assert {"Set" + name[3:] for name in RESET_4_2} == set(CHANGED)
    changed = {name: CHANGED["Set" + name[3:]] for name in RESET_4_2}
    changed = {name: args if len(args) > 1 else args[0] for name, args in changed.items()}
    for n in range(4):
        for name, args in CHANGED.items():
            getattr(any_chip.axis(n), name)(*args)
    for n in range(4):
        assert {name: getattr(any_chip.axis(n), name)() for name in RESET_4_2} == changed, n
    any_chip.axis(2).Reset()
    for n in range(4):
        assert {name: getattr(any_chip.axis(n), name)() for name in RESET_4_2} == RESET_4_2, n


# ---- the filter group is double-buffered ------------------------------------------------------------


def test_the_open_loop_motor_command_acts_at_update_not_before(chip):
    ax = chip.axis(1)
    ax.SetMotorMode(pmdfmu.PMDMotorOff)
    ax.SetMotorCommand(3000)
    chip.run(3)
    assert (ax.GetMotorCommand(), ax.GetCurrentMotorCommand()) == (3000, 0)  # Get reads the buffered register
    ax.Update()
    chip.run(1)
    assert ax.GetCurrentMotorCommand() == 3000


def test_multi_update_applies_the_filter_group_of_the_masked_axes_only(chip):
    for n in range(4):
        chip.axis(n).SetMotorMode(pmdfmu.PMDMotorOff)
        chip.axis(n).SetMotorCommand(100 * (n + 1))
    chip.axis(0).MultiUpdate(pmdfmu.PMDAxis1Mask | pmdfmu.PMDAxis3Mask)
    chip.run(1)
    assert [chip.axis(n).GetCurrentMotorCommand() for n in range(4)] == [100, 0, 300, 0]


def test_a_gain_acts_at_update_not_before():
    """Closed loop (motor on) at rest, the encoder 100 counts off: Kp set and not yet updated leaves the
    motor command at 0; Update makes it act."""
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        chip.set("axis1.actualPosition", 100)
        ax.SetKp(50)
        chip.run(2)
        assert (ax.GetKp(), ax.GetPositionError(), ax.GetCurrentMotorCommand()) == (50, 100, 0)
        ax.Update()
        chip.run(1)
        assert ax.GetCurrentMotorCommand() != 0


# ---- a C-Motion initialization ----------------------------------------------------------------------


def initialization(axis):
    """(command, arguments) of one axis's set-up, as the seeds (filter gains and integration limit, seed 004;
    PID, feedforward, motor bias and limit, output, seed 001) and the MC2440 application's chip set-up
    (reference S3, PMDsetup.c) send them, then a trapezoidal move and Update."""
    return [
        ("SetKp", 200),
        ("SetKi", 16),
        ("SetKd", 800),
        ("SetKvff", 300),
        ("SetKaff", 0),
        ("SetKout", 0xFFFF),
        ("SetIntegrationLimit", 50000),
        ("SetDerivativeTime", 1),
        ("SetMotorLimit", 30000),
        ("SetMotorBias", -200),
        ("SetOutputMode", pmdfmu.PMDMotorOutputPWMSignMagnitude),
        ("SetCommutationMode", pmdfmu.PMDCommutationModeSinusoidal),
        ("SetNumberPhases", 3),
        ("SetPhaseCounts", 2000),
        ("SetPhaseInitializeMode", pmdfmu.PMDPhaseInitAlgorithmic),
        ("SetPhaseInitializeTime", 500),
        ("SetPhasePrescale", pmdfmu.PMDPhasePrescaleOff),
        ("SetPhaseCorrectionMode", pmdfmu.PMDPhaseCorrectionEnabled),
        ("SetPhaseOffset", 0),
        ("InitializePhase",),
        ("SetEncoderSource", pmdfmu.PMDEncoderSourceIncremental),
        ("SetEncoderToStepRatio", 4000, 4000),
        ("SetActualPositionUnits", pmdfmu.PMDCounts),
        ("SetSignalSense", pmdfmu.PMDSignalMotorOutputInvertMask),
        ("SetLimitSwitchMode", pmdfmu.PMDLimitEnabled),
        ("SetPositionErrorLimit", 2000),
        ("SetTrackingWindow", 50),
        ("SetSettleWindow", 10),
        ("SetSettleTime", 20),
        ("SetMotionCompleteMode", pmdfmu.PMDMotionCompleteCommandedPosition),
        ("SetAutoStopMode", pmdfmu.PMDAutoStopEnabled),
        ("SetAxisMode", pmdfmu.PMDAxisOn),
        ("SetMotorMode", pmdfmu.PMDMotorOn),
        ("SetMotorCommand", 0),
        ("ResetEventStatus", 0),
        ("SetProfileMode", pmdfmu.PMDTrapezoidalProfile),
        ("SetPosition", 1000 * (axis + 1)),
        ("SetVelocity", 0x100000),
        ("SetAcceleration", 0x4000),
        ("SetDeceleration", 0x4000),
        ("Update",),
    ]


PREAMBLE = [
    ("Reset",),
    ("GetHostIOError",),
    ("GetVersion",),
    ("GetChecksum",),
    ("SetSampleTime", 200),
    ("SetSerialPortMode", pmdfmu.PMDSerialBaud57600, 0, 0, 0, 0),
    ("SetDiagnosticPortMode", pmdfmu.PMDDiagnosticPortModeLimited),
    ("SetSynchronizationMode", pmdfmu.PMDSynchDisabled),
]


def check_initialized(chip):
    for n in range(4):
        ax = chip.axis(n)
        assert (ax.GetKp(), ax.GetKd(), ax.GetIntegrationLimit(), ax.GetMotorLimit(), ax.GetMotorBias()) == (
            200,
            800,
            50000,
            30000,
            -200,
        )
        assert ax.GetOutputMode() == pmdfmu.PMDMotorOutputPWMSignMagnitude
        assert (
            ax.GetActivityStatus() & (PMDActivityInMotionMask | PMDActivityPhasingInitializedMask)
            == PMDActivityInMotionMask | PMDActivityPhasingInitializedMask
        )
    assert chip.axis(0).GetSampleTime() == 200
    chip.run(600)
    assert [chip.axis(n).GetCommandedPosition() for n in range(4)] == [1000, 2000, 3000, 4000]
    assert chip.axis(0).GetHostIOError() == 0


def test_a_c_motion_initialization_runs_through_the_harness(any_chip):
    ax0 = any_chip.axis(0)
    for name, *args in PREAMBLE:
        result = getattr(ax0, name)(*args)
        if name == "GetHostIOError":
            assert result == pmdfmu.PMD_ERR_ChipsetReset
        if name == "GetChecksum":
            assert result == CHECKSUM
    for n in range(4):
        for name, *args in initialization(n):
            getattr(any_chip.axis(n), name)(*args)
    check_initialized(any_chip)


def test_a_c_motion_initialization_runs_as_raw_host_words(any_chip):
    """The same sequence as words on host.word / host.strobe, in batches of at most 64 words."""
    calls = [(0, call) for call in PREAMBLE] + [(n, call) for n in range(4) for call in initialization(n)]
    batch, replies = [], []
    for n, (name, *args) in calls + [(None, (None,))]:
        words = command(name, *args, axis=n) if name else []
        if batch and (not words or len(batch) + len(words) > 64):
            error, reply = any_chip.batch(batch)
            assert error == 0, hex(error)
            replies += reply
            batch = []
        batch += words
    # GetHostIOError (1 after the Reset), GetVersion (2 words), GetChecksum (2 words, high first)
    assert replies[0] == pmdfmu.PMD_ERR_ChipsetReset
    assert pmdfmu.field_ex(replies[1], "PMDVersionGeneration") == 2
    assert replies[3] << 16 | replies[4] == CHECKSUM
    check_initialized(any_chip)


def test_the_filter_update_and_the_moves_update_in_one_batch(any_chip):
    """C-Motion set-ups often apply the gains with their own Update and then start the move with another,
    with no cycle between: the first Update leaves a trapezoidal 'move' standing on its destination, which is
    at rest, so the second may change the acceleration (seed 001 refuses that only in motion)."""
    ax = any_chip.axis(0)
    assert ax.GetHostIOError() == pmdfmu.PMD_ERR_ChipsetReset
    ax.SetKp(200)
    ax.SetKd(800)
    ax.Update()
    ax.SetPosition(1000)
    ax.SetVelocity(0x100000)
    ax.SetAcceleration(0x4000)
    ax.Update()
    assert ax.GetHostIOError() == 0 and ax.GetKp() == 200
    any_chip.run(600)
    assert ax.GetCommandedPosition() == 1000
    # in motion, the acceleration still may not change (seed 001): only the destination is applied
    ax.SetPosition(5000)
    ax.Update()
    any_chip.run(5)
    ax.SetAcceleration(0x8000)
    ax.SetPosition(6000)
    with pytest.raises(PMDError) as refusal:
        ax.Update()
    assert refusal.value.code == pmdfmu.PMD_ERR_InvalidParameterChange


def test_the_axis_out_level_follows_its_source_bit_in_the_signal_status(chip):
    """SetAxisOutSource(axis, bit, register): GetSignalStatus's AxisOut bit is the chosen status bit, so a
    breakpoint or a trace can key on it; source none reads low; the sense bit inverts it."""
    ax, mover = chip.axis(0), chip.axis(1)
    axis_out = lambda: bool(ax.GetSignalStatus() & pmdfmu.PMDSignalAxisOutMask)
    assert not axis_out()  # reset: source none
    in_motion = pmdfmu.PMDActivityInMotionMask.bit_length() - 1
    ax.SetAxisOutSource(1, in_motion, pmdfmu.PMDAxisOutSourceActivityStatus)
    assert not axis_out()
    mover.SetPosition(500)
    mover.SetVelocity(0x10000)
    mover.SetAcceleration(0x1000)
    mover.Update()
    assert axis_out()  # axis 2 in motion
    ax.SetSignalSense(pmdfmu.PMDSignalAxisOutMask)
    assert not axis_out()
    ax.SetSignalSense(0)
    chip.run(2000)
    assert mover.GetCommandedPosition() == 500 and not axis_out()
    # an event bit: axis 2's motion complete, until reset
    ax.SetAxisOutSource(1, 0, pmdfmu.PMDAxisOutSourceEventStatus)
    assert axis_out()
    mover.ResetEventStatus(0)
    assert not axis_out()
    # a signal bit of its own status (the home input), read without AxisOut bits: no circle
    home = pmdfmu.PMDSignalEncoderHomeMask.bit_length() - 1
    ax.SetAxisOutSource(0, home, pmdfmu.PMDAxisOutSourceSignalStatus)
    assert axis_out()  # home idle: reads 1
    chip.set("axis1.home", True)
    assert not axis_out()
    axis_out_bit = pmdfmu.PMDSignalAxisOutMask.bit_length() - 1
    ax.SetAxisOutSource(0, axis_out_bit, pmdfmu.PMDAxisOutSourceSignalStatus)
    assert not axis_out()
    ax.SetAxisOutSource(0, 0, pmdfmu.PMDAxisOutSourceNone)
    assert not axis_out()
