#!/usr/bin/env python3
"""The performance suite (issue 5): every figure next to a baseline measured
in the same run, as a table. Benchmarks, not tests: nothing here asserts a time.

    python bench/run.py          (./dev bench)
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

import numpy as np
from fmpy import read_model_description

import pmdfmu
from pmdfmu.profile import load_external_profile, start_external_profile

REPO = Path(__file__).resolve().parent.parent
BUILD = REPO / "build"
FMI_HEADERS = Path(__import__("fmpy").__file__).parent / "c-code"
rows = []


def report(name: str, figure: str, baseline: str, ratio: float, target: str, met: bool) -> None:
    rows.append((name, figure, baseline, f"{ratio:.2f}", target, "yes" if met else "NO"))


def best_of(n, f):
    return min(f() for _ in range(n))


def timed(f):
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


# 1. the engine against a plain C loop of the same recurrence
def engine(tmp: Path) -> None:
    """bench/engine.c, built by CMake with the FMUs' own settings (Release, link-time optimization)."""
    build = BUILD / "bench" / "cmake"
    subprocess.run(["cmake", "-S", str(REPO), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                    f"-DPython3_EXECUTABLE={sys.executable}"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", str(build), "--target", "bench_engine"], check=True,
                   stdout=subprocess.DEVNULL)
    exe = build / "bench_engine"
    plain, tuned, core = map(float, subprocess.run([str(exe)], capture_output=True, text=True,
                                                    check=True).stdout.split())
    report("1 engine, 4 axes x 5 buffers, every cycle stored", f"{core:.1f} ns/axis-cycle",
           f"plain C loop {plain:.1f} ns", core / plain, "<= 1.5x", core / plain <= 1.5)
    # the same plain loop given the engine's floor division: what the engine's bookkeeping costs
    report("1b engine over the arithmetic alone", f"{core:.1f} ns/axis-cycle",
           f"plain C loop, engine's division {tuned:.1f} ns", core / tuned, "report", True)


def load_table(chip, segments):
    """Axis 1 runs the table (seed 000's set-up, through the library)."""
    load_external_profile(chip, {0: segments})
    start_external_profile(chip, [0])


# 2. a 100-segment table across 10^9 cycles in one doStep, against cycle by cycle
def coarse() -> None:
    segments = [(1000 * i, 0x10000, 0x10, 0x100, 10_000_000) for i in range(100)] + [(0, 0, 0, 0, 0)]

    def run(cycles, block_fast_forward):
        with pmdfmu.Chip() as chip:
            load_table(chip, segments)
            if block_fast_forward:          # an armed breakpoint needs every cycle
                chip.axis(1).SetBreakpointValue(0, 2 ** 31 - 1)
                chip.axis(1).SetBreakpoint(0, 1, 0, pmdfmu.PMDBreakpointTime)
            return timed(lambda: chip.run(cycles))

    fast = best_of(3, lambda: run(10 ** 9, False))
    slow_per_cycle = run(2_000_000, True) / 2_000_000
    report("2 coarse doStep, 100 segments x 10^7 cycles", f"{1e3 * fast:.2f} ms",
           f"cycle by cycle {slow_per_cycle * 1e9:.0f} s (extrapolated)", slow_per_cycle * 1e9 / fast,
           "< 10 ms", fast < 0.010)


def trivial_fmu(tmp: Path) -> Path:
    """The same modelDescription.xml over a do-nothing binary."""
    d = tmp / "trivial"
    (d / "binaries" / "linux64").mkdir(parents=True)
    subprocess.run(["cc", "-O2", "-shared", "-fPIC", "-std=c99", f"-I{FMI_HEADERS}", str(REPO / "bench" / "trivial.c"),
                    "-o", str(d / "binaries" / "linux64" / "PMDMotionProcessor.so")], check=True)
    with zipfile.ZipFile(pmdfmu.default_fmu(2)) as z:
        (d / "modelDescription.xml").write_bytes(z.read("modelDescription.xml"))
    fmu = tmp / "trivial.fmu"
    shutil.make_archive(str(fmu.with_suffix("")), "zip", d)
    fmu.with_suffix(".zip").rename(fmu)
    return fmu


# 3. per-step overhead through FMPy: set the host inputs, doStep one cycle, get 12 outputs
def per_step(tmp: Path) -> None:
    steps = 20_000

    def loop(path):
        with pmdfmu.Chip(fmu=path) as chip:
            vr = chip.variables
            inputs = [vr[n].valueReference for n in ("host.wordCount", "host.strobe", "memory.strobe")]
            outputs = [vr[f"axis{n}.{q}"].valueReference for n in range(1, 5)
                       for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration")]
            fmu, dt, done = chip.fmu, chip.cycle_time, [0]

            def run():
                for k in range(done[0], done[0] + steps):
                    fmu.setInteger(inputs, [0, 0, 0])
                    fmu.doStep(k * dt, dt)
                    fmu.getInteger(outputs)
                done[0] += steps
            return best_of(3, lambda: timed(run)) / steps

    ours, baseline = loop(pmdfmu.default_fmu(2)), loop(trivial_fmu(tmp))
    report("3 per step through FMPy (set, doStep, get 12)", f"{ours * 1e6:.1f} us",
           f"trivial FMU {baseline * 1e6:.1f} us", ours / baseline, "<= 1.2x", ours / baseline <= 1.2)


# 4. recording every cycle of 4 axes x 3 outputs
def recording() -> None:
    names = [f"axis{n}.{q}" for n in range(1, 5) for q in ("commandedPosition", "commandedVelocity",
                                                            "commandedAcceleration")]
    cycles = 1_000_000
    with pmdfmu.Chip(fmi_version=3) as chip:           # the bulk path: FMI 3 record.data
        load_table(chip, [(0, 0x10000, 0x10, 0x100, 100)] * 10)
        rate = 4 * cycles / best_of(3, lambda: timed(lambda: chip.run(cycles, record=names)))
    from fmpy import simulate_fmu
    sim_cycles = 5_000
    t = timed(lambda: simulate_fmu(str(pmdfmu.default_fmu(2)), stop_time=sim_cycles * 1e-4, step_size=1e-4,
                                   output_interval=1e-4, output=names))
    baseline = 4 * sim_cycles / t
    report("4 recording 4 axes x 3 outputs per cycle (FMI 3)", f"{rate / 1e6:.2f} M axis-cycles/s",
           f"simulate_fmu {baseline / 1e6:.2f} M/s", rate / baseline, ">= 20 M/s and >= 200x",
           rate >= 20e6 and rate / baseline >= 200)


# 5. loading a 100 000-segment table
def upload(tmp: Path) -> None:
    n = 100_000
    segments = [(i, 0x10000, 0, 0, 1) for i in range(n)]

    def by_memory_port():
        with pmdfmu.Chip(memorySize=600_000) as chip:
            start = time.perf_counter()
            for k in range(5):
                chip.write_memory(k * n, [s[k] for s in segments])
            return time.perf_counter() - start

    def by_script():
        table, script = tmp / "big.csv", tmp / "big.script"
        start = time.perf_counter()
        with open(table, "w") as f:
            f.write("position,velocity,acceleration,jerk,time\n")
            f.writelines(f"{p},{v},{a},{j},{t}\n" for p, v, a, j, t in segments)
        script.write_text('@0\nLoadSegmentTable(Axis1, "big.csv", 0, 2)\n')
        with pmdfmu.Chip(memorySize=600_000, script=script) as chip:
            chip.run(1)
        return time.perf_counter() - start

    port, script = n / by_memory_port(), n / by_script()
    best = max(port, script)
    report("5 upload 100 000 segments", f"{best / 1e6:.2f} M segments/s (script)" if script > port
           else f"{best / 1e6:.2f} M segments/s (memory port)", f"memory port {port / 1e6:.2f} M/s",
           best / port, ">= 1 M/s", best >= 1e6)


# 6. memory per instance, and allocations in doStep, counted from outside the FMU (bench/memory.c)
def memory(tmp: Path) -> None:
    exe = tmp / "memory"
    subprocess.run(["cc", "-O1", "-std=c99", f"-I{FMI_HEADERS}", str(REPO / "bench" / "memory.c"), "-rdynamic",
                    "-ldl", "-o", str(exe)], check=True)
    with zipfile.ZipFile(pmdfmu.default_fmu(2)) as z:
        binary = Path(z.extract("binaries/linux64/PMDMotionProcessor.so", tmp))
    guid = read_model_description(str(pmdfmu.default_fmu(2))).guid
    out = subprocess.run([str(exe), str(binary), guid, str(REPO / "examples" / "two_axis.script")],
                         capture_output=True, text=True, check=True).stdout
    instance, stepping, record, recorded = map(int, out.split())
    words = 0x4000
    report("6 instance memory (memorySize 0x4000)", f"{instance / 1024:.0f} KiB, {stepping + recorded} allocations "
           "in 250 doSteps", f"memorySize x 4 = {4 * words / 1024:.0f} KiB", instance / (4 * words),
           "<= memorySize x 4 + 64 KiB, none in doStep",
           instance <= 4 * words + 64 * 1024 and stepping == 0 and recorded == 0)
    report("6b record.data buffer, once record.enabled", f"{record / 2 ** 20:.1f} MiB",
           "record.capacity 65536 x 52 bytes", record / (65536 * 52), "report", True)


# 7. a sweep on a 2-worker local cluster against the same cases run serially
def sweep_speedup(tmp: Path) -> None:
    script = REPO / "examples" / "two_axis.script"
    cases = [pmdfmu.Case(f"case{k}", script=str(script), parameters=(("cycleTime", 1e-4 * (1 + k % 3)),))
             for k in range(8)]
    serial = timed(lambda: pmdfmu.sweep(cases, scheduler="serial"))
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        pmdfmu.sweep(cases[:2], scheduler=client)                      # workers warm: FMU loaded
        parallel = timed(lambda: pmdfmu.sweep(cases, scheduler=client))
    report("7 sweep, 8 script cases on 2 local workers", f"{parallel:.2f} s", f"serial {serial:.2f} s",
           serial / parallel, "speed-up (2 cores)", serial / parallel > 1.0)


# 8. per-case overhead: cases that do (almost) nothing
def sweep_overhead(tmp: Path) -> None:
    script = tmp / "nothing.script"
    script.write_text("@0\nNoOperation(Axis1)\n")
    cases = [pmdfmu.Case(f"nothing{k}", script=str(script)) for k in range(40)]
    pmdfmu.sweep(cases[:1], scheduler="serial")                          # the instance exists
    serial = timed(lambda: pmdfmu.sweep(cases, scheduler="serial")) / len(cases)
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        pmdfmu.sweep(cases[:2], scheduler=client)
        parallel = timed(lambda: pmdfmu.sweep(cases, scheduler=client)) / len(cases)
    report("8 per-case overhead (empty cases)", f"{parallel * 1e3:.1f} ms on the cluster",
           f"serial {serial * 1e3:.1f} ms", parallel / serial, "report", True)


def main() -> int:
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for bench in (engine, coarse, per_step, recording, upload, memory, sweep_speedup, sweep_overhead):
            try:
                bench(tmp) if bench.__code__.co_argcount else bench()
            except Exception as e:            # one failing benchmark does not hide the others
                rows.append((bench.__name__, f"failed: {e}", "", "", "", "NO"))
    widths = [max(len(str(r[i])) for r in rows + [HEAD]) for i in range(6)]
    for r in [HEAD] + rows:
        print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)))
    return 0


HEAD = ("benchmark", "figure", "baseline (same run)", "ratio", "target", "met")

if __name__ == "__main__":
    sys.exit(main())
