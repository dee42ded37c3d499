# SPDX-License-Identifier: BSD-2-Clause
"""Source FMU: sources/ is self-contained; FMPy's build support rebuilds the
binary from it (FMI 2 SourceFiles, FMI 3 buildDescription.xml) and the rebuilt
FMU runs the seed's worked example."""

import shutil
import zipfile

import pytest
from fmpy.build import build_platform_binary
from fmpy.util import create_zip_archive

import pmdfmu
from scenarios import WORKED_TABLE, run_worked_example

pytestmark = pytest.mark.slow  # tests/README.md: ./dev test -m "not slow" leaves them out


@pytest.mark.skipif(not shutil.which("cmake"), reason="cmake not installed")
@pytest.mark.parametrize("version", [2, 3])
def test_the_binary_rebuilt_from_sources_runs_the_worked_example(tmp_path, version):
    unzipped = tmp_path / "fmu"
    zipfile.ZipFile(pmdfmu.default_fmu(version)).extractall(unzipped)
    shutil.rmtree(unzipped / "binaries")
    (tmp_path / "build").mkdir()
    build_platform_binary(unzipped, build_dir=tmp_path / "build")
    assert list((unzipped / "binaries").rglob("PMDMotionProcessor.so"))
    rebuilt = tmp_path / f"rebuilt-fmi{version}.fmu"
    create_zip_archive(rebuilt, unzipped)
    with pmdfmu.Chip(fmi_version=version, fmu=rebuilt) as chip:
        rows = run_worked_example(chip)
        assert [(int(r[0]), int(r[1]), int(r[2])) for r in rows] == WORKED_TABLE


@pytest.mark.parametrize("version", [2, 3])
def test_sources_hold_every_header_they_include(version):
    import re

    names = zipfile.ZipFile(pmdfmu.default_fmu(version)).namelist()
    sources = {n[len("sources/") :] for n in names if n.startswith("sources/")}
    archive = zipfile.ZipFile(pmdfmu.default_fmu(version))
    for name in sources:
        if name.endswith((".c", ".h")):
            text = archive.read("sources/" + name).decode()
            for header in re.findall(r'^\s*#\s*include "([^"]+)"', text, re.MULTILINE):
                assert header in sources, f"{name} includes {header}"
