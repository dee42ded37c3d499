# SPDX-License-Identifier: BSD-2-Clause
"""The licence (BSD-2-Clause, LICENSE) is named where tools look for it: every source file's header
(SPDX), pyproject.toml, both FMUs' model descriptions (tests/test_version.py). The seed's sample code
(tests/c/seed_1_*.c) is PMD's, as printed, and carries no licence of ours."""

import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def test_every_source_file_names_its_licence():
    files = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    sources = [f for f in files if f.endswith((".c", ".h", ".py", ".java")) and not f.startswith("tests/c/seed_1_")]
    missing = [
        f
        for f in sources + ["CMakeLists.txt", "dev", ".ci/run"]
        if "SPDX-License-Identifier: BSD-2-Clause" not in "".join((REPO / f).read_text().splitlines(True)[:3])
    ]
    assert not missing, missing


def test_the_package_and_the_licence_file_agree():
    assert "BSD 2-Clause License" in (REPO / "LICENSE").read_text()
    assert 'license = {text = "BSD-2-Clause"}' in (REPO / "pyproject.toml").read_text()
