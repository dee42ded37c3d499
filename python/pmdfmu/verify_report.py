# SPDX-License-Identifier: BSD-2-Clause
"""What pmdfmu verify found (its results: cases, checks, failures, the exit status) and its reports: the
text a person reads, JUnit XML (GitHub Actions, GitLab, Jenkins), the Markdown summary
(GITHUB_STEP_SUMMARY) and the diff plot of a golden trace (docs/verify.md). verify.py runs the checks."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Union

import numpy as np

from . import extras, files

EXIT_PASS, EXIT_FAIL, EXIT_INPUT = 0, 1, 2

# ---- results -------------------------------------------------------------------------------------


@dataclass
class Failure:
    """One violation: what check, where (axis 1..4, column, chip cycle, row of the recording), the values
    (expected/actual for a golden, value/limit for a limit, and the peak and its cycle), where the profile
    was (segment number, position buffer and its read index) when the check is a golden's, and for a
    limit on velocity, acceleration, jerk or step what broke it: source "register" (the chip's register)
    or "position difference" (the commanded position's own change from cycle to cycle)."""

    check: str
    message: str
    axis: Optional[int] = None
    column: Optional[str] = None
    cycle: Optional[int] = None
    row: Optional[int] = None
    expected: object = None
    actual: object = None
    value: object = None
    limit: object = None
    segment: Optional[int] = None
    buffer: Optional[int] = None
    read_index: Optional[int] = None
    peak: object = None
    peak_cycle: Optional[int] = None
    source: Optional[str] = None


@dataclass
class Check:
    """One JUnit test case: the golden comparison, or one assertion of one axis."""

    name: str
    failures: List[Failure] = field(default_factory=list)
    skipped: Optional[str] = None

    @property
    def passed(self) -> bool:
        return not self.failures


@dataclass
class CaseResult:
    """One script, table or case: its checks; error is why the profile did not run (a failure too)."""

    name: str
    source: str
    cycles: int = 0
    checks: List[Check] = field(default_factory=list)
    error: Optional[str] = None
    plot: Optional[Path] = None
    actual: Optional[Path] = None
    seconds: float = 0.0
    # the run's recording and the golden, for the HTML report (verify() keeps them; a case table does not)
    recording: Optional[np.ndarray] = field(default=None, repr=False, compare=False)
    expected: Optional[np.ndarray] = field(default=None, repr=False, compare=False)

    @property
    def passed(self) -> bool:
        return self.error is None and all(c.passed for c in self.checks)

    @property
    def failures(self) -> List[Failure]:
        run = [Failure("run", self.error)] if self.error is not None else []
        return run + [f for c in self.checks for f in c.failures]


@dataclass
class VerifyResult:
    """What verify() and verify_cases() return: passed, failures, and the reports (below)."""

    cases: List[CaseResult]

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.cases)

    @property
    def failures(self) -> List[Failure]:
        return [f for c in self.cases for f in c.failures]

    @property
    def exit_status(self) -> int:
        return EXIT_PASS if self.passed else EXIT_FAIL

    def report(self, verbose: bool = False) -> str:
        return text_report(self, verbose)

    def to_junit(self) -> str:
        return junit_xml(self)

    def to_markdown(self) -> str:
        return markdown(self)

    def to_html(self, path: Union[str, Path], title: str = "pmdfmu verify") -> None:
        """Writes the interactive page (the 'html' extra): every check with its result, the first
        divergence highlighted, expected vs actual vs difference (pmdfmu.html_report)."""
        from .html_report import write_verify

        write_verify(Path(path), self, title)

    def __bool__(self) -> bool:
        return self.passed


XML_FORBIDDEN = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")


def _headline(result: VerifyResult) -> str:
    passed = sum(c.passed for c in result.cases)
    return f"pmdfmu verify: {passed} of {len(result.cases)} {'case' if len(result.cases) == 1 else 'cases'} passed"


def plural(count: int, word: str) -> str:
    """`1 check`, `2 checks`."""
    return f"{count} {word}{'' if count == 1 else 's'}"


def text_report(result: VerifyResult, verbose: bool = False) -> str:
    """What `pmdfmu verify` prints: a line per case, and under a failed one every failure (verbose: every
    check, PASS, FAIL or SKIP, under every case)."""
    lines = []
    for case in result.cases:
        checks = len(case.checks)
        if case.passed:
            lines.append(f"PASS {case.name} ({case.source}): {plural(case.cycles, 'cycle')}, {plural(checks, 'check')}")
            if verbose:
                lines += [f"  {'SKIP' if c.skipped else 'PASS'} {c.name}" for c in case.checks]
            continue
        failed = sum(not c.passed for c in case.checks)
        lines.append(
            f"FAIL {case.name} ({case.source}): "
            + (
                f"did not run: {case.error}"
                if case.error is not None
                else f"{plural(case.cycles, 'cycle')}, {failed} of {plural(checks, 'check')} failed"
            )
        )
        if verbose:
            lines += [f"  {'SKIP' if c.skipped else 'PASS'} {c.name}" for c in case.checks if c.passed]
        for check in case.checks:
            for f in check.failures:
                lines.append(f"  {check.name}: {f.message}")
        for what, path in (("diff plot", case.plot), ("this run's recording", case.actual)):
            if path:
                lines.append(f"  {what}: {path}")
    lines.append(_headline(result))
    return "\n".join(lines) + "\n"


def junit_xml(result: VerifyResult) -> str:
    """A <testsuites> of one <testsuite> per case and one <testcase> per check (the golden trace, each
    assertion of each axis); a case that did not run is one <testcase name="run"> with an <error>."""
    suites = ET.Element("testsuites", name="pmdfmu verify")
    totals = dict(tests=0, failures=0, errors=0, skipped=0)
    total_time = 0.0
    for case in result.cases:
        suite = ET.SubElement(suites, "testsuite", name=case.name)
        counts = dict(tests=0, failures=0, errors=0, skipped=0)
        classname = f"pmdfmu.verify.{case.name}"
        if case.error is not None:
            tc = ET.SubElement(suite, "testcase", classname=classname, name="run", time=f"{case.seconds:.3f}")
            ET.SubElement(
                tc, "error", message=case.error.split("\n")[0][:500], type="run"
            ).text = f"{case.source} did not run: {case.error}"
            counts["tests"] += 1
            counts["errors"] += 1
        for i, check in enumerate(case.checks):
            tc = ET.SubElement(
                suite, "testcase", classname=classname, name=check.name, time=f"{case.seconds if i == 0 else 0:.3f}"
            )
            counts["tests"] += 1
            if check.skipped:
                ET.SubElement(tc, "skipped", message=check.skipped)
                counts["skipped"] += 1
            elif check.failures:
                first = check.failures[0]
                text = "\n".join(f.message for f in check.failures)
                if case.plot and check.name == "golden trace":
                    text += f"\ndiff plot: {case.plot}"
                ET.SubElement(tc, "failure", message=first.message[:500], type=first.check).text = text
                counts["failures"] += 1
        for key, value in counts.items():
            suite.set(key, str(value))
            totals[key] += value
        suite.set("time", f"{case.seconds:.3f}")
        total_time += case.seconds
    for key, value in totals.items():
        suites.set(key, str(value))
    suites.set("time", f"{total_time:.3f}")
    ET.indent(suites) if hasattr(ET, "indent") else None
    # ElementTree writes characters XML 1.0 forbids (a script's stray control byte in a message) as they
    # are, and a CI system would reject the whole report: each becomes U+FFFD (they occur in text only)
    text = XML_FORBIDDEN.sub("\ufffd", ET.tostring(suites, encoding="unicode"))
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + text + "\n"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def markdown(result: VerifyResult) -> str:
    """A short summary: a table of the cases, then each failed case's failures."""
    lines = [
        f"### {_headline(result)}",
        "",
        "| case | result | cycles | checks passed | first failure |",
        "|---|---|---|---|---|",
    ]
    for case in result.cases:
        failures = case.failures
        verdict = "pass" if case.passed else ("**error**" if case.error is not None else "**FAIL**")
        passed = sum(c.passed and not c.skipped for c in case.checks)
        lines.append(
            f"| {_cell(case.name)} | {verdict} | {case.cycles} | {passed} of {len(case.checks)} | "
            f"{_cell(failures[0].message) if failures else ''} |"
        )
    for case in result.cases:
        if case.passed:
            continue
        lines += ["", f"#### {case.name} ({case.source})", ""]
        if case.error is not None:
            lines.append(f"- did not run: {case.error}")
        for check in case.checks:
            for f in check.failures:
                lines.append(f"- {check.name}: {f.message}")
        if case.plot:
            lines.append(f"- diff plot: `{case.plot}`")
        if case.actual:
            lines.append(
                f"- this run's recording: `{case.actual}` (copy it over the golden trace to accept the change)"
            )
    return "\n".join(lines) + "\n"


def plot_diff(
    path: Path,
    expected: np.ndarray,
    actual: np.ndarray,
    failures: Sequence[Failure],
    cycle_time: float,
    title: str = "pmdfmu verify",
) -> None:
    """Per differing column (at most 4, the first diverging first): expected and actual over the row,
    and actual - expected; a line at the first diverging row."""
    plt = extras.pyplot("the verify report plot")

    first = next((f for f in failures if f.column and f.row is not None and f.check == "golden"), None)
    n = min(len(expected), len(actual))
    columns: List[str] = [first.column] if first else []
    for c in expected.dtype.names:
        if (
            c in actual.dtype.names
            and c not in columns
            and c != "cycle"
            and len(columns) < 4
            and n
            and np.any(expected[c][:n].astype(np.float64) != actual[c][:n].astype(np.float64))
        ):
            columns.append(c)
    if not columns:  # only the length or the columns differ: show the positions
        columns = [c for c in expected.dtype.names if c.endswith(".commandedPosition") and c in actual.dtype.names][:2]
    fig, grid = plt.subplots(max(1, len(columns)), 2, figsize=(13, 3.2 * max(1, len(columns))), squeeze=False)
    for (left, right), c in zip(grid, columns):
        left.plot(np.arange(len(expected)), expected[c], label="expected (golden)", color="tab:blue")
        left.plot(np.arange(len(actual)), actual[c], label="actual", color="tab:orange", linestyle="--")
        left.set_ylabel(c)
        left.legend(fontsize="small")
        diff = actual[c][:n].astype(np.float64) - expected[c][:n].astype(np.float64)
        right.plot(np.arange(n), diff, color="tab:red")
        right.set_ylabel("difference (actual - expected)")
        for panel in (left, right):
            panel.set_xlabel("row (cycles since the recording's first)")
            if first:
                panel.axvline(first.row, color="grey", linestyle=":", linewidth=1)
    if first:
        title += f"\nfirst difference: cycle {first.cycle}, {first.column}"
    fig.suptitle(title)
    fig.tight_layout()
    with files.replaced(path) as f:
        fig.savefig(f, format="png", dpi=90)
    plt.close(fig)
