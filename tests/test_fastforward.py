# SPDX-License-Identifier: BSD-2-Clause
"""Coarse doSteps fast-forward through external-profile segments in closed form;
the result is bit-identical to stepping cycle by cycle."""

import random

import pmdfmu
from pmdfmu import PMDActivityAxisSettledMask, PMDEventMotionCompleteMask, field_ex
from pmdfmu.profile import load_external_profile, start_external_profile
from reference import wrap32
from scenarios import REAL, load_random_profiles

OUT = [
    f"axis{n}.{q}"
    for n in range(1, 5)
    for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration", "activityStatus", "eventStatus")
]


def snapshot(chip):
    return [chip.get(n) for n in OUT + REAL + ["chipTime"]]


def test_coarse_steps_equal_cycle_by_cycle_at_every_step_boundary():
    """Segments with jerk, velocities coming to rest inside segments (motion-complete
    events), an idle axis; uneven doSteps against one doStep per cycle."""
    for seed in range(3):
        rng = random.Random(seed)
        with pmdfmu.Chip() as fine, pmdfmu.Chip() as coarse:
            load_random_profiles(fine, random.Random(seed))
            load_random_profiles(coarse, random.Random(seed))
            total = 0
            for _ in range(12):
                n = rng.randrange(1, 4000)
                rec = fine.run(n, record=OUT)
                coarse.run(n)  # one doStep: fast-forwards
                total += n
                assert snapshot(coarse)[: len(OUT)] == [int(rec[name][-1]) for name in OUT]
                assert snapshot(coarse) == snapshot(fine)
                for chip in (fine, coarse):  # events are sticky: judge each chunk alone
                    for axis in range(4):
                        chip.axis(axis).ResetEventStatus(0)


def test_a_billion_cycles_of_a_100_segment_table_take_one_coarse_step_and_stay_exact():
    segments = [(0, 0x10000, 0, 0, 10_000_000) for _ in range(100)] + [(7, 0, 0, 0, 0)]
    segments[50] = (segments[50][0], 0x8000, -2, 1, 10_000_000)
    with pmdfmu.Chip() as chip:
        ax = chip.axis(0)
        load_external_profile(chip, {0: segments})
        start_external_profile(chip, [0])
        chip.run(10**9 - 1)
        # segment 99 (velocity 1 count/cycle from position 0) has run 9_999_999 of its cycles
        assert ax.GetCommandedPosition() == wrap32(9_999_999 - 1)
        assert ax.GetTime() == 10**9 - 2
        chip.run(2)
        assert ax.GetCommandedPosition() == 7 and field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 0


def test_idle_axes_settle_at_the_same_cycle_in_coarse_steps():
    """The idle path: the settle count grows while fast-forwarding, as it would cycle by cycle."""
    seen = []
    for coarse in (False, True):
        with pmdfmu.Chip() as chip:
            ax = chip.axis(0)
            ax.SetSettleTime(500)
            ax.SetSettleWindow(3)
            ax.SetMotionCompleteMode(pmdfmu.PMDMotionCompleteActualPosition)
            ax.SetPosition(100)
            ax.SetVelocity(0x10000)
            ax.SetAcceleration(0x10000)
            ax.Update()
            if coarse:
                bits = []
                for _ in range(20):
                    chip.run(97)
                    bits.append(
                        (
                            ax.GetActivityStatus() & PMDActivityAxisSettledMask,
                            ax.GetEventStatus() & PMDEventMotionCompleteMask,
                        )
                    )
            else:
                rec = chip.run(97 * 20, record=["axis1.activityStatus", "axis1.eventStatus"])
                bits = [
                    (int(a) & PMDActivityAxisSettledMask, int(e) & PMDEventMotionCompleteMask)
                    for a, e in zip(rec["axis1.activityStatus"][96::97], rec["axis1.eventStatus"][96::97])
                ]
            seen.append(bits)
    assert seen[0] == seen[1] and (PMDActivityAxisSettledMask, PMDEventMotionCompleteMask) in seen[0]
    assert seen[0][0] == (0, 0)
