# SPDX-License-Identifier: BSD-2-Clause
"""What the generators beside this file share (generate.py, generate_plant.py, generate_cmotion.py,
generate_hosttime.py; fuzz/sequence_inputs.py loads the tables too): the harness's table readers,
loaded by path, and writing what they make."""

import importlib.util
import sys
from pathlib import Path
from types import ModuleType
from typing import Dict

HERE = Path(__file__).resolve().parent


def harness_tables() -> ModuleType:
    """python/pmdfmu/tables.py, the one reader of the interface tables, loaded from the source tree: the
    generators run at build time, before the package is installed."""
    return harness_module("tables")


def write_files(outdir: Path, files: Dict[str, str]) -> None:
    """Each file's text into outdir/name, only where it changed: an unchanged file keeps its time stamp,
    so nothing that depends on it is rebuilt."""
    for name, text in files.items():
        path = Path(outdir) / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if not path.exists() or path.read_text() != text:
            path.write_text(text)


def harness_module(name: str) -> ModuleType:
    """python/pmdfmu/NAME.py, a module of the harness with no third-party imports, loaded from the source
    tree: the generators run at build time, before the package is installed."""
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, HERE.parent / "python" / "pmdfmu" / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]
