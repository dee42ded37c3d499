"""The harness's native library (native/*.c, built by CMake beside the FMUs):
loops over an FMU's own FMI functions that would cost a Python call per cycle
or per word. Found like the FMUs (chip.default_fmu): $PMDFMU_FMU_DIR/native,
the installed package's native/, the source tree's build/native."""
from __future__ import annotations

import ctypes
import os
import sys
from functools import lru_cache
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
REPO = PACKAGE.parent.parent
ABI = 4                  # native/native.h PMD_NATIVE_ABI
NAME = {"win32": "pmdnative.dll", "darwin": "libpmdnative.dylib"}.get(sys.platform, "libpmdnative.so")


@lru_cache(maxsize=None)
def library() -> ctypes.CDLL:
    """The loaded library, once per process; each module declares the prototypes it calls."""
    candidates = [Path(os.environ["PMDFMU_FMU_DIR"]) / "native" / NAME] if "PMDFMU_FMU_DIR" in os.environ else []
    candidates += [PACKAGE / "native" / NAME, REPO / "build" / "native" / NAME]
    for path in candidates:
        if path.is_file():
            lib = ctypes.CDLL(str(path))
            if lib.pmd_native_abi() != ABI:
                raise ImportError(f"{path} is of ABI {lib.pmd_native_abi()}, the harness wants {ABI}: rebuild it "
                                  "(pip install . or cmake --build build)")
            return lib
    raise FileNotFoundError(f"{NAME} not found in {', '.join(map(str, candidates))}: build it first "
                            "(pip install . or cmake -S . -B build && cmake --build build)")


def address(function) -> int:
    """A ctypes function's address, to hand an FMU's FMI function to the library."""
    return ctypes.cast(function, ctypes.c_void_p).value
