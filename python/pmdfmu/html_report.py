# SPDX-License-Identifier: BSD-2-Clause
"""Pages a person opens in the browser: `pmdfmu run --html`, `pmdfmu verify --html` and `pmdfmu trace
--plot X.html` write one self-contained page each (Plotly, its JavaScript inline: it opens offline, as
a CI artifact). Zoom and pan on every panel; every recorded column with its unit; the profile's segments
marked; for verify, expected vs actual vs difference, each check with its result and the first
divergence highlighted. Long runs are decimated for display only (a min/max per bucket keeps every peak);
the checks always read every cycle. docs/verify.md, "HTML reports"."""

from __future__ import annotations

import html
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import extras, files
from .calls import CONSTANTS, FIELDS
from .units import UNITS, unit

# points per drawn line: a long run shows as its min and max per bucket (every peak, every step)
DISPLAY_POINTS = 4000
MAX_MARKS = 200  # segment marks drawn; a table of thousands of rows marks its first ones

# the activity status's fields whose change marks a segment: the profile mode and the profile segment
SEGMENT_FIELDS = CONSTANTS["PMDActivityProfileModeMask"] | CONSTANTS["PMDActivityProfileSegmentMask"]
SEGMENT_SHIFT = FIELDS["PMDActivityProfileSegment"].shift

STYLE = """
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.3em; } h2 { font-size: 1.1em; margin-top: 1.5em; }
table { border-collapse: collapse; margin: 0.5em 0; font-size: 0.9em; }
td, th { border: 1px solid #ccc; padding: 0.2em 0.6em; text-align: left; vertical-align: top; }
.PASS { color: #14722c; font-weight: bold; } .FAIL { color: #b00020; font-weight: bold; }
.SKIP { color: #777; font-weight: bold; }
tr.first-divergence { background: #ffe3e3; }
.note { color: #555; font-size: 0.85em; }
"""


def _plotly(what: str):
    go = extras.require("plotly.graph_objects", "html", what)
    subplots = extras.require("plotly.subplots", "html", what)
    return go, subplots


def decimate(n: int, values: Sequence[np.ndarray], points: int = DISPLAY_POINTS) -> np.ndarray:
    """The rows of n to draw: all of them when few; else the first and last and, per bucket, the rows of
    each column's minimum and maximum, so that no peak and no step is lost to the eye."""
    if n <= points:
        return np.arange(n)
    buckets = max(points // (2 * max(len(values), 1)), 1)
    edges = np.linspace(0, n, buckets + 1).astype(np.int64)
    keep = [np.array([0, n - 1])]
    for v in values:
        v = np.asarray(v, dtype=np.float64)
        starts = edges[:-1]
        keep.append(starts + np.array([np.argmin(v[a:b]) for a, b in zip(edges[:-1], edges[1:])]))
        keep.append(starts + np.array([np.argmax(v[a:b]) for a, b in zip(edges[:-1], edges[1:])]))
    return np.unique(np.concatenate(keep))


def segment_marks(recording: np.ndarray) -> List[Tuple[int, str]]:
    """Where the profile changes segment: each cycle an axis's activity status changes its profile mode or
    profile segment field, with a label (`axis1 segment 3`)."""
    marks = []
    for name in recording.dtype.names:
        if not name.endswith(".activityStatus"):
            continue
        fields = recording[name].astype(np.int64) & SEGMENT_FIELDS
        for row in np.flatnonzero(np.diff(fields)) + 1:
            segment = int(fields[row]) >> SEGMENT_SHIFT
            marks.append((int(recording["cycle"][row]), f"{name.partition('.')[0]} segment {segment}"))
    return sorted(marks)[:MAX_MARKS]


def _axis_quantities(names: Sequence[str]) -> Dict[str, List[str]]:
    """Columns grouped by quantity (`commandedPosition`: axis1's and axis2's), in recording order."""
    groups: Dict[str, List[str]] = {}
    for name in names:
        if name == "cycle":
            continue
        groups.setdefault(name.rpartition(".")[2], []).append(name)
    return groups


def _mark(fig, cycle: int, text: str, color: str, dash: str = "dot") -> None:
    fig.add_vline(x=cycle, line_width=1, line_dash=dash, line_color=color, opacity=0.7)
    fig.add_annotation(
        x=cycle,
        y=1,
        yref="paper",
        text=text,
        showarrow=False,
        font={"size": 9, "color": color},
        xanchor="left",
        yanchor="bottom",
        textangle=-30,
    )


def run_figure(recording: np.ndarray, title: str, marks: Optional[List[Tuple[int, str]]] = None):
    """A recording as panels, one per quantity (each axis a line), over chip time, segments marked."""
    go, subplots = _plotly("the HTML report")
    groups = _axis_quantities(recording.dtype.names)
    fig = subplots.make_subplots(rows=max(len(groups), 1), cols=1, shared_xaxes=True, vertical_spacing=0.02)
    rows = decimate(len(recording), [recording[c] for cs in groups.values() for c in cs])
    x = recording["cycle"][rows]
    for i, (quantity, columns) in enumerate(groups.items(), 1):
        for c in columns:
            fig.add_trace(
                go.Scatter(x=x, y=recording[c][rows], name=c, mode="lines", line={"width": 1.3}), row=i, col=1
            )
        fig.update_yaxes(title_text=f"{quantity}<br>[{UNITS.get(quantity, '')}]", title_font={"size": 10}, row=i, col=1)
    for cycle, text in marks if marks is not None else segment_marks(recording):
        _mark(fig, cycle, text, "#888")
    fig.update_xaxes(title_text="chip time [cycles]", row=max(len(groups), 1), col=1)
    fig.update_layout(title=title, height=180 * max(len(groups), 1) + 160, hovermode="x unified")
    return fig


def diff_figure(actual: np.ndarray, expected: np.ndarray, title: str, first: Optional[int]):
    """Expected (dashed) vs actual per golden column, and every differing column's actual - expected in
    a last panel; first: the cycle of the first divergence, marked in red."""
    go, subplots = _plotly("the HTML report")
    columns = [c for c in expected.dtype.names if c != "cycle" and c in (actual.dtype.names or ())]
    cycles = np.intersect1d(actual["cycle"], expected["cycle"])
    a = actual[np.isin(actual["cycle"], cycles)]
    e = expected[np.isin(expected["cycle"], cycles)]
    differing = [c for c in columns if np.any(a[c].astype(np.float64) != e[c].astype(np.float64))]
    n = len(columns) + 1
    fig = subplots.make_subplots(rows=n, cols=1, shared_xaxes=True, vertical_spacing=0.015)
    ra = decimate(len(actual), [actual[c] for c in columns])
    re_ = decimate(len(expected), [expected[c] for c in columns])
    for i, c in enumerate(columns, 1):
        fig.add_trace(
            go.Scatter(
                x=expected["cycle"][re_],
                y=expected[c][re_],
                name=f"{c} expected",
                mode="lines",
                line={"width": 2, "dash": "dash", "color": "#999"},
            ),
            row=i,
            col=1,
        )
        fig.add_trace(
            go.Scatter(x=actual["cycle"][ra], y=actual[c][ra], name=f"{c} actual", mode="lines", line={"width": 1.2}),
            row=i,
            col=1,
        )
        fig.update_yaxes(title_text=f"{c}<br>[{unit(c)}]", title_font={"size": 9}, row=i, col=1)
    diffs = {c: a[c].astype(np.float64) - e[c].astype(np.float64) for c in differing}
    rd = decimate(len(cycles), list(diffs.values()))
    for c, d in diffs.items():
        fig.add_trace(go.Scatter(x=cycles[rd], y=d[rd], name=f"{c} actual - expected", mode="lines"), row=n, col=1)
    fig.update_yaxes(
        title_text="actual - expected" if differing else "no difference", title_font={"size": 9}, row=n, col=1
    )
    for cycle, text in segment_marks(actual):
        _mark(fig, cycle, text, "#888")
    if first is not None:
        _mark(fig, first, "first divergence", "#d00000", dash="solid")
    fig.update_xaxes(title_text="chip time [cycles]", row=n, col=1)
    fig.update_layout(title=title, height=140 * n + 180, hovermode="x unified")
    return fig


def _page(title: str, parts: List[str]) -> str:
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>{html.escape(title)}</title><style>{STYLE}</style></head><body>\n"
        f"<h1>{html.escape(title)}</h1>\n" + "\n".join(parts) + "\n</body></html>\n"
    )


def _figures(figures) -> List[str]:
    """Each figure's div; plotly.js inline once, with the first (no network: the page opens offline)."""
    return [
        f.to_html(full_html=False, include_plotlyjs=(i == 0), config={"scrollZoom": True, "displaylogo": False})
        for i, f in enumerate(figures)
    ]


def _write(path: Path, text: str) -> None:
    with files.replaced(Path(path), text=True) as f:
        f.write(text)


def _shown(n: int, total: int) -> str:
    return (
        f'<p class="note">{total} cycles; drawn: {n} points per line (the minimum and maximum of each stretch, '
        "for display only: every check reads every cycle). Drag to zoom, shift-drag or scroll to pan, "
        "double-click to reset.</p>"
        if n < total
        else f'<p class="note">{total} cycles. Drag to zoom, scroll to pan, double-click to reset.</p>'
    )


def write_run(path: Path, recording: np.ndarray, title: str, cycle_time: float, note: str = "") -> None:
    """`pmdfmu run --html`: the recording's every column, each quantity a panel, the segments marked."""
    columns = [c for c in recording.dtype.names if c != "cycle"]
    table = "".join(f"<tr><td>{html.escape(c)}</td><td>{html.escape(unit(c))}</td></tr>" for c in columns)
    shown = len(decimate(len(recording), [recording[c] for c in columns]))
    parts = [
        f"<p>{html.escape(note)} Chip cycle time {cycle_time:g} s.</p>"
        if note
        else f"<p>Chip cycle time {cycle_time:g} s.</p>",
        _shown(shown, len(recording)),
        *_figures([run_figure(recording, title)]),
        f"<h2>Recorded columns</h2><table><tr><th>column</th><th>unit</th></tr>{table}</table>",
    ]
    _write(path, _page(title, parts))


def write_trace(path: Path, trace, title: str) -> None:
    """Trace.plot to a .html name: the scope, one panel per variable, the trigger marked."""
    go, subplots = _plotly("Trace.plot")
    names = trace.panels
    fig = subplots.make_subplots(rows=max(len(names), 1), cols=1, shared_xaxes=True, vertical_spacing=0.03)
    x = trace.samples["cycle"]
    for i, name in enumerate(names, 1):
        scale, shown_unit = trace.scales.get(name, (1.0, trace.units[name]))
        fig.add_trace(go.Scatter(x=x, y=trace.samples[name] * scale, name=name, mode="lines"), row=i, col=1)
        fig.update_yaxes(title_text=f"{name}<br>[{shown_unit}]", title_font={"size": 10}, row=i, col=1)
    if trace.trigger is not None and len(x):
        _mark(fig, int(x[trace.trigger]), "trigger", "#d00000", dash="dash")
    fig.update_xaxes(
        title_text="chip time [cycles]" if trace.chip_time else "cycles since the first sample",
        row=max(len(names), 1),
        col=1,
    )
    fig.update_layout(title=title, height=200 * max(len(names), 1) + 160, hovermode="x unified")
    summary = (
        f"<p>{len(trace)} samples, every {trace.period} cycles, {trace.mode}"
        + (", wrapped" if trace.wrapped else "")
        + (", running" if trace.running else "")
        + ".</p>"
    )
    _write(path, _page(title, [summary, *_figures([fig])]))


def _first_divergence(case) -> Optional[int]:
    """The cycle of the case's first golden failure (the first diverging row)."""
    cycles = [f.cycle for c in case.checks for f in c.failures if f.check == "golden" and f.cycle is not None]
    return min(cycles) if cycles else None


def write_verify(path: Path, result, title: str = "pmdfmu verify") -> None:
    """`pmdfmu verify --html`: per case, every check with its result and its failures (the first
    divergence's row highlighted), and the recording against the golden (expected, actual, difference)."""
    parts = [f'<p class="{"PASS" if result.passed else "FAIL"}">{html.escape(result.report().splitlines()[-1])}</p>']
    figures = []
    for case in result.cases:
        status = "PASS" if case.passed else "FAIL"
        parts.append(
            f'<h2><span class="{status}">{status}</span> {html.escape(case.name)} '
            f"({html.escape(case.source)}): {case.cycles} cycles</h2>"
        )
        if case.error is not None:
            parts.append(f'<p class="FAIL">did not run: {html.escape(case.error)}</p>')
        first = _first_divergence(case)
        rows = []
        for check in case.checks:
            result_word = "SKIP" if check.skipped else "PASS" if check.passed else "FAIL"
            detail = (
                html.escape(check.skipped or "")
                if check.passed
                else "<br>".join(html.escape(f.message) for f in check.failures)
            )
            first_row = first is not None and any(f.cycle == first and f.check == "golden" for f in check.failures)
            highlight = ' class="first-divergence"' if first_row else ""
            rows.append(
                f'<tr{highlight}><td class="{result_word}">{result_word}</td>'
                f"<td>{html.escape(check.name)}</td><td>{detail}</td></tr>"
            )
        parts.append(
            "<table><tr><th>result</th><th>check</th><th>what was found</th></tr>" + "".join(rows) + "</table>"
        )
        if first is not None:
            parts.append(f'<p class="FAIL">First divergence at chip cycle {first} (the red line).</p>')
        if case.recording is not None:
            parts.append(f'<div class="case-plot">{{figure{len(figures)}}}</div>')
            if case.expected is not None:
                figures.append(diff_figure(case.recording, case.expected, f"{case.name}: expected vs actual", first))
            else:
                figures.append(run_figure(case.recording, f"{case.name}: the run"))
        else:
            parts.append('<p class="note">The profile did not run: nothing recorded.</p>')
    divs = _figures(figures)
    text = "\n".join(parts)
    for i, div in enumerate(divs):
        text = text.replace(f"{{figure{i}}}", div, 1)
    _write(path, _page(title, [text]))
