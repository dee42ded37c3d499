# SPDX-License-Identifier: BSD-2-Clause
"""Seed 000's worked example: one constant-velocity segment, read at chip time 11003."""

import pmdfmu
from pmdfmu import PMDBufferFunctionPosition, PMDBufferFunctionTime, PMDBufferFunctionVelocity


def start_worked_example(chip):
    """The seed's two rows in buffers 2-4 of axis 1, then chip times 0 .. 11002 and
    the Update that starts the external profile: the next cycle, 11003, reads the
    first segment. (The tests run this function too: tests/scenarios.py.)"""
    ax = chip.axis(pmdfmu.PMDAxis1)
    for buffer_id, function, address in (
        (2, PMDBufferFunctionPosition, 0x200),
        (3, PMDBufferFunctionVelocity, 0x210),
        (4, PMDBufferFunctionTime, 0x220),
    ):
        ax.SetBufferStart(buffer_id, address)
        ax.SetBufferLength(buffer_id, 2)
        ax.SetBufferFunction(function, buffer_id)
    # "Initial set of values": position 0, velocity 10000h, time 10; then 10, 0, 15
    for position, velocity, time in ((0, 0x10000, 10), (10, 0, 15)):
        ax.WriteBuffer(2, position)
        ax.WriteBuffer(3, velocity)
        ax.WriteBuffer(4, time)
    chip.run(11003)  # chip times 0 .. 11002
    ax.SetProfileMode(pmdfmu.PMDExternalProfile)
    ax.Update()


if __name__ == "__main__":
    with pmdfmu.Chip() as chip:
        start_worked_example(chip)
        for row in chip.run(11, record=["axis1.commandedPosition", "axis1.commandedVelocity"]):
            print(
                f"chip time {row['cycle']}: position {row['axis1.commandedPosition']}, "
                f"velocity {row['axis1.commandedVelocity']:#x}"
            )
