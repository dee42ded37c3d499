# SPDX-License-Identifier: BSD-2-Clause
"""The C-Motion library itself (host/c/PMDfmu.c), beyond the seed's programs: one chip per thread
is safe and PMDTaskWait advances the calling thread's chips only (tests/c/cmotion_threads.c);
the FMU's messages and the transport's reach the log callback, and nothing reaches the terminal
(tests/c/cmotion_log.c).

Each program is compiled here with the library (cmotion_build.py), plainly; with
PMDFMU_C_SANITIZERS=thread,address (./dev sanitize) also under ThreadSanitizer and under
AddressSanitizer + UndefinedBehaviorSanitizer, where any report fails the test."""

import os
import re
import shutil
import subprocess

import pytest

import pmdfmu
from cmotion_build import ROOT, compile_program, generate

SANITIZERS = {"thread": "thread", "address": "address,undefined"}
FLAVOURS = ["plain"] + [s for s in os.environ.get("PMDFMU_C_SANITIZERS", "").split(",") if s]
PMD_ERR_Driver, PMD_ERR_OpeningPort = 0x1208, 0x1205  # modelDescription/cmotion_errors.csv

pytestmark = [pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler"), pytest.mark.slow]  # compiles programs


@pytest.fixture(
    scope="module", params=[f if f == "plain" else pytest.param(f, marks=pytest.mark.sanitize) for f in FLAVOURS]
)
def flavour(request):
    if request.param not in ("plain", *SANITIZERS):
        pytest.fail(f"PMDFMU_C_SANITIZERS: unknown sanitizer {request.param!r} (thread, address)")
    if request.param == "thread" and os.environ.get("PMDFMU_SANITIZED"):
        pytest.skip("a ThreadSanitizer program cannot load the ASan build of the FMU")
    return request.param


@pytest.fixture(scope="module")
def programs(flavour, tmp_path_factory):
    """name -> executable, compiled with the flavour's sanitizer."""
    tmp = tmp_path_factory.mktemp(f"cmotion-{flavour}")
    generated = generate(tmp / "generated")
    return {
        name: compile_program(ROOT / "tests" / "c" / f"{name}.c", tmp / name, generated, SANITIZERS.get(flavour, ""))
        for name in ("cmotion_threads", "cmotion_log")
    }


def run(programs, name, *args, env=None):
    """The program's run against the suite's FMI 2 FMU; a sanitizer's report fails it."""
    env = dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)), **(env or {}))
    if not programs[name].parent.name.startswith("cmotion-plain"):
        env.pop("LD_PRELOAD", None)  # ./dev sanitize's runtimes for Python, not for these
        env["TSAN_OPTIONS"] = "halt_on_error=1 exitcode=66"
        env["ASAN_OPTIONS"] = "detect_leaks=1:halt_on_error=1:exitcode=66"
    out = subprocess.run([str(programs[name]), *map(str, args)], capture_output=True, text=True, env=env, timeout=600)
    assert "Sanitizer" not in out.stderr, out.stderr
    assert out.returncode == 0, out.stderr
    return out


def messages(stderr):
    """cmotion_log's L lines: (category, status, message)."""
    return [tuple(line.split(" ", 3)[1:]) for line in stderr.splitlines() if line.startswith("L ")]


# ---- one chip per thread ----


def test_threads_each_with_its_own_chip_print_what_one_thread_prints(programs):
    """Four threads open, move, PMDTaskWait and close their own chips at once, three rounds each:
    every worker's lines equal those of the workers run one after the other."""
    sequential = run(programs, "cmotion_threads", "sequential", 4, 3).stdout.splitlines()
    threaded = run(programs, "cmotion_threads", "threads", 4, 3).stdout.splitlines()
    assert not [line for line in sequential if line.startswith("E ")]
    assert len(sequential) == 4 * 3 * 40
    assert threaded == sequential


def test_task_wait_advances_only_the_calling_threads_chips(programs):
    """After its n-th PMDTaskWait(1) a worker's chip is n milliseconds of host time on, and the
    microseconds its commands took (parallel16: some 14 us each, two reads per wait), with the
    cycles of 100 us that time holds, whatever the other threads' PMDTaskWait calls meanwhile,
    though all four chips are open while every worker waits."""
    lines = run(programs, "cmotion_threads", "threads", 4, 1).stdout.splitlines()
    assert len(lines) == 4 * 40
    for line in lines:
        _, worker, _, wait, chip_time, host_ns, *_ = line.split()
        n, host_ns = int(wait) + 1, int(host_ns)
        assert n * 1_000_000 < host_ns < n * 1_050_000 + 100_000, line
        assert abs(int(chip_time) - host_ns // 100_000) <= 1, line


# ---- the log callback ----


def test_a_bad_script_fails_setup_with_the_fmus_file_line_reason_in_the_log(programs):
    out = run(programs, "cmotion_log", "script", "@ 0\nSetPositon(Axis1, 100);\n")
    assert out.stdout.split() == ["S", f"0x{PMD_ERR_Driver:X}"]
    log = messages(out.stderr)
    fmu = [m for c, s, m in log if c == "errors"]
    assert fmu and ":2:" in fmu[0] and "SetPositon" in fmu[0], log
    # the transport's own line says what failed and quotes the FMU's reason
    transport = [m for c, s, m in log if c == "transport"]
    assert len(transport) == 1 and "fmi2ExitInitializationMode" in transport[0], log
    assert ":2:" in transport[0] and "SetPositon" in transport[0], log


def test_a_command_the_chip_refuses_in_a_script_reaches_the_log_as_a_warning(programs):
    out = run(
        programs,
        "cmotion_log",
        "script",
        "@ 0\nSetProfileMode(Axis1, PMDTrapezoidal);\n@ 5\nSetStopMode(Axis1, 9);\n",
        10,
    )
    assert out.stdout.split() == ["S", "0x0", "R", "0x0"]
    warnings = [(s, m) for c, s, m in messages(out.stderr) if c == "warnings"]
    assert len(warnings) == 1 and warnings[0][0] == "1", out.stderr  # fmi2Warning
    assert ":4:" in warnings[0][1] and "0x04" in warnings[0][1], out.stderr


MOVE = (
    "@ 0\nSetProfileMode(Axis1, PMDTrapezoidal);\nSetPosition(Axis1, 200);\nSetVelocity(Axis1, 2.0);\n"
    "SetAcceleration(Axis1, 0.25);\nUpdate(Axis1);\n"
)


def test_events_reach_the_log_only_when_their_category_is_asked_for(programs):
    default = run(programs, "cmotion_log", "script", MOVE, 400)
    events = run(programs, "cmotion_log", "script", MOVE, 400, "events")
    assert default.stdout.split() == events.stdout.split() == ["S", "0x0", "R", "0x0"]
    assert not [m for c, s, m in messages(default.stderr) if c == "events"], default.stderr
    assert [m for c, s, m in messages(events.stderr) if c == "events"], events.stderr
    assert {c for c, s, m in messages(events.stderr)} == {"events"}


def test_an_unknown_log_category_fails_setup_with_the_fmus_reason(programs):
    out = run(programs, "cmotion_log", "script", MOVE, 1, "event")
    assert out.stdout.split() == ["S", f"0x{PMD_ERR_Driver:X}"]
    transport = [m for c, s, m in messages(out.stderr) if c == "transport"]
    assert len(transport) == 1 and '"event"' in transport[0], out.stderr


# ---- nothing on the terminal but the log ----


def test_a_file_that_is_not_a_zip_gives_only_the_librarys_log_line(programs, tmp_path):
    """unzip's own complaint goes into the library's message, not onto the terminal."""
    (tmp_path / "not-a-zip.fmu").write_text("not a zip\n")
    out = run(programs, "cmotion_log", "fmu", tmp_path / "not-a-zip.fmu")
    assert out.stdout.split() == ["S", f"0x{PMD_ERR_OpeningPort:X}"]
    lines = out.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("L transport 3 cannot unpack"), out.stderr
    assert "not-a-zip.fmu" in lines[0] and re.search(r"zipfile", lines[0]), out.stderr


def test_an_fmu_named_but_missing_is_named_in_the_log(programs, tmp_path):
    """PMDFMU_FMU or PMDFMUOptions.fmu set to a path that is not there: the line names that path and
    why, not "set PMDFMU_FMU" to a user who did."""
    out = run(programs, "cmotion_log", "fmu", tmp_path / "missing.fmu")
    assert out.stdout.split() == ["S", f"0x{PMD_ERR_OpeningPort:X}"]
    lines = out.stderr.splitlines()
    assert lines == [f"L transport 3 cannot open the FMU {tmp_path / 'missing.fmu'}: No such file or directory"]


@pytest.mark.parametrize("baud", [0, 9600])
def test_a_host_interface_parameter_outside_its_range_opens_no_chip(programs, baud):
    """The attacker's finding: a serial line of 0 baud made every command take no time; the opening is
    refused with one transport line naming the parameter and its range (modelDescription/host_interfaces.csv)."""
    out = run(programs, "cmotion_log", "serial", baud)
    if baud:
        assert out.stdout.split() == ["S", "0x0"] and not out.stderr
        return
    assert out.stdout.split() == ["S", f"0x{PMD_ERR_OpeningPort:X}"]
    assert out.stderr.splitlines() == [
        "L transport 3 host interface serial: baud = 0 is not in 1 .. 4294967295: no chip opened"
    ]
