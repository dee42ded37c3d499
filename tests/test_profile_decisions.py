# SPDX-License-Identifier: BSD-2-Clause
"""The profile decisions of docs/decisions.md, each pinned by the test named
after it (docs/decisions.md, "Breakpoint actions and profile decisions"):
(a) where an external profile starts reading, (b) an Update while an external
profile runs and a restart after it stopped, (c) when Update takes effect,
(d) an S-curve parameter change in motion, (e) the velocity-contouring
direction, (f) buffers of different lengths, (g) the decisions a real program
meets (low buffers, a zero velocity, the int32 wrap, reversing through zero, the
16.16 range, the rolling trace's read index, the settle window, the motion
error after a reset, a trace's stop cycle)."""

import numpy as np
import pytest

import pmdfmu
from pmdfmu import (
    PMDAbruptStop,
    PMDActivityAxisSettledMask,
    PMDActivityInMotionMask,
    PMDBufferFunctionPosition,
    PMDBufferFunctionTime,
    PMDBufferFunctionVelocity,
    PMDError,
    PMDEventInstructionErrorMask,
    PMDEventMotionCompleteMask,
    PMDEventMotionErrorMask,
    PMDExternalProfile,
    PMDSCurveProfile,
    PMDTrapezoidalProfile,
    PMDVelocityContouringProfile,
    field_ex,
)

TRAJECTORY = ["axis1.commandedPosition", "axis1.commandedVelocity", "axis1.commandedAcceleration"]
FUNCTIONS = (PMDBufferFunctionPosition, PMDBufferFunctionVelocity, PMDBufferFunctionTime)


def external_rows(chip, rows, lengths=None):
    """Buffers 2, 3, 4 for position, velocity and time, filled with the rows
    (position, 16.16 velocity, time); lengths overrides each buffer's length."""
    ax = chip.axis(0)
    for k, function in enumerate(FUNCTIONS):
        address = 0x200 + 0x40 * k
        ax.SetBufferStart(2 + k, address)
        ax.SetBufferLength(2 + k, lengths[k] if lengths else len(rows))
        ax.SetBufferFunction(function, 2 + k)
        chip.write_memory(address, [r[k] & 0xFFFFFFFF for r in rows])


def start_external(chip):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDExternalProfile)
    ax.Update()


def positions(chip, cycles):
    return [int(p) for p in chip.run(cycles, record=["axis1.commandedPosition"])["axis1.commandedPosition"]]


def segment(chip):
    return field_ex(chip.axis(0).GetActivityStatus(), "PMDActivityProfileSegment")


# rows of 3 cycles each from 100, 200, 300 ... at 1 count/cycle; row 3 has time 0 (a stop row)
ROWS = [(100, 0x10000, 3), (200, 0x10000, 3), (300, 0x10000, 3), (400, 0, 0), (500, 0x10000, 3), (600, 0, 0)]


# ---- (a) where an external profile starts reading ------------------------------------------------


def test_external_profile_starts_at_offset_0_after_the_buffers_are_set_up(chip):
    """Seed 000: "When the external profile is first started, the data at offset 0 ... is read":
    setting a buffer's start or length puts its read index at 0, so a first start reads row 0."""
    external_rows(chip, ROWS)
    assert chip.axis(0).GetBufferReadIndex(2) == 0
    start_external(chip)
    assert positions(chip, 4) == [100, 101, 102, 200]


def test_external_profile_starts_at_the_position_buffers_read_index(chip):
    """The FMU starts at the current read index, not always at offset 0: the host may set it
    (SetBufferReadIndex) and a restart goes on where the profile stopped (seed 000, 1.3 streams
    data behind the read index). Every buffer's row is taken at the position buffer's index."""
    external_rows(chip, ROWS)
    ax = chip.axis(0)
    ax.SetBufferReadIndex(2, 4)
    ax.ReadBuffer(3)  # moves only the velocity buffer's index: not used
    start_external(chip)
    assert positions(chip, 5) == [500, 501, 502, 600, 600]
    assert ax.GetBufferReadIndex(2) == ax.GetBufferReadIndex(3) == ax.GetBufferReadIndex(4) == 0


# ---- (b) an Update while an external profile runs; a restart after it stopped --------------------


def test_update_while_an_external_profile_runs_changes_nothing():
    """An Update (no stop mode, profile mode still external) neither restarts nor re-reads: the
    segment runs on as if no Update had come; the other registers it applies are not used."""
    runs = []
    for update in (False, True):
        with pmdfmu.Chip() as chip:
            external_rows(chip, ROWS)
            start_external(chip)
            run = positions(chip, 4)
            if update:
                chip.axis(0).SetVelocity(0x50000)
                chip.axis(0).Update()
            runs.append(run + positions(chip, 10))
    assert runs[0] == runs[1] == [100, 101, 102, 200, 201, 202, 300, 301, 302, 400, 400, 400, 400, 400]


def test_restart_after_a_time_0_row_reads_the_row_after_it(chip):
    """A time-0 row halts the profile holding its position (seed 000, 1.5); the read index is then
    past it, so the next Update starts with the row after it: a time-0 row is a pause point."""
    external_rows(chip, ROWS)
    start_external(chip)
    assert positions(chip, 12)[-3:] == [400, 400, 400]
    assert segment(chip) == 0 and chip.axis(0).GetBufferReadIndex(2) == 4
    start_external(chip)
    assert positions(chip, 5) == [500, 501, 502, 600, 600]
    assert segment(chip) == 0


def test_restart_after_an_abrupt_stop_reads_the_next_row(chip):
    """An abrupt stop mid-segment drops the rest of that segment; the restart reads the next row
    (its position is the host's to match, seed 000, 1.4)."""
    external_rows(chip, ROWS)
    start_external(chip)
    assert positions(chip, 2) == [100, 101]
    ax = chip.axis(0)
    ax.SetStopMode(PMDAbruptStop)
    ax.Update()
    assert positions(chip, 3) == [101, 101, 101] and segment(chip) == 0
    start_external(chip)
    assert positions(chip, 4) == [200, 201, 202, 300]


# ---- (c) when Update takes effect ---------------------------------------------------------------


def test_update_takes_effect_at_the_next_cycle(chip):
    """Seed 004: an Update applies the registers "at the next servo loop". The FMU applies them
    when the command runs, between two cycles: the outputs read right after it still show the
    last cycle's trajectory, and the next cycle is the new profile's first - the move is the
    same whichever cycle it starts after."""
    ax = chip.axis(0)
    ax.SetPosition(3_000)
    ax.SetVelocity(0x30000)
    ax.SetAcceleration(0x2000)
    started_at_0 = chip.run(1_200, record=TRAJECTORY)  # not yet: no Update
    assert (started_at_0["axis1.commandedVelocity"] == 0).all()
    ax.Update()
    assert [chip.get(n) for n in TRAJECTORY] == [0, 0, 0]  # nothing moves before the next cycle
    after = chip.run(1_200, record=TRAJECTORY)
    with pmdfmu.Chip() as fresh:
        a = fresh.axis(0)
        a.SetPosition(3_000)
        a.SetVelocity(0x30000)
        a.SetAcceleration(0x2000)
        a.Update()  # after no cycle: cycle 0 is its first
        reference = fresh.run(1_200, record=TRAJECTORY)
    for name in TRAJECTORY:
        assert np.array_equal(after[name], reference[name])
    assert after["axis1.commandedVelocity"][0] == 0x2000 and after["axis1.commandedPosition"][-1] == 3_000


def test_an_abrupt_stop_shows_at_once_and_the_next_cycle_holds_the_position(chip):
    """Where applying at command time differs from "at the next servo loop": an abrupt stop zeroes
    the commanded velocity and acceleration and sets motion complete when the command runs, so a
    read before the next cycle already shows them. From the next cycle on the trajectory is the
    chip's: the position of the last cycle, held."""
    ax = chip.axis(0)
    ax.SetPosition(100_000)
    ax.SetVelocity(0x40000)
    ax.SetAcceleration(0x1000)
    ax.Update()
    before = chip.run(100, record=TRAJECTORY)
    held = int(before["axis1.commandedPosition"][-1])
    assert before["axis1.commandedVelocity"][-1] != 0
    ax.SetStopMode(PMDAbruptStop)
    ax.Update()
    assert [chip.get(n) for n in TRAJECTORY] == [held, 0, 0]
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask
    assert not ax.GetActivityStatus() & PMDActivityInMotionMask
    after = chip.run(5, record=TRAJECTORY)
    assert (after["axis1.commandedPosition"] == held).all() and (after["axis1.commandedVelocity"] == 0).all()


# ---- (d) an S-curve parameter change in motion -----------------------------------------------------


def test_scurve_change_in_motion_keeps_the_new_position_buffered_for_the_next_update(chip):
    """Seed 001: a change during an S-curve is a command error and "all new parameters will be
    ignored except the position". The FMU refuses the Update with 0x0C and applies nothing: the
    move ends on its planned destination. The new position is kept - in the buffered register,
    where GetPosition reads it - and the host's next Update, at rest, moves there."""
    ax = chip.axis(0)
    ax.SetProfileMode(PMDSCurveProfile)
    ax.SetPosition(20_000)
    ax.SetVelocity(0x40000)
    ax.SetAcceleration(0x400)
    ax.SetJerk(0x1000000)
    ax.Update()
    chip.run(1_000)
    ax.SetPosition(8_000)  # behind the axis, which is past 2000 by now
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0C and ax.GetEventStatus() & PMDEventInstructionErrorMask
    assert ax.GetPosition() == 8_000  # kept, buffered
    chip.run(6_000)
    assert ax.GetCommandedPosition() == 20_000 and not ax.GetActivityStatus() & PMDActivityInMotionMask
    ax.Update()  # at rest: the kept position is the next destination
    chip.run(6_000)
    assert ax.GetCommandedPosition() == 8_000


# ---- (e) velocity contouring direction ----------------------------------------------------------


def test_velocity_contouring_direction_is_the_signed_velocity(chip):
    """The Navigator (reference 5): the velocity is signed and sets the direction; the
    acceleration is a magnitude. The MC1231A's way - a positive maximum velocity and a signed
    acceleration - does not work here: its own example, an acceleration of -1.95 (0xFFFE0CCD),
    is refused at SetAcceleration with 0x0B and the register keeps its value."""
    ax = chip.axis(0)
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetAcceleration(0x8000)
    ax.SetVelocity(-0x20000)
    ax.Update()
    rec = chip.run(10, record=TRAJECTORY)
    assert list(rec["axis1.commandedVelocity"][:5]) == [-0x8000, -0x10000, -0x18000, -0x20000, -0x20000]
    assert rec["axis1.commandedPosition"][-1] < 0
    with pytest.raises(PMDError) as e:
        ax.SetAcceleration(-127_795)  # seed 001: -1.95 * 65536, sent as fffe0ccd
    assert e.value.code == 0x0B
    assert ax.GetAcceleration() == 0x8000


# ---- (f) buffers of different lengths ----------------------------------------------------------


def test_buffers_of_different_lengths_refuse_the_update_until_they_match(chip):
    """Seed 000: "each buffer must have the same length". An Update into external mode with
    assigned buffers of different lengths is refused with 0x04 (the mode stays as it was); once
    the host makes them the same, the same Update starts the profile."""
    external_rows(chip, ROWS, lengths=(len(ROWS), len(ROWS), len(ROWS) - 1))
    ax = chip.axis(0)
    ax.SetProfileMode(PMDExternalProfile)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x04
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileMode") == PMDTrapezoidalProfile
    ax.SetBufferLength(4, len(ROWS))
    ax.Update()
    assert positions(chip, 4) == [100, 101, 102, 200]


def test_buffer_lengths_changed_while_running_halt_the_profile():
    """A length changed under a running profile cannot be read "at the same offset": the
    profile halts (abruptly, holding its position) with a warning at its next segment read."""
    with pmdfmu.Chip(log_categories=["warnings"]) as chip:
        external_rows(chip, ROWS)
        start_external(chip)
        assert positions(chip, 2) == [100, 101]
        chip.axis(0).SetBufferLength(3, len(ROWS) + 1)  # the velocity buffer's length
        assert positions(chip, 4) == [102, 102, 102, 102]  # the segment ends; the next read halts
        assert segment(chip) == 0
        assert any("lengths differ" in m.message for m in chip.messages if m.category == "warnings")


# ---- (g) the decisions a real program meets (docs/decisions.md, "Decisions a real program meets") ----

MAX32, MIN32 = 2**31 - 1, -(2**31)


def test_a_buffer_starting_below_0x200_is_accepted_and_runs(chip):
    """Seed 000 reserves the first 1K x 16 words (512 32-bit words) for the motion processor, as a
    rule for the host's memory plan; no command refuses a buffer there, and nothing of the chip's
    lives there in the FMU: a profile in buffers at 0x0, 0x10 and 0x20 runs as anywhere else."""
    ax = chip.axis(0)
    for k, function in enumerate(FUNCTIONS):
        ax.SetBufferStart(2 + k, 0x10 * k)
        ax.SetBufferLength(2 + k, 2)
        ax.SetBufferFunction(function, 2 + k)
    chip.write_memory(0x00, [100, 0])
    chip.write_memory(0x10, [0x10000, 0])
    chip.write_memory(0x20, [5, 0])
    start_external(chip)
    assert positions(chip, 7) == [100, 101, 102, 103, 104, 0, 0]
    assert chip.axis(0).GetEventStatus() & PMDEventMotionCompleteMask


def test_a_trapezoidal_move_with_maximum_velocity_0_never_moves_and_stays_in_motion(chip):
    """Accepted (0 is a legal velocity); the generator may never exceed it, so the axis holds its
    position, shows "in motion" (the move has not ended) and never sets motion complete, until the
    host changes the velocity or stops it."""
    ax = chip.axis(0)
    ax.SetProfileMode(PMDTrapezoidalProfile)
    ax.SetPosition(1000)
    ax.SetVelocity(0)
    ax.SetAcceleration(0x1000)
    ax.Update()
    rec = chip.run(10_000, record=TRAJECTORY)
    assert set(int(p) for p in rec["axis1.commandedPosition"]) == {0}
    assert ax.GetActivityStatus() & PMDActivityInMotionMask
    assert not ax.GetEventStatus() & PMDEventMotionCompleteMask
    ax.SetVelocity(0x10000)
    ax.Update()
    chip.run(2_000)
    assert ax.GetCommandedPosition() == 1000 and ax.GetEventStatus() & PMDEventMotionCompleteMask


def test_a_trapezoidal_move_across_the_int32_wrap_goes_the_long_way(chip):
    """Positions are signed 32-bit numbers and a destination is one of them: from 2^31 - 101 to
    -2^31 + 100 the move runs down through 0 (4 294 967 095 counts), never across the wrap, and
    never sets the wrap-around event."""
    ax = chip.axis(0)
    ax.SetActualPosition(MAX32 - 100)
    ax.SetProfileMode(PMDTrapezoidalProfile)
    ax.SetPosition(MIN32 + 100)
    ax.SetVelocity(0x7FFF0000)
    ax.SetAcceleration(0x10000000)
    ax.Update()
    rec = chip.run(200_000, record=["axis1.commandedPosition", "axis1.eventStatus"])
    p = [int(x) for x in rec["axis1.commandedPosition"]]
    assert all(b <= a for a, b in zip(p, p[1:]))  # monotone: down all the way
    assert p[-1] == MIN32 + 100
    assert not any(int(e) & pmdfmu.PMDEventWrapAroundMask for e in rec["axis1.eventStatus"])
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask


def test_velocity_contouring_reversing_through_zero_lands_exactly_on_0_with_a_partial_step(chip):
    """Slowing down toward the other direction stops at 0 first: from 1.5 counts/cycle with a
    deceleration of 1.0 the velocity goes 0.5, then exactly 0 (a step of 0.5, not 1.0), then
    speeds up the other way at the acceleration: -1.0, -1.5."""
    ax = chip.axis(0)
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(0x18000)
    ax.SetAcceleration(0x10000)
    ax.Update()
    chip.run(3)
    ax.SetVelocity(-0x18000)
    ax.SetDeceleration(0x10000)
    ax.Update()
    rec = chip.run(5, record=TRAJECTORY)
    assert [int(v) for v in rec["axis1.commandedVelocity"]] == [0x8000, 0, -0x10000, -0x18000, -0x18000]
    assert ax.GetActivityStatus() & PMDActivityInMotionMask  # passing through 0 is not a rest


def test_the_16_16_velocity_range_is_the_full_32_bit_word(chip):
    """Seed 000, 1.7 gives 16.16 as -32768 .. 32767.99998 (the whole word); its 1.2 comment and the
    MC1231A give +-16384. The register holds the word and nothing refuses or clamps it: a
    velocity of 0x7FFFFFFF is reached in velocity contouring and read from an external profile."""
    ax = chip.axis(0)
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(0x7FFFFFFF)
    ax.SetAcceleration(0x40000000)
    ax.Update()
    chip.run(3)
    assert ax.GetVelocity() == 0x7FFFFFFF and ax.GetCommandedVelocity() == 0x7FFFFFFF
    with pmdfmu.Chip() as other:
        external_rows(other, [(0, 0x7FFFFFFF, 3), (0, 0, 0)])
        start_external(other)
        rec = other.run(3, record=TRAJECTORY)
        assert [int(v) for v in rec["axis1.commandedVelocity"]] == [0x7FFFFFFF] * 3
        assert [int(p) for p in rec["axis1.commandedPosition"]] == [0, 32767, 65535]


def rolling_time_trace(ax, length):
    ax.SetBufferStart(0, 0x100)
    ax.SetBufferLength(0, length)
    ax.SetTraceMode(pmdfmu.PMDTraceRollingBuffer)
    ax.SetTracePeriod(1)
    ax.SetTraceVariable(0, 0, pmdfmu.PMDTraceTime)
    ax.SetTraceVariable(1, 0, 0)  # one slot: the chip time


def test_a_rolling_trace_that_wrapped_moves_buffer_0s_read_index_to_its_oldest_sample_when_it_stops(chip):
    """Reference 4.3 [M]: the rolling trace moves buffer 0's read index when it completes. It
    stops with the write index on the oldest sample; the read index goes there, so ReadBuffer
    reads the samples oldest first. A rolling trace that did not wrap leaves it alone."""
    ax = chip.axis(0)
    rolling_time_trace(ax, 7)
    ax.SetTraceStart(0, pmdfmu.PMDTraceConditionImmediate, 0, 0)
    chip.run(20)
    assert ax.GetBufferReadIndex(0) == 0  # still running
    ax.SetTraceStop(0, pmdfmu.PMDTraceConditionImmediate, 0, 0)
    last = ax.GetTime()
    assert ax.GetBufferReadIndex(0) == ax.GetBufferWriteIndex(0) == 20 % 7
    assert [ax.ReadBuffer(0) for _ in range(7)] == list(range(last - 6, last + 1))
    with pmdfmu.Chip() as other:
        bx = other.axis(0)
        rolling_time_trace(bx, 30)
        bx.SetTraceStart(0, pmdfmu.PMDTraceConditionImmediate, 0, 0)
        other.run(10)
        bx.SetTraceStop(0, pmdfmu.PMDTraceConditionImmediate, 0, 0)
        assert bx.GetBufferReadIndex(0) == 0 and bx.GetBufferWriteIndex(0) == 10


def test_a_trace_stopped_by_a_trigger_keeps_the_stop_cycles_sample(chip):
    """The sample of a cycle is taken before the stop condition is checked at its end: the
    cycle that meets the condition is the last one in the buffer."""
    ax = chip.axis(0)
    ax.SetBufferStart(0, 0x100)
    ax.SetBufferLength(0, 100)
    ax.SetTraceMode(pmdfmu.PMDTraceOneTime)
    ax.SetTracePeriod(1)
    ax.SetTraceVariable(0, 0, pmdfmu.PMDTraceTime)
    ax.SetTraceVariable(1, 0, pmdfmu.PMDTraceCommandedPosition)
    ax.SetTraceVariable(2, 0, 0)
    ax.SetTraceStop(0, pmdfmu.PMDTraceConditionEventStatus, PMDEventMotionCompleteMask.bit_length() - 1, 1)
    ax.SetTraceStart(0, pmdfmu.PMDTraceConditionImmediate, 0, 0)
    ax.SetProfileMode(PMDTrapezoidalProfile)
    ax.SetPosition(10)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x10000)
    ax.Update()
    rec = chip.run(40, record=["axis1.commandedPosition", "axis1.eventStatus"])
    done = next(k for k, e in enumerate(rec["axis1.eventStatus"]) if int(e) & PMDEventMotionCompleteMask)
    count = ax.GetTraceCount()
    samples = [pmdfmu.signed(ax.ReadBuffer(0)) for _ in range(count)]
    assert samples[-2:] == [int(rec["cycle"][done]), int(rec["axis1.commandedPosition"][done])]
    assert count == 2 * (done + 1)
    assert ax.GetTraceStatus() & pmdfmu.PMDTraceStatusActivity == 0


def test_the_settle_window_is_inclusive():
    """Settled means |position error| <= the settle window for more than the settle time: an
    error equal to the window settles, one count more does not."""
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        ax.SetSettleWindow(5)
        ax.SetSettleTime(3)
        chip.set("axis1.actualPosition", 5)
        rec = chip.run(6, record=["axis1.activityStatus"])
        settled = [bool(int(s) & PMDActivityAxisSettledMask) for s in rec["axis1.activityStatus"]]
        assert ax.GetPositionError() == 5
        assert settled == [False, False, False, True, True, True]  # more than 3 cycles inside
        chip.set("axis1.actualPosition", -6)
        chip.run(10)
        assert not ax.GetActivityStatus() & PMDActivityAxisSettledMask


def test_after_reset_event_status_the_motion_error_bit_is_set_again_while_the_error_stays_beyond_the_limit():
    """The motion error is a condition checked every cycle, and the bit its latch: cleared while
    the error is still beyond the limit, it is set again at the next cycle (and each cycle after
    another reset); once the error is back inside, a reset keeps it clear."""
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        ax.SetPositionErrorLimit(10)
        chip.set("axis1.actualPosition", 50)
        chip.run(2)
        assert ax.GetEventStatus() & PMDEventMotionErrorMask
        for _ in range(3):
            ax.ResetEventStatus(0xFFFF & ~PMDEventMotionErrorMask)
            assert not ax.GetEventStatus() & PMDEventMotionErrorMask
            chip.run(1)
            assert ax.GetEventStatus() & PMDEventMotionErrorMask
        chip.set("axis1.actualPosition", 10)  # back at the limit: not beyond it
        chip.run(1)
        ax.ResetEventStatus(0xFFFF & ~PMDEventMotionErrorMask)
        chip.run(5)
        assert not ax.GetEventStatus() & PMDEventMotionErrorMask
