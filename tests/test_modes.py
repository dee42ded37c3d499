# SPDX-License-Identifier: BSD-2-Clause
"""Velocity contouring, electronic gear, on-the-fly trapezoidal changes and the
stops in every mode (seed 001; pmd-reference 5)."""

import numpy as np
import pytest

from pmdfmu import (
    PMDAbruptStop,
    PMDActivityAtMaximumVelocityMask,
    PMDActivityInMotionMask,
    PMDElectronicGearProfile,
    PMDError,
    PMDEventMotionCompleteMask,
    PMDPositionSourceActual,
    PMDPositionSourceCommanded,
    PMDSmoothStop,
    PMDTrapezoidal,
    PMDVelocityContouringProfile,
    field_ex,
)

V = [
    "axis{n}.commandedPosition",
    "axis{n}.commandedVelocity",
    "axis{n}.commandedAcceleration",
    "axis{n}.activityStatus",
]


def rec(chip, cycles, *axes):
    return chip.run(cycles, record=[v.format(n=a + 1) for a in axes for v in V])


def velocity_mode(ax, velocity, acceleration, deceleration=0):
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(velocity)
    ax.SetAcceleration(acceleration)
    ax.SetDeceleration(deceleration)
    ax.Update()


def test_velocity_contouring_ramps_holds_and_reverses(chip):
    ax = chip.axis(0)
    velocity_mode(ax, -0x30000, 0x1000, 0x2000)  # negative velocity is legal here
    r = rec(chip, 100, 0)
    v = r["axis1.commandedVelocity"]
    assert list(v[:3]) == [-0x1000, -0x2000, -0x3000]
    assert (v[47:] == -0x30000).all() and v[46] == -0x2F000
    assert (r["axis1.activityStatus"][48:] & PMDActivityAtMaximumVelocityMask).all()
    velocity_mode(ax, 0x10000, 0x1000, 0x2000)  # reverse: decelerate at 0x2000 through 0
    r = rec(chip, 60, 0)
    v = r["axis1.commandedVelocity"]
    assert v[0] == -0x2E000 and v[23] == 0 and v[24] == 0x1000 and v[-1] == 0x10000
    positions = r["axis1.commandedPosition"]
    assert (np.diff(positions[30:]) >= 0).all()


def test_velocity_zero_ends_the_motion_with_motion_complete(chip):
    ax = chip.axis(0)
    velocity_mode(ax, 0x20000, 0x4000)
    chip.run(20)
    velocity_mode(ax, 0, 0x4000)
    chip.run(7)
    assert ax.GetCommandedVelocity() == 0x20000 - 7 * 0x4000
    assert ax.GetActivityStatus() & PMDActivityInMotionMask
    chip.run(20)
    assert ax.GetCommandedVelocity() == 0
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask
    assert not ax.GetActivityStatus() & PMDActivityInMotionMask


@pytest.mark.parametrize("source", [PMDPositionSourceActual, PMDPositionSourceCommanded])
def test_gear_follows_the_master_times_the_ratio_exactly(chip, source):
    master, slave = chip.axis(0), chip.axis(2)
    slave.SetGearMaster(0, source)
    slave.SetGearRatio(-0x18000)  # -1.5
    slave.SetProfileMode(PMDElectronicGearProfile)
    slave.Update()
    assert slave.GetGearMaster() == (0, source)
    master.SetPosition(1001)
    master.SetVelocity(0x30000)
    master.SetAcceleration(0x800)
    master.Update()
    r = rec(chip, 600, 0, 2)
    m, s = r["axis1.commandedPosition"], r["axis3.commandedPosition"]
    assert m[-1] == 1001
    assert list(s) == [int(np.floor(-1.5 * x)) for x in m]
    assert slave.GetActivityStatus() & PMDActivityInMotionMask
    assert field_ex(slave.GetActivityStatus(), "PMDActivityProfileMode") == PMDElectronicGearProfile


def test_gear_smooth_stop_acts_as_abrupt(chip):
    master, slave = chip.axis(0), chip.axis(1)
    slave.SetGearMaster(0, PMDPositionSourceCommanded)
    slave.SetGearRatio(0x10000)
    slave.SetProfileMode(PMDElectronicGearProfile)
    slave.Update()
    velocity_mode(master, 0x20000, 0x20000)
    chip.run(10)
    slave.SetStopMode(PMDSmoothStop)
    slave.Update()
    held = slave.GetCommandedPosition()
    chip.run(10)
    assert slave.GetCommandedPosition() == held and slave.GetCommandedVelocity() == 0
    assert master.GetCommandedPosition() > held


def test_new_destination_inside_the_stopping_distance_overshoots_and_returns(chip):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDTrapezoidal)
    ax.SetPosition(100_000)
    ax.SetVelocity(0x80000)
    ax.SetAcceleration(0x1000)
    ax.Update()
    chip.run(300)
    here = ax.GetCommandedPosition()
    ax.SetPosition(here + 10)  # far inside the stopping distance (8^2 / 2 / (1/16) = 512)
    ax.Update()
    r = rec(chip, 1000, 0)
    p, v = r["axis1.commandedPosition"], r["axis1.commandedVelocity"]
    assert p.max() > here + 10  # overshoot
    assert p[-1] == here + 10 and v[-1] == 0
    assert (np.abs(np.diff(np.concatenate([[0x80000], v]))) <= 0x1000).all()


def test_new_maximum_velocity_on_the_fly(chip):
    ax = chip.axis(0)
    ax.SetPosition(1_000_000)
    ax.SetVelocity(0x80000)
    ax.SetAcceleration(0x1000)
    ax.Update()
    chip.run(200)
    assert ax.GetCommandedVelocity() == 0x80000
    ax.SetVelocity(0x20000)
    ax.Update()
    r = rec(chip, 200, 0)
    v = r["axis1.commandedVelocity"]
    assert v[0] == 0x80000 - 0x1000 and (v[96:] == 0x20000).all()


def test_acceleration_change_during_a_trapezoidal_move_is_0x0c_and_only_the_position_applies(chip):
    ax = chip.axis(0)
    ax.SetPosition(1_000_000)
    ax.SetVelocity(0x40000)
    ax.SetAcceleration(0x1000)
    ax.Update()
    chip.run(10)
    ax.SetAcceleration(0x2000)
    ax.SetVelocity(0x80000)
    ax.SetPosition(5000)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0C
    chip.run(1)
    assert ax.GetCommandedVelocity() == 11 * 0x1000  # acceleration unchanged
    chip.run(3000)
    assert ax.GetCommandedPosition() == 5000  # the new destination was taken


@pytest.mark.parametrize("mode", ["trapezoidal", "velocity"])
def test_abrupt_and_smooth_stop_in_every_mode(chip, mode):
    ax = chip.axis(0)
    if mode == "velocity":
        velocity_mode(ax, 0x40000, 0x1000, 0x800)
    else:
        ax.SetPosition(1_000_000)
        ax.SetVelocity(0x40000)
        ax.SetAcceleration(0x1000)
        ax.SetDeceleration(0x800)
        ax.Update()
    chip.run(100)
    ax.SetStopMode(PMDSmoothStop)
    ax.Update()
    assert ax.GetStopMode() == 0
    r = rec(chip, 200, 0)
    v = r["axis1.commandedVelocity"]
    assert v[0] == 0x40000 - 0x800 and v[127] == 0 and (v[128:] == 0).all()
    assert ax.GetEventStatus() & PMDEventMotionCompleteMask
    ax.Update()
    chip.run(50)
    assert ax.GetCommandedVelocity() > 0
    ax.SetStopMode(PMDAbruptStop)
    ax.Update()
    r = rec(chip, 3, 0)
    assert (r["axis1.commandedVelocity"] == 0).all()
