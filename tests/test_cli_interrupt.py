# SPDX-License-Identifier: BSD-2-Clause
"""Ctrl-C (SIGINT) at a random point of `pmdfmu verify --cases` and of `pmdfmu pack`: the command ends
with exit status 130 and one line, `pmdfmu CMD: interrupted`, no traceback; every file it documents is
there whole (as an uninterrupted run writes it) or not at all, no temporary file is left, and an older
output is intact (docs/cli.md)."""

import random
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from pmdfmu.sweep import HANDOFF_PREFIX, handoff_root

pytestmark = pytest.mark.slow  # tests/README.md: ./dev test -m "not slow" leaves them out

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SQUARE, GOLDEN = EXAMPLES / "square.csv", EXAMPLES / "ci" / "square.golden.csv"
# the console script's import done first (an interrupt inside Python's own start-up is Python's), then main
DRIVER = "from pmdfmu.cli import console; print('ready', flush=True); console()"
TRIALS = 5


def start(argv, cwd):
    child = subprocess.Popen(
        [sys.executable, "-c", DRIVER, *map(str, argv)],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert child.stdout.readline() == "ready\n"
    return child, time.perf_counter()


def run_whole(argv, cwd):
    """An uninterrupted run: its exit status and how long main worked (s: until its first line of output,
    which it prints when the work is done)."""
    child, begun = start(argv, cwd)
    child.stdout.readline()
    seconds = time.perf_counter() - begun
    out, err = child.communicate(timeout=300)
    return child.returncode, seconds, err


def interrupted(argv, cwd, delay, pid=False):
    """Exit status and standard error of a run sent SIGINT after delay s (and its pid, if asked)."""
    child, _ = start(argv, cwd)
    time.sleep(delay)
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=300)
    return (child.returncode, err, child.pid) if pid else (child.returncode, err)


def assert_interrupted_or_done(status, err, command, done):
    assert "Traceback" not in err, err
    if status == 130:
        assert err == f"pmdfmu {command}: interrupted\n"
    else:  # the signal came after the work was done
        assert status == done, err


def partial_files(*folders):
    return [p for folder in folders if folder.exists() for p in folder.rglob("*") if p.name.endswith(".partial")]


@pytest.mark.parametrize("scheduler", ["serial", "a local Dask cluster"])
def test_an_interrupted_verify_of_a_case_table_leaves_no_partial_report(tmp_path, scheduler):
    """Also on Dask (the default scheduler: a cluster started for the command): no sweep folder of the
    command's is left in the handoff root (/dev/shm) either."""
    changed = tmp_path / "changed.csv"  # axis 2's return leg at half the speed: the golden fails
    changed.write_text(SQUARE.read_text().replace("2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500"))
    (tmp_path / "cases.csv").write_text(
        f"name,table,golden\ngood,{SQUARE},{GOLDEN}\nchanged,changed.csv,{GOLDEN}\nagain,{SQUARE},{GOLDEN}\n"
    )

    def argv(out):
        where = ["--scheduler", "serial"] if scheduler == "serial" else []
        return ["verify", "--cases", tmp_path / "cases.csv", *where, "--out", out, "--junit", out / "junit.xml"]

    done, seconds, err = run_whole(argv(tmp_path / "whole"), tmp_path)
    assert done == 1 and "Traceback" not in err, err
    whole = {p.name: p.read_bytes() for p in (tmp_path / "whole").iterdir() if p.name != "junit.xml"}
    assert sorted(whole) == ["changed.actual.csv", "changed.diff.png"]
    rng = random.Random(17)
    statuses = []
    for trial in range(TRIALS):
        out = tmp_path / f"trial{trial}"
        status, err, pid = interrupted(argv(out), tmp_path, rng.uniform(0, seconds), pid=True)
        assert_interrupted_or_done(status, err, "verify", done)
        statuses.append(status)
        assert not partial_files(out, tmp_path)
        assert not list(Path(handoff_root()).glob(f"{HANDOFF_PREFIX}{pid}-*"))
        for path in out.iterdir() if out.exists() else ():
            if path.name == "junit.xml":
                assert status != 130 and ET.parse(path).getroot().get("tests")
            else:
                assert path.read_bytes() == whole[path.name], path
    assert 130 in statuses


def test_an_interrupted_pack_leaves_the_old_fmu_and_no_temporary_file(tmp_path):
    for name in ("two_axis.script", "two_axis_table.csv"):
        shutil.copy(EXAMPLES / name, tmp_path)
    out = tmp_path / "p.fmu"
    argv = ["pack", tmp_path / "two_axis.script", "--out", out]
    done, seconds, err = run_whole(argv, tmp_path)
    assert done == 0, err
    new = out.read_bytes()
    rng = random.Random(23)
    statuses = []
    for _ in range(TRIALS):
        out.write_bytes(b"the old FMU")
        status, err = interrupted(argv, tmp_path, rng.uniform(0, seconds))
        assert_interrupted_or_done(status, err, "pack", done)
        statuses.append(status)
        # interrupted: the old FMU, or the new one whole if the signal landed once it was in place
        assert out.read_bytes() in ((b"the old FMU", new) if status == 130 else (new,))
        assert not partial_files(tmp_path)
    assert 130 in statuses


@pytest.mark.parametrize("command", ["verify", "pack"])
def test_an_interrupt_is_answered_with_one_line_and_130(tmp_path, command):
    """The signal inside main's work: half-way through the time a whole run worked, then (a machine under
    load runs faster or slower from one run to the next) a quarter, an eighth."""
    for name in ("two_axis.script", "two_axis_table.csv"):
        shutil.copy(EXAMPLES / name, tmp_path)
    argv = (
        ["pack", tmp_path / "two_axis.script", "--out", tmp_path / "p.fmu"]
        if command == "pack"
        else ["verify", SQUARE, "--against", GOLDEN]
    )
    done, seconds, _err = run_whole(argv, tmp_path)
    for share in (2, 4, 8, 16):
        (tmp_path / "p.fmu").unlink(missing_ok=True)
        status, err = interrupted(argv, tmp_path, seconds / share)
        assert_interrupted_or_done(status, err, command, done)
        if status == 130:
            break
    assert status == 130
    assert not (tmp_path / "p.fmu").exists() and not partial_files(tmp_path)


# Ctrl-C inside a garbage collector callback, as one once landed in a weakref callback of matplotlib's
DROPPED = """
import gc
from pmdfmu.cli import console
collections = []
def interrupt(phase, info):
    collections.append(phase)
    if len(collections) == 4:  # inside the command's work (pack sees ~50 collections, verify ~8)
        raise KeyboardInterrupt
gc.callbacks.append(interrupt)
console()
"""


@pytest.mark.parametrize("command", ["verify", "pack"])
def test_an_interrupt_python_drops_inside_a_callback_still_interrupts(tmp_path, command):
    """Python drops an exception raised in a callback (reports it as unraisable, with a traceback) and the
    code around it runs on: the program delivers the interrupt again, so the command ends as at any other
    Ctrl-C, and leaves no file."""
    for name in ("two_axis.script", "two_axis_table.csv"):
        shutil.copy(EXAMPLES / name, tmp_path)
    argv = (
        ["pack", tmp_path / "two_axis.script", "--out", tmp_path / "p.fmu"]
        if command == "pack"
        else ["verify", SQUARE, "--against", GOLDEN, "--out", tmp_path / "report"]
    )
    child = subprocess.run(
        [sys.executable, "-c", DROPPED, *map(str, argv)], cwd=tmp_path, capture_output=True, text=True
    )
    assert (child.returncode, child.stderr) == (130, f"pmdfmu {command}: interrupted\n")
    assert not (tmp_path / "p.fmu").exists() and not (tmp_path / "report").exists()
    assert not partial_files(tmp_path)


# the same, then a wait the command's main thread blocks in (as on a sweep's cases); the interrupt is
# delivered again once the main thread waits there
DROPPED_THEN_WAITING = """
import gc, threading
import pmdfmu.cli as cli
Timer = threading.Timer
cli.threading.Timer = lambda interval, function: Timer(0.5, function)
def interrupt(phase, info):
    gc.callbacks.clear()
    raise KeyboardInterrupt
def wait(args):
    gc.callbacks.append(interrupt)
    gc.collect()
    threading.Event().wait(20)
    return 0
cli.cmd_path = wait
cli.sys.argv = ["pmdfmu", "path"]
cli.console()
"""


def test_an_interrupt_python_drops_wakes_a_wait_at_once():
    """The interrupt delivered again wakes the main thread's wait, as a Ctrl-C does: _thread.interrupt_main
    alone was seen only when the wait was over, here 20 s later."""
    start = time.monotonic()
    child = subprocess.run([sys.executable, "-c", DROPPED_THEN_WAITING], capture_output=True, text=True, timeout=120)
    assert (child.returncode, child.stderr) == (130, "pmdfmu path: interrupted\n")
    assert time.monotonic() - start < 15


def test_an_interrupt_inside_a_zip_members_write_reaches_the_caller_as_itself(tmp_path, monkeypatch):
    """Ctrl-C inside zipfile's write of a member (where the random signals of the test above landed once):
    pack raises KeyboardInterrupt, not the ValueError ("seek of closed file") that closing the half-written
    zip raises; no output and no partial file are left."""
    import zipfile

    from pmdfmu.pack import pack

    shutil.copy(EXAMPLES / "two_axis.script", tmp_path / "s.script")
    shutil.copy(EXAMPLES / "two_axis_table.csv", tmp_path)
    real, calls, unraisable = zipfile._ZipWriteFile.close, [], []

    def close(self):  # the second member's: interrupted before it finishes
        calls.append(1)
        if len(calls) == 2:
            raise KeyboardInterrupt
        return real(self)

    monkeypatch.setattr(zipfile._ZipWriteFile, "close", close)
    monkeypatch.setattr(sys, "unraisablehook", unraisable.append)
    with pytest.raises(KeyboardInterrupt):
        pack(tmp_path / "s.script", out=tmp_path / "p.fmu")
    import gc

    gc.collect()  # the half-written archive's finalizer, had it one to run
    assert not unraisable
    assert not (tmp_path / "p.fmu").exists() and not partial_files(tmp_path)
