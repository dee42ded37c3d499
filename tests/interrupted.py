# SPDX-License-Identifier: BSD-2-Clause
"""Recording runs to interrupt, and the checks after an interrupt (tests/test_interrupts.py; a helper
module, not a test file: conftest.py). A real Ctrl-C raises KeyboardInterrupt in the main thread at the
next point where Python checks for signals: Interrupter puts it there, counting the lines the harness
and FMPy run and calling _thread.interrupt_main() at chosen counts, as a SIGINT's arrival does."""

import _thread
import signal
import sys
import time
from pathlib import Path

import fmpy

import pmdfmu
from pmdfmu.chip import RECORDED
from pmdfmu.profile import record_outputs
from scenarios import busy_chip, without_lending

WATCHED = (str(Path(pmdfmu.__file__).parent), str(Path(fmpy.__file__).parent))
CAPACITY = 60
CYCLES = 400  # 7 chunks


class Interrupter:
    """A trace function that interrupts the main thread at the given count of lines run in the harness and
    FMPy (None: count only), and, with `then`, once more `then` seconds later by a real signal (SIGALRM,
    raising KeyboardInterrupt): the first interrupt unsets the trace function (Python unsets one an
    exception passes through), and the second lands wherever the first one's cleanup is by then."""

    def __init__(self, at=None, then=None):
        self.at, self.then, self.lines, self.fired = at, then, 0, 0

    def __enter__(self):
        # Python's own handler, which raises KeyboardInterrupt (another test may have left another one)
        self.handlers = (
            signal.signal(signal.SIGINT, signal.default_int_handler),
            signal.signal(signal.SIGALRM, self.alarm),
        )
        sys.settrace(self.call)
        return self

    def __exit__(self, *exc):
        sys.settrace(None)
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGINT, self.handlers[0])
        signal.signal(signal.SIGALRM, self.handlers[1])

    def alarm(self, signum, frame):
        self.fired += 1
        raise KeyboardInterrupt

    def call(self, frame, event, arg):
        return self.line if frame.f_code.co_filename.startswith(WATCHED) else None

    def line(self, frame, event, arg):
        if event == "line":
            self.lines += 1
            if self.lines == self.at:
                self.fired += 1
                if self.then:
                    signal.setitimer(signal.ITIMER_REAL, self.then)
                _thread.interrupt_main()
        return self.line


def interrupted_run(chip, names, at, then=None) -> int:
    """Runs the recording with an interrupt at line count `at` (and a second one `then` s later); returns
    how many interrupts landed (a second one still pending after the first lands in the wait below)."""
    with Interrupter(at, then) as interrupter:
        try:
            try:
                chip.run(CYCLES, record=names)
                checkpoint()
            except KeyboardInterrupt:
                deadline = time.monotonic() + 1
                while then and interrupter.fired < 2 and time.monotonic() < deadline:
                    time.sleep(then)  # the second one, if it did not land in the cleanup
            checkpoint()
        except KeyboardInterrupt:
            pass
    return interrupter.fired


def checkpoint():
    """A Python call: a pending interrupt is raised here at the latest."""


SCRIPT_END = 260  # the script's last line: no grid change after it


def script(tmp_path):
    path = tmp_path / "finer.pmd"
    path.write_text(f"@150\nSetSampleTime(Axis1, 50);\n@{SCRIPT_END}\nSetSampleTime(Axis1, 100);\n")
    return path


# (FMI version, recorded names, with a script whose SetSampleTime makes chunks redone cycle by cycle)
RUNS = {
    "lent columns": (2, record_outputs(range(2)), False),
    "lent columns fmi3": (3, record_outputs(range(2)), False),
    "copied columns": (3, record_outputs(range(2)), False),  # an FMU that cannot be lent memory (without_lending)
    "commanded table": (2, RECORDED[:6], False),
    "redone chunks": (2, record_outputs([0]), True),
    "redone chunks fmi3": (3, RECORDED[:3], True),
}


def chip_for(run, tmp_path):
    version, _names, scripted = RUNS[run]
    extra = {"script": script(tmp_path)} if scripted else {}
    chip = pmdfmu.Chip(fmi_version=version, **{"record.capacity": CAPACITY}, **extra)
    if run == "copied columns":
        without_lending(chip)
    busy_chip(chip)
    return chip


def assert_intact(chip, run, tmp_path):
    """The interrupted chip records as a fresh one at the same cycle, and the FMU holds no loan."""
    version, names, _ = RUNS[run]
    ran = chip.get("chipTime")
    with chip_for(run, tmp_path) as fresh:
        # cycle by cycle while the script may change the grid (a run of n cycles is n on the grid at its
        # start), then in one run
        while fresh.get("chipTime") < min(ran, 3 * SCRIPT_END):  # with a margin: @ lines count grid cycles
            fresh.run(1)
        fresh.run(ran - fresh.get("chipTime"))
        assert fresh.cycles == chip.cycles and fresh.get("chipTime") == ran
        chip.run(2 * CAPACITY)  # an unrecorded step longer than record.capacity runs
        fresh.run(2 * CAPACITY)
        assert not chip.get("record.enabled")
        assert chip.run(150, record=names).tobytes() == fresh.run(150, record=names).tobytes()
        assert chip.cycles == fresh.cycles
    if run != "copied columns":
        # a loan the FMU still held would limit this step's rows to what it holds: rows wider than the run's
        # do not fit, and the step would be refused ("the memory lent by pmdfmu_fmi*SetRecordBuffer holds")
        chip.set("record.columns", ",".join(record_outputs(range(4))))
        chip.set("record.enabled", True)
        chip._step(CAPACITY)
        chip.set("record.enabled", False)
        assert not [m for m in chip.messages if m.status == "Error"]


def line_count(run, tmp_path):
    """The lines a run of this kind takes, as the interrupted runs take them: the second count (the
    first run of a set of names fills the harness's caches, in more lines)."""
    for _ in range(2):
        with chip_for(run, tmp_path) as chip, Interrupter() as counter:
            chip.run(CYCLES, record=RUNS[run][1])
    return counter.lines
