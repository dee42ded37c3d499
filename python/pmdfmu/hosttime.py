# SPDX-License-Identifier: BSD-2-Clause
"""The host timing model: how long each command's transfer takes on the host
interface, in whole nanoseconds (docs/host-time.md,
docs/decisions.md "Host time").

The interface kinds, their parameters and defaults are modelDescription/
host_interfaces.csv; host/c/PMDhosttime.c is the same formula in C (its constants
generated from the same table), and tests/test_host_time.py compares the two."""

from __future__ import annotations

import csv
from decimal import Decimal
from fractions import Fraction
from numbers import Rational
from pathlib import Path
from typing import Dict, List, Tuple

_PACKAGE = Path(__file__).resolve().parent


def _tables_dir() -> Path:
    installed = _PACKAGE / "tables"
    return installed if installed.is_dir() else _PACKAGE.parent.parent / "modelDescription"


UINT32_MAX = (1 << 32) - 1


def read_table(path: Path = None) -> List[Tuple[str, Dict[str, Tuple[int, int, int]]]]:
    """[(kind, {parameter: (default, min, max)})] in the table's order, an empty max 2^32-1
    (modelDescription/generate_hosttime.py reads it the same way)."""
    kinds: Dict[str, Dict[str, Tuple[int, int, int]]] = {}
    with open(path or _tables_dir() / "host_interfaces.csv", newline="") as f:
        for row in csv.DictReader(f):
            params = kinds.setdefault(row["kind"], {})
            if row["parameter"]:
                params[row["parameter"]] = (int(row["default"]), int(row["min"]), int(row["max"] or UINT32_MAX))
    return list(kinds.items())


_TABLE = read_table()
KINDS: Dict[str, Dict[str, int]] = {kind: {p: d for p, (d, _lo, _hi) in params.items()} for kind, params in _TABLE}
# each parameter's range: a baud of 0 would make bytes take no time, a parity of 5 five bits
RANGES: Dict[str, Dict[str, Tuple[int, int]]] = {
    kind: {p: (lo, hi) for p, (_d, lo, hi) in params.items()} for kind, params in _TABLE
}
NS_PER_S = 1_000_000_000


def ns_of(seconds, what: str) -> int:
    """seconds (an int, float, Fraction, Decimal or numpy number) of host time as whole ns, rounded to the
    nearest; ValueError naming what for a negative one or one that is no finite number (a negative timeout
    made wait_for's native loop poll without a limit, for ever), a string among them (Fraction read "1/3")."""
    try:
        if isinstance(seconds, (str, bytes)):
            raise TypeError(seconds)
        exact = seconds if isinstance(seconds, (Rational, float, Decimal)) else float(seconds)  # np.float32
        ns = round(Fraction(exact) * NS_PER_S)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what} = {seconds!r} is not a finite number of seconds") from None
    if ns < 0:
        raise ValueError(f"{what} = {seconds!r} s is negative")
    return ns


def _bits_ns(bits: int, rate: int) -> int:
    """ceil(bits * 1e9 / rate): whole ns, rounded up transfer by transfer."""
    return -(-bits * NS_PER_S // rate) if rate else 0


class HostInterface:
    """A host interface: HostInterface("serial", baud=115200). kind is a kind of
    host_interfaces.csv (none, parallel16, parallel8, serial, spi, fixed);
    parameters not given take the table's defaults; each is an integer in the table's range
    (min .. max; baud 1 .. 2^32-1, parity 0 .. 1, stop_bits 1 .. 2)."""

    def __init__(self, kind: str = "parallel16", **parameters: int):
        if kind not in KINDS:
            raise ValueError(f"host interface {kind!r}: one of {', '.join(KINDS)}")
        unknown = set(parameters) - set(KINDS[kind])
        if unknown:
            raise ValueError(
                f"host interface {kind}: no parameter {', '.join(sorted(unknown))} "
                f"(it has {', '.join(KINDS[kind]) or 'none'})"
            )
        self.kind = kind
        self.parameters: Dict[str, int] = dict(KINDS[kind])
        for name, value in parameters.items():
            lo, hi = RANGES[kind][name]
            if isinstance(value, bool) or not isinstance(value, int) or not lo <= value <= hi:
                shown = "2^32-1" if hi == UINT32_MAX else hi
                raise ValueError(f"host interface {kind}: {name} = {value!r} is not an integer {lo} .. {shown}")
            self.parameters[name] = value

    def __getattr__(self, name: str) -> int:
        try:
            return self.__dict__["parameters"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __repr__(self) -> str:
        params = ", ".join(f"{k}={v}" for k, v in self.parameters.items())
        return f"HostInterface({self.kind!r}{', ' if params else ''}{params})"

    def __eq__(self, other) -> bool:
        return isinstance(other, HostInterface) and (self.kind, self.parameters) == (other.kind, other.parameters)

    def _per_word_cycles(self) -> int:
        """A parallel word: a status read until HostRdy, then the word (one bus cycle, two bytes on 8 bits)."""
        return 1 + (2 if self.kind == "parallel8" else 1)

    def _serial_bits(self) -> int:
        """A serial byte: 1 start bit, data bits, parity bits, stop bits (pmd-reference 3.3)."""
        return 1 + self.data_bits + self.parity + self.stop_bits

    def request_ns(self, words: int) -> int:
        """The request's transfer time: `words` host words sent (the instruction word
        and its data words)."""
        w = max(words, 0)
        if self.kind in ("parallel16", "parallel8"):
            return w * self._per_word_cycles() * self.bus_cycle_ns
        if self.kind == "serial":  # address, checksum, 2 bytes a word (reference 3.1)
            return _bits_ns((2 + 2 * w) * self._serial_bits(), self.baud)
        if self.kind == "spi":
            return _bits_ns((self.request_header_words + w) * 16, self.clock_hz)
        if self.kind == "fixed":
            return self.request_ns_
        return 0

    def reply_ns(self, words: int, failed: bool = False) -> int:
        """The reply's transfer time, the chip's processing time included: `words`
        result words; a failed command returns none (serial: 2 bytes)."""
        w = 0 if failed else max(words, 0)
        if self.kind in ("parallel16", "parallel8"):  # ready, the I/O-error test, the words (reference 3.4)
            return (
                self.processing_ns
                + self.bus_cycle_ns
                + (0 if failed else (w + self.checksum) * self._per_word_cycles() * self.bus_cycle_ns)
            )
        if self.kind == "serial":  # status, checksum, 2 bytes a word (reference 3.2)
            return self.processing_ns + _bits_ns((2 + 2 * w) * self._serial_bits(), self.baud)
        if self.kind == "spi":
            return self.processing_ns + _bits_ns((self.reply_header_words + w) * 16, self.clock_hz)
        if self.kind == "fixed":
            return self.reply_ns_
        return 0

    # the fixed kind's parameters share their names with the methods above
    @property
    def request_ns_(self) -> int:
        return self.parameters["request_ns"]

    @property
    def reply_ns_(self) -> int:
        return self.parameters["reply_ns"]


def host_interface(value) -> HostInterface:
    """What Chip(host_interface=...) takes: None (none), a kind's name, or a HostInterface."""
    if value is None:
        return HostInterface("none")
    if isinstance(value, HostInterface):
        return value
    if isinstance(value, str):
        return HostInterface(value)
    raise TypeError(f"host_interface is None, a kind's name ({', '.join(KINDS)}) or a HostInterface, not {value!r}")


def cycles_due(host_ns: int, next_cycle_ns: int, cycle_ns: int) -> int:
    """The grid's cycles at next_cycle_ns, next_cycle_ns + cycle_ns, ... that are at or
    before the host clock (PMDHostCyclesDue)."""
    return 0 if cycle_ns <= 0 or host_ns < next_cycle_ns else (host_ns - next_cycle_ns) // cycle_ns + 1
