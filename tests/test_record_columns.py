# SPDX-License-Identifier: BSD-2-Clause
"""record.columns: bulk recording of any variables in FMI 2 and FMI 3: the
FMU's rows equal a master's stepping cycle by cycle (tests/stepwise.py), bad names are refused."""

from ctypes import POINTER, byref, c_int, c_size_t, c_void_p, string_at

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import recording
from pmdfmu.chip import DTYPES
from pmdfmu.profile import record_outputs
from scenarios import busy_chip, without_lending
from stepwise import run_stepwise

VERSIONS = pytest.mark.parametrize("version", (2, 3))


def reference(version, names, cycles, set_up=busy_chip, **parameters):
    with pmdfmu.Chip(fmi_version=version, **parameters) as chip:
        set_up(chip)
        return run_stepwise(chip, cycles, names)


@VERSIONS
def test_columns_changed_between_runs_each_record_as_the_reference(version):
    sets = [
        record_outputs(range(4)),
        ["axis2.eventStatus", "io.output[1]", "host.interrupt", "nextCycle"],
        ["axis3.motorOutput"],
    ]
    with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 700}) as chip, pmdfmu.Chip(fmi_version=version) as ref:
        busy_chip(chip)
        busy_chip(ref)
        for names in sets:
            rows = chip.run(1500, record=names)
            assert chip.get("record.columns") == ",".join(names)
            assert rows.tobytes() == run_stepwise(ref, 1500, names).tobytes()


@VERSIONS
@pytest.mark.parametrize(
    "value, why",
    [
        ("axis1.nothing", "is not a variable"),
        ("script", "is not a number"),
        ("time", "is the independent variable"),
        ("chipTime,,axis1.position", "is no name"),
    ],
)
def test_a_bad_column_is_refused_naming_the_value_and_changes_nothing(version, value, why):
    with pmdfmu.Chip(fmi_version=version) as chip:
        chip.set("record.columns", "axis1.position")
        with pytest.raises(FMICallException):
            chip.set("record.columns", value)
        errors = [m.message for m in chip.messages if m.status == "Error"]
        assert any(f'fmi{version}SetString: record.columns = "{value}"' in m and why in m for m in errors), errors
        assert chip.get("record.columns") == "axis1.position" and chip.get("record.rowSize") == 12


@VERSIONS
def test_row_size_follows_the_columns(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        assert chip.get("record.rowSize") == 52
        chip.set("record.columns", "axis1.activityStatus, axis1.position ,axis4.home,axis1.motorCommand,chipTime")
        assert chip.get("record.rowSize") == 4 + 2 + 8 + 1 + 2 + 4


@VERSIONS
def test_an_fmu_state_keeps_the_instances_columns(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        busy_chip(chip)
        state = chip.get_state()
        chip.run(100, record=["axis1.velocity"])
        chip.set_state(state)
        assert chip.get("record.columns") == "axis1.velocity"
        rows = chip.run(300, record=["axis1.velocity", "axis2.activityStatus"])
    ref = reference(version, ["axis1.velocity", "axis2.activityStatus"], 300)
    assert rows.tobytes() == ref.tobytes()


def test_the_fmi2_extension_checks_its_instance_and_pointers():
    with pmdfmu.Chip(fmi_version=2) as chip:
        get = chip.fmu.dll.pmdfmu_fmi2GetRecordData
        get.restype, get.argtypes = c_int, [c_void_p, POINTER(c_void_p), POINTER(c_size_t)]
        data, size = c_void_p(), c_size_t(7)
        assert get(chip.fmu.component, byref(data), byref(size)) == 0 and size.value == 0
        assert get(chip.fmu.component, None, byref(size)) == 3
        assert any("pmdfmu_fmi2GetRecordData" in m.message for m in chip.messages if m.status == "Error")
        assert get(None, byref(data), byref(size)) == 3


def lend_function(chip):
    lend = getattr(chip.fmu.dll, f"pmdfmu_fmi{chip.fmi_version}SetRecordBuffer")
    lend.restype, lend.argtypes = c_int, [c_void_p, c_void_p, c_size_t]
    return lend


def record_data(chip):
    """Where record.data's bytes lie, (address, size): FMI 3's fmi3GetBinary, FMI 2's extension."""
    if chip.fmi_version == 3:
        from fmpy.fmi3 import fmi3Binary, fmi3ValueReference

        vrs, size, value = (fmi3ValueReference * 1)(chip._vr["record.data"]), (c_size_t * 1)(), (fmi3Binary * 1)()
        chip.fmu.fmi3GetBinary(chip.fmu.component, vrs, 1, size, value, 1)
        return c_void_p.from_buffer(value).value, size[0]
    get = chip.fmu.dll.pmdfmu_fmi2GetRecordData
    get.restype, get.argtypes = c_int, [c_void_p, POINTER(c_void_p), POINTER(c_size_t)]
    data, size = c_void_p(), c_size_t()
    assert get(chip.fmu.component, byref(data), byref(size)) == 0
    return data.value, size.value


@VERSIONS
@pytest.mark.parametrize("names", [record_outputs(range(4)), []], ids=("status + Reals", "default rows"))
def test_rows_recorded_into_lent_memory_are_record_datas_rows(version, names):
    """pmdfmu_fmi2SetRecordBuffer, pmdfmu_fmi3SetRecordBuffer: the rows of a recording doStep go into the
    caller's memory, byte for byte those record.data's own buffer holds (record.columns, and the default
    rows); record.data reports them there; NULL gives the buffer back; a step recording more cycles than
    fit is refused, naming the function, and runs nothing."""
    with pmdfmu.Chip(fmi_version=version) as chip, pmdfmu.Chip(fmi_version=version) as ref:
        for c in (chip, ref):
            busy_chip(c)
            c.set("record.columns", ",".join(names))
            c.set("record.enabled", True)
        size = chip.get("record.rowSize")
        lent = np.full(400 * size + 8, 0xA5, dtype=np.uint8)
        lend = lend_function(chip)
        assert lend(chip.fmu.component, lent.ctypes.data, 400 * size) == 0
        assert record_data(chip)[1] == 0  # nothing recorded there yet
        chip._step(400)
        ref._step(400)
        address, nbytes = record_data(chip)
        assert (address, nbytes) == (lent.ctypes.data, 400 * size)
        assert lent[:nbytes].tobytes() == string_at(*record_data(ref))
        assert (lent[nbytes:] == 0xA5).all()  # nothing past the lent size
        with pytest.raises(FMICallException):
            chip._step(401)
        lender = f"the memory lent by pmdfmu_fmi{version}SetRecordBuffer holds 400 rows"
        assert any(lender in m.message for m in chip.messages if m.status == "Error")
        assert chip.cycles == ref.cycles  # the refused step ran nothing
        assert lend(chip.fmu.component, None, 0) == 0
        chip._step(1000)
        ref._step(1000)
        assert record_data(chip)[0] != lent.ctypes.data
        assert string_at(*record_data(chip)) == string_at(*record_data(ref))


@VERSIONS
def test_lent_memory_is_checked_and_a_reset_forgets_it(version):
    with pmdfmu.Chip(fmi_version=version) as chip:
        lend = lend_function(chip)
        buffer = np.zeros(64, dtype=np.uint8)
        chip.set("record.enabled", True)
        assert lend(chip.fmu.component, buffer.ctypes.data + 1, 60) == 0
        with pytest.raises(FMICallException):  # the default rows are int32 words
            chip._step(1)
        assert any(
            f"pmdfmu_fmi{version}SetRecordBuffer" in m.message and "not aligned to 4 bytes" in m.message
            for m in chip.messages
            if m.status == "Error"
        )
        assert chip.cycles == 0 and (buffer == 0).all()
        chip.set("record.columns", "axis1.activityStatus")  # 6-byte rows: any address
        chip._step(10)
        assert record_data(chip) == (buffer.ctypes.data + 1, 60) and buffer[1:61].any()
        chip.set("record.enabled", False)
        buffer[:] = 0
        assert lend(None, buffer.ctypes.data, 64) == 3
        assert lend(chip.fmu.component, buffer.ctypes.data, 64) == 0
        chip.fmu.reset()  # the instance as instantiated: nothing lent
        chip.set("record.enabled", True)
        chip.fmu.enterInitializationMode()
        chip.fmu.exitInitializationMode()
        chip._step(10)  # 10 rows would not fit the 64 bytes
        assert record_data(chip)[0] != buffer.ctypes.data and (buffer == 0).all()


def spy_loans(monkeypatch):
    """Every (address, size) Chip.run lends its FMU for one doStep (recording.lent_stepper), in order."""
    loans = []
    real = recording.lent_stepper

    def spy(chip):
        step_into = real(chip)
        if step_into is None:  # an FMU that cannot be lent memory: its rows are copied
            return None
        return lambda address, size, *step: (loans.append((address, size)), step_into(address, size, *step))[1]

    monkeypatch.setattr(recording, "lent_stepper", spy)
    return loans


def holds_no_loan(chip, loans):
    """The FMU records into record.data's own buffer, none of the memory lent to it (a recording doStep
    with record.enabled, then record.enabled off again)."""
    chip.set("record.enabled", True)
    chip._step(10)
    chip.set("record.enabled", False)
    return record_data(chip)[0] not in {address for address, _ in loans}


@VERSIONS
def test_the_harness_records_rows_in_place_and_gives_the_memory_back(version, monkeypatch):
    """Chip.run lends its result to the FMU chunk by chunk (no copy), each loan ending with its doStep; a
    run refused before any cycle lends nothing."""
    loans = spy_loans(monkeypatch)
    names = record_outputs(range(2))
    with (
        pmdfmu.Chip(fmi_version=version, **{"record.capacity": 700}) as chip,
        pmdfmu.Chip(fmi_version=version) as ref,
    ):
        for c in (chip, ref):
            busy_chip(c)
        rows = chip.run(2000, record=names)
        assert rows.tobytes() == run_stepwise(ref, 2000, names).tobytes()
        assert [size for _, size in loans] == [700 * rows.itemsize, 700 * rows.itemsize, 600 * rows.itemsize]
        assert loans[0][0] == rows.ctypes.data and loans[2][0] == rows.ctypes.data + 1400 * rows.itemsize
        assert holds_no_loan(chip, loans)
        loans.clear()
        with pytest.raises(ValueError):
            chip.run(10, record=names + ["axis1.nothing"])  # refused before any loan
        assert not loans


@VERSIONS
def test_a_chunk_redone_stepwise_overwrites_its_lent_rows(version, monkeypatch, tmp_path):
    """A script's SetSampleTime inside a lent chunk: the harness goes back to the chunk's saved state and
    writes the stepwise rows over what the FMU wrote there; the next chunks are lent again."""
    loans = spy_loans(monkeypatch)
    script = tmp_path / "finer.pmd"
    script.write_text("@500\nSetSampleTime(Axis1, 50);\n@900\nSetSampleTime(Axis1, 20);\n")
    names = record_outputs(range(2))
    with (
        pmdfmu.Chip(fmi_version=version, script=script, **{"record.capacity": 300}) as chip,
        pmdfmu.Chip(fmi_version=version, script=script) as ref,
    ):
        rows = chip.run(2000, record=names)
        assert rows.tobytes() == run_stepwise(ref, 2000, names).tobytes()
        assert chip.cycles == ref.cycles
        assert len(loans) == 7 and holds_no_loan(chip, loans)  # 7 chunks of at most 300 cycles


@VERSIONS
def test_an_interrupt_after_a_lent_step_leaves_no_loan_and_recording_off(version, monkeypatch):
    """A KeyboardInterrupt landing just after the second chunk's doStep: the loan ended inside that native
    call, record.enabled is off again, and the next run records as a fresh chip's."""
    loans = spy_loans(monkeypatch)
    with (
        pmdfmu.Chip(fmi_version=version, **{"record.capacity": 100}) as chip,
        pmdfmu.Chip(fmi_version=version) as ref,
    ):
        for c in (chip, ref):
            busy_chip(c)
        spy = recording.lent_stepper

        def interrupting(c):
            step_into = spy(c)

            def step(*args):
                result = step_into(*args)
                if len(loans) == 2:
                    raise KeyboardInterrupt
                return result

            return step

        monkeypatch.setattr(recording, "lent_stepper", interrupting)
        with pytest.raises(KeyboardInterrupt):
            chip.run(300, record=record_outputs([0]))
        assert len(loans) == 2 and chip.cycles == 200 and not chip.get("record.enabled")
        monkeypatch.setattr(recording, "lent_stepper", spy)
        ref.run(200)
        assert chip.run(300, record=record_outputs([0])).tobytes() == ref.run(300, record=record_outputs([0])).tobytes()
        assert holds_no_loan(chip, loans)


@VERSIONS
def test_a_lent_step_whose_dostep_fails_ends_the_loan_and_the_next_run_is_a_fresh_chips(version, monkeypatch):
    """The second chunk's doStep refused inside the native lent step (a communication point the FMU is not
    at): FMICallException naming fmi2DoStep / fmi3DoStep, the loan ended by that same call, record.enabled
    off, and the next run records as a fresh chip at the same cycle does."""
    loans = spy_loans(monkeypatch)
    with (
        pmdfmu.Chip(fmi_version=version, **{"record.capacity": 100}) as chip,
        pmdfmu.Chip(fmi_version=version) as ref,
    ):
        for c in (chip, ref):
            busy_chip(c)
        spy = recording.lent_stepper

        def failing(c):
            step_into = spy(c)
            return lambda address, size, now, step: step_into(address, size, now + (len(loans) == 1), step)

        monkeypatch.setattr(recording, "lent_stepper", failing)
        with pytest.raises(FMICallException, match=f"fmi{version}DoStep"):
            chip.run(300, record=record_outputs([0]))
        assert len(loans) == 2 and chip.cycles == 100 and not chip.get("record.enabled")
        assert any(f"fmi{version}DoStep" in m.message for m in chip.messages if m.status == "Error")
        monkeypatch.setattr(recording, "lent_stepper", spy)
        ref.run(100)
        assert chip.run(300, record=record_outputs([0])).tobytes() == ref.run(300, record=record_outputs([0])).tobytes()
        assert holds_no_loan(chip, loans)


@VERSIONS
@pytest.mark.parametrize(
    "names", [record_outputs(range(4)), ["axis2.eventStatus", "io.output[1]", "host.interrupt", "axis3.motorOutput"]]
)
def test_lent_rows_are_the_copied_rows_byte_for_byte(version, names, monkeypatch):
    """The same runs with the rows lent to the FMU and copied out of record.data (an FMU without
    pmdfmu_fmi*SetRecordBuffer: an older build), fresh and into a reused array, over capacity chunks: the
    same bytes, and the same as a master stepping cycle by cycle."""
    runs, loans = {}, spy_loans(monkeypatch)
    for how in ("lent", "copied"):
        with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 900}) as chip:
            if how == "copied":
                without_lending(chip)
            busy_chip(chip)
            fresh = chip.run(2000, record=names)
            out = np.empty_like(fresh)
            out.view(np.uint8)[:] = 0xFF
            chip.run(2000, record=names, out=out)
            runs[how] = fresh.tobytes() + out.tobytes()
        assert len(loans) == 6  # the lent runs' 3 chunks each, none copied
    with pmdfmu.Chip(fmi_version=version) as ref:
        busy_chip(ref)
        expected = run_stepwise(ref, 2000, names).tobytes() + run_stepwise(ref, 2000, names).tobytes()
    assert runs["lent"] == runs["copied"] == expected


def test_a_grid_change_the_harness_cannot_redo_raises(monkeypatch, tmp_path):
    """The last guard: a recording step that ran other cycles than its rows (doStep's Warning) with no saved
    state to redo it from raises RuntimeError. Here the harness is made to believe the chip has no script."""
    script = tmp_path / "finer.pmd"
    script.write_text("@100\nSetSampleTime(Axis1, 50);\n")
    for version in (2, 3):
        with pmdfmu.Chip(fmi_version=version, script=script, **{"record.capacity": 500}) as chip:
            real = chip.get
            monkeypatch.setattr(chip, "get", lambda name, real=real: 0 if name == "script.axes" else real(name))
            with pytest.raises(RuntimeError, match="ran other cycles than its rows"):
                chip.run(400, record=record_outputs([0]))


@VERSIONS
def test_every_integer_column_is_stored_in_2_or_4_bytes(version):
    """record.c's row writer stores an Integer in 2 or 4 bytes, a Real in 8, a Boolean in 1: every variable
    record.columns accepts has one of those widths (a wider or narrower type needs a row writer for it)."""
    with pmdfmu.Chip(fmi_version=version) as chip:
        chip.set("record.columns", ",".join(every_column()))
        assert chip.get("record.rowSize") == 4 + sum(DTYPES[n].itemsize for n in every_column())
    kinds = {DTYPES[n].kind + str(DTYPES[n].itemsize) for n in every_column()}
    assert kinds <= {"f8", "i4", "u4", "i2", "u2", "b1"}, kinds


@VERSIONS
def test_the_bulk_path_is_taken_for_any_columns(version, monkeypatch):
    """The native loop is not called (record.data holds the rows) unless `time` is recorded."""
    calls = []
    monkeypatch.setattr(recording, "record", lambda *a: calls.append(a))
    with pmdfmu.Chip(fmi_version=version) as chip:
        busy_chip(chip)
        rows = chip.run(50, record=record_outputs([0, 2]))
        assert not calls and len(rows) == 50 and (np.diff(rows["cycle"].astype(int)) == 1).all()


# ---- every column kind in bulk == a master stepping cycle by cycle --------------------------------


def every_column():
    """Every variable record.columns accepts: each Real, Integer and Boolean but time (FMI 2 names); the
    record.* ones apart (they describe the recording itself: record.enabled is on only in the bulk run)."""
    return [n for n in DTYPES if n != "time" and not n.startswith("record.")]


def motors_and_idle_axes(chip):
    """busy_chip (axis 1 external, axis 2 trapezoid, a breakpoint armed on axis 1), axis 3's motor off with
    a motor command, axis 4 idle; switches and inputs at rest. Feedforward gains and a bias on every axis
    (applied by the moves' Updates): an ideal servo's motor command shows each cycle's velocity and
    acceleration, so a filter left behind would show in its columns."""
    for n in range(4):
        ax = chip.axis(n)
        ax.SetKvff(0x100)
        ax.SetKaff(0x4000)
        ax.SetMotorBias(300)
    chip.axis(3).Update()
    busy_chip(chip)
    ax = chip.axis(2)
    ax.SetMotorMode(pmdfmu.PMDMotorOff)
    ax.SetMotorCommand(-1234)
    ax.Update()
    chip.axis(0).WriteIO(2, 0xBEEF)


def a_move_that_settles(chip):
    """motors_and_idle_axes, and axis 4 on a short trapezoid that ends, settles and raises motion complete
    during the first part (an ideal servo's axis, loopback, at rest mid-run)."""
    motors_and_idle_axes(chip)
    a4 = chip.axis(3)
    a4.SetPosition(300)
    a4.SetVelocity(0x50000)
    a4.SetAcceleration(0x2000)
    a4.Update()


def run_in_parts(chip, names, bulk):
    """Runs in parts with commands between them (motor off and on, a breakpoint armed, then none):
    the bulk rows or the stepwise ones."""

    def part(cycles):
        return chip.run(cycles, record=names) if bulk else run_stepwise(chip, cycles, names)

    rows = [part(700)]
    chip.axis(1).SetMotorMode(pmdfmu.PMDMotorOff)  # the trapezoid's motor off: its filter runs open loop
    rows.append(part(300))
    chip.axis(1).SetMotorMode(pmdfmu.PMDMotorOn)
    chip.axis(0).SetBreakpoint(0, 0, pmdfmu.PMDBreakpointNoAction, pmdfmu.PMDBreakpointDisable)
    rows.append(part(900))  # no breakpoint armed: a quiet run
    return np.concatenate(rows)


@VERSIONS
@pytest.mark.parametrize("loopback", (True, False))
def test_every_column_kind_in_bulk_is_the_stepwise_value(version, loopback):
    with (
        pmdfmu.Chip(fmi_version=version, loopback=loopback, **{"record.capacity": 500}) as chip,
        pmdfmu.Chip(fmi_version=version, loopback=loopback) as ref,
    ):
        names = every_column()
        assert len(names) > 250 and {"axis1.motorOutput", "io.output[16]", "host.interrupt"} <= set(names)
        assert chip.run(1, record=["record.enabled", "record.capacity"])[0].tolist()[1:] == (True, 500)
        ref.run(1)
        motors_and_idle_axes(chip)
        motors_and_idle_axes(ref)
        rows = run_in_parts(chip, names, bulk=True)
        assert rows.tobytes() == run_in_parts(ref, names, bulk=False).tobytes()


@VERSIONS
@pytest.mark.parametrize("loopback", (True, False))
def test_every_column_but_the_filters_in_bulk_is_the_stepwise_value(version, loopback):
    """Without the motor command columns a recording doStep runs its cycles as one chip run (record.c,
    pmd_chip_run_every_cycle_with_rows), an ideal servo's filter advanced at its end: every other column (status bits of
    position error and settling, events, the Reals) as a master stepping cycle by cycle."""
    names = [n for n in every_column() if not n.endswith((".motorCommand", ".motorOutput"))]
    with (
        pmdfmu.Chip(fmi_version=version, loopback=loopback, **{"record.capacity": 450}) as chip,
        pmdfmu.Chip(fmi_version=version, loopback=loopback) as ref,
    ):
        a_move_that_settles(chip)
        a_move_that_settles(ref)
        rows = run_in_parts(chip, names, bulk=True)
        assert rows.tobytes() == run_in_parts(ref, names, bulk=False).tobytes()
        # the ideal servo's move ended and settled inside the first part; the filters are up to date after a run
        settled = pmdfmu.field_dp(0, "PMDActivityAxisSettled", 1)
        status = rows["axis4.activityStatus"]
        assert not status[0] & settled and bool(status[600] & settled) == loopback
        assert chip.get("axis1.motorCommand") == ref.get("axis1.motorCommand")


@VERSIONS
@pytest.mark.parametrize(
    "names",
    [
        record_outputs(range(4)),
        ["axis1.activityStatus", "axis2.activityStatus"],
        ["axis1.motorCommand", "axis2.motorOutput", "axis4.motorCommand"],
        ["axis2.eventStatus", "host.interrupt", "axis1.velocity"],
    ],
)
def test_column_sets_in_bulk_are_the_stepwise_values(version, names):
    """Sets that read no servo filter, only filters, or events: each as a master stepping cycle by cycle."""
    with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 333}) as chip, pmdfmu.Chip(fmi_version=version) as ref:
        motors_and_idle_axes(chip)
        motors_and_idle_axes(ref)
        assert run_in_parts(chip, names, True).tobytes() == run_in_parts(ref, names, False).tobytes()


@VERSIONS
def test_a_set_sample_time_inside_a_recording_step_records_the_cycles_stepwise(version, tmp_path):
    """One doStep across two SetSampleTime script steps, each to a coarser grid: record.data's rows (every
    cycle the step ran, on the grid as it stood) are those of a master stepping cycle by cycle. (A finer grid
    makes such a master's step run several cycles, recording the last: the harness then redoes the chunk
    stepwise, tests/test_native_record.py.)"""
    script = tmp_path / "grid.script"
    script.write_text("@40\nSetSampleTime(Axis1, 200)\n@90\nSetSampleTime(Axis1, 500)\n")
    names = [
        "nextCycleTime",
        "activeCycleTime",
        "nextCycle",
        "axis1.velocity",
        "axis1.acceleration",
        "axis2.activityStatus",
        "chipTime",
    ]
    with pmdfmu.Chip(fmi_version=version, script=script) as chip:
        busy_chip(chip)
        _, dtype = chip._columns(names)
        chip.set("record.columns", ",".join(names))
        chip.set("record.enabled", True)
        chip._step(300)
        address, size = recording.record_data(chip)()
        rows = np.frombuffer(string_at(address, size), dtype=dtype)
        assert size == len(rows) * dtype.itemsize and set(rows["activeCycleTime"]) == {1e-4, 2e-4, 5e-4}
    ref = reference(version, names, len(rows), script=script)
    assert rows.tobytes() == ref.tobytes()


@VERSIONS
@pytest.mark.parametrize("names", [record_outputs(range(4)), ["axis1.commandedPosition", "axis3.commandedVelocity"]])
def test_a_run_of_many_chunks_holds_the_stepwise_rows(version, names):
    """Five chunks of record.capacity cycles: the rows are a stepping master's, in FMI 2 (rows lent), FMI 3
    (record.data copied) and the commanded table."""
    with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 333}) as chip, pmdfmu.Chip(fmi_version=version) as ref:
        for c in (chip, ref):
            motors_and_idle_axes(c)
        rows = chip.run(1500, record=names)
        assert rows.tobytes() == run_stepwise(ref, 1500, names).tobytes()


@VERSIONS
def test_a_chip_with_record_capacity_0_records_cycle_by_cycle(version):
    """record.capacity 0: the FMU records nothing in bulk, so Chip.run records as a stepping master does."""
    names = record_outputs([0])
    with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 0}) as chip, pmdfmu.Chip(fmi_version=version) as ref:
        for c in (chip, ref):
            busy_chip(c)
        assert chip.run(300, record=names).tobytes() == run_stepwise(ref, 300, names).tobytes()
