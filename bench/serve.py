# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu serve: a command's round trip over the pty (write a GetTime packet, read its 6-byte reply)
against a raw pty echo of the same bytes (a process that writes back what it reads, the 4 bytes
out and 6 in), measured interleaved in the same run, medians. Part of ./dev bench.

Also the point of virtual time: a trapezoidal move of 5064 chip cycles (0.5 s of chip time) polled
to motion complete over the line, in wall time."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import termios
import tty
from pathlib import Path

import pmdfmu
from pmdfmu import serial_protocol as sp
from pmdfmu.chip import COMMANDS, encode, instruction_word
from common import Spread, load, report, timed

ROUND_TRIPS = 2000
RUNS = 7
TARGET = 10.0  # at most this many echoes' time per round trip

# the echo: a pty whose master side a child writes back, 6 bytes for each 4 read (the reply's size)
ECHO = """
import os, sys
fd = int(sys.argv[1])
while True:
    data = b""
    while len(data) < 4:
        data += os.read(fd, 4 - len(data))
    os.write(fd, data + data[:2])
"""


def packet(name, args=(), axis=0):
    c = COMMANDS[name]
    return sp.command_packet(instruction_word(c.opcode, 0 if c.scope == "chip" else axis), encode(c, args))


def open_raw(path) -> int:
    fd = os.open(str(path), os.O_RDWR | os.O_NOCTTY)
    tty.setraw(fd, termios.TCSANOW)
    return fd


def round_trips(fd: int, data: bytes, reply: int, n: int) -> float:
    def go():
        for _ in range(n):
            os.write(fd, data)
            got = 0
            while got < reply:
                select.select([fd], [], [])
                got += len(os.read(fd, reply - got))

    return timed(go)


def benchmarks(tmp: Path) -> None:
    link = tmp / "pmd"
    server = subprocess.Popen(
        [str(Path(sys.executable).parent / "pmdfmu"), "serve", "--serial", str(link)], stdout=subprocess.PIPE, text=True
    )
    server.stdout.readline()
    server.stdout.readline()
    master, slave = os.openpty()
    tty.setraw(slave, termios.TCSANOW)
    echo = subprocess.Popen([sys.executable, "-c", ECHO, str(master)], pass_fds=[master])
    os.close(master)
    chip_fd = open_raw(link)
    get_time = packet("GetTime")
    try:
        served, echoed = [], []
        round_trips(chip_fd, get_time, 6, 200)  # warm up both
        round_trips(slave, get_time, 6, 200)
        for _ in range(RUNS):  # interleaved: the machine's load falls on both alike
            served.append(round_trips(chip_fd, get_time, 6, ROUND_TRIPS) / ROUND_TRIPS)
            echoed.append(round_trips(slave, get_time, 6, ROUND_TRIPS) / ROUND_TRIPS)
        s, e = Spread.of(served), Spread.of(echoed)
        ratio = s.median / e.median
        report(
            f"serve: GetTime round trip over the pty ({load()})",
            s.text(1e6, "us"),
            "raw pty echo of the same bytes: " + e.text(1e6, "us"),
            ratio,
            f"<= {TARGET:g}x",
            ratio <= TARGET,
        )
        # a polled move: 5064 cycles of chip time
        with pmdfmu.Chip(device=f"serial:{link}") as chip:
            ax = chip.axis(0)

            def move():
                ax.SetProfileMode(pmdfmu.PMDTrapezoidal)
                ax.SetPosition(ax.GetCommandedPosition() + 20000)
                ax.SetVelocity(0x40000)
                ax.SetAcceleration(0x1000)
                ax.SetDeceleration(0x1000)
                ax.ResetEventStatus(0)
                ax.Update()
                while not ax.GetEventStatus() & pmdfmu.PMDEventMotionCompleteMask:
                    pass

            moves = Spread.of([timed(move) for _ in range(3)])
        report(
            "serve: a 5064-cycle (0.51 s chip time) move polled to motion complete",
            moves.text(1e3, "ms"),
            "its chip time: 506 ms",
            moves.median / 0.5064,
            "< 1 (virtual time)",
            moves.median < 0.5064,
        )
    finally:
        os.close(chip_fd)
        os.close(slave)
        echo.kill()
        echo.wait()
        server.send_signal(signal.SIGINT)
        server.wait(timeout=60)
