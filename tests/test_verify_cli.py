# SPDX-License-Identifier: BSD-2-Clause
"""`pmdfmu verify` from the command line (docs/verify.md): exit status 0 pass, 1 fail,
2 malformed input; JUnit XML and Markdown files; batches of a case table on Dask; README's example."""

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from pmdfmu.cli import main

pytestmark = pytest.mark.slow  # tests/README.md: compiles programs or runs the CLI; -m "not slow" leaves it out

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
CI = EXAMPLES / "ci"
SCRIPT, SQUARE = EXAMPLES / "two_axis.script", EXAMPLES / "square.csv"


def changed_square(tmp_path):
    """square.csv with axis 2's return leg (its fourth row) at half the speed."""
    path = tmp_path / "changed.csv"
    path.write_text(SQUARE.read_text().replace("2,1000,-0x20000,0,0,500", "2,1000,-0x10000,0,0,500"))
    return path


def test_recording_a_golden_is_one_command_and_it_passes(tmp_path, capsys):
    for name in ("g.csv", "g.npz"):
        assert main(["run", str(SCRIPT), "--csv", str(tmp_path / name)]) == 0
        assert main(["verify", str(SCRIPT), "--against", str(tmp_path / name)]) == 0
    out = capsys.readouterr().out
    assert "PASS two_axis" in out and "pmdfmu verify: 1 of 1 case passed" in out
    assert (tmp_path / "g.npz").stat().st_size * 4 < (tmp_path / "g.csv").stat().st_size


def test_the_examples_ci_job_passes_and_writes_its_reports(tmp_path, capsys):
    junit, summary = tmp_path / "reports" / "verify.xml", tmp_path / "summary.md"
    assert (
        main(
            [
                "verify",
                str(SCRIPT),
                "--against",
                str(CI / "two_axis.golden.npz"),
                "--assertions",
                str(CI / "two_axis.toml"),
                "--junit",
                str(junit),
                "--summary",
                str(summary),
                "--out",
                str(tmp_path / "out"),
            ]
        )
        == 0
    )
    root = ET.parse(junit).getroot()
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("18", "0", "0")
    assert summary.read_text().startswith("### pmdfmu verify: 1 of 1 case passed")
    assert not (tmp_path / "out").exists()  # nothing failed: no plot


def test_a_changed_table_fails_with_the_first_difference_and_a_plot(tmp_path, capsys):
    table = changed_square(tmp_path)
    assert main(["run", str(SQUARE), "--csv", str(tmp_path / "golden.csv")]) == 0
    capsys.readouterr()
    assert (
        main(
            [
                "verify",
                str(table),
                "--against",
                str(tmp_path / "golden.csv"),
                "--out",
                str(tmp_path / "out"),
                "--summary",
                "-",
            ]
        )
        == 1
    )
    out = capsys.readouterr().out
    assert (
        "FAIL changed" in out
        and "golden trace: first difference at cycle 1756 (row 1500): "
        "axis2.commandedVelocity expected -131072 (-2 counts/cycle = -20000 counts/s), actual -65536"
        in out
    )
    assert "axis 2 position buffer 7 read index 4" in out
    assert (tmp_path / "out" / "changed.diff.png").stat().st_size > 10_000
    assert (tmp_path / "out" / "changed.actual.csv").exists()
    assert "| changed | **FAIL** |" in out  # the Markdown summary, printed


def test_limit_flags(tmp_path, capsys):
    assert (
        main(
            [
                "verify",
                str(SCRIPT),
                "--max-velocity",
                "2=40000",
                "--final-position",
                "2=5000",
                "--position-window",
                "all=-10:5100",
                "--no-events",
                "all",
                "--no-host-errors",
            ]
        )
        == 0
    )
    capsys.readouterr()
    assert (
        main(["verify", str(SCRIPT), "--max-velocity", "axis2=30000", "--complete-by", "1=2000", "--units", "counts"])
        == 1
    )
    out = capsys.readouterr().out
    assert "axis2 max |velocity| <= 30000 counts/s: axis 2: |velocity| " in out
    assert "axis1 motion complete by cycle 2000: axis 1: motion complete at cycle 2100" in out
    assert main(["verify", str(SCRIPT), "--units", "raw", "--max-velocity", "2=0x40000"]) == 0
    assert main(["verify", str(SCRIPT), "--units", "raw", "--max-velocity", "2=0x3FE00"]) == 1  # peak 0x3FE5D


def test_command_line_limits_go_over_the_file(tmp_path, capsys):
    assert (
        main(["verify", str(SCRIPT), "--assertions", str(CI / "two_axis.toml"), "--final-position", "axis2=4000"]) == 1
    )
    assert "axis2 final position 4000: axis 2: final position 5000 counts" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv,message",
    [
        (["--against", "{tmp}/missing.csv"], "missing.csv: cannot read the golden trace"),
        (["--against", "{tmp}/bad.csv"], "bad.csv:3: column 2 (axis1.commandedPosition): 'zz' is not a number"),
        (["--assertions", "{tmp}/bad.toml"], "bad.toml:2: axis1.max_speed: unknown limit"),
        (
            ["--assertions", "{tmp}/broken.toml"],
            "broken.toml:1: not TOML: Expected ']' at the end of a table declaration (column 7)",
        ),
        (["--against", "{tmp}/missing.npz"], "missing.npz: cannot read the golden trace: No such file or directory\n"),
        (["--tolerance", "axis1.speed=1e-9", "--no-host-errors"], "axis1.speed: unknown column"),
        (["--max-velocity", "5=1"], "'5' is not an axis"),
        (["--max-velocity", "1=fast"], "--max-velocity: 'fast' is not a number"),
        (["--position-window", "1=5"], "expected AXIS=MIN:MAX"),
        ([], "nothing to verify"),
    ],
)
def test_malformed_input_exits_2_naming_file_and_line(tmp_path, capsys, argv, message):
    (tmp_path / "bad.csv").write_text("cycle,axis1.commandedPosition\n0,1\n1,zz\n")
    (tmp_path / "bad.toml").write_text("[axis1]\nmax_speed = 3\n")
    (tmp_path / "broken.toml").write_text("[axis1\n")
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(["verify", str(SQUARE), *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("pmdfmu verify: ") and message in err


def test_a_profile_that_does_not_run_fails_with_status_1(tmp_path, capsys):
    bad = tmp_path / "bad.script"
    bad.write_text("@ 0\nFrobnicate(Axis1);\n")
    junit = tmp_path / "j.xml"
    assert main(["verify", str(bad), "--no-host-errors", "--junit", str(junit)]) == 1
    assert "FAIL bad" in capsys.readouterr().out and "did not run" in junit.read_text()


def test_batch_of_cases_serial(tmp_path, capsys):
    junit = tmp_path / "j.xml"
    assert main(["verify", "--cases", str(CI / "cases.csv"), "--scheduler", "serial", "--junit", str(junit)]) == 0
    root = ET.parse(junit).getroot()
    assert [s.get("name") for s in root] == ["two_axis-fmi2", "two_axis-fmi3", "square", "square-small-memory"]
    assert root.get("failures") == "0" and root.get("errors") == "0"
    assert "pmdfmu verify: 4 of 4 cases passed" in capsys.readouterr().out


def test_batch_with_a_failing_and_a_broken_case(tmp_path, capsys):
    changed_square(tmp_path)
    (tmp_path / "cases.csv").write_text(
        "name,script,table,golden,assertions\n"
        f"good,,{SQUARE},{CI / 'square.golden.csv'},\n"
        f"changed,,changed.csv,{CI / 'square.golden.csv'},\n"
        f"broken,missing.script,,,{CI / 'two_axis.toml'}\n"
    )
    junit, summary = tmp_path / "j.xml", tmp_path / "s.md"
    assert (
        main(
            [
                "verify",
                "--cases",
                str(tmp_path / "cases.csv"),
                "--scheduler",
                "serial",
                "--junit",
                str(junit),
                "--summary",
                str(summary),
                "--out",
                str(tmp_path / "out"),
            ]
        )
        == 1
    )
    out = capsys.readouterr().out
    assert "PASS good" in out and "FAIL changed" in out and "FAIL broken" in out
    assert "first difference at cycle 1756 (row 1500): axis2.commandedVelocity" in out
    assert "axis 2 position buffer 7 read index 4" in out  # located by a run of the case alone
    root = ET.parse(junit).getroot()
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("5", "1", "1")
    assert (tmp_path / "out" / "changed.diff.png").exists()
    text = summary.read_text()
    assert "1 of 3 cases passed" in text and "| broken | **error** |" in text


def test_batch_malformed_golden_exits_2_before_running(tmp_path, capsys):
    (tmp_path / "g.csv").write_text("cycle,axis1.nothing\n0,0\n")
    (tmp_path / "cases.csv").write_text(f"name,table,golden\nsquare,{SQUARE},g.csv\n")
    assert main(["verify", "--cases", str(tmp_path / "cases.csv"), "--scheduler", "serial"]) == 2
    assert "g.csv:1: column 2: 'axis1.nothing' is not an output of the FMU" in capsys.readouterr().err


def test_batch_on_a_local_dask_cluster(tmp_path, capsys):
    assert main(["verify", "--cases", str(CI / "cases.csv"), "--workers", "2"]) == 0
    assert "pmdfmu verify: 4 of 4 cases passed" in capsys.readouterr().out


def test_from_a_shell(tmp_path):
    """The exit status a pipeline gates on, from a real process."""
    env = dict(os.environ)  # the pmdfmu the suite runs (installed, or PYTHONPATH + PMDFMU_FMU_DIR)
    ok = subprocess.run(
        [sys.executable, "-m", "pmdfmu.cli", "verify", str(SCRIPT), "--against", str(CI / "two_axis.golden.npz")],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert ok.returncode == 0, ok.stderr
    bad = subprocess.run(
        [
            sys.executable,
            "-m",
            "pmdfmu.cli",
            "verify",
            str(changed_square(tmp_path)),
            "--against",
            str(CI / "square.golden.csv"),
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert bad.returncode == 1 and (tmp_path / "verify-out" / "changed.diff.png").exists()
    malformed = subprocess.run(
        [sys.executable, "-m", "pmdfmu.cli", "verify", str(SCRIPT), "--against", str(tmp_path / "none.npz")],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
    )
    assert malformed.returncode == 2 and "none.npz: cannot read the golden trace" in malformed.stderr


def test_readme_example_runs(tmp_path):
    """README "A first CI gate": its shell lines, run in a copy of the repository's examples."""
    text = (REPO / "README.md").read_text()
    section = text.split("## A first CI gate\n", 1)[1].split("\n## ", 1)[0]
    code = section.split("```sh\n", 1)[1].split("```", 1)[0]
    # the pmdfmu the suite runs (installed, or PYTHONPATH + PMDFMU_FMU_DIR), this interpreter's scripts first
    env = dict(os.environ, PATH=os.path.dirname(sys.executable) + os.pathsep + os.environ["PATH"])
    pmdfmu = tmp_path / "bin" / "pmdfmu"  # the command as pip installs it, on this interpreter
    pmdfmu.parent.mkdir()
    pmdfmu.write_text(f'#!/bin/sh\nexec {sys.executable} -m pmdfmu.cli "$@"\n')
    pmdfmu.chmod(0o755)
    env["PATH"] = str(pmdfmu.parent) + os.pathsep + env["PATH"]
    work = tmp_path / "repo"
    work.mkdir()
    os.symlink(EXAMPLES, work / "examples")
    done = subprocess.run(["bash", "-euo", "pipefail", "-c", code], cwd=work, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "pmdfmu verify: 1 of 1 case passed" in done.stdout


def test_readme_python_example_runs(monkeypatch):
    """README "A first CI gate": its Python lines pass (paths relative to the repository)."""
    text = (REPO / "README.md").read_text()
    section = text.split("## A first CI gate\n", 1)[1].split("\n## ", 1)[0]
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(REPO)
    exec(compile(code, "README.md (A first CI gate)", "exec"), {})


def test_the_sample_ci_jobs_parse_and_their_commands_pass(tmp_path):
    """examples/ci's GitHub Actions and GitLab jobs: valid YAML, and their pmdfmu verify lines pass as they
    stand (run from a copy of the repository's top folder)."""
    yaml = pytest.importorskip("yaml")
    github = yaml.safe_load((CI / "github-actions.yml").read_text())
    gitlab = yaml.safe_load((CI / "gitlab-ci.yml").read_text())
    commands = [step["run"] for step in github["jobs"]["verify"]["steps"] if "pmdfmu verify" in step.get("run", "")]
    commands += [line for line in gitlab["verify-trajectory"]["script"] if line.startswith("pmdfmu verify")]
    assert len(commands) == 2
    os.symlink(EXAMPLES, tmp_path / "examples")
    summary = tmp_path / "step-summary.md"
    for command in commands:
        argv = command.replace('"$GITHUB_STEP_SUMMARY"', str(summary)).replace("\\\n", " ").split()
        assert argv[0] == "pmdfmu"
        cwd = os.getcwd()
        os.chdir(tmp_path)
        try:
            assert main(argv[1:]) == 0
        finally:
            os.chdir(cwd)
    assert (tmp_path / "reports" / "verify.xml").exists() and "4 of 4 cases passed" in summary.read_text()
    assert (tmp_path / "reports" / "verify.html").stat().st_size > 1_000_000  # plotly.js inline: opens offline
