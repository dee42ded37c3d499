# SPDX-License-Identifier: BSD-2-Clause
"""Every breakpoint action in every profile mode acts as the host's own command
sent at the cycle the breakpoint fires (reference 2.5).

Two instances run the same set-up. In one a breakpoint fires at the end of
cycle k and acts; in the other the host, after cycle k, sends what the action
stands for: SetStopMode(abrupt)+Update, SetStopMode(smooth)+Update, Update,
SetMotorMode(off). The two runs must be the same cycle by cycle in every output
of every axis: row k of the host's run is read right after its command (the
breakpoint acts at the end of cycle k, before the outputs are read), and the
event status is compared without the breakpoint's own event bits. The one
exception is the motor command of cycle k: the servo filter runs after the
breakpoints (docs/decisions.md, "Servo filter and motor output"), so a
breakpoint's action is already in the motor output of the cycle it fires in,
where the host's command reaches only the next cycle's."""

import numpy as np
import pytest

import pmdfmu
from pmdfmu import (
    PMDAbruptStop,
    PMDBreakpoint1,
    PMDBreakpointActionAbruptStop,
    PMDBreakpointActionMotorOff,
    PMDBreakpointActionSmoothStop,
    PMDBreakpointActionUpdate,
    PMDBreakpointEventStatus,
    PMDBreakpointGreaterOrEqualCommandedPosition,
    PMDBufferFunctionPosition,
    PMDBufferFunctionTime,
    PMDBufferFunctionVelocity,
    PMDElectronicGearProfile,
    PMDEventBreakpoint1Mask,
    PMDEventBreakpoint2Mask,
    PMDEventInstructionErrorMask,
    PMDEventMotionCompleteMask,
    PMDExternalProfile,
    PMDMotorOff,
    PMDPositionSourceCommanded,
    PMDSCurveProfile,
    PMDSmoothStop,
    PMDTrapezoidalProfile,
    PMDVelocityContouringProfile,
    field_ex,
)

QUANTITIES = (
    "commandedPosition",
    "commandedVelocity",
    "commandedAcceleration",
    "actualPosition",
    "activityStatus",
    "eventStatus",
    "motorCommand",
)
NAMES = [f"axis{n}.{q}" for n in range(1, 5) for q in QUANTITIES]
OTHER_EVENTS = 0xFFFF & ~(PMDEventBreakpoint1Mask | PMDEventBreakpoint2Mask)

ACTIONS = {
    "update": PMDBreakpointActionUpdate,
    "abrupt stop": PMDBreakpointActionAbruptStop,
    "smooth stop": PMDBreakpointActionSmoothStop,
    "motor off": PMDBreakpointActionMotorOff,
}


def host_command(ax, action):
    """What the host sends for a breakpoint action (reference 2.5, 4.1)."""
    if action == "update":
        ax.Update()
    elif action == "abrupt stop":
        ax.SetStopMode(PMDAbruptStop)
        ax.Update()
    elif action == "smooth stop":
        ax.SetStopMode(PMDSmoothStop)
        ax.Update()
    else:
        ax.SetMotorMode(PMDMotorOff)


# ---- the profile modes: each starts a move and returns (acting axis, breakpoint value) ----
# The breakpoint is on the acting axis's own commanded position (>= value), so it
# fires in the middle of the move; for "update", the buffered registers hold a
# change written before the breakpoint is armed.


def trapezoidal(chip, action):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDTrapezoidalProfile)
    ax.SetPosition(20_000)
    ax.SetVelocity(0x40000)  # 4.0 counts/cycle
    ax.SetAcceleration(0x1000)
    ax.SetDeceleration(0x800)
    ax.Update()
    if action == "update":
        ax.SetPosition(2_500)  # behind the axis: it brakes, overshoots, comes back
        ax.SetVelocity(0x18000)
    return 0, 3_000


def velocity_contouring(chip, action):
    """The issue's example: 2.0 counts/cycle, a breakpoint at 1000."""
    ax = chip.axis(0)
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(0x20000)
    ax.SetAcceleration(0xCCC)  # 0.05 counts/cycle^2
    ax.Update()
    if action == "update":
        ax.SetVelocity(-0x10000)  # reverse through 0 at the deceleration
    return 0, 1_000


def scurve(chip, action):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDSCurveProfile)
    ax.SetPosition(20_000)
    ax.SetVelocity(0x40000)
    ax.SetAcceleration(0x400)
    ax.SetJerk(0x1000000)
    ax.Update()
    if action == "update":
        ax.SetPosition(5_000)  # no change while an S-curve moves: 0x0C, and nothing changes
    return 0, 3_000


def gear(chip, action):
    master, slave = chip.axis(0), chip.axis(1)
    trapezoidal(chip, None)
    slave.SetGearMaster(0, PMDPositionSourceCommanded)
    slave.SetGearRatio(0x18000)  # 1.5 slave counts per master count
    slave.SetProfileMode(PMDElectronicGearProfile)
    slave.Update()
    if action == "update":
        slave.SetGearRatio(-0x8000)
    assert master.GetCommandedPosition() == 0
    return 1, 3_000


def external(chip, action):
    """Seed 000: 1.5 counts/cycle for 1600 cycles, then a time-0 row."""
    ax = chip.axis(0)
    rows = [(0, 0x18000, 1600), (2_400, 0, 0)]
    for k, function in enumerate((PMDBufferFunctionPosition, PMDBufferFunctionVelocity, PMDBufferFunctionTime)):
        ax.SetBufferStart(2 + k, 0x200 + 0x10 * k)
        ax.SetBufferLength(2 + k, len(rows))
        ax.SetBufferFunction(function, 2 + k)
        chip.write_memory(0x200 + 0x10 * k, [r[k] & 0xFFFFFFFF for r in rows])
    ax.SetProfileMode(PMDExternalProfile)
    ax.Update()
    if action == "update":
        ax.SetVelocity(0x10000)  # an Update while the profile runs: it runs on
    return 0, 1_500


MODES = {
    "trapezoidal": trapezoidal,
    "velocity contouring": velocity_contouring,
    "S-curve": scurve,
    "gear": gear,
    "external": external,
}
CYCLES = 2_200
BIAS, OPEN_LOOP = 50, 0x200


def servo(chip):
    """Feedforward gains, a bias and an open-loop command, so that the motor output of the ideal
    servo (loopback: the position error stays 0) shows the velocity, the acceleration and the
    motor mode. The move's Update applies the buffered ones."""
    for n in range(4):
        ax = chip.axis(n)
        ax.SetKvff(0x100)
        ax.SetKaff(0x4000)
        ax.SetMotorBias(BIAS)
        ax.SetMotorCommand(OPEN_LOOP)


def set_up(chip, setup, action):
    """servo(), then the move; for an update, new gains buffered as well."""
    servo(chip)
    axis, position = setup(chip, action)
    if action == "update":
        chip.axis(axis).SetKvff(0x300)
    return axis, position


def row_now(chip, dtype):
    """The outputs as they are now (after a command), as one recorded row."""
    row = np.zeros(1, dtype=dtype)
    row["cycle"] = chip.get("chipTime") & 0xFFFFFFFF
    for name in NAMES:
        kind = dtype[name]
        value = int(chip.get(name))
        row[name] = value & ((1 << 8 * kind.itemsize) - 1) if kind.kind == "u" else value
    return row


def with_breakpoint(setup, action, cycles=CYCLES, trigger=PMDBreakpointGreaterOrEqualCommandedPosition, value=None):
    """Runs setup's move with breakpoint 1 armed on the acting axis: (axis, cycle it fired, the run)."""
    with pmdfmu.Chip() as chip:
        axis, position = set_up(chip, setup, action)
        ax = chip.axis(axis)
        ax.SetBreakpointValue(PMDBreakpoint1, position if value is None else value)
        ax.SetBreakpoint(PMDBreakpoint1, axis, ACTIONS[action], trigger)
        rec = chip.run(cycles, record=NAMES)
        events = rec[f"axis{axis + 1}.eventStatus"]
        assert events[-1] & PMDEventBreakpoint1Mask, "the breakpoint never fired"
        fired = int(np.argmax(events & PMDEventBreakpoint1Mask != 0))
        assert ax.GetBreakpoint(PMDBreakpoint1)[2] == 0  # fired once, trigger cleared
        return axis, fired, rec


def with_host(setup, action, fired, cycles=CYCLES):
    """The same set-up with no breakpoint; the host's command after cycle `fired`."""
    with pmdfmu.Chip() as chip:
        axis, _ = set_up(chip, setup, action)
        before = chip.run(fired + 1, record=NAMES)
        try:
            host_command(chip.axis(axis), action)
        except pmdfmu.PMDError as e:
            assert (setup, action) == (scurve, "update") and e.code == 0x0C  # in motion: refused
        before[fired] = row_now(chip, before.dtype)[0]
        after = chip.run(cycles - fired - 1, record=NAMES)
        return np.concatenate([before, after])


def assert_same_runs(bp, host, fired):
    """Every output of every axis at every cycle, but the motor command of the cycle the
    breakpoint fired in (the module's docstring)."""
    assert np.array_equal(bp["cycle"], host["cycle"])
    for name in NAMES:
        a, b = bp[name], host[name]
        if name.endswith("eventStatus"):
            a, b = a & OTHER_EVENTS, b & OTHER_EVENTS
        if name.endswith("motorCommand"):
            a, b = np.delete(a, fired), np.delete(b, fired)
        differ = np.flatnonzero(a != b)
        assert differ.size == 0, f"{name} differs first at cycle {differ[0]}: {a[differ[0]]} vs {b[differ[0]]}"


@pytest.mark.parametrize("action", ACTIONS)
@pytest.mark.parametrize("mode", MODES)
def test_breakpoint_action_equals_the_host_command_at_that_cycle(mode, action):
    axis, fired, bp = with_breakpoint(MODES[mode], action)
    assert 100 < fired < CYCLES - 500  # mid-move, with time left to see the effect
    host = with_host(MODES[mode], action, fired)
    assert_same_runs(bp, host, fired)
    name = f"axis{axis + 1}."
    v = bp[name + "commandedVelocity"]
    motor = bp[name + "motorCommand"]
    assert motor[fired - 1] not in (BIAS, OPEN_LOOP)  # closed loop, feedforward at work
    # the cycle it fires in: the breakpoint's action is already in the motor output
    if action == "motor off":
        assert motor[fired] == OPEN_LOOP != host[name + "motorCommand"][fired]
    elif action == "abrupt stop" or (action == "smooth stop" and mode == "gear"):
        assert motor[fired] == BIAS != host[name + "motorCommand"][fired]  # no velocity left to feed
    elif action == "smooth stop" or (action == "update" and mode == "S-curve"):
        assert motor[fired] == host[name + "motorCommand"][fired]  # no register, no velocity changed
    else:
        assert motor[fired] != host[name + "motorCommand"][fired]  # the new gains
    assert v[fired - 1] != 0  # it was moving
    # and the action did what it says, whichever way the host would do it
    if action == "abrupt stop" or (action == "smooth stop" and mode == "gear"):
        assert (v[fired:] == 0).all()  # at once (gear: a smooth stop is abrupt)
    elif mode == "external" and action in ("smooth stop", "update"):
        assert (v[fired : fired + 50] == 0x18000).all()  # seed 000, 1.5: no change in motion; an Update: runs on
    elif action == "smooth stop":
        assert v[fired] != 0 and v[-1] == 0  # it brakes, then rests
        assert bp[name + "eventStatus"][-1] & PMDEventMotionCompleteMask
    elif action == "motor off":
        assert not field_ex(int(bp[name + "activityStatus"][fired]), "PMDActivityMotorOn")
        actual = bp[name + "actualPosition"]
        assert (actual[fired:] == actual[fired]).all()  # loopback, motor off: the actual position holds
    elif mode == "S-curve":
        assert bp[name + "eventStatus"][fired] & PMDEventInstructionErrorMask  # refused, as the host's 0x0C
    else:
        assert v[fired + 1] != v[fired - 1] + (v[fired - 1] - v[fired - 2])  # the new registers act


def test_velocity_contouring_smooth_stop_breakpoint_stops_where_the_hosts_smooth_stop_does():
    """The issue's numbers: 2.0 counts/cycle, breakpoint at 1000: at rest at 1040
    three thousand cycles later, as SetStopMode(smooth)+Update at that cycle, not at 5960."""
    axis, fired, bp = with_breakpoint(velocity_contouring, "smooth stop", cycles=3_000)
    host = with_host(velocity_contouring, "smooth stop", fired, cycles=3_000)
    assert_same_runs(bp, host, fired)
    assert bp["axis1.commandedPosition"][fired] >= 1_000 > bp["axis1.commandedPosition"][fired - 1]
    assert bp["axis1.commandedPosition"][-1] == host["axis1.commandedPosition"][-1] == 1_040
    assert bp["axis1.commandedVelocity"][-1] == 0


def test_update_breakpoint_on_motion_complete_starts_the_next_s_curve():
    """An S-curve cannot change in motion, but an update breakpoint on motion
    complete starts the next move at the cycle the last one ends, as the host's
    Update would."""

    def second_move(chip, action):
        axis, _ = scurve(chip, None)
        ax = chip.axis(axis)
        ax.SetPosition(16_000)
        return axis, None

    complete = (PMDEventMotionCompleteMask << 16) | PMDEventMotionCompleteMask  # select | sense
    axis, fired, bp = with_breakpoint(
        second_move, "update", cycles=9_000, trigger=PMDBreakpointEventStatus, value=complete
    )
    assert bp["axis1.commandedPosition"][fired] == 20_000 and bp["axis1.commandedVelocity"][fired] == 0
    assert_same_runs(bp, with_host(second_move, "update", fired, cycles=9_000), fired)
    assert bp["axis1.commandedPosition"][-1] == 16_000


def test_a_stop_breakpoint_leaves_the_buffered_registers_alone(chip):
    """A stop action is a stop, not an Update: what the host has written into the
    buffered registers (the next move, a stop mode of its own) stays buffered
    for its own Update (docs/decisions.md, breakpoint actions)."""
    ax = chip.axis(0)
    velocity_contouring(chip, None)
    ax.SetVelocity(-0x30000)  # the host's next move, not yet applied
    ax.SetStopMode(PMDAbruptStop)  # and a stop of its own, not yet applied
    ax.SetBreakpointValue(PMDBreakpoint1, 1_000)
    ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointActionSmoothStop, PMDBreakpointGreaterOrEqualCommandedPosition)
    chip.run(600)
    assert ax.GetEventStatus() & PMDEventBreakpoint1Mask
    assert ax.GetCommandedVelocity() == 0 and ax.GetCommandedPosition() == 1_040  # the smooth stop ran
    assert ax.GetVelocity() == -0x30000 and ax.GetStopMode() == PMDAbruptStop  # still buffered
    ax.SetStopMode(0)
    ax.Update()  # the host's Update applies them now
    chip.run(100)
    assert ax.GetCommandedVelocity() == -0x30000


def test_a_trace_on_the_next_update_starts_in_the_cycle_an_update_breakpoint_fires():
    """The one difference: the trace's "next update" start condition, checked at the end of every
    cycle, sees a breakpoint's update in the cycle it fires, and a host's Update sent after that
    cycle in the next one (its next servo loop). The breakpoint's trace takes one more sample
    first - the cycle it fired in - and then the same samples as the host's."""
    samples = {}
    for how in ("breakpoint", "host"):
        with pmdfmu.Chip() as chip:
            ax = chip.axis(0)
            ax.SetBufferStart(0, 0x100)
            ax.SetBufferLength(0, 30)
            ax.SetTraceVariable(0, 0, pmdfmu.PMDTraceTime)
            ax.SetTraceVariable(1, 0, pmdfmu.PMDTraceCommandedVelocity)
            ax.SetTraceStart(0, pmdfmu.PMDTraceConditionUpdate, 0, 0)
            ax.SetPosition(5_000)
            ax.SetVelocity(0x10000)
            ax.SetAcceleration(0x1000)
            if how == "breakpoint":
                ax.SetBreakpointValue(PMDBreakpoint1, 50)
                ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointActionUpdate, pmdfmu.PMDBreakpointTime)
                chip.run(60)
            else:
                chip.run(51)
                ax.Update()
                chip.run(9)
            words = [ax.ReadBuffer(0) for _ in range(ax.GetTraceCount())]
            samples[how] = list(zip(words[::2], words[1::2]))
    assert samples["breakpoint"][0] == (50, 0)
    assert samples["breakpoint"][1:] == samples["host"]
    assert samples["host"][0] == (51, 0x1000)  # the new move's first cycle
