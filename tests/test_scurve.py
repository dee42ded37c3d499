# SPDX-License-Identifier: BSD-2-Clause
"""S-curve point-to-point (seed 001: jerk-limited, phases I-VII, symmetric)."""

import random
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from pmdfmu import PMDActivityInMotionMask, PMDError, PMDSCurveProfile, PMDSmoothStop, field_ex

NAMES = [
    "axis1.commandedPosition",
    "axis1.commandedVelocity",
    "axis1.commandedAcceleration",
    "axis1.activityStatus",
    "axis1.position",
]


def scurve(chip, position, velocity, acceleration, jerk, cycles):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDSCurveProfile)
    ax.SetPosition(position)
    ax.SetVelocity(velocity)
    ax.SetAcceleration(acceleration)
    ax.SetJerk(jerk)
    ax.Update()
    return chip.run(cycles, record=NAMES)


def moving(rec):
    return (rec["axis1.activityStatus"] & PMDActivityInMotionMask) != 0


@pytest.mark.parametrize("seed", range(10))
def test_moves_land_exactly_and_respect_velocity_acceleration_and_jerk(chip, seed):
    rng = random.Random(seed)
    start = rng.randrange(-5000, 5000)
    if start:
        scurve(chip, start, 0x100000, 0x10000, 0x10000000, 2000)
    dest = start + rng.choice([1, -1]) * rng.choice([1, 7, rng.randrange(10, 100_000)])
    v, a, j = rng.randrange(0x1000, 0x200000), rng.randrange(0x10, 0x8000), rng.randrange(0x1000, 0x4000000)
    rec = scurve(chip, dest, v, a, j, 60_000)
    ax = chip.axis(0)
    assert not moving(rec)[-1], "the move did not finish"
    assert ax.GetCommandedPosition() == dest and chip.get("axis1.position") == dest
    assert ax.GetCommandedVelocity() == 0 and ax.GetCommandedAcceleration() == 0
    run = rec[moving(rec)]
    assert (np.abs(run["axis1.commandedVelocity"]) <= v).all()
    assert (np.abs(run["axis1.commandedAcceleration"]) <= a).all()
    acc = np.concatenate([[0], run["axis1.commandedAcceleration"], [0]])
    assert (np.abs(np.diff(acc)) <= j // 65536 + 1).all(), "jerk exceeded"
    p = rec["axis1.position"]
    assert (np.diff(p) * np.sign(dest - start) >= 0).all()


def test_phases_i_to_vii_show_in_the_profile_segment_and_the_curve_is_symmetric(chip):
    rec = scurve(chip, 20_000, 0x40000, 0x400, 0x1000000, 20_000)
    run = rec[moving(rec)]
    phases = field_ex(run["axis1.activityStatus"], "PMDActivityProfileSegment")
    assert list(dict.fromkeys(phases)) == [1, 2, 3, 4, 5, 6, 7]
    assert (np.diff(phases) >= 0).all()
    assert (field_ex(rec["axis1.activityStatus"][len(run) :], "PMDActivityProfileSegment") == 0).all()
    v = run["axis1.commandedVelocity"]  # cycles 1 .. T-1; cycle T ends at rest
    assert np.array_equal(v, v[::-1])  # V(k) = V(T - k)
    assert (run["axis1.commandedVelocity"][phases == 4] == run["axis1.commandedVelocity"][phases == 4][0]).all()


def test_duration_is_close_to_the_continuous_optimum(chip):
    d, v, a, j = 50_000, 4.0, 1 / 64, 1 / 2**14
    rec = scurve(chip, d, int(v * 65536), int(a * 65536), int(j * 2**32), 20_000)
    t1, t2 = a / j, v / a - a / j
    optimum = d / v + 2 * t1 + t2
    cycles = moving(rec).sum() + 1  # the last cycle lands and clears InMotion
    assert optimum <= cycles <= optimum + 4


def test_parameters_may_not_change_during_the_move(chip):
    scurve(chip, 100_000, 0x40000, 0x400, 0x1000000, 100)
    ax = chip.axis(0)
    ax.Update()  # nothing changed: fine
    ax.SetVelocity(0x50000)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0C
    ax.SetVelocity(0x40000)
    ax.SetPosition(5)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0C


def test_smooth_stop_decelerates_jerk_limited_to_rest_short_of_the_destination(chip):
    rec = scurve(chip, 100_000, 0x40000, 0x400, 0x1000000, 2000)
    ax = chip.axis(0)
    assert field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment") == 4
    ax.SetStopMode(PMDSmoothStop)
    ax.Update()
    rec = chip.run(2000, record=NAMES)
    assert not moving(rec)[-1]
    assert 0 < ax.GetCommandedPosition() < 100_000 and ax.GetCommandedVelocity() == 0
    acc = rec["axis1.commandedAcceleration"]
    assert (np.abs(np.diff(acc)) <= 0x1000000 // 65536 + 1).all()
    assert (np.abs(acc) <= 0x400).all()


def test_negative_velocity_and_zero_limits_are_refused(chip):
    ax = chip.axis(0)
    ax.SetProfileMode(PMDSCurveProfile)
    ax.SetPosition(100)
    ax.SetVelocity(-1)
    with pytest.raises(PMDError) as e:
        ax.Update()
    assert e.value.code == 0x0B
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x100)
    with pytest.raises(PMDError) as e:
        ax.Update()  # jerk 0: no S-curve
    assert e.value.code == 0x04


@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
def test_portable_128_bit_arithmetic_agrees_with_the_native_one(tmp_path):
    src = Path(__file__).resolve().parent.parent / "fmu_src" / "chip"
    program = tmp_path / "wide_test.c"
    program.write_text(r"""
#include <inttypes.h>
#include <stdio.h>
#include "wide.h"
static uint64_t next(uint64_t *s) { *s ^= *s << 13; *s ^= *s >> 7; *s ^= *s << 17; return *s; }
int main(void) {
    uint64_t s = 88172645463325252u;
    for (int i = 0; i < 200000; i++) {
        uint64_t a = next(&s), b = next(&s) >> (i % 64), c = (next(&s) >> (i % 63)) | 1, r, q;
        PmdU128 p = pmd_mul64(a, b);
        if (p.hi >= c)
            continue;
        q = pmd_div128(p, c, &r);
        printf("%" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 "\n", p.hi, p.lo, q, r);
    }
    return 0;
}
""")
    outputs = []
    for flags in ([], ["-DPMD_PORTABLE_WIDE"]):
        exe = tmp_path / f"wide{len(flags)}"
        subprocess.run(
            [
                "cc",
                "-std=c99",
                "-O1",
                "-Wall",
                "-Wextra",
                "-Wpedantic",
                "-Werror",
                *flags,
                f"-I{src}",
                str(program),
                "-o",
                str(exe),
            ],
            check=True,
        )
        outputs.append(subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout)
    assert outputs[0] == outputs[1] and outputs[0].count("\n") > 1000
