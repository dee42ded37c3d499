# SPDX-License-Identifier: BSD-2-Clause
"""The C library's command cost (issue 29, target 2). Part of ./dev bench (bench/run.py).

bench/c_library.c opens a chip through the C library (host/c, FMI 2 only: the library drives the FMI 2
FMU) with the host interface `none`, so that its commands run no cycle (no doStep), and a second
instance of the same FMU binary (dlopen) that it drives with the FMI calls a command needs and nothing
else: one fmi2SetInteger of host.word[..], host.wordCount and host.strobe, one fmi2GetInteger of
host.ack, host.error, host.replyCount and host.reply[..], checking ack == strobe. Contenders:
PMDSetVelocity (a Set) and PMDGetPosition (a Get with a 2-word reply) against those calls, taking
turns run by run inside the program (CLOCK_MONOTONIC); here min / median / max and the ratio of medians.
"""

from __future__ import annotations

import subprocess

from common import RUNS, build, load, report
from engine import figures
from fmpy import read_model_description

COMMANDS = 1_000_000  # per run and contender (~60 ms)
PAIRS = 2 * RUNS + 1  # runs are short (tens of ms): more pairs for a steadier median


def benchmarks(tmp) -> None:
    tree = build("bench_c_library")
    fmu = tree / "fmi2"
    description = read_model_description(str(fmu / "modelDescription.xml"))
    binary = fmu / "binaries" / "linux64" / f"{description.coSimulation.modelIdentifier}.so"
    out = subprocess.run(
        [str(tree / "bench_c_library"), str(fmu), str(binary), description.guid, str(COMMANDS), str(PAIRS)],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    fig = figures(out.splitlines(), 2)
    for kind, what in (("set", "PMDSetVelocity"), ("get", "PMDGetPosition, 2-word reply")):
        library, direct = fig[f"{kind} library"].per(COMMANDS), fig[f"{kind} fmi"].per(COMMANDS)
        ratio = library.median / direct.median
        report(
            f"C library command FMI 2: {kind} ({what}; host interface none; {load()})",
            library.text(1e9, "ns/command", ".0f"),
            f"the same FMI calls from C {direct.text(1e9, 'ns', '.0f')}",
            ratio,
            "<= 1.3x",
            ratio <= 1.3,
        )
