# SPDX-License-Identifier: BSD-2-Clause
"""The servo loop closed through a plant: examples/closed_loop.py's
DC motor and inertia, integrated here cycle by cycle, takes axis1.motorOutput and sends its
encoder count back to axis1.actualPosition with `loopback` false (docs/servo.md). The
suggested gains settle a trapezoidal move in the settle window; an unstable gain set raises
the motion error and auto-stop stops the axis and switches its motor off."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

import pmdfmu
from pmdfmu import (
    PMDActivityAxisSettledMask,
    PMDActivityMotorOnMask,
    PMDEventMotionCompleteMask,
    PMDEventMotionErrorMask,
)

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "closed_loop.py"


def load_example():
    spec = importlib.util.spec_from_file_location("examples.closed_loop", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


example = load_example()


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_the_suggested_gains_settle_a_trapezoidal_move_in_the_settle_window(fmi_version):
    with pmdfmu.Chip(fmi_version=fmi_version, loopback=False) as chip:
        ax, motor, rows = example.settle_move(chip)
        destination = example.MOVE["position"]
        assert rows[-1][3] & PMDEventMotionCompleteMask  # actual mode: settled for the settle time
        assert len(rows) < 1600  # the profile itself takes 1499 cycles
        assert not ax.GetEventStatus() & PMDEventMotionErrorMask
        assert max(abs(c - e) for c, e, _, _ in rows) <= 5  # the following error, all the way
        assert ax.GetActivityStatus() & PMDActivityAxisSettledMask
        assert abs(ax.GetActualPosition() - destination) <= ax.GetSettleWindow()
        # it stays there: the loop holds the motor inside the window
        held = example.run(chip, motor, 2000)
        assert all(abs(e - destination) <= ax.GetSettleWindow() for _, e, _, _ in held)
        assert ax.GetActivityStatus() & PMDActivityMotorOnMask
        # the FMU's outputs are the filter's: the Real is the Int16 over full scale
        assert (
            chip.get("axis1.motorOutput")
            == chip.get("axis1.motorCommand") / 32768
            == ax.GetCurrentMotorCommand() / 32768
        )


def test_without_feedforward_the_same_move_lags_but_still_settles():
    gains = dict(example.GAINS, Kvff=0, Kaff=0)
    with pmdfmu.Chip(loopback=False) as chip:
        ax, motor, rows = example.settle_move(chip, gains)
        assert rows[-1][3] & PMDEventMotionCompleteMask
        lag = max(abs(c - e) for c, e, _, _ in rows)
        assert 5 < lag < ax.GetPositionErrorLimit()


def test_an_unstable_gain_set_raises_the_motion_error_and_the_axis_stops_with_its_motor_off():
    with pmdfmu.Chip(loopback=False) as chip:
        ax, motor, rows = example.unstable_move(chip)
        errors = [c - e for c, e, _, _ in rows]
        assert rows[-1][3] & PMDEventMotionErrorMask
        assert abs(errors[-1]) > ax.GetPositionErrorLimit() >= max(abs(x) for x in errors[:-1])
        # the oscillation grew: its swings get wider before the error passes the limit
        swings = [max(abs(x) for x in errors[k : k + 100]) for k in range(0, len(errors) - 100, 100)]
        assert swings == sorted(swings) and swings[-1] > 4 * swings[0]
        # auto-stop: the trajectory stops, the motor turns off and in that very cycle the output
        # is the open-loop command (the motor command register, 0)
        assert not ax.GetActivityStatus() & PMDActivityMotorOnMask
        assert ax.GetCommandedVelocity() == 0 and rows[-1][2] == 0 and ax.GetMotorCommand() == 0
        stopped_at, speed = ax.GetCommandedPosition(), abs(motor.velocity)
        coast = example.run(chip, motor, 300)
        assert all(c == stopped_at and u == 0 for c, _, u, _ in coast)
        assert abs(motor.velocity) == pytest.approx(speed * (1 - 1 / 200) ** 300)  # unpowered: it coasts down


def test_the_closed_loop_example_runs_as_a_user_would():
    out = subprocess.run([sys.executable, str(EXAMPLE)], capture_output=True, text=True, check=True).stdout
    assert "suggested gains: motion complete after" in out and "at 10000 counts (commanded 10000)" in out
    assert "unstable gains: motion error after" in out and "motor on: False, motor command 0" in out
    # docs/servo.md quotes the first and the last line as they are
    doc = (Path(__file__).resolve().parent.parent / "docs" / "servo.md").read_text()
    lines = out.splitlines()
    assert lines[0] in doc and lines[-1] in doc


def test_the_snippet_in_docs_servo_md_settles_where_it_says(capsys):
    import re

    text = (Path(__file__).resolve().parent.parent / "docs" / "servo.md").read_text()
    (snippet,) = re.findall(r"```python\n(.*?)```", text, re.S)
    exec(compile(snippet, "docs/servo.md", "exec"), {})
    assert capsys.readouterr().out == "10000 10000\n"
