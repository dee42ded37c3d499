# SPDX-License-Identifier: BSD-2-Clause
"""FMI 3.0 Co-Simulation: the same core, names and timing as FMI 2."""

import shutil
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

import pmdfmu
from scenarios import BUSY_OUTPUTS, busy_chip

FMU3 = pmdfmu.default_fmu(3)


@pytest.mark.slow
def test_fmpy_validation_reports_nothing():
    assert validate_fmu(str(FMU3)) == []


def test_native_types_arrays_and_the_fixed_internal_step():
    md = read_model_description(str(FMU3))
    v = {x.name: x for x in md.modelVariables}
    cs = ET.fromstring(zipfile.ZipFile(FMU3).read("modelDescription.xml")).find("CoSimulation").attrib
    assert float(cs["fixedInternalStepSize"]) == 1e-4
    assert cs["canGetAndSetFMUState"] == cs["canSerializeFMUState"] == "true" and cs["hasEventMode"] == "false"
    assert (v["host.word"].type, int(v["host.word"].dimensions[0].start)) == ("UInt16", 64)
    assert (v["memory.data"].type, v["host.reply"].type) == ("UInt32", "UInt16")
    assert v["axis3.activityStatus"].type == "UInt16" and v["chipTime"].type == "UInt32"
    assert v["axis1.commandedPosition"].type == "Int32" and v["axis1.velocity"].type == "Float64"
    assert v["time"].causality == "independent"
    md2 = read_model_description(str(pmdfmu.default_fmu(2)))
    names2 = {x.name: x.valueReference for x in md2.modelVariables}
    for name, x in v.items():  # same names and value references; arrays at element 1
        if x.type != "Binary":  # record.data exists in FMI 3 only
            assert names2.get(name, names2.get(name + "[1]")) == x.valueReference


def test_the_same_scenario_gives_identical_outputs_through_fmi2_and_fmi3():
    runs = []
    for version in (2, 3):
        with pmdfmu.Chip(fmi_version=version) as chip:
            busy_chip(chip)
            runs.append(chip.run(1500, record=BUSY_OUTPUTS))
    assert np.array_equal(runs[0], runs[1])


def test_fmu_state_round_trip_through_fmi3():
    with pmdfmu.Chip(fmi_version=3) as chip:
        busy_chip(chip)
        chip.run(300)
        saved = chip.get_state()
        first = chip.run(600, record=BUSY_OUTPUTS)
        chip.set_state(saved)
        assert np.array_equal(chip.run(600, record=BUSY_OUTPUTS), first)
        with pytest.raises(FMICallException):
            chip.fmu.deserializeFMUState(saved[:-3])  # get_state is the FMU's own bytes
        assert any("refused" in m.message for m in chip.messages)


def test_bad_fmi3_calls_are_errors_with_messages():
    with pmdfmu.Chip(fmi_version=3) as chip:
        vr = chip.variables["axis1.activityStatus"].valueReference
        with pytest.raises(FMICallException):
            chip.fmu.getInt32([vr])  # it is a UInt16
        with pytest.raises(FMICallException):
            chip.fmu.getUInt16([chip.variables["host.reply"].valueReference], nValues=3)
        with pytest.raises(FMICallException):
            chip.fmu.getInt8([vr])
        with pytest.raises(FMICallException):
            chip.fmu.setUInt16([vr], [1])  # an output
        with pytest.raises(FMICallException):
            chip.fmu.doStep(0.0, -1.0)
        text = " ".join(m.message for m in chip.messages)
        for expected in (
            "is a UInt16, not Int32",
            "nValues is 3 but the value references hold 64",
            "is a UInt16, not Int8",
            "is an output",
            "fmi3DoStep",
        ):
            assert expected in text
        chip.run(2)
        assert chip.get("chipTime") == 1


def test_event_mode_and_model_exchange_are_refused():
    md = read_model_description(str(FMU3))
    d = extract(str(FMU3))
    fmu = FMU3Slave(guid=md.guid, unzipDirectory=d, modelIdentifier="PMDMotionProcessor", instanceName="x")
    with pytest.raises(Exception, match="Failed to instantiate"):  # FMPy's own Exception for a NULL instance
        fmu.instantiate(eventModeUsed=True)
    fmu = FMU3Slave(guid="{0}", unzipDirectory=d, modelIdentifier="PMDMotionProcessor", instanceName="x")
    with pytest.raises(Exception, match="Failed to instantiate"):
        fmu.instantiate()
    shutil.rmtree(d, ignore_errors=True)


def test_every_fmi3_function_is_exported_and_nothing_else(tmp_path):
    if not shutil.which("nm"):
        pytest.skip("nm not installed")
    zipfile.ZipFile(FMU3).extract("binaries/x86_64-linux/PMDMotionProcessor.so", tmp_path)
    out = subprocess.run(
        ["nm", "-D", "--defined-only", str(tmp_path / "binaries/x86_64-linux/PMDMotionProcessor.so")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    symbols = {line.split()[-1] for line in out.splitlines() if line.strip()}
    header = (pmdfmu.chip.Path(__import__("fmpy").__file__).parent / "c-code" / "fmi3Functions.h").read_text()
    declared = set(__import__("re").findall(r"FMI3_Export fmi3\w+TYPE\s+(fmi3\w+);", header))
    # and the documented extension: the memory the caller lends for its rows (docs/performance.md)
    assert declared and symbols == declared | {"pmdfmu_fmi3SetRecordBuffer"}
