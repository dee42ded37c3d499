"""Stand-alone scripts: the `script` parameter (issue 4; README, "Scripts")."""
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import FMUError
from pmdfmu.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
NAMES = ["axis1.commandedPosition", "axis1.commandedVelocity", "axis2.commandedPosition",
         "axis2.commandedAcceleration", "axis1.activityStatus", "axis2.activityStatus"]


@pytest.mark.parametrize("version", [2, 3])
def test_the_example_script_runs_as_the_same_calls_from_python(version):
    with pmdfmu.Chip(fmi_version=version, script=EXAMPLES / "two_axis.script") as chip:
        scripted = chip.run(3200, record=NAMES)
        assert chip.messages == []
    with pmdfmu.Chip(fmi_version=version) as chip:
        a1, a2 = chip.axis(0), chip.axis(1)
        # LoadSegmentTable(Axis1, "two_axis_table.csv", 0x200, 2): counts/cycle units, exactly
        rows = [(0, 0, pmdfmu.fixed_16_16("0.001"), 0, 500), (125, 0x8000, 0, 0, 1000),
                (625, 0x8000, pmdfmu.fixed_16_16("-0.001"), 0, 500), (750, 0, 0, 0, 0)]
        for k in range(5):
            a1.SetBufferStart(2 + k, 0x200 + 4 * k)
            a1.SetBufferLength(2 + k, 4)
            a1.SetBufferFunction(k, 2 + k)
            chip.write_memory(0x200 + 4 * k, [r[k] & 0xFFFFFFFF for r in rows])
        a2.SetProfileMode(pmdfmu.PMDSCurveProfile)
        a2.SetPosition(5000)
        a2.SetVelocity(4 << 16)
        a2.SetAcceleration(0x1000)
        a2.SetJerk(pmdfmu.fixed_0_32("0.0005"))
        a2.Update()
        parts = [chip.run(100, record=NAMES)]
        a1.SetProfileMode(pmdfmu.PMDExternalProfile)
        a1.MultiUpdate(pmdfmu.PMDAxis1Mask)
        parts.append(chip.run(2900, record=NAMES))
        a2.SetStopMode(pmdfmu.PMDAbruptStop)
        a2.Update()
        parts.append(chip.run(200, record=NAMES))
    assert np.array_equal(scripted, np.concatenate(parts))
    assert scripted["axis1.commandedPosition"][100] == 0 and scripted["axis1.commandedPosition"][-1] == 750


def test_decimals_are_exact_and_the_chip_still_refuses_what_it_refuses(tmp_path):
    script = tmp_path / "s.script"
    script.write_text("@0\nSetVelocity(Axis3, 2.75)\nSetJerk(PMDAxis3, .0075)\nSetGearRatio(Axis3, -1.95)\n"
                      "SetBufferReadIndex(Axis1, 2, 5)   # 0x07: buffer 2 has length 0\n")
    with pmdfmu.Chip(script=script, log_categories=["warnings"]) as chip:
        chip.run(1)
        ax = chip.axis(2)
        assert (ax.GetVelocity(), ax.GetJerk(), ax.GetGearRatio()) == (0x2C000, 0x1EB851F, pmdfmu.signed(0xFFFE0CCD))
        assert [m.message for m in chip.messages] == \
            [f"{script}:5: the chip refused the command: host I/O error 0x07"]


BAD = {
    "Frobnicate(Axis1, 3)": "2: 'Frobnicate' is not a command",
    "SetPosition(Axis1)": "2: SetPosition takes the axis and 1 arguments, not 0",
    "SetPosition(Axis5, 3)": "2: 'Axis5' is not an axis",
    "SetPosition(Axis1, 12abc)": "2: '12abc' is not a number",
    "SetPosition(Axis1, 1.5)": "2: '1.5': a decimal fraction is allowed only for 16.16 and 0.32 values",
    "SetProfileMode(Axis1, PMDNoSuchMode)": "2: 'PMDNoSuchMode' is not a C-Motion constant",
    "SetVelocity(Axis1, 40000.0)": "2: '40000.0' does not fit a 16.16 value",
    "SetStopMode(Axis1, 70000)": "2: SetStopMode: 70000 does not fit the argument",
    "@ 5\n@ 3": "3: time 3 comes before 5",
    "SetPosition Axis1 3": "2: expected Command(Axis, arguments...)",
    'LoadSegmentTable(Axis1, "missing.csv", 0x200, 2)': "2: cannot open segment table",
    'LoadSegmentTable(Axis1, "t.csv", 0x3FFE, 2)': "2: 2 rows x 2 columns at 0x3FFE leave the 16384-word memory",
    'LoadSegmentTable(Axis1, "bad.csv", 0x200, 2)': "bad.csv:3: 'x' is not a number",
}


@pytest.mark.parametrize("line", BAD)
def test_a_bad_script_is_refused_at_initialization_with_file_line_and_reason(tmp_path, line):
    (tmp_path / "t.csv").write_text("position,time\n1,2\n3,0\n")
    (tmp_path / "bad.csv").write_text("# units: raw\nposition,velocity\nx,1\n")
    script = tmp_path / "bad.script"
    script.write_text("# a comment\n" + line + "\n")
    with pytest.raises(FMUError) as e:
        pmdfmu.Chip(script=script)
    assert BAD[line] in str(e.value) and "ExitInitializationMode: script refused" in str(e.value)


def test_a_missing_script_is_refused():
    with pytest.raises(FMUError, match="cannot open the script"):
        pmdfmu.Chip(fmi_version=3, script="/nonexistent/x.script")


def test_fmu_state_keeps_the_scripts_progress():
    with pmdfmu.Chip(script=EXAMPLES / "two_axis.script") as chip:
        chip.run(50)
        saved = chip.get_state()
        first = chip.run(3100, record=NAMES)
        chip.set_state(saved)
        assert np.array_equal(chip.run(3100, record=NAMES), first)


def test_pmdfmu_run_a_script_writes_csv_and_plot(tmp_path):
    assert main(["run", str(EXAMPLES / "two_axis.script"), "--csv", str(tmp_path / "o.csv"),
                 "--plot", str(tmp_path / "o.png"), "--fmi-version", "3"]) == 0
    lines = (tmp_path / "o.csv").read_text().splitlines()
    assert lines[0].startswith("cycle,axis1.commandedPosition") and "axis2.commandedPosition" in lines[0]
    assert len(lines) > 3000 and (tmp_path / "o.png").stat().st_size > 10_000
