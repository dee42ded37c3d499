# SPDX-License-Identifier: BSD-2-Clause
"""Gates that cannot be fooled (docs/verify.md): a run that --max-cycles cuts short before its profile
ends is an error unless a window is asked for, and goldens say whether they were whole; limits on
velocity, acceleration and jerk hold on the position's own differences as well as on the registers;
the report names every differing column."""

from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu.cli import main
from pmdfmu.verify import InputError, read_golden, read_recording, write_recording

pytestmark = pytest.mark.slow  # tests/README.md: runs the CLI

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SCRIPT, SQUARE = EXAMPLES / "two_axis.script", EXAMPLES / "square.csv"


def long_table(tmp_path, cycles):
    """One axis at 1 count/cycle for `cycles` cycles, then the end."""
    path = tmp_path / "long.csv"
    path.write_text(f"axis,position,velocity,acceleration,jerk,time\n1,0,0x10000,0,0,{cycles}\n1,{cycles},0,0,0,0\n")
    return path


def jumping_script(tmp_path):
    """two_axis.script with one changed row of its table: axis 1 jumps 12.5 counts in one cycle."""
    (tmp_path / "two_axis.script").write_text(SCRIPT.read_text())
    table = (EXAMPLES / "two_axis_table.csv").read_text()
    assert "\n625,0.5," in table
    (tmp_path / "two_axis_table.csv").write_text(table.replace("\n625,0.5,", "\n637,0.5,"))
    return tmp_path / "two_axis.script"


def test_a_run_that_max_cycles_cuts_short_exits_1_and_writes_nothing(tmp_path, capsys):
    """The issue's table: 2*10^6 cycles under the default --max-cycles 10^6."""
    table = long_table(tmp_path, 2_000_000)
    assert main(["run", str(table), "--csv", str(tmp_path / "g.npz")]) == 1
    captured = capsys.readouterr()
    assert "ended at position" not in captured.out
    assert captured.err.startswith("pmdfmu run: the profile had not ended at cycle 1000255: 1000000 cycles recorded")
    assert "--cycles 1000000" in captured.err and len(captured.err.splitlines()) == 1
    assert not (tmp_path / "g.npz").exists()


@pytest.mark.parametrize("suffix", [".csv", ".npz"])
def test_a_window_is_recorded_on_request_and_the_golden_says_so(tmp_path, capsys, suffix):
    table = long_table(tmp_path, 3000)
    golden = tmp_path / f"w{suffix}"
    assert main(["run", str(table), "--cycles", "1000", "--csv", str(golden)]) == 0
    assert "a window" in capsys.readouterr().out
    read = read_golden(golden)
    assert (read.ended, len(read.recording)) == (False, 1000)
    if suffix == ".csv":
        assert golden.read_text().startswith("# pmdfmu: a window of 1000 cycles: the profile had not ended")
    whole = tmp_path / f"whole{suffix}"
    assert main(["run", str(table), "--csv", str(whole)]) == 0
    assert read_golden(whole).ended and not whole.read_bytes().startswith(b"#")


def test_verify_refuses_a_whole_run_against_a_window_golden_and_checks_the_same_window(tmp_path, capsys):
    table = long_table(tmp_path, 3000)
    golden = tmp_path / "w.npz"
    assert main(["run", str(table), "--cycles", "1000", "--csv", str(golden)]) == 0
    capsys.readouterr()
    assert main(["verify", str(table), "--against", str(golden), "--final-position", "1=999"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"pmdfmu verify: {golden}: the golden trace is a window") and "--cycles 1000" in err
    argv = ["verify", str(table), "--against", str(golden), "--final-position", "1=999", "--cycles", "1000", "-v"]
    assert main(argv) == 0
    assert "  SKIP profile ended\n" in capsys.readouterr().out
    with pytest.raises(InputError, match="is a window"):
        pmdfmu.verify(table, against=golden)


def test_verify_fails_a_run_cut_short_with_the_cycle_it_stopped_at(tmp_path, capsys):
    """The issue's gate: a truncated run's final position no longer passes."""
    table = long_table(tmp_path, 3000)
    assert main(["verify", str(table), "--max-cycles", "1000", "--final-position", "1=999"]) == 1
    out = capsys.readouterr().out
    assert "profile ended: the profile had not ended at cycle 1255: 1000 cycles recorded, the --max-cycles limit" in out
    result = pmdfmu.verify(table, assertions={"axis1": {"final_position": 999}}, cycles=1000)
    assert result.passed and result.cases[0].checks[0].skipped


def test_a_golden_that_does_not_say_reads_as_whole(tmp_path):
    """Goldens written before they said whether their profile had ended stay readable, as whole ones."""
    rec = read_recording(EXAMPLES / "ci" / "square.golden.csv")
    old = tmp_path / "old.npz"
    np.savez_compressed(old, recording=rec)
    assert read_golden(old).ended and read_golden(EXAMPLES / "ci" / "two_axis.golden.npz").ended
    write_recording(tmp_path / "new.npz", rec, ended=False)
    with np.load(tmp_path / "new.npz") as data:
        assert sorted(data.files) == ["ended", "recording"] and not data["ended"]
    bad = tmp_path / "bad.npz"
    np.savez_compressed(bad, recording=rec, ended=np.array([1, 2]))
    with pytest.raises(InputError, match="'ended' is not true or false"):
        read_golden(bad)


def test_a_case_of_a_batch_cut_short_fails(tmp_path, capsys):
    table = long_table(tmp_path, 3000)
    cases = tmp_path / "cases.csv"
    cases.write_text(f"name,table,max_cycles\nshort,{table},1000\nwhole,{table},\n")
    result = pmdfmu.verify_cases(cases, scheduler="serial", assertions={"axis1": {"final_position": 3000}})
    assert [c.passed for c in result.cases] == [False, True]
    assert result.cases[0].failures[0].check == "ended"
    assert main(["verify", "--cases", str(cases), "--cycles", "1000"]) == 2
    assert "a case table asks for a case's window in its cycles column" in capsys.readouterr().err


def test_a_case_asks_for_a_window_in_its_cycles_column(tmp_path, capsys):
    """As `pmdfmu run --cycles N`: the first N cycles, the profile ended or not, and no failure."""
    table = long_table(tmp_path, 3000)
    golden = tmp_path / "w.npz"
    assert main(["run", str(table), "--cycles", "1000", "--csv", str(golden)]) == 0
    cases = tmp_path / "cases.csv"
    cases.write_text(f"name,table,cycles,golden\nwindow,{table},1000,{golden}\nwhole,{table},,\n")
    result = pmdfmu.verify_cases(cases, scheduler="serial")
    window, whole = result.cases
    assert result.passed and (window.cycles, whole.cycles) == (1000, 3001)
    assert window.checks[0].name == "profile ended" and "a window of 1000 cycles" in window.checks[0].skipped
    assert not whole.checks[0].skipped
    swept = pmdfmu.sweep(pmdfmu.read_cases(cases), scheduler="serial")
    assert [(r["cycles"], r["ended"]) for r in swept.rows] == [(1000, "no"), (3001, "yes")]
    capsys.readouterr()
    assert main(["-v", "sweep", str(cases), "--scheduler", "serial", "--out", str(tmp_path / "out")]) == 0
    assert "ok: window: 1000 cycles, a window\n" in capsys.readouterr().out
    # the window golden against a whole case: refused before anything runs, saying where to ask for the window
    cases.write_text(f"name,table,golden\nwindow,{table},{golden}\n")
    assert main(["verify", "--cases", str(cases), "--scheduler", "serial"]) == 2
    assert "give --cycles 1000 in its cycles column" in capsys.readouterr().err


@pytest.mark.parametrize(
    "cell, reason",
    [
        ("0", "case 'w': cycles 0: a window records at least 1 cycle"),
        ("-5", "case 'w': cycles -5: a window records at least 1 cycle"),
        ("many", "cycles 'many' is not a whole number"),
        ("1000,5000", "case 'w': max_cycles or cycles, not both"),
    ],
)
def test_a_bad_cycles_cell_is_its_file_and_line_and_exit_2(tmp_path, capsys, cell, reason):
    cases = tmp_path / "cases.csv"
    max_cycles = cell.partition(",")[2]
    cases.write_text(f"name,table,cycles,max_cycles\nok,{SQUARE},,\nw,{SQUARE},{cell.partition(',')[0]},{max_cycles}\n")
    for command in (["verify", "--cases"], ["sweep"]):
        assert main([*command, str(cases), "--scheduler", "serial", "--out", str(tmp_path / "out")]) == 2
        assert capsys.readouterr().err == f"pmdfmu {command[0]}: {cases}:3: {reason}\n"
    assert not (tmp_path / "out").exists()


def test_a_position_jump_fails_the_velocity_limit_in_the_position_difference(tmp_path):
    """The issue's second profile: one changed row makes axis 1 jump 12.5 counts in one cycle, and the
    velocity register never shows it."""
    script = jumping_script(tmp_path)
    result = pmdfmu.verify(script, assertions={"axis1": {"max_velocity": 5100, "max_step": 1}})
    assert not result.passed
    velocity, step = result.failures
    assert (velocity.check, velocity.source, velocity.column) == (
        "max_velocity",
        "position difference",
        "axis1.position",
    )
    assert velocity.value == pytest.approx(125000) and velocity.cycle == 1600
    assert "in the position's difference (axis1.position moved 12.5 counts in one cycle)" in velocity.message
    assert (step.check, step.source, step.value) == ("max_step", "position difference", 12.5)
    assert "the position moved 12.5 counts in one cycle > 1 at cycle 1600" in step.message
    # the unchanged profile passes both: its jumps at a segment's start are below a count
    assert pmdfmu.verify(SCRIPT, assertions={"axis1": {"max_velocity": 5100, "max_step": 1}}).passed


def test_a_register_violation_says_it_is_the_registers_with_raw_values_converted():
    result = pmdfmu.verify(SQUARE, assertions={"units": "raw", "axis1": {"max_velocity": 0x10000}})
    (f,) = result.failures
    assert f.source == "register" and f.column == "axis1.commandedVelocity"
    assert (
        "|velocity| 131072 raw 16.16 counts/cycle (2 counts/cycle = 20000 counts/s) > 65536 at cycle 256" in f.message
    )
    assert f.message.endswith("in the register axis1.commandedVelocity")


def test_a_velocity_step_fails_the_acceleration_limit_that_the_register_misses():
    """square.csv steps its velocity 0 -> 2 counts/cycle in one cycle: its acceleration register stays 0."""
    result = pmdfmu.verify(SQUARE, assertions={"axis2": {"max_acceleration": 1e6}})
    (f,) = result.failures
    assert f.source == "position difference" and f.value == pytest.approx(2e8)
    assert "in the position's second difference (2 counts/cycle^2 of axis2.position)" in f.message


def test_the_report_lists_every_differing_column_at_its_first_cycle(tmp_path):
    table = tmp_path / "changed.csv"
    table.write_text(SQUARE.read_text().replace("2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500"))
    result = pmdfmu.verify(table, against=EXAMPLES / "ci" / "square.golden.csv")
    text = result.report()
    assert (
        "axis2.commandedVelocity expected -131072 (-2 counts/cycle = -20000 counts/s), "
        "actual -65536 (-1 counts/cycle = -10000 counts/s) (difference +65536)" in text
    )
    others = [f.column for f in result.failures[1:]]
    assert others == ["axis2.velocity", "axis2.commandedPosition", "axis2.position"]
    assert "golden trace: axis2.commandedPosition first differs at cycle 1757 (row 1501): expected 998" in text


def test_the_report_counts_in_the_singular_and_names_the_command_lines_limits(tmp_path, capsys):
    result = pmdfmu.verify(SQUARE, assertions={"axis1": {"final_position": 0}})
    assert "PASS square (" in result.report() and ": 2001 cycles, 2 checks" in result.report()
    result.cases[0].checks.pop()
    assert ": 2001 cycles, 1 check\n" in result.report()
    assert main(["verify", str(SQUARE), "--position-window", "1=5:3"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("pmdfmu verify: the command line's limits") and "command line with" not in err
