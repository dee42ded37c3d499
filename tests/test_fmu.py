# SPDX-License-Identifier: BSD-2-Clause
"""The FMU as a co-simulation tool sees it (CONTRACT 2)."""

import re
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

import pmdfmu
from pmdfmu import tables
from pmdfmu.profile import load_external_profile

FMU = pmdfmu.default_fmu()
TABLES = pmdfmu.tables_dir()


@pytest.mark.slow
def test_fmpy_validation_reports_nothing():
    assert validate_fmu(str(FMU)) == []


def test_the_fmu_holds_binary_description_sources_and_tables():
    names = zipfile.ZipFile(FMU).namelist()
    assert "modelDescription.xml" in names
    assert "binaries/linux64/PMDMotionProcessor.so" in names
    for f in (
        "sources/fmi2.c",
        "sources/profile.c",
        "sources/variables.c",
        "sources/fmi2Functions.h",
        "resources/commands.csv",
    ):
        assert f in names


def test_model_description_and_c_value_references_agree_with_the_table():
    everything = {v.name: v for v in tables.read_variables(TABLES / "variables.csv")}
    table = {n: v for n, v in everything.items() if v.type != "Binary"}  # Binary: FMI 3 only
    md = read_model_description(str(FMU))
    xml = {v.name: v for v in md.modelVariables}
    assert set(xml) == set(table)
    for name, v in table.items():
        x = xml[name]
        assert (x.valueReference, x.type, x.causality, x.variability) == (v.vr, v.type, v.causality, v.variability)
    source = zipfile.ZipFile(FMU).read("sources/variables.c").decode()
    c_rows = re.findall(r'\{(\d+), VAR_\w+, \d+, PMD_(\w+), PMD_(\w+), \d+, "([^"]+)"\}', source)
    assert {name: (int(vr), t.capitalize(), c.lower()) for vr, t, c, name in c_rows} == {
        n: (v.vr, v.type, v.causality) for n, v in everything.items()
    }
    guid = re.search(
        r'PMD_INSTANTIATION_TOKEN "([^"]+)"', zipfile.ZipFile(FMU).read("sources/variables.h").decode()
    ).group(1)
    assert guid == md.guid


def test_the_command_table_drives_the_dispatcher():
    source = zipfile.ZipFile(FMU).read("sources/command_table.c").decode()
    for c in tables.read_commands(TABLES / "commands.csv"):
        assert f'{{0x{c.opcode:02X}, "{c.name}", {int(c.scope == "chip")}, {c.arg_words}, {c.reply_words},' in source


def test_contract_variable_names():
    md = read_model_description(str(FMU))
    names = {v.name for v in md.modelVariables}
    for n in range(1, 5):
        for q in (
            "commandedPosition",
            "commandedVelocity",
            "commandedAcceleration",
            "position",
            "velocity",
            "acceleration",
            "activityStatus",
            "eventStatus",
            "actualPosition",
            "positiveLimit",
            "negativeLimit",
            "home",
        ):
            assert f"axis{n}.{q}" in names
    for i in range(1, 65):
        assert {f"host.word[{i}]", f"host.reply[{i}]", f"memory.data[{i}]"} <= names
    assert {
        "host.wordCount",
        "host.strobe",
        "host.ack",
        "host.replyCount",
        "host.error",
        "host.interrupt",
        "memory.address",
        "memory.count",
        "memory.strobe",
        "chipTime",
        "cycleTime",
        "memorySize",
        "loopback",
    } <= names


def test_outputs_after_initialization_are_the_reset_values(chip):
    assert chip.get("chipTime") == 0
    for n in range(1, 5):
        assert chip.get(f"axis{n}.commandedPosition") == 0
        assert chip.get(f"axis{n}.velocity") == 0.0
        assert chip.get(f"axis{n}.eventStatus") == 0
        # motor on, tracking; trapezoidal, at rest
        assert chip.get(f"axis{n}.activityStatus") == pmdfmu.PMDActivityMotorOnMask | pmdfmu.PMDActivityTrackingMask
    assert (chip.get("host.error"), chip.get("host.replyCount"), chip.get("host.interrupt")) == (0, 0, False)


@pytest.mark.parametrize(
    "cycle_time,h,steps", [(1e-3, 2.5e-4, 40), (1e-3, 2.5e-3, 8), (0.065, 0.065, 10), (1e-4, 3.3e-4, 30)]
)
def test_do_step_runs_exactly_the_cycles_in_t_to_t_plus_h(cycle_time, h, steps):
    with pmdfmu.Chip(cycleTime=cycle_time) as chip:
        ax = chip.axis(0)
        ax.SetVelocity(0x10000)
        ax.SetAcceleration(0x10000)
        ax.SetPosition(10**6)
        ax.Update()
        t = 0.0
        for _ in range(steps):
            chip.fmu.doStep(t, h)
            t += h  # accumulated like a master would
            cycles = int(np.ceil(round(t / cycle_time, 9)))
            assert chip.get("chipTime") == cycles - 1
            assert chip.get("axis1.commandedVelocity") == min(cycles, 1) * 0x10000


def test_real_outputs_are_in_counts_per_second(chip):
    ax = chip.axis(0)
    ax.SetVelocity(0x28000)  # 2.5 counts/cycle
    ax.SetAcceleration(0x8000)  # 0.5 counts/cycle^2
    ax.SetPosition(10**6)
    ax.Update()
    chip.run(3)
    assert chip.get("axis1.velocity") == pytest.approx(1.5 / 1e-4)
    assert chip.get("axis1.acceleration") == pytest.approx(0.5 / 1e-8)
    assert chip.get("axis1.position") == 0.5 + 1.0 + 1.5


def test_commands_before_run_take_effect_at_its_first_cycle(chip):
    ax = chip.axis(1)
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x10000)
    ax.SetPosition(100)
    ax.Update()
    rec = chip.run(3, record=["axis2.commandedPosition"])
    assert list(rec["cycle"]) == [0, 1, 2]
    assert list(rec["axis2.commandedPosition"]) == [1, 2, 3]


def profile(chip, axis, rows):
    load_external_profile(chip, {axis: rows})
    chip.axis(axis).SetProfileMode(pmdfmu.PMDExternalProfile)
    chip.axis(axis).Update()


def test_two_instances_in_one_process_run_as_each_does_alone():
    a_rows = [(0, 0x10000, 0x100, 0x1000, 50), (7, -0x20000, 0, 0, 30), (0, 0, 0, 0, 0)]
    b_rows = [(-90, 0x5000, -0x300, -0x4000, 20), (40, 0x1000, 0, 0x100000, 60), (1, 0, 0, 0, 0)]
    names = ["axis1.commandedPosition", "axis1.commandedVelocity", "axis1.commandedAcceleration", "axis1.position"]
    alone = []
    for rows in (a_rows, b_rows):
        with pmdfmu.Chip() as chip:
            profile(chip, 0, rows)
            alone.append(chip.run(120, record=names))
    with pmdfmu.Chip() as a, pmdfmu.Chip() as b:
        profile(a, 0, a_rows)
        profile(b, 0, b_rows)
        parts_a, parts_b = [], []
        for _ in range(12):
            parts_a.append(a.run(10, record=names))
            parts_b.append(b.run(10, record=names))
    assert np.array_equal(np.concatenate(parts_a), alone[0])
    assert np.array_equal(np.concatenate(parts_b), alone[1])


def test_logging_categories_are_honoured():
    with pmdfmu.Chip(log_categories=["buffers"]) as chip:
        chip.axis(0).SetBufferStart(2, 0x200)
        chip.axis(0).SetPosition(5)
        assert {m.category for m in chip.messages} == {"buffers"}
    with pmdfmu.Chip(log_categories=True) as chip:
        chip.axis(0).SetPosition(5)
        assert any(m.category == "commands" and "SetPosition" in m.message for m in chip.messages)
    with pmdfmu.Chip() as chip:
        chip.axis(0).SetPosition(5)
        assert chip.messages == []


def test_only_fmi_functions_are_exported(tmp_path):
    import shutil
    import subprocess

    if not shutil.which("nm"):
        pytest.skip("nm not installed")
    zipfile.ZipFile(FMU).extract("binaries/linux64/PMDMotionProcessor.so", tmp_path)
    out = subprocess.run(
        ["nm", "-D", "--defined-only", str(tmp_path / "binaries/linux64/PMDMotionProcessor.so")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    symbols = {line.split()[-1] for line in out.splitlines() if line.strip()}
    # and the two documented extensions (record.data, which FMI 2 has no type for, and the memory the caller
    # lends for its rows; docs/performance.md)
    extensions = {"pmdfmu_fmi2GetRecordData", "pmdfmu_fmi2SetRecordBuffer"}
    assert extensions <= symbols
    symbols -= extensions
    assert symbols and all(s.startswith("fmi2") for s in symbols)
    assert len(symbols) == 34  # every FMI 2.0 Co-Simulation function


def test_fmpy_simulate_fmu_drives_a_move_through_the_host_port():
    """A scripted run with FMPy's own master: one host batch at t = 0."""
    from fmpy import simulate_fmu

    ops = {n: pmdfmu.COMMANDS[n].opcode for n in ("SetPosition", "SetVelocity", "SetAcceleration", "Update")}
    words = [ops["SetPosition"], 0, 1000, ops["SetVelocity"], 2, 0, ops["SetAcceleration"], 0, 0x4000, ops["Update"]]
    names = [f"host.word[{i + 1}]" for i in range(len(words))] + ["host.wordCount", "host.strobe"]
    signals = np.array(
        [tuple([t] + words + [len(words), 1]) for t in (0.0, 0.1)],
        dtype=[("time", np.float64)] + [(n, np.int32) for n in names],
    )
    result = simulate_fmu(
        str(FMU),
        stop_time=0.1,
        step_size=1e-3,
        output_interval=1e-3,
        input=signals,
        output=["axis1.commandedPosition", "axis1.activityStatus", "host.ack"],
    )
    assert result["host.ack"][-1] == 1
    assert result["axis1.commandedPosition"][-1] == 1000
    assert not result["axis1.activityStatus"][-1] & pmdfmu.PMDActivityInMotionMask


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_every_real_has_a_unit_and_the_ranges_and_metadata_are_declared(fmi_version):
    """units.csv and types.csv through variables.csv: every Real a unit defined in UnitDefinitions,
    the parameters and bounded inputs their min/max, the metadata of LICENSE and the one version;
    FMPy's validation stays clean, and every name is one of FMI's structured convention."""
    path = pmdfmu.default_fmu(fmi_version)
    assert validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    units = {u.name for u in md.unitDefinitions}
    reals = [v for v in md.modelVariables if v.type in ("Real", "Float64")]
    assert reals and all(v.unit in units for v in reals), [v.name for v in reals if v.unit not in units]
    ranges = {v.name: (v.min, v.max) for v in md.modelVariables}
    assert ranges["cycleTime"] == ("1e-06", "0.065535")
    assert ranges["memorySize"] == ("1", "67108864")
    assert ranges["record.capacity"] == ("0", "16777216")
    assert ranges["host.wordCount"] == ("0", "64")
    if fmi_version == 2:  # FMPy reads no min or max of an FMI 3 array
        assert ranges["analog[1]"] == ("0", "65535")
    assert {v.name: v.declaredType.name for v in md.modelVariables if v.declaredType}["axis1.motorOutput"] == (
        "MotorOutput"
    )
    assert (md.author, md.license, md.version, md.generationTool) == (
        "pmdfmu authors",
        "BSD-2-Clause",
        pmdfmu.__version__,
        f"pmdfmu {pmdfmu.__version__}",
    )
    assert md.copyright and md.description


def test_the_names_are_structured_though_declared_flat():
    """FMPy's grammar of FMI 2's structured names accepts every name (docs/performance.md: declared
    flat, FMPy's validation would parse each one with an Earley parser)."""
    from fmpy.validation import _validate_variable_names

    md = read_model_description(str(pmdfmu.default_fmu(2)))
    assert md.variableNamingConvention == "flat"
    md.variableNamingConvention = "structured"
    assert _validate_variable_names(md) == []
