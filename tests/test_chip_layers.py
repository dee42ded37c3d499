# SPDX-License-Identifier: BSD-2-Clause
"""The chip core is built in layers (the map in fmu_src/chip/chip.h):
each C file calls only functions of its own layer and the layers below, so
there is no circle. The compiler's object files say what each file defines and
what it needs, whatever the headers claim."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CHIP = ROOT / "fmu_src" / "chip"

# Bottom up; a file belongs to the layer named by its stem or listed with it.
LAYERS = [
    ("events",),  # the log and the event status bits
    ("status",),  # register views derived from the state
    ("machine",),  # the switch and index inputs that follow the actual position
    ("memory",),  # the external memory
    ("scurve",),  # the S-curve generator
    ("profile",),  # trajectory generators, stops, Update
    ("servo",),  # the servo filter and the motor output
    ("trace",),  # the trace facility
    ("registers", "register_table"),  # the plain stored registers' Set, Get and reset values
    ("chip", "fastforward"),  # life cycle, the per-cycle sequence
    ("commands", "host", "command_table"),  # handlers (commands*.c), the dispatcher and its table
]

pytestmark = pytest.mark.skipif(not (shutil.which("cc") and shutil.which("nm")), reason="no C compiler or nm")


def layer_of(stem: str) -> int:
    for level, names in enumerate(LAYERS):
        if stem in names or (stem.startswith("commands_") and "commands" in names):
            return level
    raise AssertionError(f"fmu_src/chip/{stem}.c is in no layer of tests/test_chip_layers.py (and chip.h's map)")


def symbols(obj: Path, *flags):
    out = subprocess.run(["nm", *flags, str(obj)], check=True, capture_output=True, text=True).stdout
    return {line.split()[-1] for line in out.splitlines() if line.strip()}


@pytest.fixture(scope="module")
def needs(tmp_path_factory):
    """file stem -> {stem of another chip file it calls: [the functions]}."""
    out = tmp_path_factory.mktemp("layers")
    subprocess.run([sys.executable, str(ROOT / "modelDescription" / "generate.py"), str(out)], check=True)
    sources = sorted(CHIP.glob("*.c")) + [out / "command_table.c"]
    defined, undefined = {}, {}
    for src in sources:
        obj = out / (src.stem + ".o")
        subprocess.run(
            [
                "cc",
                "-std=c99",
                "-c",
                f"-I{CHIP}",
                f"-I{ROOT / 'fmu_src' / 'plant'}",
                f"-I{out}",
                str(src),
                "-o",
                str(obj),
            ],
            check=True,
        )
        defined[src.stem] = symbols(obj, "--defined-only", "-g")
        undefined[src.stem] = symbols(obj, "-u")
    owner = {name: stem for stem, names in defined.items() for name in names}
    graph = {}
    for stem, names in undefined.items():
        for name in sorted(names):
            if name in owner and owner[name] != stem:
                graph.setdefault(stem, {}).setdefault(owner[name], []).append(name)
    return graph


@pytest.mark.slow
def test_every_chip_file_calls_only_its_layer_and_those_below(needs):
    upward = [
        f"{stem}.c calls {', '.join(names)} of {other}.c"
        for stem, calls in needs.items()
        for other, names in calls.items()
        if layer_of(other) > layer_of(stem)
    ]
    assert not upward, "\n".join(upward)


def test_the_ground_floor_calls_nothing_of_the_chip(needs):
    assert "events" not in needs and "status" not in needs
    assert set(needs.get("memory", {})) <= {"events"}


def test_no_circle_between_chip_files(needs):
    def circle(stem, path):
        if stem in path:
            return path[path.index(stem) :] + [stem]
        for other in needs.get(stem, {}):
            found = circle(other, path + [stem])
            if found:
                return found
        return None

    for stem in needs:
        found = circle(stem, [])
        assert not found, " -> ".join(f"{s}.c" for s in found)


def includes_of(folder: str):
    """stem -> {stems it includes}: every C file and header of a folder of the product, a C file and its
    header as one."""
    import re

    files = [p for p in (ROOT / folder).rglob("*") if p.suffix in (".c", ".h")]
    stems = {p.stem for p in files}
    graph = {}
    for p in files:
        for name in re.findall(r'^\s*#\s*include\s+"([^"]+)"', p.read_text(), re.M):
            other = Path(name).stem
            if other in stems and other != p.stem:
                graph.setdefault(p.stem, set()).add(other)
    return graph


def imports_of_the_harness():
    """module -> {modules of the package it imports}: python/pmdfmu, at any depth of a module (a function's
    own import counts: it is a dependency all the same)."""
    import ast

    package = ROOT / "python" / "pmdfmu"
    modules = {p.stem for p in package.glob("*.py")}
    graph = {}
    for p in package.glob("*.py"):
        for node in ast.walk(ast.parse(p.read_text())):
            named = []
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                named = [node.module.split(".")[0]] if node.module else [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("pmdfmu."):
                named = [node.module.split(".")[1]]
            elif isinstance(node, ast.Import):
                named = [a.name.split(".")[1] for a in node.names if a.name.startswith("pmdfmu.")]
            graph.setdefault(p.stem, set()).update(m for m in named if m in modules and m != p.stem)
    return graph


def a_circle(graph):
    """A path that comes back to where it started, or None."""

    def circle(stem, path):
        if stem in path:
            return path[path.index(stem) :] + [stem]
        for other in sorted(graph.get(stem, ())):
            found = circle(other, path + [stem])
            if found:
                return found
        return None

    for stem in sorted(graph):
        found = circle(stem, [])
        if found:
            return found
    return None


def test_no_include_circle_in_fmu_src():
    """A header that includes the file that includes it (registers.c including the chip.h that includes
    registers.h, instance.h and record.c) names a layer above it: no such circle anywhere in fmu_src."""
    graph = includes_of("fmu_src")
    assert "registers" in graph.get("chip", set()) and "instance_types" in graph.get("record", set())
    found = a_circle(graph)
    assert not found, " -> ".join(found)


@pytest.mark.parametrize("folder", ["native", "host/c"])
def test_no_include_circle_in_the_native_library_or_the_c_library(folder):
    graph = includes_of(folder)
    assert graph, f"{folder}: no includes found"
    found = a_circle(graph)
    assert not found, " -> ".join(found)


def test_no_import_circle_in_the_harness():
    """verify.py and verify_report.py imported each other: the results live with their reports now."""
    graph = imports_of_the_harness()
    assert "verify_report" in graph["verify"] and "chip" in graph["verify"]
    found = a_circle(graph)
    assert not found, " -> ".join(found)
