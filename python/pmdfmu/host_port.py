# SPDX-License-Identifier: BSD-2-Clause
"""The host port in the harness's native library (native/host_port.c): a command's FMI calls (a get of
host.strobe, a set of the words, count and a new strobe, a get of the ack, error and reply that executes
it), with host time the request's time, the cycles due and the reply's time, in one native call over
the FMU's own FMI functions. The Axis methods encode their arguments into one 64-bit word and decode the
result word (chip.py, _c_motion_method); Chip.send takes the same call for one command's raw words;
Chip.batch sends raw words; Chip.wait_for polls natively.
tests/stepwise.py keeps the Python path these replace (send_stepwise), and the tests pin them to it."""

from __future__ import annotations

from ctypes import POINTER, c_int64, c_size_t, c_uint32, c_uint64
from functools import lru_cache

from . import native

WORDS = native.HOST_WORDS
TIMEOUT, FAILED = 1 << 62, 1 << 63
# the FMI function each call of host_port.h names (PmdStop.call), per FMI version
CALLS = {
    2: (
        "fmi2GetInteger",
        "fmi2SetInteger",
        "fmi2SetInteger",
        "fmi2GetInteger",
        "fmi2GetInteger",
        "fmi2GetReal",
        "fmi2DoStep",
    ),
    3: (
        "fmi3GetInt32",
        "fmi3SetUInt16",
        "fmi3SetInt32",
        "fmi3GetInt32",
        "fmi3GetUInt16",
        "fmi3GetFloat64",
        "fmi3DoStep",
    ),
}
FUNCTIONS = {
    2: ("fmi2GetInteger", "fmi2SetInteger", None, None, "fmi2GetReal", "fmi2DoStep"),
    3: ("fmi3GetInt32", "fmi3SetInt32", "fmi3SetUInt16", "fmi3GetUInt16", "fmi3GetFloat64", "fmi3DoStep"),
}


@lru_cache(maxsize=None)
def functions():
    """The library's three entries with their prototypes, declared once: (batch, command, wait_for)."""
    lib = native.library()
    batch, command, wait = lib.pmd_host_batch, lib.pmd_host_command, lib.pmd_host_wait_for
    port = POINTER(native.HostPort)
    batch.argtypes = [port, c_size_t, c_size_t]
    # command without argtypes: a pointer and three ints, each a Python int masked to a C int (host_port.h)
    wait.argtypes = [port, c_size_t, c_uint64, c_uint32, c_int64]
    batch.restype = command.restype = wait.restype = c_uint64
    return batch, command, wait


def fill(port: native.HostPort, chip) -> None:
    """The chip's port: its value references and FMI functions (the instance's, as FMPy calls them)."""
    vr, fmi3 = chip._vr, chip.fmi_version == 3
    port.fmi3 = int(fmi3)
    if fmi3:
        port.word[0], port.reply[0] = vr["host.word"], vr["host.reply"]
    else:
        port.word[:] = [vr[f"host.word[{i + 1}]"] for i in range(WORDS)]
        port.reply[:] = [vr[f"host.reply[{i + 1}]"] for i in range(WORDS)]
    port.word_count, port.strobe, port.ack = vr["host.wordCount"], vr["host.strobe"], vr["host.ack"]
    port.error, port.reply_count = vr["host.error"], vr["host.replyCount"]
    port.grid[:] = [vr[n] for n in ("time", "nextCycleTime", "activeCycleTime")]
    functions = chip.fmu._functions
    for field, name in zip(
        ("get_int", "set_int", "set_words", "get_words", "get_real", "do_step"), FUNCTIONS[chip.fmi_version]
    ):
        if name:
            setattr(port, field, native.address(functions[name]))
    port.instance = chip.fmu.component


def time_port(port: native.HostPort, interface) -> None:
    """The host interface's transfer times, per word count (hosttime.HostInterface); timed unless none."""
    port.timed = int(interface.kind != "none")
    port.request_ns[:] = [interface.request_ns(w) for w in range(WORDS + 1)]
    port.reply_ns[:] = [interface.reply_ns(w) for w in range(WORDS + 1)]
    port.failed_ns = interface.reply_ns(0, True)
