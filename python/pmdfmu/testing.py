# SPDX-License-Identifier: BSD-2-Clause
"""A team's own tests on pmdfmu runs, in one line (docs/verify.md):

    from pmdfmu.testing import assert_trajectory

    def test_pick_and_place():
        assert_trajectory("profiles/pick.script", against="profiles/pick.golden.npz",
                          assertions="profiles/limits.toml")

raises AssertionError with the readable report (first diverging cycle and column, each violation's
axis, cycle, value and limit) when the run fails any check."""

from __future__ import annotations

from .verify import VerifyResult, verify


def assert_trajectory(source, against=None, assertions=None, tolerance=None, **kwargs) -> VerifyResult:
    """pmdfmu.verify(source, against, assertions, tolerance, **kwargs); AssertionError with its report if it
    fails. Returns the result (its recording-free details: result.cases[0].checks)."""
    __tracebackhide__ = True  # pytest shows the report, not this frame
    result = verify(source, against, assertions, tolerance, **kwargs)
    if not result.passed:
        raise AssertionError("\n" + result.report())
    return result
