# SPDX-License-Identifier: BSD-2-Clause
"""Seed 000's worked table, chip times 11003..11013, out of the FMU cycle by cycle."""

import pmdfmu
from scenarios import WORKED_TABLE, run_worked_example


def test_worked_table_comes_out_cycle_by_cycle(any_chip):
    rows = run_worked_example(any_chip)
    got = [(int(r["cycle"]), int(r["axis1.commandedPosition"]), int(r["axis1.commandedVelocity"])) for r in rows]
    assert got == WORKED_TABLE
    assert (rows["axis1.commandedAcceleration"] == 0).all()
    # ProfileSegment = 1 throughout: the second row (time 15) is still running at 11013
    assert all(pmdfmu.field_ex(r, "PMDActivityProfileSegment") == 1 for r in rows["axis1.activityStatus"])


def test_velocity_1_0_is_10000h():
    assert pmdfmu.fixed_16_16(1.0) == 0x10000
