# SPDX-License-Identifier: BSD-2-Clause
"""CONTRACT 2.3 at the edges of the formats: every value seed
000's formats allow (position 32.0, velocity and acceleration 16.16, jerk 0.32,
time 32-bit unsigned), for any segment time up to 2^32-1, gives the exact
recurrence P += V + A/2 + J/6; V += A + J/2; A += J, truncated toward minus
infinity and wrapped into the 32-bit registers - and the electronic gear moves
the slave by exactly delta * ratio at any ratio and master jump. Through the
real FMU, FMI 2 and FMI 3; run with the sanitizer build (./dev sanitize) these
are also the regression tests for the undefined behaviour the review found."""

import random
import shutil
import subprocess
import zipfile
from fractions import Fraction
from math import floor
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import (
    PMDElectronicGearProfile,
    PMDEventMotionCompleteMask,
    PMDPositionSourceActual,
    PMDPositionSourceCommanded,
    PMDVelocityContouringProfile,
    field_ex,
)
from pmdfmu.profile import load_external_profile, start_external_profile
from reference import ExternalProfile, wrap32

FMI = pytest.mark.parametrize("fmi", [2, 3], ids=["fmi2", "fmi3"])
MIN32, MAX32 = 0x80000000, 0x7FFFFFFF  # the extreme raw words (0x80000000 reads -2^31)
OUT = ["commandedPosition", "commandedVelocity", "commandedAcceleration"]


def names(axis=0):
    return [f"axis{axis + 1}.{q}" for q in OUT]


class Segment:
    """One external-profile row in closed form, independent of the C core's
    representation: after n integration steps from the row's raw values,
        P = p + n V + n^2 A/2 + n^3 J/6,   V = V0 + n A0 + n^2 J/2,   A = A0 + n J
    with V0, A0 = v/2^16, a/2^16 and J = j/2^32 (test_closed_form_is_the_seeds_recurrence
    checks this against the seed's pseudo code). Exact in integers over the
    common denominator D = 6 * 2^32."""

    D = 6 << 32

    def __init__(self, p, v, a, j):
        self.p, self.v, self.a, self.j = wrap32(p), wrap32(v), wrap32(a), wrap32(j)

    def exact(self, n):
        """P, V, A after n steps, as integers over D."""
        d, v, a, j = self.D, self.v * 6 << 16, self.a * 6 << 16, self.j
        return (self.p * d + n * v + n * n * a // 2 + n**3 * j, v + n * a + 3 * j * n * n, a + 6 * j * n)

    def registers(self, n):
        P, V, A = self.exact(n)
        return wrap32(P // self.D), wrap32(V // (6 << 16)), wrap32(A // (6 << 16))

    def reals(self, n, cycle_time):
        """axisN.position, .velocity, .acceleration: the exact values, the position's whole counts wrapped."""
        P, V, A = self.exact(n)
        whole = P // self.D
        return (
            wrap32(whole) + (P - whole * self.D) / self.D,
            Fraction(V, self.D) / Fraction(cycle_time),
            Fraction(A, self.D) / Fraction(cycle_time) ** 2,
        )


def start_segment(chip, row, then=(0, 0, 0, 0, 0)):
    """Axis 1 runs `row` (position, velocity, acceleration, jerk, time) then `then`."""
    load_external_profile(chip, {0: [row, then]})
    start_external_profile(chip, [0])


def recorded(chip, cycles, axis=0):
    rec = chip.run(cycles, record=names(axis))
    return [tuple(int(x) for x in r) for r in zip(*(rec[n] for n in names(axis)))]


def registers_now(chip, axis=0):
    return tuple(int(chip.get(n)) for n in names(axis))


# ---- the closed form is the seed's recurrence ---------------------------------------


@pytest.mark.parametrize(
    "row",
    [
        (5, MIN32, MAX32, MAX32),
        (-7, MAX32, MIN32, MIN32),
        (0, 0xE0000000, 0x40000000, 0),
        (MAX32, 0x12345678, 0xFEDCBA98, 0x9E3779B9),
    ],
)
def test_closed_form_is_the_seeds_recurrence(row):
    model = ExternalProfile([row + (400,), (0, 0, 0, 0, 0)])
    assert model.run(400) == [Segment(*row).registers(n) for n in range(400)]


# ---- the review's findings, every cycle ---------------------------------------------

FINDINGS = {
    # signed overflow in move_by (profile.c); the velocity register departed at cycle 21846
    "v=0xE0000000 a=0x40000000 70000 cycles": ((0, 0xE0000000, 0x40000000, 0), 70000),
    # the 64-bit velocity wrapped: departed from the recurrence at cycle 10923
    "a=0x7FFFFFFF 11500 cycles": ((0, 0, MAX32, 0), 11500),
    # the same through the jerk: departed at cycle 37838
    "j=0x7FFFFFFF 38500 cycles": ((0, 0, 0, MAX32), 38500),
}


@FMI
@pytest.mark.parametrize("finding", FINDINGS)
def test_review_findings_follow_the_exact_recurrence_every_cycle(fmi, finding):
    row, time = FINDINGS[finding]
    seg = Segment(*row)
    with pmdfmu.Chip(fmi_version=fmi) as chip:
        start_segment(chip, row + (time,), then=(123, 0, 0, 0, 0))
        out = recorded(chip, time + 3)
    assert out[:time] == [seg.registers(n) for n in range(time)]
    assert out[time:] == [(123, 0, 0)] * 3  # the next row read: time 0, held


# ---- the Reals, bit for bit -----------------------------------------------------------


def documented_reals(seg, n, cycle_time):
    """axisN.position, .velocity, .acceleration as the FMU computes its doubles (status.c,
    pmd_commanded_reals): the position's whole counts plus its fraction divided by U = D; a
    velocity or acceleration X in U divided by U where it fits an int64 (X converted first,
    rounded beyond 2^53), else whole counts plus the fraction in 2^-33; then divided by the
    cycle time (squared)."""
    P, V, A = seg.exact(n)
    D = seg.D
    whole = P // D

    def counts(x):
        if -(1 << 63) <= x < 1 << 63:
            return float(x) / float(D)
        c = x // D
        return float(c) + float((x - c * D) // 3) / 2**33

    return (float(wrap32(whole)) + (P - whole * D) / D, counts(V) / cycle_time, counts(A) / (cycle_time * cycle_time))


@FMI
def test_the_reals_of_every_axis_are_the_documented_doubles_bit_for_bit(fmi):
    """Four axes at once (the four lanes of pmd_commanded_reals' packed divisions), recorded in bulk
    and read by the getters: velocities and accelerations from 0 through 2^53 in U (rounded before
    the division) to beyond an int64 in U (whole counts plus fraction), both signs."""
    rows = {
        0: (0, 0, MAX32, 0),
        1: (5, 0xE0000000, 0x40000000, 0),
        2: (-7, MAX32, MIN32, MIN32),
        3: (MAX32, 0x12345678, 0xFEDCBA98, 0x9E3779B9),
    }
    time = 11500  # axis 1's velocity passes 2^31/6 counts/cycle
    segments = {axis: Segment(*row) for axis, row in rows.items()}
    names = [f"axis{axis + 1}.{q}" for axis in rows for q in ("position", "velocity", "acceleration")]
    with pmdfmu.Chip(fmi_version=fmi) as chip:
        cycle_time = chip.cycle_time
        load_external_profile(chip, {axis: [row + (time,), (0, 0, 0, 0, 0)] for axis, row in rows.items()})
        start_external_profile(chip, list(rows))
        rec = chip.run(time - 1, record=names)
        for axis, seg in segments.items():
            expected = np.array([documented_reals(seg, n, cycle_time) for n in range(time - 1)])
            for k, q in enumerate(("position", "velocity", "acceleration")):
                column = rec[f"axis{axis + 1}.{q}"]
                assert column.tobytes() == expected[:, k].tobytes(), (axis, q)
            assert [chip.get(f"axis{axis + 1}.{q}") for q in ("position", "velocity", "acceleration")] == list(
                expected[-1]
            )
        velocity = abs(segments[0].exact(time - 2)[1])
        assert velocity >= 1 << 63 and any(abs(s.exact(0)[1]) < 1 << 53 for s in segments.values())


@FMI
def test_the_reals_past_an_int64_in_u_are_the_documented_doubles_bit_for_bit(fmi):
    """After 10^9 cycles at the greatest jerk (a coarse doStep: the closed form) the acceleration, too,
    is past an int64 in U on two lanes: recorded in bulk, every lane as documented."""
    rows = {0: (0, 0, 0, MAX32), 1: (0, 0, 0, MIN32), 2: (1, 0x10000, 0, 0), 3: (-1, 0, 0x10000, 1)}
    segments = {axis: Segment(*row) for axis, row in rows.items()}
    names = [f"axis{axis + 1}.{q}" for axis in rows for q in ("position", "velocity", "acceleration")]
    start = 10**9
    with pmdfmu.Chip(fmi_version=fmi) as chip:
        cycle_time = chip.cycle_time
        load_external_profile(chip, {axis: [row + (LONGEST,), (0, 0, 0, 0, 0)] for axis, row in rows.items()})
        start_external_profile(chip, list(rows))
        chip.run(start)
        rec = chip.run(50, record=names)
    for axis, seg in segments.items():
        expected = np.array([documented_reals(seg, n, cycle_time) for n in range(start, start + 50)])
        for k, q in enumerate(("position", "velocity", "acceleration")):
            assert rec[f"axis{axis + 1}.{q}"].tobytes() == expected[:, k].tobytes(), (axis, q)
    assert all(abs(segments[axis].exact(start)[2]) >= 1 << 63 for axis in (0, 1))


@pytest.mark.slow
@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
def test_every_form_of_the_reals_is_the_scalar_expressions(tmp_path):
    """pmd_commanded_reals' forms - pairs of vectors (SSE2, NEON) and plain C (PMD_PORTABLE_LANES, as a
    compiler without vectors builds it) - against the scalar expressions the
    getters had before them, over random and boundary states: the FMU's own sources (its sources/)."""
    with zipfile.ZipFile(pmdfmu.default_fmu(2)) as fmu:
        for name in fmu.namelist():
            if name.startswith("sources/") and not name.endswith("/"):
                (tmp_path / Path(name).name).write_bytes(fmu.read(name))
    program = tmp_path / "reals_forms.c"
    program.write_text(REALS_FORMS)
    for flags in ([], ["-DPMD_PORTABLE_LANES"]):
        exe = tmp_path / f"reals{len(flags)}"
        subprocess.run(
            ["cc", "-std=gnu99", "-O2", "-Wall", "-Werror", *flags, f"-I{tmp_path}", str(program), "-o", str(exe)],
            check=True,
        )
        out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout
        assert out.startswith("differ 0 of ") and int(out.split()[3]) > 10**6, out


# status.c included whole: its static forms are this program's; the reference is 0505d1e's pmd_fixed_double
REALS_FORMS = r"""
#include <stdio.h>
#include <string.h>
#include "status.c"
static double scalar_counts(PmdFixed x)
{
    const int64_t most = INT64_MAX / PMD_U_PER_COUNT;
    int64_t rest = 3 * x.fraction;
    if (x.counts >= 0 && x.counts <= most && x.counts * PMD_U_PER_COUNT <= INT64_MAX - rest)
        return (double)(x.counts * PMD_U_PER_COUNT + rest) / (double)PMD_U_PER_COUNT;
    if (x.counts < 0 && x.counts >= -most - 1 &&
        (x.counts + 1) * PMD_U_PER_COUNT >= INT64_MIN + (PMD_U_PER_COUNT - rest))
        return (double)((x.counts + 1) * PMD_U_PER_COUNT + (rest - PMD_U_PER_COUNT)) / (double)PMD_U_PER_COUNT;
    return (double)x.counts + (double)x.fraction / (double)PMD_FIXED_ONE;
}
static uint64_t seed = 88172645463325252u;
static uint64_t next(void) { seed ^= seed << 13; seed ^= seed >> 7; seed ^= seed << 17; return seed; }
static PmdFixed pick(void)
{
    const int64_t most = INT64_MAX / PMD_U_PER_COUNT;
    PmdFixed x;
    switch (next() % 6) {
    case 0: x.counts = (int64_t)next(); break;
    case 1: x.counts = most + (int64_t)(next() % 5) - 2; break;
    case 2: x.counts = -most - 1 + (int64_t)(next() % 5) - 2; break;
    case 3: x.counts = (int64_t)(next() % 2000001) - 1000000; break;
    case 4: x.counts = (next() & 1) ? INT64_MAX - (int64_t)(next() % 3) : INT64_MIN + (int64_t)(next() % 3); break;
    default: x.counts = (int64_t)(next() >> (next() % 64)) * ((next() & 1) ? 1 : -1); break;
    }
    x.fraction = (int64_t)(next() % 4 == 0 ? (next() & 1) * (PMD_FIXED_ONE - 1) : next() % PMD_FIXED_ONE);
    return x;
}
static long compare(const PmdCommandedReals *r, const PmdChip *chip, double ct)
{
    long bad = 0;
    int n;
    for (n = 0; n < PMD_AXES; n++) {
        const PmdTrajectory *t = &chip->s.axis[n].trajectory;
        double p = (double)t->position + (double)t->fraction / (double)PMD_U_PER_COUNT;
        double v = scalar_counts(t->velocity) / ct, a = scalar_counts(t->acceleration) / (ct * ct);
        bad += memcmp(&p, &r->position[n], 8) != 0 || memcmp(&v, &r->velocity[n], 8) != 0 ||
               memcmp(&a, &r->acceleration[n], 8) != 0;
    }
    return bad;
}
int main(void)
{
    static PmdChip chip;
    const double cycleTimes[] = {1e-4, 1e-6, 0.065535, 3e-5, 1.7e-5};
    long bad = 0, checked = 0, i;
    int n;
    for (i = 0; i < 300000; i++) {
        PmdCommandedReals r;
        double ct = cycleTimes[i % 5];
        for (n = 0; n < PMD_AXES; n++) {
            PmdTrajectory *t = &chip.s.axis[n].trajectory;
            t->position = (int32_t)(uint32_t)next();
            t->fraction = (int64_t)(next() % (uint64_t)PMD_U_PER_COUNT);
            t->velocity = pick();
            t->acceleration = pick();
        }
        commanded_reals(&chip, ct, &r);
        bad += compare(&r, &chip, ct);
        checked += PMD_AXES;
    }
    printf("differ %ld of %ld\n", bad, checked);
    return 0;
}
"""


# ---- the extremes, for the longest segment time -------------------------------------

EXTREMES = {
    "v=-2^15 a=max j=max": (-3, MIN32, MAX32, MAX32),
    "v=-2^15 a=-2^15 j=-2^31": (MAX32, MIN32, MIN32, MIN32),
    "v=max a=-2^15 j=max": (MIN32, MAX32, MIN32, MAX32),
    "v=max a=max j=-2^31": (0, MAX32, MAX32, MIN32),
}
LONGEST = 0xFFFFFFFF
# cycles (integration steps n) at which a coarse doStep stops and a few cycles are recorded
CHECKPOINTS = [1, 1000, 65536, 10**6, 123_456_789, 1 << 31, 3_000_000_000, LONGEST - 70_000, LONGEST - 3]


@FMI
@pytest.mark.parametrize("extreme", EXTREMES)
def test_extreme_segments_stay_exact_for_2_to_the_32_minus_1_cycles(fmi, extreme):
    """Coarse doSteps (fast-forward) to checkpoints over the whole segment, a few
    cycles recorded one by one at each, every register exact; then the last
    integration step and the read of the next row."""
    row = EXTREMES[extreme]
    seg = Segment(*row)
    with pmdfmu.Chip(fmi_version=fmi) as chip:
        cycle_time = chip.cycle_time
        start_segment(chip, row + (LONGEST,), then=(-99, 0, 0, 0, 0))
        assert recorded(chip, 1) == [seg.registers(0)]
        n = 0  # integration steps done
        for checkpoint in CHECKPOINTS:
            chip.run(checkpoint - n - 1)
            n = checkpoint - 1
            assert registers_now(chip) == seg.registers(n), n
            assert recorded(chip, 3) == [seg.registers(n + k) for k in (1, 2, 3)], n
            n += 3
            position, velocity, acceleration = seg.reals(n, cycle_time)
            assert chip.get("axis1.position") == pytest.approx(position, abs=1e-6)
            assert chip.get("axis1.velocity") == pytest.approx(float(velocity), rel=1e-12)
            assert chip.get("axis1.acceleration") == pytest.approx(float(acceleration), rel=1e-12)
            assert field_ex(chip.axis(0).GetActivityStatus(), "PMDActivityProfileSegment") == 1
        assert n == LONGEST - 1  # the segment's last cycle
        assert recorded(chip, 2) == [(-99, 0, 0)] * 2  # then the time-0 row: halted there
        assert field_ex(chip.axis(0).GetActivityStatus(), "PMDActivityProfileSegment") == 0


def extreme_word(rng):
    return rng.choice([MIN32, MAX32, MIN32 + 1, MAX32 - 1, 0, rng.randrange(1 << 32)])


@pytest.mark.slow
@FMI
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_extreme_tables_in_coarse_steps_equal_cycle_by_cycle_and_the_exact_model(fmi, seed):
    """Random tables of extreme words on two axes, one chip stepped cycle by cycle
    and checked against the seed's pseudo code in Fractions (reference.py), the
    other in uneven coarse doSteps: the same registers and event bits at every
    step boundary. Velocities through exact zeros give motion-complete events;
    one row per axis runs long enough for an extreme acceleration or jerk to
    pass what a 64-bit state in one unit could hold."""
    rng = random.Random(seed)
    tables = {}
    for axis in (0, 1):
        rows = []
        for _ in range(12):
            row = [
                rng.randrange(-(1 << 31), 1 << 31),
                extreme_word(rng),
                extreme_word(rng),
                extreme_word(rng),
                rng.choice([1, 2, rng.randrange(3, 3000)]),
            ]
            if rng.random() < 0.25:  # velocity exactly 0 after m cycles: an event
                m, a = rng.randrange(2, 1000), rng.choice([-1, 1]) * rng.randrange(1, 1 << 15)
                row[1:4] = [-m * a & 0xFFFFFFFF, a & 0xFFFFFFFF, 0]
            rows.append(tuple(row))
        long = rng.randrange(len(rows))  # one long row: past where 64 bits in one unit wrapped
        rows[long] = rows[long][:4] + (rng.randrange(12_000, 40_000),)
        tables[axis] = rows + [(rng.randrange(-100, 100), 0, 0, 0, 0)]
    total = sum(r[4] for r in tables[0] + tables[1]) + 10
    models = {axis: ExternalProfile(tables[axis]) for axis in tables}
    outputs = [f"axis{a + 1}.{q}" for a in (0, 1) for q in OUT + ["eventStatus"]]
    with pmdfmu.Chip(fmi_version=fmi) as fine, pmdfmu.Chip(fmi_version=fmi) as coarse:
        for chip in (fine, coarse):
            load_external_profile(chip, tables)
            start_external_profile(chip, [0, 1])
        done = 0
        while done < total:
            n = min(rng.randrange(1, 5000), total - done)
            rec = fine.run(n, record=outputs)
            coarse.run(n)
            done += n
            for axis in (0, 1):
                got = [tuple(int(rec[f"axis{axis + 1}.{q}"][i]) for q in OUT) for i in range(n)]
                assert got == models[axis].run(n), (axis, done)
            assert [coarse.get(name) for name in outputs] == [int(rec[name][-1]) for name in outputs]
            for chip in (fine, coarse):  # events are sticky: judge each chunk alone
                for axis in (0, 1):
                    chip.axis(axis).ResetEventStatus(0)


# ---- electronic gear ---------------------------------------------------------------


def gear_model(masters, ratio):
    """The slave's registers each cycle: it moves by exactly wrap32(delta) * ratio / 2^16
    counts; its velocity is that move, its acceleration the change from the last
    velocity (which is exact in 16.16)."""
    out, last, P, V = [], 0, Fraction(0), Fraction(0)
    for m in masters:
        move = Fraction(wrap32(m - last) * wrap32(ratio), 1 << 16)
        last = m
        P, V, A = P + move, move, move - V
        out.append((wrap32(floor(P)), wrap32(floor(V * 65536)), wrap32(floor(A * 65536))))
    return out


@FMI
@pytest.mark.parametrize("source", [PMDPositionSourceCommanded, PMDPositionSourceActual], ids=["commanded", "actual"])
@pytest.mark.parametrize("ratio", [0x40000000, MAX32, MIN32, 0xFFFF0001, 0x00018001])
def test_gear_moves_the_slave_exactly_at_any_ratio_and_master_jump(fmi, source, ratio):
    """The review's case - ratio 0x40000000 behind a master jumping 65536 counts in
    one cycle - and the extremes: the master (an external profile of one-cycle
    rows) jumps by anything up to half the 32-bit range, and across the wrap."""
    rng = random.Random(ratio)
    positions = [0, 65536, 131073, 7, 7, -MAX32, MAX32, MIN32 - (1 << 32), 0, MAX32, -1, 65535]
    positions += [rng.randrange(-(1 << 31), 1 << 31) for _ in range(200)]
    positions += [rng.randrange(-70000, 70000) for _ in range(200)]
    with pmdfmu.Chip(fmi_version=fmi) as chip:
        slave = chip.axis(1)
        slave.SetGearMaster(0, source)
        slave.SetGearRatio(wrap32(ratio))
        slave.SetProfileMode(PMDElectronicGearProfile)
        slave.Update()
        load_external_profile(chip, {0: [(p, 0, 0, 0, 1) for p in positions] + [(positions[-1], 0, 0, 0, 0)]})
        start_external_profile(chip, [0])
        rec = chip.run(len(positions) + 5, record=["axis1.commandedPosition"] + names(1))
        masters = [int(x) for x in rec["axis1.commandedPosition"]]
        got = [tuple(int(rec[n][i]) for n in names(1)) for i in range(len(masters))]
    assert masters[: len(positions)] == [wrap32(p) for p in positions]
    assert got == gear_model(masters, ratio)


# ---- a velocity beyond 16.16 handed to another mode ----------------------------------


@FMI
def test_a_velocity_beyond_the_16_16_range_hands_over_to_velocity_contouring(fmi):
    """An external segment at maximum jerk reaches ~2^60 counts/cycle; switching the
    axis to velocity contouring from there runs without undefined behaviour (the
    sanitizer build checks) and brakes at the deceleration every cycle."""
    with pmdfmu.Chip(fmi_version=fmi) as chip:
        start_segment(chip, (0, 0, 0, MAX32, LONGEST))
        chip.run(1 << 31)
        ax = chip.axis(0)
        before = chip.get("axis1.velocity")
        assert before > 2.0**59 / chip.cycle_time
        ax.SetProfileMode(PMDVelocityContouringProfile)
        ax.SetVelocity(0)
        ax.SetAcceleration(MAX32)
        ax.Update()
        velocities = []
        for _ in range(20):
            chip.run(1)
            velocities.append(chip.get("axis1.velocity"))
        assert all(b < a for a, b in zip(velocities, velocities[1:]))
        assert not ax.GetEventStatus() & PMDEventMotionCompleteMask
