# SPDX-License-Identifier: BSD-2-Clause
"""Issue target 3: pmdfmu.System (chip + plant stepped natively, examples/systems' Gauss-Seidel loop,
FMI 2, the 3000 steps of the .ssd's experiment recording its 8 outputs) against a plain C loop calling
the same FMI functions in the same order (bench/system_loop.c, on the same kind of fresh instances), and
the FMPy master it equals bit for bit (examples/systems' run_master), whole runs. Interleaved."""

from __future__ import annotations

import ctypes
import subprocess
import sys
import time
from ctypes import c_double, c_long, c_size_t, c_uint, c_void_p
from pathlib import Path

import numpy as np
from common import REPO, interleave, load, report

import pmdfmu
from pmdfmu import native

sys.path.insert(0, str(REPO / "examples" / "systems"))
import systems  # noqa: E402  examples/systems/systems.py

FMI_HEADERS = Path(__import__("fmpy").__file__).parent / "c-code"
# the Integer motor wire of a 16-bit bus (pmdfmu.System's default) and the .ssd's outputs but the Real motor
# output: what the C loop gets and sets
SYSTEM = systems.read_system(motor="motorCommand")
OUTPUTS = [c.path for c in SYSTEM.outputs if c.name != "axis1.motorOutput"]
STEPS = SYSTEM.steps


class Loop(ctypes.Structure):
    _fields_ = [
        ("get_int", c_void_p * 2),
        ("set_int", c_void_p * 2),
        ("get_real", c_void_p * 2),
        ("do_step", c_void_p * 2),
        ("instance", c_void_p * 2),
        ("encoder", c_uint),
        ("actual", c_uint),
        ("motor", c_uint),
        ("plant_motor", c_uint),
        ("chip_columns", c_uint * 3),
        ("plant_int", c_uint),
        ("plant_reals", c_uint * 4),
    ]


def bare_library(tmp: Path):
    so = tmp / "system_loop.so"
    subprocess.run(
        [
            "cc",
            "-O2",
            "-std=c99",
            "-shared",
            "-fPIC",
            f"-I{FMI_HEADERS}",
            str(REPO / "bench" / "system_loop.c"),
            "-o",
            str(so),
        ],
        check=True,
    )
    f = ctypes.CDLL(str(so)).bare_loop
    f.argtypes = [ctypes.POINTER(Loop), c_double, c_double, c_long, c_void_p, c_size_t]
    return f


def fresh():
    chip = pmdfmu.Chip(2, script=systems.script_value(), **systems.parameters()["chip"])
    return chip, pmdfmu.System(chip)


def native_run() -> float:
    chip, system = fresh()
    with chip, system:
        system.run(0, record=OUTPUTS)  # its operations made (the bare loop's struct is made untimed too)
        start = time.perf_counter()
        system.run(STEPS, record=OUTPUTS)
        return time.perf_counter() - start


def bare_run(bare) -> float:
    chip, system = fresh()
    with chip, system:
        fns = [system._fmus["chip"]._functions, system._fmus["plant"]._functions]
        vr = [system._variables["chip"], system._variables["plant"]]
        loop = Loop()
        for field, name in (
            ("get_int", "fmi2GetInteger"),
            ("set_int", "fmi2SetInteger"),
            ("get_real", "fmi2GetReal"),
            ("do_step", "fmi2DoStep"),
        ):
            getattr(loop, field)[:] = [native.address(f[name]) for f in fns]
        loop.instance[:] = [system._fmus["chip"].component, system._fmus["plant"].component]
        loop.encoder, loop.actual = vr[1]["encoderCount"].valueReference, vr[0]["axis1.actualPosition"].valueReference
        loop.motor, loop.plant_motor = vr[0]["axis1.motorCommand"].valueReference, vr[1]["motorCommand"].valueReference
        loop.chip_columns[:] = [vr[0][p[5:]].valueReference for p in OUTPUTS[:3]]
        loop.plant_int = vr[1]["encoderCount"].valueReference
        loop.plant_reals[:] = [vr[1][p[6:]].valueReference for p in OUTPUTS[4:]]
        rows = np.zeros(
            STEPS,
            dtype=[("step", np.int64)] + [(p, np.int32) for p in OUTPUTS[:4]] + [(p, np.float64) for p in OUTPUTS[4:]],
        )
        start = time.perf_counter()
        if bare(loop, system.start, system.step, STEPS, rows.ctypes.data, rows.dtype.itemsize):
            raise RuntimeError("bare loop: an FMI call failed")
        return time.perf_counter() - start


def master_run() -> float:
    start = time.perf_counter()
    systems.run_master("gauss-seidel", 2, log=lambda *a: None, motor="motorCommand")
    return time.perf_counter() - start


def whole_native_run() -> float:
    start = time.perf_counter()
    chip, system = fresh()
    with chip, system:
        system.run(STEPS, record=OUTPUTS)
    return time.perf_counter() - start


def benchmarks(tmp) -> None:
    assert len(OUTPUTS) == 8 and OUTPUTS[3] == "plant.encoderCount"
    bare = bare_library(tmp)
    t = interleave({"native": native_run, "bare": lambda: bare_run(bare)})
    ratio = t["native"].median / t["bare"].median
    report(
        f"System.run, chip + plant, {STEPS} steps, 8 columns, FMI 2 ({load()})",
        t["native"].text(1e3, "ms"),
        f"C loop of the same FMI calls {t['bare'].text(1e3, 'ms')}",
        ratio,
        "<= 1.3x",
        ratio <= 1.3,
    )
    t = interleave({"native": whole_native_run, "master": master_run}, runs=3)
    ratio = t["master"].median / t["native"].median
    report(
        f"System, whole run with set-up / FMPy master ({load()})",
        t["native"].text(1e3, "ms"),
        f"examples/systems run_master {t['master'].text(1e3, 'ms')}",
        ratio,
        "(factor, report)",
        True,
    )
