# SPDX-License-Identifier: BSD-2-Clause
"""Chip.trace() and `pmdfmu trace`: the trace buffer read for a person (docs/chip.md, "Reading the trace")."""

from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import (
    PMDTraceCommandedPosition,
    PMDTraceCommandedVelocity,
    PMDTraceConditionImmediate,
    PMDTraceRollingBuffer,
    PMDTraceTime,
)
from pmdfmu.cli import main

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "trace_breakpoint.script"


def start_move(ax):
    ax.SetPosition(1_000_000)
    ax.SetVelocity(0x30000)
    ax.SetAcceleration(0x10000)
    ax.Update()


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_breakpoint_triggered_trace_reads_as_the_recorded_run(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, script=str(EXAMPLE)) as chip:
        rec = chip.run(2000, record=["axis1.commandedPosition", "axis1.commandedVelocity"])
        trace = chip.trace()
    assert trace.variables == ["time", "axis1.commandedPosition", "axis1.commandedVelocity", "axis1.activityStatus"]
    assert trace.units["axis1.commandedVelocity"] == "16.16 counts/cycle" and trace.chip_time
    assert (trace.mode, trace.period, len(trace), trace.running, trace.trigger) == ("one-time", 4, 150, False, 0)
    first = int(trace.samples["cycle"][0])
    # the trace starts in the cycle breakpoint 1 fires: the first where the position reaches 8000
    assert first == int(rec["cycle"][np.argmax(rec["axis1.commandedPosition"] >= 8000)])
    rows = rec[np.isin(rec["cycle"], trace.samples["cycle"])]
    assert list(rows["axis1.commandedPosition"]) == list(trace.samples["axis1.commandedPosition"])
    assert list(rows["axis1.commandedVelocity"]) == list(trace.samples["axis1.commandedVelocity"])


def test_a_rolling_trace_that_wrapped_reads_oldest_first_and_leaves_the_chip_as_it_was(chip):
    ax = chip.axis(0)
    ax.SetBufferStart(0, 0x100)
    ax.SetBufferLength(0, 10)  # not a whole number of samples: the oldest word is half a sample
    ax.SetTraceMode(PMDTraceRollingBuffer)
    ax.SetTracePeriod(3)
    ax.SetTraceVariable(0, 0, PMDTraceTime)
    ax.SetTraceVariable(1, 1, PMDTraceCommandedPosition)
    ax.SetTraceVariable(2, 1, PMDTraceCommandedVelocity)
    ax.SetTraceStart(0, PMDTraceConditionImmediate, 0, 0)
    start_move(chip.axis(1))
    chip.run(100)
    before = (chip.cycles, ax.GetBufferReadIndex(0), ax.GetTraceCount(), ax.GetTraceStatus())
    trace = chip.trace()
    assert (chip.cycles, ax.GetBufferReadIndex(0), ax.GetTraceCount(), ax.GetTraceStatus()) == before
    assert trace.wrapped and trace.running and trace.trigger is None and len(trace) == 3
    assert list(np.diff(trace.samples["cycle"])) == [3, 3] and trace.samples["cycle"][-1] >= 97


def test_an_empty_trace_has_no_rows(chip):
    trace = chip.trace()
    assert len(trace) == 0 and trace.variables == []


def test_pmdfmu_trace_draws_the_scope(tmp_path, capsys):
    png = tmp_path / "trace.png"
    assert main(["trace", str(EXAMPLE), "--plot", str(png), "--csv", str(tmp_path / "t.csv")]) == 0
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"
    out = capsys.readouterr().out
    assert "150 samples of time, axis1.commandedPosition" in out
    assert out.splitlines()[-2:] == [f"wrote {tmp_path / 't.csv'} (150 samples)", f"wrote {png}"]
    assert (tmp_path / "t.csv").read_text().splitlines()[1].startswith("1199,1199,8004,")


def test_pmdfmu_trace_refuses_another_plot_suffix_with_one_line(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        main(["trace", str(EXAMPLE), "--plot", str(tmp_path / "t.txt")])
    err = capsys.readouterr().err.strip()
    assert e.value.code == 2 and len(err.splitlines()) == 1 and ".html" in err


def test_the_docs_trace_example_prints_what_it_says(tmp_path, monkeypatch):
    docs = (EXAMPLE.parent.parent / "docs" / "chip.md").read_text()
    block = docs.split("## Reading the trace", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(EXAMPLE.parent.parent)
    printed = []
    code = block.replace('"trace.png"', repr(str(tmp_path / "trace.png")))
    exec(compile(code, "docs/chip.md", "exec"), {"print": lambda *a: printed.append(" ".join(map(str, a)))})
    assert printed == ["1199 8004"] and (tmp_path / "trace.png").stat().st_size > 10_000
