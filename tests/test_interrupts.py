"""Ctrl-C anywhere in a recording run: the Chip stays usable and exact (docs/robustness.md, "Interrupts").

A real Ctrl-C raises KeyboardInterrupt in the main thread at the next point where Python checks for
signals. The tests put it there: a trace function counts the lines the harness and FMPy run, and at
chosen counts calls _thread.interrupt_main(), which is what the SIGINT handler's arrival does. After
each interrupted run (once, and twice in a row: the second lands in the cleanup of the first) the
same Chip's next recording is byte for byte a fresh Chip's at the same cycle, record.enabled is off
once the Chip steps again, and the FMU holds none of the memory it was lent."""
import _thread
import signal
import sys
from pathlib import Path

import fmpy
import numpy as np
import pytest

import pmdfmu
from pmdfmu.chip import RECORDED
from pmdfmu.profile import record_outputs
from scenarios import busy_chip

WATCHED = (str(Path(pmdfmu.__file__).parent), str(Path(fmpy.__file__).parent))
CAPACITY = 60
CYCLES = 400            # 7 chunks


class Interrupter:
    """A trace function that interrupts the main thread at the given counts of lines run in the harness and
    FMPy (None: count only)."""

    def __init__(self, at=()):
        self.at, self.lines = set(at), 0

    def __enter__(self):
        # Python's own handler, which raises KeyboardInterrupt (another test may have left another one)
        self.handler = signal.signal(signal.SIGINT, signal.default_int_handler)
        sys.settrace(self.call)
        return self

    def __exit__(self, *exc):
        sys.settrace(None)
        signal.signal(signal.SIGINT, self.handler)

    def call(self, frame, event, arg):
        return self.line if frame.f_code.co_filename.startswith(WATCHED) else None

    def line(self, frame, event, arg):
        if event == "line":
            self.lines += 1
            if self.lines in self.at:
                _thread.interrupt_main()
        return self.line


def checkpoint():
    """A Python call: a pending interrupt is raised here at the latest."""


def script(tmp_path):
    path = tmp_path / "finer.pmd"
    path.write_text("@150\nSetSampleTime(Axis1, 50);\n@260\nSetSampleTime(Axis1, 100);\n")
    return path


# (FMI version, recorded names, with a script whose SetSampleTime makes chunks redone cycle by cycle)
RUNS = {"lent columns": (2, record_outputs(range(2)), False),
        "copied columns": (3, record_outputs(range(2)), False),
        "commanded table": (2, RECORDED[:6], False),
        "redone chunks": (2, record_outputs([0]), True),
        "redone chunks fmi3": (3, RECORDED[:3], True)}


def chip_for(run, tmp_path):
    version, _names, scripted = RUNS[run]
    extra = {"script": script(tmp_path)} if scripted else {}
    chip = pmdfmu.Chip(fmi_version=version, **{"record.capacity": CAPACITY}, **extra)
    busy_chip(chip)
    return chip


def interrupted_run(chip, names, at) -> bool:
    """Runs the recording with interrupts at the given line counts; True if one landed in it."""
    try:
        with Interrupter(at):
            chip.run(CYCLES, record=names)
            checkpoint()
        checkpoint()
    except KeyboardInterrupt:
        return True
    return False


def assert_intact(chip, run, tmp_path):
    """The interrupted chip records as a fresh one at the same cycle, and the FMU holds no loan."""
    version, names, _ = RUNS[run]
    ran = chip.get("chipTime")
    with chip_for(run, tmp_path) as fresh:
        while fresh.get("chipTime") < ran:          # cycle by cycle: a run of n cycles is n on the grid at its start
            fresh.run(1)
        assert fresh.cycles == chip.cycles
        chip.run(2 * CAPACITY)                       # an unrecorded step longer than record.capacity runs
        fresh.run(2 * CAPACITY)
        assert not chip.get("record.enabled")
        assert chip.run(150, record=names).tobytes() == fresh.run(150, record=names).tobytes()
        assert chip.cycles == fresh.cycles
    if version == 2:
        # a loan the FMU still held would limit this step's rows to what it holds: rows wider than the run's
        # do not fit, and the step would be refused ("the memory lent by pmdfmu_fmi2SetRecordBuffer holds")
        chip.set("record.columns", ",".join(record_outputs(range(4))))
        chip.set("record.enabled", True)
        chip._step(CAPACITY)
        chip.set("record.enabled", False)
        assert not [m for m in chip.messages if m.status == "Error"]


def line_count(run, tmp_path):
    with chip_for(run, tmp_path) as chip, Interrupter() as counter:
        chip.run(CYCLES, record=RUNS[run][1])
    return counter.lines


@pytest.mark.parametrize("run", sorted(RUNS))
def test_an_interrupt_at_any_point_of_a_recording_run_leaves_the_chip_exact(run, tmp_path):
    total = line_count(run, tmp_path)
    # every line of the first chunk and the run's end, and points spread over the rest, once and twice
    points = sorted(set(range(1, 120)) | set(range(total - 80, total + 1)) | set(np.linspace(1, total, 60, dtype=int)))
    interrupted = 0
    for k in points:
        for at in ([k], [k, k + 1], [k, k + 4]):
            with chip_for(run, tmp_path) as chip:
                interrupted += interrupted_run(chip, RUNS[run][1], at)
                assert_intact(chip, run, tmp_path)
    assert interrupted >= len(points)            # the interrupts did land in the runs


def test_the_recording_cleanup_retries_through_interrupts(monkeypatch):
    """Chip._close_recording, interrupted inside its set of record.enabled (three times): it goes on until
    record.enabled is off, then raises the interrupt."""
    with pmdfmu.Chip(fmi_version=2, **{"record.capacity": CAPACITY}) as chip:
        chip._recording = True
        chip.set("record.enabled", True)
        real, calls = chip.set, []

        def set_interrupted(name, value):
            calls.append(name)
            if len(calls) <= 3:
                real(name, value)                  # the set ran; the interrupt lands after it
                raise KeyboardInterrupt
            real(name, value)
        monkeypatch.setattr(chip, "set", set_interrupted)
        with pytest.raises(KeyboardInterrupt):
            chip._close_recording()
        assert not chip._recording and not chip.get("record.enabled") and len(calls) == 4
        chip._recording = True                        # as if an interrupt had escaped the cleanup entirely
        monkeypatch.setattr(chip, "set", real)
        chip.set("record.enabled", True)
        chip._step(CAPACITY + 1)                      # the next doStep closes it first: no capacity error
        assert not chip.get("record.enabled") and not chip._recording


# ---- real signals at random times, in a process of its own ----

CHILD = """
import signal
import sys
signal.signal(signal.SIGINT, signal.default_int_handler)      # as in a terminal (a background job ignores it)
sys.path.insert(0, {tests!r})
import test_interrupts as t
import pathlib
tmp = pathlib.Path({tmp!r})
for run in sorted(t.RUNS):
    with t.chip_for(run, tmp) as chip:
        print("ready", flush=True)
        try:
            while True:
                chip.run(t.CYCLES, record=t.RUNS[run][1])
        except KeyboardInterrupt:
            pass
        t.assert_intact(chip, run, tmp)
        print("intact", run, flush=True)
"""


def test_sigint_at_random_times_leaves_every_kind_of_run_exact(tmp_path):
    """SIGINT, sent at random times into a process recording in a loop (each kind of run in turn): after
    each, the child checks its chip as the line-by-line test does and says so."""
    import random
    import subprocess
    import threading
    import time
    code = CHILD.format(tests=str(Path(__file__).parent), tmp=str(tmp_path))
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
    rng, said = random.Random(20261201), []
    watchdog = threading.Timer(300, child.kill)       # a child that missed a signal would record forever
    watchdog.start()
    try:
        for _ in RUNS:
            assert child.stdout.readline() == "ready\n"
            time.sleep(0.05 + 0.3 * rng.random())
            child.send_signal(signal.SIGINT)
            said.append(child.stdout.readline())
        out, err = child.communicate(timeout=120)
    finally:
        watchdog.cancel()
        child.kill()
    assert child.returncode == 0, err
    assert said == [f"intact {run}\n" for run in sorted(RUNS)]
