# SPDX-License-Identifier: BSD-2-Clause
"""FMU state: get, set, free, serialize, deserialize."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from scenarios import BUSY_OUTPUTS, busy_chip


def test_step_save_step_restore_step_gives_identical_outputs(chip):
    busy_chip(chip)
    chip.run(300)
    saved = chip.get_state()
    first = chip.run(900, record=BUSY_OUTPUTS)
    chip.set_state(saved)
    again = chip.run(900, record=BUSY_OUTPUTS)
    assert np.array_equal(first, again)
    assert first["host.interrupt"][-1]  # the run crossed the end of the profile


def test_restore_in_a_second_instance_and_a_second_process(chip, tmp_path):
    busy_chip(chip)
    chip.run(250)
    saved = chip.get_state()
    expected = chip.run(800, record=BUSY_OUTPUTS)
    with pmdfmu.Chip() as other:
        other.set_state(saved)
        assert np.array_equal(other.run(800, record=BUSY_OUTPUTS), expected)
    (tmp_path / "state.bin").write_bytes(saved)
    script = textwrap.dedent(f"""
        import numpy as np, pmdfmu, sys
        with pmdfmu.Chip() as chip:
            chip.set_state(open({str(tmp_path / "state.bin")!r}, 'rb').read())
            np.save({str(tmp_path / "out.npy")!r}, chip.run(800, record={BUSY_OUTPUTS!r}))
    """)
    subprocess.run([sys.executable, "-c", script], check=True)
    assert np.array_equal(np.load(tmp_path / "out.npy"), expected)


def test_a_state_with_another_memory_size_resizes_the_memory():
    with pmdfmu.Chip(memorySize=100) as small, pmdfmu.Chip() as big:
        small.write_memory(99, [123])
        big.set_state(small.get_state())
        assert big.get("memorySize") == 100
        ax = big.axis(0)
        ax.SetBufferStart(2, 99)
        ax.SetBufferLength(2, 1)
        assert ax.ReadBuffer(2) == 123


@pytest.mark.parametrize(
    "damage,reason",
    [
        (lambda b: b[:-1], "truncated"),
        (lambda b: b[:40], "shorter than a snapshot header"),
        (lambda b: b[:300] + bytes([b[300] ^ 0x10]) + b[301:], "checksum"),
        (lambda b: b"XXXXXXXX" + b[8:], "magic"),
        (lambda b: b[:20] + b"{00000000-0000-0000-0000-000000000000}" + b[58:], "instantiation token"),
        (lambda b: b"", "shorter"),
    ],
)
def test_a_corrupted_or_foreign_state_is_refused_and_nothing_changes(chip, damage, reason):
    busy_chip(chip)
    chip.run(100)
    blob = chip.fmu.serializeFMUState(chip.fmu.getFMUState())
    before = chip.axis(0).GetCommandedPosition()
    with pytest.raises(FMICallException):
        chip.fmu.deserializeFMUState(damage(blob))
    assert any(reason in m.message for m in chip.messages if m.status == "Error"), chip.messages[-1:]
    assert chip.axis(0).GetCommandedPosition() == before
    chip.run(1)
