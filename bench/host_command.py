# SPDX-License-Identifier: BSD-2-Clause
"""Issue target 1: a host command from Python (a Set, a Get with its reply, through the Axis methods
and as raw words through chip.send) against a no-op ctypes call into C in the same run, FMI 2 and
FMI 3; the Python path it replaced (tests/stepwise.py's StepwiseChip: encoding in Python, the FMI
calls through FMPy) for scale; and a polled move (wait_for_motion_complete with host time) against
chip.run of the same cycles. Contenders interleaved (A B A B ...), min / median / max, the ratio of medians."""

from __future__ import annotations

import sys
import time

from common import REPO, interleave, load, report

import pmdfmu
from pmdfmu import native

sys.path.insert(0, str(REPO / "tests"))
from stepwise import StepwiseChip  # noqa: E402  (the Python path, kept as the tests' oracle)

CALLS = 5_000  # a run: short, so that another job's burst on the shared machine spoils few runs, not the median
PAIRS = 21  # interleaved runs of each contender
MOVE = [
    ("SetProfileMode", 0),
    ("SetPosition", 200_000),
    ("SetVelocity", 0x80000),
    ("SetAcceleration", 0x1000),
    ("SetDeceleration", 0x1000),
    ("Update",),
]


def per_call(f, n=CALLS):
    def run():
        start = time.perf_counter()
        for _ in range(n):
            f()
        return (time.perf_counter() - start) / n

    return run


def commands(version: int, noop) -> None:
    set_velocity = pmdfmu.instruction_word(pmdfmu.COMMANDS["SetVelocity"].opcode, 0)
    get_position = pmdfmu.instruction_word(pmdfmu.COMMANDS["GetPosition"].opcode, 0)
    with pmdfmu.Chip(version) as chip, StepwiseChip(version) as slow:
        ax, sx = chip.axis(0), slow.axis(0)
        t = interleave(
            {
                "noop": per_call(noop),
                "set": per_call(lambda: ax.SetVelocity(1000)),
                "get": per_call(ax.GetPosition),
                "send set": per_call(lambda: chip.send(set_velocity, 0, 1000)),
                "send get": per_call(lambda: chip.send(get_position)),
                "python set": per_call(lambda: sx.SetVelocity(1000), CALLS // 10),
            },
            PAIRS,
        )
    base = f"no-op ctypes call {t['noop'].text(1e9, 'ns', '.0f')}"
    for name in ("set", "get", "send set", "send get"):
        ratio = t[name].median / t["noop"].median
        report(
            f"host command FMI {version}: {name} ({load()})",
            t[name].text(1e9, "ns", ".0f"),
            base,
            ratio,
            "<= 10x",
            ratio <= 10,
        )
    ratio = t["python set"].median / t["set"].median
    report(
        f"host command FMI {version}: Python path set / native set",
        t["python set"].text(1e9, "ns", ".0f"),
        f"native {t['set'].text(1e9, 'ns', '.0f')}",
        ratio,
        "(for scale)",
        True,
    )


def moved(version: int, host) -> pmdfmu.Chip:
    chip = pmdfmu.Chip(version, host_interface=host)
    ax = chip.axis(0)
    for name, *args in MOVE:
        getattr(ax, name)(*args)
    ax.ResetEventStatus(0)
    return chip


def polled_move(version: int) -> None:
    """A move polled over serial until motion complete, against chip.run of as many cycles."""
    with moved(version, "serial") as chip:
        chip.wait_for_motion_complete(0)
        cycles = chip.cycles

    def polled():
        with moved(version, "serial") as chip:
            start = time.perf_counter()
            chip.wait_for_motion_complete(0)
            return time.perf_counter() - start

    def ran():
        with moved(version, None) as chip:
            start = time.perf_counter()
            chip.run(cycles)
            return time.perf_counter() - start

    t = interleave({"polled": polled, "run": ran})
    ratio = t["polled"].median / t["run"].median
    report(
        f"polled move FMI {version} ({cycles} cycles, serial; {load()})",
        t["polled"].text(1e3, "ms"),
        f"chip.run same cycles {t['run'].text(1e3, 'ms')}",
        ratio,
        "about 1x (report)",
        True,
    )


def benchmarks(tmp) -> None:
    noop = native.library().pmd_native_abi
    for version in (2, 3):
        commands(version, noop)
    for version in (2, 3):
        polled_move(version)
