# SPDX-License-Identifier: BSD-2-Clause
"""Limit switches, actual position, motion error, settle and tracking windows,
signal sense and capture (pmd-reference 2.1-2.3, 4.5)."""

import pytest

import pmdfmu
from pmdfmu import (
    PMDActivityAxisSettledMask,
    PMDActivityInMotionMask,
    PMDActivityInNegativeLimitMask,
    PMDActivityInPositiveLimitMask,
    PMDActivityMotorOnMask,
    PMDActivityPositionCaptureMask,
    PMDActivityTrackingMask,
    PMDAutoStopEnabled,
    PMDAxis1Mask,
    PMDAxis2Mask,
    PMDAxis3Mask,
    PMDCaptureSourceHome,
    PMDError,
    PMDEventCaptureReceivedMask,
    PMDEventInNegativeLimitMask,
    PMDEventInPositiveLimitMask,
    PMDEventMotionCompleteMask,
    PMDEventMotionErrorMask,
    PMDExternalProfile,
    PMDLimitDisabled,
    PMDMotionCompleteActualPosition,
    PMDSignalEncoderAMask,
    PMDSignalEncoderBMask,
    PMDSignalEncoderHomeMask,
    PMDSignalEncoderIndexMask,
    PMDSignalNegativeLimitMask,
    PMDSignalPositiveLimitMask,
    PMDSignalSenseMask,
    PMDVelocityContouringProfile,
    field_ex,
)

# GetSignalStatus with every input idle: the signals are active low, so all read high
IDLE_SIGNALS = (
    PMDSignalEncoderAMask
    | PMDSignalEncoderBMask
    | PMDSignalEncoderIndexMask
    | PMDSignalEncoderHomeMask
    | PMDSignalPositiveLimitMask
    | PMDSignalNegativeLimitMask
)


def move(ax, position, velocity=0x20000, acceleration=0x2000):
    ax.SetPosition(position)
    ax.SetVelocity(velocity)
    ax.SetAcceleration(acceleration)
    ax.Update()


def test_entering_a_limit_sets_event_and_activity_bits_and_stops_the_axis(chip):
    ax = chip.axis(0)
    move(ax, 10_000)
    chip.run(50)
    chip.set("axis1.positiveLimit", True)
    chip.run(1)
    held = ax.GetCommandedPosition()
    assert ax.GetEventStatus() & PMDEventInPositiveLimitMask
    assert ax.GetActivityStatus() & PMDActivityInPositiveLimitMask
    assert ax.GetCommandedVelocity() == 0 and not ax.GetActivityStatus() & PMDActivityInMotionMask
    chip.run(10)
    assert ax.GetCommandedPosition() == held
    # reference 4.5: 0x0D while the event is pending, 0x0E further into the limit, out of it is fine
    ax.SetPosition(held + 100)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0D
    ax.ResetEventStatus(~PMDEventInPositiveLimitMask)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0E
    ax.SetPosition(held - 100)
    ax.Update()
    chip.run(200)
    assert ax.GetCommandedPosition() == held - 100
    chip.set("axis1.positiveLimit", False)
    chip.run(1)
    assert not ax.GetActivityStatus() & PMDActivityInPositiveLimitMask


def test_multiupdate_aborts_at_the_first_axis_moving_into_a_limit(chip):
    chip.set("axis2.negativeLimit", True)
    chip.run(1)
    chip.axis(1).ResetEventStatus(0)
    for n in range(3):
        ax = chip.axis(n)
        ax.SetPosition(-500)
        ax.SetVelocity(0x10000)
        ax.SetAcceleration(0x1000)
    with pytest.raises(PMDError) as e:
        chip.axis(0).MultiUpdate(PMDAxis1Mask | PMDAxis2Mask | PMDAxis3Mask)
    assert e.value.code == 0x0E
    chip.run(20)
    assert chip.axis(0).GetCommandedPosition() < 0  # axis 1 was updated
    assert chip.axis(2).GetCommandedPosition() == 0  # axis 3 was not
    assert chip.axis(1).GetActivityStatus() & PMDActivityInNegativeLimitMask


def test_limits_are_ignored_with_the_limit_switch_mode_off(chip):
    ax = chip.axis(0)
    ax.SetLimitSwitchMode(PMDLimitDisabled)
    chip.set("axis1.negativeLimit", True)
    move(ax, -1000)
    chip.run(100)
    assert ax.GetCommandedPosition() < 0 and not ax.GetEventStatus() & PMDEventInNegativeLimitMask


def test_an_external_profile_stops_on_a_limit(chip):
    ax = chip.axis(0)
    ax.SetBufferStart(2, 0x200)
    ax.SetBufferLength(2, 1)
    ax.SetBufferStart(3, 0x300)
    ax.SetBufferLength(3, 1)
    ax.SetBufferFunction(0, 2)
    ax.SetBufferFunction(1, 3)
    chip.write_memory(0x300, [0x10000])
    ax.SetProfileMode(PMDExternalProfile)
    ax.Update()
    chip.run(5)
    chip.set("axis1.negativeLimit", True)
    chip.run(1)
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 0
    assert ax.GetEventStatus() & PMDEventInNegativeLimitMask


def test_signal_status_is_active_low_and_sense_inverts_it(chip):
    ax = chip.axis(0)
    assert ax.GetSignalStatus() == IDLE_SIGNALS  # A, B, index, home, limits all idle (high)
    chip.set("axis1.home", True)
    assert ax.GetSignalStatus() == IDLE_SIGNALS ^ PMDSignalEncoderHomeMask
    ax.SetSignalSense(PMDSignalEncoderHomeMask)
    assert ax.GetSignalStatus() == IDLE_SIGNALS
    assert ax.GetSignalSense() == PMDSignalEncoderHomeMask
    with pytest.raises(PMDError):
        ax.SetSignalSense(PMDSignalSenseMask + 1)  # the bit above the sense mask


def test_loopback_off_actual_position_error_and_motion_error_with_auto_stop():
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        ax.SetPositionErrorLimit(100)
        ax.SetAutoStopMode(PMDAutoStopEnabled)
        ax.SetTrackingWindow(5)
        move(ax, 100_000)
        chip.run(20)
        assert ax.GetPositionError() == -ax.GetCommandedPosition()
        plant = ax.GetCommandedPosition() - 3
        chip.set("axis1.actualPosition", plant)
        chip.run(1)
        assert ax.GetActualPosition() == plant
        assert ax.GetPositionError() == -5  # 3 behind, and the trajectory moved 2
        assert ax.GetActivityStatus() & PMDActivityTrackingMask  # |error| <= tracking window 5
        chip.run(1)
        assert not ax.GetActivityStatus() & PMDActivityTrackingMask
        chip.set("axis1.actualPosition", 0)  # the motor stalls
        chip.run(200)
        assert ax.GetEventStatus() & PMDEventMotionErrorMask
        assert not ax.GetActivityStatus() & PMDActivityMotorOnMask  # auto-stop: motor off
        assert ax.GetCommandedVelocity() == 0
        assert abs(ax.GetPositionError()) > 100


def test_set_and_adjust_actual_position_cause_no_motion(chip):
    ax = chip.axis(0)
    move(ax, 1000)
    chip.run(30)
    before = ax.GetCommandedPosition()
    ax.SetActualPosition(before + 5000)
    assert ax.GetActualPosition() == before + 5000 == ax.GetCommandedPosition()
    chip.run(500)
    assert ax.GetCommandedPosition() == 6000  # the destination moved with it
    ax.AdjustActualPosition(-6000)
    assert ax.GetActualPosition() == 0 and ax.GetPositionError() == 0
    chip.run(10)
    assert ax.GetCommandedVelocity() == 0


def test_clear_position_error_applies_at_the_next_update():
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        chip.set("axis1.actualPosition", 321)
        chip.run(1)
        ax.ClearPositionError()
        assert ax.GetCommandedPosition() == 0
        ax.Update()
        assert ax.GetCommandedPosition() == 321 and ax.GetPositionError() == 0


def test_settled_and_motion_complete_in_actual_mode():
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        ax.SetMotionCompleteMode(PMDMotionCompleteActualPosition)
        ax.SetSettleWindow(2)
        ax.SetSettleTime(10)
        move(ax, 50, 0x40000, 0x10000)
        chip.run(100)
        assert ax.GetCommandedPosition() == 50 and not ax.GetActivityStatus() & PMDActivityInMotionMask
        assert not ax.GetEventStatus() & PMDEventMotionCompleteMask  # the encoder is still at 0
        chip.set("axis1.actualPosition", 49)
        chip.run(10)
        assert not ax.GetActivityStatus() & PMDActivityAxisSettledMask
        chip.run(1)
        assert ax.GetActivityStatus() & PMDActivityAxisSettledMask
        assert ax.GetEventStatus() & PMDEventMotionCompleteMask


def test_home_capture_latches_until_read(chip):
    ax = chip.axis(0)
    ax.SetCaptureSource(PMDCaptureSourceHome)
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x10000)
    ax.Update()
    chip.run(40)
    chip.set("axis1.home", True)
    chip.run(1)
    assert ax.GetActivityStatus() & PMDActivityPositionCaptureMask
    assert ax.GetEventStatus() & PMDEventCaptureReceivedMask
    chip.set("axis1.home", False)
    chip.run(5)
    chip.set("axis1.home", True)
    chip.run(1)
    assert ax.GetCaptureValue() == 41  # the first edge (seen in cycle 41, at 41 counts), held until read
    assert not ax.GetActivityStatus() & PMDActivityPositionCaptureMask


def test_an_external_profile_stops_on_a_motion_error_even_without_auto_stop():
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        ax.SetBufferStart(2, 0x200)
        ax.SetBufferLength(2, 1)
        ax.SetBufferStart(3, 0x300)
        ax.SetBufferLength(3, 1)
        ax.SetBufferStart(4, 0x400)
        ax.SetBufferLength(4, 1)
        ax.SetBufferFunction(0, 2)
        ax.SetBufferFunction(1, 3)
        ax.SetBufferFunction(4, 4)
        chip.write_memory(0x300, [0x20000])  # 2 counts/cycle for 1000 cycles; the plant stays at 0
        chip.write_memory(0x400, [1000])
        ax.SetPositionErrorLimit(50)
        ax.SetProfileMode(PMDExternalProfile)
        ax.Update()
        chip.run(40)
        assert ax.GetEventStatus() & PMDEventMotionErrorMask
        assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 0
        assert ax.GetCommandedPosition() == 52  # stopped in the cycle the error passed 50
        assert ax.GetActivityStatus() & PMDActivityMotorOnMask  # no auto-stop: the motor stays on


def test_reset_keeps_the_encoder_count_the_last_cycle_sampled_not_the_live_input():
    """Without loopback the actual position is the encoder input sampled by a cycle: a Reset (offset gone)
    reads the count the last cycle sampled, not an input set since, so no output of a batch depends on
    axisN.actualPosition without a step (no feedthrough from a plant); the next cycle samples the input."""
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        chip.set("axis1.actualPosition", 500)
        chip.run(1)
        ax.SetActualPosition(100)  # offset -400
        chip.set("axis1.actualPosition", 700)  # not sampled yet
        ax.Reset()
        assert ax.GetActualPosition() == 500 and ax.GetActualVelocity() == 0
        chip.run(1)
        assert ax.GetActualPosition() == 700
