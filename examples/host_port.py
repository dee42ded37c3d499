# SPDX-License-Identifier: BSD-2-Clause
"""The host port word by word, as a co-simulation master would drive it:
the instruction word (the axis in its PMDInstructionAxis field, bits 8-15, the opcode in
PMDInstructionOpcode, bits 0-7), then data words, 32-bit values high word first."""

import pmdfmu

with pmdfmu.Chip() as chip:
    SetPosition, Update, GetCommandedPosition = (
        pmdfmu.COMMANDS[n].opcode for n in ("SetPosition", "Update", "GetCommandedPosition")
    )
    SetVelocity, SetAcceleration = pmdfmu.COMMANDS["SetVelocity"].opcode, pmdfmu.COMMANDS["SetAcceleration"].opcode
    axis2 = pmdfmu.field_dp(0, "PMDInstructionAxis", pmdfmu.PMDAxis2)
    error, reply = chip.batch(
        [
            SetPosition | axis2,
            0x0001,
            0x86A0,  # 100000 counts
            SetVelocity | axis2,
            0x0004,
            0x0000,  # 4.0 counts/cycle
            SetAcceleration | axis2,
            0x0000,
            0x1000,  # 1/16 counts/cycle^2
            Update | axis2,
        ]
    )
    print("batch error", error)
    chip.run(500)
    error, reply = chip.batch([GetCommandedPosition | axis2])
    print("axis 2 position after 500 cycles:", pmdfmu.signed((reply[0] << 16) | reply[1]))
    error, reply = chip.batch([0x0002])  # not a Navigator opcode
    print(f"unknown opcode -> host I/O error {error:#04x}")
