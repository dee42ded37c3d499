# SPDX-License-Identifier: BSD-2-Clause
"""Register fields are declared once, as the *Mask constants of constants.csv
: the command table's packed values name them, and the C
header the FMU's sources carry derives NAME_SHIFT and NAME_LENGTH from them."""

import re
import zipfile

import pytest

import pmdfmu
from pmdfmu import tables
from pmdfmu.chip import default_fmu

TABLES = pmdfmu.tables_dir()
FIELDS = tables.read_fields(TABLES / "constants.csv")


def test_a_field_is_its_mask_without_the_suffix():
    assert FIELDS["PMDActivityProfileSegment"] == (13, 3, 0xE000)
    assert FIELDS["PMDActivityProfileMode"] == (3, 3, 0x0038)
    assert FIELDS["PMDEventMotionError"] == (4, 1, 0x0010)
    f = FIELDS["PMDTraceCondition"]
    assert f.ex(0x1234) == 3 and f.dp(0x1234, 0xF) == 0x12F4 and f.dp(0, 0x1F) == 0xF0


@pytest.mark.parametrize("mask", [0x0005, 0x0101, 0])
def test_a_mask_that_is_not_one_run_of_bits_is_no_field(mask):
    with pytest.raises(ValueError):
        tables.bit_field("PMDBadMask", mask)


def test_packed_values_name_declared_fields():
    packed = [f for c in tables.read_commands(TABLES / "commands.csv") for f in c.args + c.reply if f.kind == "bits"]
    assert packed
    for f in packed:
        declared = FIELDS[f.register_field]
        assert (f.shift, f.width) == (declared.shift, declared.length)


def test_a_packed_value_must_name_a_mask():
    with pytest.raises(ValueError, match="not a mask"):
        tables.parse_fields("axis@PMDNoSuchField", FIELDS)
    with pytest.raises(ValueError):
        tables.parse_fields("axis@0:4", FIELDS)  # bit positions are the constants' business
    with pytest.raises(ValueError, match="overlapping"):
        tables.parse_fields("a@PMDActivityProfileMode|b@PMDActivityAtMaximumVelocity|c@PMDTraceCondition", FIELDS)


def test_the_c_header_derives_shift_and_length_from_each_mask():
    header = zipfile.ZipFile(default_fmu()).read("sources/pmd_constants.h").decode()
    masks = dict(re.findall(r"#define (\w+)Mask \((0x[0-9A-F]+)\)", header))
    shifts = dict(re.findall(r"#define (\w+)_SHIFT (\d+)", header))
    lengths = dict(re.findall(r"#define (\w+)_LENGTH (\d+)", header))
    assert set(masks) == set(shifts) == set(lengths) == set(FIELDS)
    for name, f in FIELDS.items():
        assert (int(masks[name], 16), int(shifts[name]), int(lengths[name])) == (f.mask, f.shift, f.length)
