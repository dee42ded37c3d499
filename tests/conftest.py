# SPDX-License-Identifier: BSD-2-Clause
"""Where shared test code lives. tests/ holds three kinds of file:

- test_*.py: the tests. A test file never imports another test file (nor this
  one): whatever two test files share lives in one of the two places below, so
  that a test file can be read, run or deleted on its own.
- conftest.py, this file: the fixtures, which pytest hands to any test that names
  them as an argument (chip, any_chip, cases, serial). Nothing imports it.
- helper modules: plain Python with no tests in it, imported by name (pytest puts
  tests/ on sys.path): reference.py, the exact reference model of seed 000 written
  independently of the C core; states.py, work below the Chip API (FMU states as
  bytes, raw host words, pending batches, an instance left in initialization);
  scenarios.py, chip set-ups several test files run (a busy chip, seed 000's
  worked example, random external profiles); stepwise.py, the oracles of the
  recording and upload paths; interrupted.py, runs to interrupt; cmotion_build.py,
  the C library's build; reference_fmus.py, Reference-FMUs built to compare a tool's
  defect with (tests/README.md maps every topic to its files).

Fixtures for what a test receives ready-made, helper modules for what it calls or
compares with: test_suite_layout.py checks the rule.
"""

from pathlib import Path

import pytest

import pmdfmu

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


@pytest.fixture
def chip():
    with pmdfmu.Chip() as c:
        yield c


@pytest.fixture(params=[2, 3], ids=["fmi2", "fmi3"])
def any_chip(request):
    """A chip through each FMI version: the behaviour must not depend on it."""
    with pmdfmu.Chip(fmi_version=request.param) as c:
        yield c


@pytest.fixture(scope="session")
def cases():
    """examples/cases.csv, the sweep's example case table (test_sweep*.py)."""
    return pmdfmu.read_cases(EXAMPLES / "cases.csv")


@pytest.fixture(scope="session")
def serial(cases):
    """examples/cases.csv swept in this process: what every scheduler must equal."""
    return pmdfmu.sweep(cases, scheduler="serial")
