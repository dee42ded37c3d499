# SPDX-License-Identifier: BSD-2-Clause
"""Upload: 100 000 segments (5 words each: position,
velocity, acceleration, jerk, time) into the chip's memory, through the script
loader and through the memory port. Part of ./dev bench.

- Script loader: the table file exists (a user has it); timed is all that
  loading costs through the FMU: pmdfmu.Chip(memorySize=..., script=...) (the
  script's LoadSegmentTable is compiled at exitInitialization: the file read
  and parsed) and run(1) (the table's words written into memory before cycle
  0). Baseline: numpy.loadtxt reading the same CSV into int64 (numpy's C
  parser: the fastest honest way this machine has to turn the same text into
  the same numbers; pandas is not installed).
- Memory port: chip.write_memory of the 5 columns (C strobes through the FMU's
  own FMI functions). Baseline: the same writes by the harness's Python loop
  (tests/stepwise.py's write_memory_stepwise: what write_memory did before; the ratio is the
  speed-up)."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

import pmdfmu
from common import REPO, interleave, load, report, timed

sys.path.insert(0, str(REPO / "tests"))
from stepwise import write_memory_stepwise  # noqa: E402  (the tests' oracle, the baseline here)

SEGMENTS = 100_000
TARGET = 2e6  # segments/s, each path
HEADER = "position,velocity,acceleration,jerk,time"


def table(seed: int = 5) -> np.ndarray:
    """Random segments: 32-bit position and velocity, small acceleration and jerk, 1-7-cycle times."""
    rng = np.random.default_rng(seed)
    return np.stack(
        [
            rng.integers(-(2**31), 2**31, SEGMENTS),
            rng.integers(-(2**31), 2**31, SEGMENTS),
            rng.integers(-(2**20), 2**20, SEGMENTS),
            rng.integers(-(2**20), 2**20, SEGMENTS),
            rng.integers(1, 8, SEGMENTS),
        ],
        axis=1,
    )


def script_loader(tmp: Path, rows: np.ndarray, version: int) -> None:
    csv, script = tmp / "segments.csv", tmp / "upload.script"
    with open(csv, "w") as f:
        f.write(HEADER + "\n")
        f.writelines(f"{p},{v},{a},{j},{t}\n" for p, v, a, j, t in rows.tolist())
    script.write_text('@ 0\nLoadSegmentTable(Axis1, "segments.csv", 0, 2)\n')
    size = 5 * SEGMENTS

    def loader() -> float:
        start = time.perf_counter()
        with pmdfmu.Chip(version, memorySize=size, script=script) as chip:
            chip.run(1)
            took = time.perf_counter() - start
            if chip.axis(0).GetBufferLength(2) != SEGMENTS:
                raise AssertionError("the table was not loaded")
        return took

    pmdfmu.Chip(version).close()  # the FMU file's first Chip (its unzip) is not the upload's
    t = interleave(
        {"loader": loader, "numpy": lambda: timed(lambda: np.loadtxt(csv, delimiter=",", skiprows=1, dtype=np.int64))}
    )
    ours, numpy = t["loader"].rate(SEGMENTS), t["numpy"].rate(SEGMENTS)
    report(
        f"upload {SEGMENTS} segments, script loader (LoadSegmentTable), FMI {version} ({load()})",
        ours.text(1e-6, "M segments/s"),
        f"numpy.loadtxt of the same CSV {numpy.text(1e-6, 'M/s')}",
        ours.median / numpy.median,
        f">= {TARGET / 1e6:g} M/s; ratio loader / numpy",
        ours.median >= TARGET,
    )


def memory_port(rows: np.ndarray, version: int) -> None:
    columns = [np.ascontiguousarray(rows[:, f]) for f in range(5)]
    with pmdfmu.Chip(version, memorySize=5 * SEGMENTS) as chip:

        def upload(write) -> float:
            return timed(lambda: [write(f * SEGMENTS, columns[f]) for f in range(5)])

        t = interleave(
            {
                "native": lambda: upload(chip.write_memory),
                "python": lambda: upload(lambda a, w: write_memory_stepwise(chip, a, w)),
            }
        )
    ours, python = t["native"].rate(SEGMENTS), t["python"].rate(SEGMENTS)
    report(
        f"upload {SEGMENTS} segments, memory port (write_memory), FMI {version} ({load()})",
        ours.text(1e-6, "M segments/s"),
        f"the Python strobe loop {python.text(1e-6, 'M/s')}",
        ours.median / python.median,
        f">= {TARGET / 1e6:g} M/s; ratio native / Python",
        ours.median >= TARGET,
    )


def benchmarks(tmp: Path) -> None:
    rows = table()
    for version in (2, 3):
        script_loader(tmp, rows, version)
        memory_port(rows, version)
