# SPDX-License-Identifier: BSD-2-Clause
"""Homing against a machine file (docs/machine.md): the stage of
examples/machine/stage.toml has its home flag, limits and index pulses where
the file says, and the chip's inputs follow the axis every cycle. The host
only sends commands and polls, as a C-Motion program does: hunt for the home
switch with a velocity move and a capture on home, stop, move back to the
captured position and make it the origin, then capture the next index pulse.

    python examples/machine_homing.py
"""

from pathlib import Path

import pmdfmu
from pmdfmu import (
    PMDAxis1,
    PMDCaptureSourceHome,
    PMDCaptureSourceIndex,
    PMDEventCaptureReceivedMask,
    PMDEventMotionCompleteMask,
    PMDSmoothStop,
    PMDTrapezoidal,
    PMDVelocityContouringProfile,
)

MACHINE = Path(__file__).resolve().parent / "machine" / "stage.toml"


def wait_for(chip, ax, mask):
    """Polls the event status a cycle at a time until one of mask's bits is set."""
    while not ax.GetEventStatus() & mask:
        chip.run(1)


with pmdfmu.Chip(machine=MACHINE) as chip:
    ax = chip.axis(PMDAxis1)
    ax.SetCaptureSource(PMDCaptureSourceHome)
    ax.GetCaptureValue()  # reading the capture arms it
    ax.SetProfileMode(PMDVelocityContouringProfile)
    ax.SetAcceleration(0x2000)
    ax.SetVelocity(0x50000)  # 5 counts/cycle toward the switch
    ax.Update()
    wait_for(chip, ax, PMDEventCaptureReceivedMask)
    home = ax.GetCaptureValue()
    print(f"home switch captured at {home} counts (chip time {ax.GetTime()})")

    ax.SetStopMode(PMDSmoothStop)
    ax.Update()
    ax.ResetEventStatus(~PMDEventMotionCompleteMask & 0xFFFF)
    wait_for(chip, ax, PMDEventMotionCompleteMask)
    ax.SetProfileMode(PMDTrapezoidal)
    ax.SetPosition(home)
    ax.SetDeceleration(0x2000)
    ax.ResetEventStatus(~PMDEventMotionCompleteMask & 0xFFFF)
    ax.Update()
    wait_for(chip, ax, PMDEventMotionCompleteMask)
    ax.SetActualPosition(0)
    print(f"back at the switch: the origin now, actual position {ax.GetActualPosition()}")

    ax.SetCaptureSource(PMDCaptureSourceIndex)
    ax.GetCaptureValue()
    ax.ResetEventStatus(~PMDEventCaptureReceivedMask & 0xFFFF)
    ax.SetPosition(5000)
    ax.Update()
    wait_for(chip, ax, PMDEventCaptureReceivedMask)
    print(f"next index pulse captured at {ax.GetCaptureValue()} counts from the origin")
