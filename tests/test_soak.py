# SPDX-License-Identifier: BSD-2-Clause
"""Soak: 10^9 cycles of an external profile streamed through the
dual-port memory port, refilled behind the read position, checked against the
exact closed form at every checkpoint, with flat memory."""

import os
import random
from fractions import Fraction
from math import floor

import pmdfmu
from reference import wrap32
import pytest

pytestmark = pytest.mark.slow  # tests/README.md: ./dev test -m "not slow" leaves them out

T = 100_000  # cycles per segment
L = 64  # buffer entries
CHUNK = 50 * T  # cycles per doStep: the buffer always holds what it needs


def segment(i):
    rng = random.Random(i)
    return (
        rng.randrange(-100_000, 100_000),
        rng.randrange(-0x20000, 0x20000),
        2 * rng.randrange(-8, 8),
        rng.randrange(-1, 2),
        T,
    )


def expected(i, k):
    """Registers k integration steps into segment i: P0 + V0 k + A0 k^2/2 + J k^3/6, exactly."""
    p0, v0, a0, j, _ = segment(i)
    v0, a0, j = Fraction(v0, 1 << 16), Fraction(a0, 1 << 16), Fraction(j, 1 << 32)
    p = p0 + v0 * k + a0 * k * k / 2 + j * k**3 / 6
    return wrap32(floor(p)), wrap32(floor((v0 + a0 * k + j * k * k / 2) * 65536)), wrap32(floor((a0 + j * k) * 65536))


def rss_kib():
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmRSS"))


def test_a_billion_streamed_cycles_stay_exact_with_flat_memory():
    with pmdfmu.Chip() as chip:
        ax = chip.axis(0)
        for f in range(5):
            ax.SetBufferStart(2 + f, 0x200 + f * L)
            ax.SetBufferLength(2 + f, L)
            ax.SetBufferFunction(f, 2 + f)

        def write(first, last):  # segments first..last-1 into their slots, through the memory port
            for f in range(5):
                for j in range(first, last):
                    chip.write_memory(0x200 + f * L + j % L, [segment(j)[f] & 0xFFFFFFFF])

        written = L - 1
        write(0, written)
        ax.SetProfileMode(pmdfmu.PMDExternalProfile)
        ax.Update()
        start, rss = chip.cycles, []
        while chip.cycles - start < 10**9:
            chip.run(min(CHUNK, start + 10**9 - chip.cycles))
            done = chip.cycles - start  # cycles of the profile so far
            current, k = (done - 1) // T, (done - 1) % T
            assert (ax.GetCommandedPosition(), ax.GetCommandedVelocity(), ax.GetCommandedAcceleration()) == expected(
                current, k
            ), f"at cycle {done}"
            assert ax.GetBufferReadIndex(2) == (current + 1) % L
            write(written, current + L)  # refill behind the read position
            written = current + L
            rss.append(rss_kib())
        assert chip.cycles - start == 10**9
        if not os.environ.get("PMDFMU_SANITIZED"):  # ASan's quarantine grows by design
            assert max(rss[10:]) - rss[10] < 4096, "memory grows"
