# SPDX-License-Identifier: BSD-2-Clause
"""Streaming: a host streams a long external profile into
circular buffers by read index (seed 000, section 1.3: the read index tells which entries may be overwritten): run the
cycles the unread segments cover, read GetBufferReadIndex, write the freed
entries of every column with write_memory, repeat. The figure is the share of
the streamed run's wall time spent refilling (the read-index queries and the
writes), against the same profile run from one table loaded whole (the run
alone, no refill: its time is the baseline). Part of ./dev bench.

Every streamed run is checked against the whole-table run (cycles, commanded
position, velocity and activity at the end): the figure is that of a stream
that delivered the profile. The two take turns run by run (A B A B ...):
min / median / max, the ratio of medians, the machine's load beside them."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Sequence

import numpy as np

import pmdfmu
from common import RUNS, Spread, load, report

ENTRIES = 4096  # buffer entries per column (the seed's buffer_length)
SEGMENTS = 50_000  # segments streamed per run (plus the time-0 row that ends the profile)
BASE = 0x200  # the columns' buffers: BASE + f * ENTRIES
TARGET = 0.30  # the share of a streamed run spent refilling
TAIL = 64  # cycles run past the profile's segment times: it has stopped by then
RECORD = ["axis1.commandedPosition", "axis1.commandedVelocity", "axis1.commandedAcceleration"]


def profile(cycles: Sequence[int], seed: int = 16) -> np.ndarray:
    """SEGMENTS random segments of 1..7 or 8..32 cycles (position, velocity, acceleration, jerk, time
    words) and the time-0 row that stops the profile."""
    rng = np.random.default_rng(seed)
    rows = np.zeros((SEGMENTS + 1, 5), dtype=np.int64)
    rows[:SEGMENTS, 0] = np.cumsum(rng.integers(-1000, 1000, SEGMENTS))
    rows[:SEGMENTS, 1] = rng.integers(-0x40000, 0x40000, SEGMENTS)
    rows[:SEGMENTS, 2] = rng.integers(-0x100, 0x100, SEGMENTS)
    rows[:SEGMENTS, 3] = rng.integers(-4, 4, SEGMENTS)
    rows[:SEGMENTS, 4] = rng.integers(cycles[0], cycles[1] + 1, SEGMENTS)
    return rows


def buffers(chip: pmdfmu.Chip, entries: int) -> None:
    ax = chip.axis(0)
    for f in range(5):
        ax.SetBufferStart(2 + f, BASE + f * entries)
        ax.SetBufferLength(2 + f, entries)
        ax.SetBufferFunction(f, 2 + f)


def end_state(chip: pmdfmu.Chip):
    ax = chip.axis(0)
    return chip.cycles, ax.GetCommandedPosition(), ax.GetCommandedVelocity(), ax.GetActivityStatus()


def whole(version: int, rows: np.ndarray, record: Sequence[str]):
    """The profile from one table written before the start: the run's time alone, and the end state."""
    n = len(rows)
    with pmdfmu.Chip(version, memorySize=BASE + 5 * n) as chip:
        buffers(chip, n)
        for f in range(5):
            chip.write_memory(BASE + f * n, rows[:, f])
        ax = chip.axis(0)
        ax.SetProfileMode(pmdfmu.PMDExternalProfile)
        ax.Update()
        start = time.perf_counter()
        chip.run(int(rows[:, 4].sum()) + TAIL, record=record)
        took = time.perf_counter() - start
        return took, end_state(chip)


def streamed(version: int, rows: np.ndarray, record: Sequence[str]):
    """The profile streamed through ENTRIES-entry buffers: (the refill's time, the whole loop's time,
    the end state)."""
    total = len(rows)
    columns = [np.ascontiguousarray(rows[:, f] & 0xFFFFFFFF, dtype=np.uint32) for f in range(5)]
    ends = np.concatenate([[0], np.cumsum(rows[:, 4])])  # ends[i]: the cycles of segments 0..i-1
    with pmdfmu.Chip(version, memorySize=BASE + 5 * ENTRIES) as chip:
        ax = chip.axis(0)
        buffers(chip, ENTRIES)

        def write(first: int, last: int) -> None:
            """Segments first..last-1 into their entries, each column in at most two blocks (the wrap)."""
            for f in range(5):
                i = first
                while i < last:
                    slot = i % ENTRIES
                    n = min(last - i, ENTRIES - slot)
                    chip.write_memory(BASE + f * ENTRIES + slot, columns[f][i : i + n])
                    i += n

        written = min(ENTRIES - 1, total)
        write(0, written)
        ax.SetProfileMode(pmdfmu.PMDExternalProfile)
        ax.Update()
        read, index, ran, refill = 0, 0, 0, 0.0  # segments the chip has read, its read index, cycles run
        start = time.perf_counter()
        while True:
            # up to the last cycle of the last segment written: the chip never reads an entry not yet
            # written (segment i ends at cycle ends[i + 1] of the profile)
            cycles = int(ends[written]) + (TAIL if written == total else -1) - ran
            if cycles > 0:
                chip.run(cycles, record=record)
                ran += cycles
            if written == total:
                break
            begin = time.perf_counter()
            now = ax.GetBufferReadIndex(2)
            read += (now - index) % ENTRIES
            index = now
            last = min(read + ENTRIES - 1, total)  # the entry in progress was read: all others are free
            write(written, last)
            written = last
            refill += time.perf_counter() - begin
        took = time.perf_counter() - start
        return refill, took, end_state(chip)


def one(version: int, cycles: Sequence[int], record: Sequence[str], target: bool) -> None:
    rows = profile(cycles)
    runs, plain = [], []
    for _ in range(RUNS):  # in turns, as common.interleave takes them: each run returns more than a time
        runs.append(streamed(version, rows, record))
        plain.append(whole(version, rows, record))
    ends = {r[2] for r in runs} | {p[1] for p in plain}
    if len(ends) != 1:
        raise AssertionError(f"the streamed run ended elsewhere than the whole table's: {ends}")
    shares = [r[0] / r[1] for r in runs]
    loop = Spread.of([r[1] for r in runs])
    base = Spread.of([p[0] for p in plain])
    share = Spread.of(shares)
    what = f"{'recorded (3 outputs)' if record else 'not recorded'}, {cycles[0]}-{cycles[1]}-cycle segments"
    report(
        f"streamed run, FMI {version}, {what}: share refilling ({load()})",
        f"{share.text(100, '%', '.1f')} of {loop.text(1e3, 'ms', '.1f')}",
        f"the same profile from one table {base.text(1e3, 'ms', '.1f')}",
        loop.median / base.median,
        f"< {TARGET:.0%} refilling; ratio streamed / whole" if target else "report; ratio streamed / whole",
        share.median < TARGET if target else True,
    )


def benchmarks(tmp: Path) -> None:
    for version in (2, 3):
        one(version, (1, 7), (), target=True)
        one(version, (1, 7), RECORD, target=False)
        one(version, (8, 32), (), target=False)
