# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu.Chip(device="serial:PATH" | "tcp:HOST:PORT"): a chip reached over its serial packet
protocol (serial_protocol.py) -- `pmdfmu serve`'s twin or a real chip -- with the same Axis methods
as the twin in-process (docs/device.md).

Only commands cross a serial line. With the twin's monitor beside it (`pmdfmu serve --monitor`,
Chip(device=..., monitor="tcp:HOST:PORT")) run, get, write_memory, wait and the host clock reach the
twin too. What needs the FMU itself (recording, setting FMU variables, FMU states; without a monitor
also the calls above) raises NeedsFMU, naming the call."""

from __future__ import annotations

import os
import select
import socket
import stat
import termios
import time
import tty
from typing import List, Optional, Sequence, Tuple, Union

from . import hosttime
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
from .fixed import integer, to_word
from .tables import Command

# how long a reply may take before the host gives up on it and resynchronises, s
REPLY_TIMEOUT = 2.0
# C-Motion's resynchronisation: single zero bytes until a 2-byte reply comes back (S1: up to 8 tries)
RESYNC_TRIES = 8
RESYNC_WAIT = 0.05
# the chip's calls that need the FMU in-process
IN_PROCESS_ONLY = (
    "set",
    "wait_for_interrupt",
    "get_state",
    "set_state",
    "reinitialize",
    "time",
    "cycle_time",
    "messages",
    "variables",
    "model_description",
)
# and those the twin's monitor answers over a line (monitor=)
MONITORED = ("run", "get", "write_memory", "wait", "wait_ns", "cycles", "host_time_ns", "host_time")
# the termios speeds of the Navigator's baud rates that a tty has
_SPEEDS = {b: getattr(termios, f"B{b}") for b in sp.BAUD_RATES.values() if hasattr(termios, f"B{b}")}


def _named(e: OSError, what: str) -> OSError:
    """e, of its own type (ConnectionRefusedError, FileNotFoundError, ...), saying which line or monitor. One
    without an errno (socket's "getaddrinfo returns an empty list") is not shown "[Errno None] ..."."""
    text = f"{what}: {e.strerror or e}"
    return type(e)(e.errno, text) if e.errno is not None else type(e)(text)


def _connect(where: str, what: str) -> Optional[socket.socket]:
    """A connection to HOST:PORT (a [v6] address too), Nagle off: every packet waits for its reply.
    None where WHERE is no HOST:PORT; an OSError naming `what` (the device or monitor) if it cannot connect."""
    host, colon, port = where.rpartition(":")
    if not colon or not (port.isascii() and port.isdigit()):  # "²" is a digit, and no int
        return None
    if int(port) > 65535:  # getaddrinfo took 99999 as 99999 mod 65536: another server's port
        raise ValueError(f"{where}: port {port} is not 0 .. 65535")
    try:
        sock = socket.create_connection((host.strip("[]"), int(port)))
    except OSError as e:
        raise _named(e, f"{what}: cannot connect") from None
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return sock


class NeedsFMU(AttributeError):
    """A Chip call that needs the twin in-process, made on a chip over a line."""


class LineError(OSError):
    """The line gave no well-formed reply, even after resynchronising (or the monitor went)."""


class MonitorRefusal(ValueError):
    """The twin's monitor refused a request: its reason (a variable it does not have, a write leaving the
    memory, a run under --realtime)."""


class LineChip:
    """A chip over a serial line or TCP: Chip(device=...). address: its multi-drop address (the
    packets' first byte; 0 point-to-point)."""

    # the Axis methods' native host port (calls.py _fast_source) is the FMU's: over a line they take the
    # path through command()
    _fast = None
    _recording = False

    def __init__(self, device: str, address: int = 0, baud: int = 57600, monitor: Optional[str] = None):
        self.device = device
        self.address = address
        self._monitor: Optional[socket.socket] = None
        self._replies = None
        kind, _, where = device.partition(":")
        self._sock: Optional[socket.socket] = None
        self._fd = -1
        if kind == "serial" and where:
            try:
                self._fd = os.open(where, os.O_RDWR | os.O_NOCTTY)
            except OSError as e:
                raise _named(e, f"device {device!r}: cannot open the line") from None
            if stat.S_ISREG(os.fstat(self._fd).st_mode):  # the packets were written into the user's file
                os.close(self._fd)
                raise ValueError(f"device {device!r}: a regular file, not a serial line: nothing was written")
            try:
                tty.setraw(self._fd, termios.TCSANOW)
                if baud in _SPEEDS:
                    attrs = termios.tcgetattr(self._fd)
                    attrs[4] = attrs[5] = _SPEEDS[baud]
                    termios.tcsetattr(self._fd, termios.TCSANOW, attrs)
            except termios.error:
                pass  # a file or a FIFO that is no tty: bytes all the same
        elif kind == "tcp" and (sock := _connect(where, f"device {device!r}")) is not None:
            self._sock, self._fd = sock, sock.fileno()
        else:
            raise ValueError(f"device {device!r}: serial:PATH or tcp:HOST:PORT (or fmu for the twin in-process)")
        if monitor is not None:
            kind, _, where = monitor.partition(":")
            try:
                self._monitor = _connect(where, f"monitor {monitor!r}") if kind == "tcp" else None
                if self._monitor is None:
                    raise ValueError(f"monitor {monitor!r}: tcp:HOST:PORT (pmdfmu serve --monitor's)")
                self._replies = self._monitor.makefile("r", encoding="ascii", newline="\n")
                self._ask("chip", f"chip {address}")
            except (OSError, ValueError):  # MonitorRefusal too: what opened here is closed, not left to the collector
                self.close()
                raise

    # ---- life cycle ----

    def close(self) -> None:
        if self._replies is not None:
            self._replies.close()
            self._replies = None
        if self._monitor is not None:
            self._monitor.close()
            self._monitor = None
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
        if name in IN_PROCESS_ONLY or name in MONITORED:
            raise NeedsFMU(
                f"Chip(device={self.device!r}).{name}: needs the twin in-process (Chip() without device)"
                + (", or its monitor (monitor=)" if name in MONITORED else "")
                + "; over a line the chip takes commands only"
            )
        raise AttributeError(name)

    # ---- the twin's monitor ----

    def _ask(self, name: str, request: str) -> str:
        """One request to the twin's monitor: the value of its `ok` reply."""
        if self._monitor is None:
            return self.__getattr__(name)  # raises NeedsFMU
        self._monitor.sendall(request.encode("ascii") + b"\n")
        reply = self._replies.readline().rstrip("\n")
        if reply == "ok" or reply.startswith("ok "):
            return reply[3:]
        if reply.startswith("error "):
            raise MonitorRefusal(f"{request[:60]}: {reply[6:]}")
        raise LineError(f"the monitor answered {reply[:80]!r} to {request[:60]!r}" if reply else "the monitor went")

    def run(self, cycles: int, record: Sequence[str] = ()) -> None:
        """The chip runs `cycles` cycles (the monitor's run); recording needs `pmdfmu serve --record`."""
        if record:
            raise NeedsFMU(f"Chip(device={self.device!r}).run(record=...): the server records (pmdfmu serve --record)")
        if isinstance(cycles, bool) or not isinstance(cycles, int) or cycles < 0:
            raise ValueError(f"run: cycles {cycles!r} is not a whole number >= 0")
        self._ask("run", f"run {cycles}")

    def get(self, name: str):
        """An FMU variable of the chip (an int, or a float for a Real)."""
        if not isinstance(name, str) or not name.isprintable() or " " in name:
            raise ValueError(f"get: {name!r} is not a variable name")
        text = self._ask("get", f"get {name}")
        return int(text) if text.lstrip("-").isdigit() else float(text)

    def write_memory(self, address: int, words: Sequence[int]) -> None:
        """32-bit words into the chip's dual-port memory, as Chip.write_memory (the server checks them)."""
        address = integer(address, "write_memory: address")  # never truncated: int(1.5) wrote the word 1
        words = [integer(w, f"write_memory: words[{i}]") for i, w in enumerate(words)]
        self._ask("write_memory", "write " + " ".join(str(w) for w in [address, *words]))

    def wait(self, seconds) -> None:
        """Host time passes without a command: the line's clock moves on, the chips run the cycles due."""
        self.wait_ns(hosttime.ns_of(seconds, "wait: seconds"))

    def wait_ns(self, nanoseconds: int) -> None:
        nanoseconds = integer(nanoseconds, "wait_ns: nanoseconds")
        if nanoseconds < 0:
            raise ValueError(f"wait_ns: {nanoseconds} ns is negative")
        self._ask("wait", f"wait {nanoseconds}")

    @property
    def host_time_ns(self) -> int:
        """The line's clock, ns: the host time the twin in-process would have."""
        return int(self._ask("host_time_ns", "time"))

    @property
    def host_time(self) -> float:
        return self.host_time_ns / 1e9

    @property
    def cycles(self) -> int:
        """Chip cycles run (the FMU's nextCycle)."""
        return int(self.get("nextCycle"))

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
        # the packets, found before any is sent: a packet holds a whole command, so one cut short cannot be
        # sent, nor any before it; an unknown opcode is the last (the chip cannot tell where the next starts)
        packets, i = [], 0
        while i < len(words):
            c = OPCODES.get(field_ex(words[i], "PMDInstructionOpcode"))
            n = c.arg_words if c else 0
            if i + 1 + n > len(words):
                raise ValueError(
                    f"batch: {c.name} (word {i}) needs {n} data words, the batch ends after "
                    f"{len(words) - i - 1}: over a line each command is a packet of its own; nothing was sent"
                )
            packets.append((words[i], words[i + 1 : i + 1 + n], c.reply_words if c else 0))
            if c is None:  # as Chip.batch: the batch ends
                break
            i += 1 + n
        first, replies = 0, []
        for packet in packets:
            status, reply = self.exchange(*packet)
            first = first or status
            replies += reply
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
