# SPDX-License-Identifier: BSD-2-Clause
"""What a tool pays to read the model descriptions: FMPy's read_model_description and validate_fmu
(which fmpy.simulate_fmu runs on every call) of the chip's FMUs against Reference-FMUs' Feedthrough
read in the same run. Part of ./dev bench (bench/run.py).

Feedthrough's modelDescription.xml comes from a Reference-FMUs checkout or git directory named by
$PMDFMU_REFERENCE_FMUS (default /tmp/Reference-FMUs), zipped alone: both calls read the XML only.
Without one the topic says so and measures nothing."""

from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path
from typing import Optional

from fmpy import read_model_description
from fmpy.validation import validate_fmu

import pmdfmu
from common import interleave, load, report, timed

TARGET = 10.0  # issue "units and metadata": at most 10x Feedthrough's, read and validate alike


def feedthrough_xml(fmi_version: int) -> Optional[bytes]:
    """Feedthrough/FMI<v>.xml of the Reference-FMUs checkout or git directory, or None."""
    where = Path(os.environ.get("PMDFMU_REFERENCE_FMUS", "/tmp/Reference-FMUs"))
    path = where / "Feedthrough" / f"FMI{fmi_version}.xml"
    if path.is_file():
        return path.read_bytes()
    git = subprocess.run(
        ["git", "--git-dir", str(where), "show", f"HEAD:Feedthrough/FMI{fmi_version}.xml"],
        capture_output=True,
    )
    return git.stdout if git.returncode == 0 else None


CALLS = 5  # calls a run: a run of one 1-ms read is at the mercy of one reschedule on the shared machine


def measure(call, chip: str, feedthrough: str, runs: int):
    """(chip's, Feedthrough's) spreads of one call(path), each warmed first (imports, the schema), the
    two interleaved run by run (CALLS calls a run)."""
    call(chip), call(feedthrough)

    def run(path):
        return lambda: timed(lambda: [call(path) for _ in range(CALLS)])

    t = interleave({"chip": run(chip), "feedthrough": run(feedthrough)}, runs)
    return t["chip"].per(CALLS), t["feedthrough"].per(CALLS)


def benchmarks(tmp: Path) -> None:
    for version in (2, 3):
        xml = feedthrough_xml(version)
        if xml is None:
            print(
                "bench/model_description.py: skipped: no Reference-FMUs at $PMDFMU_REFERENCE_FMUS "
                "(default /tmp/Reference-FMUs; a checkout or a git directory of modelica/Reference-FMUs)",
                file=sys.stderr,
            )
            return
        feedthrough = tmp / f"Feedthrough-fmi{version}.fmu"
        with zipfile.ZipFile(feedthrough, "w") as z:
            z.writestr("modelDescription.xml", xml)
        chip = str(pmdfmu.default_fmu(version))
        size = len(zipfile.ZipFile(chip).read("modelDescription.xml"))
        for what, call, runs in (
            ("read_model_description", read_model_description, 15),
            ("validate_fmu", validate_fmu, 9),
        ):
            ours, base = measure(call, chip, str(feedthrough), runs)
            ratio = ours.median / base.median
            report(
                f"FMI {version} {what} ({size // 1000} kB; {load()})",
                ours.text(1e3, "ms"),
                "Feedthrough " + base.text(1e3, "ms"),
                ratio,
                f"<= {TARGET:g}x",
                ratio <= TARGET,
            )
