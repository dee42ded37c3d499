# SPDX-License-Identifier: BSD-2-Clause
"""chip.run(n, record=..., to="run.npy"): the rows written as they come, a chunk at a time, equal to the
in-memory run's; memory bounded by the chunk whatever n (peak RSS of a child process); a failed run
leaves no file."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu.chip import RECORDED

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "examples" / "two_axis.script"
STATUS_AND_REALS = ["axis1.activityStatus", "axis1.eventStatus", "axis1.velocity", "axis2.commandedPosition"]


@pytest.mark.parametrize("record", [list(RECORDED), STATUS_AND_REALS], ids=["commanded", "status"])
@pytest.mark.parametrize("version", [2, 3])
def test_the_file_equals_the_in_memory_run(tmp_path, version, record):
    with pmdfmu.Chip(version, script=SCRIPT) as a, pmdfmu.Chip(version, script=SCRIPT) as b:
        assert a.run(5000, record=record, to=tmp_path / "run.npy", chunk=777) is None
        rows = b.run(5000, record=record)
        assert (a.cycles, a.host_time_ns) == (b.cycles, b.host_time_ns)
        a.run(10, record=record, to=tmp_path / "more.npy", chunk=3)
        more = b.run(10, record=record)
    written = np.load(tmp_path / "run.npy")
    assert written.dtype == rows.dtype and np.array_equal(written, rows)
    assert np.array_equal(np.load(tmp_path / "more.npy"), more)
    assert not list(tmp_path.glob("*.part"))


def test_no_cycles_writes_an_empty_array_and_bad_arguments_are_refused(tmp_path):
    with pmdfmu.Chip() as chip:
        chip.run(0, record=["axis1.commandedPosition"], to=tmp_path / "empty.npy")
        assert len(np.load(tmp_path / "empty.npy")) == 0
        with pytest.raises(ValueError, match="to= needs record="):
            chip.run(5, to=tmp_path / "x.npy")
        with pytest.raises(ValueError, match="to= needs"):
            chip.run(5, record=["axis1.commandedPosition"], to=tmp_path / "x.npy", chunk=0)


def test_a_run_that_fails_leaves_no_file(tmp_path):
    class Failing(pmdfmu.recording.Recorder):
        calls = 0

        def run(self, cycles, out=None):
            Failing.calls += 1
            if Failing.calls == 3:
                raise KeyboardInterrupt
            return super().run(cycles, out)

    with pmdfmu.Chip() as chip:
        chip.recorder = Failing
        with pytest.raises(KeyboardInterrupt):
            chip.run(100, record=["axis1.commandedPosition"], to=tmp_path / "run.npy", chunk=10)
    assert not list(tmp_path.iterdir())


CHILD = """
import resource, sys, pmdfmu
from pmdfmu.chip import RECORDED
with pmdfmu.Chip(2, script=sys.argv[3]) as chip:
    chip.run(int(sys.argv[1]), record=list(RECORDED), to=sys.argv[2], chunk=1 << 14)
print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)  # KiB
"""


def test_memory_stays_a_chunk_whatever_the_length(tmp_path):
    def peak(n):
        done = subprocess.run(
            [sys.executable, "-c", CHILD, str(n), str(tmp_path / f"{n}.npy"), str(SCRIPT)],
            capture_output=True,
            text=True,
            check=True,
        )
        return int(done.stdout.split()[-1]) * 1024

    short, long = peak(10_000), peak(1_000_000)
    in_memory = np.load(tmp_path / "1000000.npy", mmap_mode="r").nbytes
    assert in_memory > 40 << 20
    assert long - short < 8 << 20, (short, long, in_memory)


@pytest.mark.parametrize("source", ["two_axis.script", "square.csv"])
def test_pmdfmu_run_out_writes_what_csv_writes(tmp_path, source):
    from pmdfmu.cli import main

    given = str(ROOT / "examples" / source)
    assert main(["run", given, "--csv", str(tmp_path / "memory.npz")]) == 0
    assert main(["run", given, "--out", str(tmp_path / "streamed.npz")]) == 0
    assert main(["run", given, "--out", str(tmp_path / "streamed.npy")]) == 0
    with np.load(tmp_path / "memory.npz") as memory, np.load(tmp_path / "streamed.npz") as streamed:
        assert sorted(memory.keys()) == sorted(streamed.keys())
        for key in memory.keys():
            assert memory[key].dtype == streamed[key].dtype and np.array_equal(memory[key], streamed[key])
        assert np.array_equal(np.load(tmp_path / "streamed.npy"), memory["recording"])


def test_pmdfmu_run_out_writes_nothing_for_a_run_cut_short_but_a_window(tmp_path, capsys):
    from pmdfmu.cli import main

    script = str(SCRIPT)
    assert main(["run", script, "--out", str(tmp_path / "cut.npy"), "--max-cycles", "100"]) == 1
    assert "had not ended" in capsys.readouterr().err and not list(tmp_path.iterdir())
    assert main(["run", script, "--out", str(tmp_path / "window.npz"), "--cycles", "100"]) == 0
    assert main(["run", script, "--csv", str(tmp_path / "window-memory.npz"), "--cycles", "100"]) == 0
    with np.load(tmp_path / "window.npz") as a, np.load(tmp_path / "window-memory.npz") as b:
        assert np.array_equal(a["recording"], b["recording"]) and not a["ended"] and not b["ended"]
