# SPDX-License-Identifier: BSD-2-Clause
"""Progress bars (pmdfmu.progress): on a terminal once the work lasts about a second, never in a pipe or
a CI log unless --progress, never with -q; Ctrl-C with a bar up ends at once with 130 and leaves no file;
a Chip.run split for its bar records the same rows; a sweep's local cluster gives its Dask dashboard link
with the bar, under the same rules."""

import fcntl
import os
import pty
import re
import select
import signal
import struct
import subprocess
import sys
import termios
import time
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import progress

pytestmark = pytest.mark.slow  # tests/README.md: runs the CLI in subprocesses for seconds

DRIVER = "from pmdfmu.cli import console; console()"


def long_table(path, cycles):
    """A one-axis table that holds still for `cycles` cycles: seconds of work for the CLI."""
    half = cycles // 2
    path.write_text(
        f"axis,position,velocity,acceleration,jerk,time\n1,0,0,0,0,{half}\n1,0,0,0,0,{cycles - half}\n1,0,0,0,0,0\n"
    )
    return path


def on_a_terminal(argv, cwd, interrupt_after=None, driver=DRIVER):
    """Runs pmdfmu with standard error on a pty: (exit status, what the terminal showed, seconds from the
    SIGINT to the exit)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # a terminal 100 columns wide
    child = subprocess.Popen(
        [sys.executable, "-c", driver, *map(str, argv)], cwd=cwd, stdout=subprocess.PIPE, stderr=slave
    )
    # the slave stays open here until the child has exited and all it wrote is read: a pty whose slave
    # closes can answer EIO with the child's last bytes unread (the run of a still table ends at once)
    shown, sent, end = b"", None, time.monotonic() + 120
    while time.monotonic() < end:
        if select.select([master], [], [], 0.05)[0]:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # the child closed the terminal
                break
            shown += chunk
        if interrupt_after and sent is None and interrupt_after.encode() in shown:
            child.send_signal(signal.SIGINT)
            sent = time.monotonic()
        if child.poll() is not None and not select.select([master], [], [], 0.1)[0]:
            break  # exited, and all it wrote has been read
    child.wait(timeout=60)
    exited = time.monotonic()
    os.close(slave)
    os.close(master)
    return child.returncode, shown.decode(errors="replace"), (exited - sent if sent else None)


def test_a_long_run_shows_a_bar_on_a_terminal_and_none_with_quiet(tmp_path):
    # the bar's delay (a second: no bar for short work) made 0, so that the bar is drawn when it opens: a
    # table that holds still is fast-forwarded, and its run may end in one update before any delay is up
    driver = "import pmdfmu.progress as p; p.DELAY = 0; " + DRIVER
    table = long_table(tmp_path / "long.csv", 2_000_000)
    status, shown, _ = on_a_terminal(["run", table, "--max-cycles", "4000000"], tmp_path, driver=driver)
    assert status == 0 and "cycles/s" in shown and "run long.csv" in shown
    status, shown, _ = on_a_terminal(["-q", "run", table, "--max-cycles", "4000000"], tmp_path, driver=driver)
    assert status == 0 and "cycles/s" not in shown


def test_a_pipe_shows_no_bar_unless_asked(tmp_path):
    table = long_table(tmp_path / "long.csv", 3_000_000)
    argv = [sys.executable, "-c", DRIVER, "run", str(table), "--max-cycles", "4000000"]
    plain = subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, check=True)
    assert "cycles/s" not in plain.stderr and plain.stderr == ""
    asked = subprocess.run(argv + ["--progress"], cwd=tmp_path, capture_output=True, text=True, check=True)
    assert "cycles/s" in asked.stderr


def test_ctrl_c_with_a_bar_up_stops_within_a_second_and_leaves_no_file(tmp_path):
    table = long_table(tmp_path / "long.csv", 40_000_000)
    argv = ["run", table, "--max-cycles", "50000000", "--csv", tmp_path / "out.csv", "--progress"]
    status, shown, seconds = on_a_terminal(argv, tmp_path, interrupt_after="cycles/s")
    assert status == 130 and "pmdfmu run: interrupted" in shown and "Traceback" not in shown
    assert seconds < 1.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["long.csv"]


def test_a_chip_run_split_for_its_bar_records_the_same_rows(capsys):
    names = ["axis1.commandedPosition", "axis1.commandedVelocity"]

    def recorded():
        with pmdfmu.Chip() as chip:
            ax = chip.axis(0)
            ax.SetPosition(3_000_000)
            ax.SetVelocity(0x80000)
            ax.SetAcceleration(0x100)
            ax.Update()
            return chip.run(250_000, record=names)

    whole = recorded()
    progress.show(True)
    try:
        split = recorded()
    finally:
        progress.show(None)
    assert np.array_equal(whole, split)
    assert "chip.run" in capsys.readouterr().err


def test_a_serial_sweep_counts_its_cases(cases, capsys):
    progress.show(True)
    try:
        pmdfmu.sweep(cases, scheduler="serial")
    finally:
        progress.show(None)
    assert f"cases:   0%|          | 0/{len(cases)}" in capsys.readouterr().err


def one_case(tmp_path):
    """A case table of one short case, for a local cluster's start."""
    table = long_table(tmp_path / "still.csv", 2000)
    (tmp_path / "cases.csv").write_text(f"name,table\nstill,{table}\n")
    return tmp_path / "cases.csv"


DASHBOARD = re.compile(r"sweep: Dask dashboard at (http://\S+/status)")


def test_a_sweep_on_a_local_cluster_gives_its_dashboard_link_with_the_bar(tmp_path):
    argv = ["sweep", one_case(tmp_path), "--workers", "1", "--out", tmp_path / "out"]
    status, shown, _ = on_a_terminal(argv, tmp_path)
    assert status == 0 and DASHBOARD.search(shown), shown
    status, shown, _ = on_a_terminal(["-q", *argv], tmp_path)
    assert status == 0 and "dashboard" not in shown


def test_a_piped_sweep_gives_no_dashboard_link_unless_asked(tmp_path):
    argv = [sys.executable, "-c", DRIVER, "sweep", str(one_case(tmp_path)), "--workers", "1", "--out", "out"]
    plain = subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, check=True)
    assert "dashboard" not in plain.stderr
    asked = subprocess.run(argv + ["--progress"], cwd=tmp_path, capture_output=True, text=True, check=True)
    assert DASHBOARD.search(asked.stderr) and "cases" in asked.stderr, asked.stderr


def test_progress_is_documented_in_the_cli_page():
    text = (Path(__file__).resolve().parent.parent / "docs" / "cli.md").read_text()
    assert "--progress" in text
