# SPDX-License-Identifier: BSD-2-Clause
"""The wrap-around event (event status bit 1, pmd-reference 2.2): the actual
position wrapped between the maximum and the minimum (docs/decisions.md, "Axis
inputs and status"). Set in the cycle it happens, going up or down, in loopback
and from the encoder input; it raises the host interrupt it is masked into and
fires event-status breakpoints; ResetEventStatus clears it; fast-forward never
skips it. Each is compared with reference.wrap_arounds."""

import pmdfmu
from pmdfmu import (
    PMDActivityInMotionMask,
    PMDBreakpoint1,
    PMDBreakpointActionAbruptStop,
    PMDBreakpointEventStatus,
    PMDEventBreakpoint1Mask,
    PMDEventWrapAroundMask,
    PMDVelocityContouringProfile,
)
from pmdfmu.profile import load_external_profile, start_external_profile
from reference import wrap32, wrap_arounds

MAX, MIN = 2**31 - 1, -(2**31)
WRAP = PMDEventWrapAroundMask
POSITION, EVENTS = "axis1.commandedPosition", "axis1.eventStatus"


def velocity_move(ax, start, velocity):
    """Velocity contouring from start at `velocity` counts/cycle, reached in one cycle."""
    ax.SetActualPosition(start)  # loopback: the commanded position moves with it
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(wrap32(velocity << 16))
    ax.SetAcceleration(abs(velocity) << 16)
    ax.Update()


def first_set(events):
    """The index of the first row whose event status has the wrap-around bit, or None."""
    hits = [k for k, e in enumerate(events) if int(e) & WRAP]
    return hits[0] if hits else None


def check_wrap_in_its_cycle(chip, start, velocity, cycles):
    ax = chip.axis(0)
    velocity_move(ax, start, velocity)
    rec = chip.run(cycles, record=[POSITION, EVENTS])
    expected = wrap_arounds(start, [int(p) for p in rec[POSITION]])
    assert len(expected) == 1
    assert first_set(rec[EVENTS]) == expected[0]
    return expected[0]


def test_loopback_going_up_sets_wrap_around_in_the_cycle_the_position_wraps(any_chip):
    k = check_wrap_in_its_cycle(any_chip, MAX - 100, 7, 40)
    assert k == 14  # MAX - 100 + 7 * 15 passes MAX in the 15th cycle


def test_loopback_going_down_sets_wrap_around_in_the_cycle_the_position_wraps(any_chip):
    k = check_wrap_in_its_cycle(any_chip, MIN + 100, -7, 40)
    assert k == 14


def test_crossing_zero_and_running_inside_the_range_set_no_wrap_around(any_chip):
    ax = any_chip.axis(0)
    velocity_move(ax, -1000, 100)
    rec = any_chip.run(100, record=[POSITION, EVENTS])
    assert int(rec[POSITION][-1]) == 9000
    assert first_set(rec[EVENTS]) is None
    assert not ax.GetEventStatus() & WRAP


def test_encoder_input_jumping_across_the_wrap_sets_wrap_around_either_way():
    for fmi in (2, 3):
        with pmdfmu.Chip(fmi_version=fmi, loopback=False) as chip:
            ax = chip.axis(0)
            ax.SetPositionErrorLimit(0x7FFFFFFF)  # the encoder alone moves: no motion error
            seen = []
            # up through MAX, through 0, a big step inside the range, down through MIN, up again
            inputs = [MAX - 600, MIN + 696, MIN + 900, -5, 5, 2_000_000_000, MIN + 10, MAX - 10, MIN]
            for p in inputs:
                chip.set("axis1.actualPosition", p)
                chip.run(1)
                seen.append(bool(ax.GetEventStatus() & WRAP))
                ax.ResetEventStatus(0xFFFF & ~WRAP)
            hits = set(wrap_arounds(0, inputs))
            assert seen == [k in hits for k in range(len(inputs))]
            assert seen == [False, True, False, False, False, False, True, True, True]


def test_reset_event_status_clears_wrap_around_and_a_later_wrap_sets_it_again(any_chip):
    ax = any_chip.axis(0)
    velocity_move(ax, MAX - 10, 1)
    any_chip.run(20)
    assert ax.GetEventStatus() & WRAP
    ax.ResetEventStatus(0xFFFF & ~WRAP)
    assert not ax.GetEventStatus() & WRAP
    any_chip.run(100)
    assert not ax.GetEventStatus() & WRAP  # running on inside the range
    ax.SetActualPosition(MAX)
    any_chip.run(2)
    assert ax.GetEventStatus() & WRAP


def test_wrap_around_raises_the_host_interrupt_it_is_masked_into(any_chip):
    ax = any_chip.axis(0)
    ax.SetInterruptMask(WRAP)
    velocity_move(ax, MAX - 50, 10)
    any_chip.run(5)
    assert not any_chip.get("host.interrupt")
    any_chip.run(1)  # 50 counts to MAX: the 6th cycle passes it
    assert any_chip.get("host.interrupt") and ax.GetEventStatus() & WRAP
    ax.ResetEventStatus(0xFFFF & ~WRAP)
    ax.ClearInterrupt()
    any_chip.run(1)
    assert not any_chip.get("host.interrupt")


def test_an_unmasked_wrap_around_leaves_the_host_interrupt_low(any_chip):
    ax = any_chip.axis(0)
    ax.SetInterruptMask(0xFFFF & ~WRAP)
    velocity_move(ax, MAX - 50, 10)
    any_chip.run(10)
    assert ax.GetEventStatus() & WRAP and not any_chip.get("host.interrupt")


def test_an_event_status_breakpoint_on_wrap_around_fires_in_the_wrap_cycle(any_chip):
    ax = any_chip.axis(0)
    ax.SetBreakpointValue(PMDBreakpoint1, (WRAP << 16) | WRAP)  # select the bit, fire when it reads 1
    ax.SetBreakpoint(PMDBreakpoint1, 0, PMDBreakpointActionAbruptStop, PMDBreakpointEventStatus)
    velocity_move(ax, MAX - 50, 10)
    rec = any_chip.run(20, record=[POSITION, EVENTS])
    k = wrap_arounds(MAX - 50, [int(p) for p in rec[POSITION]])[0]
    assert k == 5
    assert int(rec[EVENTS][k]) & PMDEventBreakpoint1Mask and not int(rec[EVENTS][k - 1]) & PMDEventBreakpoint1Mask
    # the abrupt stop holds the position the wrap cycle reached
    assert [int(p) for p in rec[POSITION][k:]] == [wrap32(MAX - 50 + 60)] * (20 - k)
    assert not ax.GetActivityStatus() & PMDActivityInMotionMask


# an external profile: 1 count/cycle from MAX - 10_000 for 30_000 cycles (wraps in cycle 10_001
# of the profile), then a segment from MIN + 100 at 2 counts/cycle braking at 64/2^16
# count/cycle^2: it turns back and comes down through MIN; then a stop row
CROSSING = [
    (MAX - 10_000, 0x10000, 0, 0, 30_000),
    (MIN + 100, 0x20000, wrap32(-64), 0, 10_000),
    (0, 0, 0, 0, 0),
]


def external_wraps(rows):
    """The profile's cycles (0 = the first cycle after the Update) whose
    position wraps, from seed 000's recurrence in exact arithmetic."""
    from reference import ExternalProfile

    profile = ExternalProfile(rows, functions=range(5))
    positions = [r[0] for r in profile.run(sum(r[4] for r in rows) + 1)]
    return wrap_arounds(0, positions), positions


def test_a_fast_forwarded_doStep_sets_wrap_around_in_the_same_cycle_as_stepping():
    wraps, positions = external_wraps(CROSSING)
    assert wraps == [10_001, 34_146]  # up through MAX, then down through MIN on the way back
    for fmi in (2, 3):
        with pmdfmu.Chip(fmi_version=fmi) as coarse, pmdfmu.Chip(fmi_version=fmi) as fine:
            for chip in (coarse, fine):
                load_external_profile(chip, {0: CROSSING})
                start_external_profile(chip, [0])
            ran = 0  # the profile's cycles run so far
            for w in wraps:
                for chip in (coarse, fine):
                    chip.axis(0).ResetEventStatus(0xFFFF & ~WRAP)
                coarse.run(w - ran)  # one doStep, fast-forwarding: ends the cycle before the wrap
                assert not coarse.axis(0).GetEventStatus() & WRAP
                coarse.run(1)
                assert coarse.axis(0).GetEventStatus() & WRAP
                rec = fine.run(w - ran + 1, record=[POSITION, EVENTS])
                assert first_set(rec[EVENTS]) == w - ran
                assert [int(p) for p in rec[POSITION][-3:]] == positions[w - 2 : w + 1]
                assert coarse.get(POSITION) == fine.get(POSITION) == positions[w]
                ran = w + 1


def test_one_long_doStep_across_each_wrap_sets_wrap_around():
    """A doStep whose middle holds the wrap: the closed-form skip must not pass it."""
    wraps, positions = external_wraps(CROSSING)
    for fmi in (2, 3):
        with pmdfmu.Chip(fmi_version=fmi) as chip:
            load_external_profile(chip, {0: CROSSING})
            start_external_profile(chip, [0])
            ran = 0
            for w, end in zip(wraps, (30_000, 40_000)):
                assert ran + 1 < w < end - 1  # inside the doStep, neither its first nor its last cycle
                chip.axis(0).ResetEventStatus(0xFFFF & ~WRAP)
                chip.run(end - ran)  # from well before the wrap to well after it
                assert chip.axis(0).GetEventStatus() & WRAP
                assert chip.get(POSITION) == positions[end - 1]
                ran = end


def test_a_recorded_quiet_run_sets_wrap_around_where_the_cycle_by_cycle_run_does():
    """A recording of the trajectory alone runs the quiet middle cycles, which
    do not sample an ideal servo's actual position: the wrap is watched there."""
    for fmi in (2, 3):
        with pmdfmu.Chip(fmi_version=fmi) as chip:
            ax = chip.axis(0)
            velocity_move(ax, MAX - 5_000, 3)
            rec = chip.run(1665, record=[POSITION])
            assert not ax.GetEventStatus() & WRAP
            rec = chip.run(1000, record=[POSITION])  # 1667 * 3 = 5001: passes MAX in its 2nd cycle
            assert wrap_arounds(MAX - 5_000 + 1665 * 3, [int(p) for p in rec[POSITION]]) == [1]
            assert ax.GetEventStatus() & WRAP


def test_a_profile_that_turns_back_before_the_maximum_sets_no_wrap_around_and_still_fast_forwards():
    # 1 count/cycle up for 10^6 cycles from MAX - 1_000_001: ends one count below MAX, then back
    rows = [(MAX - 1_000_001, 0x10000, 0, 0, 1_000_000), (MAX - 1, wrap32(-0x10000), 0, 0, 1_000_000), (0, 0, 0, 0, 0)]
    wraps, positions = external_wraps(rows)
    assert wraps == [] and max(positions) == MAX - 1
    for fmi in (2, 3):
        with pmdfmu.Chip(fmi_version=fmi) as chip:
            load_external_profile(chip, {0: rows})
            start_external_profile(chip, [0])
            chip.run(2_000_000)
            assert not chip.axis(0).GetEventStatus() & WRAP
            assert chip.get(POSITION) == positions[1_999_999]


def test_set_and_adjust_actual_position_across_the_ends_set_no_wrap_around():
    """They move the origin, not the axis: both samples move together (docs/decisions.md)."""
    for loopback in (True, False):
        with pmdfmu.Chip(loopback=loopback) as chip:
            ax = chip.axis(0)
            ax.SetActualPosition(MAX)
            chip.run(2)
            ax.SetActualPosition(MIN)
            chip.run(2)
            ax.AdjustActualPosition(-1)  # MIN - 1: the maximum again
            chip.run(2)
            assert ax.GetActualPosition() == MAX
            assert not ax.GetEventStatus() & WRAP
