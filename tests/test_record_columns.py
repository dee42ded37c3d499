"""record.columns: bulk recording of any variables in FMI 2 and FMI 3 (issue 16, target 3): the
FMU's rows equal a master's stepping cycle by cycle (Chip._run_stepwise), bad names are refused."""
from ctypes import POINTER, byref, c_int, c_size_t, c_void_p

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import recording
from pmdfmu.profile import record_outputs
from scenarios import busy_chip

VERSIONS = pytest.mark.parametrize("version", (2, 3))


def reference(version, names, cycles, set_up=busy_chip, **parameters):
    with pmdfmu.Chip(fmi_version=version, **parameters) as chip:
        set_up(chip)
        return chip._run_stepwise(cycles, names)


@VERSIONS
def test_columns_changed_between_runs_each_record_as_the_reference(version):
    sets = [record_outputs(range(4)), ["axis2.eventStatus", "io.output[1]", "host.interrupt", "nextCycle"],
            ["axis3.motorOutput"]]
    with pmdfmu.Chip(fmi_version=version, **{"record.capacity": 700}) as chip, \
            pmdfmu.Chip(fmi_version=version) as ref:
        busy_chip(chip)
        busy_chip(ref)
        for names in sets:
            rows = chip.run(1500, record=names)
            assert chip.get("record.columns") == ",".join(names)
            assert rows.tobytes() == ref._run_stepwise(1500, names).tobytes()


@VERSIONS
@pytest.mark.parametrize("value, why", [("axis1.nothing", "is not a variable"), ("script", "is not a number"),
                                        ("time", "is the independent variable"), ("chipTime,,axis1.position",
                                                                                   "is no name")])
def test_a_bad_column_is_refused_naming_the_value_and_changes_nothing(version, value, why):
    with pmdfmu.Chip(fmi_version=version) as chip:
        chip.set("record.columns", "axis1.position")
        with pytest.raises(FMICallException):
            chip.set("record.columns", value)
        errors = [m.message for m in chip.messages if m.status == "Error"]
        assert any(f"fmi{version}SetString: record.columns = \"{value}\"" in m and why in m for m in errors), errors
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


@VERSIONS
def test_the_bulk_path_is_taken_for_any_columns(version, monkeypatch):
    """The native loop is not called (record.data holds the rows) unless `time` is recorded."""
    calls = []
    monkeypatch.setattr(recording, "record", lambda *a: calls.append(a))
    with pmdfmu.Chip(fmi_version=version) as chip:
        busy_chip(chip)
        rows = chip.run(50, record=record_outputs([0, 2]))
        assert not calls and len(rows) == 50 and (np.diff(rows["cycle"].astype(int)) == 1).all()
