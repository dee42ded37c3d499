# SPDX-License-Identifier: BSD-2-Clause
"""The harness's native library (native/*.c, built by CMake beside the FMUs):
loops over an FMU's own FMI functions that would cost a Python call per cycle
or per word. Found like the FMUs (chip.default_fmu): $PMDFMU_FMU_DIR/native,
the installed package's native/, the source tree's build/native. The structs
and enums it shares with the harness are mirrored here with ctypes, and the
library's own layout of them (pmd_native_layout) is checked at load."""

from __future__ import annotations

import ctypes
from ctypes import POINTER, Structure, c_double, c_int, c_int32, c_int64, c_size_t, c_uint16, c_uint32, c_void_p
import os
import sys
from functools import lru_cache
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
REPO = PACKAGE.parent.parent
ABI = 6  # native/native.h PMD_NATIVE_ABI
NAME = {"win32": "pmdnative.dll", "darwin": "libpmdnative.dylib"}.get(sys.platform, "libpmdnative.so")
BLOCK_WORDS = 64  # memory.data[64]: the words one strobe writes

# record_loop.h's PmdLoopType: the C type of a getter's values
DOUBLE, INT32, UINT32, UINT16, INT16, INT, BOOL = range(7)
# memory_port.h's calls, record_loop.h's calls of pmd_record_step_lent, in their order
MEMORY_SET, MEMORY_SET_INT32, MEMORY_GET = range(3)
STEP_LEND, STEP_DO_STEP, STEP_GET_DATA, STEP_END_LOAN = range(4)
HOST_WORDS = 64  # host.word[64], host.reply[64]
# host_port.h's calls (PmdStop.call of a host command), in their order
HOST_GET_STROBE, HOST_SET_WORDS, HOST_SET_INT, HOST_GET_ACK, HOST_GET_REPLY, HOST_GRID, HOST_DO_STEP, HOST_ACK = range(
    8
)
LOOP_FIELD_SIZE = -2  # the call record_loop.h's loops name for a column of another size than 1, 2, 4, 8


class Stop(Structure):
    """native.h's PmdStop: where a loop stopped (after `done` rows or blocks, call `call` returned `status`)."""

    _fields_ = [("done", c_size_t), ("call", c_int), ("status", c_int)]


class Group(Structure):
    """record_loop.h's PmdLoopGroup: one get a cycle."""

    _fields_ = [
        ("get", c_void_p),
        ("vrs", POINTER(c_uint32)),
        ("n_vrs", c_size_t),
        ("n_values", c_size_t),
        ("type", c_int),
        ("values", c_void_p),
    ]


class Column(Structure):
    """record_loop.h's PmdLoopColumn: one field of a row."""

    _fields_ = [("source", c_void_p), ("offset", c_size_t), ("size", c_size_t), ("truth", c_int)]


class Port(Structure):
    """memory_port.h's PmdMemoryPort: the value references a strobe uses."""

    _fields_ = [
        ("data", c_uint32 * BLOCK_WORDS),
        ("address", c_uint32),
        ("count", c_uint32),
        ("strobe", c_uint32),
        ("ack", c_uint32),
    ]


class HostPort(Structure):
    """host_port.h's PmdHostPort: a Chip's host port, its FMI functions and host time (host_port.py)."""

    _fields_ = [
        ("get_int", c_void_p),
        ("set_int", c_void_p),
        ("set_words", c_void_p),
        ("get_words", c_void_p),
        ("get_real", c_void_p),
        ("do_step", c_void_p),
        ("instance", c_void_p),
        ("fmi3", c_int),
        ("word", c_uint32 * HOST_WORDS),
        ("reply", c_uint32 * HOST_WORDS),
        ("word_count", c_uint32),
        ("strobe", c_uint32),
        ("ack", c_uint32),
        ("error", c_uint32),
        ("reply_count", c_uint32),
        ("grid", c_uint32 * 3),
        ("timed", c_int),
        ("host_ns", c_int64),
        ("request_ns", c_int64 * (HOST_WORDS + 1)),
        ("reply_ns", c_int64 * (HOST_WORDS + 1)),
        ("failed_ns", c_int64),
        ("in_", c_uint16 * HOST_WORDS),
        ("out", c_uint16 * HOST_WORDS),
        ("count", c_int32),
        ("error_word", c_int32),
        ("ack_word", c_int32),
        ("strobe_sent", c_int32),
        ("stop", Stop),
    ]


class SystemValue(Structure):
    """system.h's PmdSystemValue: a value between a get and its sets, both readings."""

    _fields_ = [("integer", c_int64), ("real", c_double)]


class SystemOp(Structure):
    """system.h's PmdSystemOp: a get, a set or a doStep of a system's step."""

    _fields_ = [
        ("kind", c_int),
        ("type", c_int),
        ("fn", c_void_p),
        ("instance", c_void_p),
        ("vr", c_uint32),
        ("value", c_size_t),
    ]


class SystemColumn(Structure):
    """system.h's PmdSystemColumn: one field of a system's row."""

    _fields_ = [("value", c_size_t), ("offset", c_size_t), ("size", c_size_t), ("real", c_int)]


SYSTEM_GET, SYSTEM_SET, SYSTEM_STEP = range(3)


def layout() -> list:
    """What pmd_native_layout returns for a library built with this harness: abi.c's order."""
    out = []
    for struct in (Stop, Group, Column, Port, HostPort, SystemValue, SystemOp, SystemColumn):
        out += [ctypes.sizeof(struct)] + [getattr(struct, name).offset for name, _type in struct._fields_]
    return (
        out
        + [DOUBLE, INT32, UINT32, UINT16, INT16, INT, BOOL]
        + [MEMORY_SET, MEMORY_SET_INT32, MEMORY_GET]
        + [STEP_LEND, STEP_DO_STEP, STEP_GET_DATA, STEP_END_LOAN]
        + [-LOOP_FIELD_SIZE]
        + [HOST_GET_STROBE, HOST_SET_WORDS, HOST_SET_INT, HOST_GET_ACK, HOST_GET_REPLY, HOST_GRID, HOST_DO_STEP]
        + [HOST_ACK, HOST_WORDS]
        + [SYSTEM_GET, SYSTEM_SET, SYSTEM_STEP]
    )


@lru_cache(maxsize=None)
def library() -> ctypes.CDLL:
    """The loaded library, once per process; each module declares the prototypes it calls."""
    candidates = [Path(os.environ["PMDFMU_FMU_DIR"]) / "native" / NAME] if "PMDFMU_FMU_DIR" in os.environ else []
    candidates += [PACKAGE / "native" / NAME, REPO / "build" / "native" / NAME]
    for path in candidates:
        if path.is_file():
            lib = ctypes.CDLL(str(path))
            if lib.pmd_native_abi() != ABI:
                raise ImportError(
                    f"{path} is of ABI {lib.pmd_native_abi()}, the harness wants {ABI}: rebuild it "
                    "(pip install . or cmake --build build)"
                )
            lib.pmd_native_layout.restype = c_size_t
            lib.pmd_native_layout.argtypes = [POINTER(c_size_t), c_size_t]
            want = layout()
            got = (c_size_t * len(want))()
            count = lib.pmd_native_layout(got, len(want))
            if count != len(want) or list(got) != want:
                raise ImportError(
                    f"{path} lays out its structs and enums otherwise than the harness's ctypes "
                    f"(native.py; {list(got)[:count]} against {want}): rebuild it or fix native.py"
                )
            return lib
    raise FileNotFoundError(
        f"{NAME} not found in {', '.join(map(str, candidates))}: build it first "
        "(pip install . or cmake -S . -B build && cmake --build build)"
    )


def address(function) -> int:
    """A ctypes function's address, to hand an FMU's FMI function to the library."""
    return ctypes.cast(function, ctypes.c_void_p).value
