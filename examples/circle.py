# SPDX-License-Identifier: BSD-2-Clause
"""A 2-axis external profile from a segment table, synchronized start, run to completion."""

import pmdfmu
from pmdfmu.demo import circle_table
from pmdfmu.profile import run_segment_table

with pmdfmu.Chip() as chip:
    recorded = run_segment_table(chip, circle_table(radius=5000, segments=32))
print(
    f"{len(recorded)} cycles; axis 1 ends at {recorded['axis1.commandedPosition'][-1]}, "
    f"axis 2 at {recorded['axis2.commandedPosition'][-1]}"
)
