# SPDX-License-Identifier: BSD-2-Clause
"""Reference-FMUs (modelica/Reference-FMUs) built for a test: the tools' defects are checked
against an FMU of the same feature that is not this project's, to tell the tool's defect from the
FMU's. The source is $PMDFMU_REFERENCE_FMUS, a checkout or a git directory (as
bench/model_description.py takes it; default /tmp/Reference-FMUs); without one the test skips,
since no package registry has Reference-FMUs' binaries. Built with CMake once per process."""

import functools
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest


def _source() -> Path:
    """A checkout of the Reference-FMUs source: $PMDFMU_REFERENCE_FMUS itself, or its HEAD unpacked."""
    where = Path(os.environ.get("PMDFMU_REFERENCE_FMUS", "/tmp/Reference-FMUs"))
    if (where / "CMakeLists.txt").is_file():
        return where
    out = Path(tempfile.mkdtemp(prefix="reference-fmus-"))
    archive = subprocess.run(["git", "--git-dir", str(where), "archive", "HEAD"], capture_output=True)
    if archive.returncode != 0:
        pytest.skip(
            f"no Reference-FMUs at $PMDFMU_REFERENCE_FMUS ({where}): a checkout or git directory of "
            "modelica/Reference-FMUs"
        )
    subprocess.run(["tar", "x", "-C", str(out)], input=archive.stdout, check=True)
    return out


@functools.lru_cache(maxsize=None)
def _built(fmi_version: int) -> Path:
    if not shutil.which("cmake"):
        pytest.skip("cmake not installed: it builds Reference-FMUs")
    source = _source()
    build = Path(tempfile.mkdtemp(prefix=f"reference-fmus-fmi{fmi_version}-"))
    configure = ["cmake", "-S", str(source), "-B", str(build), f"-DFMI_VERSION={fmi_version}", "-DFMI_TYPE=CS"]
    subprocess.run(configure + ["-DCMAKE_BUILD_TYPE=Release"], check=True, capture_output=True, timeout=300)
    subprocess.run(
        ["cmake", "--build", str(build), "--target", "Feedthrough", "BouncingBall"],
        check=True,
        capture_output=True,
        timeout=600,
    )
    return build / "fmus"


def reference_fmu(name: str, fmi_version: int) -> Path:
    """Reference-FMUs' FMU `name` (Feedthrough or BouncingBall), Co-Simulation, FMI 2 or 3."""
    return _built(fmi_version) / f"{name}.fmu"
