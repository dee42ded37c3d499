# SPDX-License-Identifier: BSD-2-Clause
"""An unrecorded doStep runs ordinary cycles in batches and fast-forwards only where a cheap
bound says it can skip many (fastforward.c, pmd_chip_run_fast_forwarding). Whatever way
the cycles go, the outputs and the state are those of a recorded doStep (every cycle run) and of
cycle by cycle; a doStep over long segments stays O(segments). Pinned by outputs, never by time."""

import random
import re
from pathlib import Path

import pmdfmu
from pmdfmu import PMDBreakpointActionAbruptStop, PMDBreakpointTime, PMDTraceCommandedPosition, PMDTraceTime
from pmdfmu.profile import load_external_profile, start_external_profile
from reference import wrap32
from scenarios import REAL

# fastforward.c's least skip worth an attempt, read from the source the FMU is built from
FAST_FORWARD_MIN = int(
    re.search(
        r"^#define FAST_FORWARD_MIN (\d+)$",
        (Path(__file__).resolve().parent.parent / "fmu_src" / "chip" / "fastforward.c").read_text(),
        re.M,
    ).group(1)
)
OUT = [
    f"axis{n}.{q}"
    for n in range(1, 5)
    for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration", "activityStatus", "eventStatus")
]


def snapshot(chip):
    return (
        [chip.get(n) for n in OUT + REAL + ["chipTime", "axis1.motorCommand"]]
        + [chip.axis(a).GetActualVelocity() for a in range(4)]
        + [chip.axis(a).GetBufferReadIndex(2 + 5 * a) for a in range(3)]
    )


def bound_tables(rng):
    """Segment times around the bound (one below, at, one above, and short ones), velocities that
    come exactly to rest inside a segment (a motion-complete event ends a skip early)."""
    tables = {}
    for axis in range(3):
        rows = []
        for _ in range(14):
            t = rng.choice(
                [
                    1,
                    2,
                    7,
                    FAST_FORWARD_MIN - 1,
                    FAST_FORWARD_MIN,
                    FAST_FORWARD_MIN + 1,
                    FAST_FORWARD_MIN + 2,
                    2 * FAST_FORWARD_MIN,
                    1000,
                ]
            )
            v, a, j = rng.randrange(-0x30000, 0x30000), rng.randrange(-0x400, 0x400), rng.randrange(-0x1000, 0x1000)
            if rng.random() < 0.3:  # at rest after m cycles, m near the bound
                m = rng.choice([FAST_FORWARD_MIN - 1, FAST_FORWARD_MIN, FAST_FORWARD_MIN + 1])
                a = rng.choice([1, -1]) * rng.randrange(1, 0x40)
                v, j = -m * a, 0
            rows.append((rng.randrange(-5000, 5000), v, a, j, t))
        rows.append((rng.randrange(-10, 10), 0, 0, 0, 0))
        tables[axis] = rows
    return tables


def started(chip, tables):
    load_external_profile(chip, tables)
    start_external_profile(chip, tables)
    return chip


def test_unrecorded_steps_equal_recorded_steps_around_the_bound():
    for seed in range(4):
        rng = random.Random(seed)
        tables = bound_tables(rng)
        with started(pmdfmu.Chip(), tables) as plain, started(pmdfmu.Chip(), tables) as recorded:
            for _ in range(16):
                n = rng.choice(
                    [1, 2, FAST_FORWARD_MIN - 1, FAST_FORWARD_MIN, FAST_FORWARD_MIN + 1, rng.randrange(1, 3000)]
                )
                rows = recorded.run(n, record=OUT)
                plain.run(n)  # one unrecorded doStep
                assert snapshot(plain)[: len(OUT)] == [int(rows[name][-1]) for name in OUT]
                assert snapshot(plain) == snapshot(recorded)


def test_an_armed_breakpoint_or_trace_steps_every_cycle_with_the_same_result():
    """Neither fast-forwards; the breakpoint fires inside a long segment, mid-step."""
    tables = {0: [(0, 0x18000, 0, 0, 5000), (0, 0, 0, 0, 0)], 1: [(100, -0x4000, 0x10, 0, 3000), (0, 0, 0, 0, 0)]}
    for armed in ("breakpoint", "trace"):
        chips = [started(pmdfmu.Chip(), tables), started(pmdfmu.Chip(), tables)]
        try:
            for chip in chips:
                ax = chip.axis(0)
                if armed == "breakpoint":
                    ax.SetBreakpointValue(0, 2345)
                    ax.SetBreakpoint(0, 0, PMDBreakpointActionAbruptStop, PMDBreakpointTime)
                else:
                    ax.SetBufferStart(0, 0x3000)
                    ax.SetBufferLength(0, 64)
                    ax.SetTracePeriod(97)
                    ax.SetTraceVariable(0, 0, PMDTraceTime)
                    ax.SetTraceVariable(1, 1, PMDTraceCommandedPosition)
                    ax.SetTraceStart(0, 0, 0, 0)  # immediate: rolling samples the whole run
            rows = chips[1].run(4000, record=OUT)
            chips[0].run(4000)
            assert snapshot(chips[0]) == snapshot(chips[1])
            assert snapshot(chips[0])[: len(OUT)] == [int(rows[name][-1]) for name in OUT]
            if armed == "breakpoint":
                assert chips[0].axis(0).GetCommandedVelocity() == 0  # stopped at 2345, mid-step
            else:
                assert [chips[0].axis(0).GetTraceCount()] == [chips[1].axis(0).GetTraceCount()] != [0]
        finally:
            for chip in chips:
                chip.close()


def test_long_segments_after_many_short_ones_take_one_step_in_o_segments():
    """Hundreds of short segments (the batches grow while fast-forward cannot pay), then 30 segments of
    2*10^9 cycles (each skipped at once): 6*10^10 cycles in one doStep. Cycle by cycle this would
    take hours; its end is exact."""
    rng = random.Random(7)
    short = [
        (rng.randrange(-5000, 5000), rng.randrange(-0x30000, 0x30000), 0, 0, rng.randrange(1, 8)) for _ in range(600)
    ]
    long = [
        (rng.randrange(-(2**31), 2**31), rng.randrange(-0x7FFFFFFF, 0x7FFFFFFF), 0, 0, 2_000_000_000) for _ in range(30)
    ]
    tables = {0: short + long + [(7, 0, 0, 0, 0)], 2: long[:3] + [(5, 0, 0, 0, 0)]}
    with started(pmdfmu.Chip(), tables) as chip:
        into_last = 1_234_567
        cycles = sum(r[4] for r in short + long[:-1]) + into_last
        chip.run(cycles)
        p, v = long[-1][0], long[-1][1]
        # the last segment read at its first cycle, then into_last - 1 steps of v / 2^16 counts
        assert chip.axis(0).GetCommandedPosition() == wrap32(p + ((into_last - 1) * v >> 16))
        assert chip.axis(0).GetCommandedVelocity() == v
        assert chip.axis(2).GetCommandedPosition() == 5  # its table ended long ago
        assert chip.get("chipTime") == wrap32(cycles - 1)


def test_a_chip_at_rest_with_loopback_off_takes_a_huge_step_at_once():
    """Every axis at rest, the servo closed by the plant (loopback 0), a limit input's sense set (the
    run is not quiet): 10^12 cycles in one doStep are skipped as before the batch policy (the fuzzer's
    sequence target found the policy stepping them one by one). The settle count saturates, the
    motor command holds, the time is exact."""
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        ax.SetSignalSense(2420)
        ax.SetSettleWindow(2)
        chip.set("axis1.actualPosition", 1)
        cycles = 10**12
        chip.run(cycles)
        assert chip.get("chipTime") == wrap32(cycles - 1)
        assert ax.GetActualPosition() == 1 and ax.GetCommandedPosition() == 0


def test_steps_of_a_host_polls_size_equal_recorded_steps_through_a_servoed_move():
    """A host polling over a slow interface steps the chip a dozen cycles at a time (Chip.wait_for):
    a doStep too short for a fast-forward runs as one batch, its ideal servo's filter brought up to
    date at its end; the outputs and the motor command are those of a recorded run (every cycle run)
    and of cycle by cycle."""
    rng = random.Random(3)
    with pmdfmu.Chip() as plain, pmdfmu.Chip() as recorded, pmdfmu.Chip() as single:
        for chip in (plain, recorded, single):
            ax = chip.axis(0)
            for name, *args in [
                ("SetProfileMode", 0),
                ("SetPosition", 3000),
                ("SetVelocity", 0x80000),
                ("SetAcceleration", 0x1000),
                ("SetDeceleration", 0x1000),
                ("Update",),
            ]:
                getattr(ax, name)(*args)
        while plain.cycles < 1200:
            n = rng.choice([1, 2, 3, 14, FAST_FORWARD_MIN - 1, FAST_FORWARD_MIN, FAST_FORWARD_MIN + 1, 200])
            rows = recorded.run(n, record=OUT)
            plain.run(n)
            assert snapshot(plain)[: len(OUT)] == [int(rows[name][-1]) for name in OUT]
            assert snapshot(plain) == snapshot(recorded)
        assert plain.axis(0).GetEventStatus() & pmdfmu.PMDEventMotionCompleteMask
        while single.cycles < plain.cycles:
            single.run(1)
        assert snapshot(plain) == snapshot(single)
