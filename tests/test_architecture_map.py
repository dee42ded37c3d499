# SPDX-License-Identifier: BSD-2-Clause
"""The map is part of the code: docs/architecture.md and the README's Layout name every top-level folder
of the repository and every folder of fmu_src/, so a folder added without a word about it fails here."""

import re
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def folders():
    """The repository's top-level folders and fmu_src's, as git knows them (a fresh clone's)."""
    files = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    top = {f.split("/")[0] for f in files if "/" in f}
    fmu = {"/".join(f.split("/")[:2]) for f in files if f.startswith("fmu_src/") and f.count("/") >= 2}
    return sorted(top), sorted(fmu)


def test_the_architecture_page_names_every_folder():
    text = (REPO / "docs" / "architecture.md").read_text()
    top, fmu = folders()
    missing = [f for f in top + fmu if not re.search(rf"(?<![\w/.]){re.escape(f)}/", text)]
    assert not missing, f"docs/architecture.md does not name {missing}"


def test_the_readme_layout_names_every_top_level_folder():
    text = (REPO / "README.md").read_text()
    layout = text[text.index("## Layout") :]
    top, fmu = folders()
    missing = [f for f in top + fmu if f"`{f}/" not in layout]
    assert not missing, f"the README's Layout table does not name {missing}"


def test_the_docs_index_lists_every_page():
    index = (REPO / "docs" / "README.md").read_text()
    pages = sorted(p.name for p in (REPO / "docs").glob("*.md") if p.name != "README.md")
    missing = [p for p in pages if f"]({p})" not in index]
    assert not missing, f"docs/README.md does not list {missing}"
