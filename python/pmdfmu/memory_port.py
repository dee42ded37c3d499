# SPDX-License-Identifier: BSD-2-Clause
"""Chip.write_memory's strobes in the harness's native library (native/memory_port.c):
per block of 64 words one set of memory.data, .address, .count and a new
.strobe, then a get of host.ack that executes the write, through the FMU's own
FMI functions with the arguments the harness's Python loop passed
(tests/stepwise.py, kept as the reference)."""

from __future__ import annotations

from ctypes import POINTER, Array, addressof, c_char, c_int, c_int32, c_size_t, c_uint32, c_void_p
from functools import lru_cache
from operator import is_
from typing import Dict, List, Tuple

import numpy as np
from fmpy.fmi1 import FMICallException

from . import native

BLOCK_WORDS = native.BLOCK_WORDS

# the FMI functions each version's loop calls, in memory_port.h's order (native.MEMORY_SET, _SET_INT32, _GET)
FUNCTIONS = {
    2: ("fmi2SetInteger", "fmi2SetInteger", "fmi2GetInteger"),
    3: ("fmi3SetUInt32", "fmi3SetInt32", "fmi3GetInt32"),
}
# the ones each version's native loop takes, in its argument order
NAMES = {2: (FUNCTIONS[2][0], FUNCTIONS[2][2]), 3: FUNCTIONS[3]}


@lru_cache(maxsize=None)
def _writers():
    """The library's two loops with their prototypes, declared once."""
    lib = native.library()
    fmi2, fmi3 = lib.pmd_memory_write_fmi2, lib.pmd_memory_write_fmi3
    tail = [c_void_p, POINTER(native.Port), c_uint32, c_void_p, c_size_t, c_int32, POINTER(native.Stop)]
    fmi2.argtypes, fmi3.argtypes = [c_void_p] * 2 + tail, [c_void_p] * 3 + tail
    fmi2.restype = fmi3.restype = c_int
    return {2: fmi2, 3: fmi3}


# per FMU model (the harness shares one name -> value reference map among the Chips of an FMU file):
# the port's value references and those of the get before the strobes (memorySize, memory.strobe),
# kept with the map so that its id stays its own
_ports: Dict[int, Tuple[dict, native.Port, Array]] = {}
# the FMI functions' addresses, by the ctypes functions FMPy calls (looked up each write, as FMPy's
# own wrappers do, so that the native loop calls whatever FMPy would)
_addresses: Dict[Tuple[int, ...], Tuple[tuple, List[int]]] = {}


def _port(chip) -> Tuple[dict, native.Port, Array]:
    vr = chip._vr
    kept = _ports.get(id(vr))
    if kept is None or kept[0] is not vr:
        data = (
            [vr[f"memory.data[{i + 1}]"] for i in range(BLOCK_WORDS)]
            if chip.fmi_version == 2
            else [vr["memory.data"]] + [0] * (BLOCK_WORDS - 1)
        )
        kept = _ports[id(vr)] = (
            vr,
            native.Port(
                (c_uint32 * BLOCK_WORDS)(*data),
                vr["memory.address"],
                vr["memory.count"],
                vr["memory.strobe"],
                vr["host.ack"],
            ),
            (c_uint32 * 2)(vr["memorySize"], vr["memory.strobe"]),
        )
    return kept


def _calls(chip) -> List[int]:
    functions = chip.fmu._functions
    now = tuple([functions[n] for n in NAMES[chip.fmi_version]])
    kept = _addresses.get(tuple(map(id, now)))
    if kept is None or not all(map(is_, kept[0], now)):
        kept = _addresses[tuple(map(id, now))] = (now, [native.address(f) for f in now])
    return kept[1]


def _pointer(words: np.ndarray) -> int:
    """The address of a contiguous array's first word: through the buffer protocol where it is
    writable (a fraction of a microsecond less than numpy's .ctypes, which builds an object)."""
    if len(words) and words.flags.writeable:
        return addressof(c_char.from_buffer(words))
    return words.ctypes.data


def write(chip, address: int, words: np.ndarray) -> None:
    """Reads memorySize and memory.strobe (one get, through FMPy), then, if the uint32 words (checked
    by the caller) fit at address.. (0 <= address, address + len(words) <= memorySize), writes
    them, the first block with strobe (strobe + 1) & 0x7FFFFFFF; if they do not, raises
    Chip._memory_fits' ValueError, nothing written. Raises as FMPy would for a call that failed
    (FMICallException naming it: the FMU's messages are in chip.messages), the blocks before it
    written."""
    words = np.ascontiguousarray(words, dtype=np.uint32)
    _vr, port, read = _port(chip)
    fmu, got = chip.fmu, (c_int32 * 2)()
    if chip.fmi_version == 2:
        fmu.fmi2GetInteger(fmu.component, read, 2, got)
    else:
        fmu.fmi3GetInt32(fmu.component, read, 2, got, 2)
    size, strobe = got
    chip._memory_fits(address, len(words), size)
    stop = native.Stop()
    if _writers()[chip.fmi_version](
        *_calls(chip), fmu.component, port, address, _pointer(words), len(words), strobe, stop
    ):
        raise FMICallException(function=FUNCTIONS[chip.fmi_version][stop.call], status=stop.status)
