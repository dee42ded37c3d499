# SPDX-License-Identifier: BSD-2-Clause
"""The FMU as any importer sees it: the cost of one FMI step through
FMPy against a do-nothing FMU with the same variables, and the heap an
instance holds. The two FMUs step in turns run by run (A B A B ...): min / median / max, the ratio of
medians, the machine's load beside them. Part of ./dev bench (bench/run.py)."""

from __future__ import annotations

import shutil
import subprocess
import zipfile
from contextlib import ExitStack
from pathlib import Path

from fmpy import read_model_description

import pmdfmu
from common import REPO, interleave, load, report, timed

FMI_HEADERS = Path(__import__("fmpy").__file__).parent / "c-code"


def trivial_fmu(tmp: Path) -> Path:
    """The same modelDescription.xml over a do-nothing binary (bench/trivial.c)."""
    d = tmp / "trivial"
    (d / "binaries" / "linux64").mkdir(parents=True)
    subprocess.run(
        [
            "cc",
            "-O2",
            "-shared",
            "-fPIC",
            "-std=c99",
            f"-I{FMI_HEADERS}",
            str(REPO / "bench" / "trivial.c"),
            "-o",
            str(d / "binaries" / "linux64" / "PMDMotionProcessor.so"),
        ],
        check=True,
    )
    with zipfile.ZipFile(pmdfmu.default_fmu(2)) as z:
        (d / "modelDescription.xml").write_bytes(z.read("modelDescription.xml"))
    fmu = tmp / "trivial.fmu"
    shutil.make_archive(str(fmu.with_suffix("")), "zip", d)
    fmu.with_suffix(".zip").rename(fmu)
    return fmu


def per_step(tmp: Path) -> None:
    """FMPy's own calls, one cycle per step: set the host inputs, doStep, get 12 outputs."""
    steps = 20_000

    def stepper(chip):
        """A run of `steps` steps on the open chip, timed (each run goes on where the last stopped)."""
        vr = chip.variables
        inputs = [vr[n].valueReference for n in ("host.wordCount", "host.strobe", "memory.strobe")]
        outputs = [
            vr[f"axis{n}.{q}"].valueReference
            for n in range(1, 5)
            for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration")
        ]
        fmu, dt, done = chip.fmu, chip.cycle_time, [0]

        def run():
            for k in range(done[0], done[0] + steps):
                fmu.setInteger(inputs, [0, 0, 0])
                fmu.doStep(k * dt, dt)
                fmu.getInteger(outputs)
            done[0] += steps

        return lambda: timed(run)

    with ExitStack() as stack:
        ours = stack.enter_context(pmdfmu.Chip(fmu=pmdfmu.default_fmu(2)))
        trivial = stack.enter_context(pmdfmu.Chip(fmu=trivial_fmu(tmp)))
        t = interleave({"ours": stepper(ours), "trivial": stepper(trivial)})
    ours, baseline = t["ours"].per(steps), t["trivial"].per(steps)
    report(
        f"per step through FMPy (set, doStep, get 12; {load()})",
        ours.text(1e6, "us"),
        f"trivial FMU {baseline.text(1e6, 'us')}",
        ours.median / baseline.median,
        "<= 1.2x",
        ours.median / baseline.median <= 1.2,
    )


def memory(tmp: Path) -> None:
    """bench/memory.c counts, from outside the FMU, its heap and the allocations its doSteps make:
    counts, not times, so one run says it."""
    exe = tmp / "memory"
    subprocess.run(
        [
            "cc",
            "-O1",
            "-std=c99",
            f"-I{FMI_HEADERS}",
            str(REPO / "bench" / "memory.c"),
            "-rdynamic",
            "-ldl",
            "-o",
            str(exe),
        ],
        check=True,
    )
    with zipfile.ZipFile(pmdfmu.default_fmu(2)) as z:
        binary = Path(z.extract("binaries/linux64/PMDMotionProcessor.so", tmp))
    guid = read_model_description(str(pmdfmu.default_fmu(2))).guid
    out = subprocess.run(
        [str(exe), str(binary), guid, str(REPO / "examples" / "two_axis.script")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    instance, stepping, record, recorded = map(int, out.split())
    words = 0x4000
    report(
        "instance memory (memorySize 0x4000)",
        f"{instance / 1024:.0f} KiB, {stepping + recorded} allocations in 250 doSteps",
        f"memorySize x 4 = {4 * words / 1024:.0f} KiB",
        instance / (4 * words),
        "<= memorySize x 4 + 64 KiB, none in doStep",
        instance <= 4 * words + 64 * 1024 and stepping == 0 and recorded == 0,
    )
    report(
        "record.data buffer, once record.enabled",
        f"{record / 2**20:.1f} MiB",
        "record.capacity 65536 x 52 bytes",
        record / (65536 * 52),
        "report",
        True,
    )


def benchmarks(tmp: Path) -> None:
    per_step(tmp)
    memory(tmp)
