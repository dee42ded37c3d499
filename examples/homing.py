# SPDX-License-Identifier: BSD-2-Clause
"""Homing, in the spirit of seed 002: hunt for the home switch with a velocity
move, capture the position where it trips, stop, make that point the origin,
and move back to it with a trapezoidal move.

The plant is a simple stage: an ideal servo (loopback) and a home switch that
is active at and beyond HOME_AT counts of travel. The script steps the chip one
cycle at a time and sets the switch input from the stage's travel, as a plant
model in a co-simulation would (so the switch reaches the chip one cycle late)."""

import pmdfmu
from pmdfmu import (
    PMDActivityInMotionMask,
    PMDActivityPositionCaptureMask,
    PMDAxis1,
    PMDCaptureSourceHome,
    PMDSmoothStop,
    PMDTrapezoidal,
    PMDVelocityContouringProfile,
)

HOME_AT = 12_345  # where the switch sits, unknown to the host


class Stage:
    """Travel = the chip's position plus the origin shifts the host made."""

    def __init__(self, chip):
        self.chip = chip
        self.origin = 0

    def step(self):
        self.chip.run(1)
        travel = self.chip.get("axis1.commandedPosition") + self.origin
        self.chip.set("axis1.home", travel >= HOME_AT)


def home(chip):
    ax = chip.axis(PMDAxis1)
    stage = Stage(chip)
    # configure the capture to trigger off the home input, and arm it (reading it re-arms)
    ax.SetCaptureSource(PMDCaptureSourceHome)
    if ax.GetActivityStatus() & PMDActivityPositionCaptureMask:
        ax.GetCaptureValue()
    # hunt for the home point with a velocity move
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetVelocity(pmdfmu.fixed_16_16(8.0))  # 8 counts/cycle
    ax.SetAcceleration(pmdfmu.fixed_16_16(0.25))
    ax.Update()
    while not ax.GetActivityStatus() & PMDActivityPositionCaptureMask:
        stage.step()
    # home detected: stop smoothly, then make the captured position the origin
    ax.SetStopMode(PMDSmoothStop)
    ax.Update()
    while ax.GetActivityStatus() & PMDActivityInMotionMask:
        stage.step()
    captured = ax.GetCaptureValue()
    ax.AdjustActualPosition(-captured)  # the home point is now 0
    stage.origin += captured
    overshoot = ax.GetActualPosition()
    # and a trapezoidal move back to the origin
    ax.SetProfileMode(PMDTrapezoidal)
    ax.SetPosition(0)
    ax.SetVelocity(pmdfmu.fixed_16_16(4.0))
    ax.SetAcceleration(pmdfmu.fixed_16_16(0.125))
    ax.Update()
    while ax.GetActivityStatus() & PMDActivityInMotionMask:
        stage.step()
    return captured, overshoot, ax.GetCommandedPosition()


if __name__ == "__main__":
    with pmdfmu.Chip() as chip:
        captured, overshoot, final = home(chip)
        print(
            f"home switch captured at {captured} counts; stopped {overshoot} counts past it; "
            f"back at {final} (the new origin), switch active: {bool(chip.get('axis1.home'))}"
        )
