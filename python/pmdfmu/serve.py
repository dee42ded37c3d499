# SPDX-License-Identifier: BSD-2-Clause
"""`pmdfmu serve`: the twin as a virtual device on a pty or a TCP port, speaking the chip's serial
packet protocol (serial_protocol.py, pmd-reference 3.1-3.3) byte for byte (docs/device.md).

A Line holds the chips on one serial line (--chips N: multi-drop addresses 0..N-1) and the line's
clock. Time is virtual by default: each packet costs its transfer time at the line's baud (the host
timing model, hosttime.py, through each chip's host_interface "serial"), so a host polling over the
line sees the chip times it would see in-process with Chip(host_interface="serial"). --realtime
paces the chips to the wall clock as well.

A Monitor (--monitor HOST:PORT, as QEMU's monitor beside its serial port) takes what a real chip has
no packet for: cycles run, host time passing, the FMU's variables read, the dual-port memory written,
so that a program written for the twin in-process (the C library's PMDFMU_RunCycles, PMDFMU_Wait,
PMDFMU_GetInteger, PMDWriteDPRAM with PMDFMU_MONITOR set) runs over the line unchanged."""

from __future__ import annotations

import errno
import os
import select
import signal
import socket
import sys
import termios
import time
import tty
from pathlib import Path
from typing import IO, List, Optional

import numpy as np

from . import hosttime
from . import serial_protocol as sp
from .chip import Chip, FMUError
from .recording import RECORDED

# how often an idle server looks at the wall clock (--realtime) and for a pty's next client, s
IDLE_TICK = 0.005
RECONNECT_POLL = 0.02
# a monitor request's longest line (a write of ~6000 words), and the cycles a run goes between looks at Ctrl-C
MONITOR_LINE = 1 << 16
MONITOR_RUN_PART = 100_000


class ServedChip(Chip):
    """A chip on the line: its serial port mode (the chip's own register, kept here as it changes:
    the framing and the line's timing follow it) and, with --record, its cycles' rows."""

    record_names: List[str] = []

    def _step(self, cycles: int) -> int:
        # with --record every cycle the host's traffic runs is recorded (Chip.run's recorder)
        if not self.record_names:
            return super()._step(cycles)
        self.rows.append(self._run(cycles, self.record_names, None))
        return 0

    def start(self, address: Optional[int], record: bool) -> None:
        """The mode after reset (GetSerialPortMode, sent in no chip time), then, on a line of several
        chips, multi-drop with this address; then every command takes its time on the line."""
        self.host_interface = hosttime.HostInterface("none")
        self.rows: List[np.ndarray] = []
        self.record_names = list(RECORDED) if record else []
        baud, parity, stop, _protocol, _address = self.command(0, "GetSerialPortMode")
        self.reset_mode = sp.SerialPortMode.word(baud, parity, stop, sp.POINT_TO_POINT, 0)
        mode = self.reset_mode
        if address is not None:
            self.command(0, "SetSerialPortMode", [baud, parity, stop, sp.MULTI_DROP_ADDRESS_BIT, address])
            mode = sp.SerialPortMode.word(baud, parity, stop, sp.MULTI_DROP_ADDRESS_BIT, address)
        self.set_mode(mode)

    def set_mode(self, word: int) -> None:
        """A new serial port mode: from the next command on (reference 3.3: the reply to
        SetSerialPortMode still goes out with the old settings)."""
        self.mode = sp.SerialPortMode.of(word)
        self.host_interface = hosttime.HostInterface(
            "serial", baud=self.mode.baud, parity=1 if self.mode.parity else 0, stop_bits=self.mode.stop_bits
        )

    def recording(self) -> np.ndarray:
        return np.concatenate(self.rows) if self.rows else np.zeros(0, dtype=self._columns(self.record_names)[1])


class Line:
    """The chips on one serial line: bytes in, the chips' replies out."""

    def __init__(self, chips: List[ServedChip], realtime: bool = False, log: Optional[IO[str]] = None):
        self.chips = chips
        self.realtime = realtime
        self.log = log
        self.decoder = sp.PacketDecoder()
        self.line_ns = 0  # the line's clock: ns of chip time its traffic (and, --realtime, the wall) took
        self.t0 = time.monotonic_ns()
        self.packets = 0

    def _line(self, text: str) -> None:
        if self.log:
            self.log.write(text + "\n")

    def tick(self) -> None:
        """--realtime: every chip runs the cycles the wall clock has reached."""
        if not self.realtime:
            return
        wall = time.monotonic_ns() - self.t0
        for c in self.chips:
            if wall > c.host_time_ns:
                c.wait_ns(wall - c.host_time_ns)
        self.line_ns = max(self.line_ns, wall)

    def receive(self, data: bytes) -> bytes:
        """The replies to the packets data completes."""
        out = b""
        for packet in self.decoder.feed(data):
            out += self.packet(packet)
        return out

    def disconnected(self, why: str) -> None:
        """A client went: a packet it left unfinished is dropped, never executed."""
        dropped = self.decoder.reset()
        self._line(
            f"{self.line_ns} ns: {why}" + (f"; {dropped} bytes of an unfinished packet dropped" if dropped else "")
        )

    def restart(self) -> None:
        """--reset-on-connect: every chip as new, the line's clock at 0."""
        for c in self.chips:
            address = c.mode.address if c.mode.multi_drop else None
            record = bool(c.record_names)
            c.reinitialize(**c.parameters)
            c.start(address, record)
        self.line_ns, self.t0 = 0, time.monotonic_ns()

    def catch_up(self, chip: ServedChip) -> None:
        """The chip runs the cycles the line's time (its other traffic, a monitor's wait) has reached."""
        if chip.host_time_ns < self.line_ns:
            chip.wait_ns(self.line_ns - chip.host_time_ns)

    def wait_ns(self, ns: int) -> None:
        """Host time passes on the line without traffic (a monitor's wait: the host's sleep)."""
        self.line_ns += ns
        for c in self.chips:
            self.catch_up(c)

    def packet(self, p: sp.Packet) -> bytes:
        self.packets += 1
        self.tick()
        words = 1 + len(p.args)
        reply = b""
        targets = [c for c in self.chips if c.mode.answers(p.address)]
        if not targets:  # for another address: its bytes still take the line's time
            self.line_ns += self.chips[0].host_interface.request_ns(words)
            self._line(f"{self.line_ns} ns: in {p.data.hex(' ')}: no chip at address {p.address}")
            return b""
        for c in targets:
            self.catch_up(c)
            address = c.mode.reply_address()
            if not p.checksum_ok:  # received whole, answered with the checksum error, not executed
                c.wait_ns(c.host_interface.request_ns(words))
                status, result = sp.BAD_CHECKSUM, []
                c.wait_ns(c.host_interface.reply_ns(0, failed=True))
            else:
                status, result = c.batch([p.instruction, *p.args])
                if status == 0 and p.opcode == sp.SET_SERIAL_PORT_MODE:
                    c.set_mode(p.args[0])
                elif status == 0 and p.opcode == sp.RESET:
                    c.set_mode(c.reset_mode)
            self.line_ns = max(self.line_ns, c.host_time_ns)
            answer = sp.reply_packet(status, result, address)
            reply += answer
            if self.log:
                name = sp.OPCODE_NAMES.get(p.opcode, "unknown opcode")
                self._line(
                    f"{self.line_ns} ns cycle {c.cycles} chip {self.chips.index(c)}: in {p.data.hex(' ')} "
                    f"({name}) out {answer.hex(' ')}"
                )
        return reply


# ---- the endpoints ----


class _Stop:
    """SIGINT and SIGTERM end the server between packets: the handler sets the flag, and the
    wake-up pipe ends the select the loop waits in."""

    def __init__(self):
        self.signal = 0
        self.r, self.w = os.pipe()
        os.set_blocking(self.w, False)
        os.set_blocking(self.r, False)
        self.old = {s: signal.signal(s, self._handle) for s in (signal.SIGINT, signal.SIGTERM)}
        self.old_fd = signal.set_wakeup_fd(self.w)

    def _handle(self, signum, _frame) -> None:
        self.signal = signum

    def close(self) -> None:
        signal.set_wakeup_fd(self.old_fd)
        for s, h in self.old.items():
            signal.signal(s, h)
        os.close(self.r)
        os.close(self.w)


def _write_all(fd: int, data: bytes, stop: "_Stop") -> bool:
    """Writes data whole into a non-blocking fd; False if the client went meanwhile, or if the server is
    stopping while a client that reads no replies keeps the fd full (a blocking write waited for it for
    ever: SIGTERM and Ctrl-C could not stop the server). A client that reads gets its reply whole, also
    when the signal came while the chip computed it: the server stops between packets."""
    view = memoryview(data)
    while view:
        try:
            n = os.write(fd, view)
        except BlockingIOError:
            if stop.signal:
                return False
            select.select([], [fd], [], 1.0)
            continue
        except OSError as e:
            if e.errno in (errno.EIO, errno.EPIPE, errno.ECONNRESET):
                return False
            raise
        view = view[n:]
    return True


class PtyEndpoint:
    """A pseudo-terminal, PATH a symlink to its slave side (as socat's link=). The chip sees no
    connection on a serial line, but a pty tells when the last client closed it (EIO): the server
    then drops an unfinished packet and waits for the next client."""

    def __init__(self, path: Path):
        self.path = path
        if os.path.lexists(path):
            raise FileExistsError(errno.EEXIST, "exists already: pmdfmu serve makes the link itself", str(path))
        self.master, slave = os.openpty()
        # raw bytes both ways (no echo, no line editing) for a client that sets no mode of its own
        tty.setraw(slave, termios.TCSANOW)
        self.slave_name = os.ttyname(slave)
        os.close(slave)
        os.set_blocking(self.master, False)
        os.symlink(self.slave_name, path)
        self.connected = False

    def describe(self) -> str:
        return f"serial {self.path} (pty {self.slave_name})"

    def close(self) -> None:
        try:
            if os.readlink(self.path) == self.slave_name:
                os.unlink(self.path)
        except OSError:
            pass
        os.close(self.master)


def _monitor_ready(monitor: Optional[Monitor], readable: list) -> list:
    """The monitor's readable sockets served; the rest of readable."""
    if monitor is None:
        return readable
    mine = monitor.sockets()  # taken before serving them: a client served may go meanwhile
    for sock in [r for r in readable if r in mine]:
        monitor.ready(sock)
    return [r for r in readable if r not in mine]


def _serve_pty(end: PtyEndpoint, line: Line, stop: _Stop, reset_on_connect: bool, monitor: Optional[Monitor]) -> None:
    while not stop.signal:
        waiting = [end.master, stop.r, *(monitor.sockets() if monitor else [])]
        readable, _, _ = select.select(waiting, [], [], IDLE_TICK if line.realtime else None)
        if stop.r in readable:
            os.read(stop.r, 64)
            continue
        rest = _monitor_ready(monitor, readable)
        if readable and not rest:
            continue  # the monitor's turn only
        readable = rest
        if end.master not in readable:
            line.tick()
            continue
        try:
            data = os.read(end.master, 65536)
        except BlockingIOError:
            continue
        except OSError as e:
            if e.errno != errno.EIO:
                raise
            # no client has the slave open: wait for one (a pty's master is readable meanwhile)
            if end.connected:
                end.connected = False
                line.disconnected("the client closed the port")
            time.sleep(RECONNECT_POLL)
            line.tick()
            continue
        if not end.connected:
            end.connected = True
            if reset_on_connect:
                line.restart()
        reply = line.receive(data)
        if reply and not _write_all(end.master, reply, stop):
            end.connected = False
            line.disconnected("the client closed the port before the reply")


class TcpEndpoint:
    """A TCP port, one client at a time, the bytes as on the serial line (a serial-to-Ethernet
    converter); the next client waits in the listen queue."""

    def __init__(self, host: str, port: int):
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
        family, kind, proto, _name, address = infos[0]
        self.listener = socket.socket(family, kind, proto)
        self.listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.listener.bind(address)
        self.listener.listen(8)
        self.address = self.listener.getsockname()

    def describe(self) -> str:
        host, port = self.address[0], self.address[1]
        return f"tcp {'[' + host + ']' if ':' in host else host}:{port}"

    def close(self) -> None:
        self.listener.close()


class Monitor:
    """The twin's monitor: one request a line, one reply a line, `ok [VALUE]` or `error REASON`
    (docs/device.md, "The monitor"). Requests go to the selected chip (`chip K`, K its multi-drop
    address; 0 at first), each client its own; several clients may be connected.

        chip K              select chip K
        run N               the chip runs N cycles; the line's clock moves up to its last cycle
        wait NS             the line's clock moves on NS ns; every chip runs the cycles due
        time                the line's clock, ns (the host time PMDFMU_GetHostTime gives in-process)
        get NAME            an FMU variable of the chip (PMDFMU_GetInteger, PMDFMU_GetReal)
        write ADDRESS W...  32-bit words into the chip's dual-port memory (PMDWriteDPRAM)

    Under --realtime the chips follow the wall clock: run and wait are refused."""

    def __init__(self, host: str, port: int, line: Line, stop: "_Stop"):
        self.endpoint = TcpEndpoint(host, port)
        self.line = line
        self.stop = stop
        self.clients: dict = {}  # socket -> [bytes received, the chip selected, inside a line refused]

    def describe(self) -> str:
        return "monitor " + self.endpoint.describe()

    def sockets(self) -> list:
        return [self.endpoint.listener, *self.clients]

    def ready(self, sock) -> None:
        """A readable socket of the monitor's: a new client, or a client's bytes (or its going)."""
        if sock is self.endpoint.listener:
            client, _peer = sock.accept()
            client.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            client.setblocking(False)  # _write_all
            self.clients[client] = [b"", 0, False]  # bytes received, the chip selected, inside a line refused
            return
        state = self.clients[sock]
        try:
            data = sock.recv(65536)
        except BlockingIOError:
            return
        except OSError:
            data = b""
        if not data:
            self._drop(sock)
            return
        state[0] += data
        too_long = f"error a request longer than {MONITOR_LINE} bytes"
        while True:
            request, newline, rest = state[0].partition(b"\n")
            reply = None
            if not newline:  # a line not yet whole: one too long is refused now, its bytes dropped to its end
                if len(request) > MONITOR_LINE and not state[2]:
                    state[2], reply = True, too_long
                if state[2]:
                    state[0] = b""
            elif state[2]:  # the end of a line refused
                state[0], state[2] = rest, False
                continue
            else:
                state[0] = rest
                reply = too_long if len(request) > MONITOR_LINE else self.answer(request, state)
            if reply is not None and not _write_all(sock.fileno(), (reply + "\n").encode(), self.stop):
                self._drop(sock)
                return
            if not newline:
                return

    def _drop(self, sock) -> None:
        del self.clients[sock]
        sock.close()

    def close(self) -> None:
        for sock in list(self.clients):
            self._drop(sock)
        self.endpoint.close()

    def answer(self, request: bytes, state: list) -> str:
        text = request.decode("ascii", "replace").strip()
        try:
            reply = self._do(text.split(), state)
        except (ValueError, KeyError, OverflowError, FMUError) as e:  # a bad request, or the FMU's refusal: one line
            reply = "error " + " ".join(str(e).split())[:1000]
        self.line._line(f"{self.line.line_ns} ns: monitor {text!r} -> {reply}")
        return reply

    def _do(self, words: List[str], state: list) -> str:
        if not words:
            raise ValueError("an empty request (chip, run, wait, time, get, write)")
        verb, args = words[0], words[1:]
        chips = self.line.chips
        if verb == "chip" and len(args) == 1:
            k = _count(args[0], "chip")
            if k >= len(chips):
                raise ValueError(f"chip {k}: the line has chips 0..{len(chips) - 1}")
            state[1] = k
            return "ok"
        if verb == "time" and not args:
            return f"ok {self.line.line_ns}"
        chip = chips[state[1]]
        if verb in ("run", "wait") and len(args) == 1:
            n = _count(args[0], verb)
            if self.line.realtime:
                raise ValueError(f"{verb}: under --realtime the chips follow the wall clock")
            # a long run or wait goes in parts, and still stops within a moment of Ctrl-C
            if verb == "wait":
                part = max(1, round(MONITOR_RUN_PART * chip.cycle_time * 1e9))
                while n and not self.stop.signal:
                    self.line.wait_ns(min(n, part))
                    n -= min(n, part)
                return "ok" if not n else f"error stopped with {n} ns not waited: the server is stopping"
            self.line.catch_up(chip)
            while n and not self.stop.signal:
                part = min(n, MONITOR_RUN_PART)
                chip.run(part)
                n -= part
            self.line.line_ns = max(self.line.line_ns, chip.host_time_ns)
            return "ok" if not n else f"error stopped with {n} cycles not run: the server is stopping"
        if verb == "get" and len(args) == 1:
            value = chip.get(args[0])  # a Boolean as 0 or 1, a Real in the digits that read back the same
            if isinstance(value, str):  # a script's text may hold line feeds: no one-line answer
                raise ValueError(
                    f"get {args[0]}: a String variable; the monitor answers numbers (Integer, Boolean, Real)"
                )
            return f"ok {int(value)}" if isinstance(value, (bool, int)) else f"ok {float(value)!r}"
        if verb == "write" and len(args) >= 2:
            chip.write_memory(_count(args[0], "write: address"), [int(w, 0) for w in args[1:]])
            return "ok"
        raise ValueError(
            f"{' '.join(words)[:80]!r}: not a request (chip K, run N, wait NS, time, get NAME, write ADDRESS WORD...)"
        )


def _count(text: str, what: str) -> int:
    """A whole number >= 0 of a monitor request."""
    if not text.isdigit():
        raise ValueError(f"{what} {text[:40]!r}: expected a whole number >= 0")
    return int(text)


def _serve_tcp(end: TcpEndpoint, line: Line, stop: _Stop, reset_on_connect: bool, monitor: Optional[Monitor]) -> None:
    client: Optional[socket.socket] = None
    try:
        while not stop.signal:
            waiting = [stop.r, client if client else end.listener, *(monitor.sockets() if monitor else [])]
            readable, _, _ = select.select(waiting, [], [], IDLE_TICK if line.realtime else None)
            if stop.r in readable:
                os.read(stop.r, 64)
                continue
            if readable and not _monitor_ready(monitor, readable):
                continue  # the monitor's turn only
            if not readable:
                line.tick()
                continue
            if client is None:
                client, _peer = end.listener.accept()
                client.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                client.setblocking(False)  # _write_all
                if reset_on_connect:
                    line.restart()
                continue
            try:
                data = client.recv(65536)
            except BlockingIOError:
                continue
            except OSError:
                data = b""
            if not data:
                client.close()
                client = None
                line.disconnected("the client disconnected")
                continue
            reply = line.receive(data)
            if reply and not _write_all(client.fileno(), reply, stop):
                client.close()
                client = None
                line.disconnected("the client disconnected before the reply")
    finally:
        if client is not None:
            client.close()


def record_paths(record: Optional[Path], chips: int) -> List[Path]:
    """The files --record writes: record itself for one chip, else NAME-chipK.SUFFIX for chip K."""
    if record is None:
        return []
    return [record] if chips == 1 else [record.with_name(f"{record.stem}-chip{k}{record.suffix}") for k in range(chips)]


def serve(
    serial: Optional[Path] = None,
    tcp: Optional[tuple] = None,
    chips: int = 1,
    fmi_version: int = 2,
    fmu: Optional[Path] = None,
    realtime: bool = False,
    reset_on_connect: bool = False,
    record: Optional[Path] = None,
    log: Optional[Path] = None,
    monitor: Optional[tuple] = None,
    out: IO[str] = sys.stdout,
    **parameters,
) -> int:
    """Serves until SIGINT or SIGTERM (the normal stop: returns 0); parameters are the FMU's
    (cycleTime, script, machine)."""
    from .verify import write_recording

    served: List[ServedChip] = []
    end = watcher = None
    log_file = open(log, "w") if log else None
    stop = _Stop()
    try:
        for k in range(chips):
            c = ServedChip(fmi_version, fmu, **parameters)
            c.parameters = parameters
            served.append(c)
            c.start(k if chips > 1 else None, record is not None)
        end = PtyEndpoint(serial) if serial is not None else TcpEndpoint(*tcp)
        line = Line(served, realtime, log_file)
        watcher = Monitor(*monitor, line, stop) if monitor is not None else None
        m = served[0].mode
        time_text = (
            "real time: chip cycles paced to the wall clock"
            if realtime
            else f"virtual time: chip time from the line's traffic at {m.baud} baud"
        )
        drop = f", multi-drop addresses 0..{chips - 1}" if chips > 1 else ""
        print(f"pmdfmu serve: {end.describe()}, {chips} chip{'s' if chips > 1 else ''}{drop}, {time_text}", file=out)
        print(f"{watcher.describe()}; " if watcher else "", "Ctrl-C or SIGTERM stops it", sep="", file=out, flush=True)
        (_serve_pty if serial is not None else _serve_tcp)(end, line, stop, reset_on_connect, watcher)
        print(f"pmdfmu serve: stopped after {line.packets} packets", file=out, flush=True)
        if record is not None:
            for path, c in zip(record_paths(record, chips), served):
                write_recording(path, c.recording())
                print(f"wrote {path}", file=out, flush=True)
        return 0
    finally:
        stop.close()
        if end is not None:
            end.close()
        if watcher is not None:
            watcher.close()
        if log_file:
            log_file.close()
        for c in served:
            c.close()
