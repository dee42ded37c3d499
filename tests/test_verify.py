# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu.verify (docs/verify.md): a run against a golden trace and assertions, in Python.
Goldens are written by the same run (`pmdfmu run`'s profile.run_profile), then the profile or the
limits are changed and the failure must name the right cycle, column, segment and values."""

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import field_ex, profile
from pmdfmu.testing import assert_trajectory
from pmdfmu.verify import InputError, check_assertions, load_assertions, read_recording, write_recording

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCRIPT = EXAMPLES / "two_axis.script"
SQUARE = EXAMPLES / "square.csv"
LEG = 500  # square.csv: every segment lasts 500 cycles


@pytest.fixture(scope="module")
def goldens(tmp_path_factory):
    """The square table and the two-axis script recorded as `pmdfmu run` records them, as CSV and .npz."""
    folder = tmp_path_factory.mktemp("goldens")
    square, script = profile.run_profile(SQUARE), profile.run_profile(SCRIPT)
    for name, run in (("square", square), ("script", script)):
        write_recording(folder / f"{name}.csv", run.recording)
        write_recording(folder / f"{name}.npz", run.recording)
    return folder, square.recording, script.recording


def changed_square(tmp_path, old, new):
    text = SQUARE.read_text()
    assert text.count(old) == 1
    path = tmp_path / "changed.csv"
    path.write_text(text.replace(old, new))
    return path


def test_a_run_passes_against_its_own_golden_csv_and_npz(goldens):
    folder, square, script = goldens
    for suffix in ("csv", "npz"):
        result = pmdfmu.verify(SQUARE, against=folder / f"square.{suffix}")
        assert result.passed and result.exit_status == 0 and not result.failures
        assert result.cases[0].cycles == len(square) and [c.name for c in result.cases[0].checks] == [
            "profile ended",
            "golden trace",
        ]
        assert pmdfmu.verify(SCRIPT, against=folder / f"script.{suffix}", fmi_version=3).passed


def test_csv_and_npz_goldens_read_back_the_recording_exactly(goldens):
    folder, square, script = goldens
    for rec, name in ((square, "square"), (script, "script")):
        for suffix in ("csv", "npz"):
            back = read_recording(folder / f"{name}.{suffix}")
            assert back.dtype.names == rec.dtype.names
            for c in rec.dtype.names:
                assert np.array_equal(back[c], rec[c]), (suffix, c)  # Reals too: repr round-trips


def test_a_changed_segment_is_caught_at_its_first_cycle_with_its_segment(goldens, tmp_path):
    """Axis 2's fourth row (its return leg, rows 1500..1999 of the recording) at half the speed: the
    first difference is the leg's first cycle, in axis2.commandedVelocity; the chip's position buffer
    of axis 2 has read that row (read index 4: one past it) and the profile segment field is the
    golden's."""
    folder, square, _ = goldens
    table = changed_square(tmp_path, "2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500")
    result = pmdfmu.verify(table, against=folder / "square.npz", out=tmp_path / "out")
    assert not result.passed and result.exit_status == 1
    f, *others = result.failures  # the first difference, then each other column's first
    assert [o.column for o in others] == ["axis2.velocity", "axis2.commandedPosition", "axis2.position"]
    row = 3 * LEG
    assert (f.check, f.column, f.axis, f.row, f.cycle) == (
        "golden",
        "axis2.commandedVelocity",
        2,
        row,
        int(square["cycle"][row]),
    )
    assert (f.expected, f.actual) == (-0x20000, -0x10000)
    assert f.segment == field_ex(int(square["axis2.activityStatus"][row]), "PMDActivityProfileSegment")
    assert (f.buffer, f.read_index) == (7, 4)  # axis 2's buffers are 7..11 (axis 1's 2..6); row 4 read
    assert (
        f"first difference at cycle {f.cycle} (row {row}): axis2.commandedVelocity expected -131072 "
        "(-2 counts/cycle = -20000 counts/s), actual -65536 (-1 counts/cycle = -10000 counts/s)" in f.message
    )
    assert "axis 2 position buffer 7 read index 4" in f.message
    case = result.cases[0]
    assert case.plot == tmp_path / "out" / "changed.diff.png" and case.plot.stat().st_size > 10_000
    assert np.array_equal(
        read_recording(case.actual)["axis2.commandedVelocity"],
        profile.run_profile(table).recording["axis2.commandedVelocity"],
    )


def test_a_changed_first_segment_shows_in_axis_1_at_the_profiles_first_cycle(goldens, tmp_path):
    folder, square, _ = goldens
    table = changed_square(tmp_path, "1,0,0x20000,0,0,500", "1,0,0x20001,0,0,500")
    f = pmdfmu.verify(table, against=folder / "square.csv").failures[0]
    assert (f.column, f.row, f.cycle, f.read_index) == ("axis1.commandedVelocity", 0, int(square["cycle"][0]), 1)


def test_a_different_length_fails_and_says_so(goldens, tmp_path):
    folder, square, _ = goldens
    table = changed_square(tmp_path, "1,0,0,0,0,500\n1,0,0,0,0,0", "1,0,0,0,0,600\n1,0,0,0,0,0")
    failures = pmdfmu.verify(table, against=folder / "square.csv").failures
    length = [f for f in failures if f.check == "length"]
    assert len(length) == 1 and (length[0].expected, length[0].actual) == (len(square), len(square) + 100)
    assert f"the run recorded {len(square) + 100} cycles" in length[0].message


def test_reals_are_exact_by_default_and_take_a_tolerance_on_request(goldens, tmp_path):
    folder, square, _ = goldens
    golden = square.copy()
    golden["axis1.velocity"][700] += 1e-7
    write_recording(tmp_path / "g.npz", golden)
    [f] = pmdfmu.verify(SQUARE, against=tmp_path / "g.npz").failures
    assert (f.column, f.row) == ("axis1.velocity", 700)
    assert pmdfmu.verify(SQUARE, against=tmp_path / "g.npz", tolerance={"axis1.velocity": 1e-6}).passed
    assert pmdfmu.verify(SQUARE, against=tmp_path / "g.npz", assertions={"tolerance": {"axis1.velocity": 1e-6}}).passed
    assert not pmdfmu.verify(SQUARE, against=tmp_path / "g.npz", tolerance={"axis1.velocity": 1e-8}).passed


def test_a_golden_of_other_axes_fails_naming_the_columns(goldens, tmp_path):
    """A golden of axis 1 alone: the run of both axes records axis 2's columns, which it lacks."""
    folder, square, _ = goldens
    write_recording(tmp_path / "axis1.csv", square[[n for n in square.dtype.names if not n.startswith("axis2")]])
    [f] = pmdfmu.verify(SQUARE, against=tmp_path / "axis1.csv").failures
    assert f.check == "golden" and f.column == "axis2.commandedPosition"
    assert "the run records axis2.commandedPosition, axis2.commandedVelocity" in f.message


# ---- assertions --------------------------------------------------------------------------------


def one_failure(result, check):
    failures = [f for f in result.failures if f.check == check]
    assert len(failures) == 1, result.report()
    return failures[0]


@pytest.fixture(scope="module")
def script_run():
    run = profile.run_profile(SCRIPT, record=[f"axis{n}.eventStatus" for n in range(1, 5)])
    return run.recording


def test_the_demo_limits_pass(script_run):
    result = pmdfmu.verify(SCRIPT, assertions=EXAMPLES / "ci" / "two_axis.toml")
    assert result.passed, result.report()
    assert len(result.cases[0].checks) == 17  # the profile ended, 7 of axis 1, 8 of axis 2, host errors


@pytest.mark.parametrize("units,column,scale", [("counts", "velocity", 1), ("raw", "commandedVelocity", 1)])
def test_a_velocity_limit_reports_axis_cycle_value_and_limit(script_run, units, column, scale):
    values = np.abs(script_run[f"axis2.{column}"].astype(np.float64))
    limit = float(values.max()) - 1
    f = one_failure(
        pmdfmu.verify(SCRIPT, assertions={"units": units, "axis2": {"max_velocity": limit}}), "max_velocity"
    )
    first = int(np.argmax(values > limit))
    assert (f.axis, f.row, f.cycle, f.value, f.limit) == (
        2,
        first,
        int(script_run["cycle"][first]),
        float(script_run[f"axis2.{column}"][first]),
        limit,
    )
    assert "axis 2: |velocity| " in f.message and f"at cycle {f.cycle}" in f.message


def test_acceleration_and_jerk_limits(script_run):
    acc = script_run["axis2.acceleration"]
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"axis2": {"max_acceleration": 4e6}}), "max_acceleration")
    assert f.row == int(np.argmax(np.abs(acc) > 4e6)) and abs(f.value) > 4e6
    jerk = np.diff(acc) / 1e-4  # counts/s^3 from the recorded acceleration
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"axis2": {"max_jerk": 5e8}}), "max_jerk")
    assert f.row == int(np.argmax(np.abs(jerk) > 5e8)) + 1 and f.value == jerk[f.row - 1]
    raw = np.diff(script_run["axis2.commandedAcceleration"].astype(np.int64)) * 65536  # 0.32 counts/cycle^3
    limit = int(np.abs(raw).max()) - 1
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"units": "raw", "axis2": {"max_jerk": limit}}), "max_jerk")
    assert f.row == int(np.argmax(np.abs(raw) > limit)) + 1 and f.value == raw[f.row - 1]
    assert "raw 0.32 counts/cycle^3" in f.message


def test_position_window_final_position_and_completion(script_run):
    pos = script_run["axis2.commandedPosition"]
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"all_axes": {"position_max": 4000}}), "position_max")
    assert (f.axis, f.row, f.value, f.limit) == (2, int(np.argmax(pos > 4000)), int(pos[np.argmax(pos > 4000)]), 4000)
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"axis1": {"position_min": 1}}), "position_min")
    assert (f.axis, f.row, f.value) == (1, 0, 0)
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"axis2": {"final_position": 4999}}), "final_position")
    assert (f.value, f.limit, f.row) == (5000, 4999, len(script_run) - 1)
    moving = np.nonzero(script_run["axis2.commandedVelocity"] != 0)[0]
    done = int(script_run["cycle"][moving[-1] + 1])
    assert pmdfmu.verify(SCRIPT, assertions={"axis2": {"complete_by": done}}).passed
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"axis2": {"complete_by": done - 1}}), "complete_by")
    assert (f.axis, f.cycle, f.limit) == (2, done, done - 1)


def test_an_axis_not_recorded_fails(script_run):
    f = one_failure(pmdfmu.verify(SCRIPT, assertions={"axis3": {"max_velocity": 1}}), "max_velocity")
    assert f.axis == 3 and "axis 3 was not recorded" in f.message


LIMIT_SCRIPT = """@ 0
SetProfileMode(Axis1, PMDTrapezoidalProfile);
SetPosition(Axis1, 2000);
SetVelocity(Axis1, 2.0);
SetAcceleration(Axis1, 0.01);
Update(Axis1);
@ 300
SetBufferReadIndex(Axis1, 40, 1);
"""


def test_limit_events_and_host_errors(tmp_path):
    """A positive limit switch trips while the script's move runs: an InPositiveLimit event at that
    cycle; a command the chip refuses (buffer 40 does not exist) is a host I/O error at its cycle."""
    script = tmp_path / "limit.script"
    script.write_text(LIMIT_SCRIPT)
    run = profile.run_profile(script, record=["axis1.eventStatus"])
    status = run.recording["axis1.eventStatus"]
    refused = int(np.argmax(status & pmdfmu.PMDEventInstructionErrorMask))
    assert status[refused] and run.recording["cycle"][refused] == 300
    result = pmdfmu.verify(script, assertions={"no_host_errors": True, "axis1": {"no_events": True}})
    f = one_failure(result, "no_host_errors")
    assert (f.axis, f.cycle, f.value) == (1, 300, 1)
    assert "limit.script:8: the chip refused the command: host I/O error" in f.message
    # no limit input moved: no limit event
    assert [c.passed for c in result.cases[0].checks if c.name.startswith("axis1 no event")] == [True]
    f = one_failure(pmdfmu.verify(script, assertions={"axis1": {"no_events": ["InstructionError"]}}), "no_events")
    assert (f.axis, f.cycle, f.value & pmdfmu.PMDEventInstructionErrorMask) == (1, 300, 0x80)
    assert "event InstructionError at cycle 300" in f.message


def test_a_limit_switch_event_is_caught_at_its_cycle():
    """The chip's limit inputs are FMU inputs, which a script cannot set: check the assertion on a
    recording where the event status shows InPositiveLimit from a cycle on."""
    rec = profile.run_profile(SQUARE, record=["axis1.eventStatus"]).recording
    rec["axis1.eventStatus"][1234:] |= pmdfmu.PMDEventInPositiveLimitMask
    spec = load_assertions({"axis1": {"no_events": True}})
    [check] = check_assertions(spec, rec, [0, 1], 1e-4)
    [f] = check.failures
    assert (f.axis, f.row, f.cycle) == (1, 1234, int(rec["cycle"][1234]))
    assert f"axis 1: event InPositiveLimit at cycle {f.cycle}" in f.message


# ---- malformed inputs: InputError naming file and line ---------------------------------------------


@pytest.mark.parametrize(
    "text,message",
    [
        ("", "g.csv:1: no header"),
        ("axis1.commandedPosition\n1\n", "g.csv:1: no 'cycle' column"),
        ("cycle,axis1.bogus\n0,1\n", "g.csv:1: column 2: 'axis1.bogus' is not an output of the FMU"),
        ("cycle,cycle\n0,1\n", "g.csv:1: column 2: 'cycle' named twice"),
        ("cycle,axis1.commandedPosition\n0,1\n1\n", "g.csv:3: 1 values, the header names 2 columns"),
        (
            "cycle,axis1.commandedPosition\n0,1\n1,x1\n",
            "g.csv:3: column 2 (axis1.commandedPosition): 'x1' is not a number",
        ),
        (
            "cycle,axis1.commandedPosition\n0,1\n1,nan\n",
            "g.csv:3: column 2 (axis1.commandedPosition): 'nan' is not an integer",
        ),
        (
            "cycle,axis1.commandedPosition\n0,1.5\n",
            "g.csv:2: column 2 (axis1.commandedPosition): '1.5' is not an integer",
        ),
    ],
)
def test_a_malformed_golden_csv_is_an_input_error(tmp_path, text, message):
    (tmp_path / "g.csv").write_text(text)
    with pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        pmdfmu.verify(SQUARE, against=tmp_path / "g.csv")


def test_a_malformed_or_missing_npz_is_an_input_error(tmp_path):
    (tmp_path / "g.npz").write_bytes(b"not a zip")
    with pytest.raises(InputError, match="g.npz: cannot read the golden trace"):
        read_recording(tmp_path / "g.npz")
    np.savez_compressed(tmp_path / "h.npz", other=np.zeros(3))
    with pytest.raises(InputError, match="h.npz: no array 'recording'"):
        read_recording(tmp_path / "h.npz")
    with pytest.raises(InputError, match="missing.csv: cannot read the golden trace"):
        read_recording(tmp_path / "missing.csv")


@pytest.mark.parametrize(
    "text,message",
    [
        ("units = counts\n", r"a.toml:1: not TOML: "),
        ("[axis1]\nmax_velocity = 10\nmax_speed = 3\n", "a.toml:3: axis1.max_speed: unknown limit"),
        ("limits = 3\n", "a.toml:1: limits: unknown key"),
        ('units = "mm"\n', "a.toml:1: units: 'mm' is not one of counts, raw"),
        ("[axis2]\nfinal_position = 1.5\n", "a.toml:2: axis2.final_position: 1.5 is not a whole number"),
        ('[axis2]\nmax_jerk = "fast"\n', "a.toml:2: axis2.max_jerk: 'fast' is not a number"),
        ('[all_axes]\nno_events = ["Bogus"]\n', "a.toml:2: all_axes.no_events: unknown event 'Bogus'"),
        ('[tolerance]\n"axis1.speed" = 1e-9\n', "a.toml:2: axis1.speed: unknown column"),
        ("[axis1]\nposition_min = 5\nposition_max = 4\n", "a.toml:2: axis1.position_min: is above position_max"),
        ("[axis1]\nmax_velocity = nan\n", "a.toml:2: axis1.max_velocity: nan is not a finite number"),
        ("[axis1]\nmax_jerk = inf\n", "a.toml:2: axis1.max_jerk: inf is not a finite number"),
        ("[axis2]\ncomplete_by = 1e300\n", "a.toml:2: axis2.complete_by: 1e[+]300 is not a finite number in"),
        ("[axis2]\nmax_velocity = -1e19\n", "a.toml:2: axis2.max_velocity: -1e[+]19 is not a finite number in"),
        ('[tolerance]\n"axis1.velocity" = nan\n', "a.toml:2: axis1.velocity: the tolerance nan is not a finite number"),
    ],
)
def test_a_malformed_assertion_file_is_an_input_error(tmp_path, text, message):
    (tmp_path / "a.toml").write_text(text)
    with pytest.raises(InputError, match=message):
        pmdfmu.verify(SQUARE, assertions=tmp_path / "a.toml")


# ---- reports --------------------------------------------------------------------------------------


def test_junit_xml_has_one_testcase_per_check_and_the_right_counts(goldens, tmp_path):
    folder, _, _ = goldens
    table = changed_square(tmp_path, "2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500")
    result = pmdfmu.verify(
        table, against=folder / "square.csv", assertions={"all_axes": {"max_velocity": 1e9, "final_position": 1}}
    )
    root = ET.fromstring(result.to_junit())
    assert root.tag == "testsuites" and (root.get("tests"), root.get("failures"), root.get("errors")) == ("6", "3", "0")
    [suite] = root
    assert suite.get("name") == "changed" and suite.get("tests") == "6" and suite.get("failures") == "3"
    cases = {tc.get("name"): tc for tc in suite}
    assert set(cases) == {
        "profile ended",
        "golden trace",
        "axis1 max |velocity| <= 1e+09 counts/s",
        "axis1 final position 1",
        "axis2 max |velocity| <= 1e+09 counts/s",
        "axis2 final position 1",
    }
    failure = cases["golden trace"].find("failure")
    assert failure.get("message").startswith("first difference at cycle") and failure.get("type") == "golden"
    assert cases["axis1 max |velocity| <= 1e+09 counts/s"].find("failure") is None
    assert "final position 0 counts" in cases["axis2 final position 1"].find("failure").get("message")


def test_a_profile_that_does_not_run_is_a_junit_error(tmp_path):
    bad = tmp_path / "bad.script"
    bad.write_text("@ 0\nFrobnicate(Axis1);\n")
    result = pmdfmu.verify(bad, assertions={"no_host_errors": True})
    assert not result.passed and result.cases[0].error and "Frobnicate" in result.cases[0].error
    root = ET.fromstring(result.to_junit())
    assert (root.get("tests"), root.get("errors"), root.get("failures")) == ("1", "1", "0")
    assert root.find("testsuite/testcase/error") is not None


def test_markdown_summary(goldens, tmp_path):
    folder, _, _ = goldens
    good = pmdfmu.verify(SQUARE, against=folder / "square.csv")
    text = good.to_markdown()
    assert text.startswith("### pmdfmu verify: 1 of 1 case passed\n") and "| square | pass | 2001 | 2 of 2 |" in text
    table = changed_square(tmp_path, "2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500")
    bad = pmdfmu.verify(table, against=folder / "square.csv", out=tmp_path)
    text = bad.to_markdown()
    assert "0 of 1 case passed" in text and "| changed | **FAIL** | 2001 | 1 of 2 | first difference at cycle" in text
    assert "#### changed" in text and "diff plot: `" in text


def test_the_pytest_helper_raises_the_readable_report(goldens, tmp_path):
    folder, _, _ = goldens
    assert assert_trajectory(SQUARE, against=folder / "square.npz").passed
    table = changed_square(tmp_path, "2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500")
    with pytest.raises(AssertionError) as e:
        assert_trajectory(table, against=folder / "square.npz", assertions={"axis1": {"final_position": 5}})
    text = str(e.value)
    assert "FAIL changed" in text and "golden trace: first difference at cycle" in text
    assert "axis1 final position 5: axis 1: final position 0 counts" in text


def test_a_result_is_truthy_when_it_passes(goldens):
    folder, _, _ = goldens
    assert pmdfmu.verify(SQUARE, against=folder / "square.csv")
    assert not pmdfmu.verify(SQUARE, assertions={"axis1": {"final_position": 5}})


def test_the_examples_ci_golden_still_passes():
    """examples/ci's golden trace of the demo script, recorded with `pmdfmu run`: any change of the FMU's
    behaviour on it shows here first (re-record it with the command of examples/ci/README.md if the
    change is intended)."""
    ci = EXAMPLES / "ci"
    result = pmdfmu.verify(SCRIPT, against=ci / "two_axis.golden.npz", assertions=ci / "two_axis.toml")
    assert result.passed, result.report()
    assert pmdfmu.verify(SQUARE, against=ci / "square.golden.csv").passed


def test_a_batch_checks_events_each_case_records(tmp_path):
    """verify_cases asks each case (sweep.Case.record) for the event status its assertions need: the
    refused command's InstructionError is caught at its cycle in a batch as in a single run, not skipped."""
    (tmp_path / "limit.script").write_text(LIMIT_SCRIPT)
    (tmp_path / "events.toml").write_text('[axis1]\nno_events = ["InstructionError"]\n')
    (tmp_path / "cases.csv").write_text("name,script,assertions\nlimit,limit.script,events.toml\n")
    result = pmdfmu.verify_cases(tmp_path / "cases.csv", scheduler="serial", out=tmp_path / "out")
    [check] = [c for c in result.cases[0].checks if c.name.startswith("axis1 no event")]
    assert check.skipped is None and not check.passed
    assert (check.failures[0].cycle, check.failures[0].value & pmdfmu.PMDEventInstructionErrorMask) == (300, 0x80)


@pytest.mark.parametrize("cycles", [0, -5])
def test_a_run_of_no_cycles_is_an_input_error(cycles):
    with pytest.raises(InputError, match=f"max_cycles {cycles}: a run records at least 1 cycle"):
        pmdfmu.verify(SQUARE, assertions={"axis1": {"final_position": 1}}, max_cycles=cycles)


def test_junit_xml_stays_xml_when_a_message_holds_a_control_character(tmp_path):
    """A script's stray control byte reaches the failure messages: the report must still parse."""
    script = tmp_path / "ctl.script"
    script.write_bytes(b"@ 0\nSetPosition(Axis1, 1\x01);\n")
    result = pmdfmu.verify(script, assertions={"no_host_errors": True})
    assert "\x01" in result.cases[0].error
    root = ET.fromstring(result.to_junit())
    assert root.get("errors") == "1" and "\ufffd" in root.find("testsuite/testcase/error").text
