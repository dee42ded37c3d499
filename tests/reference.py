# SPDX-License-Identifier: BSD-2-Clause
"""Exact reference models written independently of the C core: seed 000's
external profile (Python Fractions in counts, the seed's pseudo code line by
line), the servo filter (docs/decisions.md's formula in Python integers) and
the wrap-around event (in unbounded Python integers)."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from fractions import Fraction
from math import floor
from typing import List, Optional, Sequence, Tuple

POSITION, VELOCITY, ACCELERATION, JERK, TIME = range(5)


def wrap32(x: int) -> int:
    x &= 0xFFFFFFFF
    return x - (1 << 32) if x >= (1 << 31) else x


def wrap_arounds(previous: int, positions: Sequence[int]) -> List[int]:
    """The indexes of the cycles whose actual position wrapped between the
    maximum and the minimum (event status bit 1, reference 2.2), given the
    actual position before the first: each cycle's change is the encoder's
    signed 32-bit step, and the position it reaches without wrapping lies
    outside the int32 range."""
    cycles = []
    for k, p in enumerate(positions):
        if not -(1 << 31) <= previous + wrap32(p - previous) < (1 << 31):
            cycles.append(k)
        previous = p
    return cycles


def registers(p: Fraction, v: Fraction, a: Fraction) -> Tuple[int, int, int]:
    """GetCommandedPosition/Velocity/Acceleration: truncated toward minus infinity."""
    return wrap32(floor(p)), wrap32(floor(v * 65536)), wrap32(floor(a * 65536))


class ExternalProfile:
    """One axis running an external profile over a segment table.

    rows: the table, one tuple (position, velocity, acceleration, jerk, time)
    of raw 32-bit values per offset; functions: which of the five buffers are
    assigned (absent ones read 0, an absent time reads 1). start: the read index."""

    def __init__(self, rows: Sequence[Sequence[int]], functions: Sequence[int] = range(5), start: int = 0):
        self.rows = [tuple(r) for r in rows]
        self.functions = set(functions)
        self.index = start
        self.segment_time = 0
        self.running = True
        self.p = self.v = self.a = self.j = Fraction(0)

    def entry(self, f: int) -> int:
        if f not in self.functions:
            return 1 if f == TIME else 0
        raw = self.rows[self.index][f] & 0xFFFFFFFF
        return raw if f == TIME else wrap32(raw)  # PMD_TIME is unsigned

    def cycle(self) -> Optional[Tuple[int, int, int]]:
        """One chip cycle; returns the three registers, or None once halted."""
        if not self.running:
            return registers(self.p, self.v, self.a)
        if self.segment_time == 0:
            self.p = Fraction(self.entry(POSITION))
            self.v = Fraction(self.entry(VELOCITY), 1 << 16)
            self.a = Fraction(self.entry(ACCELERATION), 1 << 16)
            self.j = Fraction(self.entry(JERK), 1 << 32)
            self.segment_time = self.entry(TIME)
            self.index = (self.index + 1) % len(self.rows)
            if self.segment_time == 0:  # StopTrajectory()
                self.v = self.a = self.j = Fraction(0)
                self.running = False
                return registers(self.p, self.v, self.a)
        else:
            self.p += self.v + self.a / 2 + self.j / 6
            self.v += self.a + self.j / 2
            self.a += self.j
        self.segment_time -= 1
        return registers(self.p, self.v, self.a)

    def run(self, n: int) -> List[Tuple[int, int, int]]:
        return [self.cycle() for _ in range(n)]


# ---- the servo filter (docs/decisions.md, "Servo filter and motor output") ----


def _clamp(x: int, low: int, high: int) -> int:
    return max(low, min(high, x))


@dataclass
class FilterRegisters:
    """The filter group (reference 4.1), reset values of reference 4.2."""

    kp: int = 0
    ki: int = 0
    kd: int = 0
    kvff: int = 0
    kaff: int = 0
    kout: int = 0xFFFF
    integration_limit: int = 0
    derivative_time: int = 1
    motor_command: int = 0


@dataclass
class ServoFilter:
    """One axis's servo filter, written from docs/decisions.md's formula in
    Python integers (// floors toward minus infinity, as the page says).

    The test sets `buffered` as the host's Set commands do and calls update()
    where Update applies it; motor_bias and motor_limit act at once."""

    buffered: FilterRegisters = field(default_factory=FilterRegisters)
    active: FilterRegisters = field(default_factory=FilterRegisters)
    motor_bias: int = 0
    motor_limit: int = 32767
    integral: int = 0
    derivative: int = 0
    previous_error: int = 0  # E at the last derivative sample
    count: int = 0  # cycles since the last derivative sample
    output: int = 0

    def update(self) -> None:
        self.active = replace(self.buffered)

    def cycle(self, commanded: int, actual: int, velocity: int, acceleration: int, motor_on: bool) -> int:
        """One cycle, given the registers as the cycle left them: commanded and
        actual position, commanded velocity and acceleration (16.16 registers)."""
        r = self.active
        e = wrap32(commanded - actual)
        if not motor_on:
            self.integral = self.derivative = self.count = 0
            self.previous_error = e
            self.output = wrap16(r.motor_command)
            return self.output
        self.integral = _clamp(self.integral + e, -r.integration_limit, r.integration_limit)
        self.count += 1
        if self.count >= r.derivative_time:
            self.derivative = _clamp(e - self.previous_error, -32768, 32767)
            self.previous_error = e
            self.count = 0
        s = (
            r.kp * e
            + r.kd * self.derivative
            + (r.ki * self.integral) // 256
            + (r.kvff * velocity) // 65536
            + (r.kaff * acceleration) // 65536
        )
        s = _clamp(s, -(2**31), 2**31 - 1)
        u = (r.kout * s) // 65536 + self.motor_bias
        self.output = _clamp(u, -self.motor_limit, self.motor_limit)
        return self.output


def wrap16(x: int) -> int:
    x &= 0xFFFF
    return x - (1 << 16) if x >= (1 << 15) else x
