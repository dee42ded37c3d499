# SPDX-License-Identifier: BSD-2-Clause
"""External profile mode (seed 000) against the exact reference model."""

import random
from fractions import Fraction
from math import floor

import pytest

import pmdfmu
from pmdfmu import (
    PMDAbruptStop,
    PMDActivityInMotionMask,
    PMDBufferFunctionPosition,
    PMDBufferFunctionVelocity,
    PMDError,
    PMDEventMotionCompleteMask,
    PMDExternalProfile,
    PMDSmoothStop,
    PMDTrapezoidalProfile,
    field_ex,
)
from reference import ExternalProfile, wrap32

OUTPUTS = ["axis{n}.commandedPosition", "axis{n}.commandedVelocity", "axis{n}.commandedAcceleration"]


def assign(chip, axis, rows, functions, first_id=2, start=0x200, upload="memory"):
    """Buffers for the given functions only, filled with the table's columns."""
    ax = chip.axis(axis)
    for k, f in enumerate(functions):
        bid, address = first_id + k, start + k * len(rows)
        ax.SetBufferStart(bid, address)
        ax.SetBufferLength(bid, len(rows))
        ax.SetBufferFunction(f, bid)
        column = [r[f] & 0xFFFFFFFF for r in rows]
        if upload == "memory":
            chip.write_memory(address, column)
        else:
            for v in column:
                ax.WriteBuffer(bid, v)


def start(chip, axis):
    ax = chip.axis(axis)
    ax.SetProfileMode(PMDExternalProfile)
    ax.Update()


def record(chip, cycles, axis=0):
    names = [o.format(n=axis + 1) for o in OUTPUTS]
    rec = chip.run(cycles, record=names)
    return [tuple(int(x) for x in r) for r in zip(*(rec[n] for n in names))]


def random_table(rng, n, stop=True):
    i32 = lambda: rng.randrange(-(1 << 31), 1 << 31)
    rows = [(i32(), i32(), rng.randrange(-(1 << 24), 1 << 24), i32(), rng.randrange(1, 40)) for _ in range(n)]
    if stop:
        rows.append((i32(), 0, 0, 0, 0))
    return rows


SUBSETS = {
    "all five": (0, 1, 2, 3, 4),
    "position only": (0,),
    "position+velocity": (0, 1),
    "position+time": (0, 4),
    "position+velocity+acceleration+time": (0, 1, 2, 4),
    "position+jerk+time": (0, 3, 4),
}


@pytest.mark.parametrize("subset", SUBSETS)
@pytest.mark.parametrize("seed", [1, 2])
def test_random_tables_match_the_exact_model_cycle_by_cycle(chip, subset, seed):
    rng = random.Random(seed * 100 + len(subset))
    functions = SUBSETS[subset]
    rows = random_table(rng, 60)
    assign(chip, 0, rows, functions)
    start(chip, 0)
    model = ExternalProfile(rows, functions)
    n = sum(r[4] for r in rows) + 50 if 4 in functions else len(rows) + 50
    assert record(chip, n) == model.run(n)


def test_buffers_are_read_circularly_without_a_time_0_row(chip):
    rows = [(100, 0x8000, 0x100, 0x1000000, 7), (-50, -0x18000, 0, 0, 3), (0, 0, -0x200, -0x2000000, 5)]
    assign(chip, 0, rows, range(5))
    start(chip, 0)
    assert record(chip, 200) == ExternalProfile(rows).run(200)
    assert field_ex(chip.axis(0).GetActivityStatus(), "PMDActivityProfileSegment") == 1


def test_commanded_writebuffer_upload_equals_dual_port_upload():
    rows = random_table(random.Random(7), 30)
    results = []
    for upload in ("command", "memory"):
        with pmdfmu.Chip() as chip:
            assign(chip, 0, rows, range(5), upload=upload)
            start(chip, 0)
            results.append(record(chip, 600))
    assert results[0] == results[1] == ExternalProfile(rows).run(600)


def test_time_0_stops_holding_that_rows_position(chip):
    rows = [(5, 0x30000, 0x1000, 0, 4), (1234, 0x50000, 0x7000, 0x100, 0), (99, 0, 0, 0, 9)]
    assign(chip, 0, rows, range(5))
    start(chip, 0)
    out = record(chip, 10)
    assert out[:4] == ExternalProfile(rows).run(4)
    assert out[4:] == [(1234, 0, 0)] * 6
    ax = chip.axis(0)
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 0  # halted (seed 1.6)
    assert ax.GetActivityStatus() & PMDActivityInMotionMask == 0
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileMode") == PMDExternalProfile  # still external


def test_abrupt_stop_holds_position_and_smooth_stop_changes_nothing(chip):
    rows = [(0, 0x18000, 0x80, 0, 1000), (0, 0, 0, 0, 0)]
    assign(chip, 0, rows, range(5))
    start(chip, 0)
    ax = chip.axis(0)
    model = ExternalProfile(rows)
    assert record(chip, 20) == model.run(20)
    ax.SetStopMode(PMDSmoothStop)
    ax.Update()
    assert ax.GetStopMode() == 0
    before = record(chip, 20)
    assert before == model.run(20)  # seed 1.5: no change in motion
    ax.SetStopMode(PMDAbruptStop)
    ax.Update()
    held = before[-1][0]
    assert held > 0
    assert record(chip, 5) == [(held, 0, 0)] * 5  # velocity zeroed at once, position held
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 0


def test_a_profile_with_jerk_keeps_its_exact_fraction(chip):
    # 0.32 jerk 1: the position fraction grows by 1/(6*2^32) steps that 16.16 cannot hold
    rows = [(0, 0, 0, 1, 5000), (0, 0, 0, 0, 0)]
    assign(chip, 0, rows, range(5))
    start(chip, 0)
    chip.run(4000)
    n = 3999
    exact = Fraction(n**3, 6 << 32)
    assert chip.get("axis1.position") == pytest.approx(float(exact), rel=1e-12)
    assert chip.axis(0).GetCommandedPosition() == floor(exact)
    assert chip.axis(0).GetCommandedVelocity() == floor(Fraction(n * n, 2 << 32) * 65536)


@pytest.mark.parametrize("case", ["no position buffer", "zero length", "different lengths"])
def test_start_is_refused_with_0x04_and_the_mode_unchanged(chip, case):
    ax = chip.axis(0)
    if case != "no position buffer":
        ax.SetBufferStart(2, 0x200)
        ax.SetBufferLength(2, 0 if case == "zero length" else 8)
        ax.SetBufferFunction(PMDBufferFunctionPosition, 2)
    ax.SetBufferStart(3, 0x300)
    ax.SetBufferLength(3, 4)
    ax.SetBufferFunction(PMDBufferFunctionVelocity, 3)
    ax.SetProfileMode(PMDExternalProfile)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x04
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileMode") == PMDTrapezoidalProfile  # still active
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 0
    assert ax.GetEventStatus() & pmdfmu.PMDEventInstructionErrorMask


def test_read_index_overtaking_the_write_index_warns_and_carries_on():
    with pmdfmu.Chip(log_categories=["warnings"]) as chip:
        ax = chip.axis(0)
        ax.SetBufferStart(2, 0x200)
        ax.SetBufferLength(2, 4)
        ax.SetBufferFunction(PMDBufferFunctionPosition, 2)
        ax.WriteBuffer(2, 10)
        ax.WriteBuffer(2, 20)
        start(chip, 0)
        out = record(chip, 6)
        # two entries written, then the 0s of unwritten memory, then around again: as the chip reads
        assert [p for p, _, _ in out] == [10, 20, 0, 0, 10, 20]
        warnings = [m for m in chip.messages if m.category == "warnings"]
        assert len(warnings) == 1 and "overtakes its write index" in warnings[0].message
        assert warnings[0].status == "Warning"


@pytest.mark.slow
def test_streaming_refill_following_the_read_index_for_100000_cycles(chip):
    """Seed 000, 1.3: the host reads the read index and refills the free entries
    while the profile runs. (The seed's free-entry formula uses the memory size
    where the buffer length is meant; we use the buffer length, and keep one
    entry free so that read == write always means empty.)"""
    rng = random.Random(3)
    segments = 25_000
    table = [
        (
            rng.randrange(-10_000, 10_000),
            rng.randrange(-0x40000, 0x40000),
            rng.randrange(-0x800, 0x800),
            rng.randrange(-(1 << 20), 1 << 20),
            4,
        )
        for _ in range(segments)
    ] + [(7, 0, 0, 0, 0)]
    buffer_length = 64
    ax = chip.axis(0)
    for variable in range(5):
        ax.SetBufferStart(2 + variable, 0x200 + variable * buffer_length)
        ax.SetBufferLength(2 + variable, buffer_length)
        ax.SetBufferFunction(variable, 2 + variable)
    written = 0

    def refill():
        nonlocal written
        readindex = ax.GetBufferReadIndex(2)
        writeindex = ax.GetBufferWriteIndex(2)
        if readindex > writeindex:
            free_buffer_entries = readindex - writeindex
        else:
            free_buffer_entries = buffer_length - (writeindex - readindex)
        count = min(free_buffer_entries - 1, len(table) - written)
        for variable in range(5):
            for index in range(written, written + count):
                ax.WriteBuffer(2 + variable, table[index][variable])
        written += count

    refill()
    start(chip, 0)
    got = []
    while len(got) < 4 * segments + 10:
        got += record(chip, 64)  # 16 segments per 64 cycles; the buffer holds 63
        refill()
    assert len(got) >= 100_000
    assert got == ExternalProfile(table).run(len(got))
    assert got[-1] == (7, 0, 0)


def test_no_drift_over_10_8_cycles(chip):
    """One segment of 10^8 + 1 cycles with every term non-zero: the recurrence is
    a cubic's exact Taylor step, so after n cycles P = P0 + V0 n + A0 n^2/2 + J n^3/6
    exactly; the position register wraps at 32 bits like the chip's."""
    p0, v0, a0, j = 12345, 0x12345, -0x3, 150
    rows = [(p0, v0, a0, j, 10**8 + 1), (0, 0, 0, 0, 0)]
    assign(chip, 0, rows, range(5))
    start(chip, 0)
    chip.run(10**8)
    n = 10**8 - 1  # the first cycle reads, the rest integrate
    V0, A0, J = Fraction(v0, 1 << 16), Fraction(a0, 1 << 16), Fraction(j, 1 << 32)
    p = p0 + V0 * n + A0 * n**2 / 2 + J * n**3 / 6
    v = V0 + A0 * n + J * n**2 / 2
    a = A0 + J * n
    ax = chip.axis(0)
    assert ax.GetCommandedPosition() == wrap32(floor(p))
    assert ax.GetCommandedVelocity() == wrap32(floor(v * 65536))
    assert ax.GetCommandedAcceleration() == wrap32(floor(a * 65536))
    assert ax.GetTime() == 10**8 - 1
