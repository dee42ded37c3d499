# SPDX-License-Identifier: BSD-2-Clause
"""Recording: Chip.run(cycles, record=names) on a real profile, 4 axes moving,
in FMI 2 and FMI 3, (a) the 12 commanded outputs, (b) 7 columns per axis with the Reals and the
activity status (pmdfmu.profile.record_outputs). Figures: M axis-cycles/s (4 axes x cycles / time),
target >= 20 M; and the ratio to fmpy.simulate_fmu recording the same outputs of the same instance,
one output per cycle (stop_time = cycles x cycleTime, step_size = output_interval = cycleTime), at
20 000 and 10^6 cycles, for scale (no longer a target: docs/performance.md, "Against simulate_fmu").

Against a bare C loop writing the same rows (bench/recording_loop.c: the chip core run every cycle,
each row written in the result's packed layout, nothing else), both column sets, 20 000 and 10^6
cycles, FMI 2 and FMI 3, the four contenders taking turns: run(out=) into a result a former run
filled against the loop into a buffer it filled before, target <= 1.5x; run() into a fresh result
against the loop into a fresh malloc'd buffer (freed in the timed span, as the dropped result is),
target <= 3x. The loop's rows are checked to be run()'s bytes first.

simulate_fmu's fastest honest form is the baseline: the FMU already extracted, no validation, the
prepared instance handed over (fmu_instance, initialize=False), so that it runs the same profile
and nothing but its loop is timed."""

from __future__ import annotations

import random
import subprocess
from pathlib import Path

import fmpy
import numpy as np

import common
import pmdfmu
from pmdfmu import recording
from pmdfmu.chip import RECORDED
from pmdfmu.profile import load_external_profile, record_outputs, start_external_profile

AXES = 4
SETS = {"12 commanded": RECORDED, "status + Reals (7/axis)": record_outputs(range(AXES))}
# each set's name in bench/recording_loop.c
LOOP_SETS = {"12 commanded": "commanded", "status + Reals (7/axis)": "status"}
CYCLES = (20_000, 1_000_000)
# simulate_fmu at 10^6 cycles takes 6-18 s a run (4 of them): 3 runs there keep the module under ~3 min; its
# spread is a few %, far below the ratio's distance from the target. Every other figure: common.RUNS.
SIMULATE_RUNS = {1_000_000: 3}


def segment_table(seed: int = 16, rows: int = 200):
    """Random segments of 100-3000 cycles with jerk on every axis (the table repeats after ~300 000 cycles)."""
    rng = random.Random(seed)
    return {
        axis: [
            (
                rng.randrange(-(10**6), 10**6),
                rng.randrange(-5 << 16, 5 << 16),
                rng.randrange(-1 << 12, 1 << 12),
                rng.randrange(-1 << 20, 1 << 20),
                rng.randrange(100, 3000),
            )
            for _ in range(rows)
        ]
        for axis in range(AXES)
    }


def prepared(version: int, table) -> pmdfmu.Chip:
    """A chip at time 0 with the table loaded and every axis started (no cycle run yet)."""
    chip = pmdfmu.Chip(fmi_version=version)
    load_external_profile(chip, table)
    start_external_profile(chip, range(AXES))
    return chip


def simulate(chip: pmdfmu.Chip, names, cycles: int):
    ct = chip.cycle_time
    return fmpy.simulate_fmu(
        chip._unzipdir,
        validate=False,
        fmi_type="CoSimulation",
        fmu_instance=chip.fmu,
        initialize=False,
        terminate=False,
        start_time=0.0,
        stop_time=cycles * ct,
        step_size=ct,
        output_interval=ct,
        output=list(names),
    )


def measure(version: int, table, action):
    """A run of action(chip), timed on a fresh prepared chip (for common.interleave)."""

    def once():
        with prepared(version, table) as chip:
            return common.timed(lambda: action(chip))

    return once


def benchmarks(tmp: Path) -> None:
    table = segment_table()
    for version in (2, 3):
        for label, names in SETS.items():
            # the same rows as simulate_fmu's (its first row is time 0, before any cycle)
            with prepared(version, table) as a, prepared(version, table) as b:
                ours, theirs = a.run(2000, record=names), simulate(b, names, 2000)
                assert len(theirs) == 2001 and all((ours[n] == theirs[n][1:]).all() for n in names)
            for cycles in CYCLES:
                sim_runs = SIMULATE_RUNS.get(cycles, common.RUNS)
                t = common.interleave(
                    {
                        "run": measure(
                            version, table, lambda chip, cycles=cycles, names=names: chip.run(cycles, record=names)
                        ),
                        "sim": measure(
                            version, table, lambda chip, cycles=cycles, names=names: simulate(chip, names, cycles)
                        ),
                    },
                    sim_runs,
                )
                run, sim = t["run"], t["sim"]
                axis_cycles = AXES * cycles
                name = f"chip.run(record) FMI {version}, {label}, {cycles:,} cycles ({common.load()})"
                common.report(
                    name + ": rate",
                    run.rate(axis_cycles).text(1e-6, "M axis-cycles/s", ".1f"),
                    "-",
                    axis_cycles / run.median / 1e6 / 20,
                    ">= 20 M axis-cycles/s (ratio: /20 M)",
                    axis_cycles / run.median >= 20e6,
                )
                ratio = sim.median / run.median
                common.report(
                    name + ": vs simulate_fmu",
                    run.text(1e3, "ms"),
                    f"simulate_fmu {sim.text(1e3, 'ms', '.0f')}"
                    + (f" ({sim_runs} pairs)" if sim_runs != common.RUNS else ""),
                    ratio,
                    "report: for scale (was >= 200x; docs/performance.md)",
                    True,
                )
    lending(table)
    against_bare_loop(tmp, table)


def lending(table) -> None:
    """Lent rows (pmdfmu_fmi2SetRecordBuffer, pmdfmu_fmi3SetRecordBuffer: the FMU writes the result in place)
    against the copy of record.data into the result that an FMU without them gets (recording.lent_stepper
    made to give None), interleaved run by run, status + Reals, FMI 2 and FMI 3: what the extension buys,
    per recorded row."""
    names = SETS["status + Reals (7/axis)"]
    real = recording.lent_stepper
    for version in (2, 3):
        for cycles in CYCLES:
            lent, copied = [], []
            for _ in range(common.RUNS):
                for times, stepper in ((lent, real), (copied, lambda chip: None)):
                    recording.lent_stepper = stepper
                    try:
                        with prepared(version, table) as chip:
                            times.append(common.timed(lambda chip=chip, cycles=cycles: chip.run(cycles, record=names)))
                    finally:
                        recording.lent_stepper = real
            lent_f, copied_f = common.Spread.of(lent), common.Spread.of(copied)
            saved = (copied_f.median - lent_f.median) / lent_f.median
            common.report(
                f"lent vs copied rows, FMI {version}, status + Reals, {cycles:,} cycles ({common.load()})",
                lent_f.per(cycles).text(1e9, "ns/row"),
                f"copied {copied_f.per(cycles).text(1e9, 'ns/row')}",
                copied_f.median / lent_f.median,
                f"report (the copy costs {saved:.0%} of a lent row: the extension stays if > 10 %)",
                True,
            )


class BareLoop:
    """bench/recording_loop.c, built by CMake with the FMUs' settings (Release, link-time optimization), running
    as a child process that takes one command a line: its own clock times each run, so that no pipe is timed."""

    def __init__(self, tmp: Path, table):
        target = "bench_recording_loop"
        tree = common.build(target)
        rows = len(table[0])
        text = [str(rows)] + [" ".join(str(v) for v in row) for axis in range(AXES) for row in table[axis]]
        path = tmp / "segments.txt"
        path.write_text("\n".join(text) + "\n")
        self.tmp = tmp
        self.process = subprocess.Popen(
            [str(tree / target), str(path)], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
        )

    def _ask(self, line: str) -> str:
        self.process.stdin.write(line + "\n")
        self.process.stdin.flush()
        answer = self.process.stdout.readline()
        if not answer:
            raise RuntimeError(f"bench_recording_loop stopped at {line!r} (exit {self.process.wait()})")
        return answer.strip()

    def run(self, label: str, cycles: int, result: str) -> float:
        """One run's seconds: result "reused" (a buffer a former run filled) or "fresh" (malloc'd, freed)."""
        return float(self._ask(f"run {LOOP_SETS[label]} {cycles} {result}"))

    def rows(self, label: str, cycles: int) -> np.ndarray:
        """The loop's rows of `cycles` cycles from the start, as bytes."""
        path = self.tmp / "rows.bin"
        self._ask(f"dump {LOOP_SETS[label]} {cycles} {path}")
        try:
            return np.fromfile(path, dtype=np.uint8)
        finally:
            path.unlink()

    def close(self) -> None:
        self.process.stdin.close()
        self.process.wait()


def against_bare_loop(tmp: Path, table) -> None:
    loop = BareLoop(tmp, table)
    try:
        for label, names in SETS.items():
            for cycles in CYCLES:
                expected = loop.rows(label, cycles)
                for version in (2, 3):
                    with prepared(version, table) as chip:
                        out = chip.run(cycles, record=names)
                    # "the same rows": the same values in the same layout, byte for byte, before anything is timed
                    if out.dtype.itemsize * cycles != expected.size or not np.array_equal(
                        out.view(np.uint8).reshape(-1), expected
                    ):
                        raise AssertionError(f"bench_recording_loop's {label} rows are not run()'s (FMI {version})")
                    t = common.interleave(
                        {
                            "reused": measure(
                                version,
                                table,
                                lambda chip, cycles=cycles, names=names, out=out: chip.run(
                                    cycles, record=names, out=out
                                ),
                            ),
                            "loop reused": lambda label=label, cycles=cycles: loop.run(label, cycles, "reused"),
                            "fresh": measure(
                                version, table, lambda chip, cycles=cycles, names=names: chip.run(cycles, record=names)
                            ),
                            "loop fresh": lambda label=label, cycles=cycles: loop.run(label, cycles, "fresh"),
                        }
                    )
                    name = f"run() vs bare C loop, FMI {version}, {label}, {cycles:,} cycles ({common.load()})"
                    for result, target in (("reused", 1.5), ("fresh", 3.0)):
                        ours, bare = t[result], t[f"loop {result}"]
                        ratio = ours.median / bare.median
                        common.report(
                            f"{name}: {'run(out=) reused' if result == 'reused' else 'run() fresh'} result",
                            ours.per(cycles).text(1e9, "ns/row"),
                            f"bare C loop, {result} buffer {bare.per(cycles).text(1e9, 'ns/row')}",
                            ratio,
                            f"<= {target}x",
                            ratio <= target,
                        )
                del expected
    finally:
        loop.close()
