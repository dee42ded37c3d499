# SPDX-License-Identifier: BSD-2-Clause
"""The chip's serial packet protocol (pmd-reference 3.1-3.3), both ends: the packets a host sends
and the chip's replies, their checksums, the chip's packet decoder and the serial port mode word.

No I/O and no FMU here: `pmdfmu serve` (serve.py) runs the chip side over a pty or TCP, and
pmdfmu.Chip(device=...) (line.py) the host side. host/c/PMDserial.c is the same codec in C for the
C library; tests/data/serial_vectors.csv holds the byte vectors both are tested against.

Command packet: address, checksum, the instruction word's high byte (the axis field), the opcode,
then the data words big-endian. Reply: status (the host I/O error code), checksum, the result words
big-endian; on error the 2 bytes alone. In multi-drop idle-line mode a reply starts with the
responder's address. Every packet's bytes, checksum included, add up to 0 mod 256."""

from __future__ import annotations

import csv
import re
from typing import Dict, List, NamedTuple, Optional, Sequence, Tuple

from . import tables
from .hosttime import _tables_dir

_COMMANDS = tables.read_commands(_tables_dir() / "commands.csv")
_CONSTANTS = {name: value for _group, name, value in tables.read_constants(_tables_dir() / "constants.csv")}
_FIELDS = tables.read_fields(_tables_dir() / "constants.csv")

# data words each opcode's packet carries: commands.csv's; for an opcode the Navigator lacks
# (out_of_scope.csv), the words C-Motion sends with it (cmotion_calls.csv), so that the packet is
# answered whole with invalid instruction, as the twin in-process answers it, instead of being cut
# after 4 bytes (a choice: the public sources do not say how a Navigator frames such a packet, [L]);
# any other opcode carries none
ARG_WORDS: Dict[int, int] = {c.opcode: c.arg_words for c in _COMMANDS}
_TYPE_WORDS = {"u16": 1, "i16": 1, "u32": 2, "i32": 2}
with open(_tables_dir() / "out_of_scope.csv", newline="") as _f:
    _LACKED = {int(row["opcode"], 16) for row in csv.DictReader(_f)}
with open(_tables_dir() / "cmotion_calls.csv", newline="") as _f:
    for _row in csv.DictReader(_f):
        if _row["opcode"] and int(_row["opcode"], 16) in _LACKED:
            ARG_WORDS.setdefault(
                int(_row["opcode"], 16), sum(_TYPE_WORDS[a.split(":")[-1]] for a in _row["args"].split())
            )
REPLY_WORDS: Dict[int, int] = {c.opcode: c.reply_words for c in _COMMANDS}
OPCODE_NAMES: Dict[int, str] = {c.opcode: c.name for c in _COMMANDS}
SET_SERIAL_PORT_MODE = next(c.opcode for c in _COMMANDS if c.name == "SetSerialPortMode")
RESET = next(c.opcode for c in _COMMANDS if c.name == "Reset")
BAD_CHECKSUM = _CONSTANTS["PMD_ERR_BadSerialChecksum"]
INVALID_INSTRUCTION = _CONSTANTS["PMD_ERR_InvalidInstruction"]
# the baud rates of the Navigator's codes: the constants' names carry them (PMDSerialBaud57600 = 4)
BAUD_RATES: Dict[int, int] = {
    v: int(m.group(1)) for n, v in _CONSTANTS.items() if (m := re.fullmatch(r"PMDSerialBaud(\d+)", n))
}
POINT_TO_POINT = _CONSTANTS["PMDSerialProtocolPoint2Point"]
MULTI_DROP_ADDRESS_BIT = _CONSTANTS["PMDSerialProtocolMultiDropUsingAddressBit"]
MULTI_DROP_IDLE_LINE = _CONSTANTS["PMDSerialProtocolMultiDropUsingIdleLineDetection"]
# the longest command packet: address, checksum, instruction, the most data words
MAX_PACKET = 4 + 2 * max(ARG_WORDS.values())


class ProtocolError(ValueError):
    """Bytes that are not the packet expected (a reply of the wrong length or checksum)."""


def checksum(data: bytes) -> int:
    """The byte that makes data's bytes and itself add up to 0 mod 256."""
    return -sum(data) & 0xFF


def command_packet(instruction: int, args: Sequence[int] = (), address: int = 0) -> bytes:
    """A command packet: the instruction word ((axis << 8) | opcode) and its data words."""
    body = bytes([instruction >> 8 & 0xFF, instruction & 0xFF]) + b"".join(
        (w & 0xFFFF).to_bytes(2, "big") for w in args
    )
    return bytes([address & 0xFF, checksum(bytes([address & 0xFF]) + body)]) + body


def reply_packet(status: int, words: Sequence[int] = (), address: Optional[int] = None) -> bytes:
    """The chip's reply: status and checksum, then the words unless status is an error (3.2);
    address: the responder's address first (multi-drop idle-line), counted in the checksum."""
    head = b"" if address is None else bytes([address & 0xFF])
    data = b"" if status else b"".join((w & 0xFFFF).to_bytes(2, "big") for w in words)
    return head + bytes([status & 0xFF, checksum(head + bytes([status & 0xFF]) + data)]) + data


def reply_length(words: int, address: bool = False) -> int:
    """Bytes of a successful reply of `words` result words (an error reply: reply_length(0))."""
    return int(address) + 2 + 2 * words


def parse_reply(data: bytes, address: bool = False) -> Tuple[int, List[int]]:
    """(status, words) of a whole reply; ProtocolError for a bad checksum or an odd length."""
    if len(data) < reply_length(0, address) or (len(data) - int(address)) % 2:
        raise ProtocolError(f"a reply of {len(data)} bytes: {data.hex(' ')}")
    if sum(data) & 0xFF:
        raise ProtocolError(f"a reply with a bad checksum: {data.hex(' ')}")
    body = data[int(address) :]
    return body[0], [int.from_bytes(body[i : i + 2], "big") for i in range(2, len(body), 2)]


class Packet(NamedTuple):
    """A whole command packet as the chip received it."""

    address: int
    instruction: int  # (axis byte << 8) | opcode
    args: Tuple[int, ...]
    checksum_ok: bool
    data: bytes  # the packet's bytes

    @property
    def opcode(self) -> int:
        return self.instruction & 0xFF


def packet_length(opcode: int) -> int:
    """The bytes of a command packet with this opcode."""
    return 4 + 2 * ARG_WORDS.get(opcode, 0)


class PacketDecoder:
    """The chip's receiver: bytes in, whole packets out. A packet's length comes from its opcode
    (byte 3); the bytes of a packet not yet whole wait for the rest (reset() drops them: a
    disconnect cuts the packet, which is never executed)."""

    def __init__(self):
        self._pending = bytearray()

    @property
    def pending(self) -> int:
        """Bytes of a packet not yet whole."""
        return len(self._pending)

    def reset(self) -> int:
        """Drops a packet not yet whole; returns how many bytes it had."""
        n = len(self._pending)
        self._pending.clear()
        return n

    def feed(self, data: bytes) -> List[Packet]:
        """The packets data completes, in order."""
        buf = self._pending
        buf += data
        out, start = [], 0
        while len(buf) - start >= 4:
            n = packet_length(buf[start + 3])
            if len(buf) - start < n:
                break
            raw = bytes(buf[start : start + n])
            args = tuple(int.from_bytes(raw[i : i + 2], "big") for i in range(4, n, 2))
            out.append(Packet(raw[0], raw[2] << 8 | raw[3], args, sum(raw) & 0xFF == 0, raw))
            start += n
        del buf[:start]
        return out


class SerialPortMode(NamedTuple):
    """The serial port mode word's fields (3.3)."""

    baud: int  # bit/s
    parity: int  # 0 none, 1 odd, 2 even
    stop_bits: int  # 1 or 2
    protocol: int  # POINT_TO_POINT, MULTI_DROP_ADDRESS_BIT, MULTI_DROP_IDLE_LINE
    address: int  # the multi-drop address 0..31

    @classmethod
    def of(cls, word: int) -> "SerialPortMode":
        def ex(name: str) -> int:
            return _FIELDS[name].ex(word)

        return cls(
            BAUD_RATES[ex("PMDSerialPortBaud")],
            ex("PMDSerialPortParity"),
            1 + ex("PMDSerialPortStopBits"),
            ex("PMDSerialPortProtocol"),
            ex("PMDSerialPortMultiDropID"),
        )

    @staticmethod
    def word(baud_code: int, parity: int, stop_bits_code: int, protocol: int, address: int) -> int:
        """The mode word from SetSerialPortMode's arguments."""
        word = 0
        for name, value in (
            ("PMDSerialPortBaud", baud_code),
            ("PMDSerialPortParity", parity),
            ("PMDSerialPortStopBits", stop_bits_code),
            ("PMDSerialPortProtocol", protocol),
            ("PMDSerialPortMultiDropID", address),
        ):
            word = _FIELDS[name].dp(word, value)
        return word

    @property
    def multi_drop(self) -> bool:
        return self.protocol in (MULTI_DROP_ADDRESS_BIT, MULTI_DROP_IDLE_LINE)

    def answers(self, address: int) -> bool:
        """Whether a chip in this mode executes and answers a packet with this address byte:
        point-to-point, every packet (the byte is 0 by convention); multi-drop, its own."""
        return not self.multi_drop or address == self.address

    def reply_address(self) -> Optional[int]:
        """The address byte a reply starts with: idle-line multi-drop only (3.2)."""
        return self.address if self.protocol == MULTI_DROP_IDLE_LINE else None
