# SPDX-License-Identifier: BSD-2-Clause
"""Fixed-point encoding of trajectory parameters (seed 000, section 1.7).

The chip uses three 32-bit formats: 32.0 (unity scaling: positions), 16.16
(scaled by 2^16: velocity, acceleration) and 0.32 (scaled by 2^32: jerk).
`to_fixed` returns the 32-bit word the chip is sent; `from_fixed` reads one back.

Values are converted exactly: a float is taken as the decimal it prints as
(0.0075 is 3/400, not the nearest binary double), multiplied by the scale and
rounded to the nearest integer, halves away from zero. A value outside the
format's range raises ValueError: nothing is clamped.

Words are never masked: a 32-bit word is an integer from -2^31 to 2^32-1 (its
signed or its unsigned reading, the same 32 bits); anything else raises
ValueError (`to_word` checks this for any width, and the harness uses it for every
value it sends).
"""

from __future__ import annotations

import math
import numbers
import operator
from decimal import Decimal
from fractions import Fraction
from typing import Union

Number = Union[int, float, str, Decimal, Fraction]

FORMATS = {"32.0": 0, "16.16": 16, "0.32": 32}


def integer(value, what: str = "value") -> int:
    """value as a Python int if it is an integer (int, bool, numpy integer);
    anything else (a float, even 2.0, a string) raises ValueError naming `what`."""
    try:
        return operator.index(value)
    except TypeError:
        raise ValueError(f"{what} = {value!r} is not an integer") from None


def _hex(v: int) -> str:
    return f"-0x{-v:X}" if v < 0 else f"0x{v:X}"


def to_word(value, bits: int = 32, what: str = "word") -> int:
    """The `bits`-wide word (0 .. 2^bits-1) an integer stands for: 0 .. 2^bits-1 as
    it is, -2^(bits-1) .. -1 as its two's complement (to_word(-1, 16) == 0xFFFF).
    Anything outside -2^(bits-1) .. 2^bits-1, or not an integer, raises ValueError
    naming `what` and the range: no bits are dropped."""
    v = integer(value, what)
    lo, hi = -(1 << (bits - 1)), (1 << bits) - 1
    if not lo <= v <= hi:
        raise ValueError(
            f"{what} = {v} ({_hex(v)}) does not fit {bits} bits: a {bits}-bit word is {lo} .. {hi} "
            f"(0 .. {_hex(hi)}, or its two's complement {_hex(lo)} .. -1)"
        )
    return v & hi


def _format(fmt: str) -> int:
    if fmt not in FORMATS:
        raise ValueError(f"fixed-point format {fmt!r}: the chip's formats are {', '.join(FORMATS)}")
    return FORMATS[fmt]


def _exact(value: Number) -> Fraction:
    if isinstance(value, numbers.Real) and not isinstance(value, numbers.Rational):  # float, numpy floats
        if not math.isfinite(value):
            raise ValueError(f"{value} is not a finite number")
        return Fraction(str(value))  # the decimal it prints as (str: numpy's repr adds its type)
    if isinstance(value, Decimal) and not value.is_finite():
        raise ValueError(f"{value} is not a finite number")
    return Fraction(value)


def to_fixed(value: Number, fmt: str) -> int:
    """The 32-bit word (0 .. 2^32-1) that represents value in fmt ("32.0", "16.16",
    "0.32"), rounded to nearest, halves away from zero; a value outside the format's
    signed range (-2^31 .. 2^31-1 after scaling), or not finite, raises ValueError."""
    scale = _format(fmt)
    scaled = _exact(value) * (1 << scale)
    n = int(abs(scaled) + Fraction(1, 2)) * (1 if scaled >= 0 else -1)
    if not -(1 << 31) <= n < (1 << 31):
        raise ValueError(
            f"{value} does not fit the {fmt} format ({-(1 << 31) / (1 << scale):.12g} .. "
            f"{((1 << 31) - 1) / (1 << scale):.10g})"
        )
    return n & 0xFFFFFFFF


def signed(word: int) -> int:
    """A 32-bit word read as two's complement: signed(0xFFFFFFFF) == signed(-1) == -1.
    The word is an integer from -2^31 to 2^32-1; anything else raises ValueError."""
    w = to_word(word, 32, "signed: word")
    return w - (1 << 32) if w & 0x80000000 else w


def from_fixed(word: int, fmt: str) -> Fraction:
    """The exact value of a 32-bit word in fmt, read as signed. The word is an
    integer from -2^31 to 2^32-1 (signed or unsigned reading of the same bits);
    anything else raises ValueError rather than being masked."""
    scale = _format(fmt)
    w = to_word(word, 32, "from_fixed: word")
    return Fraction(w - (1 << 32) if w & 0x80000000 else w, 1 << scale)


def fixed_16_16(value: Number) -> int:
    """to_fixed(value, "16.16")."""
    return to_fixed(value, "16.16")


def fixed_0_32(value: Number) -> int:
    """to_fixed(value, "0.32")."""
    return to_fixed(value, "0.32")


def fixed_32_0(value: Number) -> int:
    """to_fixed(value, "32.0")."""
    return to_fixed(value, "32.0")
