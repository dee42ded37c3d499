# SPDX-License-Identifier: BSD-2-Clause
"""Instances from C: four instances stepped concurrently from four
threads give exactly the sequential results; 1000 rounds of instantiate, run,
save/restore state and free under valgrind leak nothing and raise no error."""

import os
import shutil
import subprocess
import zipfile
from pathlib import Path

import pytest
from fmpy import read_model_description

import pmdfmu
from states import command

SOURCE = Path(__file__).resolve().parent / "c" / "instances.c"
HEADERS = Path(__import__("fmpy").__file__).parent / "c-code"


def scenario(path: Path, steps: int = 40, cycles: int = 25):
    """Axis 1 external profile from memory (the driver adds an offset per instance), axis 2 trapezoidal."""
    rows = [(0, 0x18000, 0x40, 0x1000, 30), (50, -0x8000, 0, 0, 40), (20, 0x2000, -0x20, 0, 0)]
    lines = []
    setup = []
    for k in range(5):
        setup += command("SetBufferStart", 2 + k, 0x200 + 4 * k) + command("SetBufferLength", 2 + k, 3)
        setup += command("SetBufferFunction", k, 2 + k)
    for i in range(0, len(setup), 60):
        lines.append("H " + " ".join(map(str, setup[i : i + 60])))
    for k in range(5):
        lines.append(f"M {0x200 + 4 * k} " + " ".join(str(pmdfmu.signed(r[k] & 0xFFFFFFFF)) for r in rows))
    lines.append(
        "H "
        + " ".join(
            map(
                str,
                command("SetProfileMode", 4)
                + command("Update")
                + command("SetPosition", 777, axis=1)
                + command("SetVelocity", 0x20000, axis=1)
                + command("SetAcceleration", 0x800, axis=1)
                + command("Update", axis=1),
            )
        )
    )
    lines += [f"S {cycles}"] * steps
    path.write_text("\n".join(lines) + "\n")


def build(tmp: Path) -> Path:
    exe = tmp / "instances"
    subprocess.run(
        [
            "cc",
            "-O1",
            "-g",
            "-std=c99",
            "-D_POSIX_C_SOURCE=200809L",
            "-pthread",
            f"-I{HEADERS}",
            str(SOURCE),
            "-o",
            str(exe),
            "-ldl",
        ],
        check=True,
    )
    return exe


def fmu_binary(tmp: Path) -> Path:
    zipfile.ZipFile(pmdfmu.default_fmu(2)).extract("binaries/linux64/PMDMotionProcessor.so", tmp)
    return tmp / "binaries/linux64/PMDMotionProcessor.so"


def guid():
    return read_model_description(str(pmdfmu.default_fmu(2))).guid


@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
def test_four_instances_in_four_threads_equal_the_sequential_run(tmp_path):
    scenario(tmp_path / "s.txt")
    out = subprocess.run(
        [str(build(tmp_path)), str(fmu_binary(tmp_path)), guid(), str(tmp_path / "s.txt"), "threads"],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr
    assert "4 threads = sequential" in out.stdout


@pytest.mark.slow
@pytest.mark.sanitize
@pytest.mark.skipif(not shutil.which("valgrind") and not os.environ.get("CI"), reason="valgrind not installed")
def test_a_thousand_rounds_under_valgrind_leak_nothing(tmp_path):
    scenario(tmp_path / "s.txt", steps=4, cycles=25)
    out = subprocess.run(
        [
            "valgrind",
            "--leak-check=full",
            "--errors-for-leak-kinds=definite,indirect",
            "--error-exitcode=99",
            str(build(tmp_path)),
            str(fmu_binary(tmp_path)),
            guid(),
            str(tmp_path / "s.txt"),
            "cycles",
            "1000",
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert out.returncode == 0, out.stderr[-3000:]
    assert "1000 rounds" in out.stdout
    assert "ERROR SUMMARY: 0 errors" in out.stderr
    assert "definitely lost: 0 bytes" in out.stderr or "All heap blocks were freed" in out.stderr


@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
@pytest.mark.skipif(bool(os.environ.get("PMDFMU_SANITIZED")), reason="the driver's malloc would bypass ASan's")
def test_an_instance_holds_at_most_memory_plus_64_kib_and_dosteps_allocate_nothing(tmp_path):
    """bench/memory.c counts the FMU's allocations from outside: 250 doSteps of a running
    script, 50 of them recording, allocate nothing (CONTRACT 2: no allocation in doStep)."""
    exe = tmp_path / "memory"
    subprocess.run(
        [
            "cc",
            "-O1",
            "-std=c99",
            f"-I{HEADERS}",
            str(SOURCE.parent.parent.parent / "bench" / "memory.c"),
            "-rdynamic",
            "-ldl",
            "-o",
            str(exe),
        ],
        check=True,
    )
    script = SOURCE.parent.parent.parent / "examples" / "two_axis.script"
    out = subprocess.run(
        [str(exe), str(fmu_binary(tmp_path)), guid(), str(script)], capture_output=True, text=True, check=True
    ).stdout
    instance, stepping, record, recorded = map(int, out.split())
    assert 4 * 0x4000 <= instance <= 4 * 0x4000 + 64 * 1024
    assert stepping == 0 and recorded == 0
    assert record >= 65536 * 52  # allocated when record.enabled was set
