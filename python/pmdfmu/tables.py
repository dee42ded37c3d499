# SPDX-License-Identifier: BSD-2-Clause
"""The interface tables under modelDescription/: variables, commands, registers, constants.

This module has no third-party imports: the build's code generator
(modelDescription/generate.py) loads it by path, and the harness uses it to
build its C-Motion calls, so both read the tables the same way.
"""

from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, NamedTuple, Optional, Tuple

AXES = 4


@dataclass(frozen=True)
class Variable:
    """One FMU variable, expanded from a row of variables.csv."""

    name: str  # e.g. "axis2.commandedPosition", "host.word[3]"
    family: str  # the row's name pattern as a C identifier, e.g. "axis_commandedPosition"
    index: int  # axis number 0..3, array element 0..n-1, else 0
    vr: int
    type: str  # FMI 2: Real, Integer, Boolean
    fmi3Type: str  # FMI 3: Float64, Int32, UInt32, UInt16, Boolean
    causality: str  # parameter, input, output
    variability: str
    start: str  # "" for outputs
    description: str


def _family(pattern: str) -> str:
    base = pattern.replace("{axis}", "").split("[")[0]
    return re.sub(r"[^A-Za-z0-9]", "_", base)


def read_variables(path: Path) -> List[Variable]:
    """Expands `axis{axis}.x` rows into axes 1..4 (vr + 100 per axis) and
    `name[n]` rows into elements 1..n (vr + element - 1)."""
    out: List[Variable] = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            pattern, vr = row["name"], int(row["vr"])
            rest = (
                row["type"],
                row["fmi3Type"],
                row["causality"],
                row["variability"],
                row["start"],
                row["description"],
            )
            m = re.fullmatch(r"(.*)\[(\d+)\]", pattern)
            if "{axis}" in pattern:
                for axis in range(AXES):
                    out.append(
                        Variable(
                            pattern.replace("{axis}", str(axis + 1)), _family(pattern), axis, vr + 100 * axis, *rest
                        )
                    )
            elif m:
                for i in range(int(m.group(2))):
                    out.append(Variable(f"{m.group(1)}[{i + 1}]", _family(pattern), i, vr + i, *rest))
            else:
                out.append(Variable(pattern, _family(pattern), 0, vr, *rest))
    vrs = [v.vr for v in out]
    if len(set(vrs)) != len(vrs):
        raise ValueError(f"{path}: duplicate value references")
    return out


@dataclass(frozen=True)
class Variable3:
    """One FMI 3 variable: a row of variables.csv with arrays kept whole
    (`host.word`, 64 elements, whose value reference is that of host.word[1])."""

    name: str
    family: str
    index: int  # axis number 0..3, else 0
    vr: int
    count: int  # array elements, 1 for a scalar
    type: str  # Float64, Int32, UInt32, UInt16, Boolean
    causality: str
    variability: str
    start: str
    description: str


def read_variables3(path: Path) -> List[Variable3]:
    out: List[Variable3] = []
    for v in read_variables(path):
        m = re.fullmatch(r"(.*)\[(\d+)\]", v.name)
        if m and m.group(2) != "1":
            out[-1] = Variable3(**{**out[-1].__dict__, "count": int(m.group(2))})
            continue
        out.append(
            Variable3(
                m.group(1) if m else v.name,
                v.family,
                0 if m else v.index,
                v.vr,
                1,
                v.fmi3Type,
                v.causality,
                v.variability,
                v.start,
                v.description,
            )
        )
    return out


class BitField(NamedTuple):
    """A register field, declared once in constants.csv as a C-Motion-style
    mask (PMDActivityProfileModeMask 0x0038 declares PMDActivityProfileMode:
    shift 3, length 3), as QEMU's include/hw/registerfields.h declares FIELD()s.
    The C side has the same as NAME_SHIFT, NAME_LENGTH, NAMEMask and
    PMD_FIELD_EX / PMD_FIELD_DP (pmd_constants.h, generated)."""

    shift: int
    length: int
    mask: int

    def ex(self, value: int) -> int:
        """The field's value inside a register word (PMD_FIELD_EX)."""
        return (value & self.mask) >> self.shift

    def dp(self, value: int, x: int) -> int:
        """value with the field replaced by x, cut to the field's width (PMD_FIELD_DP)."""
        return (value & ~self.mask) | ((x << self.shift) & self.mask)


def bit_field(name: str, mask: int) -> BitField:
    """The field a mask constant declares; a mask whose bits are not one run is refused."""
    if mask <= 0:
        raise ValueError(f"{name} = {mask:#x}: a field mask has at least one bit set")
    shift = (mask & -mask).bit_length() - 1
    length = (mask >> shift).bit_length()
    if mask >> shift != (1 << length) - 1:
        raise ValueError(f"{name} = {mask:#x}: not one contiguous run of bits, so no field")
    return BitField(shift, length, mask)


def read_fields(path: Path) -> Dict[str, BitField]:
    """Every *Mask constant of constants.csv as a field, by its name without
    `Mask` (PMDActivityProfileSegment -> its shift, length and mask)."""
    return {
        name[: -len("Mask")]: bit_field(name, value)
        for _group, name, value in read_constants(path)
        if name.endswith("Mask")
    }


@dataclass(frozen=True)
class Field:
    """One argument or reply value of a command, as C-Motion passes it.

    kind is u16/i16 (one word), u32/i32 (two words, high word first) or bits
    (width bits at shift inside one word: the register field named by
    register_field, a mask of constants.csv); fixed is the fixed-point format of
    a 32-bit value ("16.16" or "0.32"), which scripts may write as a decimal."""

    name: str
    kind: str
    word: int
    shift: int = 0
    width: int = 16
    fixed: str = ""
    register_field: str = ""  # bits: the field's name in constants.csv, without "Mask"

    @property
    def signed(self) -> bool:
        return self.kind in ("i16", "i32")


def parse_fields(spec: str, fields: Optional[Dict[str, BitField]] = None) -> Tuple[Tuple[Field, ...], int]:
    """Parses an args/reply cell: space-separated words, each `name:u16|i16|u32|i32`
    (a 32-bit one may add `:16.16` or `:0.32`) or a packed word
    `name@FIELD|name@FIELD...`, each FIELD a register field of `fields`
    (read_fields). Returns (fields, word count)."""
    out: List[Field] = []
    word = 0
    for token in spec.split():
        if "@" in token:
            used = 0
            for part in token.split("|"):
                m = re.fullmatch(r"(\w+)@(\w+)", part)
                if not m:
                    raise ValueError(f"bad packed field {part!r}: name@FIELD")
                if fields is None or m.group(2) not in fields:
                    raise ValueError(f"packed field {part!r}: {m.group(2)}Mask is not a mask of constants.csv")
                f = fields[m.group(2)]
                if used & f.mask or f.mask > 0xFFFF:
                    raise ValueError(f"overlapping or oversized field {part!r}")
                used |= f.mask
                out.append(Field(m.group(1), "bits", word, f.shift, f.length, "", m.group(2)))
            word += 1
        else:
            name, kind, *fixed = token.split(":")
            if (
                kind not in ("u16", "i16", "u32", "i32")
                or fixed not in ([], ["16.16"], ["0.32"])
                or (fixed and not kind.endswith("32"))
            ):
                raise ValueError(f"bad field type {token!r}")
            out.append(Field(name, kind, word, 0, 32 if kind.endswith("32") else 16, "".join(fixed)))
            word += 2 if kind.endswith("32") else 1
    return tuple(out), word


@dataclass(frozen=True)
class Command:
    opcode: int
    name: str
    scope: str  # "axis": acts on the axis in the instruction word; "chip": chip-wide
    args: Tuple[Field, ...]
    arg_words: int
    reply: Tuple[Field, ...]
    reply_words: int
    summary: str


def read_commands(path: Path, constants: Optional[Path] = None) -> List[Command]:
    """The rows of commands.csv; packed fields name the masks of constants.csv
    (by default the one beside it)."""
    fields = read_fields(constants or Path(path).parent / "constants.csv")
    out: List[Command] = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            args, nargs = parse_fields(row["args"], fields)
            reply, nreply = parse_fields(row["reply"], fields)
            if row["scope"] not in ("axis", "chip"):
                raise ValueError(f"{row['name']}: scope must be axis or chip")
            out.append(
                Command(int(row["opcode"], 16), row["name"], row["scope"], args, nargs, reply, nreply, row["summary"])
            )
    if len({c.opcode for c in out}) != len(out) or len({c.name for c in out}) != len(out):
        raise ValueError(f"{path}: duplicate opcode or name")
    return out


@dataclass(frozen=True)
class Register:
    """A plain stored register: a row of registers.csv. Its Set and Get
    commands (commands.csv, Set<name> and Get<name>) have no handler of their
    own: Set checks the guard and the range and stores, Get reads back, Reset
    writes the reset value (QEMU's RegisterAccessInfo with .reset and .ro)."""

    name: str
    storage: str  # the member: of PmdProfileRegisters (buffered "profile"), PmdFilterRegisters
    # (buffered "filter"), PmdChipState (a chip-wide command) or PmdAxis
    access: str  # "rw": Set<name> stores it; "ro": only Get<name> is the table's
    reset: Optional[int]  # None: pmd_chip_reset derives it (e.g. the actual position from the input)
    reset_text: str  # as written: a number or a constant's name
    low: Optional[int]  # valid values low..high; None: every value the argument holds
    high: Optional[int]
    valid: str  # the valid values in words: "1..65535", "0 (PMDTraceOneTime) or 1 (PMDTraceRollingBuffer)"
    error: str  # the host I/O error a value outside low..high answers, e.g. PMD_ERR_InvalidParameter
    error_code: int
    buffered: str  # "profile", "filter": double-buffered, Update copies the group to its active set;
    # "" not buffered
    guard: str  # a C function (chip, command) that may refuse a Set first, e.g. pmd_trace_busy
    note: str  # where the facts come from, what else to know


def read_registers(path: Path, constants: Optional[Path] = None) -> List[Register]:
    """The rows of registers.csv. Values may be numbers or names of constants.csv
    (by default the one beside it); a range is low..high or a group of
    constants.csv, whose values must be contiguous."""
    rows = read_constants(constants or Path(path).parent / "constants.csv")
    value_of = {name: value for _group, name, value in rows}

    def value(text: str, what: str) -> int:
        try:
            return value_of[text] if text in value_of else int(text, 0)
        except ValueError:
            raise ValueError(f"{path}: {what}: {text!r} is neither a number nor a constant") from None

    out: List[Register] = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            name, text = row["register"], row["range"]
            what = f"{name}: range"
            if not text:
                low = high = None
                valid = ""
            elif ".." in text:
                lo_text, hi_text = text.split("..")
                low, high = value(lo_text, what), value(hi_text, what)
                valid = "..".join(t if t not in value_of else f"0x{value_of[t]:X}" for t in (lo_text, hi_text))
            else:
                group = {}
                for g, n, v in rows:
                    if g == text:
                        group.setdefault(v, n)  # the first name of a value (PMDTrapezoidalProfile)
                if not group or sorted(group) != list(range(min(group), max(group) + 1)):
                    raise ValueError(f"{path}: {what}: {text!r} is no group of contiguous values in constants.csv")
                low, high = min(group), max(group)
                names = [f"{v} ({group[v]})" for v in sorted(group)]
                valid = ", ".join(names[:-1]) + " or " + names[-1] if len(names) > 1 else names[0]
            if row["access"] not in ("rw", "ro") or row["buffered"] not in ("", "profile", "filter"):
                raise ValueError(f"{path}: {name}: access is rw or ro, buffered is profile, filter or empty")
            if (low is None) != (row["error"] == ""):
                raise ValueError(f"{path}: {name}: a range needs the error code that refuses it, and only a range")
            if row["error"] and row["error"] not in value_of:
                raise ValueError(f"{path}: {name}: error {row['error']!r} is not a constant")
            out.append(
                Register(
                    name,
                    row["storage"],
                    row["access"],
                    value(row["reset"], f"{name}: reset") if row["reset"] else None,
                    row["reset"],
                    low,
                    high,
                    valid,
                    row["error"],
                    value_of.get(row["error"], 0),
                    row["buffered"],
                    row["guard"],
                    row["note"],
                )
            )
    if len({r.name for r in out}) != len(out):
        raise ValueError(f"{path}: duplicate register")
    return out


def read_log_categories(path: Path) -> List[Tuple[str, str]]:
    """(name, description) rows of log_categories.csv, in the order of the C enum PmdLogCategory."""
    with open(path, newline="") as f:
        return [(r["name"], r["description"]) for r in csv.DictReader(f)]


def read_constants(path: Path) -> List[Tuple[str, str, int]]:
    """(group, C-Motion name, value) rows."""
    with open(path, newline="") as f:
        return [(r["group"], r["name"], int(r["value"], 0)) for r in csv.DictReader(f)]


@dataclass(frozen=True)
class CMotionCall:
    """A C-Motion call that is not a command of commands.csv under its own name and arguments: a row
    of cmotion_calls.csv. With an opcode it is sent to the chip like any command (a Magellan-only
    opcode of out_of_scope.csv, or a Navigator opcode under the 5.x name or argument types); without
    one it is a library call written in host/c (opening, closing, messages), listed for the docs."""

    name: str
    opcode: Optional[int]
    scope: str
    era: Tuple[str, ...]  # the generations whose API has the name: ("2",), ("5",), ("2", "5")
    args: Tuple[Field, ...]
    arg_words: int
    reply: Tuple[Field, ...]
    reply_words: int
    inherit: bool  # no fields given: the opcode's commands.csv fields
    types: Dict[str, str]  # field -> the C type the generation's header gives it, where not its kind's
    summary: str


def read_cmotion_calls(path: Path, constants: Optional[Path] = None) -> List[CMotionCall]:
    """The rows of cmotion_calls.csv (fields in commands.csv's notation)."""
    fields = read_fields(constants or Path(path).parent / "constants.csv")
    out: List[CMotionCall] = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            args, nargs = parse_fields(row["args"], fields)
            reply, nreply = parse_fields(row["reply"], fields)
            era = tuple(row["era"].split())
            if not era or set(era) - {"2", "5"}:
                raise ValueError(f"{path}: {row['call']}: era must be 2, 5 or '2 5'")
            types = dict(t.split("=", 1) for t in row["types"].split())
            out.append(
                CMotionCall(
                    row["call"],
                    int(row["opcode"], 16) if row["opcode"] else None,
                    row["scope"],
                    era,
                    args,
                    nargs,
                    reply,
                    nreply,
                    not row["args"] and not row["reply"],
                    types,
                    row["summary"],
                )
            )
    if len({c.name for c in out}) != len(out):
        raise ValueError(f"{path}: a call twice")
    return out


def read_cmotion_names(path: Path) -> List[Tuple[str, str, int]]:
    """(the 5.x type name, the constant's name, value) rows of cmotion_names.csv."""
    with open(path, newline="") as f:
        return [(r["group"], r["name"], int(r["value"], 0)) for r in csv.DictReader(f)]


def read_cmotion_errors(path: Path) -> List[Tuple[str, int, str]]:
    """(name, value, the vendor's message) rows of cmotion_errors.csv."""
    with open(path, newline="") as f:
        return [(r["name"], int(r["value"], 0), r["message"]) for r in csv.DictReader(f)]
