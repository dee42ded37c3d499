# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu.Chip(device="serial:PATH" | "tcp:HOST:PORT"): a chip reached over its serial packet
protocol (serial_protocol.py) -- `pmdfmu serve`'s twin or a real chip -- with the same Axis methods
as the twin in-process (docs/device.md).

Only commands cross a serial line. What needs the FMU itself (run and its recording, FMU variables,
the dual-port memory, host time, FMU states) raises NeedsFMU, naming the call."""

from __future__ import annotations

import os
import select
import socket
import termios
import time
import tty
from typing import List, Optional, Sequence, Tuple, Union

from . import serial_protocol as sp
from .calls import (
    BATCH_WORDS,
    COMMANDS,
    OPCODES,
    Axis,
    PMDError,
    axis_number,
    decode,
    encode,
    field_ex,
    instruction_word,
    sent_name,
    sent_words,
)
from .fixed import to_word
from .tables import Command

# how long a reply may take before the host gives up on it and resynchronises, s
REPLY_TIMEOUT = 2.0
# C-Motion's resynchronisation: single zero bytes until a 2-byte reply comes back (S1: up to 8 tries)
RESYNC_TRIES = 8
RESYNC_WAIT = 0.05
# the chip's calls that need the FMU in-process
IN_PROCESS_ONLY = (
    "run",
    "get",
    "set",
    "write_memory",
    "wait",
    "wait_ns",
    "wait_for_interrupt",
    "get_state",
    "set_state",
    "reinitialize",
    "cycles",
    "time",
    "cycle_time",
    "host_time_ns",
    "host_time",
    "messages",
    "variables",
    "model_description",
)
# the termios speeds of the Navigator's baud rates that a tty has
_SPEEDS = {b: getattr(termios, f"B{b}") for b in sp.BAUD_RATES.values() if hasattr(termios, f"B{b}")}


class NeedsFMU(AttributeError):
    """A Chip call that needs the twin in-process, made on a chip over a line."""


class LineError(OSError):
    """The line gave no well-formed reply, even after resynchronising."""


class LineChip:
    """A chip over a serial line or TCP: Chip(device=...). address: its multi-drop address (the
    packets' first byte; 0 point-to-point)."""

    # the Axis methods' native host port (calls.py _fast_source) is the FMU's: over a line they take the
    # path through command()
    _fast = None
    _recording = False

    def __init__(self, device: str, address: int = 0, baud: int = 57600):
        self.device = device
        self.address = address
        kind, _, where = device.partition(":")
        self._sock: Optional[socket.socket] = None
        self._fd = -1
        if kind == "serial" and where:
            self._fd = os.open(where, os.O_RDWR | os.O_NOCTTY)
            try:
                tty.setraw(self._fd, termios.TCSANOW)
                if baud in _SPEEDS:
                    attrs = termios.tcgetattr(self._fd)
                    attrs[4] = attrs[5] = _SPEEDS[baud]
                    termios.tcsetattr(self._fd, termios.TCSANOW, attrs)
            except termios.error:
                pass  # a file or a FIFO that is no tty: bytes all the same
        elif kind == "tcp" and ":" in where:
            host, _, port = where.rpartition(":")
            self._sock = socket.create_connection((host.strip("[]"), int(port)))
            self._sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            self._fd = self._sock.fileno()
        else:
            raise ValueError(f"device {device!r}: serial:PATH or tcp:HOST:PORT (or fmu for the twin in-process)")

    # ---- life cycle ----

    def close(self) -> None:
        if self._sock is not None:
            self._sock.close()
        elif self._fd >= 0:
            os.close(self._fd)
        self._fd, self._sock = -1, None

    def __enter__(self) -> "LineChip":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __getattr__(self, name: str):
        if name in IN_PROCESS_ONLY:
            raise NeedsFMU(
                f"Chip(device={self.device!r}).{name}: needs the twin in-process (Chip() without device); "
                "over a line the chip takes commands only"
            )
        raise AttributeError(name)

    # ---- the line ----

    def _read(self, n: int, timeout: float) -> bytes:
        data, end = b"", time.monotonic() + timeout
        while len(data) < n:
            left = end - time.monotonic()
            if left <= 0 or not select.select([self._fd], [], [], left)[0]:
                break
            chunk = os.read(self._fd, n - len(data))
            if not chunk:
                break
            data += chunk
        return data

    def _write(self, data: bytes) -> None:
        view = memoryview(data)
        while view:
            view = view[os.write(self._fd, view) :]

    def _drain(self) -> None:
        while select.select([self._fd], [], [], 0)[0] and os.read(self._fd, 4096):
            pass

    def resync(self) -> None:
        """C-Motion's resynchronisation: single zero bytes, one at a time, until a 2-byte reply
        comes back (the chip completed a packet with them)."""
        self._drain()
        for _ in range(RESYNC_TRIES):
            self._write(b"\0")
            if len(self._read(2, RESYNC_WAIT)) == 2:
                self._drain()
                return
        raise LineError(f"{self.device}: no reply to {RESYNC_TRIES} resynchronising zero bytes")

    def exchange(self, instruction: int, args: Sequence[int], reply_words: int) -> Tuple[int, List[int]]:
        """One command packet out, its reply in: (status, words). A malformed or missing reply, or the
        checksum error, resynchronises and sends the packet once more."""
        packet = sp.command_packet(instruction, args, self.address)
        for _attempt in range(2):
            self._write(packet)
            head = self._read(2, REPLY_TIMEOUT)
            if len(head) == 2 and head[0] != 0 and sum(head) & 0xFF == 0:
                status, words = head[0], []
            elif len(head) == 2:
                rest = self._read(2 * reply_words, REPLY_TIMEOUT)
                try:
                    status, words = sp.parse_reply(head + rest)
                except sp.ProtocolError:
                    status = -1
                if status == 0 and len(words) != reply_words:
                    status = -1
            else:
                status = -1
            if status == sp.BAD_CHECKSUM or status == -1:
                self.resync()
                continue
            return status, words
        raise LineError(f"{self.device}: no well-formed reply to {packet.hex(' ')}")

    # ---- commands, as Chip's ----

    def axis(self, n: int) -> Axis:
        """Axis handle n = 0..3 (C-Motion's PMDAxis1..PMDAxis4)."""
        return Axis(self, n)

    def batch(self, words: Sequence[int]) -> Tuple[int, List[int]]:
        """Raw host words (whole commands), each command its own packet: (first error, replies)."""
        if len(words) > BATCH_WORDS:
            raise ValueError(f"a batch holds at most {BATCH_WORDS} words, not {len(words)}")
        words = [to_word(w, 16, f"batch: word {i}") for i, w in enumerate(words)]
        first, replies, i = 0, [], 0
        while i < len(words):
            c = OPCODES.get(field_ex(words[i], "PMDInstructionOpcode"))
            n = c.arg_words if c else 0
            status, reply = self.exchange(words[i], words[i + 1 : i + 1 + n], c.reply_words if c else 0)
            first = first or status
            replies += reply
            i += 1 + n
        return first, replies

    def send(self, instruction: int, *data: int) -> Tuple[int, ...]:
        """One command as raw words, its packet out and its reply words back (Chip.send); raises PMDError
        if the chip refuses it."""
        words, command = sent_words(instruction, data)
        status, reply = self.exchange(words[0], words[1:], command.reply_words if command else 0)
        if status:
            raise PMDError(status, sent_name(command, words[0]))
        return tuple(reply)

    def command(self, axis: int, command: Union[str, Command], args: Sequence[int] = ()):
        """Executes one C-Motion call; raises PMDError if the chip refuses it."""
        if isinstance(command, str):
            command = COMMANDS[command]
        axis = axis_number(axis)
        instruction = instruction_word(command.opcode, 0 if command.scope == "chip" else axis)
        error, reply = self.exchange(instruction, encode(command, args), command.reply_words)
        if error:
            raise PMDError(error, command.name)
        values = decode(command.reply, reply)
        return None if not values else values[0] if len(values) == 1 else tuple(values)
