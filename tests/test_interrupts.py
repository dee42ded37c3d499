# SPDX-License-Identifier: BSD-2-Clause
"""Ctrl-C anywhere in a recording run: the Chip stays usable and exact (docs/robustness.md, "Interrupts").

A real Ctrl-C raises KeyboardInterrupt in the main thread at the next point where Python checks for
signals. The tests put it there: a trace function counts the lines the harness and FMPy run, and at a
chosen count calls _thread.interrupt_main(), which is what the SIGINT handler's arrival does; a second
one follows by a real signal 20 or 300 us later, into the first one's cleanup. After each interrupted
run the same Chip's next recording is byte for byte a fresh Chip's at the same cycle, record.enabled
is off once the Chip steps again, and the FMU holds none of the memory it was lent."""

import os
import sys
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from interrupted import CAPACITY, RUNS, assert_intact, chip_for, interrupted_run, line_count
from pmdfmu import recording

pytestmark = pytest.mark.slow  # tests/README.md: ./dev test -m "not slow" leaves them out


# The second interrupt (a SIGALRM whose handler raises KeyboardInterrupt) may land inside a garbage
# collector callback (hypothesis installs one), where Python reports it as unraisable and drops it:
# not the harness's doing, and the chip is checked as after any other run.
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("run", sorted(RUNS))
def test_an_interrupt_at_any_point_of_a_recording_run_leaves_the_chip_exact(run, tmp_path):
    total = line_count(run, tmp_path)
    # every line of the first chunk and the run's end, and points spread over the rest, once and twice
    points = sorted(set(range(1, 120)) | set(range(total - 80, total + 1)) | set(np.linspace(1, total, 60, dtype=int)))
    fired = {None: 0, 2e-5: 0, 3e-4: 0}
    for k in points:
        for then in fired:  # once, and twice: the second a real signal, 20 or 300 us later
            with chip_for(run, tmp_path) as chip:
                fired[then] += interrupted_run(chip, RUNS[run][1], k, then)
                assert_intact(chip, run, tmp_path)
    assert fired[None] == len(points) and fired[2e-5] == fired[3e-4] == 2 * len(points)


def test_the_recording_cleanup_retries_through_interrupts(monkeypatch):
    """recording.close, interrupted inside its set of record.enabled (three times): it goes on until
    record.enabled is off, then raises the interrupt."""
    with pmdfmu.Chip(fmi_version=2, **{"record.capacity": CAPACITY}) as chip:
        chip._recording = True
        chip.set("record.enabled", True)
        real, calls = chip.set, []

        def set_interrupted(name, value):
            calls.append(name)
            if len(calls) <= 3:
                real(name, value)  # the set ran; the interrupt lands after it
                raise KeyboardInterrupt
            real(name, value)

        monkeypatch.setattr(chip, "set", set_interrupted)
        with pytest.raises(KeyboardInterrupt):
            recording.close(chip)
        assert not chip._recording and not chip.get("record.enabled") and len(calls) == 4
        chip._recording = True  # as if an interrupt had escaped the cleanup entirely
        monkeypatch.setattr(chip, "set", real)
        chip.set("record.enabled", True)
        chip._step(CAPACITY + 1)  # the next doStep closes it first: no capacity error
        assert not chip.get("record.enabled") and not chip._recording


# ---- real signals at random times, in a process of its own ----

CHILD = """
import signal
import sys
signal.signal(signal.SIGINT, signal.default_int_handler)      # as in a terminal (a background job ignores it)
sys.path.insert(0, {tests!r})
import interrupted as t
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
    import queue
    import random
    import signal
    import subprocess
    import threading
    import time

    code = CHILD.format(tests=str(Path(__file__).parent), tmp=str(tmp_path))
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    rng, said = random.Random(20261201), []
    watchdog = threading.Timer(300, child.kill)  # a child that missed a signal would record forever
    watchdog.start()
    try:
        lines = queue.Queue()
        threading.Thread(target=lambda: [lines.put(x) for x in iter(child.stdout.readline, "")], daemon=True).start()
        for _ in RUNS:
            line = lines.get(timeout=120)
            if line != "ready\n":  # the child ended: what it said on the way
                child.kill()
                child.wait(timeout=60)
                pytest.fail(f"the child said {said + [line]}, then: {child.stderr.read()}")
            time.sleep(0.05 + 0.3 * rng.random())
            child.send_signal(signal.SIGINT)
            # Python drops a KeyboardInterrupt raised where it cannot propagate (a ctypes callback, a
            # finalizer: "Exception ignored ..."), as a user's Ctrl-C then needs pressing again; the
            # property here is the chip after the interrupt that lands, so SIGINT goes again until one does
            while True:
                try:
                    said.append(lines.get(timeout=10))
                    break
                except queue.Empty:
                    child.send_signal(signal.SIGINT)
        child.wait(timeout=120)  # the reader thread has its standard output
        err = child.stderr.read()
    finally:
        watchdog.cancel()
        child.kill()
    assert child.returncode == 0, err
    assert said == [f"intact {run}\n" for run in sorted(RUNS)]


def rss_bytes() -> int:
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


@pytest.mark.skipif(
    not Path("/proc/self/statm").exists() or bool(os.environ.get("PMDFMU_SANITIZED")),
    reason="no /proc, or ASan's quarantine holds freed memory (./dev sanitize)",
)
def test_an_interrupt_as_an_fmu_state_is_saved_leaks_no_state(tmp_path):
    """A KeyboardInterrupt landing just as the FMU's GetFMUState returns (the chunk's saved state of a
    scripted run, and get_state): the state is freed all the same. 200 interrupts would keep 200 states of
    ~70 kB (14 MB) alive if the pointer were lost."""
    import _thread
    import signal

    def interrupt_on_return(frame, event, arg):
        if event == "return" and frame.f_code.co_name == "_save_fmu_state":
            _thread.interrupt_main()
        return interrupt_on_return

    def tracer(frame, event, arg):
        return interrupt_on_return if frame.f_code.co_name == "_save_fmu_state" else None

    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with chip_for("redone chunks", tmp_path) as chip:
            for what in ("run", "get_state"):
                chip.run(1)
                start = rss_bytes()
                for _ in range(200):
                    try:
                        sys.settrace(tracer)
                        chip.run(10, record=RUNS["redone chunks"][1]) if what == "run" else chip.get_state()
                    except KeyboardInterrupt:
                        pass
                    finally:
                        sys.settrace(None)
                assert rss_bytes() - start < 4 << 20, what
    finally:
        signal.signal(signal.SIGINT, handler)
