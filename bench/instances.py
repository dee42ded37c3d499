# SPDX-License-Identifier: BSD-2-Clause
"""Instances: pmdfmu.Chip() after the first of an FMU file, against the
first Chip of a file (what every Chip() cost before: extract the FMU, read its model
description, declare FMPy's FMI prototypes, instantiate, initialize), interleaved run by run.
Part of ./dev bench."""

from __future__ import annotations

import shutil
import time
from pathlib import Path

import pmdfmu
from common import interleave, load, report, timed

LATER = 50  # instances made per timed run of the later Chip()
TARGET = 2e-3  # s: a later Chip()


def folders(chip: pmdfmu.Chip) -> int:
    """The FMU folders extracted in this process so far (the cache's root holds one per file)."""
    return sum(1 for _ in Path(chip._unzipdir).parent.iterdir())


def one_version(tmp: Path, fmi_version: int) -> None:
    source = pmdfmu.default_fmu(fmi_version)
    copies = iter(range(10**6))

    def first() -> float:
        """The first Chip of an FMU file: a copy written for this run, never seen by the process."""
        path = Path(shutil.copy(source, tmp / f"first-{fmi_version}-{next(copies)}.fmu"))
        start = time.perf_counter()
        chip = pmdfmu.Chip(fmi_version, path)
        took = time.perf_counter() - start
        chip.close()
        return took

    path = Path(shutil.copy(source, tmp / f"later-{fmi_version}.fmu"))
    keeper = pmdfmu.Chip(fmi_version, path)  # the file's first instance
    chips = []
    new_folders = 0

    def later() -> float:
        nonlocal new_folders
        before = folders(keeper)
        took = timed(lambda: chips.extend(pmdfmu.Chip(fmi_version, path) for _ in range(LATER)))
        new_folders += folders(keeper) - before
        for chip in chips:
            chip.close()
        chips.clear()
        return took

    t = interleave({"first": first, "later": later})
    fresh, ours = t["first"], t["later"].per(LATER)
    keeper.close()
    report(
        f"Chip() after the first of an FMU file, FMI {fmi_version} ({load()})",
        ours.text(1e3, "ms", ".3f"),
        f"first Chip of the file {fresh.text(1e3, 'ms')}",
        fresh.median / ours.median,
        f"<= {TARGET * 1e3:g} ms, no new unzip ({new_folders} made); ratio first / later",
        ours.median <= TARGET and new_folders == 0,
    )


def benchmarks(tmp: Path) -> None:
    for version in (2, 3):
        one_version(tmp, version)
