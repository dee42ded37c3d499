# SPDX-License-Identifier: BSD-2-Clause
"""Trapezoidal point-to-point moves (seed 001; seed 000 1.4's initial move)."""

import random

import numpy as np
import pytest

import pmdfmu
from pmdfmu import (
    PMDActivityAtMaximumVelocityMask,
    PMDActivityInMotionMask,
    PMDError,
    PMDEventMotionCompleteMask,
    PMDTrapezoidal,
)

NAMES = [
    "axis1.commandedPosition",
    "axis1.commandedVelocity",
    "axis1.commandedAcceleration",
    "axis1.activityStatus",
    "axis1.position",
]


def move(chip, position, velocity, acceleration, deceleration=0, max_cycles=200_000):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDTrapezoidal)
    ax.SetPosition(position)
    ax.SetVelocity(velocity)
    ax.SetAcceleration(acceleration)
    ax.SetDeceleration(deceleration)
    ax.Update()
    parts = []
    while True:
        rec = chip.run(2000, record=NAMES)
        parts.append(rec)
        if not rec["axis1.activityStatus"][-1] & PMDActivityInMotionMask or sum(map(len, parts)) > max_cycles:
            return np.concatenate(parts)


def check_limits(rec, start_velocity, vmax, acc, dec):
    v = np.concatenate([[start_velocity], rec["axis1.commandedVelocity"]]).astype(np.int64)
    assert (np.abs(v) <= vmax).all(), "maximum velocity exceeded"
    dv = np.diff(v)
    speeding = np.abs(v[1:]) > np.abs(v[:-1])
    assert (np.abs(dv[speeding]) <= acc).all(), "acceleration exceeded"
    assert (np.abs(dv[~speeding]) <= max(dec, acc if dec == 0 else dec)).all(), "deceleration exceeded"
    assert (rec["axis1.commandedAcceleration"] == dv).all()


@pytest.mark.parametrize("seed", range(12))
def test_moves_end_exactly_at_the_destination_at_rest_within_limits(chip, seed):
    rng = random.Random(seed)
    start = rng.randrange(-100_000, 100_000)
    if start:
        move(chip, start, 0x80000, 0x8000)
    dest = start + rng.choice([1, -1]) * rng.randrange(0, 200_000)
    vmax = rng.randrange(1, 0x100000)
    acc = rng.randrange(1, 0x20000)
    dec = rng.choice([0, rng.randrange(1, 0x20000)])
    rec = move(chip, dest, vmax, acc, dec)
    ax = chip.axis(0)
    assert ax.GetCommandedPosition() == dest
    assert chip.get("axis1.position") == dest  # no fraction left over
    assert ax.GetCommandedVelocity() == 0 and ax.GetCommandedAcceleration() == 0
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask
    check_limits(rec, 0, vmax, acc, dec)
    positions = rec["axis1.position"]
    direction = np.sign(dest - start)
    assert (np.diff(positions) * direction >= 0).all(), "a move from rest never goes back"


def test_deceleration_0_uses_the_acceleration():
    outs = []
    for dec in (0, 0x3000):
        with pmdfmu.Chip() as chip:
            outs.append(move(chip, 50_000, 0x50000, 0x3000, dec))
    assert np.array_equal(outs[0], outs[1])


def test_a_short_move_never_reaches_maximum_velocity_and_a_long_one_cruises(chip):
    rec = move(chip, 100, 0x100000, 0x1000)
    assert not (rec["axis1.activityStatus"] & PMDActivityAtMaximumVelocityMask).any()
    rec = move(chip, 100_000, 0x20000, 0x1000)
    at_max = (rec["axis1.activityStatus"] & PMDActivityAtMaximumVelocityMask) != 0
    assert at_max.any()
    assert (rec["axis1.commandedVelocity"][at_max] == 0x20000).all()


def test_duration_is_close_to_the_continuous_optimum(chip):
    d, v, a = 100_000, 0x40000, 0x800  # 4 counts/cycle, 1/32 counts/cycle^2
    rec = move(chip, d, v, a)
    vc, ac = v / 65536, a / 65536
    optimum = d / vc + vc / ac
    cycles = int(np.argmax((rec["axis1.activityStatus"] & PMDActivityInMotionMask) == 0)) + 1
    assert optimum <= cycles <= optimum + 3


def test_negative_velocity_in_trapezoidal_mode_is_refused_with_0x0b(chip):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDTrapezoidal)
    ax.SetVelocity(-5)
    ax.SetAcceleration(100)
    ax.SetPosition(1000)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0B
    chip.run(10)
    assert ax.GetCommandedPosition() == 0 and not ax.GetActivityStatus() & PMDActivityInMotionMask


def test_get_returns_the_buffered_register_until_update(chip):
    ax = chip.axis(0)
    ax.SetPosition(777)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x100)
    assert (ax.GetPosition(), ax.GetVelocity(), ax.GetAcceleration()) == (777, 0x10000, 0x100)
    chip.run(100)
    assert ax.GetCommandedPosition() == 0  # nothing moves before Update
    ax.Update()
    chip.run(1)
    assert ax.GetCommandedVelocity() == 0x100


def test_abrupt_and_smooth_stop_in_trapezoidal_mode(chip):
    ax = chip.axis(0)
    ax.SetPosition(1_000_000)
    ax.SetVelocity(0x80000)
    ax.SetAcceleration(0x2000)
    ax.Update()
    chip.run(300)
    ax.SetStopMode(pmdfmu.PMDSmoothStop)
    ax.Update()
    rec = chip.run(400, record=NAMES)
    v = rec["axis1.commandedVelocity"]
    assert v[-1] == 0 and (np.diff(v) >= -0x2000).all() and (np.diff(v) <= 0).all()
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask
    ax.Update()  # resumes toward the destination
    chip.run(100)
    assert ax.GetCommandedVelocity() > 0
    ax.SetStopMode(pmdfmu.PMDAbruptStop)
    ax.Update()
    held = ax.GetCommandedPosition()
    rec = chip.run(5, record=NAMES)
    assert (rec["axis1.commandedPosition"] == held).all() and (rec["axis1.commandedVelocity"] == 0).all()
