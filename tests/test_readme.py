# SPDX-License-Identifier: BSD-2-Clause
"""The README is a front door whose examples run: its Python blocks print what their `# ->` lines
say, its C programs compile against the C-Motion library and prints what it says (the CI gate's
commands are run by tests/test_verify_cli.py, the systems' by tests/test_systems.py)."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import pmdfmu
from cmotion_build import compile_program, generate

REPO = Path(__file__).resolve().parent.parent
README = (REPO / "README.md").read_text()


def blocks(language: str):
    return re.findall(rf"```{language}\n(.*?)```", README, re.S)


def test_the_readme_is_a_front_door():
    assert len(README.splitlines()) <= 200
    assert README.index("./dev demo") < README.index("## A first host script")


def test_every_python_block_prints_what_it_says(tmp_path):
    for code in blocks("python"):
        expected = [line[len("# -> ") :] for line in code.splitlines() if line.startswith("# -> ")]
        done = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        if expected:
            assert done.stdout.splitlines() == expected


@pytest.mark.slow
def test_the_c_programs_run_to_their_printed_results(tmp_path):
    """The 2.x and the 5.x program, each compiled as shown, opening the twin from its own set-up code."""
    programs = blocks("c")
    assert len(programs) == 2
    generated = generate(tmp_path / "generated")
    for n, code in enumerate(programs):
        source = tmp_path / f"program{n}.c"
        source.write_text(code)
        exe = compile_program(source, tmp_path / f"program{n}", generated)
        env = dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)))
        done = subprocess.run([str(exe)], cwd=tmp_path, capture_output=True, text=True, timeout=120, env=env)
        assert done.returncode == 0, done.stderr
        assert done.stdout.split() == re.findall(r"/\* -> (\S+) \*/", code)
