# SPDX-License-Identifier: BSD-2-Clause
"""Facts that two languages hold must agree: where one side cannot be generated from the other, the
copy is checked here (the version: tests/test_version.py; the ctypes layouts of native/: native.py at
load; the fuzzer's operation list: tests/test_determinism.py)."""

import re
from pathlib import Path

import pmdfmu
from pmdfmu import chip, native, recording

REPO = Path(__file__).resolve().parent.parent


def c_define(path: str, name: str) -> str:
    return re.search(rf"^#define {name} (\S+)", (REPO / path).read_text(), re.M).group(1)


def test_a_batch_holds_as_many_words_in_python_as_in_c():
    assert chip.BATCH_WORDS == int(c_define("fmu_src/chip/chip_types.h", "PMD_BATCH_WORDS"))
    replies = [n for n in chip._VARIABLES if n.startswith("host.reply[")]
    assert len(replies) == chip.BATCH_WORDS


def test_a_memory_block_holds_as_many_words_in_python_as_in_c():
    data = [n for n in chip._VARIABLES if n.startswith("memory.data[")]
    assert native.BLOCK_WORDS == len(data) == int(c_define("native/memory_port.c", "BLOCK_WORDS"))


def test_the_default_row_is_the_chip_time_then_each_axis_commanded_outputs():
    assert int(c_define("fmu_src/chip/chip.h", "PMD_RECORD_WORDS").strip("()").split("+")[0]) == 1
    assert recording.RECORDED == [
        f"axis{n}.commanded{q}" for n in range(1, 5) for q in ("Position", "Velocity", "Acceleration")
    ]
    assert len(recording.RECORDED) == 3 * 4


def test_the_default_cycle_time_is_the_model_descriptions():
    with pmdfmu.Chip() as c:
        assert c.cycle_time == chip.DEFAULT_CYCLE_TIME == 1e-4
