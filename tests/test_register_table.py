# SPDX-License-Identifier: BSD-2-Clause
"""The register table (modelDescription/registers.csv): every
plain stored register resets to its row's value, keeps what its Set stores,
refuses a value outside its range with its row's error code and message, and
has no hand-written handler."""

import re
import zipfile

import pytest

import pmdfmu
from pmdfmu import COMMANDS, PMDError, tables
from pmdfmu.chip import default_fmu

REGISTERS = tables.read_registers(pmdfmu.tables_dir() / "registers.csv")
FIELD_RANGE = {"u16": (0, 0xFFFF), "i16": (-0x8000, 0x7FFF), "u32": (0, 0xFFFFFFFF), "i32": (-0x80000000, 0x7FFFFFFF)}


def names(access):
    return [r.name for r in REGISTERS if r.access in access]


def register(name):
    return next(r for r in REGISTERS if r.name == name)


@pytest.mark.parametrize("name", [r.name for r in REGISTERS if r.reset is not None])
def test_a_register_reads_its_reset_value_after_a_reset_on_every_axis(chip, name):
    r = register(name)
    for n in range(4):
        ax = chip.axis(n)
        if r.access == "rw":
            low, high = (r.low, r.high) if r.low is not None else FIELD_RANGE[COMMANDS["Set" + name].args[0].kind]
            getattr(ax, "Set" + name)(high if high != r.reset else low)
        ax.Reset()
        assert getattr(ax, "Get" + name)() == r.reset, (name, n)


@pytest.mark.parametrize("name", names(["rw"]))
def test_a_register_keeps_each_end_of_its_range(chip, name):
    r = register(name)
    low, high = (r.low, r.high) if r.low is not None else FIELD_RANGE[COMMANDS["Set" + name].args[0].kind]
    ax = chip.axis(3)
    for value in (low, high):
        getattr(ax, "Set" + name)(value)
        assert getattr(ax, "Get" + name)() == value


@pytest.mark.parametrize("name", [r.name for r in REGISTERS if r.low is not None])
def test_a_value_outside_the_range_is_refused_with_the_rows_code_and_reason(name):
    with pmdfmu.Chip(log_categories=["errors"]) as chip:
        refused_outside_the_range(chip, register(name))


def refused_outside_the_range(chip, r):
    name = r.name
    kind_low, kind_high = FIELD_RANGE[COMMANDS["Set" + name].args[0].kind]
    ax = chip.axis(1)
    before = getattr(ax, "Get" + name)()
    outside = [v for v in (r.low - 1, r.high + 1) if kind_low <= v <= kind_high]
    assert outside
    for value in outside:
        chip.messages.clear()
        with pytest.raises(PMDError) as e:
            getattr(ax, "Set" + name)(value)
        assert e.value.code == r.error_code
        assert getattr(ax, "Get" + name)() == before
        text = " ".join(m.message for m in chip.messages)
        assert f"Set{name}(" in text and r.valid in text
        assert "axis 2: " in text or COMMANDS["Set" + name].scope == "chip"


@pytest.mark.slow
def test_registers_have_no_handler_of_their_own():
    fmu = zipfile.ZipFile(default_fmu())
    sources = " ".join(fmu.read(n).decode() for n in fmu.namelist() if n.startswith("sources/") and n[-2:] in ".c.h")
    served = {p + r.name for r in REGISTERS for p in (("Get", "Set") if r.access == "rw" else ("Get",))}
    assert served <= set(COMMANDS)
    assert not {name for name in served if re.search(rf"\bcmd_{name}\b", sources)}
    assert all(re.search(rf"\bcmd_{name}\b", sources) for name in set(COMMANDS) - served)
