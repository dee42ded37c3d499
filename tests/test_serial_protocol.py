# SPDX-License-Identifier: BSD-2-Clause
"""The serial packet codec (pmd-reference 3.1-3.3) in Python (python/pmdfmu/serial_protocol.py, what
`pmdfmu serve` speaks) and in C (host/c/PMDserial.c, the C library's), both against the same byte
vectors (tests/data/serial_vectors.csv); the chip's decoder emits whole packets only."""

import csv
import shutil
import subprocess
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pmdfmu import serial_protocol as sp

ROOT = Path(__file__).resolve().parent.parent
VECTORS = list(csv.DictReader(open(Path(__file__).parent / "data" / "serial_vectors.csv", newline="")))


def words_of(text):
    return [int(w, 16) for w in text.split()]


@pytest.mark.parametrize("v", VECTORS, ids=[v["note"] for v in VECTORS])
def test_python_codec_makes_and_reads_every_vector(v):
    data = bytes.fromhex(v["bytes"])
    assert sum(data) & 0xFF == 0
    if v["kind"] == "command":
        assert sp.command_packet(int(v["instruction"], 16), words_of(v["words"]), int(v["address"])) == data
        (packet,) = sp.PacketDecoder().feed(data)
        assert packet.checksum_ok and packet.address == int(v["address"])
        assert packet.instruction == int(v["instruction"], 16) and list(packet.args) == words_of(v["words"])
    else:
        address = int(v["address"]) if v["address"] else None
        assert sp.reply_packet(int(v["status"]), words_of(v["words"]), address) == data
        assert sp.parse_reply(data, address is not None) == (int(v["status"]), words_of(v["words"]))


@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
def test_c_codec_makes_and_reads_the_same_vectors(tmp_path):
    """One C program per run, the vectors compiled in: it prints each packet it makes, and what it
    reads back from each reply."""
    lines = []
    for v in VECTORS:
        words = words_of(v["words"])
        array = "{" + ", ".join(map(str, words or [0])) + "}"
        if v["kind"] == "command":
            lines.append(
                f"{{ uint16_t a[] = {array}; n = PMDSerialCommandPacket(out, {v['address']}, {v['instruction']}, a, "
                f"{len(words)}); show(out, n); }}"
            )
        else:
            data = bytes.fromhex(v["bytes"])
            addressed = 1 if v["address"] else 0
            lines.append(
                f"{{ uint16_t a[] = {array}; n = PMDSerialReplyPacket(out, {v['status']}, a, {len(words)}, "
                f"{v['address'] or -1}); show(out, n); "
                f"{{ static const uint8_t in[] = {{{', '.join(map(str, data))}}}; "
                f"r = PMDSerialParseReply(in, sizeof in, {addressed}, &status, back, 64, &count); "
                f'printf("parsed %d %u", r, status); for (i = 0; i < count; i++) printf(" %04x", back[i]); '
                'printf("\\n"); } }'
            )
    source = tmp_path / "vectors.c"
    source.write_text(
        '#include <stdio.h>\n#include "PMDserial.h"\n'
        "static void show(const uint8_t *b, size_t n) { size_t i; for (i = 0; i < n; i++) "
        'printf(i ? " %02x" : "%02x", b[i]); printf("\\n"); }\n'
        "int main(void) { uint8_t out[256], status = 0; uint16_t back[64]; size_t n; int r, i, count = 0;\n"
        + "\n".join(lines)
        + "\n(void)r; (void)i; return 0; }\n"
    )
    exe = tmp_path / "vectors"
    subprocess.run(
        [
            "cc",
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Wpedantic",
            "-Werror",
            f"-I{ROOT / 'host' / 'c'}",
            str(source),
            str(ROOT / "host" / "c" / "PMDserial.c"),
            "-o",
            str(exe),
        ],
        check=True,
    )
    out = iter(subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.splitlines())
    for v in VECTORS:
        assert next(out) == v["bytes"], v["note"]
        if v["kind"] == "reply":
            expected = " ".join(["parsed 0", v["status"], *[f"{w:04x}" for w in words_of(v["words"])]])
            assert next(out) == expected, v["note"]


@settings(max_examples=300, deadline=None)
@given(st.binary(max_size=200), st.integers(min_value=1, max_value=17))
def test_the_chips_decoder_emits_whole_packets_only_however_the_bytes_arrive(data, chunk):
    """Any bytes, in chunks of any size: the packets are the stream cut at each opcode's length, the
    bytes left over are less than a packet, and a packet is good exactly when its bytes add up to 0."""
    decoder, packets = sp.PacketDecoder(), []
    for i in range(0, len(data), chunk):
        packets += decoder.feed(data[i : i + chunk])
    assert b"".join(p.data for p in packets) + data[len(data) - decoder.pending :] == data
    for p in packets:
        assert len(p.data) == sp.packet_length(p.opcode) and p.checksum_ok == (sum(p.data) & 0xFF == 0)
    rest = data[len(data) - decoder.pending :]
    assert len(rest) < 4 or len(rest) < sp.packet_length(rest[3])


def test_a_reply_with_a_bad_checksum_or_length_is_refused():
    with pytest.raises(sp.ProtocolError):
        sp.parse_reply(bytes.fromhex("00 88 24 41 00 12"))
    with pytest.raises(sp.ProtocolError):
        sp.parse_reply(bytes.fromhex("00"))


def test_the_serial_port_mode_word_reads_as_reference_3_3_says():
    """0x0004 is the reset mode: 57600 baud, no parity, 1 stop bit, point-to-point; code 5 is 115200 and
    protocol 3 idle-line multi-drop, the address in bits 11-15."""
    assert sp.SerialPortMode.of(0x0004) == (57600, 0, 1, sp.POINT_TO_POINT, 0)
    word = sp.SerialPortMode.word(5, 2, 1, sp.MULTI_DROP_IDLE_LINE, 7)
    assert word == 5 | 2 << 4 | 1 << 6 | 3 << 7 | 7 << 11
    mode = sp.SerialPortMode.of(word)
    assert mode == (115200, 2, 2, sp.MULTI_DROP_IDLE_LINE, 7)
    assert mode.answers(7) and not mode.answers(0) and mode.reply_address() == 7
