# SPDX-License-Identifier: BSD-2-Clause
"""The servo loop closed through a plant model (docs/servo.md): a DC motor
driving an inertia, integrated here one chip cycle at a time, takes the FMU's
motor output and sends its encoder count back to axis 1's actual position, with
`loopback` false. The chip runs a trapezoidal move with the suggested gains and
settles in the settle window; an unstable gain set raises the motion error, and
auto-stop switches the motor off.

    python examples/closed_loop.py
"""

import math
from dataclasses import dataclass

import pmdfmu
from pmdfmu import (
    PMDActivityMotorOnMask,
    PMDAutoStopEnabled,
    PMDEventMotionCompleteMask,
    PMDEventMotionErrorMask,
    PMDMotionCompleteActualPosition,
    PMDMotorOn,
    PMDTrapezoidalProfile,
)


@dataclass
class Motor:
    """A DC motor and its load in counts and chip cycles: the amplifier turns
    the motor output u (-1 .. 1 of full scale, the FMU's axisN.motorOutput) into
    a torque, back-EMF and viscous friction brake the speed:

        a = full_scale_acceleration * u - v / time_constant

    (counts/cycle^2), so the no-load speed at full scale is
    full_scale_acceleration * time_constant counts/cycle. Integrated once per
    cycle (semi-implicit Euler); the encoder reads the whole counts."""

    full_scale_acceleration: float = 1.0  # counts/cycle^2 at u = 1
    time_constant: float = 200.0  # cycles
    position: float = 0.0  # counts
    velocity: float = 0.0  # counts/cycle

    def step(self, u: float) -> None:
        self.velocity += self.full_scale_acceleration * u - self.velocity / self.time_constant
        self.position += self.velocity

    @property
    def encoder(self) -> int:
        return math.floor(self.position)


# Suggested gains for this motor (docs/servo.md says how they follow from it).
# Kvff and Kaff cancel the motor's own response to the commanded velocity and
# acceleration: Kvff V/2^16 = u_full * v / (a_full * tau), Kaff A/2^16 = u_full * a / a_full,
# u_full = 32768 counts of motor command.
GAINS = dict(Kp=100, Ki=200, Kd=4000, DerivativeTime=4, IntegrationLimit=20_000, Kvff=164, Kaff=32768, Kout=0xFFFF)
# A PI loop with far too much integral gain and no derivative: it oscillates with growing amplitude.
UNSTABLE_GAINS = dict(Kp=100, Ki=1000, Kd=0, DerivativeTime=1, IntegrationLimit=0x7FFFFFFF, Kvff=0, Kaff=0, Kout=0xFFFF)

MOVE = dict(position=10_000, velocity=10.0, acceleration=0.02)  # counts, counts/cycle, counts/cycle^2


def set_up(chip, gains, settle_window=5, settle_time=20, position_error_limit=1000):
    """Axis 1: the filter gains (buffered: one Update applies them), the motion
    error and settling set-up, the motor on: a C-Motion initialization sequence."""
    ax = chip.axis(0)
    for name, value in gains.items():
        getattr(ax, "Set" + name)(value)
    ax.SetMotorLimit(32767)
    ax.SetMotorBias(0)
    ax.SetPositionErrorLimit(position_error_limit)
    ax.SetAutoStopMode(PMDAutoStopEnabled)
    ax.SetSettleWindow(settle_window)
    ax.SetSettleTime(settle_time)
    ax.SetMotionCompleteMode(PMDMotionCompleteActualPosition)
    ax.Update()
    ax.SetMotorMode(PMDMotorOn)
    return ax


def start_move(ax, position=MOVE["position"], velocity=MOVE["velocity"], acceleration=MOVE["acceleration"]):
    ax.SetProfileMode(PMDTrapezoidalProfile)
    ax.SetPosition(position)
    ax.SetVelocity(pmdfmu.fixed_16_16(velocity))
    ax.SetAcceleration(pmdfmu.fixed_16_16(acceleration))
    ax.Update()


def run(chip, motor, cycles, until=None):
    """Cycle by cycle: the encoder count into the chip, one cycle, the motor
    output into the motor. Returns one row per cycle: the commanded position
    and the encoder count the cycle saw, the motor command it sent out and the
    event status; stops after the first row for which until(row) holds."""
    rows = []
    for _ in range(cycles):
        encoder = motor.encoder
        chip.set("axis1.actualPosition", encoder)
        chip.run(1)
        motor.step(chip.get("axis1.motorOutput"))
        row = (
            chip.get("axis1.commandedPosition"),
            encoder,
            chip.get("axis1.motorCommand"),
            chip.get("axis1.eventStatus"),
        )
        rows.append(row)
        if until and until(row):
            break
    return rows


def settle_move(chip, gains=GAINS, cycles=5000):
    """The suggested gains: the servo holds the motor at rest for 10 cycles,
    then a trapezoidal move to MOVE's position runs until motion complete
    (actual mode: inside the settle window for the settle time)."""
    ax = set_up(chip, gains)
    motor = Motor()
    run(chip, motor, 10)
    start_move(ax)
    return ax, motor, run(chip, motor, cycles, until=lambda row: row[3] & PMDEventMotionCompleteMask)


def unstable_move(chip, gains=UNSTABLE_GAINS, cycles=5000):
    """The unstable gains: the same move until the motion error."""
    ax = set_up(chip, gains)
    motor = Motor()
    run(chip, motor, 10)
    start_move(ax)
    return ax, motor, run(chip, motor, cycles, until=lambda row: row[3] & PMDEventMotionErrorMask)


if __name__ == "__main__":
    with pmdfmu.Chip(loopback=False) as chip:
        ax, motor, rows = settle_move(chip)
        worst = max(abs(c - e) for c, e, _, _ in rows)
        print(
            f"suggested gains: motion complete after {len(rows)} cycles at {rows[-1][1]} counts "
            f"(commanded {rows[-1][0]}); largest following error {worst} counts"
        )
        for k in range(0, len(rows), 250):
            c, e, u, _ = rows[k]
            print(f"  cycle {k + 1:5d}: commanded {c:6d}  encoder {e:6d}  motor command {u:6d}")
    with pmdfmu.Chip(loopback=False) as chip:
        ax, motor, rows = unstable_move(chip)
        print(
            f"unstable gains: motion error after {len(rows)} cycles, position error {ax.GetPositionError()}; "
            f"motor on: {bool(ax.GetActivityStatus() & PMDActivityMotorOnMask)}, "
            f"motor command {chip.get('axis1.motorCommand')}"
        )
