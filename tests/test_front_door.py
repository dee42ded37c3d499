# SPDX-License-Identifier: BSD-2-Clause
"""What a new user sees first: `pmdfmu info` with descriptions and units (as `fmpy info`), the demo saying
what it shows and ending on the table's positions, and a sweep's summary plot that keeps coinciding cases
apart and shows seconds when the cases' cycle times differ."""

import numpy as np
import pytest

import pmdfmu
from pmdfmu.cli import main
from pmdfmu.sweep import SweepResult


def test_info_shows_each_variables_unit_and_description(capsys):
    assert main(["info"]) == 0
    lines = capsys.readouterr().out.splitlines()
    velocity = next(line for line in lines if " axis1.commandedVelocity " in line)
    assert "raw 16.16 counts/cycle" in velocity and "GetCommandedVelocity" in velocity
    assert any(" cycleTime " in line and "0.0001" in line and " s " in line for line in lines)


def test_info_shows_the_plants_declared_units(capsys):
    assert main(["info", str(pmdfmu.default_fmu(2).with_name("pmdplant-fmi2.fmu"))]) == 0
    assert any(" supplyVoltage " in line and " V " in line for line in capsys.readouterr().out.splitlines())


def test_the_demo_says_what_it_shows_and_ends_on_the_tables_positions(tmp_path, capsys):
    assert main(["demo", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "trace a circle" in out and "first move to the first row (20000, 0)" in out
    assert "axis 1: ended at position 20000 after 16385 cycles (as the table's last row, 20000)" in out
    assert "(as the table's last row, 10)" in out


def sweep_result(cycle_times):
    """Three cases that coincide: the same recording."""
    rec = np.zeros(500, dtype=[("cycle", "i8"), ("axis1.position", "f8")])
    rec["cycle"] = np.arange(500) + 100
    rec["axis1.position"] = np.linspace(0, 1000, 500)
    rows = [
        {"name": n, "status": "ok", **{f"axis{k}.peakVelocity": 10.0 for k in range(1, 5)}} for n in ("a", "b", "c")
    ]
    return SweepResult(rows, {n: rec for n in "abc"}, dict(zip("abc", cycle_times)))


@pytest.mark.parametrize("cycle_times,label", [((1e-4,) * 3, "cycles"), ((1e-4, 2e-4, 5e-5), "time [s]")])
def test_the_sweep_plot_keeps_coinciding_cases_apart(tmp_path, monkeypatch, cycle_times, label):
    plt = pytest.importorskip("matplotlib.pyplot")
    figures = []
    monkeypatch.setattr(plt, "close", lambda fig: figures.append(fig))
    sweep_result(cycle_times).plot(tmp_path / "summary.png")
    top = figures[0].axes[0]
    lines = top.get_lines()
    assert len({(line.get_linestyle(), line.get_marker()) for line in lines}) == 3  # each its own style
    assert top.get_xlabel() == label
    if label == "time [s]":
        assert lines[1].get_xdata()[-1] == pytest.approx(499 * 2e-4)
