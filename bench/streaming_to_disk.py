# SPDX-License-Identifier: BSD-2-Clause
"""Issue target 5: chip.run(n, record=..., to="run.npy") against chip.run(n, record=...) in memory, the
same profile (bench/recording.py's random table, 4 axes), 10^6 cycles, the 12 commanded outputs and the
status + Reals set, FMI 2. Interleaved; the file goes to the bench's temporary folder (its disk's speed
is part of the figure); target: >= 0.5x the in-memory rate."""

from __future__ import annotations

import time

from common import interleave, load, report
from recording import AXES, SETS, prepared, segment_table

CYCLES = 1_000_000


def one_set(tmp, table, label: str, names: list) -> None:
    def memory():
        with prepared(2, table) as chip:
            start = time.perf_counter()
            chip.run(CYCLES, record=names)
            return time.perf_counter() - start

    def disk():
        with prepared(2, table) as chip:
            start = time.perf_counter()
            chip.run(CYCLES, record=names, to=tmp / "run.npy")
            took = time.perf_counter() - start
        (tmp / "run.npy").unlink()
        return took

    t = interleave({"disk": disk, "memory": memory})
    rate = t["memory"].median / t["disk"].median  # the file's rate over the in-memory rate
    report(
        f"run(to=.npy), {label}, 10^6 cycles, FMI 2 ({load()})",
        f"{AXES * CYCLES / t['disk'].median / 1e6:.0f} M axis-cycles/s ({t['disk'].text(1e3, 'ms', '.0f')})",
        f"in memory {AXES * CYCLES / t['memory'].median / 1e6:.0f} M/s ({t['memory'].text(1e3, 'ms', '.0f')})",
        rate,
        ">= 0.5x",
        rate >= 0.5,
    )


def benchmarks(tmp) -> None:
    table = segment_table()
    for label, names in SETS.items():
        one_set(tmp, table, label, list(names))
