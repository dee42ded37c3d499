# SPDX-License-Identifier: BSD-2-Clause
"""Short sequences of legal calls that corrupted memory, overflowed or
changed state they were refused. Each runs through the real FMU in FMI 2 and
FMI 3; a refused call must leave the FMU state byte for byte as it was."""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave

import pmdfmu
from pmdfmu import PMDTraceCommandedPosition, PMDTraceConditionUpdate, PMDTraceRollingBuffer
from states import InitializationChip, command, pend_batch, snapshot, vr
from stepwise import run_stepwise


def errors(chip):
    return " ".join(m.message for m in chip.messages if m.status == "Error")


def refused_changes_nothing(chip, call) -> str:
    """call() must raise an FMI error and leave the state as it was; returns the error messages."""
    before = snapshot(chip)
    chip.messages.clear()
    with pytest.raises(FMICallException):
        call()
    assert snapshot(chip) == before, "a refused call changed the FMU state"
    return errors(chip)


def pend_memory_write(chip, address, words, strobe=None):
    if chip.fmi_version == 2:
        for i, w in enumerate(words):
            chip.set(f"memory.data[{i + 1}]", pmdfmu.signed(w))
    else:
        chip.set("memory.data", list(words) + [0] * (64 - len(words)))
    chip.set("memory.address", address)
    chip.set("memory.count", len(words))
    chip.set("memory.strobe", chip.get("memory.strobe") + 1 if strobe is None else strobe)


# ---- 1. the trace writes only into buffer 0 as it is when it writes ----


def test_a_trace_armed_on_a_buffer_that_later_shrinks_to_nothing_does_not_start(any_chip):
    chip, ax = any_chip, any_chip.axis(0)
    chip.set("memory.address", 0)  # (FMI 3 reads need a defined port)
    ax.SetBufferStart(0, 0x3FFF)
    ax.SetBufferLength(0, 1)
    ax.SetTraceVariable(0, 0, PMDTraceCommandedPosition)
    ax.SetTraceMode(PMDTraceRollingBuffer)
    ax.SetTraceStart(0, PMDTraceConditionUpdate, 0, 0)
    ax.SetBufferLength(0, 0)  # accepted: the trace only waits
    ax.SetBufferStart(0, 0x4000)
    chip.messages.clear()
    ax.Update()
    chip.run(20)
    assert ax.GetTraceStatus() & pmdfmu.PMDTraceStatusActivity == 0
    assert ax.GetTraceCount() == 0
    assert ax.GetTraceStart() == (0, 0, 0, 0), "the start condition is used up"


def test_a_trace_armed_on_a_moved_buffer_writes_into_the_new_one(any_chip):
    chip, ax = any_chip, any_chip.axis(0)
    ax.SetBufferStart(0, 0x100)
    ax.SetBufferLength(0, 4)
    ax.SetTraceVariable(0, 0, pmdfmu.PMDTraceTime)
    ax.SetTraceStart(0, PMDTraceConditionUpdate, 0, 0)
    ax.SetBufferLength(0, 2)
    ax.SetBufferStart(0, 0x3FFE)  # now the last two words of the memory
    ax.Update()
    chip.run(10)
    assert ax.GetTraceCount() == 2
    assert ax.GetBufferStart(0) == 0x3FFE and [ax.ReadBuffer(0) for _ in range(2)] == [0, 1]


# ---- 2. recording never writes past record.capacity ----


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_script_restarting_the_grid_inside_a_recording_step_records_at_most_the_capacity(tmp_path, fmi_version):
    """FMI 2 records too (record.enabled, record.capacity), though only FMI 3 can read record.data."""
    script = tmp_path / "fine.pmd"
    script.write_text("@0\nSetSampleTime(Axis1, 1);\n")
    with pmdfmu.Chip(
        fmi_version=fmi_version, script=script, log_categories=["warnings"], **{"record.capacity": 100}
    ) as chip:
        chip.set("record.enabled", True)
        chip.messages.clear()
        chip.fmu.doStep(0.0, 100 * 1e-4)  # Warning: ran the step, recorded what fits
        assert chip.get("chipTime") == 10_000 - 1
        assert any(m.status == "Warning" and "record.data holds the first 100" in m.message for m in chip.messages)
        if fmi_version == 3:
            assert len(chip.fmu.getBinary([vr(chip, "record.data")])[0]) == 100 * 13 * 4


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_pending_sample_time_change_in_a_recording_step_records_at_most_the_capacity(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, log_categories=["warnings"], **{"record.capacity": 10}) as chip:
        chip.set("record.enabled", True)
        pend_batch(chip, command("SetSampleTime", 10))
        chip.messages.clear()
        chip.fmu.doStep(0.0, 10 * 1e-4)
        assert chip.get("chipTime") == 99
        assert any("record.data holds the first 10" in m.message for m in chip.messages)
        if fmi_version == 3:
            assert len(chip.fmu.getBinary([vr(chip, "record.data")])[0]) == 10 * 13 * 4


@pytest.mark.parametrize("version", [2, 3])
def test_a_script_that_makes_the_grid_finer_mid_recording_gets_a_stepping_masters_rows(tmp_path, version):
    """A step of 100 us then holds 100 cycles of 1 us, more than one row: the harness redoes that chunk
    cycle by cycle from its saved state (once it raised), and the rows are a stepping master's."""
    script = tmp_path / "fine.pmd"
    script.write_text("@0\nSetSampleTime(Axis1, 1);\n")
    with (
        pmdfmu.Chip(fmi_version=version, script=script) as chip,
        pmdfmu.Chip(fmi_version=version, script=script) as stepping,
    ):
        rows = chip.run(1000, record=["axis1.commandedPosition"])
        assert rows.tobytes() == run_stepwise(stepping, 1000, ["axis1.commandedPosition"]).tobytes()
        assert chip.cycles == stepping.cycles


# A recording step of n cycles at the coarsest cycle time whose grid a SetSampleTime(1) makes 65 535 times
# finer (pending, or a script's at @0): its n * 65 535 cycles in a child process, which must finish within a
# minute where running the cycles past the room one by one takes several. The child prints what it found.
COARSE_STEP = r"""
import json, sys
from ctypes import POINTER, byref, c_int, c_size_t, c_void_p, string_at
sys.path.insert(0, sys.argv[2])
import numpy as np
import pmdfmu
from pmdfmu.profile import load_external_profile, start_external_profile
from states import command, pend_batch, snapshot, vr

version, how, columns, n, script = json.loads(sys.argv[1])
COARSE = 0.065535


def chip_of(record, capacity):
    parameters = {"cycleTime": COARSE, "record.capacity": capacity}
    if how == "script":
        parameters["script"] = script
    chip = pmdfmu.Chip(fmi_version=version, log_categories=["warnings"], **parameters)
    # axis 1 integrates one long external segment throughout: fast-forward has work to do
    load_external_profile(chip, {0: [(0, 0x345, 0, 0, 0xFFFFFFFF), (0, 0, 0, 0, 0)]})
    start_external_profile(chip, [0])
    chip.set("record.columns", columns)
    if record:
        chip.set("record.enabled", True)
    row_size = chip.get("record.rowSize")        # (a get: before the batch, which the next get would run)
    if how != "script":
        pend_batch(chip, command("SetSampleTime", 1))
    chip.messages.clear()
    return chip, row_size


def extension(chip, name, *argtypes):
    f = getattr(chip.fmu.dll, name)
    f.restype, f.argtypes = c_int, [c_void_p, *argtypes]
    return f


def rows_of(chip):
    if version == 3:
        return bytes(chip.fmu.getBinary([vr(chip, "record.data")])[0])
    data, size = c_void_p(), c_size_t()
    get = extension(chip, "pmdfmu_fmi2GetRecordData", POINTER(c_void_p), POINTER(c_size_t))
    assert get(chip.fmu.component, byref(data), byref(size)) == 0
    return string_at(data.value, size.value) if size.value else b""


recorded, size = chip_of(True, n if how != "lent" else 65536)
guard = 64
if how == "lent":                   # the memory lent holds n rows, record.capacity more
    lent = np.full(n * size + 2 * guard, 0xA5, dtype=np.uint8)
    lend = extension(recorded, f"pmdfmu_fmi{version}SetRecordBuffer", c_void_p, c_size_t)
    assert lend(recorded.fmu.component, lent.ctypes.data + guard, n * size) == 0
recorded.fmu.doStep(0.0, n * COARSE)
rows = rows_of(recorded)
warnings = [m.message for m in recorded.messages if m.status == "Warning"]
recorded.set("record.enabled", False)       # the one field of the state that then differs

plain = chip_of(False, n)[0]
plain.fmu.doStep(0.0, n * COARSE)
# the rows kept: the first n cycles of the finer grid, as a recording step of just those n cycles has them
first = chip_of(True, n)[0]
first.fmu.doStep(0.0, n * 1e-6)
print(json.dumps({
    "chipTime": [c.get("chipTime") for c in (recorded, plain)],
    "position": [c.get("axis1.commandedPosition") for c in (recorded, plain)],
    "same state": snapshot(recorded) == snapshot(plain),
    "rows": len(rows) // size,
    "rows as a step of n cycles": rows == rows_of(first),
    "warnings": warnings,
    "guards": how != "lent" or bool((lent[:guard] == 0xA5).all() and (lent[guard + n * size:] == 0xA5).all()),
}))
"""


@pytest.mark.parametrize(
    "fmi_version,how,columns",
    [
        (2, "pending", ""),
        (3, "pending", "axis1.commandedPosition,axis2.activityStatus"),
        (3, "script", ""),
        (2, "script", "axis1.position,axis1.motorCommand"),
        (2, "lent", ""),
        (2, "lent", "axis1.commandedPosition,axis2.activityStatus"),
        (3, "lent", "axis1.commandedPosition,axis2.activityStatus"),
    ],
)
@pytest.mark.slow
def test_cycles_past_a_recording_steps_room_run_as_an_unrecorded_step_does(tmp_path, fmi_version, how, columns):
    """The rows past record.capacity (or the memory lent by pmdfmu_fmi*SetRecordBuffer) are not kept: they
    run as a step that records nothing runs them, fast-forwarded (60 000 coarse cycles: 4 * 10^9 fine ones,
    minutes one by one). The step ends where the unrecorded one does, the rows kept are the first ones."""
    n = 60_000
    script = tmp_path / "fine.pmd"
    script.write_text("@0\nSetSampleTime(Axis1, 1);\n")
    try:
        child = subprocess.run(
            [
                sys.executable,
                "-c",
                COARSE_STEP,
                json.dumps([fmi_version, how, columns, n, str(script)]),
                str(Path(__file__).resolve().parent),
            ],
            capture_output=True,
            text=True,
            timeout=60,
        )
    except subprocess.TimeoutExpired:
        pytest.fail("the recording step ran on for more than 60 s: the cycles past its room went one by one")
    assert child.returncode == 0, child.stderr[-2000:]
    found = json.loads(child.stdout)
    assert [t & 0xFFFFFFFF for t in found["chipTime"]] == [n * 65535 - 1] * 2  # (FMI 2: an Integer)
    assert found["position"][0] == found["position"][1] != 0
    assert found["same state"], "the recorded step ended elsewhere than the unrecorded one"
    assert found["rows"] == n and found["rows as a step of n cycles"]
    limit = f"the memory lent by pmdfmu_fmi{fmi_version}SetRecordBuffer" if how == "lent" else "record.capacity"
    assert any(f"record.data holds the first {n} ({limit})" in w for w in found["warnings"]), found["warnings"]
    assert found["guards"], "a row was written outside the memory lent"


# ---- 4. a refused set changes nothing ----


def test_a_refused_memory_address_keeps_the_pending_write(any_chip):
    chip = any_chip
    pend_memory_write(chip, 0x100, list(range(1, 65)))
    message = refused_changes_nothing(chip, lambda: chip.set("memory.address", 0x3FF0))
    assert "memory.strobe" in message and "leaves" in message
    assert chip.get("memory.address") == 0x100
    ax = chip.axis(0)
    ax.SetBufferStart(2, 0x100)
    ax.SetBufferLength(2, 64)
    assert [ax.ReadBuffer(2) for _ in range(64)] == list(range(1, 65)), "the valid write executed"


def test_a_refused_memory_strobe_keeps_its_old_value(any_chip):
    chip = any_chip
    chip.set("memory.address", 0x3FF0)
    chip.set("memory.count", 64)
    old = chip.get("memory.strobe")
    message = refused_changes_nothing(chip, lambda: chip.set("memory.strobe", old + 1))
    assert "leaves the 16384-word memory" in message
    assert chip.get("memory.strobe") == old


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_refused_memory_size_in_initialization_keeps_size_memory_and_registers(fmi_version):
    chip = InitializationChip(fmi_version)
    try:
        pend_memory_write(chip, 0x1000, [7] * 8)
        message = refused_changes_nothing(chip, lambda: chip.set("memorySize", 0x800))
        assert "memory.strobe" in message
        assert chip.get("memorySize") == 0x4000
    finally:
        chip.free()


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_memory_size_in_initialization_keeps_the_pending_port_writes(fmi_version):
    """Initialization Mode's gets execute nothing: a batch and a memory write made there wait, through
    memory size changes (one the write would leave is refused), for the first get after it."""
    chip = InitializationChip(fmi_version)
    try:
        pend_batch(
            chip, command("SetBufferStart", 2, 0x10) + command("SetBufferLength", 2, 8) + command("SetPosition", 1234)
        )
        pend_memory_write(chip, 0x10, [5, 6, 7])
        before = snapshot(chip)
        assert chip.get("host.ack") == 0
        chip.set("memorySize", 0x4000)  # the same size: nothing happens
        assert snapshot(chip) == before
        message = refused_changes_nothing(chip, lambda: chip.set("memorySize", 0x12))  # the write needs 0x13
        assert "memory.strobe" in message
        chip.set("memorySize", 0x13)
        chip.set("memorySize", 0x8000)
        chip.fmu.exitInitializationMode()
        assert chip.get("host.ack") == 1  # the batch, then the write
        pend_batch(chip, command("GetBufferStart", 2) + command("GetPosition") + command("ReadBuffer", 2) * 3)
        chip.get("host.ack")
        assert chip.reply() == [0, 0x10, 0, 1234, 0, 5, 0, 6, 0, 7]
    finally:
        chip.free()


# ---- 5. a huge step after a sample-time change ----


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_step_that_a_pending_sample_time_change_would_make_too_long_is_refused(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, cycleTime=0.065535) as chip:
        pend_batch(chip, command("SetSampleTime", 1))
        message = refused_changes_nothing(chip, lambda: chip.fmu.doStep(0.0, 2.0**52 * 0.065535))
        assert "2^53 cycles of 1 us" in message
        chip.fmu.doStep(0.0, 0.001)  # the instance steps on: 1000 cycles of 1 us
        assert chip.get("chipTime") == 999


# ---- 9. no silent rounding or wiping ----


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("cycle_time", [1.0, 123.4567e-6, 0.5e-6, 0.0655355, -1e-4, math.nan])
def test_a_cycle_time_the_sample_time_register_cannot_hold_is_refused(fmi_version, cycle_time):
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        chip.fmu.reset()  # instantiated again: parameters may be set
        message = refused_changes_nothing(chip, lambda: chip.set("cycleTime", cycle_time))
        chip.reinitialize()
    assert "whole number of microseconds" in message


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("cycle_time,micros", [(1e-6, 1), (1e-4, 100), (0.065535, 65535), (123e-6, 123)])
def test_a_whole_number_of_microseconds_is_the_sample_time(fmi_version, cycle_time, micros):
    with pmdfmu.Chip(fmi_version=fmi_version, cycleTime=cycle_time) as chip:
        assert chip.axis(0).GetSampleTime() == micros


# ---- 10. smaller ones ----


def test_a_refused_enter_initialization_changes_nothing():
    chip = pmdfmu.Chip()
    try:
        fresh = FMU2Slave(
            guid=chip.model_description.guid,
            unzipDirectory=chip._unzipdir,
            modelIdentifier=chip.model_description.coSimulation.modelIdentifier,
            instanceName="x",
        )
        fresh.instantiate(loggingOn=False)
        fresh.setReal([vr(chip, "cycleTime")], [1e-3])
        fresh.setupExperiment(startTime=1e10)  # 10^13 cycles of 1 ms: on the grid
        fresh.setReal([vr(chip, "cycleTime")], [1e-6])  # 10^16 cycles of 1 us: no cycle index holds it
        probe = type("Probe", (), {"fmu": fresh})()
        before = snapshot(probe)
        with pytest.raises(FMICallException):
            fresh.enterInitializationMode()
        assert snapshot(probe) == before
        fresh.freeInstance()
    finally:
        chip.close()


def test_an_fmi2_get_refused_for_an_unknown_value_reference_executes_nothing(chip):
    pend_batch(chip, command("SetPosition", 99))
    refused_changes_nothing(chip, lambda: chip.fmu.getInteger([vr(chip, "host.ack"), 999_999]))
    assert chip.get("host.ack") == chip.get("host.strobe")  # this get executes it


def test_fmi3_messages_show_uint32_values_unsigned():
    with pmdfmu.Chip(fmi_version=3) as chip:
        message = refused_changes_nothing(chip, lambda: chip.fmu.setUInt32([vr(chip, "memory.address")], [0x80000000]))
        assert "2147483648" in message and "-2147483648" not in message


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_refused_exit_initialization_changes_nothing(fmi_version, tmp_path):
    bad = tmp_path / "bad.pmd"
    bad.write_text("@0\nNoSuchCommand(Axis1);\n")
    chip = InitializationChip(fmi_version)
    try:
        chip.fmu.setString([vr(chip, "script")], [str(bad)])
        chip.set("cycleTime", 1e-3)
        message = refused_changes_nothing(chip, chip.fmu.exitInitializationMode)
        assert "NoSuchCommand" in message
    finally:
        chip.free()


# ---- found by review: legal sequences that overflowed ----


@pytest.mark.parametrize("fmi_version", [2, 3])
@pytest.mark.parametrize("sizes", [[0x100000, 16], [16, 0x100000], [0x4000, 16]])
def test_a_set_call_naming_memory_size_twice_takes_the_last(fmi_version, sizes):
    chip = InitializationChip(fmi_version)
    try:
        memory_size = chip.variables["memorySize"]
        chip._setters[memory_size.type]([memory_size.valueReference] * 2, sizes)
        assert chip.get("memorySize") == sizes[-1]
        chip.fmu.exitInitializationMode()
        chip.fmu.doStep(0.0, 1e-3)
        assert chip.get("chipTime") == 9
    finally:
        chip.free()


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_record_columns_are_set_before_the_end_of_initialization_whatever_the_capacity(fmi_version):
    """(found by the sequence fuzzer's record.columns) record.enabled set, then record.capacity 0: a valid
    record.columns was refused ("record.enabled: record.capacity is 0"), as if the step recorded now; the end
    of initialization sizes the buffer for the columns and the capacity as they stand then."""
    chip = InitializationChip(fmi_version)
    try:
        chip.set("record.enabled", True)
        chip.set("record.capacity", 0)
        chip.fmu.setString([vr(chip, "record.columns")], ["loopback,axis1.commandedPosition"])
        columns = chip.fmu.getString([vr(chip, "record.columns")])[0]
        assert (columns.decode() if isinstance(columns, bytes) else columns) == "loopback,axis1.commandedPosition"
        assert chip.get("record.rowSize") == 4 + 1 + 4
        chip.set("record.capacity", 10)
        chip.fmu.exitInitializationMode()
        chip.fmu.doStep(0.0, 10 * 1e-4)
        if fmi_version == 3:
            assert len(chip.fmu.getBinary([vr(chip, "record.data")])[0]) == 10 * 9
    finally:
        chip.free()


def test_a_restored_recording_state_records_into_a_buffer_of_the_current_capacity():
    with pmdfmu.Chip(fmi_version=3, **{"record.capacity": 64}) as chip:
        chip.set("record.enabled", True)
        state = chip.fmu.getFMUState()
        chip.fmu.reset()
        chip.set("record.enabled", True)  # a buffer of 64 rows
        chip.set("record.capacity", 5000)
        chip.fmu.setFMUState(state)  # a state that records: with a buffer of 5000
        chip.fmu.freeFMUState(state)
        chip.set("record.enabled", True)
        chip.fmu.doStep(0.0, 5000 * 1e-4)
        assert len(chip.fmu.getBinary([vr(chip, "record.data")])[0]) == 5000 * 13 * 4


def test_a_refused_fmi3_enter_initialization_changes_nothing():
    with pmdfmu.Chip(fmi_version=3) as chip:
        chip.fmu.reset()
        chip.set("cycleTime", 1e-6)
        refused_changes_nothing(chip, lambda: chip.fmu.enterInitializationMode(startTime=1e10))
        chip.reinitialize()


# ---- every class of bad FMI 3 call, checked as "the state bytes do not change" ----
# (tests/test_robustness.py runs the FMI 2 calls this way on a busy pair of instances)

FMI3_REFUSALS = {
    "unknown value reference": lambda c: c.fmu.getInt32([7777]),
    "wrong type": lambda c: c.fmu.getFloat64([vr(c, "axis1.commandedPosition")]),
    "an output set": lambda c: c.fmu.setInt32([vr(c, "host.ack")], [3]),
    "a fixed parameter after initialization": lambda c: c.fmu.setFloat64([vr(c, "cycleTime")], [1e-3]),
    "a word count over 64": lambda c: c.fmu.setInt32([vr(c, "host.wordCount")], [65]),
    "a memory address past the memory": lambda c: c.fmu.setUInt32([vr(c, "memory.address")], [0x80000000]),
    "a NaN step size": lambda c: c.fmu.doStep(c.time, math.nan),
    "a negative step size": lambda c: c.fmu.doStep(c.time, -1e-4),
    "a huge step size": lambda c: c.fmu.doStep(c.time, 1e300),
    "a step not at the last communication point": lambda c: c.fmu.doStep(c.time + 1.0, 1e-4),
    "EnterInitializationMode twice": lambda c: c.fmu.enterInitializationMode(),
    "an unknown log category": lambda c: c.fmu.setDebugLogging(True, ["nonsense"]),
    "a truncated state blob": lambda c: c.fmu.deserializeFMUState(snapshot(c)[:-100]),
    "a foreign state blob": lambda c: c.fmu.deserializeFMUState(b"FOREIGN!" + bytes(400)),
    "a get with an unknown value reference while a batch is pending": lambda c: c.fmu.getInt32(
        [vr(c, "host.ack"), 7777]
    ),
}


@pytest.mark.parametrize("name", FMI3_REFUSALS)
def test_fmi3_refusals_change_nothing(name):
    with pmdfmu.Chip(fmi_version=3) as chip:
        chip.axis(1).SetVelocity(0x20000)
        chip.axis(1).SetAcceleration(0x1000)
        chip.axis(1).SetPosition(100_000)
        chip.axis(1).Update()
        chip.run(50)
        if "pending" in name:  # the batch is part of the state before the call
            pend_batch(chip, command("SetPosition", 5))
        refused_changes_nothing(chip, lambda: FMI3_REFUSALS[name](chip))
