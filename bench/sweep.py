# SPDX-License-Identifier: BSD-2-Clause
"""Sweeps: the per-case overhead of a sweep, on a running 2-worker local
cluster (its client reused, workers warm) and in this process, with cases that do next to
nothing; and the speed-up of 8 cases of at least 0.2 s each on that cluster over the same cases
run serially in this process. Part of ./dev bench."""

from __future__ import annotations

import logging
import time
from pathlib import Path

import pmdfmu
from common import interleave, load, report, timed
from pmdfmu.profile import record_outputs
from pmdfmu.sweep import Case

EMPTY = 64  # cases per timed sweep of empty cases
HEAVY = 8  # cases of the speed-up
HEAVY_SECONDS = 0.25  # each heavy case's serial time, at least (the target asks >= 0.2 s)
OVERHEAD = 2e-3  # s per case
SPEED_UP = 1.8  # on 2 workers


def long_move(path: Path, cycles: int) -> Path:
    """A script that keeps axis 1 in a trapezoidal move for `cycles` cycles, then stops it."""
    path.write_text(
        "@ 0\nSetProfileMode(Axis1, PMDTrapezoidalProfile);\nSetPosition(Axis1, 2000000000);\n"
        "SetVelocity(Axis1, 0x10000);\nSetAcceleration(Axis1, 0x100);\nUpdate(Axis1);\n"
        f"@ {cycles}\nSetStopMode(Axis1, PMDAbruptStop);\nUpdate(Axis1);\n"
    )
    return path


def heavy_cases(tmp: Path, fmu: str):
    """HEAVY cases of one script long enough for HEAVY_SECONDS each, run serially here."""
    cycles = 200_000
    for _ in range(20):
        case = Case(
            "probe", script=str(long_move(tmp / f"long{cycles}.script", cycles)), fmu=fmu, max_cycles=2 * cycles
        )
        result = pmdfmu.sweep([case], scheduler="serial")
        if result.rows[0]["status"] != "ok" or result.rows[0]["cycles"] < cycles:
            raise RuntimeError(f"the speed-up's case fails: {result.rows[0]}")
        took = min(timed(lambda case=case: pmdfmu.sweep([case], scheduler="serial")) for _ in range(2))
        if took >= HEAVY_SECONDS:
            return [
                Case(f"long{k}", script=case.script, fmu=fmu, max_cycles=case.max_cycles) for k in range(HEAVY)
            ], took
        cycles = int(cycles * max(1.2, 1.1 * HEAVY_SECONDS / took))
    raise RuntimeError(f"no case of {cycles} cycles takes {HEAVY_SECONDS} s")


def benchmarks(tmp: Path) -> None:
    from dask.distributed import Client, LocalCluster

    fmu = str(pmdfmu.default_fmu(2))
    # an empty script: the case records its shortest run, one chunk of 1000 cycles of axis 1
    (tmp / "empty.script").write_text("")
    empty = [Case(f"empty{k}", script=str(tmp / "empty.script"), fmu=fmu) for k in range(EMPTY)]
    heavy, case_seconds = heavy_cases(tmp, fmu)

    pmdfmu.sweep(empty[:2], scheduler="serial")  # this process's instance made
    names = record_outputs([0])
    with (
        pmdfmu.Chip(fmu=fmu) as chip,  # what an empty case runs, bare
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None, silence_logs=logging.ERROR
        ) as cluster,
        Client(cluster) as client,
    ):
        start = time.perf_counter()
        pmdfmu.sweep(heavy[:2], scheduler=client)  # warm-up: each worker's first FMU instance
        warm_up = time.perf_counter() - start
        # the contenders take turns: a change of the machine's load touches them alike
        t = interleave(
            {
                "bare": lambda: timed(lambda: chip.run(1000, record=names)),
                "serial": lambda: timed(lambda: pmdfmu.sweep(empty, scheduler="serial")),
                "cluster": lambda: timed(lambda: pmdfmu.sweep(empty, scheduler=client)),
            }
        )
        bare, serial_empty, cluster_empty = t["bare"], t["serial"].per(EMPTY), t["cluster"].per(EMPTY)
        t = interleave(
            {
                "serial": lambda: timed(lambda: pmdfmu.sweep(heavy, scheduler="serial")),
                "cluster": lambda: timed(lambda: pmdfmu.sweep(heavy, scheduler=client)),
            }
        )
        serial_heavy, cluster_heavy = t["serial"], t["cluster"]

    report(
        f"sweep per-case overhead, 2-worker cluster (client reused), empty cases ({load()})",
        cluster_empty.text(1e3, "ms", ".3f"),
        f"serial here {serial_empty.text(1e3, 'ms', '.3f')}",
        cluster_empty.median / serial_empty.median,
        f"<= {OVERHEAD * 1e3:g} ms per case",
        cluster_empty.median <= OVERHEAD,
    )
    report(
        f"sweep per-case overhead, serial, empty cases (1000 recorded cycles each; {load()})",
        serial_empty.text(1e3, "ms", ".3f"),
        f"bare chip.run(1000) {bare.text(1e3, 'ms', '.3f')}",
        serial_empty.median / bare.median,
        f"<= {OVERHEAD * 1e3:g} ms per case",
        serial_empty.median <= OVERHEAD,
    )
    report(
        f"sweep of {HEAVY} cases of {case_seconds:.2f} s, 2-worker cluster (client reused, "
        f"warm-up {warm_up:.2f} s once; {load()})",
        cluster_heavy.text(1, "s"),
        f"serial here {serial_heavy.text(1, 's')}",
        serial_heavy.median / cluster_heavy.median,
        f">= {SPEED_UP}x (ratio serial / cluster)",
        serial_heavy.median / cluster_heavy.median >= SPEED_UP,
    )
