# SPDX-License-Identifier: BSD-2-Clause
"""The project's one version, python/pmdfmu/__init__.py's __version__: the installed package's metadata
(pyproject.toml reads it there), both FMUs' model descriptions (modelDescription/generate.py reads it),
the C library's header (a copy, checked here) and `pmdfmu --version` say the same."""

import importlib.metadata
import re
import zipfile
from pathlib import Path

import pytest

import pmdfmu

REPO = Path(__file__).resolve().parent.parent


def test_the_package_metadata_is_the_one_version():
    assert re.fullmatch(r"\d+\.\d+\.\d+", pmdfmu.__version__)
    assert importlib.metadata.version("pmdfmu") == pmdfmu.__version__


@pytest.mark.parametrize("version", [2, 3])
def test_the_model_descriptions_carry_the_version_and_licence(version):
    fmus = [pmdfmu.default_fmu(version), pmdfmu.default_fmu(version).parent / f"pmdplant-fmi{version}.fmu"]
    for fmu in fmus:
        with zipfile.ZipFile(fmu) as z:
            head = z.read("modelDescription.xml").decode()[:2000]
        assert f'version="{pmdfmu.__version__}"' in head and 'license="BSD-2-Clause"' in head, fmu
        assert f'generationTool="pmdfmu {pmdfmu.__version__}"' in head, fmu


def test_the_c_library_header_says_the_same_version():
    header = (REPO / "host" / "c" / "PMDfmu.h").read_text()
    assert f'#define PMDFMU_VERSION "{pmdfmu.__version__}"' in header


def test_pmdfmu_version_prints_it():
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "pmdfmu.cli", "--version"], capture_output=True, text=True)
    assert done.returncode == 0 and done.stdout == f"pmdfmu {pmdfmu.__version__}\n"
