# SPDX-License-Identifier: BSD-2-Clause
"""What every benchmark module shares: contenders run in turns, figures as
min / median / max, a report table. Benchmarks, not tests: nothing asserts a time.

A benchmark module (bench/<topic>.py) defines benchmarks(tmp: Path) -> None,
which measures and calls report(); bench/run.py runs them all."""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, List, Tuple

REPO = Path(__file__).resolve().parent.parent
BUILD = Path(os.environ.get("PMDFMU_FMU_DIR") or REPO / "build")
RUNS = 5  # every figure: min, median and max of at least this many runs

rows: List[Tuple[str, ...]] = []


def build(*targets: str) -> Path:
    """The bench's C programs (CMake targets), built with the FMUs' own settings (Release, link-time
    optimization) in one build dir under the FMU's, beside the FMUs built there; the dir."""
    tree = BUILD / "bench" / "programs"
    configure = ["cmake", "-S", str(REPO), "-B", str(tree), "-DCMAKE_BUILD_TYPE=Release"]
    subprocess.run(configure + [f"-DPython3_EXECUTABLE={sys.executable}"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(tree), "--target", *targets], check=True, stdout=subprocess.DEVNULL)
    return tree


def timed(f: Callable[[], object]) -> float:
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def report(name: str, figure: str, baseline: str, ratio: float, target: str, met: bool) -> None:
    """One row of the table; ratio from medians (figure / baseline unless the row says otherwise)."""
    rows.append((name, figure, baseline, f"{ratio:.2f}", target, "yes" if met else "NO"))


@dataclass(frozen=True)
class Spread:
    """A time measured in interleaved runs (A B A B ...): least, median, greatest."""

    min: float
    median: float
    max: float

    def text(self, scale: float, unit: str, fmt: str = ".2f") -> str:
        return f"{self.min * scale:{fmt}} / {self.median * scale:{fmt}} / {self.max * scale:{fmt}} {unit}"

    @staticmethod
    def of(values) -> "Spread":
        """The least, the median and the greatest of measured values."""
        return Spread(min(values), statistics.median(values), max(values))

    def per(self, n: float) -> "Spread":
        """time per item"""
        return Spread(self.min / n, self.median / n, self.max / n)

    def rate(self, n: float) -> "Spread":
        """n items over the time: items per second, least (the slowest run) to greatest"""
        return Spread(n / self.max, n / self.median, n / self.min)


def interleave(contenders, runs: int = RUNS):
    """Each contender (a callable returning a time in s) run `runs` times, taking turns A B A B ..., so that
    the machine's load falls on all alike: {name: Spread}."""
    times = {name: [] for name in contenders}
    for _ in range(runs):
        for name, f in contenders.items():
            times[name].append(f())
    return {n: Spread.of(t) for n, t in times.items()}


def load() -> str:
    """The machine's load (os.getloadavg), printed beside the figures it affects."""
    import os

    return "load %.1f %.1f %.1f" % os.getloadavg()
