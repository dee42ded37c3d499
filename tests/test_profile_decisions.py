# SPDX-License-Identifier: BSD-2-Clause
"""The profile decisions of docs/decisions.md, each pinned by the test named
after it (docs/decisions.md, "Breakpoint actions and profile decisions"):
(a) where an external profile starts reading, (b) an Update while an external
profile runs and a restart after it stopped, (c) when Update takes effect,
(d) an S-curve parameter change in motion, (e) the velocity-contouring
direction, (f) buffers of different lengths."""

import numpy as np
import pytest

import pmdfmu
from pmdfmu import (
    PMDAbruptStop,
    PMDActivityInMotionMask,
    PMDBufferFunctionPosition,
    PMDBufferFunctionTime,
    PMDBufferFunctionVelocity,
    PMDError,
    PMDEventInstructionErrorMask,
    PMDEventMotionCompleteMask,
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
