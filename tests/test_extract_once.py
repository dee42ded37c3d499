# SPDX-License-Identifier: BSD-2-Clause
"""An FMU file is extracted once per process: every Chip of the
file shares its folder, model description and FMI prototypes; a rewritten file is
extracted anew; instances of the shared folder give exactly what an instance of a
fresh extract gives; closing one leaves the others working; the folder goes when
the interpreter exits."""

import os
import shutil
import subprocess
import sys
import threading
import zipfile
from pathlib import Path

import numpy as np
import pytest

import pmdfmu

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCRIPT = EXAMPLES / "two_axis.script"
COLUMNS = [
    "axis1.commandedPosition",
    "axis2.commandedVelocity",
    "axis1.position",
    "axis2.velocity",
    "axis1.activityStatus",
    "axis2.eventStatus",
    "host.interrupt",
]
CYCLES = 3200  # past the script's last command (cycle 3000)


def folders(root: Path):
    return sorted(p.name for p in root.iterdir())


def copy_of(fmi_version: int, where: Path) -> Path:
    """The built FMU under another path: another file, extracted on its own."""
    where.mkdir(parents=True, exist_ok=True)
    return Path(shutil.copy(pmdfmu.default_fmu(fmi_version), where / pmdfmu.default_fmu(fmi_version).name))


def run(chip: pmdfmu.Chip):
    """What a chip computes for the example script: its recording and its FMU state after it."""
    return chip.run(CYCLES, record=COLUMNS), chip.get_state()


@pytest.mark.parametrize("version", [2, 3])
def test_a_second_chip_of_an_fmu_extracts_nothing_new(version, tmp_path):
    fmu = copy_of(version, tmp_path)
    with pmdfmu.Chip(version, fmu) as first:
        folder = Path(first._unzipdir)
        root = folder.parent
        before = folders(root)
        with pmdfmu.Chip(version, fmu) as second, pmdfmu.Chip(version, str(fmu)) as third:
            assert second._unzipdir == third._unzipdir == first._unzipdir
            assert second.model_description is first.model_description
            assert folders(root) == before
        assert folder.is_dir() and (folder / "modelDescription.xml").is_file()


@pytest.mark.parametrize("version", [2, 3])
def test_a_rewritten_fmu_file_is_extracted_anew(version, tmp_path):
    fmu = copy_of(version, tmp_path)
    old = pmdfmu.Chip(version, fmu)
    try:
        assert not (Path(old._unzipdir) / "resources" / "marker.txt").exists()
        with zipfile.ZipFile(fmu, "a") as z:  # the same path, another file
            z.writestr("resources/marker.txt", "rewritten")
        with pmdfmu.Chip(version, fmu) as new:
            assert new._unzipdir != old._unzipdir
            assert (Path(new._unzipdir) / "resources" / "marker.txt").read_text() == "rewritten"
            assert new.model_description is not old.model_description
            with pmdfmu.Chip(version, fmu) as again:
                assert again._unzipdir == new._unzipdir
            assert np.array_equal(run(new)[0], run(old)[0])  # the instance of the old file still runs
    finally:
        old.close()


@pytest.mark.parametrize("version", [2, 3])
def test_many_instances_of_one_extract_equal_an_instance_of_a_fresh_extract(version, tmp_path):
    with pmdfmu.Chip(version, copy_of(version, tmp_path / "fresh"), script=SCRIPT) as fresh:
        expected, state = run(fresh)
    chips = [pmdfmu.Chip(version, script=SCRIPT) for _ in range(6)]
    try:
        assert len({c._unzipdir for c in chips}) == 1 and chips[0]._unzipdir != fresh._unzipdir
        # interleaved: every instance steps while the others hold their own state
        parts = [[] for _ in chips]
        for start in range(0, CYCLES, 400):
            for chip, part in zip(chips, parts):
                part.append(chip.run(min(400, CYCLES - start), record=COLUMNS))
        for chip, part in zip(chips, parts):
            assert np.array_equal(np.concatenate(part), expected)
            assert chip.get_state() == state
        for chip in chips[:3]:
            chip.reinitialize(script=str(SCRIPT))
            assert np.array_equal(run(chip)[0], expected)
    finally:
        for chip in chips:
            chip.close()


@pytest.mark.parametrize("version", [2, 3])
def test_closing_one_instance_leaves_the_others_working(version, tmp_path):
    fmu = copy_of(version, tmp_path)
    with pmdfmu.Chip(version, fmu, script=SCRIPT) as reference:
        expected = run(reference)
    a, b = pmdfmu.Chip(version, fmu, script=SCRIPT), pmdfmu.Chip(version, fmu, script=SCRIPT)
    a.close()
    a.close()  # twice: nothing more happens
    try:
        assert Path(b._unzipdir).is_dir()
        assert run(b)[0].tobytes() == expected[0].tobytes() and b.get_state() == expected[1]
    finally:
        b.close()
    # every instance closed (each instance's dlclose balanced its dlopen): a new one still works
    with pmdfmu.Chip(version, fmu, script=SCRIPT) as c:
        assert np.array_equal(run(c)[0], expected[0])


def test_chips_made_in_threads_at_once_share_one_extract(tmp_path):
    fmu = copy_of(2, tmp_path)
    chips, errors = [], []
    cwd = os.getcwd()  # FMPy's constructor changes it for a moment: one at a time, it comes back

    def make():
        try:
            chips.append(pmdfmu.Chip(2, fmu))
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=make) for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    try:
        assert not errors and len(chips) == 6
        assert len({c._unzipdir for c in chips}) == 1
        assert len({id(c.model_description) for c in chips}) == 1
        assert os.getcwd() == cwd
    finally:
        for chip in chips:
            chip.close()


def test_the_extracted_folders_are_removed_when_the_interpreter_exits(tmp_path):
    code = (
        "import pathlib, pmdfmu\n"
        "a = pmdfmu.Chip(2)\n"
        "b = pmdfmu.Chip(3)\n"
        "a.close()\n"
        "print(a._unzipdir)\n"
        "print(b._unzipdir)\n"
        "assert pathlib.Path(a._unzipdir).is_dir()\n"
    )  # closing does not remove it: b's is open
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    unzipped = [Path(line) for line in out.stdout.split()]
    assert len(unzipped) == 2 and unzipped[0].parent == unzipped[1].parent
    assert not unzipped[0].exists() and not unzipped[1].exists() and not unzipped[0].parent.exists()
