# SPDX-License-Identifier: BSD-2-Clause
"""Trace in buffer 0 (pmd-reference 4.4, 2.6) and SetSampleTime (CONTRACT 2.2)."""

import pytest

import pmdfmu
from pmdfmu import (
    FIELDS,
    PMDError,
    PMDTraceActivityStatus,
    PMDTraceCommandedPosition,
    PMDTraceCommandedVelocity,
    PMDTraceConditionActivityStatus,
    PMDTraceConditionImmediate,
    PMDTraceConditionUpdate,
    PMDTraceOneTime,
    PMDTraceRollingBuffer,
    PMDTraceStatusActivity,
    PMDTraceStatusDataWrap,
    PMDTraceStatusMode,
    PMDTraceTime,
    PMDTraceTriggerStateHigh,
    PMDTraceTriggerStateLow,
)


def bit(field):
    """A trace condition's bit number: where a one-bit status field lies."""
    return FIELDS[field].shift


def setup_trace(ax, length, mode=PMDTraceOneTime, period=1):
    ax.SetBufferStart(0, 0x100)
    ax.SetBufferLength(0, length)
    ax.SetTraceMode(mode)
    ax.SetTracePeriod(period)
    ax.SetTraceVariable(0, 0, PMDTraceTime)
    ax.SetTraceVariable(1, 1, PMDTraceCommandedPosition)
    ax.SetTraceVariable(2, 1, PMDTraceCommandedVelocity)


def read_samples(ax, count, slots=3):
    values = [pmdfmu.signed(ax.ReadBuffer(0)) for _ in range(count)]
    return [tuple(values[i : i + slots]) for i in range(0, count, slots)]


def start_axis2(ax):
    ax.SetPosition(1_000_000)
    ax.SetVelocity(0x30000)
    ax.SetAcceleration(0x10000)
    ax.Update()


def test_one_time_trace_on_the_next_update_samples_every_period_until_full(chip):
    ax, ax2 = chip.axis(0), chip.axis(1)
    setup_trace(ax, 30, period=4)
    ax.SetTraceStart(1, PMDTraceConditionUpdate, 0, 0)
    assert ax.GetTraceStart() == (1, PMDTraceConditionUpdate, 0, 0)
    chip.run(10)
    assert ax.GetTraceStatus() == 0 and ax.GetTraceCount() == 0
    start_axis2(ax2)  # chip time 10 is the first cycle after the update
    rec = chip.run(60, record=["axis2.commandedPosition", "axis2.commandedVelocity"])
    assert ax.GetTraceCount() == 30 and ax.GetTraceStatus() == 0  # full: stopped by itself
    assert ax.GetTraceStart() == (0, 0, 0, 0)
    expected = [
        (int(r["cycle"]), int(r["axis2.commandedPosition"]), int(r["axis2.commandedVelocity"])) for r in rec[::4][:10]
    ]
    assert read_samples(ax, 30) == expected


def test_rolling_trace_wraps_and_stops_on_an_activity_bit(chip):
    ax, ax2 = chip.axis(0), chip.axis(1)
    setup_trace(ax, 9, mode=PMDTraceRollingBuffer)
    ax.SetTraceVariable(3, 1, PMDTraceActivityStatus)
    ax.SetTraceVariable(3, 0, 0)  # variable 0 ends the list: three slots
    # stop when axis 2 is at maximum velocity
    ax.SetTraceStop(1, PMDTraceConditionActivityStatus, bit("PMDActivityAtMaximumVelocity"), PMDTraceTriggerStateHigh)
    ax.SetTraceStart(0, PMDTraceConditionImmediate, 0, 0)
    assert ax.GetTraceStatus() == PMDTraceStatusMode | PMDTraceStatusActivity
    start_axis2(ax2)
    with pytest.raises(PMDError) as e:
        ax.SetBufferLength(0, 3)  # changing buffer 0 while tracing
    assert e.value.code == 0x05
    with pytest.raises(PMDError):
        ax.SetTracePeriod(2)
    chip.run(10)
    assert ax.GetTraceStatus() == PMDTraceStatusMode | PMDTraceStatusDataWrap  # rolling, stopped, wrapped
    assert ax.GetTraceCount() == 9
    assert ax.GetTraceStop() == (0, 0, 0, 0)
    # axis 2 reached 3 counts/cycle in cycle 2; the last three samples are cycles 0..2, wrapped in place
    assert sorted(read_samples(ax, 9)) == [(0, 1, 0x10000), (1, 3, 0x20000), (2, 6, 0x30000)]


def test_trace_errors(chip):
    ax = chip.axis(0)
    with pytest.raises(PMDError) as e:
        ax.SetTraceStart(0, PMDTraceConditionImmediate, 0, 0)
    assert e.value.code == 0x08  # zero-length buffer 0
    for call, args in (
        ("SetTracePeriod", (0,)),
        ("SetTraceMode", (2,)),
        ("SetTraceVariable", (4, 0, 2)),
        ("SetTraceVariable", (0, 0, 28)),
        ("SetTraceStart", (0, 5, 0, 0)),
    ):
        with pytest.raises(PMDError) as e:
            getattr(ax, call)(*args)
        assert e.value.code == 0x04, call


def test_set_sample_time_restarts_the_grid_with_the_new_cycle_time():
    with pmdfmu.Chip(cycleTime=1e-3) as chip:
        ax = chip.axis(0)
        assert ax.GetSampleTime() == 1000
        chip.run(10)  # cycles 0..9 at 0 .. 9 ms; now t = 10 ms
        ax.SetSampleTime(250)
        assert ax.GetSampleTime() == 250 and chip.cycle_time == 250e-6
        chip.run(4)  # one doStep of 1 ms: 4 cycles of 250 us
        assert ax.GetTime() == 13
        assert chip.time == pytest.approx(0.011)
        rec = chip.run(4, record=["chipTime"])
        assert list(rec["cycle"]) == [14, 15, 16, 17]
        ax.SetVelocity(0x10000)
        ax.SetAcceleration(0x10000)
        ax.SetPosition(100)
        ax.Update()
        chip.run(2)
        assert chip.get("axis1.velocity") == pytest.approx(1 / 250e-6)  # 1 count/cycle, in counts/s of the new cycle
        with pytest.raises(PMDError):
            ax.SetSampleTime(0)


def test_trace_starts_on_a_signal_bit_and_stops_on_an_event_bit(chip):
    ax = chip.axis(0)
    setup_trace(ax, 60)
    # start when axis 3's home input is active (reads 0), stop at axis 3's breakpoint 1 event
    ax.SetTraceStart(2, pmdfmu.PMDTraceConditionSignalStatus, bit("PMDSignalEncoderHome"), PMDTraceTriggerStateLow)
    ax.SetTraceStop(2, pmdfmu.PMDTraceConditionEventStatus, bit("PMDEventBreakpoint1"), PMDTraceTriggerStateHigh)
    chip.axis(2).SetBreakpointValue(pmdfmu.PMDBreakpoint1, 20)
    chip.axis(2).SetBreakpoint(pmdfmu.PMDBreakpoint1, 2, pmdfmu.PMDBreakpointNoAction, pmdfmu.PMDBreakpointTime)
    chip.run(5)
    assert ax.GetTraceStatus() == 0
    chip.set("axis3.home", True)
    chip.run(5)  # chip times 5..9: sampled from 5 on
    assert ax.GetTraceStatus() == PMDTraceStatusActivity
    chip.run(20)  # the breakpoint fires at chip time 20
    assert ax.GetTraceStatus() == 0 and ax.GetTraceCount() == 3 * 16
    assert [s[0] for s in read_samples(ax, 48)] == list(range(5, 21))


def test_every_trajectory_side_trace_variable_samples_what_the_get_commands_read():
    """Reference 2.6: IDs 1..27 (7, 10, 11: the servo filter's motor command, integral and derivative;
    15..19 the commutator's phase angle, offset and phase commands; 20..27 the analog inputs 1..8),
    four per trace, one sample each."""
    with pmdfmu.Chip(loopback=False) as chip:
        ax, a2 = chip.axis(0), chip.axis(1)
        ax.SetBufferStart(0, 0x100)
        ax.SetBufferLength(0, 64)
        a2.SetCaptureSource(pmdfmu.PMDCaptureSourceHome)
        chip.set("axis2.home", True)  # captured in the first cycle
        chip.set("axis2.actualPosition", 77)
        a2.SetProfileMode(pmdfmu.PMDVelocityContouringProfile)
        a2.SetVelocity(-0x28000)
        a2.SetAcceleration(0x8000)
        a2.Update()
        a2.SetPhaseAngle(0x1234)
        a2.SetPhaseOffset(0x0321)
        a2.SetMotorMode(pmdfmu.PMDMotorOff)  # phase A carries the open-loop motor command
        a2.SetMotorCommand(-2345)
        a2.Update()  # the motor command is in the filter group
        chip.set("analog", [100 * (i + 1) + i for i in range(8)])
        chip.run(3)
        ids = list(range(1, 28))
        seen = {}
        for first in range(0, len(ids), 4):
            group = ids[first : first + 4]
            for slot in range(4):
                ax.SetTraceVariable(slot, 1, group[slot] if slot < len(group) else 0)
            ax.SetTraceStart(0, PMDTraceConditionImmediate, 0, 0)
            chip.run(1)  # one sample, at the end of this cycle
            ax.SetTraceStop(0, PMDTraceConditionImmediate, 0, 0)
            sampled = [pmdfmu.signed(ax.ReadBuffer(0)) for _ in group]
            reads = {
                1: a2.GetPositionError,
                2: a2.GetCommandedPosition,
                3: a2.GetCommandedVelocity,
                4: a2.GetCommandedAcceleration,
                5: a2.GetActualPosition,
                6: a2.GetActualVelocity,
                7: a2.GetCurrentMotorCommand,
                8: a2.GetTime,
                10: a2.GetIntegral,
                11: a2.GetDerivative,
                12: a2.GetEventStatus,
                13: a2.GetActivityStatus,
                14: a2.GetSignalStatus,
                15: a2.GetPhaseAngle,
                16: a2.GetPhaseOffset,
                **{17 + p: (lambda p=p: a2.GetPhaseCommand(p)) for p in range(3)},
                **{20 + i: (lambda i=i: chip.get(f"analog[{i + 1}]")) for i in range(8)},
                9: lambda: 77,
            }  # the capture value (not read: reading re-arms it)
            assert sampled == [reads[v]() for v in group], group
            seen.update(zip(group, sampled))
        assert (seen[15], seen[16], seen[17], seen[18], seen[20], seen[27]) == (0x1234, 0x0321, -2345, 0, 100, 807)
