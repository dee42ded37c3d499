# SPDX-License-Identifier: BSD-2-Clause
"""`pmdfmu run --html`, `pmdfmu verify --html` and `pmdfmu trace --plot X.html`: one self-contained page
each, opened offline in headless Chromium (tests/browser.py), which must show no console error, request
nothing from the network, and draw every plot (docs/verify.md, "HTML reports")."""

from pathlib import Path

import numpy as np
import pytest

from browser import open_page, require_chromium
from pmdfmu import html_report
from pmdfmu.verify import read_recording, write_recording
from pmdfmu.cli import main

pytestmark = pytest.mark.slow  # tests/README.md: runs the CLI and a browser

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def check_page(path, tmp_path, plots):
    """The page in Chromium: no error, no request, `plots` plots each with points drawn; its screenshot."""
    require_chromium()
    page = open_page(path, tmp_path / (path.stem + ".png"))
    assert page.errors == []
    assert page.requests == []  # offline: plotly.js is inline
    assert len(page.plots) == plots and all(p["points"] > 0 and p["drawn"] > 0 for p in page.plots), page.plots
    assert (tmp_path / (path.stem + ".png")).stat().st_size > 20_000  # a screenshot with something on it
    return page


def test_a_run_report_shows_every_recorded_column_with_its_unit(tmp_path):
    page_path = tmp_path / "run.html"
    assert main(["run", str(EXAMPLES / "square.csv"), "--html", str(page_path)]) == 0
    text = page_path.read_text()
    assert "<script src=" not in text  # the browser below sees no request either
    page = check_page(page_path, tmp_path, plots=1)
    for column in ("axis1.commandedVelocity", "axis2.acceleration", "axis1.activityStatus"):
        assert column in page.text
    assert "raw 16.16 counts/cycle" in page.text and "counts/s^2" in page.text


def test_a_failed_verify_report_shows_each_check_and_highlights_the_first_divergence(tmp_path):
    golden = read_recording(EXAMPLES / "ci" / "two_axis.golden.npz")
    golden["axis1.commandedPosition"][1500:] += 1  # one count off from cycle 1500 on
    write_recording(tmp_path / "golden.npz", golden)
    page_path = tmp_path / "verify.html"
    args = ["verify", str(EXAMPLES / "two_axis.script"), "--against", str(tmp_path / "golden.npz")]
    assert main(args + ["--max-velocity", "all=1e9", "--html", str(page_path), "--out", str(tmp_path)]) == 1
    page = check_page(page_path, tmp_path, plots=1)
    assert "First divergence at chip cycle 1500" in page.text
    assert page.text.count("PASS") >= 2 and "FAIL" in page.text
    assert page_path.read_text().count('class="first-divergence"') == 1


def test_a_passed_verify_report_and_a_trace_page_open(tmp_path):
    page_path = tmp_path / "pass.html"
    args = ["verify", str(EXAMPLES / "two_axis.script"), "--against", str(EXAMPLES / "ci" / "two_axis.golden.npz")]
    assert main(args + ["--html", str(page_path)]) == 0
    check_page(page_path, tmp_path, plots=1)
    trace_path = tmp_path / "trace.html"
    assert main(["trace", str(EXAMPLES / "trace_breakpoint.script"), "--plot", str(trace_path)]) == 0
    assert "trigger" in check_page(trace_path, tmp_path, plots=1).text


def test_a_case_tables_report_plots_every_case(tmp_path):
    page_path = tmp_path / "cases.html"
    args = ["verify", "--cases", str(EXAMPLES / "ci" / "cases.csv"), "--scheduler", "serial"]
    assert main(args + ["--html", str(page_path), "--out", str(tmp_path)]) == 0
    page = check_page(page_path, tmp_path, plots=4)
    assert page.text.count("PASS") >= 4


def test_a_long_run_is_decimated_for_display_only_and_keeps_every_peak():
    rng = np.random.default_rng(1)
    values = np.cumsum(rng.integers(-5, 6, 1_000_000))
    values[777_777] = 10**9  # a one-cycle spike
    rows = html_report.decimate(len(values), [values])
    assert len(rows) <= html_report.DISPLAY_POINTS + 2
    assert 777_777 in rows and values[rows].min() == values.min() and values[rows].max() == values.max()


def test_a_long_run_report_stays_small(tmp_path):
    recording = np.zeros(500_000, dtype=[("cycle", "i8"), ("axis1.commandedPosition", "i4")])
    recording["cycle"] = np.arange(len(recording))
    recording["axis1.commandedPosition"] = np.arange(len(recording)) % 1000
    html_report.write_run(tmp_path / "long.html", recording, "long", 1e-4)
    assert (tmp_path / "long.html").stat().st_size < 6_000_000


def test_html_wants_an_html_name_with_one_line(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        main(["run", str(EXAMPLES / "square.csv"), "--html", str(tmp_path / "r.png")])
    err = capsys.readouterr().err.strip()
    assert e.value.code == 2 and len(err.splitlines()) == 1 and ".html" in err


def test_html_without_plotly_names_the_extra_in_one_line(tmp_path, capsys, monkeypatch):
    import importlib

    real = importlib.import_module

    def without_plotly(name, *args, **kwargs):
        if name.startswith("plotly"):
            raise ImportError(f"No module named {name!r}")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(importlib, "import_module", without_plotly)
    assert main(["run", str(EXAMPLES / "square.csv"), "--html", str(tmp_path / "r.html")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "pip install 'pmdfmu[html]'" in err and not (tmp_path / "r.html").exists()
