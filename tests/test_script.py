# SPDX-License-Identifier: BSD-2-Clause
"""Stand-alone scripts: the `script` parameter (docs/scripts.md)."""

import os
import threading
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import FMUError
from pmdfmu.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
NAMES = [
    "axis1.commandedPosition",
    "axis1.commandedVelocity",
    "axis2.commandedPosition",
    "axis2.commandedAcceleration",
    "axis1.activityStatus",
    "axis2.activityStatus",
]


@pytest.mark.parametrize("version", [2, 3])
def test_the_example_script_runs_as_the_same_calls_from_python(version):
    with pmdfmu.Chip(fmi_version=version, script=EXAMPLES / "two_axis.script") as chip:
        scripted = chip.run(3200, record=NAMES)
        assert chip.messages == []
    with pmdfmu.Chip(fmi_version=version) as chip:
        a1, a2 = chip.axis(0), chip.axis(1)
        # LoadSegmentTable(Axis1, "two_axis_table.csv", 0x200, 2): counts/cycle units, exactly
        rows = [
            (0, 0, pmdfmu.fixed_16_16("0.001"), 0, 500),
            (125, 0x8000, 0, 0, 1000),
            (625, 0x8000, pmdfmu.fixed_16_16("-0.001"), 0, 500),
            (750, 0, 0, 0, 0),
        ]
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
    script.write_text(
        "@0\nSetVelocity(Axis3, 2.75)\nSetJerk(PMDAxis3, .0075)\nSetGearRatio(Axis3, -1.95)\n"
        "SetBufferReadIndex(Axis1, 2, 5)   # 0x07: buffer 2 has length 0\n"
    )
    with pmdfmu.Chip(script=script, log_categories=["warnings"]) as chip:
        chip.run(1)
        ax = chip.axis(2)
        assert (ax.GetVelocity(), ax.GetJerk(), ax.GetGearRatio()) == (0x2C000, 0x1EB851F, pmdfmu.signed(0xFFFE0CCD))
        assert [m.message for m in chip.messages] == [f"{script}:5: the chip refused the command: host I/O error 0x07"]


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
    assert (
        main(
            [
                "run",
                str(EXAMPLES / "two_axis.script"),
                "--csv",
                str(tmp_path / "o.csv"),
                "--plot",
                str(tmp_path / "o.png"),
                "--fmi-version",
                "3",
            ]
        )
        == 0
    )
    lines = (tmp_path / "o.csv").read_text().splitlines()
    assert lines[0].startswith("cycle,axis1.commandedPosition") and "axis2.commandedPosition" in lines[0]
    assert len(lines) > 3000 and (tmp_path / "o.png").stat().st_size > 10_000


def test_pmdfmu_run_a_script_without_outputs_says_where_the_axes_ended(capsys):
    """cli.md's `pmdfmu run two_axis.script --machine ...` asks for no file: it printed nothing at all."""
    assert main(["run", str(EXAMPLES / "two_axis.script")]) == 0
    assert capsys.readouterr().out.splitlines() == [
        "axis 1: ended at position 750 after 4000 cycles",
        "axis 2: ended at position 5000 after 4000 cycles",
    ]


# ---- files that are not a script or a table (hangs and silent acceptance once) ----


def refusal(version, script, seconds=60):
    """What the FMU says when it refuses the script; a hang fails the test instead of stalling the suite."""
    said = []

    def initialize():
        try:
            pmdfmu.Chip(fmi_version=version, script=script).close()
            said.append(None)
        except FMUError as e:
            said.append(str(e))

    thread = threading.Thread(target=initialize, daemon=True)
    thread.start()
    thread.join(seconds)
    assert said, f"no answer in {seconds} s: the FMU hangs"
    assert said[0] is not None, "the script was accepted"
    assert "ExitInitializationMode: script refused" in said[0]
    return said[0]


def script_loading(tmp_path, table):
    script = tmp_path / "s.script"
    script.write_text(f'LoadSegmentTable(Axis1, "{table}", 0x200, 2)\n')
    return script


@pytest.mark.parametrize("version", [2, 3])
def test_a_table_that_never_ends_or_blocks_is_refused_as_not_a_regular_file(tmp_path, version):
    fifo = tmp_path / "fifo.csv"
    os.mkfifo(fifo)
    for table in ("/dev/zero", fifo):
        assert f"s.script:1: cannot open segment table {table}: not a regular file" in refusal(
            version, script_loading(tmp_path, table)
        )


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_that_is_a_fifo_a_device_or_a_folder_is_refused_as_not_a_regular_file(tmp_path, version):
    fifo = tmp_path / "fifo.script"
    os.mkfifo(fifo)
    for script in (fifo, "/dev/zero", tmp_path):
        assert f"{Path(script).resolve()}: cannot open the script: not a regular file" in refusal(version, script)


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_or_table_over_1_GiB_is_refused_unread(tmp_path, version):
    huge = tmp_path / "huge.csv"
    with open(huge, "wb") as f:  # sparse: nothing is written
        f.truncate((1 << 30) + 1)
    assert f"{huge.resolve()}: cannot open the script: larger than 1 GiB" in refusal(version, huge)
    assert f"s.script:1: cannot open segment table {huge}: larger than 1 GiB" in refusal(
        version, script_loading(tmp_path, huge)
    )


@pytest.mark.skipif(not Path("/proc/self/mem").exists(), reason="needs Linux's /proc/self/mem")
@pytest.mark.parametrize("version", [2, 3])
def test_a_read_error_is_refused_not_taken_for_the_end_of_the_script(version):
    # /proc/self/mem is a regular file whose first page cannot be read (EIO)
    assert "/mem:1: cannot read: Input/output error" in refusal(version, "/proc/self/mem")


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="root reads any file")
@pytest.mark.parametrize("version", [2, 3])
def test_an_unreadable_script_is_refused(tmp_path, version):
    script = tmp_path / "s.script"
    script.write_text("@ 0\n")
    script.chmod(0)
    assert "s.script: cannot open the script: Permission denied" in refusal(version, script)


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_that_cannot_be_opened_is_refused_even_for_root(tmp_path, version):
    """An open that fails, as CI can try it (it runs as root, which reads any file): a path through a file."""
    (tmp_path / "file").write_text("")
    script = tmp_path / "file" / "s.script"
    assert "s.script: cannot open the script: Not a directory" in refusal(version, script)


LONG = "x" * 4096
HEADER_17 = "position," * 16 + "bogus"
# the script's line 2 (after a comment), the table t.csv next to it -> what the refusal says
BAD_FILES = {
    "script line too long": ("# " + LONG, None, "s.script:2: line longer than 4095 characters"),
    "NUL in a script": ("SetPosition(Axis1,\0 5)", None, "s.script:2: NUL byte in the line"),
    "hex with a blank": ("SetPosition(Axis1, 0x 5)", None, "s.script:2: '0x 5' is not a 32-bit hexadecimal number"),
    "hex with a sign": ("SetPosition(Axis1, 0x+7)", None, "s.script:2: '0x+7' is not a 32-bit hexadecimal number"),
    "hex past 32 bits": ("@ 0x000100000000", None, "s.script:2: '0x000100000000' is not a 32-bit hexadecimal"),
    "empty argument": ("SetPosition(Axis1, )", None, "s.script:2: a value is missing"),
    "quote in a path": (
        'LoadSegmentTable(Axis1, "t"x".csv", 0x200, 2)',
        None,
        's.script:2: LoadSegmentTable: a quote inside the file name "t"x".csv"',
    ),
    "path too long": (
        f'LoadSegmentTable(Axis1, "{"d/" * 600}t.csv", 0x200, 2)',
        None,
        "s.script:2: LoadSegmentTable: the table's path is longer than 1023 characters",
    ),
    "table comment too long": (None, "# " + LONG + "\nposition\n1\n", "t.csv:1: line longer than 4095 characters"),
    "NUL in a table": (None, "position\n1\0\n", "t.csv:2: NUL byte in the line"),
    "17 columns": (
        None,
        HEADER_17 + "\n" + "1," * 16 + "1\n",
        "t.csv:1: 17 columns: a segment table has at most one each of position, velocity, acceleration, jerk, time",
    ),
    "column twice": (None, "position,time,position\n1,2,3\n", "t.csv:1: column 'position' named twice"),
    "row too long": (None, "position,time\n1,2\n3,4,5\n", "t.csv:3: expected 2 values (one per column), found 3"),
    "row too short": (None, "position,time\n1\n", "t.csv:2: expected 2 values (one per column), found 1"),
    "empty cell": (None, "position,time\n1,\n", "t.csv:2: a value is missing"),
    "trailing garbage": (None, "position\n5x\n", "t.csv:2: '5x' is not a number"),
    "hex in a table": (None, "position\n0x 5\n", "t.csv:2: '0x 5' is not a 32-bit hexadecimal number"),
    "units contradicted": (
        None,
        "# units: raw\nposition,velocity\n1,2\n# units: counts/cycle\n",
        "t.csv:4: units 'counts/cycle' contradict the units stated before",
    ),
}


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("case", BAD_FILES)
def test_a_bad_file_is_refused_with_file_line_and_reason(tmp_path, version, case):
    line, table, expected = BAD_FILES[case]
    if table is not None:
        (tmp_path / "t.csv").write_bytes(table.encode())
        line = 'LoadSegmentTable(Axis1, "t.csv", 0x200, 2)'
    script = tmp_path / "s.script"
    script.write_bytes(("# a comment\n" + line + "\n").encode())
    assert expected in refusal(version, script)


@pytest.mark.parametrize("version", [2, 3])
def test_lines_of_4095_characters_and_blanks_around_cells_are_accepted(tmp_path, version):
    (tmp_path / "t.csv").write_text(
        "# units: raw\n#" + "x" * 4094 + "\n position , time \n 7 , 0x10 \n-3,0\n# units: raw\n"
    )
    script = tmp_path / "s.script"
    script.write_text("#" + "y" * 4094 + '\nLoadSegmentTable(Axis1, "t.csv", 0x200, 2)')  # no final newline
    with pmdfmu.Chip(fmi_version=version, script=script) as chip:
        chip.run(1)
        ax = chip.axis(0)
        assert [ax.GetBufferLength(b) for b in (2, 3)] == [2, 2]
        assert [ax.ReadBuffer(2), ax.ReadBuffer(2), ax.ReadBuffer(3)] == [7, -3, 16]
