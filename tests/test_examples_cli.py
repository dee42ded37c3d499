# SPDX-License-Identifier: BSD-2-Clause
"""The README's examples and the pmdfmu command, run as a user would."""

import csv
import subprocess
import sys
from pathlib import Path

import pytest

from pmdfmu import field_ex
from pmdfmu.cli import main

pytestmark = pytest.mark.slow  # tests/README.md: compiles programs or runs the CLI; -m "not slow" leaves it out

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def run_example(name):
    return subprocess.run([sys.executable, str(EXAMPLES / name)], capture_output=True, text=True, check=True).stdout


def test_worked_example_prints_the_seed_table():
    out = run_example("worked_example.py").splitlines()
    assert out[0] == "chip time 11003: position 0, velocity 0x10000"
    assert out[-1] == "chip time 11013: position 10, velocity 0x0"


def test_host_port_example():
    out = run_example("host_port.py")
    assert "batch error 0" in out and "unknown opcode -> host I/O error 0x02" in out


def test_circle_example_ends_at_rest():
    assert "cycles; axis 1 ends at 5000" in run_example("circle.py")


def test_run_a_segment_table_writes_csv_and_plot(tmp_path, capsys):
    assert (
        main(["run", str(EXAMPLES / "square.csv"), "--csv", str(tmp_path / "o.csv"), "--plot", str(tmp_path / "o.png")])
        == 0
    )
    rows = list(csv.DictReader(open(tmp_path / "o.csv")))
    assert len(rows) == 2001  # 4 legs of 500 cycles, then the stop row
    assert [int(rows[i]["axis1.commandedPosition"]) for i in (0, 499, 500, 1000, 2000)] == [0, 998, 1000, 1000, 0]
    assert [int(rows[i]["axis2.commandedPosition"]) for i in (0, 500, 999, 1000, 1500, 2000)] == [
        0,
        0,
        998,
        1000,
        1000,
        0,
    ]
    assert (tmp_path / "o.png").stat().st_size > 10_000
    assert "axis 1: ended at position 0" in capsys.readouterr().out


@pytest.mark.parametrize("upload", ["command", "memory"])
def test_run_uploads_either_way_with_the_same_result(tmp_path, upload):
    assert main(["run", str(EXAMPLES / "square.csv"), "--csv", str(tmp_path / "o.csv"), "--upload", upload]) == 0
    assert (tmp_path / "o.csv").read_text().count("\n") == 2002


def test_demo_writes_table_csv_and_png(tmp_path):
    assert main(["demo", "--out", str(tmp_path)]) == 0
    for f in ("demo_table.csv", "demo.csv", "demo.png"):
        assert (tmp_path / f).stat().st_size > 1000
    rows = list(csv.DictReader(open(tmp_path / "demo.csv")))
    assert field_ex(int(rows[-1]["axis1.activityStatus"]), "PMDActivityProfileSegment") == 0
    assert field_ex(int(rows[-1]["axis2.activityStatus"]), "PMDActivityProfileSegment") == 0


def test_validate_and_info(capsys):
    assert main(["validate"]) == 0
    assert main(["info"]) == 0
    out = capsys.readouterr().out
    assert "valid" in out and "0xCA SetBufferFunction(function, bufferID)" in out


def test_a_bad_table_names_file_and_line(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("axis,position,velocity,acceleration,jerk,time\n1,0,0,0,0,5\n7,0,0,0,0,0\n")
    assert main(["run", str(bad)]) == 2
    assert capsys.readouterr().err == f"pmdfmu run: {bad}:3: axis 7 is not 1..4\n"


def test_homing_sequence_finds_the_switch_and_returns_to_it():
    out = run_example("homing.py")
    # the switch trips at the first cycle at or past 12345 (12348) and reaches the chip
    # one cycle later, 8 counts on: that position becomes the origin
    assert "home switch captured at 12356 counts" in out
    assert "back at 0 (the new origin), switch active: True" in out
