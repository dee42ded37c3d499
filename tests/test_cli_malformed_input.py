# SPDX-License-Identifier: BSD-2-Clause
"""A bad input on the command line answers with one line, `pmdfmu CMD: file:line: reason`, and exit
status 2 -- never a traceback, never status 1 (verify's "the profile failed"); nothing overwrites a
user's file (docs/cli.md; docs/verify.md, "Exit status"). Each finding of the attack on
the CLI first, then generated malformed inputs (hypothesis)."""

import os
import shutil
import zipfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pmdfmu.cli import main

pytestmark = pytest.mark.slow  # tests/README.md: compiles programs or runs the CLI; -m "not slow" leaves it out

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SCRIPT, TABLE, SQUARE = EXAMPLES / "two_axis.script", EXAMPLES / "two_axis_table.csv", EXAMPLES / "square.csv"
GOLDEN = EXAMPLES / "ci" / "square.golden.csv"


def cli(capsys, *argv):
    """main's exit status, standard output and standard error."""
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


def assert_one_line(result, command, *expected):
    """Exit status 2 and one line on standard error naming the command, holding each expected text."""
    status, _out, err = result
    assert status == 2, err
    assert err.count("\n") == 1 and err.endswith("\n") and err.startswith(f"pmdfmu {command}: "), err
    for text in expected:
        assert text in err


@pytest.fixture
def profile(tmp_path):
    """two_axis.script and its table in a folder of their own."""
    shutil.copy(SCRIPT, tmp_path / "s.script")
    shutil.copy(TABLE, tmp_path / "two_axis_table.csv")
    return tmp_path / "s.script"


# ---- 1, 2: pack writes no input and never through a planted name -----------------------------------


@pytest.mark.parametrize("how", ["the script", "its table", "a symlink to the script", "a hard link to the table"])
def test_pack_refuses_an_output_that_is_one_of_its_inputs(profile, capsys, how):
    table = profile.parent / "two_axis_table.csv"
    out = {"the script": profile, "its table": table}.get(how, profile.parent / "out.fmu")
    if how == "a symlink to the script":
        out.symlink_to(profile)
    elif how == "a hard link to the table":
        os.link(table, out)
    before = {p: p.read_bytes() for p in (profile, table)}
    assert_one_line(cli(capsys, "pack", profile, "--out", out), "pack", "must not overwrite")
    assert {p: p.read_bytes() for p in before} == before
    assert sorted(p.name for p in profile.parent.iterdir()) == sorted(
        ["s.script", "two_axis_table.csv"] + (["out.fmu"] if out.name == "out.fmu" else [])
    )


def test_pack_never_writes_through_a_planted_partial_name(profile, capsys):
    victim = profile.parent / "victim.txt"
    victim.write_text("the victim's data\n")
    out = profile.parent / "x.fmu"
    out.with_name("x.fmu.partial").symlink_to(victim)
    status, _out, err = cli(capsys, "pack", profile, "--out", out)
    assert status == 0, err
    assert victim.read_text() == "the victim's data\n"
    assert not out.is_symlink() and zipfile.ZipFile(out).read("resources/script.start") == b"profile/s.script"
    assert not [p for p in profile.parent.iterdir() if p.name.startswith(".x.fmu.")]


def test_run_and_verify_write_no_output_over_an_input(profile, capsys):
    script = profile.read_bytes()
    assert_one_line(cli(capsys, "run", profile, "--csv", profile), "run", "--csv", "names the input")
    changed = profile.parent / "changed.csv"
    changed.write_text(SQUARE.read_text().replace("2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500"))
    golden = shutil.copy(GOLDEN, profile.parent / "changed.actual.csv")  # a copied actual, as a golden
    assert_one_line(
        cli(capsys, "verify", changed, "--against", golden, "--out", profile.parent),
        "verify",
        "would write its recording over the input",
    )
    assert_one_line(
        cli(capsys, "verify", changed, "--against", GOLDEN, "--junit", changed), "verify", "--junit", "names the input"
    )
    assert profile.read_bytes() == script and Path(golden).read_bytes() == GOLDEN.read_bytes()


MACHINE = EXAMPLES / "machine" / "stage.toml"
TRACE = """@ 0
SetBufferStart(Axis1, 0, 0x1000);
SetBufferLength(Axis1, 0, 400);
SetTraceMode(Axis1, PMDTraceOneTime);
SetTraceVariable(Axis1, PMDTrace1, PMDAxis2, PMDTraceCommandedPosition);
SetTraceStart(Axis1, PMDAxis1, PMDTraceConditionImmediate, 0, PMDTraceTriggerStateLow);
"""  # a trace for pmdfmu trace to write, before two_axis.script


@pytest.mark.parametrize(
    "argv",
    [
        ["run", "{script}", "--csv", "{table}"],
        ["run", "{script}", "--machine", "{machine}", "--csv", "{machine}"],
        ["run", "{script}", "--out", "{npz}"],
        ["run", "{script}", "--machine", "{npz}", "--out", "{npz}"],
        ["trace", "{script}", "--csv", "{table}"],
        ["trace", "{script}", "--machine", "{machine}", "--csv", "{machine}"],
        ["verify", "{script}", "--max-velocity", "all=1e9", "--junit", "{table}"],
        ["serve", "--tcp", "127.0.0.1:0", "--script", "{script}", "--log", "{table}"],
        ["serve", "--tcp", "127.0.0.1:0", "--script", "{script}", "--record", "{table}"],
    ],
    ids=lambda argv: " ".join(a for a in argv if a.startswith("--") or a.isalpha()),
)
def test_no_output_overwrites_a_table_the_script_loads_or_the_machine_file(profile, capsys, argv):
    """The attacker's finding: only the files named on the command line were inputs; the segment table a
    script loads (LoadSegmentTable) and the --machine file were written over by the run's output."""
    folder = profile.parent
    shutil.copy(MACHINE, folder / "m.toml")
    table = folder / "t.npz"  # a table the script loads may have any name
    table.write_bytes((folder / "two_axis_table.csv").read_bytes())
    shutil.copy(MACHINE, folder / "m.npz")
    profile.write_text(TRACE + SCRIPT.read_text() + '\n@ 4000\nLoadSegmentTable(Axis3, "t.npz", 0x400, 2);\n')
    names = {"script": profile, "table": folder / "two_axis_table.csv", "machine": folder / "m.toml"}
    names["npz"] = table if "--machine" not in argv else folder / "m.npz"
    argv = [a.format(**names) for a in argv]
    before = {p: p.read_bytes() for p in folder.iterdir()}
    assert_one_line(cli(capsys, *argv), argv[0], "names the input")
    assert {p: p.read_bytes() for p in folder.iterdir()} == before


@pytest.mark.parametrize(
    "argv,bommed",
    [
        (["run", "{script}"], "{script}"),
        (["run", "{table}"], "{table}"),
        (["run", "{script}"], "{table}"),  # the FMU's LoadSegmentTable
        (["machine", "--check", "{machine}"], "{machine}"),
        (["run", "{script}", "--machine", "{machine}"], "{machine}"),
        (["verify", "{table}", "--against", "{golden}"], "{golden}"),
        (["verify", "{table}", "--assertions", "{assertions}"], "{assertions}"),
        (["sweep", "{cases}", "--scheduler", "serial"], "{cases}"),
    ],
    ids=["script", "table", "loaded table", "machine", "run --machine", "golden", "assertions", "case table"],
)
def test_a_file_beginning_with_a_byte_order_mark_is_refused_by_name(profile, capsys, argv, bommed):
    """The attacker's finding: a UTF-8 BOM (Notepad, Excel's "CSV UTF-8") was an invisible character in
    the first command, column or key: `expected Command(...), got ''`, and for a machine file whose first
    line is a comment, `expected a key, a [table] or a comment`."""
    folder = profile.parent
    names = {
        "script": profile,
        "table": folder / "two_axis_table.csv",
        "machine": shutil.copy(MACHINE, folder / "m.toml"),
        "golden": shutil.copy(GOLDEN, folder / "g.csv"),
        "assertions": folder / "a.toml",
        "cases": folder / "cases.csv",
    }
    names["assertions"].write_text("# limits\n[axis1]\nmax_velocity = 1e9\n")
    names["cases"].write_text("name,script\none,s.script\n")
    path = Path(bommed.format(**names))
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    argv = [a.format(**names) for a in argv]
    assert_one_line(cli(capsys, *argv), argv[0], path.name, "byte order mark (BOM)")


@pytest.mark.parametrize("command", ["run", "trace", "pack"])
def test_a_script_path_in_a_symlink_loop_answers_with_one_line(tmp_path, capsys, monkeypatch, command):
    """The attacker's finding: Path.resolve raised RuntimeError (Python < 3.13) for a symlink loop, a
    traceback and exit status 1 (a relative name is resolved before the FMU gets it)."""
    monkeypatch.chdir(tmp_path)
    Path("a.script").symlink_to("b.script")
    Path("b.script").symlink_to("a.script")
    argv = ["--out", "p.fmu"] if command == "pack" else []
    assert_one_line(cli(capsys, command, "a.script", *argv), command, "a.script")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.script", "b.script"]


# ---- 3: verify's own malformed inputs ----------------------------------------------------------------


def _npz(path, **dtypes):
    """A golden .npz of square.golden.csv's columns, the named ones of another type."""
    rows = np.genfromtxt(GOLDEN, delimiter=",", names=True, max_rows=5, deletechars="")
    names = rows.dtype.names
    rec = np.zeros(
        len(rows),
        dtype=[
            (
                n,
                dtypes.get(
                    n, "f8" if "." in n and n.split(".")[1] in ("position", "velocity", "acceleration") else "i8"
                ),
            )
            for n in names
        ],
    )
    for n in names:
        rec[n] = rows[n].astype(rec.dtype[n]) if rec.dtype[n].kind != "U" else rows[n].astype(str)
    np.savez_compressed(path, recording=rec)
    return path


@pytest.mark.parametrize(
    "kind,flag,expected",
    [
        ("40-digit integer", "--against", "g.csv:2: column 1 (cycle): '1111111111"),
        ("200 000-character field", "--against", "g.csv:2: field larger than field limit"),
        ("TOML nested 5000 deep", "--assertions", "a.toml: not TOML this parser reads: arrays or tables nested"),
        ("npz of strings", "--against", "g.npz: column 2 (axis1.commandedPosition): <U"),
        ("npz of float16", "--against", "g.npz: column 5 (axis1.position): <f2 is not a recording's type"),
        ("npz of complex", "--against", "g.npz: column 5 (axis1.position): <c16 is not a recording's type"),
        ("a FIFO", "--against", "g.csv: cannot read the golden trace: a FIFO, not a regular file"),
    ],
)
def test_verify_answers_a_malformed_golden_or_assertion_file_with_status_2(tmp_path, capsys, kind, flag, expected):
    path = tmp_path / ("a.toml" if flag == "--assertions" else "g.npz" if "npz" in kind else "g.csv")
    header = "cycle,axis1.commandedPosition\n"
    if kind == "40-digit integer":
        path.write_text(header + "1" * 40 + ",0\n")
    elif kind == "200 000-character field":
        path.write_text(header + "1" * 200_000 + ",0\n")
    elif kind == "TOML nested 5000 deep":
        path.write_text("[axis1]\nmax_velocity = " + "[" * 5000 + "]" * 5000 + "\n")
    elif kind == "npz of strings":
        _npz(path, **{"axis1.commandedPosition": "U8"})
    elif kind == "npz of float16":
        _npz(path, **{"axis1.position": "f2"})
    elif kind == "npz of complex":
        _npz(path, **{"axis1.position": "c16"})
    elif kind == "a FIFO":
        os.mkfifo(path)
    assert_one_line(cli(capsys, "verify", SQUARE, flag, path), "verify", expected)


# ---- 4: the front door: run and info -------------------------------------------------------------------


@pytest.mark.parametrize(
    "mistake,expected",
    [
        ("a missing script", "missing.script: cannot open the script"),
        ("a misspelt command", "s.script:2: 'SetPositon' is not a command of this chip"),
        ("Axis7", "s.script:2: 'Axis7' is not an axis"),
        ("a golden .npz as the script", "g.npz:1: NUL byte in the line"),
        ("a misspelt header", "t.csv:1: column 3: 'velocty' is not a segment column (axis, position, velocity"),
        ("a decimal in a raw table", "t.csv:3: column position: '1.5' is not an integer"),
        ("a first position out of reach", "t.csv: the initial move (axis 1 to 2147483647) is not complete after"),
        ("a missing FMU", "nope.fmu: No such file or directory"),
        ("a script as the FMU", "s.script: not an FMU"),
    ],
)
def test_run_answers_a_common_mistake_with_one_line(tmp_path, capsys, mistake, expected):
    script, table = tmp_path / "s.script", tmp_path / "t.csv"
    argv = ["run", script]
    if mistake == "a missing script":
        argv = ["run", tmp_path / "missing.script"]
    elif mistake in ("a misspelt command", "Axis7"):
        script.write_text("@ 0\n" + ("SetPositon(Axis1, 5)\n" if mistake != "Axis7" else "SetPosition(Axis7, 5)\n"))
    elif mistake == "a golden .npz as the script":
        argv = ["run", shutil.copy(EXAMPLES / "ci" / "two_axis.golden.npz", tmp_path / "g.npz")]
    elif mistake == "a misspelt header":
        table.write_text("axis,position,velocty,acceleration,jerk,time\n1,0,0,0,0,100\n")
        argv = ["run", table]
    elif mistake == "a decimal in a raw table":
        table.write_text("# a comment line\naxis,position,velocity,acceleration,jerk,time\n1,1.5,0,0,0,100\n")
        argv = ["run", table]
    elif mistake == "a first position out of reach":
        table.write_text("axis,position,velocity,acceleration,jerk,time\n1,0x7FFFFFFF,0,0,0,100\n")
        argv = ["run", table]
    elif mistake == "a missing FMU":
        argv = ["run", SCRIPT, "--fmu", tmp_path / "nope.fmu"]
    elif mistake == "a script as the FMU":
        argv = ["run", SCRIPT, "--fmu", shutil.copy(SCRIPT, script)]
    assert_one_line(cli(capsys, *argv), "run", expected)


@pytest.mark.parametrize(
    "what,expected",
    [
        ("missing", "nope.fmu: No such file or directory"),
        ("a folder", "a folder, not a regular file"),
        ("a zip without a model description", "g.npz: not an FMU"),
        ("no zip", "x.fmu: not an FMU: File is not a zip file"),
    ],
)
@pytest.mark.parametrize("command", ["info", "validate"])
def test_info_and_validate_answer_a_bad_fmu_with_one_line_naming_it(tmp_path, capsys, what, expected, command):
    fmu = {
        "missing": tmp_path / "nope.fmu",
        "a folder": tmp_path,
        "a zip without a model description": EXAMPLES / "ci" / "two_axis.golden.npz",
        "no zip": tmp_path / "x.fmu",
    }[what]
    if what.startswith("a zip"):
        fmu = shutil.copy(fmu, tmp_path / "g.npz")
    if what == "no zip":
        fmu.write_text("not a zip")
    assert_one_line(cli(capsys, command, fmu), command, expected)


def test_a_genuine_bug_keeps_its_traceback(monkeypatch, capsys):
    """Only input errors are answered with one line: an internal error propagates."""
    from pmdfmu import profile

    def broken(*args, **kwargs):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(profile, "run_profile", broken)
    with pytest.raises(ZeroDivisionError):
        main(["run", str(SCRIPT)])


# ---- 5: a file argument is a file, never a script's text ---------------------------------------------


@pytest.mark.parametrize("command", ["run", "verify"])
def test_a_script_path_holding_a_line_feed_is_refused_not_compiled_as_text(tmp_path, capsys, command):
    # its path, as text, would be a valid script: a comment line and an empty one
    script = tmp_path / "# dir\nnew.script"
    shutil.copy(SCRIPT, script)
    argv = [command, script] + (["--max-velocity", "all=1e9"] if command == "verify" else [])
    assert_one_line(cli(capsys, *argv), command, r"# dir\nnew.script: the script's path holds a line feed")


def test_pack_packs_a_script_whose_name_holds_a_line_feed(tmp_path, capsys):
    script = tmp_path / "dir\nnew.script"
    shutil.copy(SCRIPT, script)
    shutil.copy(TABLE, tmp_path)
    status, out, err = cli(capsys, "pack", script, "--out", tmp_path / "p.fmu")
    assert status == 0, err
    packed = zipfile.ZipFile(tmp_path / "p.fmu")
    assert packed.read("resources/script.start") == b"profile/dir_new.script"
    assert packed.read("resources/profile/dir_new.script") == SCRIPT.read_bytes()
    assert packed.read("resources/profile/two_axis_table.csv") == TABLE.read_bytes()


def test_pack_of_a_line_feed_script_refuses_a_table_outside_its_folder(tmp_path, capsys):
    """Such a script is compiled through a mirror of its folder in the temporary folder: a table named
    `../t.csv` would be looked for beside the mirror (where anyone may plant one), so it is refused."""
    folder = tmp_path / "work"
    folder.mkdir()
    script = folder / "dir\nnew.script"
    script.write_text(SCRIPT.read_text().replace(TABLE.name, f"../{TABLE.name}"))
    shutil.copy(TABLE, tmp_path)
    import tempfile

    planted = Path(tempfile.gettempdir()) / TABLE.name
    planted_here = not planted.exists()
    if planted_here:
        shutil.copy(TABLE, planted)  # the table the mirror would find
    try:
        status, out, err = cli(capsys, "pack", script, "--out", tmp_path / "p.fmu")
    finally:
        if planted_here:
            planted.unlink()
    assert status == 2 and "lies outside the script's folder" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "p.fmu").exists()


# ---- 6: generated malformed inputs ---------------------------------------------------------------------

GENERATED = settings(
    max_examples=30,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)
HUGE = st.sampled_from(["1" * 40, "-" + "9" * 25, "0x" + "F" * 20, "9" * 5000, "1e400", "nan", "-inf"])
CELL = st.one_of(
    HUGE,
    st.text(max_size=8),
    st.just("1" * 140_000),
    st.just("\x00"),
    st.just('"'),
    st.sampled_from(["1.5", "0x", "0x+7", " ", "", "1,2", "'", "\u2028"]),
)
GARBAGE = st.one_of(
    st.binary(max_size=300),
    st.just(b""),
    st.just(b"\xff\xfe" + "axis".encode("utf-16-le")),
    st.just("\u00e9,\u00fc\n".encode("latin-1")),
    st.just(b"\x00" * 64),
)


def _written(path: Path, content) -> Path:
    """content as the file path: bytes, or "folder"/"fifo" for a file that is none."""
    if content == "folder":
        path.mkdir()
    elif content == "fifo":
        os.mkfifo(path)
    else:
        path.write_bytes(content)
    return path


def _damaged(text: str, draw) -> bytes:
    """text with one line cut off or one cell replaced by a malformed one."""
    lines = text.splitlines()
    i = draw(st.integers(1, len(lines) - 1))
    if draw(st.booleans()):
        cut = draw(st.integers(0, len(lines[i])))
        lines = lines[:i] + [lines[i][:cut] + draw(st.sampled_from(["", ",", ",,x"]))] + lines[i + 1 :]
    else:
        cells = lines[i].split(",")
        cells[draw(st.integers(0, len(cells) - 1))] = draw(CELL)
        lines[i] = ",".join(cells)
    return ("\n".join(lines) + "\n").encode("utf-8", "surrogatepass")


@st.composite
def malformed_file(draw, good: str):
    """A damaged copy of the well-formed file good, garbage, an empty file, a folder or a FIFO."""
    kind = draw(st.sampled_from(["damaged", "damaged", "garbage", "folder", "fifo"]))
    if kind == "damaged":
        return _damaged(good, draw)
    return draw(GARBAGE) if kind == "garbage" else kind


def _assert_no_traceback_nor_status_1(result, command):
    status, _out, err = result
    assert status in (0, 2) and "Traceback" not in err, err
    if status == 2:
        assert err.count("\n") == 1 and err.startswith(f"pmdfmu {command}: "), err


@GENERATED
@given(content=malformed_file(SQUARE.read_text()))
def test_run_of_a_malformed_table_or_script_answers_with_one_line(tmp_path_factory, capsys, content):
    folder = tmp_path_factory.mktemp("run")
    for name in ("t.csv", "s.script"):
        path = _written(folder / name, content)
        _assert_no_traceback_nor_status_1(cli(capsys, "run", path, "--max-cycles", "3000"), "run")


@GENERATED
@given(content=malformed_file(SCRIPT.read_text()))
def test_pack_of_a_malformed_script_answers_with_one_line(tmp_path_factory, capsys, content):
    folder = tmp_path_factory.mktemp("pack")
    shutil.copy(TABLE, folder)
    _assert_no_traceback_nor_status_1(
        cli(capsys, "pack", _written(folder / "s.script", content), "--out", folder / "p.fmu"), "pack"
    )


@GENERATED
@given(content=malformed_file(GOLDEN.read_text()))
def test_verify_of_a_malformed_golden_csv_exits_2(tmp_path_factory, capsys, content):
    folder = tmp_path_factory.mktemp("golden")
    path = _written(folder / "g.csv", content)
    status, out, err = cli(capsys, "verify", SQUARE, "--against", path, "--out", folder / "out")
    assert "Traceback" not in err
    if status == 1:  # a cell replaced by another number: a golden that reads, and differs
        assert "FAIL square" in out and not err
    else:
        assert status == 2 and err.count("\n") == 1 and err.startswith("pmdfmu verify: "), err


NPZ_TYPES = st.sampled_from(["f2", "f4", "c8", "c16", "U4", "S4", "V8", "u8", "(2,)i4", "M8[s]", "m8[s]"])


@GENERATED
@given(dtype=NPZ_TYPES, column=st.integers(0, 7), cut=st.one_of(st.none(), st.integers(0, 2000)))
def test_verify_of_a_malformed_golden_npz_exits_2(tmp_path_factory, capsys, dtype, column, cut):
    folder = tmp_path_factory.mktemp("npz")
    rows = np.genfromtxt(GOLDEN, delimiter=",", names=True, max_rows=3, deletechars="")
    names = rows.dtype.names
    rec = np.zeros(len(rows), dtype=[(n, dtype if i == column else "i8") for i, n in enumerate(names)])
    if dtype == "u8":
        rec[names[column]] = 2**64 - 1  # a register's column no register holds
    path = folder / "g.npz"
    np.savez_compressed(path, recording=rec)
    if cut is not None:
        path.write_bytes(path.read_bytes()[:cut])
    status, _out, err = cli(capsys, "verify", SQUARE, "--against", path, "--out", folder / "out")
    assert status == 2 and err.count("\n") == 1 and err.startswith("pmdfmu verify: "), err


TOML_VALUES = st.one_of(
    st.text(max_size=5).map(lambda t: '"' + t.replace("\\", "").replace('"', "") + '"'),
    st.sampled_from(
        [
            "nan",
            "inf",
            "-inf",
            "true",
            "[1, 2]",
            "{a = 1}",
            "1979-05-27",
            "[[[[[[[[1]]]]]]]]",
            "1" * 30,
            '"1" "2"',
            "=",
            "0x",
            "1e999",
        ]
    ),
)


@st.composite
def malformed_toml(draw):
    kind = draw(st.sampled_from(["value", "key", "nesting", "garbage", "folder", "fifo"]))
    if kind == "value":  # a limit whose value is of no number
        key = draw(st.sampled_from(["max_velocity", "position_min", "final_position", "complete_by", "no_events"]))
        return f"[axis{draw(st.integers(1, 4))}]\n{key} = {draw(TOML_VALUES)}\n".encode()
    if kind == "key":
        return f"[{draw(st.sampled_from(['axis5', 'axes', 'all_axes.x', 'tolerance']))}]\nspeed = 1\n".encode()
    if kind == "nesting":
        depth = draw(st.integers(500, 20_000))
        opening, closing = draw(st.sampled_from([("[", "]"), ("{a = ", "}")]))
        return f"x = {opening * depth}{closing * depth}\n".encode()
    return draw(GARBAGE.filter(lambda b: b.strip() not in (b"",))) if kind == "garbage" else kind


@GENERATED
@given(content=malformed_toml())
def test_verify_of_a_malformed_assertion_file_exits_2(tmp_path_factory, capsys, content):
    path = _written(tmp_path_factory.mktemp("toml") / "a.toml", content)
    status, _out, err = cli(capsys, "verify", SQUARE, "--assertions", path)
    assert status == 2 and err.count("\n") == 1 and err.startswith("pmdfmu verify: "), err


CASE_NAMES = st.text(
    st.characters(blacklist_categories=("Cs", "Cc"), blacklist_characters='/\\,"'), min_size=1, max_size=6
)
# one defect, each a malformed case table whatever the rest of it is
DEFECTS = st.sampled_from(
    [
        "misspelt column",
        "unknown column",
        "name twice",
        "name with a slash",
        "name ..",
        "no name",
        "fmi_version 7",
        "max_cycles 0",
        "cycleTime fast",
        "memorySize huge",
        "script and table",
        "neither script nor table",
        "script with a line feed",
        "no case",
        "garbage",
    ]
)


@st.composite
def malformed_case_table(draw):
    """A table of 1-3 cases that would run, then exactly one defect from DEFECTS: bytes."""
    names = draw(
        st.lists(
            CASE_NAMES.map(str.strip).filter(lambda n: n not in ("", ".", "..")), min_size=1, max_size=3, unique=True
        )
    )
    header = ["name", "table", "fmi_version", "max_cycles", "cycleTime", "memorySize"]
    rows = [[n, str(SQUARE), str(draw(st.sampled_from([2, 3]))), "3000", "", ""] for n in names]
    defect = draw(DEFECTS)
    row = draw(st.integers(0, len(rows) - 1))
    if defect == "misspelt column":
        header[draw(st.integers(2, 5))] = draw(st.sampled_from(["fmi", "max_cycle", "cycletime", "memory_size"]))
    elif defect == "unknown column":
        header.append(draw(st.sampled_from(["speed", "Name", " name", "axis1"])))
        for r in rows:
            r.append("1")
    elif defect == "name twice":
        rows.append(list(rows[row]))
    elif defect == "name with a slash":
        rows[row][0] = draw(st.sampled_from(["../x", "a/b", "..\\x", "/abs", "summary", "Summary"]))
    elif defect in ("name ..", "no name"):
        rows[row][0] = ".." if defect == "name .." else " "
    elif defect == "fmi_version 7":
        rows[row][2] = "7"
    elif defect == "max_cycles 0":
        rows[row][3] = "0"
    elif defect == "cycleTime fast":
        rows[row][4] = draw(st.sampled_from(["fast", "1e-4s", "0x"]))
    elif defect == "memorySize huge":
        rows[row][5] = "9" * draw(st.integers(20, 5000))
    elif defect in ("script and table", "neither script nor table"):
        header.append("script")
        for i, r in enumerate(rows):
            r.append(str(SCRIPT) if defect == "script and table" and i == row else "")
        if defect == "neither script nor table":
            rows[row][1] = ""
    elif defect == "script with a line feed":
        header.append("script")
        rows[row][1] = ""
        for i, r in enumerate(rows):
            r.append('"a\nb.script"' if i == row else "")
    elif defect == "no case":
        rows = []
    else:
        return draw(GARBAGE)
    return ("\n".join(",".join(r) for r in [header, *rows]) + "\n").encode()


@GENERATED
@given(
    content=st.one_of(
        malformed_case_table(),
        st.sampled_from(["folder", "fifo"]),
        st.just(('name,table\nx,"' + "y" * 140_000 + '"\n').encode()),
    )
)
def test_verify_and_sweep_of_a_malformed_case_table_exit_2(tmp_path_factory, capsys, content):
    folder = tmp_path_factory.mktemp("cases")
    path = _written(folder / "cases.csv", content)
    for command in (["verify", "--cases"], ["sweep"]):
        status, _out, err = cli(capsys, *command, path, "--scheduler", "serial", "--out", folder / "out")
        assert status == 2 and err.count("\n") == 1 and err.startswith(f"pmdfmu {command[0]}: "), err
    assert not (folder / "out").exists()


@pytest.mark.parametrize("flag", ["--junit", "--summary"])
@pytest.mark.parametrize("named", ["two_axis_table.csv", "g.csv"])
def test_verify_cases_writes_no_report_over_a_cases_table_or_golden(tmp_path, capsys, flag, named):
    """`verify --cases` checked its reports against the case table alone: --junit naming the table a
    case's script loads, or a case's golden, wrote over it."""
    shutil.copy(SCRIPT, tmp_path / "s.script")
    shutil.copy(TABLE, tmp_path / "two_axis_table.csv")
    shutil.copy(GOLDEN, tmp_path / "g.csv")
    (tmp_path / "cases.csv").write_text("name,script,golden\none,s.script,g.csv\n")
    before = {p: p.read_bytes() for p in tmp_path.iterdir()}
    result = cli(capsys, "verify", "--cases", tmp_path / "cases.csv", "--scheduler", "serial", flag, tmp_path / named)
    assert_one_line(result, "verify", "names the input")
    assert {p: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_a_sweeps_check_of_its_inputs_compiles_each_script_once(tmp_path, monkeypatch):
    """Re-running a sweep into its --out (its files exist) compiled every case's script to learn the tables
    it loads: 500 cases of one script were 500 compiles before the first case ran."""
    import pmdfmu.pack
    from pmdfmu.sweep import Case, refuse_writing_over_inputs

    shutil.copy(SCRIPT, tmp_path / "s.script")
    shutil.copy(TABLE, tmp_path / "two_axis_table.csv")
    (tmp_path / "summary.csv").write_text("an earlier sweep's\n")
    compiled = []
    real = pmdfmu.pack.tables_loaded
    monkeypatch.setattr(pmdfmu.pack, "tables_loaded", lambda *a: compiled.append(a) or real(*a))
    cases = [Case(f"c{k}", script=str(tmp_path / "s.script"), fmi_version=2 + k % 2) for k in range(500)]
    refuse_writing_over_inputs(cases, tmp_path)
    assert len(compiled) == 2  # one script, two FMI versions
    with pytest.raises(ValueError, match="two_axis_table.csv: the sweep would write over its input"):
        refuse_writing_over_inputs([*cases, Case("two_axis_table", script=str(tmp_path / "s.script"))], tmp_path)


@pytest.mark.parametrize(
    "how",
    [
        "the table's folder, the table named summary.csv",
        "a case named after its table",
        "a case named after the table its script loads",
    ],
)
def test_sweep_refuses_an_output_that_is_one_of_its_inputs(tmp_path, capsys, how):
    """`--out .` beside the case table: summary.csv or NAME.csv must not replace an input. The third is
    the attacker's finding: a table a case's script loads was no input, and the sweep wrote over it."""
    shutil.copy(SQUARE, tmp_path / "square.csv")
    # the table named summary.csv, or a case named after the table it runs
    name = "a" if how.startswith("the table") else "square"
    cases = tmp_path / ("summary.csv" if name == "a" else "cases.csv")
    cases.write_text(f"name,table\n{name},square.csv\n")
    if how.endswith("its script loads"):
        shutil.copy(SCRIPT, tmp_path / "s.script")
        shutil.copy(TABLE, tmp_path / "two_axis_table.csv")
        cases.write_text("name,script\ntwo_axis_table,s.script\n")
    before = {p: p.read_bytes() for p in tmp_path.iterdir()}
    result = cli(capsys, "sweep", cases, "--scheduler", "serial", "--out", tmp_path)
    assert_one_line(result, "sweep", "would write over its input", "give another --out")
    assert {p: p.read_bytes() for p in tmp_path.iterdir()} == before


def test_an_output_through_a_link_or_onto_a_device_is_written_as_asked(tmp_path):
    """files.replaced: a symbolic link keeps naming the file, now the new one, with the old permissions;
    a device (/dev/null, as /dev/stdout would be) is written through, never replaced by a file; a missing
    folder or a folder as the output is named as the user named it, and nothing is left behind."""
    import stat as stat_
    from pmdfmu import files

    target, link = tmp_path / "t.csv", tmp_path / "l.csv"
    target.write_text("old")
    target.chmod(0o640)
    link.symlink_to(target.name)
    with files.replaced(link, text=True) as f:
        f.write("new")
    assert link.is_symlink() and target.read_text() == "new" and stat_.S_IMODE(target.stat().st_mode) == 0o640
    with files.replaced("/dev/null") as f:
        f.write(b"x")
    assert Path("/dev/null").is_char_device()
    for bad, why in ((tmp_path / "none" / "x.csv", "No such file or directory"), (tmp_path, "a folder")):
        with pytest.raises(OSError, match=why) as info:
            with files.replaced(bad) as f:
                f.write(b"x")
        assert info.value.filename == str(bad)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["l.csv", "t.csv"]


def test_a_plot_name_without_a_plot_format_and_outputs_naming_each_other_are_refused(tmp_path, capsys):
    for args, why in (
        (["--plot", tmp_path / "x.txt"], "a plot is written as its suffix says"),
        (["--csv", tmp_path / "a.png", "--plot", tmp_path / "a.png"], "names the file --csv writes too"),
    ):
        try:
            status = main([str(a) for a in ["run", SCRIPT, *args]])
        except SystemExit as e:  # argparse's own refusal: the same one line and status
            status = e.code
        err = capsys.readouterr().err
        assert status == 2 and why in err and len(err.strip().splitlines()) == 1, err
    assert not list(tmp_path.iterdir())
