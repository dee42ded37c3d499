# SPDX-License-Identifier: BSD-2-Clause
"""One segment-table format (docs/scripts.md, "Segment tables"): `pmdfmu run`'s tables and a script's
LoadSegmentTable read the same columns, optional columns, `# units:` line and decimals, and name a bad
header with the column meant."""

import pytest

import pmdfmu
from pmdfmu import FMUError
from pmdfmu.cli import main
from pmdfmu.profile import TableError, read_segment_table

TABLE = """# units: counts/cycle
# position and velocity only: acceleration and jerk read 0, time 1 (no time column: the profile goes on)
velocity,position
2.5,0
-1.00001,10
0x18000,20
0.0000076,-30
"""


def loaded_words(tmp_path, text, columns):
    """The words LoadSegmentTable put in memory, per column present, read back with ReadBuffer."""
    (tmp_path / "t.csv").write_text(text)
    script = tmp_path / "s.script"
    script.write_text('@ 0\nLoadSegmentTable(Axis1, "t.csv", 0x200, 2);\n')
    with pmdfmu.Chip(script=str(script)) as chip:
        chip.run(1)
        ax = chip.axis(0)
        words = {}
        for k, column in enumerate(columns):
            n = ax.GetBufferLength(2 + k)
            words[column] = [pmdfmu.signed(ax.ReadBuffer(2 + k)) for _ in range(n)]
    return words


def test_a_run_table_and_load_segment_table_read_the_same_words(tmp_path):
    rows = read_segment_table_text(tmp_path, TABLE)[0]
    words = loaded_words(tmp_path, TABLE, ["position", "velocity"])
    assert [r[0] for r in rows] == words["position"] == [0, 10, 20, -30]
    assert [r[1] for r in rows] == words["velocity"] == [0x28000, -65537, 0x18000, 0]
    assert {(r[2], r[3], r[4]) for r in rows} == {(0, 0, 1)}  # absent: what the chip reads without the buffer


def test_jerk_decimals_are_0_32_and_an_axis_column_is_optional(tmp_path):
    text = "# units: counts/cycle\nposition,jerk,time,axis\n0,0.0000001,100,2\n5,0x10,0,2\n"
    tables = read_segment_table_text(tmp_path, text)
    assert list(tables) == [1] and [r[3] for r in tables[1]] == [429, 16]
    words = loaded_words(tmp_path, text.replace(",axis", "").replace(",2\n", "\n"), ["position", "jerk", "time"])
    assert words["jerk"] == [429, 16] and words["time"] == [100, 0]


def read_segment_table_text(tmp_path, text):
    path = tmp_path / "run.csv"
    path.write_text(text)
    return read_segment_table(path)


@pytest.mark.parametrize("header", ["velocty", "Velocity", "posiiton"])
def test_a_misspelt_header_names_the_column_meant_in_both_readers(tmp_path, header):
    meant = "velocity" if header != "posiiton" else "position"
    text = f"position,{header}\n0,1\n" if header != "posiiton" else "posiiton,velocity\n0,1\n"
    with pytest.raises(TableError, match=f"'{header}' is not a segment column .*did you mean '{meant}'"):
        read_segment_table_text(tmp_path, text)
    (tmp_path / "t.csv").write_text(text)
    with pytest.raises(FMUError, match=f"'{header}' is not a segment column .*did you mean '{meant}'"):
        pmdfmu.Chip(
            script='@ 0\nLoadSegmentTable(Axis1, "t.csv", 0x200, 2);\n'.replace("t.csv", str(tmp_path / "t.csv"))
        )


def test_contradicting_units_and_a_decimal_in_a_raw_table_are_one_line_errors(tmp_path, capsys):
    with pytest.raises(TableError, match=r"run.csv:2: units 'raw' contradict"):
        read_segment_table_text(tmp_path, "# units: counts/cycle\n# units: raw\nposition\n0\n")
    (tmp_path / "raw.csv").write_text("axis,position,velocity,time\n1,0,2.5,100\n1,0,0,0\n")
    assert main(["run", str(tmp_path / "raw.csv")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "`# units: counts/cycle` takes decimals" in err


def test_pmdfmu_run_takes_a_table_in_counts_per_cycle(tmp_path, capsys):
    (tmp_path / "c.csv").write_text("# units: counts/cycle\nposition,velocity,time\n0,2.5,100\n250,0,0\n")
    assert main(["run", str(tmp_path / "c.csv")]) == 0
    assert "axis 1: ended at position 250" in capsys.readouterr().out


@pytest.mark.parametrize("upload", ["memory", "command"])
def test_a_table_value_that_does_not_fit_32_bits_is_refused_by_either_upload(upload):
    """The attacker's finding: load_external_profile's memory upload masked every value with 0xFFFFFFFF,
    so a position of 2^32 + 5 was loaded as 5, where the command upload (WriteBuffer) refused it."""
    from pmdfmu.profile import load_external_profile

    with pmdfmu.Chip() as chip:
        with pytest.raises(ValueError, match="4294967301 .* does not fit 32 bits"):
            load_external_profile(chip, {0: [(2**32 + 5, 0, 0, 0, 1)]}, upload=upload)
        ids = load_external_profile(chip, {0: [(-5, -(2**31), 0xFFFFFFFF, 0, 1)]}, upload=upload)
        ax = chip.axis(0)
        assert [ax.ReadBuffer(i) for i in ids[0][:3]] == [-5, -(2**31), -1]
