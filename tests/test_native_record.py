# SPDX-License-Identifier: BSD-2-Clause
"""Chip.run(record=...) in bulk (the FMU's record.data and record.columns, rows lent
or copied) and through the native loop (native/record_loop.c,
pmdfmu.recording) is the harness's cycle-by-cycle Python loop (tests/stepwise.py,
kept as the reference), bit for bit: rows, errors, log messages, host clock
."""

from ctypes import CFUNCTYPE

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import recording
from pmdfmu.chip import RECORDED
from pmdfmu.profile import record_outputs
from scenarios import busy_chip
from stepwise import NativeLoop, Stepwise

# every FMI type the rows hold: UInt32 (chipTime), Int32, Float64, UInt16 (status, an array's element with its
# high bit set), Int16 (a negative motor command), Boolean (an input and an output)
EVERY_TYPE = [
    "chipTime",
    "axis1.commandedPosition",
    "axis2.commandedVelocity",
    "axis1.position",
    "axis2.velocity",
    "axis1.acceleration",
    "axis1.activityStatus",
    "axis1.eventStatus",
    "axis3.motorCommand",
    "io.output[3]",
    "io.output[16]",
    "analog[2]",
    "axis4.home",
    "host.interrupt",
    "nextCycleTime",
]


@pytest.fixture
def reference(monkeypatch):
    """run() with the Python loop in place of the native one: everything else run() does (checks, the
    host clock) stays."""
    monkeypatch.setattr(pmdfmu.Chip, "recorder", Stepwise)


@pytest.fixture
def native_loop(monkeypatch):
    """run() through the native loop, as for an FMU without bulk recording of any columns."""
    monkeypatch.setattr(pmdfmu.Chip, "recorder", NativeLoop)


def every_type_chip(chip):
    busy_chip(chip)
    ax = chip.axis(2)
    ax.SetMotorMode(pmdfmu.PMDMotorOff)
    ax.SetMotorCommand(-1234)
    ax.Update()
    chip.axis(0).WriteIO(2, 0xBEEF)  # io.output[3]: UInt16 above 0x7FFF (FMI 2 reads Integers)
    chip.set("analog[2]", 0xFEDC)
    chip.set("axis4.home", True)


def recorded(version, names, cycles, set_up=every_type_chip, **parameters):
    with pmdfmu.Chip(fmi_version=version, **parameters) as chip:
        set_up(chip)
        rows = chip.run(cycles, record=names)
        return rows, chip.cycles, [(m.status, m.category, m.message) for m in chip.messages]


def same(a, b):
    assert a[0].dtype == b[0].dtype and a[0].tobytes() == b[0].tobytes()
    assert a[1:] == b[1:]


@pytest.mark.parametrize("version", (2, 3))
def test_every_fmi_type_and_an_array_element_is_recorded_as_the_python_loop_records_it(version, request):
    native = recorded(version, EVERY_TYPE, 1500)
    request.getfixturevalue("reference")
    same(native, recorded(version, EVERY_TYPE, 1500))
    rows = native[0]
    assert rows["axis3.motorCommand"][-1] == -1234 and rows["io.output[3]"][-1] == 0xBEEF
    assert rows["analog[2]"][-1] == 0xFEDC and rows["axis4.home"].all() and rows["host.interrupt"].any()
    assert list(rows["cycle"][:3]) == [0, 1, 2] and (rows["cycle"] == rows["chipTime"]).all()


@pytest.mark.parametrize("version", (2, 3))
def test_status_and_reals_of_every_axis(version, request):
    names = record_outputs(range(4))
    native = recorded(version, names, 2000, busy_chip)
    request.getfixturevalue("reference")
    same(native, recorded(version, names, 2000, busy_chip))


def test_the_commanded_outputs_through_fmi3_native_and_bulk_are_the_same_rows():
    """FMI 3's 12 commanded outputs go through record.data (faster); the native loop gives the same rows."""
    runs = []
    for native in (True, False):
        with pmdfmu.Chip(fmi_version=3) as chip:
            busy_chip(chip)
            if native:
                where, dtype = chip._columns(RECORDED)
                rows = np.zeros(1200, dtype=dtype)
                recording.record(chip, recording.Plan(chip, where, dtype), rows)
            else:
                rows = chip.run(1200, record=RECORDED)
            runs.append((rows.tobytes(), chip.cycles))
    assert runs[0] == runs[1]


@pytest.mark.parametrize("size", (0, 3, 16))
def test_the_native_loop_refuses_a_field_of_a_size_it_does_not_copy_before_any_cycle_runs(size):
    """record_loop.c copies fields of 1, 2, 4 or 8 bytes; another size is refused, never stored as one byte."""
    with pmdfmu.Chip() as chip:
        where, dtype = chip._columns(["axis1.commandedPosition"])
        plan = recording.Plan(chip, where, dtype)
        plan.columns[1].size = size
        with pytest.raises(ValueError, match="not 1, 2, 4 or 8 bytes wide"):
            recording.record(chip, plan, np.zeros(10, dtype=dtype))
        assert chip.cycles == 0


@pytest.mark.parametrize("version", (2, 3))
def test_a_script_changing_the_sample_time_mid_run(version, tmp_path, request):
    """Each cycle's step goes to the next cycle of the grid as it stands before it (the step in which the grid
    gets finer runs the cycles of the new grid that its end passes): the rows go on at the new time."""
    script = tmp_path / "slower.script"
    script.write_text("@10\nSetSampleTime(Axis1, 200)\n@20\nSetSampleTime(Axis1, 50)\n")
    names = ["axis1.commandedPosition", "activeCycleTime", "nextCycleTime", "time"]
    native = recorded(version, names, 100, busy_chip, script=script)
    request.getfixturevalue("reference")
    same(native, recorded(version, names, 100, busy_chip, script=script))
    assert native[1] >= 100 and set(native[0]["activeCycleTime"]) == {1e-4, 2e-4, 5e-5}


@pytest.mark.parametrize("version", (2, 3))
def test_logging_on_and_warnings_during_the_run(version, tmp_path, request):
    """The FMU's logger is a Python callback, called from inside the native loop (ctypes takes the GIL back)."""
    script = tmp_path / "refused.script"
    script.write_text("@5\nSetProfileMode(Axis1, 9)\n@7\nSetVelocity(Axis2, 0x10000)\n")
    native = recorded(version, EVERY_TYPE, 50, log_categories=True, script=script)
    request.getfixturevalue("reference")
    same(native, recorded(version, EVERY_TYPE, 50, log_categories=True, script=script))
    assert any(status == "Warning" and "refused" in message for status, _c, message in native[2])


def failing_step(chip, at):
    """The FMU's own doStep, asked for a step of 0 s at its `at`-th call (the FMU refuses it: Error, and
    logs why), as FMPy's wrapper and the native loop both call it."""
    name = f"fmi{chip.fmi_version}DoStep"
    step = chip.fmu._functions[name]
    calls = [0]

    def do_step(instance, t, h, *rest):
        calls[0] += 1
        return step(instance, t, 0.0 if calls[0] == at else h, *rest)

    fake = CFUNCTYPE(step.restype, *step.argtypes)(do_step)
    fake.argtypes, fake.restype = step.argtypes, step.restype  # FMPy's _call reads them
    return name, fake


@pytest.mark.parametrize("version", (2, 3))
def test_an_error_mid_run_raises_as_the_python_loop_raised(version, monkeypatch):
    results = []
    for native in (True, False):
        with monkeypatch.context() as m:
            # a doStep a cycle: the native loop's error, and the Python loop's
            m.setattr(pmdfmu.Chip, "recorder", NativeLoop if native else Stepwise)
            with pmdfmu.Chip(fmi_version=version, host_interface="parallel16") as chip:
                busy_chip(chip)  # the commands' host time runs cycles
                start = chip.cycles
                name, fake = failing_step(chip, 300)
                m.setitem(chip.fmu._functions, name, fake)  # the FMPy slaves of one FMU file may share them
                with pytest.raises(FMICallException) as e:
                    chip.run(1000, record=EVERY_TYPE)
                results.append(
                    (
                        type(e.value),
                        str(e.value),
                        chip.cycles - start,
                        chip.host_time_ns,
                        [(x.status, x.message) for x in chip.messages],
                    )
                )
                chip.run(5)  # the instance goes on
                assert chip.cycles == start + results[-1][2] + 5
    assert results[0] == results[1]
    assert results[0][1].startswith(f"fmi{version}DoStep failed with status 3")
    assert results[0][2] == 299 and any("step size must be finite and > 0" in m for _s, m in results[0][4])


@pytest.mark.parametrize("version", (2, 3))
def test_recording_0_cycles(version, request):
    for names in (EVERY_TYPE, RECORDED):
        native = recorded(version, names, 0)
        request.getfixturevalue("reference")
        same(native, recorded(version, names, 0))
        assert len(native[0]) == 0 and native[1] == 0


@pytest.mark.parametrize("version", (2, 3))
@pytest.mark.parametrize("names", (["axis1.position", "axis1.position"], RECORDED + RECORDED[:1]))
def test_a_column_given_twice_is_refused_before_any_cycle_runs(version, names):
    with pmdfmu.Chip(fmi_version=version) as chip:
        with pytest.raises(ValueError, match="occurs more than once"):
            chip.run(10, record=names)
        assert chip.cycles == 0


@pytest.mark.parametrize("version", (2, 3))
def test_a_variable_read_for_two_reasons_is_read_once(version, request):
    """chipTime (also the `cycle` column), the grid's time, an array's two elements: each is one value read."""
    names = ["chipTime", "time", "activeCycleTime", "io.output[3]", "io.output[2]", "axis1.position"]
    native = recorded(version, names, 30)
    request.getfixturevalue("reference")
    same(native, recorded(version, names, 30))


@pytest.mark.parametrize("version", (2, 3))
def test_a_chip_with_a_host_interface_moves_the_host_clock_as_before(version, request):
    def run(chip_):
        chip_.wait(0.0123)
        rows = chip_.run(777, record=EVERY_TYPE)
        return rows, chip_.host_time_ns, chip_.cycles

    results = []
    for use_reference in (False, True):
        if use_reference:
            request.getfixturevalue("reference")
        with pmdfmu.Chip(fmi_version=version, host_interface="serial") as chip:
            every_type_chip(chip)
            rows, host_ns, cycles = run(chip)
            results.append((rows.tobytes(), host_ns, cycles))
    assert results[0] == results[1]
    assert results[0][1] > 0


@pytest.mark.parametrize("version", (2, 3))
@pytest.mark.parametrize("names", (EVERY_TYPE, record_outputs(range(4)), RECORDED))
def test_the_native_loop_records_as_the_bulk_path(version, names, request):
    bulk = recorded(version, names, 1500)
    request.getfixturevalue("native_loop")
    same(bulk, recorded(version, names, 1500))


@pytest.mark.parametrize("version", (2, 3))
@pytest.mark.parametrize("names", (EVERY_TYPE, RECORDED))
def test_a_failed_bulk_step_raises_and_leaves_recording_off(version, names, monkeypatch):
    """A doStep that fails in bulk (here: the FMU refuses a step of 0 s) raises FMPy's FMICallException;
    record.enabled is off again and the instance goes on."""
    with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 100}) as chip:
        busy_chip(chip)
        name, fake = failing_step(chip, 3)
        with monkeypatch.context() as m:
            m.setitem(chip.fmu._functions, name, fake)  # the FMPy slaves of one FMU file may share them
            with pytest.raises(FMICallException, match=f"fmi{version}DoStep failed with status 3"):
                chip.run(1000, record=names)
        assert not chip.get("record.enabled")
        assert any("step size must be finite and > 0" in m.message for m in chip.messages)
        start = chip.cycles
        chip.run(5)
        assert chip.cycles == start + 5
