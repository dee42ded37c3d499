# SPDX-License-Identifier: BSD-2-Clause
"""Every Set command reads back through its Get (pmd-reference 1.2), with the
reset values of reference 4.2, and the remaining single-purpose commands."""

import pytest

import pmdfmu
from pmdfmu import COMMANDS, PMDError

# an interrupt mask of three event bits, the highest one among them
EVENTS = pmdfmu.PMDEventBreakpoint2Mask | pmdfmu.PMDEventBreakpoint1Mask | pmdfmu.PMDEventMotionCompleteMask
# Set command: (value written, reset value). Buffered registers read back the buffered value.
ROUND_TRIPS = {
    "SetProfileMode": ((2,), 0),
    "SetPosition": ((-123456,), 0),
    "SetVelocity": ((0x12345,), 0),
    "SetAcceleration": ((0x7FFFFFFF,), 0),
    "SetDeceleration": ((77,), 0),
    "SetJerk": ((0x1234567,), 0),
    "SetStopMode": ((2,), 0),
    "SetGearRatio": ((-0x18000,), 0),
    "SetInterruptMask": ((EVENTS,), 0),
    "SetPositionErrorLimit": ((1000,), 0xFFFF),
    "SetAutoStopMode": ((1,), 0),
    "SetLimitSwitchMode": ((0,), 1),
    "SetMotionCompleteMode": ((1,), 0),
    "SetSettleTime": ((65535,), 0),
    "SetSettleWindow": ((9,), 0),
    "SetTrackingWindow": ((10,), 0),
    "SetSignalSense": ((pmdfmu.PMDSignalSenseMask,), 0),
    "SetCaptureSource": ((1,), 0),
    "SetMotorMode": ((0,), 1),
    "SetGearMaster": ((3, 1), (0, 0)),
}
CHIP_ROUND_TRIPS = {"SetTraceMode": ((1,), 0), "SetTracePeriod": ((500,), 1), "SetSampleTime": ((333,), 100)}


@pytest.mark.parametrize("setter", list(ROUND_TRIPS) + list(CHIP_ROUND_TRIPS))
def test_set_then_get_returns_the_value_and_reset_restores_the_default(chip, setter):
    value, reset = {**ROUND_TRIPS, **CHIP_ROUND_TRIPS}[setter]
    getter = "Get" + setter[3:]
    ax = chip.axis(2)
    assert getattr(ax, getter)() == reset
    getattr(ax, setter)(*value)
    assert getattr(ax, getter)() == (value[0] if len(value) == 1 else value)
    if setter != "SetSampleTime":  # the cycle grid belongs to the FMU: Reset keeps it
        ax.Reset()
        assert getattr(ax, getter)() == reset


def test_breakpoint_value_and_trace_variable_read_back(chip):
    ax = chip.axis(1)
    ax.SetBreakpointValue(1, -5)
    assert ax.GetBreakpointValue(1) == -5 and ax.GetBreakpointValue(0) == 0
    ax.SetTraceVariable(2, 3, pmdfmu.PMDTraceActualVelocity)
    assert ax.GetTraceVariable(2) == (3, pmdfmu.PMDTraceActualVelocity)
    with pytest.raises(PMDError):
        ax.GetTraceVariable(4)


def test_no_operation_and_clear_interrupt(chip):
    ax = chip.axis(0)
    assert ax.NoOperation() is None
    ax.SetInterruptMask(pmdfmu.PMDEventMotionCompleteMask)
    ax.SetPosition(3)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x10000)
    ax.Update()
    chip.run(10)
    assert chip.get("host.interrupt") and ax.GetInterruptAxis() == pmdfmu.PMDAxis1Mask
    ax.ClearInterrupt()
    assert chip.get("host.interrupt")  # the masked event bit is still set: it rises again
    ax.ResetEventStatus(0)
    ax.ClearInterrupt()
    assert not chip.get("host.interrupt") and ax.GetInterruptAxis() == 0


def test_actual_velocity_is_whole_counts_per_cycle(chip):
    ax = chip.axis(0)
    ax.SetProfileMode(pmdfmu.PMDVelocityContouringProfile)
    ax.SetVelocity(0x30000)
    ax.SetAcceleration(0x30000)
    ax.Update()
    chip.run(5)
    assert ax.GetActualVelocity() == 3 << 16


def test_motor_off_freezes_the_ideal_servo(chip):
    ax = chip.axis(0)
    ax.SetMotorMode(pmdfmu.PMDMotorOff)
    ax.SetPosition(100)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x10000)
    ax.Update()
    chip.run(10)
    assert ax.GetActualPosition() == 0 and ax.GetPositionError() == -10
    ax.SetMotorMode(pmdfmu.PMDMotorOn)
    chip.run(1)
    assert ax.GetPositionError() == 0


def test_every_command_is_in_this_suite():
    import pathlib
    import re

    text = "".join(p.read_text() for p in pathlib.Path(__file__).parent.glob("*.py"))
    text += "".join(p.read_text() for p in (pathlib.Path(__file__).parent.parent / "examples").glob("*.py"))
    names = (
        set(ROUND_TRIPS)
        | set(CHIP_ROUND_TRIPS)
        | {"Get" + s[3:] for s in ROUND_TRIPS}
        | {"Get" + s[3:] for s in CHIP_ROUND_TRIPS}
    )
    missing = [c for c in COMMANDS if c not in names and not re.search(r"\b" + c + r"\b", text)]
    assert missing == []
