# SPDX-License-Identifier: BSD-2-Clause
"""The engine and doStep. Part of ./dev bench (bench/run.py).

1a/1b  bench/engine.c: the chip core running random, never repeating external profiles on 4 axes,
       every cycle's row stored, against a bare C loop of the same exact recurrence storing the same
       rows; the baseline is the fastest of the bare loop's floor divisions in the same run.
2a/2b  bench/dostep.c: one doStep of 10^6 cycles through the FMU's FMI 3 binary, not recorded
       against recorded (record.data), over short and over long segments.
2c     a coarse doStep: 100 segments x 10^7 cycles, against cycle by cycle.
The C programs take the contenders in turns within each run (A B A B ...) and print every run's
time; here they become min / median / max (common.Spread), the ratio of medians, the machine's load
beside them; 2c alternates its two contenders run by run (common.interleave).
"""

from __future__ import annotations

import random
import subprocess
import zipfile
from pathlib import Path

from fmpy import read_model_description

import pmdfmu
from common import RUNS, Spread, build, interleave, load, report, timed

AXES = 4
FAMILIES = {"short": (1, 7), "long": (1000, 2000)}  # segment times, cycles
DOSTEP_CYCLES = 10**6
CYCLES_ENGINE = 1_000_000  # bench/engine.c's CYCLES


def figures(lines, key_fields: int) -> dict:
    """'KEY... SECONDS' lines, a line per run and contender -> {key: Spread} (least, median, greatest)."""
    times = {}
    for line in lines:
        *key, seconds = line.split()
        times.setdefault(" ".join(key[:key_fields]), []).append(float(seconds))
    return {k: Spread.of(v) for k, v in times.items()}


def engine(tree: Path) -> None:
    out = subprocess.run([str(tree / "bench_engine"), str(RUNS)], capture_output=True, text=True, check=True).stdout
    fig = figures(out.splitlines(), 2)
    per = CYCLES_ENGINE * AXES
    for label, family in (("1a", "short"), ("1b", "long")):
        core = fig[f"{family} engine"].per(per)
        name, bare = min(
            ((k.split()[1], f.per(per)) for k, f in fig.items() if k.startswith(f"{family} bare")),
            key=lambda x: x[1].median,
        )
        lo, hi = FAMILIES[family]
        ratio = core.median / bare.median
        report(
            f"{label} engine, {lo}-{hi}-cycle random segments, 4 axes, every cycle stored ({load()})",
            core.text(1e9, "ns/axis-cycle"),
            f"bare C loop ({name}) {bare.text(1e9, 'ns')}",
            ratio,
            "<= 1.3x",
            ratio <= 1.3,
        )


def tables(tmp: Path, family: str) -> tuple:
    """A script loading random segment tables (raw words, never repeating within the run) on the four
    axes and starting them; returns (script, memory words)."""
    lo, hi = FAMILIES[family]
    rng = random.Random(16)
    d = tmp / family
    d.mkdir(exist_ok=True)
    lines, address = ["@ 0"], 0
    for axis in range(1, AXES + 1):
        rows, cycles = [], 0
        while cycles <= DOSTEP_CYCLES + 10:
            t = rng.randint(lo, hi)
            rows.append(
                f"{rng.randrange(-(2**31), 2**31)},{rng.randrange(-(2**23), 2**23)},"
                f"{rng.randrange(-(2**11), 2**11)},{rng.randrange(-(2**19), 2**19)},{t}"
            )
            cycles += t
        (d / f"axis{axis}.csv").write_text(
            "# units: raw\nposition,velocity,acceleration,jerk,time\n" + "\n".join(rows) + "\n"
        )
        lines += [
            f'LoadSegmentTable(Axis{axis}, "axis{axis}.csv", {address}, {2 + 5 * (axis - 1)});',
            f"SetProfileMode(Axis{axis}, PMDExternalProfile);",
            f"Update(Axis{axis});",
        ]
        address += 5 * len(rows)
    script = d / "profile.script"
    script.write_text("\n".join(lines) + "\n")
    return script, address


def dostep(tmp: Path, tree: Path) -> None:
    fmu = pmdfmu.default_fmu(3)
    with zipfile.ZipFile(fmu) as z:
        binary = Path(z.extract("binaries/x86_64-linux/PMDMotionProcessor.so", tmp / "fmi3"))
    token = read_model_description(str(fmu)).guid
    for label, family in (("2a", "short"), ("2b", "long")):
        script, words = tables(tmp, family)
        out = subprocess.run(
            [str(tree / "bench_dostep"), str(binary), token, str(script), str(words), str(DOSTEP_CYCLES), str(RUNS)],
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        fig = figures(out.splitlines(), 1)
        plain, recorded = fig["unrecorded"].per(DOSTEP_CYCLES), fig["recorded"].per(DOSTEP_CYCLES)
        lo, hi = FAMILIES[family]
        ratio = plain.median / recorded.median
        report(
            f"{label} doStep of 10^6 cycles, {lo}-{hi}-cycle segments, not recorded ({load()})",
            plain.text(1e9, "ns/cycle"),
            f"recorded (record.data) {recorded.text(1e9, 'ns')}",
            ratio,
            "<= 1.0x",
            ratio <= 1.0,
        )


def coarse() -> None:
    """One doStep of 10^9 cycles over a 100-segment table: fast-forward, O(segments)."""
    from pmdfmu.profile import load_external_profile, start_external_profile

    segments = [(1000 * i, 0x10000, 0x10, 0x100, 10_000_000) for i in range(100)] + [(0, 0, 0, 0, 0)]

    def run(cycles, block_fast_forward):
        with pmdfmu.Chip() as chip:
            load_external_profile(chip, {0: segments})
            start_external_profile(chip, [0])
            if block_fast_forward:  # an armed breakpoint needs every cycle
                chip.axis(1).SetBreakpointValue(0, 2**31 - 1)
                chip.axis(1).SetBreakpoint(0, 1, 0, pmdfmu.PMDBreakpointTime)
            return timed(lambda: chip.run(cycles))

    t = interleave({"fast": lambda: run(10**9, False), "slow": lambda: run(1_000_000, True)})
    fast, slow = t["fast"], t["slow"].per(1_000_000)
    extrapolated = slow.median * 1e9
    report(
        f"2c coarse doStep, 100 segments x 10^7 cycles (ratio: speed-up; {load()})",
        fast.text(1e3, "ms"),
        f"cycle by cycle {slow.min * 1e9:.0f} / {extrapolated:.0f} / {slow.max * 1e9:.0f} s (extrapolated)",
        extrapolated / fast.median,
        "< 10 ms",
        fast.median < 0.010,
    )


def benchmarks(tmp: Path) -> None:
    tree = build("bench_engine", "bench_dostep")
    engine(tree)
    dostep(tmp, tree)
    coarse()
