# SPDX-License-Identifier: BSD-2-Clause
"""docs/commands.md lists every opcode with its status, and the FMU agrees."""

import subprocess
import sys
from pathlib import Path

import pytest

from pmdfmu import COMMANDS
from pmdfmu.docs import commands_markdown, out_of_scope

DOC = Path(__file__).resolve().parent.parent / "docs" / "commands.md"


def test_commands_md_is_current():
    assert DOC.read_text() == commands_markdown(), "run: python -m pmdfmu.docs"


def test_the_tables_do_not_overlap():
    implemented = {c.opcode for c in COMMANDS.values()}
    assert not implemented & {op for op, _, _ in out_of_scope()}


@pytest.mark.parametrize("opcode,name", [(op, name) for op, name, _ in out_of_scope()])
def test_out_of_scope_opcodes_answer_invalid_instruction(chip, opcode, name):
    assert chip.batch([opcode])[0] == 0x02, name


def test_every_opcode_is_either_implemented_or_invalid(chip):
    implemented = {c.opcode for c in COMMANDS.values()}
    for opcode in range(256):
        if opcode not in implemented:
            assert chip.batch([opcode])[0] == 0x02, hex(opcode)


def test_the_generator_run_elsewhere_says_where_to_run_it(tmp_path):
    """In a folder with no docs/ it raised FileNotFoundError with a traceback."""
    done = subprocess.run([sys.executable, "-m", "pmdfmu.docs"], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 1 and not (tmp_path / "docs").exists()
    assert (
        done.stderr == "python -m pmdfmu.docs: docs/commands.md: no folder docs: run it in the checkout's top folder\n"
    )
