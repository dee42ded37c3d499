# SPDX-License-Identifier: BSD-2-Clause
"""A quiet run (pmd_chip_run_every_cycle in fmu_src/chip/chip.c) leaves out the per-cycle work
that cannot happen while no axis is geared, no breakpoint is armed, no trace runs
or waits and no switch is active. Pinned here: the same runs with a
breakpoint armed that never fires, which makes every cycle do all of its checks,
give the same outputs at every cycle, through FMI 2 cycle by cycle and through
FMI 3's bulk recording."""

import random

import numpy as np
import pytest

import pmdfmu
from scenarios import REAL, load_random_profiles

STATUS = [
    f"axis{n}.{q}"
    for n in range(1, 5)
    for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration", "activityStatus", "eventStatus")
]
BULK = [
    f"axis{n}.{q}" for n in range(1, 5) for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration")
]


def never_fires(chip):
    """A breakpoint on chip time 2^31 - 1: armed all run long, never reached."""
    ax = chip.axis(3)
    ax.SetBreakpointValue(0, 2**31 - 1)
    ax.SetBreakpoint(0, 3, pmdfmu.PMDBreakpointNoAction, pmdfmu.PMDBreakpointTime)


def mixed(chip, seed):
    """External profiles with short and long segments on axes 1-3 (velocities coming
    to rest: events), then every other mode in turn on axis 4 and a motor turned off."""
    load_random_profiles(chip, random.Random(seed), long=(1, 60))
    ax = chip.axis(0)
    ax.SetMotionCompleteMode(pmdfmu.PMDMotionCompleteActualPosition)
    ax.SetSettleTime(3)
    ax.SetSettleWindow(2)
    a4 = chip.axis(3)
    a4.SetPosition(2500)
    a4.SetVelocity(0x30000)
    a4.SetAcceleration(0x1000)
    a4.Update()


def run(chip, cycles, names, chunk=97):
    return np.concatenate([chip.run(chunk, record=names) for _ in range(cycles // chunk)])


def servo(chip):
    """What the outputs do not show: actual positions, velocities, errors."""
    return [
        (chip.axis(n).GetActualPosition(), chip.axis(n).GetActualVelocity(), chip.axis(n).GetPositionError())
        for n in range(4)
    ]


@pytest.mark.parametrize("seed", range(3))
def test_quiet_runs_equal_fully_checked_runs_cycle_by_cycle(seed):
    runs = []
    for armed in (False, True):
        with pmdfmu.Chip() as chip:
            mixed(chip, seed)
            if armed:
                never_fires(chip)
            rec = run(chip, 2910, STATUS + REAL)
            chip.axis(3).SetProfileMode(pmdfmu.PMDVelocityContouringProfile)
            chip.axis(3).SetVelocity(-0x8000)
            chip.axis(3).Update()
            chip.axis(2).SetMotorMode(0)  # motor off: the actual position holds
            runs.append((np.concatenate([rec, run(chip, 1940, STATUS + REAL)]), servo(chip)))
    assert np.array_equal(runs[0][0], runs[1][0]) and runs[0][1] == runs[1][1]


def test_quiet_bulk_recording_equals_fully_checked_bulk_recording():
    runs = []
    for armed in (False, True):
        with pmdfmu.Chip(fmi_version=3, **{"record.capacity": 1000}) as chip:
            mixed(chip, 7)
            if armed:
                never_fires(chip)
            runs.append(chip.run(4000, record=BULK))
            runs.append([chip.get(n) for n in STATUS + ["chipTime"]] + servo(chip))
    assert np.array_equal(runs[0], runs[2]) and runs[1] == runs[3]


def test_without_loopback_quiet_runs_follow_the_encoder_like_fully_checked_runs():
    """The plant follows each axis a chunk late: position errors, a motion error
    (axis 2, auto-stop: motor off), settling inside the window once at rest."""
    runs = []
    for armed in (False, True):
        with pmdfmu.Chip(loopback=False) as chip:
            mixed(chip, 11)
            chip.axis(1).SetPositionErrorLimit(3000)
            chip.axis(1).SetAutoStopMode(1)
            for n in range(4):
                chip.axis(n).SetSettleWindow(5)
            if armed:
                never_fires(chip)
            parts = []
            for _ in range(60):
                for n in range(4):
                    chip.set(f"axis{n + 1}.actualPosition", chip.axis(n).GetCommandedPosition())
                parts.append(chip.run(25, record=STATUS + REAL))
            runs.append((np.concatenate(parts), servo(chip)))
    assert np.array_equal(runs[0][0], runs[1][0]) and runs[0][1] == runs[1][1]
    events = runs[0][0]["axis2.eventStatus"] | runs[0][0]["axis4.eventStatus"]
    assert events[-1] & pmdfmu.PMDEventMotionErrorMask and events[-1] & pmdfmu.PMDEventMotionCompleteMask
