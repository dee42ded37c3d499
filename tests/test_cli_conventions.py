# SPDX-License-Identifier: BSD-2-Clause
"""The pmdfmu command follows the conventions of the CLIs users know (docs/cli.md): --version, help text
on every option, one spelling per option across commands, -q/--quiet and -v/--verbose, the exit statuses
in `pmdfmu --help`, a sweep whose failed cases change its status only on request."""

import argparse
import subprocess
import sys
from pathlib import Path

import pytest

from pmdfmu import __version__
from pmdfmu.cli import _parser, main

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"


def commands():
    parser = _parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return parser, sub.choices


def test_every_option_of_every_command_has_help_text_and_one_spelling():
    parser, choices = commands()
    spellings = {}  # an option (its destination, and value for -q/-v) -> its option strings, in all commands
    for name, command in [("pmdfmu", parser), *choices.items()]:
        for action in command._actions:
            if isinstance(action, argparse._SubParsersAction):
                continue
            what = f"pmdfmu {name}: {'/'.join(action.option_strings) or action.dest}"
            assert action.help and action.help != argparse.SUPPRESS, f"{what} has no help text"
            if not action.option_strings:
                continue
            longs = [o for o in action.option_strings if o.startswith("--")]
            assert len(longs) == 1, f"{what}: one long spelling per option"
            key = action.dest if action.const is None else (action.dest, action.const)
            seen = spellings.setdefault(key, tuple(action.option_strings))
            assert seen == tuple(action.option_strings), f"{what}: also spelt {'/'.join(seen)} elsewhere"
    assert spellings["fmi_version"] == ("--fmi-version",)
    assert (spellings[("verbosity", -1)], spellings[("verbosity", 1)]) == (("-q", "--quiet"), ("-v", "--verbose"))


def test_pack_reads_fmi_as_an_abbreviation_of_fmi_version():
    args = _parser().parse_args(["pack", "s.script", "--out", "x.fmu", "--fmi", "3"])
    assert args.fmi_version == 3


def test_every_fmi_version_option_is_spelt_fmi_version():
    """path's was --fmi, so `pmdfmu path --fmi-version 3`, as every other command spells it, was refused."""
    _, choices = commands()
    for name, command in choices.items():
        for action in command._actions:
            assert "--fmi" not in action.option_strings, f"pmdfmu {name}: --fmi, not --fmi-version"
    assert _parser().parse_args(["path", "plant", "--fmi-version", "3"]).fmi_version == 3


def test_an_unknown_option_is_named_by_its_command(capsys):
    with pytest.raises(SystemExit) as exit:
        main(["path", "chip", "--bogus"])
    assert exit.value.code == 2
    assert capsys.readouterr().err == "pmdfmu path: unrecognized arguments: --bogus (pmdfmu path --help)\n"


def test_version(capsys):
    with pytest.raises(SystemExit) as exit:
        main(["--version"])
    assert exit.value.code == 0 and capsys.readouterr().out == f"pmdfmu {__version__}\n"


def test_help_lists_the_exit_statuses(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    for status in ("0    done", "1    a check failed", "2    bad input", "130  interrupted"):
        assert status in out
    with pytest.raises(SystemExit):
        main(["verify", "--help"])
    assert "exit status: pmdfmu --help" in capsys.readouterr().out


@pytest.mark.slow
def test_a_reader_that_goes_away_ends_the_command_quietly():
    """`pmdfmu info | head -1` said "pmdfmu info: [Errno 32] Broken pipe" and exited 2, bad input: under
    a CI shell's pipefail a gate would read that as a malformed file."""
    info = subprocess.Popen(
        [sys.executable, "-m", "pmdfmu.cli", "info"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    info.stdout.close()  # before its first line: it is still importing
    assert info.wait(timeout=120) == 141
    assert info.stderr.read() == ""


# a command whose own socket's peer went away, while its standard output is read on
PEER_GONE = """
import socket
import pmdfmu.cli as cli
line, peer = socket.socketpair()
peer.close()
def send(args):
    line.sendall(b"x" * 100_000)
    return 0
cli.cmd_path = send
raise SystemExit(cli.main(["path"]))
"""


@pytest.mark.slow
def test_a_broken_pipe_of_the_commands_own_is_named_not_silenced():
    """Only standard output's reader going away is the quiet 141: a line or socket of the command's own
    that breaks is an error, and said."""
    child = subprocess.run([sys.executable, "-c", PEER_GONE], capture_output=True, text=True, timeout=120)
    assert (child.returncode, child.stdout) == (2, "")
    assert child.stderr == "pmdfmu path: [Errno 32] Broken pipe\n"


@pytest.mark.slow
def test_sweep_leaves_its_status_0_for_a_failed_case_unless_asked(tmp_path, capsys):
    with pytest.raises(SystemExit):
        main(["sweep", "--help"])
    assert "does not change the exit status" in " ".join(capsys.readouterr().out.split())
    cases = tmp_path / "cases.csv"
    cases.write_text(f"name,table\nsquare,{EXAMPLES / 'square.csv'}\nbroken,{tmp_path / 'missing.csv'}\n")
    argv = ["sweep", str(cases), "--scheduler", "serial", "--out", str(tmp_path / "out")]
    assert main(argv) == 0
    assert "failed: broken:" in capsys.readouterr().out
    assert main([*argv, "--fail-on-error"]) == 1


@pytest.mark.slow
def test_quiet_prints_only_what_went_wrong_and_verbose_every_check(tmp_path, capsys):
    square = str(EXAMPLES / "square.csv")
    for argv in (["-q", "run", square, "--csv", str(tmp_path / "a.csv")], ["run", square, "--quiet"]):
        assert main(argv) == 0
        assert capsys.readouterr() == ("", "")
    assert main(["verify", square, "-q", "--final-position", "1=0"]) == 0
    assert capsys.readouterr().out == ""
    assert main(["verify", square, "-q", "--final-position", "1=5"]) == 1
    assert "FAIL square" in capsys.readouterr().out
    assert main(["verify", square, "--verbose", "--final-position", "1=0", "--max-step", "1=2"]) == 0
    out = capsys.readouterr().out
    assert "  PASS axis1 final position 0\n" in out and "  PASS axis1 max |position step| <= 2 counts/cycle\n" in out
    with pytest.raises(SystemExit) as exit:
        main(["run", square, "-q", "-v"])
    assert exit.value.code == 2 and "not allowed with argument" in capsys.readouterr().err


def test_build_finds_the_checkout_from_an_installed_package(tmp_path, monkeypatch, capsys):
    """./dev installs pmdfmu into .venv, where the package has no sources beside it: `pmdfmu build` took
    .venv/lib/python3.X for the source folder and cmake failed. It builds the working directory's checkout."""
    import pmdfmu.cli as cli

    monkeypatch.setattr(cli, "REPO", tmp_path / "lib")  # an installed package's two folders up: no checkout
    monkeypatch.chdir(tmp_path)
    assert main(["build"]) == 2
    assert capsys.readouterr().err == (
        "pmdfmu build: no pmdfmu checkout to build: run pmdfmu build in its top folder, or give --source\n"
    )
    (tmp_path / "CMakeLists.txt").write_text("")
    (tmp_path / "fmu_src").mkdir()
    commands = []
    monkeypatch.setattr(
        cli.subprocess, "run", lambda command: commands.append(command) or argparse.Namespace(returncode=0)
    )
    assert main(["build"]) == 0
    assert commands[0][1:5] == ["-S", str(Path.cwd()), "-B", str(Path.cwd() / "build")]
    assert commands[1] == ["cmake", "--build", str(Path.cwd() / "build")]
