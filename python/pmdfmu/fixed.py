"""Fixed-point encoding of trajectory parameters (seed 000, section 1.7).

The chip uses three 32-bit formats: 32.0 (unity scaling: positions), 16.16
(scaled by 2^16: velocity, acceleration) and 0.32 (scaled by 2^32: jerk).
`to_fixed` returns the 32-bit word the chip is sent; `from_fixed` reads one back.

Values are converted exactly: a float is taken as the decimal it prints as
(0.0075 is 3/400, not the nearest binary double), multiplied by the scale and
rounded to the nearest integer, halves away from zero. A value outside the
format's range raises ValueError: nothing is clamped.
"""
from __future__ import annotations

from decimal import Decimal
from fractions import Fraction
from typing import Union

Number = Union[int, float, str, Decimal, Fraction]

FORMATS = {"32.0": 0, "16.16": 16, "0.32": 32}


def _exact(value: Number) -> Fraction:
    if isinstance(value, float):
        return Fraction(repr(value))
    return Fraction(value)


def to_fixed(value: Number, fmt: str) -> int:
    """The 32-bit word (0 .. 2^32-1) that represents value in fmt."""
    scaled = _exact(value) * (1 << FORMATS[fmt])
    n = int(abs(scaled) + Fraction(1, 2)) * (1 if scaled >= 0 else -1)
    if not -(1 << 31) <= n < (1 << 31):
        raise ValueError(f"{value} does not fit the {fmt} format")
    return n & 0xFFFFFFFF


def signed(word: int) -> int:
    """A 32-bit word read as two's complement."""
    word &= 0xFFFFFFFF
    return word - (1 << 32) if word & 0x80000000 else word


def from_fixed(word: int, fmt: str) -> Fraction:
    """The exact value of a signed 32-bit word in fmt."""
    return Fraction(signed(word), 1 << FORMATS[fmt])


def fixed_16_16(value: Number) -> int:
    return to_fixed(value, "16.16")


def fixed_0_32(value: Number) -> int:
    return to_fixed(value, "0.32")


def fixed_32_0(value: Number) -> int:
    return to_fixed(value, "32.0")
