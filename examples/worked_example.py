"""Seed 000's worked example: one constant-velocity segment, read at chip time 11003."""
import pmdfmu
from pmdfmu import PMDBufferFunctionPosition, PMDBufferFunctionTime, PMDBufferFunctionVelocity

with pmdfmu.Chip() as chip:
    ax = chip.axis(pmdfmu.PMDAxis1)
    for buffer_id, function, address in ((2, PMDBufferFunctionPosition, 0x200),
                                         (3, PMDBufferFunctionVelocity, 0x210),
                                         (4, PMDBufferFunctionTime, 0x220)):
        ax.SetBufferStart(buffer_id, address)
        ax.SetBufferLength(buffer_id, 2)
        ax.SetBufferFunction(function, buffer_id)
    for position, velocity, time in ((0, 0x10000, 10), (10, 0, 15)):
        ax.WriteBuffer(2, position)
        ax.WriteBuffer(3, velocity)
        ax.WriteBuffer(4, time)
    chip.run(11003)                                   # chip times 0 .. 11002
    ax.SetProfileMode(pmdfmu.PMDExternalProfile)
    ax.Update()                                       # the next cycle, 11003, reads the first segment
    for row in chip.run(11, record=["axis1.commandedPosition", "axis1.commandedVelocity"]):
        print(f"chip time {row['cycle']}: position {row['axis1.commandedPosition']}, "
              f"velocity {row['axis1.commandedVelocity']:#x}")
