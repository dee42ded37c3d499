# SPDX-License-Identifier: BSD-2-Clause
"""A second, independent importer: FMI4j (Java, from Maven Central) runs the
FMI 2.0 FMU with the example script; its CSV equals FMPy's, with the script as the
parameter or packed inside the FMU with no parameter set."""

import csv
import os
import shutil
import subprocess
from pathlib import Path

import pytest

import pmdfmu
from pmdfmu.pack import pack

pytestmark = [pytest.mark.slow, pytest.mark.tools]  # tests/README.md: ./dev test -m "not slow" leaves them out

ROOT = Path(__file__).resolve().parent.parent
PROJECT = ROOT / "importers" / "fmi4j"
SCRIPT = ROOT / "examples" / "two_axis.script"
NAMES = [
    f"axis{n}.{q}"
    for n in (1, 2)
    for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration", "activityStatus", "eventStatus")
]
CYCLES = 3200

needs_java = pytest.mark.skipif(
    not (shutil.which("java") and shutil.which("mvn")) and not os.environ.get("CI"),
    reason="java and mvn not installed (CI installs them)",
)


@pytest.fixture(scope="module")
def fmi4j_run():
    """importers/fmi4j built once for the module"""
    subprocess.run(
        ["mvn", "-q", "-B", "-f", str(PROJECT / "pom.xml"), "package", "-DskipTests"], check=True, timeout=900
    )


@needs_java
@pytest.mark.parametrize("packed", [False, True], ids=["parameter", "packed"])
def test_fmi4j_runs_the_scripted_profile_and_its_csv_equals_fmpys(tmp_path, packed, fmi4j_run):
    """The script as the `script` parameter, or packed into the FMU (`pmdfmu pack`,
    docs/scripts.md) with no parameter set: the same run."""
    fmu = pmdfmu.default_fmu(2)
    with pmdfmu.Chip(script=SCRIPT) as chip:
        vrs = {n: chip.variables[n].valueReference for n in NAMES}
        fmpy_rows = chip.run(CYCLES, record=NAMES)
    if packed:
        fmu = tmp_path / "two_axis.fmu"
        pack(SCRIPT, fmu)
    out = tmp_path / "fmi4j.csv"
    classpath = f"{PROJECT / 'target' / 'fmi4j-run-1.0.jar'}{os.pathsep}{PROJECT / 'target' / 'lib' / '*'}"
    subprocess.run(
        [
            "java",
            "-cp",
            classpath,
            "pmdfmu.Fmi4jRun",
            str(fmu),
            "-" if packed else str(SCRIPT),
            "1e-4",
            str(CYCLES),
            str(out),
        ]
        + [f"{n}={vrs[n]}" for n in NAMES],
        check=True,
        timeout=600,
    )
    rows = list(csv.reader(open(out)))
    assert rows[0] == ["cycle"] + NAMES
    fmi4j = [[int(x) for x in r] for r in rows[1:]]
    assert fmi4j == [[int(r["cycle"])] + [int(r[n]) for n in NAMES] for r in fmpy_rows]
    assert fmi4j[-1][1] == 750  # axis 1 finished its table


def fmi4j_booleans(fmu, vr, value, lengths):
    """importers/fmi4j's Fmi4jBoolean: [(array length, status, value read back)] of FMI4j's
    writeBoolean of `value` to one variable with value arrays of each length, in Initialization Mode."""
    classpath = f"{PROJECT / 'target' / 'fmi4j-run-1.0.jar'}{os.pathsep}{PROJECT / 'target' / 'lib' / '*'}"
    out = subprocess.run(
        ["java", "-cp", classpath, "pmdfmu.Fmi4jBoolean", str(fmu), str(vr), str(value).lower()]
        + [str(n) for n in lengths],
        capture_output=True,
        text=True,
        check=True,
        timeout=300,
    )
    rows = [line.split() for line in out.stdout.splitlines() if line[:1].isdigit()]
    assert [int(r[0]) for r in rows] == list(lengths) and {r[1] for r in rows} == {str(value).lower()}, out.stdout
    return [(int(r[0]), r[2], r[3] == "true") for r in rows]


@needs_java
@pytest.mark.parametrize("fmu", ["chip", "Feedthrough"])
def test_fmi4j_writes_false_as_true_with_a_one_element_array(fmu, fmi4j_run):
    """FMI4j 0.38.0's writeBoolean of false with a 1-element array (what a scalar write is) returns OK,
    and the variable reads back true, for the chip's `loopback` and for Reference-FMUs' FMI 2
    Feedthrough's `Boolean_input` (start false) alike: FMI4j's defect. The same with a 4-element array
    (the same variable four times) reads back false: the workaround docs/tools.md gives. Reading is
    right: with no write, Feedthrough reads false. This test fails when FMI4j writes false right."""
    if fmu == "chip":
        import fmpy

        path = pmdfmu.default_fmu(2)
        vr = next(
            v.valueReference for v in fmpy.read_model_description(str(path)).modelVariables if v.name == "loopback"
        )
    else:
        from reference_fmus import reference_fmu

        path = reference_fmu("Feedthrough", 2)
        vr = 27  # Boolean_input
    lengths = [0, 1, 1, 1, 4, 4] if fmu == "Feedthrough" else [1, 1, 1, 4, 4]
    runs = fmi4j_booleans(path, vr, False, lengths)
    assert {status for _, status, _ in runs} == {"OK"}
    if fmu == "Feedthrough":
        assert runs[0] == (0, "OK", False)  # its start value, read right
    assert any(read for n, _, read in runs if n == 1), runs  # false written, true read: at least once
    assert not any(read for n, _, read in runs if n == 4), runs
