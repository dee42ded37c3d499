# SPDX-License-Identifier: BSD-2-Clause
"""The test suite's own layout (tests/conftest.py): no test file imports another
test file or conftest.py; helper modules hold no tests."""

import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parent


def imported_modules(path: Path):
    tree = ast.parse(path.read_text(), str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            yield from (alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module.split(".")[0]


def test_no_test_file_imports_another_test_file_or_conftest():
    for path in sorted(TESTS.glob("*.py")):
        wrong = [m for m in imported_modules(path) if m.startswith("test_") or m == "conftest"]
        assert not wrong, f"{path.name} imports {wrong}: move what they share to conftest.py or a helper module"


def test_helper_modules_hold_no_tests():
    for path in sorted(TESTS.glob("*.py")):
        if path.name.startswith("test_") or path.name == "conftest.py":
            continue
        tree = ast.parse(path.read_text(), str(path))
        tests = [
            n.name
            for n in tree.body
            if isinstance(n, (ast.FunctionDef, ast.ClassDef)) and n.name.lower().startswith("test")
        ]
        assert not tests, f"{path.name} is a helper module but defines {tests}"


def test_every_test_file_is_in_the_readme_map_and_every_file_it_names_exists():
    """tests/README.md's table is how a newcomer finds a topic's tests: it names every file, and only files."""
    import re

    named = set(re.findall(r"`(\w+\.py)`", (TESTS / "README.md").read_text()))
    files = {p.name for p in TESTS.glob("*.py")} - {"conftest.py"}
    assert not files - named, f"tests/README.md does not name {sorted(files - named)}"
    assert not named - files - {"conftest.py"}, f"tests/README.md names missing files {sorted(named - files)}"
