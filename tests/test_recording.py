# SPDX-License-Identifier: BSD-2-Clause
"""Bulk recording through FMI 3 record.data: the same rows as
recording cycle by cycle, far fewer FMI calls."""

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu.chip import RECORDED
from pmdfmu.profile import record_outputs
from scenarios import busy_chip
from stepwise import run_stepwise


def test_bulk_recording_equals_cycle_by_cycle_recording_through_fmi2():
    runs = []
    for version in (2, 3):
        with pmdfmu.Chip(fmi_version=version, **({"record.capacity": 1000} if version == 3 else {})) as chip:
            busy_chip(chip)
            runs.append(chip.run(2500, record=RECORDED))  # FMI 3: three record chunks
    assert np.array_equal(runs[0], runs[1])


def test_record_data_holds_chip_time_then_position_velocity_acceleration_per_axis():
    with pmdfmu.Chip(fmi_version=3) as chip:
        busy_chip(chip)
        chip.set("record.enabled", True)
        chip.fmu.doStep(0.0, 5 * chip.cycle_time)
        rows = np.frombuffer(chip.fmu.getBinary([chip.variables["record.data"].valueReference])[0], "<i4")
        rows = rows.reshape(5, 13)
        assert list(rows[:, 0]) == [0, 1, 2, 3, 4]
        assert rows[-1, 1] == chip.axis(0).GetCommandedPosition() and rows[-1, 2] == chip.axis(0).GetCommandedVelocity()
        assert rows[-1, 4] == chip.axis(1).GetCommandedPosition()


def test_a_recording_step_longer_than_the_capacity_is_refused():
    with pmdfmu.Chip(fmi_version=3, **{"record.capacity": 10}) as chip:
        chip.set("record.enabled", True)
        with pytest.raises(FMICallException):
            chip.fmu.doStep(0.0, 11 * chip.cycle_time)
        assert any("record.capacity is 10" in m.message for m in chip.messages)
        chip.fmu.doStep(0.0, 10 * chip.cycle_time)
        assert chip.get("chipTime") == 9
    with pmdfmu.Chip(fmi_version=3, **{"record.capacity": 0}) as chip:
        with pytest.raises(FMICallException):
            chip.set("record.enabled", True)


@pytest.mark.parametrize("version", (2, 3))
def test_recording_an_unknown_variable_is_refused_before_any_cycle_runs(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        with pytest.raises(ValueError, match="axis1.signalStatus"):
            chip.run(10, record=["axis1.commandedPosition", "axis1.signalStatus"])
        assert chip.cycles == 0 and chip.get("chipTime") == 0


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_changing_the_sample_time_during_a_bulk_recording_is_recorded_as_a_stepping_master_sees_it(
    tmp_path, version
):
    """A chunk whose grid a script step changes (a step of 100 cycles then holds 55) is redone from its
    saved state cycle by cycle: the rows of a master stepping cycle by cycle, and the run ends where
    that master's would (once this raised and left the chip 55 cycles on)."""
    script = tmp_path / "slower.script"
    script.write_text("@10\nSetSampleTime(Axis1, 200)\n")
    with (
        pmdfmu.Chip(fmi_version=version, script=script) as bulk,
        pmdfmu.Chip(fmi_version=version, script=script) as stepping,
    ):
        rows = bulk.run(100, record=RECORDED)
        expected = run_stepwise(stepping, 100, RECORDED)
        assert rows.tobytes() == expected.tobytes() and len(rows) == 100
        assert bulk.cycles == stepping.cycles == 100


# every way a run records: the commanded table, record.columns (lent; copied: tests/test_record_columns.py), the
# native loop
OUT_KINDS = {
    "commanded": (list(RECORDED[:5]), {}),
    "columns": (["axis1.commandedPosition", "axis2.activityStatus", "axis1.motorCommand", "loopback"], {}),
    "native loop": (["time", "axis1.commandedPosition"], {}),
    "capacity 0": (["axis1.commandedPosition"], {"record.capacity": 0}),
}


@pytest.mark.parametrize("kind", OUT_KINDS)
@pytest.mark.parametrize("version", (2, 3))
def test_a_run_into_a_reused_array_records_what_a_fresh_array_gets(version, kind):
    """run(out=): the rows of a fresh run, byte for byte, whatever the array held before (it is
    filled with 0xFF bytes), in the array passed, which is returned; twice in a row, over capacity chunks."""
    names, parameters = OUT_KINDS[kind]
    with (
        pmdfmu.Chip(fmi_version=version, **parameters) as fresh,
        pmdfmu.Chip(fmi_version=version, **parameters) as reused,
    ):
        busy_chip(fresh)
        busy_chip(reused)
        out = None
        for cycles in (1500, 1500):
            want = fresh.run(cycles, record=names)
            if out is None:
                out = np.empty_like(want)
            out.view(np.uint8)[:] = 0xFF
            got = reused.run(cycles, record=names, out=out)
            assert got is out
            assert got.tobytes() == want.tobytes()


@pytest.mark.parametrize("names", (RECORDED, record_outputs(range(4))), ids=("commanded", "status + Reals"))
def test_copied_rows_in_cache_sized_chunks_are_the_rows_of_capacity_chunks(names, monkeypatch):
    """Rows copied out of record.data (the commanded table; record.columns from an FMU that cannot be lent
    memory) go into the result in chunks of COPIED_CHUNK_BYTES at most (the rows still in the cache): the
    same bytes as one chunk of record.capacity (65 536 rows), with chunks of 641 / 1923 rows too."""
    from pmdfmu import recording

    monkeypatch.setattr(recording, "lent_stepper", lambda chip: None)
    runs = []
    for chunk_bytes in (recording.COPIED_CHUNK_BYTES, 100_000, 1 << 40):
        monkeypatch.setattr(recording, "COPIED_CHUNK_BYTES", chunk_bytes)
        with pmdfmu.Chip(fmi_version=3) as chip:
            busy_chip(chip)
            runs.append(chip.run(30_000, record=names).tobytes())
    assert runs[0] == runs[1] == runs[2]


@pytest.mark.parametrize(
    "out, why",
    [
        (lambda rows: list(rows), "is a list, not a numpy array"),
        (lambda rows: np.empty(len(rows), dtype=[("cycle", "<u4")]), "has dtype"),
        (lambda rows: np.empty(len(rows) + 1, dtype=rows.dtype), r"has shape \(11,\), not \(10,\)"),
        (lambda rows: np.empty(2 * len(rows), dtype=rows.dtype)[::2], "is not a writeable, aligned, contiguous"),
        (lambda rows: np.frombuffer(rows.tobytes(), dtype=rows.dtype), "is not a writeable"),
    ],
)
def test_a_run_into_an_array_that_cannot_hold_its_rows_is_refused_before_any_cycle_runs(out, why):
    with pmdfmu.Chip() as chip:
        rows = chip.run(10, record=["axis1.commandedPosition"])
        with pytest.raises(ValueError, match="run: out= " + why):
            chip.run(10, record=["axis1.commandedPosition"], out=out(rows))
        assert chip.cycles == 10
        with pytest.raises(ValueError, match="out= needs record="):
            chip.run(10, out=rows)
