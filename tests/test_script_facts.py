# SPDX-License-Identifier: BSD-2-Clause
"""What the compiled script knows about itself: the axes its
calls address (script.axes) and the time of its last @ line (script.lastCycle),
as FMU outputs, so that no one parses a script again to find them."""

from pathlib import Path

import pytest

import pmdfmu
from states import InitializationChip

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def facts(chip):
    return chip.get("script.axes"), chip.get("script.lastCycle")


@pytest.mark.parametrize("version", [2, 3])
def test_the_axes_and_the_last_time_of_a_script(version, tmp_path):
    script = tmp_path / "s.pmd"
    script.write_text(
        "# Axis4 is named only in this comment\n"
        "@ 0\n"
        "SetPosition(Axis1, 100);      // and Axis2 only here\n"
        "SetSampleTime(PMDAxis3, 200)   # a chip-wide command: its axis argument counts\n"
        "@ 0x20\n"
        "Update(Axis1);\n"
        "@ 500\n"
    )  # a last time with no call after it
    with pmdfmu.Chip(fmi_version=version, script=script) as chip:
        assert facts(chip) == (0b101, 500.0)
        chip.run(10)
        assert facts(chip) == (0b101, 500.0)


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_without_times_or_calls(version, tmp_path):
    only_calls, empty = tmp_path / "calls.pmd", tmp_path / "empty.pmd"
    only_calls.write_text("SetVelocity(Axis2, 5)\nSetVelocity(PMDAxis4, 5)\n")
    empty.write_text("# nothing\n")
    with pmdfmu.Chip(fmi_version=version, script=only_calls) as chip:
        assert facts(chip) == (0b1010, 0.0)
    with pmdfmu.Chip(fmi_version=version, script=empty) as chip:
        assert facts(chip) == (0, 0.0)
    with pmdfmu.Chip(fmi_version=version) as chip:
        assert facts(chip) == (0, 0.0)


def test_the_example_script_and_a_large_time(tmp_path):
    with pmdfmu.Chip(script=EXAMPLES / "two_axis.script") as chip:
        assert facts(chip) == (0b11, 3000.0)
    script = tmp_path / "far.pmd"
    script.write_text("@ 100000000000000000\nUpdate(Axis1)\n")  # 10^17 cycles: a double holds it exactly
    with pmdfmu.Chip(fmi_version=3, script=script) as chip:
        assert facts(chip) == (0b1, 1e17)


@pytest.mark.parametrize("version", [2, 3])
def test_before_the_end_of_initialization_there_is_no_compiled_script(version):
    chip = InitializationChip(version)
    try:
        assert (chip.get("script.axes"), chip.get("script.lastCycle")) == (0, 0.0)
    finally:
        chip.free()


@pytest.mark.parametrize("version", [2, 3])
def test_a_reset_forgets_the_script(version, tmp_path):
    script = tmp_path / "s.pmd"
    script.write_text("@ 7\nUpdate(Axis2)\n")
    with pmdfmu.Chip(fmi_version=version, script=script) as chip:
        assert facts(chip) == (0b10, 7.0)
        chip.reinitialize(script="")
        assert facts(chip) == (0, 0.0)
