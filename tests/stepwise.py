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


def send_stepwise(chip: pmdfmu.Chip, words) -> tuple:
    """Chip._send in Python through FMPy, as the harness made it before native/host_port.c: a get of
    host.strobe, one set of the words, host.wordCount and a new strobe, one get of host.ack, host.error,
    host.replyCount and the reply (FMI 3: the arrays whole). Returns (host.error, reply words)."""
    from ctypes import c_int32, c_uint16

    n, fmu, c, vr = len(words), chip.fmu, chip.fmu.component, chip._vr
    u32 = pmdfmu.chip.c_uint32
    if chip.fmi_version == 2:
        strobe = (c_int32 * 1)()
        fmu.fmi2GetInteger(c, (u32 * 1)(vr["host.strobe"]), 1, strobe)
        new = (strobe[0] + 1) & 0x7FFFFFFF  # a new strobe value, whoever set the last one
        set_vrs = (u32 * (n + 2))(
            *[vr[f"host.word[{i + 1}]"] for i in range(n)], vr["host.wordCount"], vr["host.strobe"]
        )
        fmu.fmi2SetInteger(c, set_vrs, n + 2, (c_int32 * (n + 2))(*words, n, new))
        get_vrs = [vr["host.ack"], vr["host.error"], vr["host.replyCount"]]
        get_vrs += [vr[f"host.reply[{i + 1}]"] for i in range(BATCH_WORDS)]
        out = (c_int32 * len(get_vrs))()
        fmu.fmi2GetInteger(c, (u32 * len(get_vrs))(*get_vrs), len(get_vrs), out)
        ack, error, count = out[0], out[1], out[2]
        reply = out[3 : 3 + count]
    else:
        strobe = (c_int32 * 1)()
        fmu.fmi3GetInt32(c, (u32 * 1)(vr["host.strobe"]), 1, strobe, 1)
        new = (strobe[0] + 1) & 0x7FFFFFFF
        words16 = (c_uint16 * BATCH_WORDS)(*words)
        fmu.fmi3SetUInt16(c, (u32 * 1)(vr["host.word"]), 1, words16, BATCH_WORDS)  # the array is set whole
        fmu.fmi3SetInt32(c, (u32 * 2)(vr["host.wordCount"], vr["host.strobe"]), 2, (c_int32 * 2)(n, new), 2)
        out = (c_int32 * 2)()
        fmu.fmi3GetInt32(c, (u32 * 2)(vr["host.ack"], vr["host.replyCount"]), 2, out, 2)
        reply16 = (c_uint16 * (1 + BATCH_WORDS))()
        fmu.fmi3GetUInt16(c, (u32 * 2)(vr["host.error"], vr["host.reply"]), 2, reply16, 1 + BATCH_WORDS)
        ack, count, error = out[0], out[1], reply16[0]
        reply = reply16[1 : 1 + count]
    if ack != new:
        raise pmdfmu.chip.FMUError(f"host.ack is {ack}, not the strobe {new}: the FMU did not execute the batch")
    return error, list(reply)


class StepwiseChip(pmdfmu.Chip):
    """A Chip whose every command goes the Python way: Chip.command's encoding, batch's checks and host
    time in Python, and send_stepwise's FMI calls through FMPy (the Axis methods see another _send and
    take their slow path)."""

    def _send(self, words):
        return send_stepwise(self, words)


def wait_for_stepwise(chip: pmdfmu.Chip, mask: int, axis: int = 0, timeout=None):
    """chip.wait_for(mask, axis, timeout) as a Python host loop: GetEventStatus until a bit of mask,
    a cycle after each unsatisfied poll with the host interface none."""
    from fractions import Fraction

    limit = None if timeout is None else chip.host_time_ns + round(Fraction(timeout) * 1_000_000_000)
    ax = chip.axis(axis)
    while True:
        status = ax.GetEventStatus()
        if status & mask:
            return status
        if limit is not None and chip.host_time_ns > limit:
            return None
        if chip.host_interface.kind == "none":
            chip.run(1)
