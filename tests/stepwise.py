# SPDX-License-Identifier: BSD-2-Clause
"""The harness's oracles: what Chip.run(record=...) and Chip.write_memory did in Python through FMPy
before the FMU recorded in bulk and the native loops came (pmdfmu.recording, pmdfmu.memory_port).
The tests pin those paths to these, bit for bit (a helper module, not a test file: conftest.py)."""

from typing import Sequence

import numpy as np

import pmdfmu
from pmdfmu.chip import BATCH_WORDS, DTYPES, _refusals
from pmdfmu.fixed import integer

# FMI 2 reads unsigned registers as signed Integers: these masks give back their bits
UNSIGNED = {n: (1 << 8 * t.itemsize) - 1 for n, t in DTYPES.items() if t.kind == "u"}


@_refusals  # an FMI call the FMU refuses raises as from Chip's own calls
def run_stepwise(chip: pmdfmu.Chip, cycles: int, record: Sequence[str]) -> np.ndarray:
    """chip.run(cycles, record) cycle by cycle: a doStep of one cycle, then one get per FMI type."""
    names = list(record)
    where, dtype = chip._columns(names)
    out = np.zeros(cycles, dtype=dtype)
    # one get per FMI type a cycle: the type's variables (each array once), and each column's
    # place among the values it returns
    groups = []
    for t, get in chip._getters.items():
        ns = [n for n in names if chip.variables[where[n][0]].type == t]
        read = list(dict.fromkeys(where[n][0] for n in ns))
        if not ns:
            continue
        offsets = np.cumsum([0] + [chip._size(r) for r in read])
        places = [int(offsets[read.index(where[n][0])]) + where[n][1] for n in ns]
        vrs = [chip._vr[r] for r in read]
        if chip.fmi_version == 3 and offsets[-1] != len(read):
            get = (lambda g, total: lambda vrs: g(vrs, nValues=total))(get, int(offsets[-1]))
        groups.append((get, ns, vrs, places))
    get_time, time_vr = chip._getters[chip.variables["chipTime"].type], [chip._vr["chipTime"]]
    for i in range(cycles):
        chip._step(1)
        out["cycle"][i] = get_time(time_vr)[0] & 0xFFFFFFFF  # FMI 2 Integer: the same 32 bits
        for get, ns, vrs, places in groups:
            values = get(vrs)
            for n, p in zip(ns, places):
                out[n][i] = values[p] & UNSIGNED[n] if n in UNSIGNED else values[p]
    return out


class Stepwise(pmdfmu.recording.Recorder):
    """A Chip.recorder that runs every recording as run_stepwise does (everything else Chip.run does, the
    checks and the host clock, stays)."""

    def run(self, cycles: int, out=None) -> np.ndarray:
        rows = run_stepwise(self.chip, cycles, self.names)
        if out is None:
            return rows
        out[:] = rows
        return out


class NativeLoop(pmdfmu.recording.Recorder):
    """A Chip.recorder that runs every recording cycle by cycle in the native loop, as for an FMU without
    bulk recording of its columns."""

    def run(self, cycles: int, out=None) -> np.ndarray:
        return self.stepwise(cycles, out)


@_refusals
def write_memory_stepwise(chip: pmdfmu.Chip, address: int, words: Sequence[int]) -> None:
    """chip.write_memory(address, words) block by block: set memory.data, address, count and strobe,
    then a get that executes the write."""
    data = chip._memory_words(words)
    address = integer(address, "write_memory: address")
    chip._memory_fits(address, len(data), chip.get("memorySize"))
    strobe = chip.get("memory.strobe")
    for start in range(0, len(data), BATCH_WORDS):
        strobe = (strobe + 1) & 0x7FFFFFFF
        chip._memory_strobe(address + start, data[start : start + BATCH_WORDS], strobe)
        chip.get("host.ack")  # executes the write now
