# SPDX-License-Identifier: BSD-2-Clause
"""The optional parts of pmdfmu's dependencies, imported when a call needs them: matplotlib for plots
(`pip install 'pmdfmu[plot]'`), Dask for sweeps on a cluster (`pip install 'pmdfmu[sweep]'`), Plotly for the
HTML reports (`pip install 'pmdfmu[html]'`). A call
that needs a missing one raises ImportError saying which extra installs it."""

from __future__ import annotations

import importlib
from types import ModuleType


class MissingExtra(ImportError):
    """An optional dependency is not installed: the message names the extra (the CLI says it in one line)."""


def require(module: str, extra: str, what: str) -> ModuleType:
    """The module, or MissingExtra (an ImportError) naming the extra that installs it and what needed it."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise MissingExtra(
            f"{what} needs {module.split('.')[0]}, which comes with pmdfmu's {extra!r} extra: "
            f"pip install 'pmdfmu[{extra}]'"
        ) from e


def pyplot(what: str) -> ModuleType:
    """matplotlib.pyplot, drawing into files (the Agg backend: no display needed)."""
    require("matplotlib", "plot", what).use("Agg")
    return require("matplotlib.pyplot", "plot", what)
