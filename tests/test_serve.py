# SPDX-License-Identifier: BSD-2-Clause
"""`pmdfmu serve` with real clients (docs/device.md): pyserial on the pty, sockets on TCP,
pmdfmu.Chip(device=...). Every reply equals, byte for byte, what the twin in-process answers
with host_interface="serial" to the same commands, so chip times equal the host timing model's."""

import math
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu import serial_protocol as sp
from pmdfmu.chip import COMMANDS, encode, instruction_word
from pmdfmu.line import LineChip, NeedsFMU

serial = pytest.importorskip("serial")  # pyserial: the test extra's

PMDFMU = Path(sys.executable).parent / "pmdfmu"


class Server:
    """pmdfmu serve in a process of its own; its first line says where it listens."""

    def __init__(self, *args):
        self.process = subprocess.Popen(
            [str(PMDFMU), "serve", *map(str, args)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
        )
        self.first = self.process.stdout.readline()
        assert self.first.startswith("pmdfmu serve: "), self.first + self.process.stderr.read()
        self.second = self.process.stdout.readline()  # the monitor's endpoint (--monitor), how to stop it

    @property
    def tcp(self):
        host_port = self.first.split()[3].rstrip(",")
        host, _, port = host_port.rpartition(":")
        return host, int(port)

    def stop(self, sig=signal.SIGINT):
        self.process.send_signal(sig)
        out, err = self.process.communicate(timeout=60)
        return self.process.returncode, out, err

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.process.poll() is None:
            self.process.kill()
            self.process.communicate()


def packet(name, args=(), axis=0, address=0):
    c = COMMANDS[name]
    return sp.command_packet(instruction_word(c.opcode, 0 if c.scope == "chip" else axis), encode(c, args), address)


class Twin:
    """The reference: the twin in-process, each good packet sent as a timed batch on the serial host
    interface, a packet with a bad checksum only its time on the line (it is not executed)."""

    def __init__(self):
        self.chip = pmdfmu.Chip(host_interface="serial")

    def reply(self, data: bytes) -> bytes:
        out = b""
        for p in sp.PacketDecoder().feed(data):
            if not p.checksum_ok:
                h = self.chip.host_interface
                self.chip.wait_ns(h.request_ns(1 + len(p.args)) + h.reply_ns(0, failed=True))
                out += sp.reply_packet(sp.BAD_CHECKSUM)
                continue
            status, words = self.chip.batch([p.instruction, *p.args])
            out += sp.reply_packet(status, words)
        return out


def exchange(port, data: bytes, n: int) -> bytes:
    port.write(data)
    return port.read(n)


def reply_length(name, failed=False):
    return sp.reply_length(0 if failed else COMMANDS[name].reply_words)


@pytest.fixture
def pty_server(tmp_path):
    link = tmp_path / "pmd"
    with Server("--serial", link, "--log", tmp_path / "log.txt", "--record", tmp_path / "rec.csv") as s:
        s.link = link
        yield s


def test_a_pyserial_session_is_answered_as_the_twin_in_process_answers_it(pty_server, tmp_path):
    """Version, a trapezoidal move polled to motion complete, an external profile uploaded with
    WriteBuffer and run, a bad checksum, an opcode the Navigator lacks, garbage then C-Motion's
    resynchronisation: byte for byte the in-process twin's replies, GetTime's chip times included."""
    twin = Twin()
    port = serial.Serial(str(pty_server.link), 57600, timeout=2)

    def same(data, n):
        got = exchange(port, data, n)
        assert got == twin.reply(data), data.hex(" ")
        return got

    version = same(packet("GetVersion"), reply_length("GetVersion"))
    assert version[0] == 0 and len(version) == 6
    for name, args in [
        ("SetProfileMode", [pmdfmu.PMDTrapezoidal]),
        ("SetPosition", [2000]),
        ("SetVelocity", [0x40000]),
        ("SetAcceleration", [0x1000]),
        ("SetDeceleration", [0x1000]),
        ("Update", []),
    ]:
        assert same(packet(name, args), reply_length(name)) == b"\x00\x00"
    polls = 0
    while True:
        status = sp.parse_reply(same(packet("GetEventStatus"), reply_length("GetEventStatus")))[1][0]
        polls += 1
        if status & pmdfmu.PMDEventMotionCompleteMask:
            break
    assert polls > 10
    same(packet("GetTime"), reply_length("GetTime"))
    # an external profile: 20 cycles at 1 count/cycle, uploaded through the processor (WriteBuffer)
    rows = [(0, 0x10000, 0, 0, 20), (20, 0, 0, 0, 0)]
    for f in range(5):
        for name, args in [
            ("SetBufferStart", [2 + f, 0x200 + 8 * f]),
            ("SetBufferLength", [2 + f, 8]),
            ("SetBufferFunction", [f, 2 + f]),
        ]:
            same(packet(name, args), reply_length(name))
        for row in rows:
            same(packet("WriteBuffer", [2 + f, row[f]]), reply_length("WriteBuffer"))
    for name, args in [("SetProfileMode", [pmdfmu.PMDExternalProfile]), ("Update", [])]:
        same(packet(name, args), reply_length(name))
    while sp.parse_reply(same(packet("GetActivityStatus"), 4))[1][0] & pmdfmu.PMDActivityProfileSegmentMask:
        pass
    assert sp.parse_reply(same(packet("GetCommandedPosition"), 6))[1] == [0, 20]  # the rows are positions
    # a bad checksum: the checksum error alone, nothing executed
    bad = bytearray(packet("SetPosition", [777]))
    bad[1] ^= 0x55
    assert same(bytes(bad), 2) == bytes.fromhex("09 f7")
    assert sp.parse_reply(same(packet("GetPosition"), 6))[1] == [0, 2000]
    # an opcode the Navigator lacks (SetOperatingMode, Magellan only): invalid instruction
    assert same(sp.command_packet(0x65, [1]), 2) == bytes.fromhex("02 fe")
    # garbage, then single zero bytes until a 2-byte reply comes back
    port.write(bytes.fromhex("05 07"))
    twin_garbage, port.timeout = b"\x05\x07", 0.2
    for _ in range(8):
        port.write(b"\0")
        twin_garbage += b"\0"
        got = port.read(2)
        if len(got) == 2:
            break
    port.timeout = 2
    assert got == twin.reply(twin_garbage)
    same(packet("GetTime"), reply_length("GetTime"))
    port.close()
    code, out, err = pty_server.stop()
    assert code == 0 and not err and not pty_server.link.exists()
    assert "wrote" in out
    log = (tmp_path / "log.txt").read_text()
    assert "in 00 71 00 8f (GetVersion) out " + version.hex(" ") in log
    recording = (tmp_path / "rec.csv").read_text().splitlines()
    assert recording[0].startswith("cycle,axis1.commandedPosition")
    assert int(recording[-1].split(",")[0]) == twin.chip.cycles - 1


def test_a_baud_change_takes_effect_from_the_next_command(tmp_path):
    """Reference 3.3: the reply to SetSerialPortMode still goes at the old baud; the next command's
    bytes take 115200's time, as the twin in-process with that host interface from then on."""
    twin = Twin()
    with Server("--serial", tmp_path / "pmd") as s:
        port = serial.Serial(str(tmp_path / "pmd"), 57600, timeout=2)
        mode = packet("SetSerialPortMode", [pmdfmu.PMDSerialBaud115200, 0, 0, 0, 0])
        assert exchange(port, mode, 2) == twin.reply(mode) == b"\x00\x00"
        twin.chip.host_interface = pmdfmu.HostInterface("serial", baud=115200)
        for _ in range(3):
            assert exchange(port, packet("GetTime"), 6) == twin.reply(packet("GetTime"))
        port.close()
        assert s.stop()[0] == 0


def test_tcp_clients_one_after_another_and_one_killed_mid_packet(tmp_path):
    """The chip stays as the last client left it; a packet cut by a disconnect is never executed,
    and the next client is answered at once."""
    with Server("--tcp", "127.0.0.1:0") as s:
        with socket.create_connection(s.tcp) as c:
            c.sendall(packet("SetPosition", [1234]))
            assert c.recv(2) == b"\x00\x00"
        with socket.create_connection(s.tcp) as c:
            c.sendall(packet("GetPosition"))
            assert sp.parse_reply(c.recv(6)) == (0, [0, 1234])
        cut = packet("SetPosition", [4321])[:5]
        killed = subprocess.run(
            [
                sys.executable,
                "-c",
                "import os, socket, sys; c = socket.create_connection(('%s', %d)); c.sendall(bytes.fromhex(sys.argv[1])); "
                "os.kill(os.getpid(), 9)" % s.tcp,
                cut.hex(),
            ]
        )
        assert killed.returncode == -9
        with pmdfmu.Chip(device="tcp:%s:%d" % s.tcp) as chip:
            ax = chip.axis(pmdfmu.PMDAxis1)
            assert ax.GetPosition() == 1234
            assert ax.GetVersion() == pmdfmu.Chip().axis(0).GetVersion()
            with pytest.raises(NeedsFMU, match="needs the twin in-process"):
                chip.run(10)
            with pytest.raises(pmdfmu.PMDError):
                ax.SetBufferFunction(99, 99)
            # chip.send over the line: a command's raw words, its reply words; an opcode of no command
            # (0x04: not a C-Motion call either, so its packet has no data words) refused as in-process
            assert chip.send(instruction_word(COMMANDS["GetPosition"].opcode, 0)) == (0, 1234)
            with pytest.raises(pmdfmu.PMDError, match="instruction word 0x0004") as refused:
                chip.send(0x0004)
            assert refused.value.code == pmdfmu.PMD_ERR_InvalidInstruction
        # a flood: 0xFF bytes frame as packets of an unknown opcode with a bad checksum, each answered
        # with the checksum error; the client goes without reading them, the server stays up
        with socket.create_connection(s.tcp) as c:
            c.sendall(b"\xff" * 50_001)
        with pmdfmu.Chip(device="tcp:%s:%d" % s.tcp) as chip:
            assert chip.axis(0).GetPosition() == 1234
        code, out, err = s.stop(signal.SIGTERM)
        assert code == 0 and not err


def test_a_multi_drop_line_of_two_chips_each_answering_only_its_address(tmp_path):
    """--chips 2: addresses 0 and 1; a packet for address 5 gets no answer; each chip keeps its own
    registers; Chip(device=..., address=1) talks to the second."""
    with Server("--tcp", "127.0.0.1:0", "--chips", "2") as s:
        assert "multi-drop addresses 0..1" in s.first
        with socket.create_connection(s.tcp) as c:
            c.settimeout(2)
            c.sendall(packet("SetPosition", [500], address=1))
            assert c.recv(2) == b"\x00\x00"
            c.sendall(packet("GetSerialPortMode", address=1))
            assert sp.parse_reply(c.recv(4))[1] == [sp.SerialPortMode.word(4, 0, 0, sp.MULTI_DROP_ADDRESS_BIT, 1)]
            c.sendall(packet("GetPosition", address=5))
            c.settimeout(0.3)
            with pytest.raises(socket.timeout):
                c.recv(6)
        with pmdfmu.Chip(device="tcp:%s:%d" % s.tcp, address=0) as chip0:
            assert chip0.axis(0).GetPosition() == 0
        with pmdfmu.Chip(device="tcp:%s:%d" % s.tcp, address=1) as chip1:
            assert chip1.axis(0).GetPosition() == 500
        assert s.stop()[0] == 0


def test_reset_on_connect_gives_each_client_a_chip_as_after_power_up(tmp_path):
    with Server("--tcp", "127.0.0.1:0", "--reset-on-connect") as s:
        for _ in range(2):
            with pmdfmu.Chip(device="tcp:%s:%d" % s.tcp) as chip:
                assert chip.axis(0).GetHostIOError() == pmdfmu.PMD_ERR_ChipsetReset
        assert s.stop()[0] == 0


def test_realtime_says_so_in_its_first_line_and_chip_time_follows_the_wall_clock(tmp_path):
    with Server("--tcp", "127.0.0.1:0", "--realtime") as s:
        assert "real time" in s.first
        with pmdfmu.Chip(device="tcp:%s:%d" % s.tcp) as chip:
            t0 = chip.axis(0).GetTime()
            time.sleep(0.3)
            t1 = chip.axis(0).GetTime()
        assert 2000 <= t1 - t0 <= 30000  # 0.3 s of 100 us cycles, give or take a slow machine
        assert s.stop()[0] == 0


@pytest.mark.parametrize(
    "args,reason",
    [
        (["--tcp", "nowhere"], "argument --tcp: invalid HOST:PORT value"),
        (["--tcp", "127.0.0.1:0", "--chips", "33"], "invalid number of chips 1..32 value"),
        (["--serial", "{existing}"], "exists already"),
        (["--tcp", "127.0.0.1:0", "--script", "{missing}"], "No such file"),
        # at once, not when Ctrl-C ends the session whose recording it was
        (["--tcp", "127.0.0.1:0", "--record", "{missing}/r.csv"], "is no folder to write it in"),
    ],
)
def test_bad_command_lines_exit_2_with_one_line(tmp_path, args, reason):
    existing = tmp_path / "file"
    existing.write_text("")
    args = [a.format(existing=existing, missing=tmp_path / "missing.script") for a in args]
    out = subprocess.run([str(PMDFMU), "serve", *args], capture_output=True, text=True, timeout=60)
    assert out.returncode == 2
    assert len(out.stderr.splitlines()) == 1 and out.stderr.startswith("pmdfmu serve")
    assert reason in out.stderr
    assert os.path.exists(existing)


# ---- the twin's monitor (--monitor) ----


def monitor_of(server):
    """--monitor's HOST:PORT, from the server's second line."""
    return server.second.split(";")[0].split()[-1]


def ask(sock, request: bytes) -> str:
    sock.sendall(request + b"\n")
    reply = b""
    while not reply.endswith(b"\n"):
        chunk = sock.recv(4096)
        assert chunk, "the monitor closed the connection"
        reply += chunk
    return reply.decode().rstrip("\n")


@pytest.mark.parametrize("device", ["tcp:127.0.0.1:port", "tcp:4001", "ttyS0"])
def test_a_device_that_is_no_line_is_refused_by_its_name(device):
    with pytest.raises(ValueError, match=f"device '{device}': serial:PATH or tcp:HOST:PORT"):
        LineChip(device)


def test_a_line_that_cannot_be_opened_is_named(tmp_path):
    """The OSError keeps its type, and says which device: ConnectionRefusedError said only
    "[Errno 111] Connection refused"."""
    with socket.create_server(("127.0.0.1", 0)) as gone:
        closed = "tcp:127.0.0.1:%d" % gone.getsockname()[1]
    with pytest.raises(ConnectionRefusedError, match=f"device '{closed}': cannot connect: Connection refused"):
        pmdfmu.Chip(device=closed)
    missing = f"serial:{tmp_path / 'pmd'}"
    with pytest.raises(FileNotFoundError, match=f"device '{missing}': cannot open the line: No such file"):
        pmdfmu.Chip(device=missing)


def test_a_line_error_without_an_errno_is_named_without_one(monkeypatch):
    """socket.create_connection raises OSError("getaddrinfo returns an empty list"), errno None."""

    def empty(address):
        raise OSError("getaddrinfo returns an empty list")

    monkeypatch.setattr(socket, "create_connection", empty)
    with pytest.raises(OSError) as info:
        LineChip("tcp:example.invalid:1")
    assert str(info.value) == "device 'tcp:example.invalid:1': cannot connect: getaddrinfo returns an empty list"


def test_a_refused_monitor_closes_the_line_it_opened():
    with socket.create_server(("127.0.0.1", 0)) as line, socket.create_server(("127.0.0.1", 0)) as gone:
        closed = "tcp:127.0.0.1:%d" % gone.getsockname()[1]
        gone.close()  # nobody listens there now
        fds = len(os.listdir("/proc/self/fd"))
        with pytest.raises(ConnectionRefusedError) as refused:
            LineChip("tcp:127.0.0.1:%d" % line.getsockname()[1], monitor=closed)
        # closed at once, not when the collector frees the LineChip the traceback holds
        assert refused.traceback and len(os.listdir("/proc/self/fd")) == fds


def test_a_chip_the_monitor_refuses_closes_the_line_and_the_monitor(tmp_path):
    """`chip 5` on a line of one chip: the monitor's refusal is raised, and what the LineChip opened
    (the line, the monitor's connection) is closed before it is."""
    link = tmp_path / "pmd"
    with Server("--serial", link, "--monitor", "127.0.0.1:0") as s:
        fds = len(os.listdir("/proc/self/fd"))
        with pytest.raises(pmdfmu.line.MonitorRefusal) as refused:
            LineChip(f"serial:{link}", address=5, monitor="tcp:" + monitor_of(s))
        assert refused.traceback and len(os.listdir("/proc/self/fd")) == fds
        assert s.stop()[0] == 0


def test_the_monitor_gives_a_line_chip_what_the_twin_in_process_gives(tmp_path):
    """Chip(device=..., monitor=...): commands over the line, cycles, waits, FMU variables, the dual-port
    memory and the host clock through the monitor; every value equals the twin in-process timed as a
    serial line, and the server's recording has every cycle."""
    link, record = tmp_path / "pmd", tmp_path / "rec.csv"

    def session(chip):
        ax = chip.axis(pmdfmu.PMDAxis1)
        ax.SetProfileMode(pmdfmu.PMDTrapezoidal)
        ax.SetPosition(3000)
        ax.SetVelocity(0x40000)
        ax.SetAcceleration(0x1000)
        ax.Update()
        chip.run(150)
        seen = [chip.cycles, chip.host_time_ns, chip.get("axis1.commandedPosition"), chip.get("axis1.position")]
        chip.wait(0.0123)
        chip.write_memory(0x300, [7, -1, 0xFFFFFFFF])
        ax.SetBufferStart(0, 0x300)
        ax.SetBufferLength(0, 3)
        seen += [chip.cycles, chip.host_time_ns, ax.ReadBuffer(0), ax.ReadBuffer(0), ax.GetPosition()]
        seen += [chip.get("host.interrupt"), chip.get("cycleTime"), ax.GetTime()]
        return seen + [chip.cycles]

    with pmdfmu.Chip(host_interface="serial") as twin:
        expected = session(twin)
    with Server("--serial", link, "--monitor", "127.0.0.1:0", "--record", record) as s:
        assert s.second.startswith("monitor tcp 127.0.0.1:")
        with pmdfmu.Chip(device=f"serial:{link}", monitor="tcp:" + monitor_of(s)) as chip:
            assert session(chip) == expected
            with pytest.raises(pmdfmu.line.MonitorRefusal, match="'nope' is not a variable of the FMU"):
                chip.get("nope")
            with pytest.raises(NeedsFMU, match="pmdfmu serve --record"):
                chip.run(5, record=["axis1.commandedPosition"])
            with pytest.raises(NeedsFMU, match="needs the twin in-process"):
                chip.set("axis1.home", True)
        assert s.stop()[0] == 0
    rows = np.loadtxt(record, delimiter=",", skiprows=1, dtype=np.int64, ndmin=2)
    assert rows[:, 0].tolist() == list(range(len(rows))) and len(rows) == expected[-1]


def _flood_until_the_server_stops_reading(sock, data: bytes) -> None:
    """Sends data again and again, reading nothing, until the server has taken nothing for a second: its
    replies fill the client's small receive buffer and the server's send buffer."""
    sock.setblocking(False)
    burst, last = data * 1000, time.monotonic()
    while time.monotonic() - last < 1.0:
        try:
            if sock.send(burst):
                last = time.monotonic()
        except BlockingIOError:
            time.sleep(0.02)


def test_a_client_that_reads_no_replies_does_not_keep_the_server_from_stopping():
    """The attacker's finding: replies were written to a blocking socket, so a TCP client that sent
    requests and read nothing blocked the server in its write for ever; SIGTERM and Ctrl-C could not stop
    it. (The monitor's clients and the pty share _write_all, which now gives up when the server stops.)"""
    with Server("--tcp", "127.0.0.1:0", "--monitor", "127.0.0.1:0") as s:
        host, number = s.tcp
        with socket.socket() as sock:
            sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 2048)
            sock.connect((host, number))
            _flood_until_the_server_stops_reading(sock, packet("GetVersion"))
            s.process.send_signal(signal.SIGTERM)
            out, _err = s.process.communicate(timeout=15)  # it stops within a second or so
        assert s.process.returncode == 0 and "stopped after" in out


def test_a_reply_computed_as_the_server_is_told_to_stop_still_reaches_a_client_that_reads():
    """The server stops between packets: a SIGTERM that lands while the chip computes a reply leaves the
    reply to a client that reads (_write_all gave it up before its first write, and the client waited for
    a reply that never came); only a client whose socket stays full is given up."""
    from types import SimpleNamespace

    from pmdfmu.serve import _write_all

    stopping = SimpleNamespace(signal=signal.SIGTERM)
    server, client = socket.socketpair()
    with server, client:
        server.setblocking(False)
        assert _write_all(server.fileno(), b"reply", stopping)
        assert client.recv(16) == b"reply"
        while True:  # the client reads nothing more: its socket fills
            try:
                server.send(b"x" * 65536)
            except BlockingIOError:
                break
        started = time.monotonic()
        assert not _write_all(server.fileno(), b"reply", stopping)
        assert time.monotonic() - started < 1


def test_a_line_chips_batch_cut_short_or_with_an_unknown_opcode_does_what_chips_does():
    """The attacker's finding: Chip(device=...).batch sent a command whose data words the batch cut short
    as a short packet: the device waited for the rest, the line chip timed out after 4 s with LineError
    and resynchronised; after an unknown opcode it went on sending the batch's words as commands, where
    the twin in-process ends the batch there."""
    set_position, bogus = instruction_word(COMMANDS["SetPosition"].opcode, 0), 0x00FF
    assert bogus & 0xFF not in {c.opcode for c in COMMANDS.values()}
    with Server("--tcp", "127.0.0.1:0") as s:
        host, port = s.tcp
        with pmdfmu.Chip(device=f"tcp:{host}:{port}") as chip, pmdfmu.Chip() as twin:
            started = time.monotonic()
            with pytest.raises(ValueError, match="SetPosition .* needs 2 data words, the batch ends after 1"):
                chip.batch([set_position, 0, 7, set_position, 0])
            assert time.monotonic() - started < 1 and chip.axis(0).GetPosition() == 0
            assert chip.batch([bogus, set_position, 0, 7]) == twin.batch([bogus, set_position, 0, 7]) == (0x02, [])
            assert chip.axis(0).GetPosition() == twin.axis(0).GetPosition() == 0


def test_a_line_chip_refuses_what_chip_refuses_and_sends_nothing(tmp_path):
    """The attacker's finding: Chip(device=...).write_memory(0x300, [1.5]) wrote the word 1 and
    wait_ns(2.5) waited 2 ns (int() truncated them), wait(nan) raised Fraction's bare message, where the
    twin in-process refuses each with a ValueError naming it."""
    with Server("--tcp", "127.0.0.1:0", "--monitor", "127.0.0.1:0") as s:
        host, port = s.tcp
        with pmdfmu.Chip(device=f"tcp:{host}:{port}", monitor="tcp:" + monitor_of(s)) as chip:
            chip.write_memory(0x300, [7])
            for call, message in (
                (lambda: chip.write_memory(0x300, [1.5]), "write_memory: words\\[0\\] = 1.5 is not an integer"),
                (lambda: chip.write_memory(768.0, [1]), "write_memory: address = 768.0 is not an integer"),
                (lambda: chip.wait_ns(2.5), "wait_ns: nanoseconds = 2.5 is not an integer"),
                (lambda: chip.wait(math.nan), "wait: seconds = nan is not a finite number"),
                (lambda: chip.wait(-1), "wait: seconds = -1 s is negative"),
            ):
                with pytest.raises(ValueError, match=message):
                    call()
            assert chip.host_time_ns == 0 and chip.cycles == 0
            ax = chip.axis(pmdfmu.PMDAxis1)
            ax.SetBufferStart(0, 0x300)
            ax.SetBufferLength(0, 1)
            assert ax.ReadBuffer(0) == 7
        assert s.stop()[0] == 0


def test_the_monitor_answers_every_request_with_one_line_and_refuses_bad_ones(tmp_path):
    """Bad requests get `error REASON` and change nothing; a line too long is refused; `chip K` selects
    a chip of a multi-drop line; a client killed mid-request leaves the server answering the next."""
    with Server("--tcp", "127.0.0.1:0", "--chips", "2", "--monitor", "127.0.0.1:0") as s:
        host, _, port = monitor_of(s).rpartition(":")
        with socket.create_connection((host, int(port))) as m:
            for request, reply in [
                (b"", "error an empty request"),
                (b"fly 3", "error 'fly 3': not a request"),
                (b"run -5", "error run '-5': expected a whole number >= 0"),
                (b"run 1 2", "error 'run 1 2': not a request"),
                (b"chip 2", "error chip 2: the line has chips 0..1"),
                (b"get axis1.nope", "error get: 'axis1.nope' is not a variable of the FMU"),
                (b"write 16384 1", "error write_memory: 1 words at address 16384 leave the 16384-word memory"),
                (b"write 0 4294967296", "error write_memory:"),
                (b"\xff\xfe run", "error"),
                (b"get script", "error get script: a String variable; the monitor answers numbers"),  # was float('')'s
                (b"time", "ok 0"),
                (b"get nextCycle", "ok 0"),
                (b"chip 1", "ok"),
                (b"run 10", "ok"),
                (b"get nextCycle", "ok 10"),
                (b"time", "ok 900000"),
                (b"chip 0", "ok"),
                (b"get nextCycle", "ok 0"),  # its cycles run when the line's traffic or a wait reaches it
                (b"wait 1000000", "ok"),
                (b"get nextCycle", "ok 20"),
            ]:
                assert ask(m, request).startswith(reply), request
            assert ask(m, b"write 0 " + b"1 " * 40_000).startswith("error a request longer than 65536 bytes")
            assert ask(m, b"time") == "ok 1900000"
            rng = np.random.default_rng(27)
            for _ in range(300):  # noise: one line of reply each, nothing run
                noise = rng.integers(0, 256, rng.integers(1, 200), dtype=np.uint8).tobytes().replace(b"\n", b" ")
                assert ask(m, noise).startswith(("ok", "error ")), noise
            assert ask(m, b"time") == "ok 1900000"
        killed = subprocess.run(
            [
                sys.executable,
                "-c",
                "import os, socket; c = socket.create_connection(('%s', %s)); c.sendall(b'run 10'); "
                "os.kill(os.getpid(), 9)" % (host, port),
            ]
        )
        assert killed.returncode == -9
        with socket.create_connection((host, int(port))) as m:
            assert ask(m, b"time") == "ok 1900000"  # the cut request never ran
        assert s.stop()[0] == 0


def test_under_realtime_the_monitor_refuses_to_run_or_wait_and_ctrl_c_ends_a_long_run(tmp_path):
    with Server("--tcp", "127.0.0.1:0", "--realtime", "--monitor", "127.0.0.1:0") as s:
        host, _, port = monitor_of(s).rpartition(":")
        with socket.create_connection((host, int(port))) as m:
            assert ask(m, b"run 10") == "error run: under --realtime the chips follow the wall clock"
            assert ask(m, b"wait 10") == "error wait: under --realtime the chips follow the wall clock"
            assert ask(m, b"get chipTime").startswith("ok ")
        assert s.stop()[0] == 0
    with Server("--tcp", "127.0.0.1:0", "--monitor", "127.0.0.1:0") as s:
        host, _, port = monitor_of(s).rpartition(":")
        with socket.create_connection((host, int(port))) as m:
            m.sendall(b"run 1000000000\nwait 100000000000000\n")  # hours of cycles: Ctrl-C ends them at once
            time.sleep(1)
            start = time.monotonic()
            code, _out, err = s.stop()
            assert code == 0 and not err and time.monotonic() - start < 20
