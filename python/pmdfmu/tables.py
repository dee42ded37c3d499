"""The interface tables under modelDescription/: variables, commands, constants.

This module has no third-party imports: the build's code generator
(modelDescription/generate.py) loads it by path, and the harness uses it to
build its C-Motion calls, so both read the tables the same way.
"""
from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path
from typing import List, Tuple

AXES = 4


@dataclass(frozen=True)
class Variable:
    """One FMU variable, expanded from a row of variables.csv."""
    name: str           # e.g. "axis2.commandedPosition", "host.word[3]"
    family: str         # the row's name pattern as a C identifier, e.g. "axis_commandedPosition"
    index: int          # axis number 0..3, array element 0..n-1, else 0
    vr: int
    type: str           # FMI 2: Real, Integer, Boolean
    fmi3Type: str       # FMI 3: Float64, Int32, UInt32, UInt16, Boolean
    causality: str      # parameter, input, output
    variability: str
    start: str          # "" for outputs
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
            rest = (row["type"], row["fmi3Type"], row["causality"], row["variability"], row["start"],
                    row["description"])
            m = re.fullmatch(r"(.*)\[(\d+)\]", pattern)
            if "{axis}" in pattern:
                for axis in range(AXES):
                    out.append(Variable(pattern.replace("{axis}", str(axis + 1)), _family(pattern), axis,
                                        vr + 100 * axis, *rest))
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
    index: int          # axis number 0..3, else 0
    vr: int
    count: int          # array elements, 1 for a scalar
    type: str           # Float64, Int32, UInt32, UInt16, Boolean
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
        out.append(Variable3(m.group(1) if m else v.name, v.family, 0 if m else v.index, v.vr, 1, v.fmi3Type,
                             v.causality, v.variability, v.start, v.description))
    return out


@dataclass(frozen=True)
class Field:
    """One argument or reply value of a command, as C-Motion passes it.

    kind is u16/i16 (one word), u32/i32 (two words, high word first) or bits
    (width bits at shift inside one word); fixed is the fixed-point format of a
    32-bit value ("16.16" or "0.32"), which scripts may write as a decimal."""
    name: str
    kind: str
    word: int
    shift: int = 0
    width: int = 16
    fixed: str = ""

    @property
    def signed(self) -> bool:
        return self.kind in ("i16", "i32")


def parse_fields(spec: str) -> Tuple[Tuple[Field, ...], int]:
    """Parses an args/reply cell: space-separated words, each `name:u16|i16|u32|i32`
    (a 32-bit one may add `:16.16` or `:0.32`) or a packed word
    `name@shift:width|name@shift:width...`. Returns (fields, word count)."""
    fields: List[Field] = []
    word = 0
    for token in spec.split():
        if "@" in token:
            used = 0
            for part in token.split("|"):
                m = re.fullmatch(r"(\w+)@(\d+):(\d+)", part)
                if not m:
                    raise ValueError(f"bad packed field {part!r}")
                shift, width = int(m.group(2)), int(m.group(3))
                bits = ((1 << width) - 1) << shift
                if used & bits or shift + width > 16:
                    raise ValueError(f"overlapping or oversized field {part!r}")
                used |= bits
                fields.append(Field(m.group(1), "bits", word, shift, width))
            word += 1
        else:
            name, kind, *fixed = token.split(":")
            if kind not in ("u16", "i16", "u32", "i32") or fixed not in ([], ["16.16"], ["0.32"]) or \
                    (fixed and not kind.endswith("32")):
                raise ValueError(f"bad field type {token!r}")
            fields.append(Field(name, kind, word, 0, 32 if kind.endswith("32") else 16, "".join(fixed)))
            word += 2 if kind.endswith("32") else 1
    return tuple(fields), word


@dataclass(frozen=True)
class Command:
    opcode: int
    name: str
    scope: str          # "axis": acts on the axis in the instruction word; "chip": chip-wide
    args: Tuple[Field, ...]
    arg_words: int
    reply: Tuple[Field, ...]
    reply_words: int
    summary: str


def read_commands(path: Path) -> List[Command]:
    out: List[Command] = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            args, nargs = parse_fields(row["args"])
            reply, nreply = parse_fields(row["reply"])
            if row["scope"] not in ("axis", "chip"):
                raise ValueError(f"{row['name']}: scope must be axis or chip")
            out.append(Command(int(row["opcode"], 16), row["name"], row["scope"], args, nargs,
                               reply, nreply, row["summary"]))
    if len({c.opcode for c in out}) != len(out) or len({c.name for c in out}) != len(out):
        raise ValueError(f"{path}: duplicate opcode or name")
    return out


def read_constants(path: Path) -> List[Tuple[str, str, int]]:
    """(group, C-Motion name, value) rows."""
    with open(path, newline="") as f:
        return [(r["group"], r["name"], int(r["value"], 0)) for r in csv.DictReader(f)]
