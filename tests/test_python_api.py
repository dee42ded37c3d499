# SPDX-License-Identifier: BSD-2-Clause
"""The Python API explains itself: the C-Motion methods made from the command table
have real signatures, names and docstrings, and wrong calls say which call was wrong."""

import ast
import inspect
import pydoc
from pathlib import Path

import pytest

import pmdfmu
from pmdfmu import profile
from pmdfmu.chip import COMMANDS, Axis, FMUError
from scenarios import busy_chip
from states import snapshot

PACKAGE = Path(pmdfmu.__file__).parent


def test_every_command_is_a_method_of_the_class_with_its_arguments_as_parameters(chip):
    ax = chip.axis(0)
    for name, command in COMMANDS.items():
        method = vars(Axis)[name]  # on the class itself, not made on attribute lookup
        assert method.__name__ == name
        assert method.__qualname__ == f"Axis.{name}"
        assert method.__module__ == Axis.__module__ == "pmdfmu.calls"  # the calls' layer (calls.py)
        assert list(inspect.signature(getattr(ax, name)).parameters) == [f.name for f in command.args]
        assert list(inspect.signature(method).parameters) == ["self"] + [f.name for f in command.args]
        assert name in dir(ax)


def test_signatures_read_as_c_motion_writes_them(chip):
    ax = chip.axis(0)
    assert str(inspect.signature(ax.SetPosition)) == "(position)"
    assert str(inspect.signature(ax.SetBufferStart)) == "(bufferID, address)"
    assert str(inspect.signature(ax.SetTraceStart)) == "(triggerAxis, condition, bit, state)"
    assert str(inspect.signature(ax.GetActivityStatus)) == "()"


def test_docstrings_give_the_summary_the_formats_and_what_a_call_returns(chip):
    ax = chip.axis(0)
    for name, command in COMMANDS.items():
        doc = inspect.getdoc(getattr(ax, name))
        assert doc.startswith(command.summary)
        assert f"0x{command.opcode:02X}" in doc
        for f in command.args + command.reply:
            assert f"{f.name}: " in doc
    velocity = pydoc.render_doc(ax.SetVelocity, renderer=pydoc.plaintext)
    assert "SetVelocity(velocity)" in velocity
    assert "16.16" in velocity and "fixed_16_16" in velocity and "Returns None." in velocity
    assert "0.32" in inspect.getdoc(ax.SetJerk) and "fixed_0_32" in inspect.getdoc(ax.SetJerk)
    assert "the 16.16 word SetVelocity takes" in " ".join(inspect.getdoc(ax.GetVelocity).split())
    trace = inspect.getdoc(ax.SetTraceStart)
    assert "condition: packed field PMDTraceCondition: bits 4..7 of word 1, 0 .. 15" in trace
    version = inspect.getdoc(ax.GetVersion)
    assert "Returns the tuple (generation, motorType, numberAxes, special, custom, major, minor)" in version
    assert "16-bit unsigned integer" in inspect.getdoc(ax.SetProfileMode)
    assert "chip-wide" in inspect.getdoc(ax.SetBufferStart)


def test_help_on_the_class_lists_the_c_motion_calls():
    text = pydoc.render_doc(Axis, renderer=pydoc.plaintext)
    for name in ("SetPosition(self, position)", "GetVersion(self)", "SetBufferStart(self, bufferID, address)"):
        assert name in text


def test_a_wrong_number_of_arguments_raises_type_error_naming_the_call_and_sends_nothing(any_chip):
    ax = any_chip.axis(1)
    strobe = any_chip.get("host.strobe")
    with pytest.raises(TypeError, match=r"^SetPosition\(position\): too many positional arguments"):
        ax.SetPosition(1, 2)
    with pytest.raises(
        TypeError,
        match=r"^SetBufferStart\(bufferID, address\): missing a required argument: "
        r"'address'",
    ):
        ax.SetBufferStart(2)
    with pytest.raises(TypeError, match=r"^GetPosition\(\): too many positional arguments"):
        ax.GetPosition(0)
    with pytest.raises(TypeError, match=r"^SetVelocity\(velocity\): got an unexpected keyword argument 'speed'"):
        ax.SetVelocity(0, speed=1)
    assert any_chip.get("host.strobe") == strobe


def test_arguments_may_be_named_as_in_the_signature(any_chip):
    ax = any_chip.axis(2)
    ax.SetBufferStart(address=0x300, bufferID=5)
    assert ax.GetBufferStart(bufferID=5) == 0x300
    ax.SetPosition(position=-7)
    assert ax.GetPosition() == -7


def test_chip_command_still_takes_a_name_and_an_argument_list(chip):
    chip.command(3, "SetPosition", [1234])
    assert chip.command(3, "GetPosition") == 1234 == chip.axis(3).GetPosition()
    with pytest.raises(TypeError, match=r"SetPosition\(position\) takes 1 arguments, 0 given"):
        chip.command(3, "SetPosition", [])


def test_an_unknown_method_says_it_is_not_a_command(chip):
    with pytest.raises(AttributeError, match="SetWarpSpeed is not a command of this chip"):
        _ = chip.axis(0).SetWarpSpeed


def test_a_batch_the_fmu_did_not_acknowledge_raises_fmu_error(chip, monkeypatch):
    # the native host port (host_port.c) reads host.ack where the port says: here host.error (0), never the strobe
    monkeypatch.setattr(chip._port, "ack", chip._vr["host.error"])
    with pytest.raises(FMUError, match="did not execute the batch"):
        chip.axis(0).GetPosition()
    with pytest.raises(FMUError, match="did not execute the batch"):
        chip.batch([0x4A])


def test_no_assert_statement_does_a_runtime_check_in_the_package():
    for path in sorted(PACKAGE.glob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        asserts = [node.lineno for node in ast.walk(tree) if isinstance(node, ast.Assert)]
        assert not asserts, f"{path.name}: assert at lines {asserts} (python -O drops it): raise instead"


# ---- the harness keeps no copy of what the FMU knows ----


def test_get_state_is_the_fmus_serialized_state_as_it_is(any_chip):
    busy_chip(any_chip)
    any_chip.run(10)
    assert any_chip.get_state() == snapshot(any_chip)


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_grid_a_script_changes_is_read_from_the_fmu_cycle_by_cycle(tmp_path, fmi_version):
    script = tmp_path / "slower.script"
    script.write_text("@10\nSetSampleTime(Axis1, 200)\n")
    with pmdfmu.Chip(fmi_version=fmi_version, script=script) as chip:
        rec = chip.run(30, record=["axis1.activityStatus"])  # one doStep per cycle, in FMI 3 too
        assert list(rec["cycle"]) == list(range(30))  # no cycle skipped or run twice
        assert chip.cycle_time == chip.get("activeCycleTime") == 200e-6
        assert chip.cycles == chip.get("nextCycle") == 30
        assert chip.time == chip.get("nextCycleTime")


def test_what_a_script_addresses_comes_from_the_compiled_script(tmp_path):
    script = tmp_path / "axes.script"
    script.write_text(
        "# Axis3 is named only in this comment\n"
        "@ 0\nSetPosition(Axis2, 5);\nMultiUpdate(Axis4, PMDAxis2Mask);\n"
        "@ 250\nSetStopMode(Axis2, PMDAbruptStop);\nUpdate(Axis2);\n"
    )
    with pmdfmu.Chip(script=script) as chip:
        assert profile.script_axes(chip) == [1, 3]
        rec = profile.run_script(chip)
        assert rec["cycle"][-1] >= 250 and "axis4.commandedPosition" in rec.dtype.names
    with pmdfmu.Chip() as chip:  # no script: axis 1 alone
        assert profile.script_axes(chip) == [0]


def test_no_module_of_the_package_parses_scripts_again():
    for name in ("cli.py", "sweep.py", "profile.py"):
        tree = ast.parse((PACKAGE / name).read_text())
        imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names}
        assert "re" not in imported, f"{name} imports re: ask the compiled script (script.axes, script.lastCycle)"


# ---- register fields: declared once, in constants.csv ----


def test_field_ex_reads_a_field_of_a_word_or_of_a_recorded_column(chip):
    assert pmdfmu.field_ex(pmdfmu.PMDActivityProfileSegmentMask, "PMDActivityProfileSegment") == 7
    assert pmdfmu.field_ex(pmdfmu.PMDActivityProfileModeMask, "PMDActivityProfileSegment") == 0
    ax = chip.axis(0)
    ax.SetProfileMode(pmdfmu.PMDVelocityContouringProfile)
    ax.SetVelocity(pmdfmu.fixed_16_16(1))
    ax.SetAcceleration(pmdfmu.fixed_16_16(1))
    ax.Update()
    rec = chip.run(3, record=["axis1.activityStatus"])
    assert (
        list(pmdfmu.field_ex(rec["axis1.activityStatus"], "PMDActivityProfileMode"))
        == [pmdfmu.PMDVelocityContouringProfile] * 3
    )
    assert pmdfmu.field_ex(ax.GetActivityStatus(), "PMDActivityProfileMode") == pmdfmu.PMDVelocityContouringProfile


def test_field_dp_puts_a_value_into_a_field_and_leaves_the_others():
    word = pmdfmu.field_dp(pmdfmu.PMDActivityInMotionMask, "PMDActivityProfileMode", pmdfmu.PMDExternalProfile)
    assert word & pmdfmu.PMDActivityInMotionMask
    assert pmdfmu.field_ex(word, "PMDActivityProfileMode") == pmdfmu.PMDExternalProfile
    assert pmdfmu.field_dp(word, "PMDActivityProfileMode", 0) == pmdfmu.PMDActivityInMotionMask


def test_the_instruction_word_is_made_of_its_declared_fields(chip):
    from pmdfmu.chip import instruction_word

    set_position = COMMANDS["SetPosition"].opcode
    word = instruction_word(set_position, pmdfmu.PMDAxis3)
    assert pmdfmu.field_ex(word, "PMDInstructionOpcode") == set_position
    assert pmdfmu.field_ex(word, "PMDInstructionAxis") == pmdfmu.PMDAxis3
    assert chip.batch([word, 0, 5]) == (0, [])
    assert chip.axis(pmdfmu.PMDAxis3).GetPosition() == 5


def test_profile_keeps_no_status_constants_of_its_own():
    tree = ast.parse((PACKAGE / "profile.py").read_text())
    numbers = [
        t.id
        for node in tree.body
        if isinstance(node, ast.Assign) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, int)
        for t in node.targets
    ]
    assert not numbers, f"profile.py defines {numbers}: use the constants and fields of constants.csv"
