# SPDX-License-Identifier: BSD-2-Clause
"""Forged FMU states: a snapshot whose checksum was recomputed after a
field was changed must still be refused when the field holds a value the model
never gives it, with a message naming the field, and the instance must stay as
it was. The declared field list (fmu_src/fmi/state_fields.c) drives the forger;
the compiler's debug information checks that the list names every struct member."""

import shutil
import struct
import subprocess
import sys
from pathlib import Path

import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import PMDTraceCommandedPosition, PMDTraceConditionUpdate, PMDTraceRollingBuffer, PMDTraceTime, field_dp
from pmdfmu.profile import load_external_profile, start_external_profile
from states import InitializationChip, command, pend_batch, snapshot

ROOT = Path(__file__).resolve().parent.parent
HEADERS = Path(__import__("fmpy").__file__).parent / "c-code"
SF_UNSIGNED, SF_SIGNED, SF_REAL, SF_PROCESS = 0, 1, 2, 4

pytestmark = pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")


def includes(gen: Path):
    return [f"-I{ROOT / 'fmu_src' / d}" for d in ("chip", "script", "machine", "plant", "fmi", "fmi_common")] + [
        f"-I{gen}",
        f"-I{HEADERS}",
    ]


@pytest.fixture(scope="module")
def generated(tmp_path_factory) -> Path:
    gen = tmp_path_factory.mktemp("generated")
    subprocess.run([sys.executable, str(ROOT / "modelDescription" / "generate.py"), str(gen)], check=True)
    return gen


@pytest.fixture(scope="module")
def declared(generated, tmp_path_factory):
    """The declared state as tests/c/state_fields_list.c prints it, compiled like the FMU's sources."""
    exe = tmp_path_factory.mktemp("lister") / "state_fields_list"
    subprocess.run(
        [
            "cc",
            "-std=c99",
            *includes(generated),
            str(ROOT / "tests" / "c" / "state_fields_list.c"),
            str(ROOT / "fmu_src" / "fmi" / "state_fields.c"),
            "-lm",
            "-o",
            str(exe),
        ],
        check=True,
    )
    header, leaves, members = None, [], {}
    for line in subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.splitlines():
        kind, *rest = line.split()
        if kind == "header":
            header = tuple(map(int, rest))
        elif kind == "leaf":
            path, offset, size, k, lo, hi = rest
            leaves.append((path, int(offset), int(size), int(k), int(lo), int(hi)))
        else:
            members.setdefault(rest[0], []).append(rest[1])
    return header, leaves, members


def test_every_member_of_the_instance_structs_is_declared(generated, declared, tmp_path):
    """A field added to a struct but not to state_fields.c fails here: the
    members come from the DWARF of a compiled translation unit."""
    elftools = pytest.importorskip("elftools.elf.elffile")
    probe = tmp_path / "probe.c"
    probe.write_text('#include "instance.h"\nPmdInstance probe;\n')
    obj = tmp_path / "probe.o"
    subprocess.run(["cc", "-std=c99", "-g", "-c", *includes(generated), str(probe), "-o", str(obj)], check=True)
    found = {}
    with open(obj, "rb") as f:
        dwarf = elftools.ELFFile(f).get_dwarf_info()
        for cu in dwarf.iter_CUs():
            for die in cu.iter_DIEs():
                if die.tag != "DW_TAG_typedef" or "DW_AT_name" not in die.attributes:
                    continue
                name = die.attributes["DW_AT_name"].value.decode()
                target = die.get_DIE_from_attribute("DW_AT_type")
                if name in declared[2] and target.tag == "DW_TAG_structure_type":
                    found[name] = [
                        c.attributes["DW_AT_name"].value.decode()
                        for c in target.iter_children()
                        if c.tag == "DW_TAG_member"
                    ]
    assert set(found) == set(declared[2]), "every struct the list describes appears in the debug information"
    for name, members in found.items():
        assert members == declared[2][name], f"{name}: the struct's members (left) and state_fields.c's list"


def rich_state_chip(fmi_version):
    """A chip in the middle of everything a snapshot holds: an external profile
    streaming from five buffers, an S-curve, a rolling trace, breakpoints, a gear."""
    chip = pmdfmu.Chip(fmi_version=fmi_version, memorySize=0x400, log_categories=["errors"])
    rows = [(0, 0x18000, 0x40, 0x1000, 30), (50, -0x8000, 0, 0, 40), (20, 0x2000, -0x20, 0, 0)]
    load_external_profile(chip, {0: rows}, memory_start=0x200)
    start_external_profile(chip, [0])
    ax2 = chip.axis(1)
    ax2.SetProfileMode(pmdfmu.PMDSCurveProfile)
    ax2.SetPosition(5000)
    ax2.SetVelocity(0x40000)
    ax2.SetAcceleration(0x1000)
    ax2.SetJerk(0x1000000)
    ax2.Update()
    ax3 = chip.axis(2)
    ax3.SetGearMaster(0, pmdfmu.PMDPositionSourceCommanded)
    ax3.SetGearRatio(0x20000)
    ax3.SetProfileMode(pmdfmu.PMDElectronicGearProfile)
    ax3.Update()
    ax = chip.axis(3)
    ax.SetBreakpointValue(0, 100)
    ax.SetBreakpoint(0, 0, pmdfmu.PMDBreakpointActionMotorOff, pmdfmu.PMDBreakpointGreaterOrEqualCommandedPosition)
    ax.SetBufferStart(0, 0x100)
    ax.SetBufferLength(0, 16)
    ax.SetTraceMode(PMDTraceRollingBuffer)
    ax.SetTracePeriod(3)
    ax.SetTraceVariable(0, 0, PMDTraceTime)
    ax.SetTraceVariable(1, 1, PMDTraceCommandedPosition)
    ax.SetTraceStart(1, PMDTraceConditionUpdate, 0, 0)
    ax2.Update()  # no change: the trace starts on this update
    chip.run(25)
    return chip


def fnv1a(data: bytes) -> int:
    h = 14695981039346656037
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


class Forger:
    def __init__(self, blob: bytes, header):
        self.blob, (self.header, self.checksum_at) = blob, header

    def forge(self, offset: int, raw: bytes, in_header: bool = False) -> bytes:
        data = bytearray(self.blob)
        at = offset if in_header else self.header + offset
        data[at : at + len(raw)] = raw
        data[self.checksum_at : self.checksum_at + 8] = fnv1a(bytes(data[self.header :])).to_bytes(8, "little")
        return bytes(data)


def restore(chip, data: bytes):
    state = chip.fmu.deserializeFMUState(data)
    try:
        chip.fmu.setFMUState(state)
    finally:
        chip.fmu.freeFMUState(state)


def refused(chip, data: bytes) -> str:
    """Restores data, expecting a refusal; returns the error message; the state is unchanged."""
    before = snapshot(chip)
    chip.messages.clear()
    with pytest.raises(FMICallException):
        restore(chip, data)
    assert snapshot(chip) == before, "a refused state changes nothing"
    return " ".join(m.message for m in chip.messages if m.status == "Error")


def outside(size: int, kind: int, lo: int, hi: int):
    """Values just outside [lo, hi] that the field's bytes can hold."""
    bits = 8 * size
    tmin, tmax = (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if kind == SF_SIGNED else (0, (1 << bits) - 1)
    return [v for v in (lo - 1, hi + 1, tmin, tmax) if tmin <= v <= tmax and not lo <= v <= hi]


@pytest.fixture(scope="module", params=[2, 3], ids=["fmi2", "fmi3"])
def rich(request):
    chip = rich_state_chip(request.param)
    yield chip
    chip.close()


def test_the_snapshot_resigned_unchanged_is_accepted(rich, declared):
    blob = snapshot(rich)
    forger = Forger(blob, declared[0])
    restore(rich, forger.forge(0, blob[declared[0][0] : declared[0][0] + 1]))
    assert snapshot(rich) == blob


@pytest.mark.slow
def test_every_field_just_outside_its_range_is_refused_naming_it(rich, declared):
    forger = Forger(snapshot(rich), declared[0])
    tried = 0
    for path, offset, size, kind, lo, hi in declared[1]:
        if kind == SF_REAL:
            values = [(float("nan"), "<d"), (float("inf"), "<d")]
            raws = [struct.pack(fmt, v) for v, fmt in values]
        elif kind in (SF_UNSIGNED, SF_SIGNED):
            raws = [(v & ((1 << (8 * size)) - 1)).to_bytes(size, "little") for v in outside(size, kind, lo, hi)]
        else:
            continue
        for raw in raws:
            message = refused(rich, forger.forge(offset, raw))
            assert path in message, (path, message)
            tried += 1
    assert tried > 500


# a trace slot's word (SetTraceVariable): commanded position of axis 15, which the chip does not have
TRACE_AXIS_15 = field_dp(field_dp(0, "PMDTraceVariableID", PMDTraceCommandedPosition), "PMDTraceVariableAxis", 15)
FORGERIES = {  # finding: the fields changed, and what the message must name
    "host word count 100000 with a batch pending": ({"hostWordCount": 100000, "hostStrobe": 12345}, "hostWordCount"),
    "gear master axis 60000": ({"chip.s.axis[2].gearMasterAxis": 60000}, "gearMasterAxis"),
    "a segment start near 2^32": ({"chip.s.axis[0].segmentStart[0]": 0xFFFFFFF0}, "segmentStart"),
    "a buffer leaving the memory": ({"chip.s.buffer[3].start": 0x3FF}, "chip.s.buffer[3]"),
    "a trace variable of axis 15": ({"chip.s.trace.variable[1]": TRACE_AXIS_15}, "chip.s.trace.variable[1]"),
    "a read index past its buffer": ({"chip.s.buffer[2].readIndex": 3}, "chip.s.buffer[2]"),
    "a plan that reads another buffer": ({"chip.s.axis[0].segmentStart[1]": 0x100}, "chip.s.axis[0].segment"),
}


@pytest.mark.parametrize("finding", FORGERIES)
def test_the_forgeries_found_by_review_are_refused(rich, declared, finding):
    """Each of these was accepted and then read or wrote out of bounds."""
    leaves = {path: (offset, size) for path, offset, size, *_ in declared[1]}
    edits, expected = FORGERIES[finding]
    data = snapshot(rich)
    for path, value in edits.items():
        offset, size = leaves[path]
        data = Forger(data, declared[0]).forge(offset, value.to_bytes(size, "little"))
    assert expected in refused(rich, data)


def test_a_header_memory_size_that_differs_from_the_body_is_refused(rich, declared):
    """The header says one word more (and the body has it): the instance image's memorySize disagrees."""
    header = declared[0][0]
    blob = bytearray(snapshot(rich) + b"\0\0\0\0")
    words = int.from_bytes(blob[72:80], "little")
    blob[64:72] = len(blob).to_bytes(8, "little")  # totalSize
    blob[72:80] = (words + 1).to_bytes(8, "little")  # memoryWords
    data = Forger(bytes(blob), declared[0]).forge(0, bytes(blob[header : header + 1]))
    assert "memorySize" in refused(rich, data)


def test_header_bytes_after_the_token_are_checked(rich, declared):
    blob = bytearray(snapshot(rich))
    blob[16 + 47] = 0x41  # the last byte of the token field, after its NUL
    assert "instantiation token" in refused(rich, bytes(blob))


GRID_FORGERIES = {  # field: forged value, and what the message must name (found by review)
    "nextCycle": (-(1 << 62), "nextCycle"),  # a doStep would run 2^62 cycles
    "anchorCycle": (1 << 40, "anchorCycle"),
    "anchorTime": (1e9, "anchorTime"),  # an anchor after the time: negative steps
    "cycleTime": (1.0, "cycleTime"),  # no 16-bit sample time holds it
    "chip.s.sampleTime": (0, "sampleTime"),  # the grid's cycle time (the register's, 1..65535 us)
}


@pytest.mark.parametrize("name", GRID_FORGERIES)
def test_a_forged_time_grid_is_refused(rich, declared, name):
    leaves = {path: (offset, size, kind) for path, offset, size, kind, *_ in declared[1]}
    value, expected = GRID_FORGERIES[name]
    offset, size, kind = leaves[name]
    raw = struct.pack("<d", value) if kind == SF_REAL else value.to_bytes(size, "little", signed=True)
    assert expected in refused(rich, Forger(snapshot(rich), declared[0]).forge(offset, raw))


@pytest.mark.parametrize("field", ["p6", "v2", "a", "step"])
def test_an_s_curve_off_its_unit_curve_is_refused(rich, declared, field):
    """Each value alone in range, but not where the unit curve is after `step` steps: the move would
    run off without bound (found by review: a constant acceleration through the cruise)."""
    leaves = {path: (offset, size) for path, offset, size, *_ in declared[1]}
    blob = snapshot(rich)
    offset, size = leaves[f"chip.s.axis[1].scurve.{field}"]
    value = int.from_bytes(blob[declared[0][0] + offset :][:size], "little", signed=True)
    assert "scurve" in refused(
        rich, Forger(blob, declared[0]).forge(offset, (value + 1).to_bytes(size, "little", signed=True))
    )


def test_a_state_that_ran_a_script_restores_only_where_that_script_runs(tmp_path):
    one, other = tmp_path / "one.pmd", tmp_path / "other.pmd"
    one.write_text("@0\nSetPosition(Axis1, 100);\n@5\nSetPosition(Axis1, 200);\n")
    other.write_text("@0\nSetPosition(Axis1, 100);\n@6\nSetPosition(Axis1, 200);\n")
    with pmdfmu.Chip(script=one) as a, pmdfmu.Chip(script=one) as same, pmdfmu.Chip(script=other) as b:
        a.run(3)
        data = snapshot(a)
        restore(same, data)
        assert snapshot(same) == data
        assert "scriptDigest" in refused(b, data)


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_a_buffer_of_length_0_may_start_beyond_a_memory_made_smaller(fmi_version):
    """A state the model reaches (found by review): SetBufferStart(5, 0x3000) with length 0, then memorySize 0x1000."""
    chip = InitializationChip(fmi_version)
    try:
        pend_batch(chip, command("SetBufferStart", 5, 0x3000))
        chip.get("host.ack")
        chip.set("memorySize", 0x1000)
        data = snapshot(chip)
        restore(chip, data)
        assert snapshot(chip) == data
    finally:
        chip.free()
