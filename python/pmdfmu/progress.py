# SPDX-License-Identifier: BSD-2-Clause
"""Progress bars for long work (Chip.run, `pmdfmu run`, `verify --cases`, sweeps), with tqdm: shown on
standard error once the work has lasted about a second, and only when standard error is a terminal, so a
pipe or a CI log never holds one; `show(True)` (`--progress`) asks for it there too, `show(False)`
(`--quiet`) silences it. A bar that closes (the work done, or Ctrl-C) clears its line. note() puts a
line beside them under the same rule (a sweep's local cluster: its Dask dashboard link)."""

from __future__ import annotations

import sys
from contextlib import contextmanager
from typing import Iterator, Optional

DELAY = 1.0  # seconds of work before a bar appears
CHIP_RUN_CYCLES = 200_000  # a Chip.run shorter than this never shows one (and runs in one piece)
_shown: Optional[bool] = None  # None: on a terminal; True: always (--progress); False: never (--quiet)


def show(value: Optional[bool]) -> None:
    """Bars on a terminal (None, the default), always (True: --progress) or never (False: --quiet)."""
    global _shown
    _shown = value


def wanted() -> bool:
    """Whether a bar may be shown: asked for, or standard error is a terminal and not silenced."""
    if _shown is not None:
        return _shown
    try:
        return sys.stderr is not None and sys.stderr.isatty()
    except (AttributeError, ValueError):  # a closed or replaced stderr
        return False


def note(text: str) -> None:
    """A line on standard error with the bars (a sweep's Dask dashboard link), shown where a bar would be."""
    if wanted():
        print(text, file=sys.stderr, flush=True)


class _Silent:
    def update(self, n: int = 1) -> None:
        pass


@contextmanager
def bar(description: str, total: Optional[int] = None, unit: str = "cycles", enabled: bool = True) -> Iterator[object]:
    """A bar with update(n), or one that does nothing when none is wanted (or not enabled: a Dask
    worker's part of a sweep, say; or tqdm is missing)."""
    if not enabled or not wanted():
        yield _Silent()
        return
    try:
        from tqdm import tqdm
    except ImportError:
        yield _Silent()
        return
    # delay: nothing for work under a second; leave=False: the line is cleared when it closes
    with tqdm(
        total=total,
        desc=description,
        unit=" " + unit if unit else "it",
        unit_scale=unit == "cycles",
        delay=0 if _shown else DELAY,
        leave=False,
        file=sys.stderr,
        dynamic_ncols=True,
        mininterval=0.2,
    ) as t:
        yield t
