# SPDX-License-Identifier: BSD-2-Clause
"""The servo filter and the motor output: docs/decisions.md's
"Servo filter and motor output", pinned cycle by cycle against tests/reference.py's
ServoFilter (written from that page), with `loopback` false and a scripted encoder;
double buffering, open loop, the ideal servo and coarse steps."""

import random

import pytest

import pmdfmu
from pmdfmu import (
    PMDActivityMotorOnMask,
    PMDBreakpointActionMotorOff,
    PMDBreakpointActionUpdate,
    PMDBreakpointDisable,
    PMDBreakpointGreaterOrEqualCommandedPosition,
    PMDBreakpointTime,
    PMDEventMotionErrorMask,
    PMDMotorOff,
    PMDMotorOn,
    PMDTraceConditionImmediate,
    PMDTrapezoidalProfile,
    PMDVelocityContouringProfile,
)
from pmdfmu.profile import load_external_profile, start_external_profile
from reference import ServoFilter, wrap32
from states import snapshot

# the filter group (reference 4.1): the model's field -> the register's command name
GROUP = {
    "kp": "Kp",
    "ki": "Ki",
    "kd": "Kd",
    "kvff": "Kvff",
    "kaff": "Kaff",
    "kout": "Kout",
    "integration_limit": "IntegrationLimit",
    "derivative_time": "DerivativeTime",
    "motor_command": "MotorCommand",
}
INT32_MAX = 2**31 - 1


class Rig:
    """Axis n of a chip, and the reference filter beside it: the test sends the
    host's commands through the rig, which mirrors them in the model, and
    scripts the encoder (loopback false)."""

    def __init__(self, chip, n=0):
        self.chip, self.n, self.ax = chip, n, chip.axis(n)
        self.name = f"axis{n + 1}"
        self.model = ServoFilter()
        self.motor_on = True
        self.commanded = 0

    def set(self, **registers):
        """Set commands of the filter group: buffered, nothing acts yet."""
        for name, value in registers.items():
            getattr(self.ax, "Set" + GROUP[name])(value)
            setattr(self.model.buffered, name, value)

    def update(self):
        self.ax.Update()
        self.model.update()

    def bias(self, value):
        self.ax.SetMotorBias(value)
        self.model.motor_bias = value

    def limit(self, value):
        self.ax.SetMotorLimit(value)
        self.model.motor_limit = value

    def motor(self, on):
        self.ax.SetMotorMode(PMDMotorOn if on else PMDMotorOff)
        self.motor_on = on

    def registers(self):
        """commanded position, velocity and acceleration as the last cycle left them"""
        return tuple(
            self.chip.get(f"{self.name}.{q}")
            for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration")
        )

    def cycle(self, encoder, check_gets=True):
        """One cycle with the encoder at `encoder`; the FMU's motor command,
        integral and derivative must be the model's."""
        encoder = wrap32(encoder)
        self.chip.set(f"{self.name}.actualPosition", encoder)
        self.chip.run(1)
        return self.check(encoder, check_gets)

    def check(self, encoder, check_gets=True):
        """The model's cycle beside the one the chip has just run (the encoder at `encoder`)."""
        c, v, a = self.registers()
        self.commanded = c
        expected = self.model.cycle(c, encoder, v, a, self.motor_on)
        assert self.chip.get(f"{self.name}.motorCommand") == expected
        assert self.chip.get(f"{self.name}.motorOutput") == expected / 32768.0
        if check_gets:
            assert (self.ax.GetCurrentMotorCommand(), self.ax.GetIntegral(), self.ax.GetDerivative()) == (
                expected,
                self.model.integral,
                self.model.derivative,
            )
        return expected


def start_trapezoid(ax, position, velocity, acceleration):
    ax.SetProfileMode(PMDTrapezoidalProfile)
    ax.SetPosition(position)
    ax.SetVelocity(velocity)
    ax.SetAcceleration(acceleration)


def random_registers(rng):
    def gain():
        return rng.choice([0, rng.randrange(1, 64), rng.randrange(64, 4096), rng.randrange(0x10000), 0xFFFF])

    return dict(
        kp=gain(),
        ki=gain(),
        kd=gain(),
        kvff=gain(),
        kaff=gain(),
        kout=rng.choice([0xFFFF, 0x8000, 1, rng.randrange(0x10000)]),
        integration_limit=rng.choice([0, rng.randrange(1, 1000), rng.randrange(1, 1 << 24), INT32_MAX]),
        derivative_time=rng.choice([1, 1, rng.randrange(2, 8), rng.randrange(8, 40)]),
        motor_command=rng.randrange(-0x8000, 0x8000),
    )


def random_offset(rng, offset):
    """The encoder's distance behind the commanded position: a random walk, now
    and then a jump anywhere in 32 bits (sums and differences saturate)."""
    r = rng.random()
    if r < 0.03:
        return rng.randrange(-(2**31), 2**31)
    if r < 0.06:
        return 0
    return offset + rng.randrange(-40, 41)


# ---- the formula, by hand, then the model ---------------------------------------


def test_reset_values_and_a_first_closed_loop_cycle_by_hand():
    with pmdfmu.Chip(loopback=False) as chip:
        ax = chip.axis(0)
        assert [getattr(ax, "Get" + c)() for c in GROUP.values()] == [0, 0, 0, 0, 0, 0xFFFF, 0, 1, 0]
        assert (ax.GetMotorLimit(), ax.GetMotorBias(), ax.GetCurrentMotorCommand()) == (32767, 0, 0)
        assert ax.GetActivityStatus() & PMDActivityMotorOnMask
        ax.SetKp(300)
        ax.SetKi(512)
        ax.SetKd(40)
        ax.SetIntegrationLimit(1000)
        ax.SetKout(0x8000)
        ax.Update()
        ax.SetMotorBias(-7)
        chip.set("axis1.actualPosition", -10)
        chip.run(1)
        # E = 0 - (-10) = 10; I = 10; D = 10 - 0; S = 300*10 + 40*10 + 512*10/256 = 3420; u = 3420/2 - 7
        assert (ax.GetIntegral(), ax.GetDerivative(), ax.GetCurrentMotorCommand()) == (10, 10, 1703)
        assert ax.GetPositionError() == -10  # actual - commanded: -E
        chip.set("axis1.actualPosition", -13)
        chip.run(1)
        # E = 13; I = 23; D = 3; S = 3900 + 120 + floor(512*23/256) = 4066; u = 2033 - 7
        assert (ax.GetIntegral(), ax.GetDerivative(), ax.GetCurrentMotorCommand()) == (23, 3, 2026)


@pytest.mark.parametrize("seed", range(10))
def test_random_filters_match_the_reference_model_cycle_by_cycle(seed):
    """Random gains, Kout, integration limits, derivative times, bias and motor
    limit; a move in either direction; an encoder that wanders and jumps; Sets
    without Update (nothing changes, the Gets read them), Updates, bias and limit
    changes (at once), the motor off and on."""
    rng = random.Random(seed)
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip, rng.randrange(4))
        rig.set(**random_registers(rng))
        rig.bias(rng.randrange(-0x8000, 0x8000))
        rig.limit(rng.choice([32767, rng.randrange(32768), 0]))
        if rng.random() < 0.5:
            start_trapezoid(rig.ax, rng.randrange(-50_000, 50_000), rng.randrange(1, 0x80000), rng.randrange(1, 0x4000))
        else:
            rig.ax.SetProfileMode(PMDVelocityContouringProfile)
            rig.ax.SetVelocity(rng.randrange(-0x80000, 0x80000))
            rig.ax.SetAcceleration(rng.randrange(1, 0x4000))
        rig.update()
        offset = 0
        for k in range(250):
            if k % 25 == 24:
                event = rng.randrange(6)
                if event == 0:  # buffered only: the Gets read them, the filter does not
                    regs = {name: value for name, value in random_registers(rng).items() if rng.random() < 0.5}
                    rig.set(**regs)
                    assert {name: getattr(rig.ax, "Get" + GROUP[name])() for name in regs} == regs
                elif event == 1:
                    rig.update()
                elif event == 2:
                    rig.bias(rng.randrange(-0x8000, 0x8000))
                elif event == 3:
                    rig.limit(rng.randrange(32768))
                elif event == 4:
                    rig.motor(not rig.motor_on)
            offset = random_offset(rng, offset)
            rig.cycle(rig.commanded - offset, check_gets=k % 3 == 0)


def test_saturations_and_clamps():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        rig.set(kp=0xFFFF, ki=0xFFFF, kout=1, integration_limit=5000)
        rig.update()
        rig.bias(-32767)
        # S = 65535 * 2^30 saturates to 2^31 - 1: Kout 1 makes it 32767, the bias brings it to 0
        # (unsaturated it would be 2^30 - 32767, limited to 32767)
        assert rig.cycle(-(2**30)) == 0
        assert chip.axis(0).GetIntegral() == 5000  # I clamped at the integration limit
        assert chip.axis(0).GetDerivative() == 32767  # D = 2^30, saturated to 16 bits
        assert rig.cycle(2**30) == -32767  # S = -2^31: u = -32768 - 32767, limited
        assert chip.axis(0).GetIntegral() == -5000 and chip.axis(0).GetDerivative() == -32768
        # E = 0 - (-2^31) wraps to -2^31; GetPositionError (actual - commanded) reads -2^31 too
        rig.cycle(-(2**31))
        assert chip.axis(0).GetPositionError() == -(2**31)
        rig.set(kp=0, kout=0xFFFF, integration_limit=100)  # lowered: clamps at the next cycle
        rig.update()
        rig.bias(0)
        rig.limit(1000)
        assert rig.cycle(0) == -1000 and chip.axis(0).GetIntegral() == -100  # S = 65535 * -100 / 256
        rig.limit(0)
        assert rig.cycle(12345) == 0  # motor limit 0: nothing goes out


def test_the_derivative_samples_every_derivative_time_cycles_and_holds():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        rig.set(kd=10, derivative_time=4)
        rig.update()
        derivatives = []
        for k in range(7):
            rig.cycle(-3 * k * k)  # E = 3 k^2
            derivatives.append(chip.axis(0).GetDerivative())
        # a sample at the fourth cycle (k = 3): E - E at the previous sample (0 before the first)
        assert derivatives == [0, 0, 0, 27, 27, 27, 27]
        rig.set(derivative_time=2)  # lowered below the count (3): samples at the next cycle
        rig.update()
        for k in range(7, 10):
            rig.cycle(-3 * k * k)
            derivatives.append(chip.axis(0).GetDerivative())
        assert derivatives[7:] == [147 - 27, 147 - 27, 243 - 147]


# ---- double buffering ------------------------------------------------------------


def test_set_without_update_changes_nothing_and_update_applies_the_filter_group():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        rig.set(kp=100)
        rig.update()
        assert rig.cycle(-5) == 500 - 1  # Kout 65535: floor(500 * 65535 / 65536)
        rig.set(
            kp=200,
            ki=0xFFFF,
            kd=7,
            kvff=3,
            kaff=4,
            kout=0x4000,
            integration_limit=77,
            derivative_time=9,
            motor_command=-1234,
        )
        for _ in range(3):
            assert rig.cycle(-5) == 499 and chip.axis(0).GetIntegral() == 0
        assert chip.axis(0).GetKp() == 200 and chip.axis(0).GetMotorCommand() == -1234
        rig.update()
        assert rig.cycle(-5) != 499


def test_multi_update_applies_the_filter_group_of_the_masked_axes_only():
    with pmdfmu.Chip(loopback=False) as chip:
        rigs = [Rig(chip, n) for n in range(4)]
        for rig in rigs:
            rig.set(kp=10 * (rig.n + 1))
        chip.axis(0).MultiUpdate(pmdfmu.PMDAxis1Mask | pmdfmu.PMDAxis3Mask)
        for rig in (rigs[0], rigs[2]):
            rig.model.update()
        for k in range(3):
            for rig in rigs:
                chip.set(f"{rig.name}.actualPosition", -100 - k)
            chip.run(1)
            for rig in rigs:
                rig.check(-100 - k)
        assert [chip.get(f"axis{n}.motorCommand") for n in range(1, 5)] == [1019, 0, 3059, 0]


def test_an_update_breakpoint_applies_the_filter_group_in_the_cycle_it_fires():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        start_trapezoid(rig.ax, 1000, 0x10000, 0x10000)  # 1 count per cycle
        rig.update()
        rig.set(kp=50)
        rig.ax.SetBreakpointValue(0, 10)
        rig.ax.SetBreakpoint(0, 0, PMDBreakpointActionUpdate, PMDBreakpointGreaterOrEqualCommandedPosition)
        for k in range(30):
            encoder = rig.commanded - 3
            chip.set("axis1.actualPosition", encoder)
            chip.run(1)
            c, v, a = rig.registers()
            rig.commanded = c
            if c == 10:
                rig.model.update()  # the breakpoint fires in this cycle, before the filter runs
            assert chip.get("axis1.motorCommand") == rig.model.cycle(c, encoder, v, a, True), k
        assert rig.model.active.kp == 50 and chip.get("axis1.motorCommand") == 50 * 4 - 1


# ---- open loop -------------------------------------------------------------------


def test_open_loop_sends_the_motor_command_register_without_bias_or_limit():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        rig.set(kp=100, ki=256, integration_limit=1000, derivative_time=3)
        rig.update()
        rig.bias(500)
        rig.limit(1000)
        for _ in range(5):
            rig.cycle(-20)
        rig.motor(False)
        rig.set(motor_command=-20000)
        assert rig.cycle(-20) == 0  # the active motor command: not updated yet
        assert (chip.axis(0).GetIntegral(), chip.axis(0).GetDerivative()) == (0, 0)
        rig.update()
        assert rig.cycle(-25) == -20000  # no bias, no limit
        assert not chip.axis(0).GetActivityStatus() & PMDActivityMotorOnMask
        rig.motor(True)  # closes again: empty integral, no kick
        for k in range(6):
            rig.cycle(-25 - k)
        assert chip.axis(0).GetIntegral() == 25 + 26 + 27 + 28 + 29 + 30


def test_a_motor_off_breakpoint_switches_the_output_in_the_cycle_it_fires():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        rig.set(kp=100, motor_command=321)
        start_trapezoid(rig.ax, 1000, 0x10000, 0x10000)
        rig.update()
        rig.ax.SetBreakpointValue(0, 10)
        rig.ax.SetBreakpoint(0, 0, PMDBreakpointActionMotorOff, PMDBreakpointGreaterOrEqualCommandedPosition)
        outputs = []
        for _ in range(14):
            chip.set("axis1.actualPosition", 0)
            chip.run(1)
            outputs.append((rig.registers()[0], chip.get("axis1.motorCommand")))
        assert [c for c, u in outputs] == list(range(1, 15))  # positions 1, 2, ...: fires at 10
        assert [u for c, u in outputs if c < 10] == [100 * c - 1 for c, u in outputs if c < 10]
        assert [u for c, u in outputs if c >= 10] == [321] * sum(c >= 10 for c, u in outputs)


def test_auto_stop_on_a_motion_error_switches_to_the_open_loop_command_at_once():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip)
        rig.set(kp=10, motor_command=-5)
        rig.update()
        rig.ax.SetPositionErrorLimit(100)
        rig.ax.SetAutoStopMode(pmdfmu.PMDAutoStopEnabled)
        assert rig.cycle(-100) == 999
        rig.motor_on = False  # |error| 101 > 100: the motor turns off
        assert rig.cycle(-101) == -5
        assert rig.ax.GetEventStatus() & PMDEventMotionErrorMask
        assert not rig.ax.GetActivityStatus() & PMDActivityMotorOnMask


# ---- the ideal servo ---------------------------------------------------------------


def test_loopback_keeps_the_ideal_servo_and_outputs_feedforward_and_bias():
    with pmdfmu.Chip() as chip:
        ax = chip.axis(1)
        model = ServoFilter()
        ax.SetMotorBias(-300)
        model.motor_bias = -300
        chip.run(3)
        assert chip.get("axis2.motorCommand") == -300  # reset gains: the bias
        for name, value in dict(
            kp=0xFFFF, ki=0xFFFF, kd=0xFFFF, kvff=900, kaff=5000, kout=0xC000, integration_limit=INT32_MAX
        ).items():
            getattr(ax, "Set" + GROUP[name])(value)
            setattr(model.buffered, name, value)
        start_trapezoid(ax, -3000, 0x28000, 0x3000)
        ax.Update()
        model.update()
        for _ in range(300):
            chip.run(1)
            c, v, a = (
                chip.get(f"axis2.{q}") for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration")
            )
            assert ax.GetPositionError() == 0
            assert chip.get("axis2.motorCommand") == model.cycle(c, c, v, a, True)
            assert (ax.GetIntegral(), ax.GetDerivative()) == (0, 0)
        chip.run(2000)  # at rest: no feedforward, the bias
        assert ax.GetCommandedPosition() == -3000 and chip.get("axis2.motorCommand") == -300


def test_motor_on_after_an_open_loop_move_in_loopback_gives_one_derivative_sample():
    """Loopback with the motor off holds the actual position; the derivative's
    history follows the error; motor on: the ideal servo's error drops to 0, and
    the next derivative sample sees that step once."""
    with pmdfmu.Chip() as chip:
        ax = chip.axis(0)
        ax.SetKd(2)
        ax.SetDerivativeTime(5)
        ax.SetMotorMode(PMDMotorOff)
        start_trapezoid(ax, 400, 0x20000, 0x10000)
        ax.Update()
        chip.run(300)
        assert ax.GetPositionError() == -400
        ax.SetMotorMode(PMDMotorOn)
        seen = []
        for _ in range(12):
            chip.run(1)
            seen.append((ax.GetDerivative(), chip.get("axis1.motorCommand")))
        # samples at the 5th and 10th closed-loop cycles: 0 - 400, then 0 - 0
        assert seen == [(0, 0)] * 4 + [(-400, -800)] * 5 + [(0, 0)] * 3


# ---- trace ---------------------------------------------------------------------------


def test_trace_variables_7_10_11_sample_the_filter_every_cycle():
    with pmdfmu.Chip(loopback=False) as chip:
        rig = Rig(chip, 2)
        rig.set(kp=7, ki=3000, kd=11, integration_limit=400, derivative_time=2)
        rig.update()
        ax = chip.axis(0)
        ax.SetBufferStart(0, 0x100)
        ax.SetBufferLength(0, 300)
        for slot, variable in enumerate((7, 10, 11)):
            ax.SetTraceVariable(slot, 2, variable)
        ax.SetTraceStart(0, PMDTraceConditionImmediate, 0, 0)
        expected = []
        rng = random.Random(5)
        for _ in range(60):
            rig.cycle(rng.randrange(-80, 80), check_gets=False)
            expected.append((rig.model.output, rig.model.integral, rig.model.derivative))
        values = [pmdfmu.signed(ax.ReadBuffer(0)) for _ in range(180)]
        assert [tuple(values[i : i + 3]) for i in range(0, 180, 3)] == expected


# ---- coarse steps ----------------------------------------------------------------------


def twins(loopback, count=2):
    """Chips alike (FMI 3) but for a breakpoint armed far in the future on axis 4
    of the first: it runs every cycle one by one (no quiet run, no
    fast-forward), the others in closed form where they can."""
    chips = [pmdfmu.Chip(fmi_version=3, loopback=loopback) for _ in range(count)]
    for chip in chips:
        chip.axis(3).SetBreakpointValue(0, INT32_MAX)
        chip.axis(3).SetBreakpoint(0, 3, 0, PMDBreakpointTime if chip is chips[0] else PMDBreakpointDisable)
    return chips


def filter_registers(chip):
    return [
        (
            chip.axis(n).GetIntegral(),
            chip.axis(n).GetDerivative(),
            chip.axis(n).GetCurrentMotorCommand(),
            chip.get(f"axis{n + 1}.motorCommand"),
        )
        for n in range(4)
    ]


def run_twins(chips, chunks, between, recorded=()):
    """Every chip runs the chunks (the ones in `recorded` recording, so that the
    FMU runs each chunk's cycles in one quiet run), `between(chip, k)` before
    chunk k; the filters agree at every chunk's end, and the whole FMU states at
    the end."""
    for k, n in enumerate(chunks):
        for chip in chips:
            between(chip, k)
            chip.run(n, record=["axis1.commandedPosition"] if chip in recorded else ())
        first = filter_registers(chips[0])
        for chip in chips[1:]:
            assert filter_registers(chip) == first, k
    for chip in chips:  # the same batches for all: the host port's strobes agree
        chip.axis(3).SetBreakpoint(0, 3, 0, PMDBreakpointDisable)
    for chip in chips[1:]:
        assert snapshot(chip) == snapshot(chips[0])  # derivative counts and all


@pytest.mark.parametrize("seed", range(3))
def test_coarse_steps_with_loopback_equal_cycle_by_cycle(seed):
    """Quiet runs and the fast-forward through external-profile segments: the
    ideal servo's feedforward, a derivative held over a long derivative time."""
    rng = random.Random(seed)
    fine, coarse, recorded = twins(True, 3)
    with fine, coarse, recorded:
        for chip in (fine, coarse, recorded):
            load_external_profile(
                chip, {0: [(0, 0x18000, 0x20, 0, 3000), (5000, -0x8000, 0, 0x100, 2000), (0, 0, 0, 0, 0)]}
            )
            for n in range(3):
                ax = chip.axis(n)
                ax.SetKvff(300 * (n + 1))
                ax.SetKaff(0xFFFF)
                ax.SetKd(0x2000)
                ax.SetDerivativeTime(37 + n)
                ax.SetMotorBias(11 * n)
            start_trapezoid(chip.axis(1), 7000, 0x30000, 0x400)
            chip.axis(1).Update()
            chip.axis(2).SetMotorMode(PMDMotorOff)
            start_trapezoid(chip.axis(2), -900, 0x10000, 0x100)
            chip.axis(2).Update()
            start_external_profile(chip, [0])

        def between(chip, k):
            if k == 3:
                chip.axis(2).SetMotorMode(PMDMotorOn)  # the held error drops to 0: one derivative sample
            if k == 4:  # below the count: samples at the next cycle
                chip.axis(1).SetDerivativeTime(3)
                chip.axis(1).Update()
            if k == 6:
                chip.axis(0).SetMotorMode(PMDMotorOff)
            if k == 8:
                chip.axis(0).SetMotorMode(PMDMotorOn)

        run_twins([fine, coarse, recorded], [rng.randrange(1, 900) for _ in range(14)], between, [recorded])


@pytest.mark.parametrize("seed", range(3))
def test_coarse_steps_of_idle_axes_with_errors_equal_cycle_by_cycle(seed):
    """Without loopback, idle axes with constant errors fast-forward: the
    integral runs into its limit, the derivative samples the steps in the encoder
    once and then 0, the motor command follows."""
    rng = random.Random(seed)
    fine, coarse = twins(False)
    with fine, coarse:
        limits = [3_000_000] + [rng.choice([0, 50_000, 3_000_000]) for _ in range(3)]
        times = [rng.randrange(1, 100) for _ in range(4)]
        for chip in (fine, coarse):
            for n in range(4):
                ax = chip.axis(n)
                ax.SetKp(3)
                ax.SetKi(100 + n)
                ax.SetKd(50)
                ax.SetIntegrationLimit(limits[n])
                ax.SetDerivativeTime(times[n])
                ax.SetKout(0x2000)
                ax.Update()
            chip.axis(3).SetMotorMode(PMDMotorOff)
        # axis 1's error stays small: its integral ramps through the fast-forwards without reaching the limit
        encoders = [[rng.randrange(-3, 4)] + [rng.randrange(-5000, 5000) for _ in range(3)] for _ in range(12)]

        def between(chip, k):
            for n in range(4):
                chip.set(f"axis{n + 1}.actualPosition", encoders[k][n])
            if k == 5:
                chip.axis(1).SetMotorMode(PMDMotorOff)
                chip.axis(3).SetMotorMode(PMDMotorOn)

        run_twins([fine, coarse], [rng.randrange(1, 50_000) for _ in range(12)], between)


def test_a_refused_update_applies_no_filter_register():
    """A refused Update changes nothing (the contract), the filter group included: the trapezoid's
    acceleration changed in motion (0x0C) applies only the destination (seed 001), not the motor
    command written with it; the host's next accepted Update applies it."""
    with pmdfmu.Chip() as chip:
        ax = chip.axis(0)
        ax.SetMotorMode(PMDMotorOff)
        start_trapezoid(ax, 10_000, 0x40000, 0x1000)
        ax.Update()
        chip.run(20)
        ax.SetAcceleration(0x2000)
        ax.SetMotorCommand(-3000)
        with pytest.raises(pmdfmu.PMDError) as refusal:
            ax.Update()
        assert refusal.value.code == pmdfmu.PMD_ERR_InvalidParameterChange
        chip.run(1)
        assert ax.GetCurrentMotorCommand() == 0 and ax.GetMotorCommand() == -3000
        chip.run(5000)  # at rest: the same Update is accepted
        ax.Update()
        chip.run(1)
        assert ax.GetCurrentMotorCommand() == -3000
