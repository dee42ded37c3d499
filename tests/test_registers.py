# SPDX-License-Identifier: BSD-2-Clause
"""Breakpoints, interrupts, Reset, actual position and the ports' order (pmd-reference 2.5, 4.1, 4.2)."""

import numpy as np

import pmdfmu
from pmdfmu import (
    PMDBreakpoint1,
    PMDBreakpoint2,
    PMDBreakpointActionAbruptStop,
    PMDBreakpointActionMotorOff,
    PMDBreakpointActionSmoothStop,
    PMDBreakpointActionUpdate,
    PMDBreakpointCommandedPositionCrossed,
    PMDBreakpointEventStatus,
    PMDBreakpointGreaterOrEqualCommandedPosition,
    PMDBreakpointLessOrEqualActualPosition,
    PMDBreakpointNoAction,
    PMDBreakpointSignalStatus,
    PMDBreakpointTime,
    PMDEventBreakpoint1Mask,
    PMDEventBreakpoint2Mask,
    PMDEventMotionCompleteMask,
    PMDSignalEncoderHomeMask,
)


def start_move(ax, position=1_000_000, velocity=0x40000, acceleration=0x1000):
    ax.SetPosition(position)
    ax.SetVelocity(velocity)
    ax.SetAcceleration(acceleration)
    ax.Update()


def test_time_breakpoint_with_update_applies_the_buffered_registers_at_that_cycle(chip):
    ax = chip.axis(0)
    ax.SetPosition(5000)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x10000)
    ax.SetBreakpointValue(PMDBreakpoint2, 100)
    ax.SetBreakpoint(PMDBreakpoint2, 0, PMDBreakpointActionUpdate, PMDBreakpointTime)
    rec = chip.run(110, record=["axis1.commandedVelocity", "axis1.eventStatus"])
    assert (rec["axis1.commandedVelocity"][:101] == 0).all()  # the update happens at the end of cycle 100
    assert rec["axis1.commandedVelocity"][101] == 0x10000
    assert not rec["axis1.eventStatus"][99] & PMDEventBreakpoint2Mask
    assert rec["axis1.eventStatus"][100] & PMDEventBreakpoint2Mask
    assert ax.GetBreakpoint(PMDBreakpoint2) == (0, PMDBreakpointActionUpdate, 0)


def test_position_breakpoint_on_another_axis_stops_this_one(chip):
    a1, a2 = chip.axis(0), chip.axis(1)
    start_move(a1)
    start_move(a2)
    a2.SetBreakpointValue(PMDBreakpoint1, 2000)
    a2.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointActionAbruptStop, PMDBreakpointGreaterOrEqualCommandedPosition)
    rec = chip.run(700, record=["axis1.commandedPosition", "axis2.commandedVelocity"])  # 2000 at ~530
    assert rec["axis1.commandedPosition"][-1] > 2000
    fired = int(np.argmax(rec["axis1.commandedPosition"] >= 2000))
    assert rec["axis2.commandedVelocity"][fired] == 0 and rec["axis2.commandedVelocity"][fired - 1] > 0
    assert (rec["axis2.commandedVelocity"][fired:] == 0).all()
    assert a2.GetEventStatus() & (PMDEventBreakpoint1Mask | PMDEventMotionCompleteMask)
    assert a1.GetCommandedVelocity() > 0


def test_crossed_is_converted_when_issued(chip):
    ax = chip.axis(0)
    ax.SetBreakpointValue(PMDBreakpoint1, 300)
    ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointNoAction, PMDBreakpointCommandedPositionCrossed)
    assert ax.GetBreakpoint(PMDBreakpoint1)[2] == PMDBreakpointGreaterOrEqualCommandedPosition


def test_smooth_stop_and_motor_off_actions(chip):
    ax = chip.axis(0)
    start_move(ax)
    ax.SetBreakpointValue(PMDBreakpoint1, 50)
    ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointActionSmoothStop, PMDBreakpointTime)
    ax.SetBreakpointValue(PMDBreakpoint2, 60)
    ax.SetBreakpoint(PMDBreakpoint2, 0, PMDBreakpointActionMotorOff, PMDBreakpointTime)
    rec = chip.run(200, record=["axis1.commandedVelocity", "axis1.activityStatus"])
    v = rec["axis1.commandedVelocity"]
    assert v[50] == 51 * 0x1000 and v[51] == 50 * 0x1000 and v[-1] == 0
    motor_on = rec["axis1.activityStatus"] & pmdfmu.PMDActivityMotorOnMask
    assert motor_on[59] and not motor_on[60]


def test_status_breakpoints_use_select_and_sense_masks(chip):
    ax = chip.axis(0)
    ax.SetInterruptMask(PMDEventBreakpoint1Mask)
    # a status breakpoint's value: the select mask in the high word, the sense mask in the low word
    ax.SetBreakpointValue(PMDBreakpoint1, (PMDSignalEncoderHomeMask << 16) | 0)  # home reads 0: active (low)
    ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointNoAction, PMDBreakpointSignalStatus)
    chip.run(10)
    assert not chip.get("host.interrupt")
    chip.set("axis1.home", True)
    chip.run(1)
    assert chip.get("host.interrupt") and ax.GetEventStatus() & PMDEventBreakpoint1Mask
    ax.ResetEventStatus(~PMDEventBreakpoint1Mask)
    assert not chip.get("host.interrupt")
    # event status: fire when motion complete is 1
    ax.SetBreakpointValue(PMDBreakpoint2, (PMDEventMotionCompleteMask << 16) | PMDEventMotionCompleteMask)
    ax.SetBreakpoint(PMDBreakpoint2, 0, PMDBreakpointNoAction, PMDBreakpointEventStatus)
    start_move(ax, position=10)
    chip.run(5)
    assert not ax.GetEventStatus() & PMDEventBreakpoint2Mask
    chip.run(100)
    assert ax.GetEventStatus() & PMDEventBreakpoint2Mask


def test_actual_position_comes_from_the_input_when_loopback_is_off():
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        chip.set("axis1.actualPosition", -42)
        chip.run(1)
        assert ax.GetActualPosition() == -42
        assert not ax.GetActivityStatus() & pmdfmu.PMDActivityTrackingMask
        ax.SetBreakpointValue(PMDBreakpoint1, -40)
        ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointNoAction, PMDBreakpointLessOrEqualActualPosition)
        chip.run(1)
        assert ax.GetEventStatus() & PMDEventBreakpoint1Mask
    with pmdfmu.Chip() as chip:
        start_move(chip.axis(0))
        chip.run(30)
        assert chip.axis(0).GetActualPosition() == chip.axis(0).GetCommandedPosition() > 0


def test_reset_restores_registers_and_time_but_keeps_the_memory(chip):
    ax = chip.axis(0)
    ax.SetBufferStart(2, 0x300)
    ax.SetBufferLength(2, 4)
    ax.WriteBuffer(2, 1234)
    start_move(ax)
    chip.run(50)
    ax.GetHostIOError()
    ax.Reset()
    assert ax.GetHostIOError() == 1
    assert (ax.GetBufferStart(2), ax.GetBufferLength(2), ax.GetPosition(), ax.GetTime()) == (0, 0, 0, 0)
    assert ax.GetCommandedPosition() == 0 and ax.GetBufferFunction(0) == -1
    chip.run(3)
    assert ax.GetTime() == 2
    ax.SetBufferStart(2, 0x300)
    ax.SetBufferLength(2, 4)
    assert ax.ReadBuffer(2) == 1234


def test_get_version_is_a_four_axis_navigator(chip):
    assert chip.axis(3).GetVersion() == (2, 1, 4, 0, 0, 1, 0)


def test_host_batch_executes_before_the_memory_write_of_the_same_step(chip):
    ax = chip.axis(0)
    ax.SetBufferStart(2, 0x300)
    ax.SetBufferLength(2, 1)
    vr = {n: v.valueReference for n, v in chip.variables.items()}
    read_buffer = pmdfmu.COMMANDS["ReadBuffer"].opcode
    chip.fmu.setInteger(
        [
            vr["memory.address"],
            vr["memory.count"],
            vr["memory.data[1]"],
            vr["memory.strobe"],
            vr["host.word[1]"],
            vr["host.word[2]"],
            vr["host.wordCount"],
            vr["host.strobe"],
        ],
        [0x300, 1, 77, 1, read_buffer, 2, 2, chip.get("host.strobe") + 1],
    )
    chip.fmu.doStep(0.0, 1e-4)
    assert chip.fmu.getInteger([vr["host.replyCount"], vr["host.reply[1]"], vr["host.reply[2]"]]) == [2, 0, 0]
    assert ax.ReadBuffer(2) == 77
