"""An exact reference model of seed 000's external profile, written
independently of the C core: Python Fractions in counts, the seed's pseudo
code line by line."""
from __future__ import annotations

from fractions import Fraction
from math import floor
from typing import List, Optional, Sequence, Tuple

POSITION, VELOCITY, ACCELERATION, JERK, TIME = range(5)


def wrap32(x: int) -> int:
    x &= 0xFFFFFFFF
    return x - (1 << 32) if x >= (1 << 31) else x


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
        return raw if f == TIME else wrap32(raw)     # PMD_TIME is unsigned

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
            if self.segment_time == 0:              # StopTrajectory()
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
