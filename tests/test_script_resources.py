# SPDX-License-Identifier: BSD-2-Clause
"""Profiles that travel with the FMU (docs/scripts.md).

The `script` parameter: a value holding a line feed is the script's text; a
relative path is looked for in the FMU's resources folder (FMI 2's
fmuResourceLocation, a file URI; FMI 3's resourcePath), then the working
directory; an absolute one is taken as it is. A segment table a script file
loads is looked for in the script's folder, then the resources folder; one a
script given as text loads, in the resources folder, then the working
directory. A file not found names each place it was looked for. `pmdfmu pack`
writes a copy of the FMU with the script and its tables inside and `script`
starting at it. Most tests here run the FMU below the harness, as a tool does:
FMPy's simulate_fmu, or FMPy's classes with the resource location a tool gives."""

import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile
from ctypes import byref
from pathlib import Path

import fmpy
import numpy as np
import pytest
from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, fmi2CoSimulation
from fmpy.fmi3 import (
    FMU3Slave,
    fmi3Boolean,
    fmi3InstanceEnvironment,
    fmi3IntermediateUpdateCallback,
    fmi3LogMessageCallback,
    fmi3ValueReference,
)

import pmdfmu
from pmdfmu.cli import main
from pmdfmu.documentation import documentation_html
from pmdfmu.pack import PackError, pack, set_script_start

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SCRIPT = EXAMPLES / "two_axis.script"
TABLE = EXAMPLES / "two_axis_table.csv"
VERSIONS = pytest.mark.parametrize("version", [2, 3])
OUTPUTS = [
    "axis1.commandedPosition",
    "axis2.commandedPosition",
    "axis1.commandedVelocity",
    "axis2.commandedVelocity",
    "axis1.commandedAcceleration",
]


def move(position: int) -> str:
    """A script moving axis 2 to position with a trapezoidal profile."""
    return (
        "@ 0\nSetProfileMode(Axis2, PMDTrapezoidalProfile)\n"
        f"SetPosition(Axis2, {position})\nSetVelocity(Axis2, 4.0)\nSetAcceleration(Axis2, 0.0625)\n"
        "SetDeceleration(Axis2, 0.0625)\nUpdate(Axis2)\n"
    )


def simulate(fmu, start_values=None, stop_time=0.4):
    """FMPy's simulate_fmu as a tool runs an FMU: no parameter but those given."""
    return fmpy.simulate_fmu(
        str(fmu), start_values=start_values or {}, stop_time=stop_time, output_interval=1e-3, output=OUTPUTS
    )


def final(result, name="axis2.commandedPosition"):
    return int(result[name][-1])


def with_resources(fmu: Path, out: Path, files: dict) -> Path:
    """A copy of fmu with files (name under resources/ -> bytes or str) added, replaced or (None) removed."""
    with zipfile.ZipFile(fmu) as zin, zipfile.ZipFile(out, "w") as zout:
        for info in zin.infolist():
            if info.filename.removeprefix("resources/") not in files:
                zout.writestr(info, zin.read(info))
        for name, data in files.items():
            if data is not None:
                zout.writestr(f"resources/{name}", data.encode() if isinstance(data, str) else data)
    return out


DEFAULT = object()  # the resource location FMPy gives


class Raw:
    """An instance made below the Chip API, as a tool makes it: resource location as given
    (FMI 2: a URI string; FMI 3: a path or None), every log category on, messages kept."""

    def __init__(self, fmu, version, location=DEFAULT, unzipdir=None, guid=None):
        self.version = version
        self.md = fmpy.read_model_description(str(fmu))
        self.guid = guid or self.md.guid
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.unzipdir = fmpy.extract(str(fmu), unzipdir=str(unzipdir) if unzipdir else None)
        self.messages = []
        kwargs = dict(
            guid=self.md.guid,
            unzipDirectory=self.unzipdir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName="raw",
        )
        resources = Path(self.unzipdir, "resources")
        if version == 2:
            self.fmu = FMU2Slave(**kwargs)
            self.callbacks = fmi2CallbackFunctions()
            self.callbacks.logger = fmi2CallbackLoggerTYPE(
                lambda env, name, status, category, message: self.messages.append(message.decode().replace("%%", "%"))
            )
            uri = resources.as_uri() if location is DEFAULT else location
            self.fmu.component = self.fmu.fmi2Instantiate(
                b"raw",
                fmi2CoSimulation,
                self.guid.encode(),
                uri.encode() if uri is not None else None,
                byref(self.callbacks),
                0,
                1,
            )
        else:
            self.fmu = FMU3Slave(**kwargs)
            self.log = fmi3LogMessageCallback(
                lambda env, status, category, message: self.messages.append(message.decode())
            )
            self.update = fmi3IntermediateUpdateCallback()
            path = str(resources) + os.sep if location is DEFAULT else location
            self.fmu.component = self.fmu.fmi3InstantiateCoSimulation(
                b"raw",
                self.guid.encode(),
                path.encode() if path is not None else None,
                fmi3Boolean(False),
                fmi3Boolean(True),
                fmi3Boolean(False),
                fmi3Boolean(False),
                (fmi3ValueReference * 0)(),
                0,
                fmi3InstanceEnvironment(),
                self.log,
                self.update,
            )
        self.instantiated = bool(self.fmu.component)

    def initialize(self, script=None) -> bool:
        """Sets script (None: leaves its start value) and initializes; whether the FMU accepted."""
        try:
            if self.version == 2:
                self.fmu.setupExperiment(startTime=0.0)
            if script is not None:
                self.fmu.setString([self.vr["script"]], [script])
            self.fmu.enterInitializationMode()
            self.fmu.exitInitializationMode()
            return True
        except Exception:
            return False

    def script(self) -> str:
        value = self.fmu.getString([self.vr["script"]])[0]
        return value.decode() if isinstance(value, bytes) else value

    def errors(self) -> str:
        return "\n".join(self.messages)

    def state(self) -> bytes:
        state = self.fmu.getFMUState()
        try:
            return bytes(self.fmu.serializeFMUState(state))
        finally:
            self.fmu.freeFMUState(state)

    def close(self):
        if self.instantiated:
            self.fmu.fmi2FreeInstance(self.fmu.component) if self.version == 2 else self.fmu.fmi3FreeInstance(
                self.fmu.component
            )
        self.fmu.freeLibrary()
        shutil.rmtree(self.unzipdir, ignore_errors=True)


def refusal(fmu, version, script, **kwargs) -> str:
    raw = Raw(fmu, version, **kwargs)
    try:
        assert not raw.initialize(script), "the script was accepted"
        return raw.errors()
    finally:
        raw.close()


def tables_read(fmu, version, script=None, **kwargs):
    """(script read from, [tables read]) as the FMU logs them at the end of initialization."""
    raw = Raw(fmu, version, **kwargs)
    try:
        assert raw.initialize(script), raw.errors()
        said = raw.messages
        source = [m.split("script read from ", 1)[1] for m in said if "script read from " in m]
        return source, [m.split(" read from ", 1)[1] for m in said if "segment table" in m]
    finally:
        raw.close()


@pytest.fixture
def built():
    return {v: pmdfmu.default_fmu(v) for v in (2, 3)}


@pytest.fixture
def by_path():
    """The example script run by its absolute path: what every other way must equal."""
    return simulate(pmdfmu.default_fmu(2), {"script": str(SCRIPT)})


# ---- the script parameter: where a path is looked for ----


@VERSIONS
def test_a_relative_path_is_looked_for_in_the_resources_folder_first(tmp_path, monkeypatch, built, version):
    fmu = with_resources(built[version], tmp_path / "r.fmu", {"p/s.script": move(5000)})
    (tmp_path / "cwd" / "p").mkdir(parents=True)
    (tmp_path / "cwd" / "p" / "s.script").write_text(move(3000))
    monkeypatch.chdir(tmp_path / "cwd")
    assert final(simulate(fmu, {"script": "p/s.script"})) == 5000
    assert final(simulate(fmu, {"script": "./p/s.script"})) == 5000
    source, _ = tables_read(fmu, version, "p/s.script")
    assert source[0].endswith("/resources/p/s.script") and not source[0].startswith(str(tmp_path / "cwd"))


@VERSIONS
def test_a_relative_path_the_fmu_does_not_hold_is_taken_from_the_working_directory(
    tmp_path, monkeypatch, built, version, by_path
):
    (tmp_path / "sub").mkdir()
    shutil.copy(SCRIPT, tmp_path / "sub")
    shutil.copy(TABLE, tmp_path / "sub")
    monkeypatch.chdir(tmp_path)
    result = simulate(built[version], {"script": "sub/two_axis.script"})
    assert np.array_equal(result, by_path)
    assert tables_read(built[version], version, "sub/two_axis.script") == (
        ["sub/two_axis.script"],
        ["sub/two_axis_table.csv"],
    )


@VERSIONS
def test_without_a_resources_folder_a_relative_path_is_taken_from_the_working_directory(
    tmp_path, monkeypatch, built, version
):
    (tmp_path / "s.script").write_text(move(1234))
    monkeypatch.chdir(tmp_path)
    location = None if version == 3 else ""
    raw = Raw(built[version], version, location=location)
    try:
        assert raw.initialize("s.script"), raw.errors()
    finally:
        raw.close()


@VERSIONS
def test_an_absolute_path_is_taken_as_it_is(tmp_path, built, version):
    (tmp_path / "s.script").write_text(move(2222))
    fmu = with_resources(built[version], tmp_path / "r.fmu", {str(tmp_path / "s.script").lstrip("/"): move(1111)})
    assert final(simulate(fmu, {"script": str(tmp_path / "s.script")})) == 2222
    missing = tmp_path / "none.script"
    said = refusal(built[version], version, str(missing))
    assert f"{missing}: cannot open the script: No such file or directory" in said and "not found in" not in said


# ---- tables ----

TABLE_B = "position,time\n3,0\n"


@VERSIONS
def test_a_table_is_looked_for_in_the_scripts_folder_then_the_resources_folder(tmp_path, built, version):
    fmu = with_resources(built[version], tmp_path / "r.fmu", {"t.csv": TABLE.read_text()})
    folder = tmp_path / "scripts"
    folder.mkdir()
    script = folder / "s.script"
    script.write_text('LoadSegmentTable(Axis1, "t.csv", 0x200, 2)\n')
    _, tables = tables_read(fmu, version, str(script))
    assert len(tables) == 1 and tables[0].endswith("/resources/t.csv")
    (folder / "t.csv").write_text(TABLE_B)
    assert tables_read(fmu, version, str(script))[1] == [str(folder / "t.csv")]


@VERSIONS
def test_a_script_in_the_fmu_loads_its_tables_from_its_own_folder_in_the_fmu(
    tmp_path, monkeypatch, built, version, by_path
):
    fmu = with_resources(
        built[version],
        tmp_path / "r.fmu",
        {
            "a/b/s.script": SCRIPT.read_text().replace('"two_axis_table.csv"', '"../t/table.csv"'),
            "a/t/table.csv": TABLE.read_text(),
        },
    )
    monkeypatch.chdir(tmp_path)
    assert np.array_equal(simulate(fmu, {"script": "a/b/s.script"}), by_path)


@VERSIONS
def test_a_table_found_nowhere_is_refused_naming_each_place_looked_in(tmp_path, built, version):
    script = tmp_path / "s.script"
    script.write_text('# the table\nLoadSegmentTable(Axis1, "sub/none.csv", 0x200, 2)\n')
    raw = Raw(built[version], version)
    try:
        assert not raw.initialize(str(script))
        resources = Path(raw.unzipdir, "resources")
        assert (
            f"ExitInitializationMode: script refused: {script}:2: cannot open segment table sub/none.csv: "
            f"not found in the script's folder ({tmp_path}/sub/none.csv: No such file or directory) nor in the "
            f"FMU's resources folder ({resources}/sub/none.csv: No such file or directory)"
        ) in raw.errors()
    finally:
        raw.close()


@VERSIONS
def test_an_absolute_table_path_is_taken_as_it_is(tmp_path, built, version):
    (tmp_path / "t.csv").write_text(TABLE_B)
    script = tmp_path / "s.script"
    script.write_text(f'LoadSegmentTable(Axis1, "{tmp_path / "t.csv"}", 0x200, 2)\n')
    assert tables_read(built[version], version, str(script))[1] == [str(tmp_path / "t.csv")]


# ---- the script's text as the value ----


@VERSIONS
def test_a_value_holding_a_line_feed_is_the_scripts_text(tmp_path, monkeypatch, built, version, by_path):
    monkeypatch.chdir(EXAMPLES)  # its table: from the working directory
    text = SCRIPT.read_text()
    assert np.array_equal(simulate(built[version], {"script": text}), by_path)
    assert np.array_equal(simulate(built[version], {"script": text.replace("\n", "\r\n")}), by_path)
    assert tables_read(built[version], version, text) == ([], ["two_axis_table.csv"])


@VERSIONS
def test_a_text_scripts_tables_come_from_the_resources_folder_first(tmp_path, monkeypatch, built, version, by_path):
    fmu = with_resources(built[version], tmp_path / "r.fmu", {"two_axis_table.csv": TABLE.read_text()})
    (tmp_path / "two_axis_table.csv").write_text(TABLE_B)  # not this one
    monkeypatch.chdir(tmp_path)
    assert np.array_equal(simulate(fmu, {"script": SCRIPT.read_text()}), by_path)
    assert tables_read(fmu, version, SCRIPT.read_text())[1][0].endswith("/resources/two_axis_table.csv")


@VERSIONS
def test_a_one_line_script_is_its_line_and_a_line_feed(built, version):
    for text in ("SetSampleTime(Axis1, 250)\n", "SetSampleTime(Axis1, 250);\r\n", "\nSetSampleTime(Axis1, 250)"):
        result = fmpy.simulate_fmu(
            str(built[version]),
            start_values={"script": text},
            stop_time=0.01,
            output_interval=1e-3,
            output=["activeCycleTime"],
        )
        assert result["activeCycleTime"][-1] == 250e-6, repr(text)
    # without one, the same words are a path
    said = refusal(built[version], version, "SetSampleTime(Axis1, 250)")
    assert (
        "script refused: SetSampleTime(Axis1, 250): cannot open the script: not found in the FMU's resources "
        "folder" in said
    )


@VERSIONS
def test_a_bad_text_script_is_refused_with_line_and_reason(built, version):
    said = refusal(built[version], version, "@ 0\nFrobnicate(Axis1, 3)\n")
    assert "ExitInitializationMode: script refused: (script text):2: 'Frobnicate' is not a command" in said
    raw = Raw(built[version], version)  # what the chip refuses while it runs: a warning, with the line
    try:
        assert raw.initialize("@0\nSetBufferReadIndex(Axis1, 2, 5)\n"), raw.errors()
        raw.fmu.doStep(0.0, 1e-4)
        assert "(script text):2: the chip refused the command: host I/O error 0x07" in raw.messages
    finally:
        raw.close()
    said = refusal(built[version], version, 'LoadSegmentTable(Axis1, "none.csv", 0x200, 2)\n')
    assert "(script text):1: cannot open segment table none.csv: not found in the FMU's resources folder (" in said
    assert (
        f"none.csv: No such file or directory) nor in the working directory ({os.getcwd()}/none.csv: No such "
        "file or directory)" in said
    )


@VERSIONS
def test_text_and_file_compile_to_the_same_script(tmp_path, monkeypatch, built, version):
    """The same lines as text or as a file: the same FMU state, so a snapshot restores across them."""
    monkeypatch.chdir(EXAMPLES)
    states = []
    for value in (str(SCRIPT), SCRIPT.read_text()):
        raw = Raw(built[version], version)
        try:
            assert raw.initialize(value), raw.errors()
            states.append(raw.state())
        finally:
            raw.close()
    assert states[0] == states[1]


def test_the_harness_passes_text_and_paths_inside_the_fmu(tmp_path, monkeypatch, by_path):
    monkeypatch.chdir(EXAMPLES)
    with pmdfmu.Chip(script=SCRIPT.read_text()) as chip:
        assert chip.get("script") == SCRIPT.read_text()
    fmu = with_resources(pmdfmu.default_fmu(2), tmp_path / "r.fmu", {"p/s.script": move(77)})
    with pmdfmu.Chip(fmu=fmu, script="p/s.script") as chip:
        chip.run(3000)
        assert chip.axis(1).GetCommandedPosition() == 77


# ---- the resource location an importer gives ----


@pytest.mark.parametrize("form", ["file:///{}", "file://localhost/{}", "file:/{}", "file:///{}/", "FILE:///{}"])
def test_fmi2_resource_locations_are_file_uris_decoded(tmp_path, built, form):
    folder = tmp_path / "a folder 100%" / "ü"  # a blank, a percent sign and a non-ASCII letter
    fmu = with_resources(built[2], tmp_path / "r.fmu", {"s.script": move(10)})
    raw = Raw(fmu, 2, unzipdir=folder)
    raw.close()
    resources = folder / "resources"
    encoded = resources.as_uri()[len("file:///") :]  # percent-encoded by pathlib
    assert "%20" in encoded and "%25" in encoded and "%C3%BC" in encoded
    raw = Raw(fmu, 2, location=form.format(encoded), unzipdir=folder)
    try:
        assert raw.initialize("s.script"), raw.errors()
    finally:
        raw.close()


@pytest.mark.parametrize(
    "location, why",
    [
        ("", "the importer gave no fmuResourceLocation"),
        (None, "the importer gave no fmuResourceLocation"),
        ("http://example.com/resources", "fmuResourceLocation is not a file: URI"),
        ("file://elsewhere/tmp/resources", "fmuResourceLocation names another host"),
        ("file:///tmp/a%zzb/resources", "fmuResourceLocation has a bad percent-encoding"),
        ("file:///tmp/a%00b/resources", "fmuResourceLocation has a bad percent-encoding"),
        ("file:relative/resources", "fmuResourceLocation's path is not absolute"),
    ],
)
def test_an_fmi2_resource_location_that_is_no_local_folder_is_named_when_a_script_is_not_found(built, location, why):
    said = refusal(built[2], 2, "none.script", location=location)
    assert (
        f"none.script: cannot open the script: not found in the FMU's resources folder (none: {why}) nor in the "
        f"working directory ({os.getcwd()}/none.script: No such file or directory)" in said
    )


def test_fmi3_resource_paths_with_and_without_a_separator_or_null(tmp_path, built):
    fmu = with_resources(built[3], tmp_path / "r.fmu", {"s.script": move(10)})
    folder = tmp_path / "unzipped"
    for path, found in (
        (str(folder / "resources") + os.sep, True),
        (str(folder / "resources"), True),
        (None, False),
        ("", False),
    ):
        raw = Raw(fmu, 3, location=path, unzipdir=folder)
        try:
            assert raw.initialize("s.script") == found, raw.errors()
            if path is None:
                assert "the FMU's resources folder (none: the importer gave no resourcePath (NULL))" in raw.errors()
            elif not found:
                assert "the FMU's resources folder (none: the importer gave an empty resourcePath)" in raw.errors()
        finally:
            raw.close()


# ---- a start value inside the FMU (resources/script.start) ----


@VERSIONS
def test_the_start_value_a_packed_fmu_carries_is_the_value_until_set(tmp_path, built, version):
    fmu = with_resources(built[version], tmp_path / "r.fmu", {"p/s.script": move(4321), "script.start": "p/s.script"})
    raw = Raw(fmu, version)
    try:
        assert raw.initialize(), raw.errors()
        assert raw.script() == "p/s.script"
        raw.fmu.reset()  # a reset goes back to it
        assert raw.initialize(), raw.errors()
        assert raw.script() == "p/s.script"
        raw.fmu.reset()  # set empty: no script
        assert raw.initialize("") and raw.script() == ""
    finally:
        raw.close()
    assert final(simulate(fmu)) == 4321


@VERSIONS
def test_a_start_value_file_that_cannot_be_read_refuses_instantiation(tmp_path, built, version):
    fmu = with_resources(built[version], tmp_path / "r.fmu", {"script.start/x": "folder, not a file"})
    raw = Raw(fmu, version)
    try:
        assert not raw.instantiated
        assert (
            f"Instantiate{'' if version == 2 else 'CoSimulation'}: the script parameter's start value: "
            f"{raw.unzipdir}{os.sep}resources{os.sep}script.start: cannot open: not a regular file" in raw.errors()
        )
    finally:
        raw.close()


# ---- pmdfmu pack ----


@pytest.mark.slow
@VERSIONS
def test_a_packed_fmu_runs_its_profile_with_no_parameter_set_from_any_directory(
    tmp_path, monkeypatch, built, version, by_path
):
    packed = pack(SCRIPT, tmp_path / "my-profile.fmu", version)
    assert packed.start == "profile/two_axis.script"
    assert packed.files == [
        "resources/profile/two_axis.script",
        "resources/profile/two_axis_table.csv",
        "resources/script.start",
        "resources/instantiation.token",
    ]
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    result = simulate(packed.fmu)
    assert np.array_equal(result, by_path)
    assert np.array_equal(result, simulate(built[version], {"script": str(SCRIPT)}))
    with pmdfmu.Chip(version, packed.fmu) as chip:  # the harness too, with no script given
        assert chip.get("script") == "profile/two_axis.script"
        rec = pmdfmu.profile.run_script(chip)
    with pmdfmu.Chip(version, script=SCRIPT) as chip:
        assert np.array_equal(pmdfmu.profile.run_script(chip), rec)
    assert not fmpy.validation.validate_fmu(str(packed.fmu))


@VERSIONS
def test_pack_changes_only_the_start_value_and_the_identity_and_adds_the_profile(tmp_path, built, version):
    packed = pack(SCRIPT, tmp_path / "p.fmu", version)
    with zipfile.ZipFile(built[version]) as a, zipfile.ZipFile(packed.fmu) as b:
        old, new = {i.filename: a.read(i) for i in a.infolist()}, {i.filename: b.read(i) for i in b.infolist()}
    assert set(new) - set(old) == set(packed.files)
    for name in old:
        if name not in ("modelDescription.xml", "documentation/index.html"):
            assert new[name] == old[name], name
    assert new["documentation/index.html"].decode() == documentation_html(new["modelDescription.xml"].decode())
    empty, start = (
        ('<String start=""/>', '<String start="profile/two_axis.script"/>')
        if version == 2
        else ('<Start value=""/>', '<Start value="profile/two_axis.script"/>')
    )
    xml = old["modelDescription.xml"].decode()
    # the first empty String start is the script's (record.columns, an input, has one too)
    script = xml.index('name="script"')
    assert script < xml.index(empty) < xml.index("</ScalarVariable>" if version == 2 else "</String>", script)
    md_old, md_new = (fmpy.read_model_description(str(f)) for f in (built[version], packed.fmu))
    token = "guid" if version == 2 else "instantiationToken"
    expected = (
        xml.replace(empty, start, 1)
        .replace(f'{token}="{md_old.guid}"', f'{token}="{packed.token}"', 1)
        .replace('modelName="PMDMotionProcessor"', 'modelName="PMDMotionProcessor.two_axis"', 1)
        .replace(
            f'description="{md_old.description}"',
            f'description="{md_old.description}; runs the profile two_axis, packed in resources/profile/two_axis.script"',
            1,
        )
    )
    assert new["modelDescription.xml"].decode() == expected
    assert new["resources/script.start"] == b"profile/two_axis.script"
    assert new["resources/instantiation.token"] == packed.token.encode()
    assert new["resources/profile/two_axis.script"] == SCRIPT.read_bytes()
    assert new["resources/profile/two_axis_table.csv"] == TABLE.read_bytes()
    # a model of its own over the same variables: the binary's token, '+' and a fingerprint
    assert md_new.guid == packed.token and packed.token.startswith(md_old.guid + "+{")
    assert md_new.modelName == packed.model_name == "PMDMotionProcessor.two_axis"
    assert md_new.coSimulation.modelIdentifier == md_old.coSimulation.modelIdentifier
    raw = Raw(packed.fmu, version)
    try:
        assert raw.instantiated and raw.initialize() and raw.script() == "profile/two_axis.script"
    finally:
        raw.close()


@VERSIONS
def test_pack_keeps_the_relative_layout_of_the_tables(tmp_path, monkeypatch, version, by_path):
    (tmp_path / "profiles" / "x").mkdir(parents=True)
    (tmp_path / "profiles" / "tables").mkdir()
    shutil.copy(TABLE, tmp_path / "profiles" / "tables" / "t.csv")
    text = SCRIPT.read_text().replace('"two_axis_table.csv"', '"../tables/t.csv"')
    text += 'LoadSegmentTable(Axis3, "../tables/t.csv", 0x1000, 10)\n'  # the same table twice
    (tmp_path / "profiles" / "x" / "s.script").write_text(text)
    monkeypatch.chdir(tmp_path / "profiles" / "x")
    assert main(["pack", "s.script", "--out", str(tmp_path / "p.fmu"), "--fmi", str(version)]) == 0
    packed = zipfile.ZipFile(tmp_path / "p.fmu")
    assert {"resources/profile/x/s.script", "resources/profile/tables/t.csv"} <= set(packed.namelist())
    assert packed.read("resources/script.start") == b"profile/x/s.script"
    monkeypatch.chdir(tmp_path)
    result = simulate(tmp_path / "p.fmu")
    assert np.array_equal(result[OUTPUTS[:2]], by_path[OUTPUTS[:2]])


def test_pack_refuses_what_would_not_travel(tmp_path, capsys):
    (tmp_path / "t.csv").write_text(TABLE.read_text())
    script = tmp_path / "s.script"
    script.write_text(f'LoadSegmentTable(Axis1, "{tmp_path / "t.csv"}", 0x200, 2)\n')
    with pytest.raises(PackError, match=r"s.script:1: the table .*t.csv is named by an absolute path"):
        pack(script, tmp_path / "p.fmu")
    script.write_text("Frobnicate(Axis1)\n")
    with pytest.raises(PackError, match="the FMU refuses the script: .*'Frobnicate' is not a command"):
        pack(script, tmp_path / "p.fmu")
    assert main(["pack", str(script), "--out", str(tmp_path / "p.fmu")]) == 2
    assert "pmdfmu pack: " in capsys.readouterr().err
    packed = pack(SCRIPT, tmp_path / "p.fmu")
    with pytest.raises(PackError, match="is a packed FMU already"):
        pack(SCRIPT, tmp_path / "q.fmu", fmu=packed.fmu)
    with pytest.raises(PackError, match="must not overwrite"):
        pack(SCRIPT, packed.fmu, fmu=packed.fmu)
    assert not list(tmp_path.glob("*.partial"))


# ---- a packed FMU's identity (fmu_src/fmi_common/token.h) ----


@VERSIONS
def test_two_packed_profiles_are_two_models_that_run_side_by_side(tmp_path, built, version):
    (tmp_path / "move.script").write_text(move(4321))
    first = pack(SCRIPT, tmp_path / "a.fmu", version)
    second = pack(tmp_path / "move.script", tmp_path / "b.fmu", version)
    models = [fmpy.read_model_description(str(p.fmu)) for p in (first, second)]
    assert [m.modelName for m in models] == ["PMDMotionProcessor.two_axis", "PMDMotionProcessor.move"]
    assert models[0].guid != models[1].guid
    assert all(
        m.description.endswith(f"runs the profile {n}, packed in resources/profile/{n}.script")
        for m, n in zip(models, ("two_axis", "move"))
    )
    assert {m.coSimulation.modelIdentifier for m in models} == {"PMDMotionProcessor"}
    raws = [Raw(p.fmu, version) for p in (first, second)]  # both instantiated in one process at once
    try:
        assert all(r.instantiated and r.initialize() for r in raws), [r.errors() for r in raws]
        assert [r.script() for r in raws] == ["profile/two_axis.script", "profile/move.script"]
    finally:
        for r in raws:
            r.close()
    assert final(simulate(second.fmu)) == 4321
    for p in (first, second):
        assert not fmpy.validation.validate_fmu(str(p.fmu))
    assert pack(SCRIPT, tmp_path / "c.fmu", version, name="circle").model_name == "PMDMotionProcessor.circle"
    with pytest.raises(PackError, match="a profile's name is letters, digits and '_'"):
        pack(SCRIPT, tmp_path / "d.fmu", version, name="two axis")


@VERSIONS
def test_the_same_inputs_give_the_same_packed_fmu(tmp_path, version):
    first = pack(SCRIPT, tmp_path / "a.fmu", version)
    second = pack(SCRIPT, tmp_path / "b.fmu", version)
    assert first.token == second.token
    assert first.fmu.read_bytes() == second.fmu.read_bytes()
    copy = tmp_path / "copy"  # one byte more in a table: another model
    shutil.copytree(EXAMPLES, copy, ignore=lambda d, names: [n for n in names if not n.startswith("two_axis")])
    (copy / "two_axis_table.csv").write_text(TABLE.read_text() + "\n")
    assert pack(copy / "two_axis.script", tmp_path / "c.fmu", version).token != first.token


def instantiation_refused(fmu, version, **kwargs) -> str:
    raw = Raw(fmu, version, **kwargs)
    try:
        assert not raw.instantiated, "instantiated"
        return raw.errors()
    finally:
        raw.close()


@VERSIONS
def test_a_packed_fmu_accepts_its_token_and_the_binarys_and_no_other(tmp_path, built, version):
    packed = pack(SCRIPT, tmp_path / "p.fmu", version)
    own = fmpy.read_model_description(str(built[version])).guid
    fn, what = ("fmi2Instantiate", "GUID") if version == 2 else ("fmi3InstantiateCoSimulation", "instantiation token")
    for guid in (packed.token, own):  # the base FMU's model description describes the same variables
        raw = Raw(packed.fmu, version, guid=guid)
        try:
            assert raw.instantiated and raw.initialize(), raw.errors()
        finally:
            raw.close()
    other = own + "+{00000000-0000-0000-0000-000000000000}"  # another packed FMU's model description
    said = instantiation_refused(packed.fmu, version, guid=other)
    assert f"{fn}: the {what} {other} matches neither this binary's {own} nor this packed FMU's {packed.token}" in said
    # the file gone, the packed token is refused, as it is without a resources folder to read it from
    gone = with_resources(packed.fmu, tmp_path / "gone.fmu", {"instantiation.token": None})
    assert f"{fn}: the {what} {packed.token} does not match this binary's {own}" in instantiation_refused(gone, version)
    said = instantiation_refused(packed.fmu, version, location=None)
    assert f"does not match this binary's {own} (nor can a packed FMU's be read: the importer gave no" in said
    # an editor's line end after the token is no part of it
    edited = with_resources(packed.fmu, tmp_path / "lf.fmu", {"instantiation.token": packed.token + "\r\n"})
    raw = Raw(edited, version)
    try:
        assert raw.instantiated, raw.errors()
    finally:
        raw.close()


@VERSIONS
def test_a_token_file_of_another_binary_refuses_every_token(tmp_path, built, version):
    """A packed FMU whose binary was swapped for another build's, or whose token file names another
    binary's token: the file cannot make the binary take a model description of other variables, and
    it is never ignored, not even for the binary's own token."""
    own = fmpy.read_model_description(str(built[version])).guid
    plant = fmpy.read_model_description(str(built[version].with_name(f"pmdplant-fmi{version}.fmu"))).guid
    packed = pack(SCRIPT, tmp_path / "p.fmu", version)
    for i, forged in enumerate(
        [plant + "+{1}", plant, own, own + "+", own + "+{x}\n+", own + "+" + "0" * 65, "", own + "+{\x00}", "%s%n"]
    ):
        fmu = with_resources(packed.fmu, tmp_path / f"f{i}.fmu", {"instantiation.token": forged})
        for guid in {forged.strip() or own, own, packed.token}:
            said = instantiation_refused(fmu, version, guid=guid)
            assert (
                f"instantiation.token holds no packed {'GUID' if version == 2 else 'instantiation token'} of "
                f"this binary (one begins with its {own} and '+'): the FMU was packed onto another binary" in said
            )
    folder = with_resources(packed.fmu, tmp_path / "d.fmu", {"instantiation.token": None, "instantiation.token/x": ""})
    assert "instantiation.token: not a regular file" in instantiation_refused(folder, version)


@VERSIONS
def test_a_start_value_holding_text_survives_the_xml(built, version):
    """The start value an SSP or a tool could carry: line feeds, quotes and markup as references."""
    text = 'SetSampleTime(Axis1, 250)\n# "quoted" & <marked>\tup\r\n'
    with zipfile.ZipFile(built[version]) as z:
        xml = z.read("modelDescription.xml")
    edited = set_script_start(xml, text)
    assert "&#10;" in edited.decode() and "&quot;" in edited.decode()
    root = ET.fromstring(edited)
    starts = [e.get("start", e.get("value")) for v in root.iter() if v.get("name") == "script" for e in v]
    assert starts == [text]
    assert set_script_start(edited, "") == xml


def test_the_docs_pack_example_runs_as_written(tmp_path):
    text = (REPO / "docs" / "scripts.md").read_text()
    section = text[text.index("**A profile inside the FMU: `pmdfmu pack`.**") :]
    block = re.search(r"```sh\n(.*?)```", section, re.S).group(1)
    commands = [line for line in block.splitlines() if line and not line.startswith("#")]
    expected = [line[len("# -> ") :] for line in block.splitlines() if line.startswith("# -> ")]
    assert commands[0].startswith("pmdfmu pack examples/") and expected
    for example in ("two_axis.script", "two_axis_table.csv"):  # the repository's examples, from elsewhere
        (tmp_path / "examples").mkdir(exist_ok=True)
        shutil.copy(EXAMPLES / example, tmp_path / "examples")
    out = []
    for command in commands:
        if command.startswith("pmdfmu "):
            command = f"{sys.executable} -m pmdfmu.cli " + command[len("pmdfmu ") :]
        elif command.startswith("python "):
            command = sys.executable + command[len("python") :]
        out.append(subprocess.run(command, shell=True, cwd=tmp_path, capture_output=True, text=True, check=True).stdout)
    assert out[-1].splitlines() == expected
