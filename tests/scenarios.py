# SPDX-License-Identifier: BSD-2-Clause
"""Chip set-ups that several test files run (a helper module, not a test file:
see conftest.py for where shared test code lives)."""

import importlib.util
from pathlib import Path

import pmdfmu
from pmdfmu.profile import load_external_profile, start_external_profile


def _example(name):
    """A module of examples/, loaded by path (the examples are scripts, not a package)."""
    path = Path(__file__).resolve().parent.parent / "examples" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"examples.{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_worked_example = _example("worked_example")

# ---- a busy chip: everything moving at once (FMU state tests) ---------------------

BUSY_OUTPUTS = [
    "axis1.commandedPosition",
    "axis1.commandedVelocity",
    "axis1.commandedAcceleration",
    "axis1.activityStatus",
    "axis1.eventStatus",
    "axis2.commandedPosition",
    "axis1.position",
    "host.interrupt",
]


def busy_chip(chip):
    """An external profile with jerk streaming on axis 1, a trapezoid on axis 2, a breakpoint armed."""
    ax = chip.axis(0)
    rows = [(0, 0x12345, 0x321, 0x1234567, 700), (5, -0x20000, 0, -0x1000, 400), (0, 0, 0, 0, 0)]
    for v in range(5):
        ax.SetBufferStart(2 + v, 0x200 + 4 * v)
        ax.SetBufferLength(2 + v, 3)
        ax.SetBufferFunction(v, 2 + v)
        for r in rows:
            ax.WriteBuffer(2 + v, r[v])
    ax.SetProfileMode(pmdfmu.PMDExternalProfile)
    ax.Update()
    ax.SetInterruptMask(pmdfmu.PMDEventBreakpoint1Mask)
    # a status breakpoint: select mask in the high word (the profile segment number's lowest bit), sense 0 low
    ax.SetBreakpointValue(0, pmdfmu.field_dp(0, "PMDActivityProfileSegment", 1) << 16)
    ax.SetBreakpoint(0, 0, pmdfmu.PMDBreakpointNoAction, pmdfmu.PMDBreakpointActivityStatus)
    a2 = chip.axis(1)
    a2.SetPosition(-30_000)
    a2.SetVelocity(0x50000)
    a2.SetAcceleration(0x800)
    a2.Update()


# ---- seed 000's worked table ---------------------------------------------------------

# chip time, commanded position, commanded velocity (the table's rows)
WORKED_TABLE = [
    (11003, 0, 0x10000),
    (11004, 1, 0x10000),
    (11005, 2, 0x10000),
    (11006, 3, 0x10000),
    (11007, 4, 0x10000),
    (11008, 5, 0x10000),
    (11009, 6, 0x10000),
    (11010, 7, 0x10000),
    (11011, 8, 0x10000),
    (11012, 9, 0x10000),
    (11013, 10, 0),
]


def without_lending(chip):
    """The chip as one of an FMU without pmdfmu_fmi*SetRecordBuffer (an older build): the harness copies its
    rows out of record.data. Its own copy of the extensions its FMU's Chips share, the function absent."""
    chip._extensions = {**chip._extensions, f"pmdfmu_fmi{chip.fmi_version}SetRecordBuffer": None}
    return chip


def run_worked_example(chip):
    """The seed's two rows, started as examples/worked_example.py starts them (the
    first read at chip time 11003), and the 11 cycles of the seed's table."""
    _worked_example.start_worked_example(chip)
    assert chip.axis(pmdfmu.PMDAxis1).GetTime() == 11002
    return chip.run(
        11,
        record=[
            "axis1.commandedPosition",
            "axis1.commandedVelocity",
            "axis1.commandedAcceleration",
            "axis1.activityStatus",
        ],
    )


# ---- random external profiles on axes 1-3 (fast-forward and quiet-run tests) ---------

REAL = [f"axis{n}.{q}" for n in range(1, 5) for q in ("position", "velocity", "acceleration")]


def load_random_profiles(chip, rng, rows_per_axis=12, long=(50, 4000)):
    """Random segment tables on axes 1-3 (axis 4 stays idle), loaded and started together:
    jerk, and velocities coming exactly to rest inside segments (motion-complete events)."""
    tables = {}
    for axis in range(3):
        rows = []
        for _ in range(rows_per_axis):
            v = rng.choice([0, rng.randrange(-0x30000, 0x30000)])
            a = rng.choice([0, rng.randrange(-0x400, 0x400)])
            j = rng.choice([0, rng.randrange(-0x100000, 0x100000)])
            if rng.random() < 0.3:  # velocity exactly 0 after 100 cycles: an event
                m = rng.choice([1, -1]) * rng.randrange(1, 0x100)
                v, a, j = 200 * m, -2 * m, 0
            rows.append((rng.randrange(-5000, 5000), v, a, j, rng.randrange(*long)))
        rows.append((rng.randrange(-10, 10), 0, 0, 0, 0))
        tables[axis] = rows
    load_external_profile(chip, tables)
    start_external_profile(chip, tables)
