# SPDX-License-Identifier: BSD-2-Clause
"""The bundled demo: a 2-axis external profile tracing a circle, written as a
segment table the way a host planner would, run through the FMU.

Each segment is (position, velocity, acceleration, jerk=0, time=256). The
velocities are multiples of 512 raw (1/128 count/cycle) and each acceleration
is (next velocity - velocity)/256, so every segment ends exactly on the next
row's position and velocity: the chip's integration and the table agree to the
count (seed 000's equations with J = 0: P += V + A/2, V += A)."""

from __future__ import annotations

import math
from typing import Dict, List

from .profile import Row

SEGMENT_CYCLES = 256
QUANTUM = 512


def describe_demo(tables: Dict[int, List[Row]]) -> str:
    """What the demo shows, printed before it runs."""
    (x0, *_), (y0, *_) = tables[0][0], tables[1][0]
    segments = len(tables[0]) - 1
    return (
        f"pmdfmu demo: axes 1 and 2 trace a circle from a segment table written as a host planner would "
        f"({segments} segments of {SEGMENT_CYCLES} cycles per axis, velocities in 16.16, accelerations chosen "
        f"so each segment lands exactly on the next row). The axes first move to the first row ({x0}, {y0}) "
        "with a trapezoidal move; the recording starts when the external profile starts."
    )


def circle_table(radius: int = 20_000, segments: int = 64) -> Dict[int, List[Row]]:
    """Axis 1 traces x = R cos(theta), axis 2 y = R sin(theta), theta going once
    around with zero speed at both ends, then a time-0 row stops each axis."""

    def theta_rate(s: float) -> float:  # d theta / d s for theta(s) = 2 pi (s - sin(2 pi s) / (2 pi))
        return 2 * math.pi * (1 - math.cos(2 * math.pi * s))

    total = segments * SEGMENT_CYCLES
    tables: Dict[int, List[Row]] = {}
    for axis, (start, derivative) in enumerate(((radius, lambda th: -math.sin(th)), (0, lambda th: math.cos(th)))):
        velocities = []
        for k in range(segments + 1):
            s = k / segments
            th = 2 * math.pi * (s - math.sin(2 * math.pi * s) / (2 * math.pi))
            counts_per_cycle = radius * derivative(th) * theta_rate(s) / total
            velocities.append(round(counts_per_cycle * 65536 / QUANTUM) * QUANTUM)
        velocities[0] = velocities[-1] = 0
        rows: List[Row] = []
        position = start
        for v, v_next in zip(velocities, velocities[1:]):
            a = (v_next - v) // SEGMENT_CYCLES
            rows.append((position, v, a, 0, SEGMENT_CYCLES))
            position += (v + v_next) * SEGMENT_CYCLES // 2 // 65536  # exact: both are multiples of 512
        rows.append((position, 0, 0, 0, 0))
        tables[axis] = rows
    return tables
