# SPDX-License-Identifier: BSD-2-Clause
"""The motor output and the peripheral bus as FMU variables: every
axis's `motorCommand` (GetCurrentMotorCommand, Int16) and `motorOutput` (the
fraction of full scale, Float64), the analog inputs `analog[1..8]` that
ReadAnalog reads, and the I/O bus `io.input[1..16]` (ReadIO) and
`io.output[1..16]` (WriteIO), through FMI 2 and FMI 3: their declarations, start
values, reads and sets and refusals, the chip's Reset (the inputs are wires and
stay, the latched outputs go to 0), FMU states, recording and the commands."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import PMDError
from states import InitializationChip, command, pend_batch, snapshot, vr

FMU_PAGE = Path(__file__).resolve().parent.parent / "docs" / "fmu.md"
AXES = range(1, 5)
# name: (FMI 2 type, FMI 3 type, causality, start, elements, value reference of axis 1 / element 1)
PER_AXIS = {
    "motorCommand": ("Integer", "Int16", "output", None, 1, 108),
    "motorOutput": ("Real", "Float64", "output", None, 1, 109),
}
ARRAYS = {
    "analog": ("Integer", "UInt16", "input", "0", 8, 1601),
    "io.input": ("Integer", "UInt16", "input", "0", 16, 1701),
    "io.output": ("Integer", "UInt16", "output", None, 16, 1801),
}
FULL_SCALE = 32768  # the 16-bit motor command's 2^15: 100/2^15 % of full scale per count


def description(fmi_version):
    return {v.name: v for v in read_model_description(str(pmdfmu.chip.default_fmu(fmi_version))).modelVariables}


def io_words(chip, name):
    """An array's values through raw FMI calls: FMI 2 element by element, FMI 3 whole."""
    n = ARRAYS[name][4]
    if chip.fmi_version == 2:
        return chip.fmu.getInteger([vr(chip, f"{name}[{i + 1}]") for i in range(n)])
    return chip.fmu.getUInt16([vr(chip, name)], nValues=n)


def set_words(chip, name, values):
    """Sets a whole input array through raw FMI calls, in one call."""
    if chip.fmi_version == 2:
        chip.fmu.setInteger([vr(chip, f"{name}[{i + 1}]") for i in range(len(values))], values)
    else:
        chip.fmu.setUInt16([vr(chip, name)], values)


def refused(chip, call, *expected):
    """call() must fail with Error, log a message holding every expected text, and change nothing."""
    before = snapshot(chip)
    chip.messages.clear()
    with pytest.raises(FMICallException):
        call()
    errors = [m.message for m in chip.messages if m.status == "Error"]
    assert any(all(e in m for e in expected) for m in errors), (expected, errors)
    assert snapshot(chip) == before


# ---- declarations ----


def test_fmi2_declares_the_motor_outputs_and_the_bus_as_scalars():
    v = description(2)
    for name, (kind, _, causality, start, _, ref) in PER_AXIS.items():
        for n in AXES:
            x = v[f"axis{n}.{name}"]
            assert (x.type, x.causality, x.variability, x.start) == (kind, causality, "discrete", start)
            assert x.valueReference == ref + 100 * (n - 1)
    for name, (kind, _, causality, start, count, ref) in ARRAYS.items():
        for i in range(1, count + 1):
            x = v[f"{name}[{i}]"]
            assert (x.type, x.causality, x.variability, x.start) == (kind, causality, "discrete", start)
            assert x.valueReference == ref + i - 1
        assert f"{name}[{count + 1}]" not in v and name not in v


def test_fmi3_declares_native_types_and_keeps_the_bus_arrays_whole():
    v = description(3)
    for name, (_, kind, causality, start, _, ref) in PER_AXIS.items():
        for n in AXES:
            x = v[f"axis{n}.{name}"]
            assert (x.type, x.causality, x.variability, x.start) == (kind, causality, "discrete", start)
            assert x.valueReference == ref + 100 * (n - 1) and not x.dimensions
    for name, (_, kind, causality, start, count, ref) in ARRAYS.items():
        x = v[name]
        assert (x.type, x.causality, x.variability, x.valueReference) == (kind, causality, "discrete", ref)
        assert int(x.dimensions[0].start) == count
        assert x.start == (" ".join([start] * count) if start else None)
        assert f"{name}[1]" not in v


def test_the_outputs_are_listed_in_both_model_structures():
    for fmi_version in (2, 3):
        md = read_model_description(str(pmdfmu.chip.default_fmu(fmi_version)))
        outputs = {u.variable.name for u in md.outputs}
        assert {f"axis{n}.{q}" for n in AXES for q in PER_AXIS} <= outputs
        assert ({f"io.output[{i}]" for i in range(1, 17)} if fmi_version == 2 else {"io.output"}) <= outputs
        assert not any(o.startswith(("analog", "io.input")) for o in outputs)


# ---- start values, reads and sets ----


def test_a_new_chip_reads_zero_everywhere(any_chip):
    for n in AXES:
        assert any_chip.get(f"axis{n}.motorCommand") == 0
        assert any_chip.get(f"axis{n}.motorOutput") == 0.0
    for name, (_, _, _, _, count, _) in ARRAYS.items():
        assert list(io_words(any_chip, name)) == [0] * count
        assert any_chip.get(name) == [0] * count


@pytest.mark.parametrize("name", ["analog", "io.input"])
def test_an_input_reads_back_what_was_set_over_its_whole_16_bits(any_chip, name):
    count = ARRAYS[name][4]
    values = [0xFFFF, 0, 1, 0x8000, 0x7FFF, 512, 1023, 0xABCD, *range(100, 100 + count - 8)]
    set_words(any_chip, name, values)
    assert list(io_words(any_chip, name)) == values
    any_chip.run(5)  # the chip does not change a wire
    assert any_chip.get(name) == values
    assert [any_chip.get(f"{name}[{i + 1}]") for i in range(count)] == values


def test_the_harness_sets_an_element_or_the_whole_array_by_the_same_names(any_chip):
    any_chip.set("analog[3]", 512)
    any_chip.set("io.input", list(range(16, 32)))
    any_chip.set("io.input[16]", -1)  # the 16-bit two's complement: 0xFFFF
    assert any_chip.get("analog") == [0, 0, 512, 0, 0, 0, 0, 0]
    assert any_chip.get("analog[3]") == 512
    assert any_chip.get("io.input") == list(range(16, 31)) + [0xFFFF]
    with pytest.raises(ValueError, match=r"set: analog\[2\] = 65536 .*does not fit 16 bits"):
        any_chip.set("analog[2]", 65536)
    with pytest.raises(ValueError, match=r"set: analog has 8 elements, 3 values given"):
        any_chip.set("analog", [1, 2, 3])
    assert any_chip.get("analog") == [0, 0, 512, 0, 0, 0, 0, 0]


@pytest.mark.parametrize("value", [65536, -1, (1 << 31) - 1, -(1 << 31)])
@pytest.mark.parametrize("name", ["analog[1]", "io.input[16]"])
def test_fmi2_refuses_an_integer_outside_the_16_bits_naming_variable_and_value(chip, name, value):
    refused(
        chip,
        lambda: chip.fmu.setInteger([vr(chip, name)], [value]),
        "fmi2SetInteger",
        f"{name} = {value}",
        "out of range",
        "0 .. 65535",
        "not set",
    )
    assert chip.get(name) == 0


def test_fmi2_a_set_call_with_one_bad_value_sets_none_of_them(chip):
    refused(
        chip,
        lambda: chip.fmu.setInteger([vr(chip, "analog[1]"), vr(chip, "io.input[2]")], [7, 70000]),
        "fmi2SetInteger",
        "io.input[2] = 70000",
    )
    assert chip.get("analog[1]") == 0


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_the_outputs_cannot_be_set_and_wrong_types_are_refused(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        if fmi_version == 2:
            refused(
                chip,
                lambda: chip.fmu.setInteger([vr(chip, "io.output[1]")], [1]),
                "fmi2SetInteger",
                "value reference 1801",
                "io.output[1]",
                "output",
            )
            refused(
                chip,
                lambda: chip.fmu.setInteger([vr(chip, "axis2.motorCommand")], [1]),
                "fmi2SetInteger",
                "value reference 208",
                "is an output",
            )
            refused(
                chip,
                lambda: chip.fmu.setReal([vr(chip, "axis1.motorOutput")], [0.5]),
                "fmi2SetReal",
                "value reference 109",
                "is an output",
            )
            refused(
                chip,
                lambda: chip.fmu.getReal([vr(chip, "axis1.motorCommand")]),
                "fmi2GetReal",
                "value reference 108",
                "is a Integer, not Real",
            )
        else:
            refused(
                chip,
                lambda: chip.fmu.setUInt16([vr(chip, "io.output")], [1] * 16),
                "fmi3SetUInt16",
                "value reference 1801",
                "is an output",
            )
            refused(
                chip,
                lambda: chip.fmu.setInt16([vr(chip, "axis2.motorCommand")], [1]),
                "fmi3SetInt16",
                "value reference 208",
                "is an output",
            )
            refused(
                chip,
                lambda: chip.fmu.getUInt16([vr(chip, "axis1.motorCommand")]),
                "fmi3GetUInt16",
                "value reference 108",
                "is a Int16, not UInt16",
            )
            refused(
                chip,
                lambda: chip.fmu.getInt16([vr(chip, "analog")], nValues=8),
                "fmi3GetInt16",
                "value reference 1601",
                "is a UInt16, not Int16",
            )
            refused(
                chip,
                lambda: chip.fmu.getUInt16([vr(chip, "analog")], nValues=3),
                "fmi3GetUInt16",
                "nValues is 3 but the value references hold 8",
            )
            refused(
                chip,
                lambda: chip.fmu.getInt16([vr(chip, "axis1.motorCommand"), vr(chip, "axis2.motorCommand")], nValues=1),
                "fmi3GetInt16",
                "nValues is 1",
            )


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_inputs_set_in_initialization_mode_are_kept_by_its_end(fmi_version):
    init = InitializationChip(fmi_version)
    try:
        set_words(init, "analog", [11 * (i + 1) for i in range(8)])
        init.set("io.input[4]", 0xBEEF)
        init.fmu.exitInitializationMode()
        assert list(io_words(init, "analog")) == [11 * (i + 1) for i in range(8)]
        assert init.get("io.input[4]") == 0xBEEF
    finally:
        init.free()


# ---- the motor output ----


def test_motor_command_is_get_current_motor_command_and_motor_output_its_fraction(any_chip):
    """Open loop (motor off) the motor command is SetMotorCommand's value, applied by Update;
    closed loop with the ideal servo (loopback) and no gains it is the motor bias."""
    ax1, ax3 = any_chip.axis(0), any_chip.axis(2)
    ax1.SetMotorMode(0)
    ax1.SetMotorCommand(-12345)
    any_chip.run(1)
    assert any_chip.get("axis1.motorCommand") == 0  # buffered: not before the Update
    ax1.Update()
    ax3.SetKp(0)
    ax3.SetMotorBias(16384)
    rows = any_chip.run(
        3,
        record=[
            "axis1.motorCommand",
            "axis1.motorOutput",
            "axis3.motorCommand",
            "axis3.motorOutput",
            "axis2.motorCommand",
        ],
    )
    assert rows.dtype["axis1.motorCommand"] == np.int16 and rows.dtype["axis1.motorOutput"] == np.float64
    assert list(rows["axis1.motorCommand"]) == [-12345] * 3
    assert list(rows["axis1.motorOutput"]) == [-12345 / FULL_SCALE] * 3
    assert list(rows["axis3.motorCommand"]) == [16384] * 3 and list(rows["axis3.motorOutput"]) == [0.5] * 3
    assert list(rows["axis2.motorCommand"]) == [0] * 3
    for n, ax in ((1, ax1), (3, ax3)):
        assert any_chip.get(f"axis{n}.motorCommand") == ax.GetCurrentMotorCommand()
        assert any_chip.get(f"axis{n}.motorOutput") == ax.GetCurrentMotorCommand() / FULL_SCALE


@pytest.mark.parametrize("value", [-32768, 32767, -1])
def test_motor_output_spans_full_scale(any_chip, value):
    ax = any_chip.axis(1)
    ax.SetMotorMode(0)
    ax.SetMotorCommand(value)
    ax.Update()
    any_chip.run(1)
    raw = (
        any_chip.fmu.getInteger([vr(any_chip, "axis2.motorCommand")])[0]
        if any_chip.fmi_version == 2
        else any_chip.fmu.getInt16([vr(any_chip, "axis2.motorCommand")])[0]
    )
    assert raw == value
    assert any_chip.get("axis2.motorOutput") == value / FULL_SCALE
    assert -1.0 <= any_chip.get("axis2.motorOutput") < 1.0


# ---- recording ----


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_recorded_columns_have_the_registers_widths(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        chip.set("analog[8]", 0xFFFF)
        chip.set("io.input[1]", 0x8001)
        names = [
            "axis4.motorCommand",
            "axis4.motorOutput",
            "analog[8]",
            "io.input[1]",
            "io.output[16]",
            "axis1.commandedPosition",
        ]
        rows = chip.run(4, record=names)
        assert [rows.dtype[n] for n in names] == [np.int16, np.float64, np.uint16, np.uint16, np.uint16, np.int32]
        assert list(rows["analog[8]"]) == [0xFFFF] * 4 and list(rows["io.input[1]"]) == [0x8001] * 4
        assert list(rows["cycle"]) == [0, 1, 2, 3]


def test_bulk_recording_of_commanded_values_is_unchanged_by_the_new_columns():
    """FMI 3's record.data holds the commanded values only: with a motor column in the
    list, run() reads cycle by cycle, and the commanded columns are the same."""
    with pmdfmu.Chip(fmi_version=3) as bulk, pmdfmu.Chip(fmi_version=3) as stepped:
        for chip in (bulk, stepped):
            ax = chip.axis(0)
            ax.SetMotorMode(0)
            ax.SetMotorCommand(300)
            ax.SetVelocity(0x30000)
            ax.SetAcceleration(0x1000)
            ax.SetPosition(5000)
            ax.Update()
        a = bulk.run(400, record=["axis1.commandedPosition"])
        b = stepped.run(400, record=["axis1.commandedPosition", "axis1.motorCommand"])
        assert np.array_equal(a["axis1.commandedPosition"], b["axis1.commandedPosition"])
        assert list(b["axis1.motorCommand"]) == [300] * 400


# ---- Reset, FMU states ----


def test_the_chips_reset_keeps_the_inputs_and_clears_the_motor_command(any_chip):
    ax = any_chip.axis(0)
    any_chip.set("analog", [1000 + i for i in range(8)])
    any_chip.set("io.input", [0xF000 + i for i in range(16)])
    ax.SetMotorMode(0)
    ax.SetMotorCommand(777)
    ax.Update()
    any_chip.run(2)
    assert any_chip.get("axis1.motorCommand") == 777
    any_chip.batch(command("Reset"))
    any_chip.run(1)
    assert any_chip.get("analog") == [1000 + i for i in range(8)]  # wires, not registers
    assert any_chip.get("io.input") == [0xF000 + i for i in range(16)]
    assert any_chip.get("axis1.motorCommand") == ax.GetCurrentMotorCommand()
    assert ax.GetMotorCommand() == 0


def test_an_fmu_state_restores_the_inputs_and_the_motor_command(any_chip):
    ax = any_chip.axis(2)
    any_chip.set("analog", list(range(1, 9)))
    any_chip.set("io.input", [3 * i for i in range(16)])
    ax.SetMotorMode(0)
    ax.SetMotorCommand(-2000)
    ax.Update()
    any_chip.run(1)
    saved = any_chip.get_state()
    any_chip.set("analog", [9] * 8)
    any_chip.set("io.input", [9] * 16)
    ax.SetMotorCommand(5)
    ax.Update()
    any_chip.run(1)
    any_chip.set_state(saved)
    assert any_chip.get("analog") == list(range(1, 9))
    assert any_chip.get("io.input") == [3 * i for i in range(16)]
    assert any_chip.get("axis3.motorCommand") == -2000 and any_chip.get("axis3.motorOutput") == -2000 / FULL_SCALE
    with pmdfmu.Chip(fmi_version=any_chip.fmi_version) as other:
        other.set_state(saved)
        assert other.get("analog") == list(range(1, 9)) and other.get("axis3.motorCommand") == -2000
        assert other.run(5, record=["axis3.motorCommand"])["axis3.motorCommand"].tolist() == [-2000] * 5


# ---- the peripheral commands (ReadAnalog, ReadIO, WriteIO) ----


def test_read_analog_reads_the_analog_input_of_its_channel(any_chip):
    ax = any_chip.axis(0)
    any_chip.set("analog", [100 * (i + 1) for i in range(8)])
    assert [ax.ReadAnalog(channel) for channel in range(8)] == [100 * (i + 1) for i in range(8)]
    any_chip.set("analog[5]", 0xFFFF)
    assert ax.ReadAnalog(4) == 0xFFFF
    with pytest.raises(PMDError) as e:
        ax.ReadAnalog(8)
    assert e.value.code == pmdfmu.PMD_ERR_InvalidParameter


def test_read_io_reads_the_bus_input_and_write_io_latches_the_bus_output(any_chip):
    ax = any_chip.axis(0)
    any_chip.set("io.input", [0x100 + a for a in range(16)])
    assert [ax.ReadIO(address) for address in range(16)] == [0x100 + a for a in range(16)]
    for address in range(16):
        ax.WriteIO(address, 0xA000 + address)
    assert any_chip.get("io.output") == [0xA000 + a for a in range(16)]
    assert list(io_words(any_chip, "io.output")) == [0xA000 + a for a in range(16)]
    ax.WriteIO(15, 0xFFFF)
    assert any_chip.get("io.output[16]") == 0xFFFF
    for bad in (lambda: ax.ReadIO(16), lambda: ax.WriteIO(16, 1)):
        with pytest.raises(PMDError) as e:
            bad()
        assert e.value.code == pmdfmu.PMD_ERR_InvalidParameter
    assert any_chip.get("io.output") == [0xA000 + a for a in range(15)] + [0xFFFF]


def test_a_read_sent_with_a_new_input_in_the_same_round_reads_the_new_value(any_chip):
    """Inputs set between steps are in place when the next get or doStep executes the batch."""
    pend_batch(any_chip, command("ReadAnalog", 2) + command("ReadIO", 7))
    set_words(any_chip, "analog", [0, 0, 4321, 0, 0, 0, 0, 0])
    set_words(any_chip, "io.input", [0] * 7 + [0x5A5A] + [0] * 8)
    assert any_chip.get("host.error") == 0
    assert any_chip.get("host.replyCount") == 2
    reply = [any_chip.get(f"host.reply[{i}]") for i in (1, 2)]
    assert reply == [4321, 0x5A5A]


def test_write_io_outputs_go_to_zero_on_reset_and_come_back_with_an_fmu_state(any_chip):
    ax = any_chip.axis(0)
    any_chip.set("io.input[2]", 55)
    ax.WriteIO(1, 0x1234)
    saved = any_chip.get_state()
    any_chip.batch(command("Reset"))
    assert any_chip.get("io.output") == [0] * 16
    assert ax.ReadIO(1) == 55
    any_chip.set_state(saved)
    assert any_chip.get("io.output[2]") == 0x1234


# ---- docs/fmu.md ----


def test_the_docs_peripheral_snippet_runs(tmp_path):
    text = FMU_PAGE.read_text()
    section = text[text.index("**Peripheral inputs.**") :]
    snippet = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    (tmp_path / "snippet.py").write_text(snippet)
    out = subprocess.run(
        [sys.executable, str(tmp_path / "snippet.py")], capture_output=True, text=True, check=True
    ).stdout
    expected = re.findall(r"# -> (.*)", snippet)
    assert out.splitlines() == expected
