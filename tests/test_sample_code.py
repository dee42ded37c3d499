# SPDX-License-Identifier: BSD-2-Clause
"""Seed 000's sample code, sections 1.1-1.6, transcribed line by line.

The seed's set-up loop computes buffer_start = memory_start + axis*variable*
buffer_length, so its buffers overlap (axis 1's five buffers all start at
0x200, and so does axis 2's position buffer). The chip does what it is told;
so do we. Each axis's profile is checked against the reference model over
the memory the seed's writes really leave behind."""

import pytest

from pmdfmu import (
    PMDAbruptStop,
    PMDActivityInMotionMask,
    PMDAxis1,
    PMDAxis1Mask,
    PMDAxis2Mask,
    PMDAxis3Mask,
    PMDBreakpoint1,
    PMDBreakpointActivityStatus,
    PMDBreakpointNoAction,
    PMDBufferFunctionPosition,
    PMDBufferFunctionTime,
    PMDEventBreakpoint1Mask,
    PMDExternalProfile,
    PMDTrapezoidal,
    field_ex,
)
from reference import ExternalProfile

num_variables = 5
max_vel = 0x20000  # 2 counts/cycle
max_acc = 0x800  # 1/32 count/cycle^2
SEGMENT_CYCLES = 256


def make_data(num_axes):
    """data[axis][variable][index]: constant-velocity legs between positive
    waypoints, back to 0, then a time-0 row that ends the profile. Velocity
    d*65536/256 is exact, so each leg lands on its waypoint."""
    data = []
    for axis in range(num_axes):
        waypoints = [400 * (axis + 1), 1200 + 100 * axis, 800, 1600 - 200 * axis, 0]
        rows = [
            (p, (q - p) * 65536 // SEGMENT_CYCLES, 0, 0, SEGMENT_CYCLES) for p, q in zip(waypoints, waypoints[1:])
        ] + [(0, 0, 0, 0, 0)]
        data.append([[row[v] for row in rows] for v in range(num_variables)])
    return data


def seed_setup(hAxis, num_axes):
    """Section 1.1, verbatim."""
    final_variable = PMDBufferFunctionTime
    memory_start = 0x200  # first 1Kx16 reserved by motion processor
    memory_size = 0x4000  # 16Kx32
    buffer_id = 2  # ID 0 is reserved for the trace buffer, ID 1 is also used as a read index
    buffer_start = memory_start
    buffer_length = (memory_size - memory_start) // (num_axes * num_variables)
    for axis in range(num_axes):
        for variable in range(final_variable + 1):
            buffer_start = memory_start + (axis * variable * buffer_length)
            hAxis[axis].SetBufferStart(buffer_id, buffer_start)
            hAxis[axis].SetBufferLength(buffer_id, buffer_length)
            # assign a trajectory variable to the buffer
            hAxis[axis].SetBufferFunction(variable, buffer_id)
            buffer_id += 1
    return memory_start, buffer_length


def seed_populate(hAxis, num_axes, data):
    """Section 1.3, verbatim: WriteBuffer."""
    num_data_entries = len(data[0][0])
    for axis in range(num_axes):
        for variable in range(num_variables):
            for index in range(num_data_entries):
                # the buffer_id starts at 2
                buffer_id = 2 + (axis * num_variables) + variable
                hAxis[axis].WriteBuffer(buffer_id, data[axis][variable][index])


def memory_after_writes(num_axes, data, memory_start, buffer_length):
    """What the writes of 1.3 leave in memory, replayed independently of the chip."""
    memory = {}
    for axis in range(num_axes):
        for variable in range(num_variables):
            start = memory_start + axis * variable * buffer_length
            for index, value in enumerate(data[axis][variable]):
                memory[start + index] = value
    return memory


def expected_profile(axis, memory, memory_start, buffer_length):
    starts = [memory_start + axis * v * buffer_length for v in range(num_variables)]
    rows = [tuple(memory.get(s + i, 0) for s in starts) for i in range(buffer_length)]
    return ExternalProfile(rows)


def seed_initial_moves(hAxis, num_axes, data):
    """Section 1.4: move each axis to its starting location."""
    for axis in range(num_axes):
        hAxis[axis].SetProfileMode(PMDTrapezoidal)
        hAxis[axis].SetVelocity(max_vel)
        hAxis[axis].SetAcceleration(max_acc)
        hAxis[axis].SetPosition(data[axis][PMDBufferFunctionPosition][0])
        hAxis[axis].Update()


def seed_start(hAxis, num_axes):
    """Section 1.4: synchronized start with MultiUpdate."""
    masks = [PMDAxis1Mask, PMDAxis2Mask, PMDAxis3Mask]
    for axis in range(num_axes):
        hAxis[axis].SetProfileMode(PMDExternalProfile)
    # the mask selects which axis is updated
    hAxis[PMDAxis1].MultiUpdate(sum(masks[:num_axes]))


def wait_at_rest(chip, hAxis, num_axes):
    while any(hAxis[a].GetActivityStatus() & PMDActivityInMotionMask for a in range(num_axes)):
        chip.run(64)


def recorded_names(num_axes):
    return [
        f"axis{a + 1}.{q}"
        for a in range(num_axes)
        for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration", "activityStatus")
    ] + ["host.interrupt", "axis1.eventStatus"]


@pytest.mark.parametrize("num_axes", [2, 3])
def test_seed_sample_code_runs_as_the_chip_would(any_chip, num_axes):
    chip = any_chip
    hAxis = [chip.axis(n) for n in range(4)]
    data = make_data(num_axes)
    memory_start, buffer_length = seed_setup(hAxis, num_axes)
    # the seed's loop really does make the buffers overlap: emulated, not fixed
    assert [hAxis[0].GetBufferStart(b) for b in range(2, 7)] == [0x200] * 5
    assert hAxis[0].GetBufferStart(7) == 0x200
    seed_populate(hAxis, num_axes, data)

    # 1.3: the read/write indexes of the position buffer (buffer #2) of axis 1
    readindex = hAxis[PMDAxis1].GetBufferReadIndex(2)
    writeindex = hAxis[PMDAxis1].GetBufferWriteIndex(2)
    assert (readindex, writeindex) == (0, len(data[0][0]))

    # 1.4: the initial trapezoidal moves land exactly on the first table entries, at rest
    seed_initial_moves(hAxis, num_axes, data)
    wait_at_rest(chip, hAxis, num_axes)
    for axis in range(num_axes):
        assert hAxis[axis].GetCommandedPosition() == data[axis][PMDBufferFunctionPosition][0]
        assert hAxis[axis].GetCommandedVelocity() == 0

    seed_start(hAxis, num_axes)
    # 1.6: a breakpoint on the profile segment number raises the interrupt at completion
    axis = PMDAxis1
    hAxis[PMDAxis1].SetInterruptMask(PMDEventBreakpoint1Mask)
    # the seed's own words: 0x2000 selects bit 13, the lowest bit of the profile segment number
    # (PMDActivityProfileSegmentMask), with sense 0
    hAxis[PMDAxis1].SetBreakpointValue(PMDBreakpoint1, (0x2000 << 16) | 0x0000)
    hAxis[PMDAxis1].SetBreakpoint(PMDBreakpoint1, axis, PMDBreakpointNoAction, PMDBreakpointActivityStatus)

    first_cycle = chip.cycles
    rec = chip.run(12000, record=recorded_names(num_axes))
    memory = memory_after_writes(num_axes, data, memory_start, buffer_length)
    for a in range(num_axes):
        model = expected_profile(a, memory, memory_start, buffer_length)
        got = list(
            zip(
                rec[f"axis{a + 1}.commandedPosition"],
                rec[f"axis{a + 1}.commandedVelocity"],
                rec[f"axis{a + 1}.commandedAcceleration"],
            )
        )
        assert got == model.run(len(rec)), f"axis {a + 1}"

    # the last axis's table is where the seed meant it to be: it runs its legs exactly
    last = num_axes - 1
    positions = rec[f"axis{last + 1}.commandedPosition"]
    for k, p in enumerate(data[last][PMDBufferFunctionPosition][:-1]):
        assert positions[k * SEGMENT_CYCLES] == p

    # synchronized start: every axis reads its first segment in the first cycle, and
    # runs on (segment number 1) unless the time it read there is 0
    assert rec["cycle"][0] == first_cycle
    for a in range(num_axes):
        first_time = expected_profile(a, memory, memory_start, buffer_length).rows[0][PMDBufferFunctionTime]
        assert field_ex(rec[f"axis{a + 1}.activityStatus"][0], "PMDActivityProfileSegment") == (1 if first_time else 0)

    # completion of axis 1: segment number 0 and the interrupt in the same cycle, once
    done = int((field_ex(rec["axis1.activityStatus"], "PMDActivityProfileSegment") == 0).argmax())
    assert done > 0
    assert not rec["host.interrupt"][:done].any() and rec["host.interrupt"][done:].all()
    assert rec["axis1.eventStatus"][done] & PMDEventBreakpoint1Mask
    assert hAxis[PMDAxis1].GetBreakpoint(PMDBreakpoint1)[2] == 0  # trigger disarmed after firing
    hAxis[PMDAxis1].ResetEventStatus(~PMDEventBreakpoint1Mask)
    chip.run(100)
    assert not chip.get("host.interrupt")  # fired once: no new event


@pytest.mark.parametrize("num_axes", [2, 3])
def test_seed_abrupt_stop_halts_all_axes_in_one_cycle(any_chip, num_axes):
    chip = any_chip
    hAxis = [chip.axis(n) for n in range(4)]
    data = make_data(num_axes)
    seed_setup(hAxis, num_axes)
    seed_populate(hAxis, num_axes, data)
    seed_initial_moves(hAxis, num_axes, data)
    wait_at_rest(chip, hAxis, num_axes)
    seed_start(hAxis, num_axes)
    chip.run(300)
    held = [hAxis[a].GetCommandedPosition() for a in range(num_axes)]

    # 1.5: synchronized stop
    masks = [PMDAxis1Mask, PMDAxis2Mask, PMDAxis3Mask]
    for a in range(num_axes):
        hAxis[a].SetStopMode(PMDAbruptStop)
    hAxis[PMDAxis1].MultiUpdate(sum(masks[:num_axes]))

    rec = chip.run(50, record=recorded_names(num_axes))
    for a in range(num_axes):
        assert (rec[f"axis{a + 1}.commandedPosition"] == held[a]).all()
        assert (rec[f"axis{a + 1}.commandedVelocity"] == 0).all()
        assert (rec[f"axis{a + 1}.commandedAcceleration"] == 0).all()
        assert (field_ex(rec[f"axis{a + 1}.activityStatus"], "PMDActivityProfileSegment") == 0).all()
        assert hAxis[a].GetStopMode() == 0  # the stop mode resets itself after the Update
