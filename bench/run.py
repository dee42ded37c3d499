#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-2-Clause
"""The performance suite: every figure next to a baseline measured in the same
run, the contenders taking turns (common.interleave: A B A B ..., min / median /
max, at least 5 pairs where a run is short), as a table; ratios are of medians,
the machine's load printed with them. Benchmarks, not tests: nothing here
asserts a time. Each topic is a module of this folder with benchmarks(tmp).

    python bench/run.py [TOPIC ...]          (./dev bench)
"""

from __future__ import annotations

import importlib
import os
import sys
import tempfile
import traceback
from pathlib import Path

# numpy's OpenBLAS threads spin while idle and take a core of this 2-core machine from the figures
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parent))
import common  # noqa: E402  (this folder's modules import it by name)

TOPICS = [
    "engine",
    "c_library",
    "host_command",
    "system",
    "recording",
    "instances",
    "upload",
    "streaming",
    "streaming_to_disk",
    "sweep",
    "footprint",
    "serve",
    "model_description",
]
HEAD = ("benchmark", "figure (min / median / max)", "baseline, same run (min / median / max)", "ratio", "target", "met")


def main(argv) -> int:
    topics = argv or TOPICS
    print(f"machine {common.load()} at the start (os.getloadavg: 1, 5, 15 min); figures need an idle machine")
    with tempfile.TemporaryDirectory() as d:
        for topic in topics:
            tmp = Path(d) / topic
            tmp.mkdir()
            try:
                importlib.import_module(topic).benchmarks(tmp)
            except Exception as e:  # one failing benchmark does not hide the others
                traceback.print_exc()
                common.rows.append((topic, f"failed: {e}", "", "", "", "NO"))
    print(f"machine {common.load()} at the end")
    rows = [HEAD] + common.rows
    widths = [max(len(str(r[i])) for r in rows) for i in range(len(HEAD))]
    for r in rows:
        print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)))
    return 0 if all(r[5] == "yes" for r in common.rows) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
