# SPDX-License-Identifier: BSD-2-Clause
"""Host time (docs/host-time.md, docs/decisions.md "Host time"):
each command takes its transfer time on the host interface, the chip runs the
cycles that fall due meanwhile, so an unchanged polling loop ends at the cycle it
would on hardware. The transfer times are checked against values worked by hand,
the Python and C formulas against each other, and the seed's 1.6 completion
detection (polling, and the breakpoint interrupt) against the exact reference model
plus the host's transfer times, computed here independently of the harness."""

import ctypes
import re
import importlib.util
import shutil
import subprocess
from fractions import Fraction
from pathlib import Path

import pytest

import pmdfmu
from pmdfmu import (
    COMMANDS,
    HostInterface,
    PMDActivityProfileSegmentMask,
    PMDBreakpoint1,
    PMDBreakpointActivityStatus,
    PMDBreakpointNoAction,
    PMDEventBreakpoint1Mask,
    PMDExternalProfile,
    field_ex,
)
from pmdfmu.hosttime import KINDS, RANGES, cycles_due
from reference import ExternalProfile

REPO = Path(__file__).resolve().parents[1]
CYCLE_NS = 100_000  # the FMU's default cycle time, 100 us


def ceil_div(a, b):
    return -(-a // b)


# ---- transfer times, worked by hand ----


def test_serial_getversion_at_57600_8n1_as_worked_by_hand():
    serial = HostInterface("serial")
    assert (serial.baud, serial.data_bits, serial.parity, serial.stop_bits) == (57600, 8, 0, 1)
    # request 00 71 00 8F (pmd-reference 3.1): 4 bytes of 1 start + 8 data + 1 stop bits = 40 bits
    assert serial.request_ns(1) == ceil_div(40 * 10**9, 57600) == 694_445
    # reply 00 89 24 41 00 12 (reference 3.2): 6 bytes = 60 bits, after the chip's processing time
    assert serial.reply_ns(2) == 5000 + ceil_div(60 * 10**9, 57600) == 5000 + 1_041_667
    # an error reply is status and checksum only: 2 bytes
    assert serial.reply_ns(2, failed=True) == 5000 + ceil_div(20 * 10**9, 57600) == 5000 + 347_223
    # SetBufferStart(2, 0x200): instruction + 3 data words = 4 + 2*3 = 10 bytes
    assert serial.request_ns(4) == ceil_div(100 * 10**9, 57600)
    # 8 data bits, even parity, 2 stop bits at 9600: 12 bits a byte
    slow = HostInterface("serial", baud=9600, parity=1, stop_bits=2)
    assert slow.request_ns(1) == 4 * 12 * 10**9 // 9600 == 5_000_000
    assert slow.reply_ns(1) == 5000 + 4 * 12 * 10**9 // 9600


def test_parallel_spi_fixed_and_none_as_worked_by_hand():
    p16, p8 = HostInterface("parallel16"), HostInterface("parallel8")
    # each word: a status read (HostRdy) and the word, 250 ns a bus cycle
    assert p16.request_ns(1) == 2 * 250 and p16.request_ns(4) == 4 * 2 * 250
    # processing, the I/O-error status read, then per result word a status read and the read
    assert p16.reply_ns(2) == 5000 + 250 + 2 * 2 * 250
    assert p16.reply_ns(2, failed=True) == 5000 + 250
    assert HostInterface("parallel16", checksum=1).reply_ns(2) == 5000 + 250 + 3 * 2 * 250
    # 8/8 mode: a word is two byte cycles, the status one
    assert p8.request_ns(3) == 3 * 3 * 250 and p8.reply_ns(2) == 5000 + 250 + 2 * 3 * 250
    # SPI at 4 MHz: 16 bits a word, one header word each way
    spi = HostInterface("spi")
    assert spi.request_ns(1) == 2 * 16 * 250 and spi.reply_ns(2) == 5000 + 3 * 16 * 250
    assert spi.reply_ns(2, failed=True) == 5000 + 16 * 250
    fixed = HostInterface("fixed", request_ns=7, reply_ns=11)
    assert (fixed.request_ns(9), fixed.reply_ns(9), fixed.reply_ns(0, True)) == (7, 11, 11)
    none = HostInterface("none")
    assert (none.request_ns(5), none.reply_ns(5)) == (0, 0)


def test_host_interface_refuses_what_the_table_does_not_have():
    with pytest.raises(ValueError, match="one of none, parallel16"):
        HostInterface("usb")
    with pytest.raises(ValueError, match="no parameter baud"):
        HostInterface("parallel16", baud=9600)
    with pytest.raises(ValueError, match="not an integer"):
        HostInterface("serial", baud=9600.0)
    with pytest.raises(TypeError):
        pmdfmu.Chip(host_interface=3)


# the attacker's finding: baud 0 made every byte take no time, parity 5 and stop_bits 7 were taken
OUT_OF_RANGE = [
    ("serial", "baud", 0, "1 .. 2^32-1"),
    ("serial", "parity", 5, "0 .. 1"),
    ("serial", "stop_bits", 7, "1 .. 2"),
    ("serial", "stop_bits", 0, "1 .. 2"),
    ("serial", "data_bits", 9, "5 .. 8"),
    ("spi", "clock_hz", 0, "1 .. 2^32-1"),
    ("parallel16", "checksum", 2, "0 .. 1"),
    ("fixed", "reply_ns", 2**32, "0 .. 2^32-1"),
]


@pytest.mark.parametrize("kind, name, value, shown", OUT_OF_RANGE)
def test_host_interface_refuses_a_parameter_outside_the_tables_range(kind, name, value, shown):
    with pytest.raises(
        ValueError, match=rf"host interface {kind}: {name} = {value} is not an integer {re.escape(shown)}$"
    ):
        HostInterface(kind, **{name: value})


def test_every_default_lies_in_its_range_and_the_ranges_ends_are_taken():
    for kind, ranges in RANGES.items():
        for name, (lo, hi) in ranges.items():
            assert lo <= KINDS[kind][name] <= hi, (kind, name)
            assert HostInterface(kind, **{name: lo}).parameters[name] == lo
            assert HostInterface(kind, **{name: hi}).parameters[name] == hi


def test_every_number_of_the_table_has_a_unit_source_and_confidence():
    import csv

    with open(REPO / "modelDescription" / "host_interfaces.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["kind"] for r in rows if not r["parameter"]] == ["none"]
    for r in rows:
        if r["parameter"]:
            assert r["unit"] and r["source"] and r["confidence"] in ("H", "M", "L") and r["description"], r
            if r["source"] == "chosen":
                assert r["confidence"] == "L", r
    assert [k for k in KINDS] == ["none", "parallel16", "parallel8", "serial", "spi", "fixed"]


# ---- Python and C agree ----


@pytest.fixture(scope="module")
def c_hosttime(tmp_path_factory):
    """host/c/PMDhosttime.c with the generator's header, as a shared library."""
    cc = shutil.which("cc") or shutil.which("gcc")
    if not cc:
        pytest.skip("no C compiler")
    out = tmp_path_factory.mktemp("hosttime")
    spec = importlib.util.spec_from_file_location(
        "generate_hosttime", REPO / "modelDescription" / "generate_hosttime.py"
    )
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    generator.main(["generate_hosttime.py", str(out)])
    library = out / "libhosttime.so"
    subprocess.run(
        [
            cc,
            "-std=c99",
            "-Wall",
            "-Wextra",
            "-Wpedantic",
            "-Werror",
            "-shared",
            "-fPIC",
            "-I",
            str(out),
            "-I",
            str(REPO / "host" / "c"),
            str(REPO / "host" / "c" / "PMDhosttime.c"),
            "-o",
            str(library),
        ],
        check=True,
    )
    members = list(dict.fromkeys(p for _k, params in generator.read_table() for p in params))

    class Interface(ctypes.Structure):
        _fields_ = [("kind", ctypes.c_int)] + [(generator.camel(m), ctypes.c_uint32) for m in members]

    lib = ctypes.CDLL(str(library))
    lib.PMDHostInterfaceOf.restype = Interface
    lib.PMDHostInterfaceDefault.restype = Interface
    for f in ("PMDHostRequestNs", "PMDHostReplyNs", "PMDHostTransferNs", "PMDHostCyclesDue"):
        getattr(lib, f).restype = ctypes.c_uint64
    lib.PMDHostCyclesDue.argtypes = [ctypes.c_uint64] * 3
    lib.PMDHostInterfaceName.restype = ctypes.c_char_p
    return lib, Interface, generator


def c_interface(Interface, generator, host: HostInterface):
    s = Interface(kind=list(KINDS).index(host.kind))
    for name, value in host.parameters.items():
        setattr(s, generator.camel(name), value)
    return s


INTERFACES = (
    [HostInterface(k) for k in KINDS]
    + [
        HostInterface("serial", baud=b, parity=p, stop_bits=s, processing_ns=0)
        for b in (1200, 9600, 19200, 115200, 250000, 416667)
        for p in (0, 1)
        for s in (1, 2)
    ]
    + [
        HostInterface("parallel16", checksum=1, bus_cycle_ns=70, processing_ns=1234),
        HostInterface("parallel8", checksum=1, bus_cycle_ns=333),
        HostInterface("spi", clock_hz=3_000_000, request_header_words=0, reply_header_words=2),
        HostInterface("spi", clock_hz=1),
        HostInterface("fixed", request_ns=0xFFFFFFFF, reply_ns=1),
    ]
)


def test_python_and_c_agree_on_every_interface_and_word_count(c_hosttime):
    lib, Interface, generator = c_hosttime
    for k, kind in enumerate(KINDS):  # the same defaults, names and kinds
        got = lib.PMDHostInterfaceOf(k)
        assert {m: getattr(got, generator.camel(m)) for m in KINDS[kind]} == KINDS[kind]
        assert got.kind == k and lib.PMDHostInterfaceName(k).decode() == kind
        assert lib.PMDHostInterfaceKind(kind.encode()) == k
    assert lib.PMDHostInterfaceDefault().kind == list(KINDS).index("parallel16")
    assert lib.PMDHostInterfaceKind(b"usb") == -1
    lib.PMDHostInterfaceRefused.restype = ctypes.c_char_p
    value, lo, hi = ctypes.c_uint32(), ctypes.c_uint32(), ctypes.c_uint32()
    for host in INTERFACES:  # every one in range, as Python took it
        assert lib.PMDHostInterfaceRefused(ctypes.byref(c_interface(Interface, generator, host)), value, lo, hi) is None
    for kind, name, bad, _shown in OUT_OF_RANGE[:-1]:  # the same ranges: C refuses what Python does
        s = c_interface(Interface, generator, HostInterface(kind))
        setattr(s, generator.camel(name), bad)
        refused = lib.PMDHostInterfaceRefused(ctypes.byref(s), ctypes.byref(value), ctypes.byref(lo), ctypes.byref(hi))
        assert (refused.decode(), value.value, (lo.value, hi.value)) == (name, bad, RANGES[kind][name])
    s = Interface(kind=len(KINDS))
    assert (
        lib.PMDHostInterfaceRefused(ctypes.byref(s), ctypes.byref(value), ctypes.byref(lo), ctypes.byref(hi)) == b"kind"
    )
    for host in INTERFACES:
        s = ctypes.byref(c_interface(Interface, generator, host))
        for words in range(1, 66):
            assert lib.PMDHostRequestNs(s, words) == host.request_ns(words), (host, words)
            assert lib.PMDHostTransferNs(s, 0, words, 0) == host.request_ns(words)
        for words in range(0, 65):
            for failed in (0, 1):
                assert lib.PMDHostReplyNs(s, words, failed) == host.reply_ns(words, bool(failed)), (host, words)
                assert lib.PMDHostTransferNs(s, 1, words, failed) == host.reply_ns(words, bool(failed))
    for host_ns, next_ns, cycle_ns in [
        (0, 0, 100),
        (99, 100, 100),
        (100, 100, 100),
        (199, 100, 100),
        (200, 100, 100),
        (10**15 + 7, 3, 51_200),
        (5, 0, 0),
        (2**63, 0, 1),
    ]:
        assert lib.PMDHostCyclesDue(host_ns, next_ns, cycle_ns) == cycles_due(host_ns, next_ns, cycle_ns)


# ---- the harness ----


def command_ns(host: HostInterface, name: str, failed: bool = False) -> int:
    """One command's request and reply, from the command table's word counts."""
    c = COMMANDS[name]
    return host.request_ns(1 + c.arg_words) + host.reply_ns(0 if failed else c.reply_words, failed)


def grid_points_at_or_before(host_ns: int) -> int:
    """Cycles of the default grid (0, 100 us, ...) at or before a host time: the cycles run by then."""
    return host_ns // CYCLE_NS + 1


def history(chip):
    """A sequence of commands, raw batches (one refused), runs and a wait."""
    ax = chip.axis(0)
    out = [ax.GetVersion(), ax.GetTime()]
    ax.SetVelocity(0x10000)
    ax.SetAcceleration(0x1000)
    ax.SetPosition(5000)
    ax.Update()
    out.append(chip.batch([0x3E, 0x3E, 0x0AA6, 0xA6]))
    chip.run(7)
    out += [ax.GetTime(), ax.GetCommandedPosition()]
    chip.wait(0.00123)
    out += [ax.GetTime(), ax.GetCommandedPosition(), chip.cycles]
    return out


def test_none_is_todays_behaviour_bit_for_bit():
    with (
        pmdfmu.Chip() as default,
        pmdfmu.Chip(host_interface="none") as none,
        pmdfmu.Chip(host_interface=HostInterface("none")) as explicit,
    ):
        assert default.host_interface == HostInterface("none")
        results = [history(c) for c in (default, none, explicit)]
        assert results[0] == results[1] == results[2]
        assert default.get_state() == none.get_state() == explicit.get_state()
    # commands took no chip time: the run of 7 and the wait's cycles are all there are
    with pmdfmu.Chip() as chip:
        ax = chip.axis(0)
        for _ in range(100):
            ax.GetActivityStatus()
        assert chip.cycles == 0 and chip.host_time_ns == 0


@pytest.mark.parametrize("kind", list(KINDS)[1:])
def test_each_command_runs_the_cycles_due_by_the_host_clock(kind):
    host = HostInterface(kind)
    with pmdfmu.Chip(host_interface=kind) as chip:
        ax, clock = chip.axis(0), 0
        for _ in range(40):
            clock += host.request_ns(1)
            expected = grid_points_at_or_before(clock)
            assert ax.GetTime() == expected - 1  # GetTime: the last cycle run
            clock += host.reply_ns(2)
            assert chip.cycles == expected and chip.host_time_ns == clock
            if kind in ("parallel16", "parallel8"):
                chip.wait_ns(CYCLE_NS // 3)  # make the polls cross cycles
                clock += CYCLE_NS // 3


def test_a_batch_is_timed_command_by_command_and_an_error_reply_is_shorter():
    host = HostInterface("fixed", request_ns=150_000, reply_ns=0)
    with pmdfmu.Chip(host_interface=host) as chip:
        # GetTime, GetTime on axis field 10 (refused 0x03), GetTime: executed at 150, 300, 450 us
        error, reply = chip.batch([0x3E, 0x0A3E, 0x3E])
        assert error == pmdfmu.PMD_ERR_InvalidAxis  # the first error of the batch
        assert reply == [0, 1, 0, 4]  # cycles 0-1 ran before the first, 0-4 before the third
        assert chip.host_time_ns == 450_000 and chip.cycles == 5
    serial = HostInterface("serial")
    with pmdfmu.Chip(host_interface=serial) as chip:
        error, reply = chip.batch([0x0A8F])  # GetVersion on axis 10: refused, a 2-byte reply
        assert error == pmdfmu.PMD_ERR_InvalidAxis and reply == []
        assert chip.host_time_ns == serial.request_ns(1) + serial.reply_ns(2, failed=True)
        # an unknown opcode ends the batch with the words after it: one transfer of all three
        before = chip.host_time_ns
        assert chip.batch([0x00FF, 0x3E, 0x3E])[0] == pmdfmu.PMD_ERR_InvalidInstruction
        assert chip.host_time_ns == before + serial.request_ns(3) + serial.reply_ns(0, failed=True)
    with pmdfmu.Chip(host_interface="parallel16") as chip:
        with pytest.raises(ValueError, match="timed batch"):
            chip.batch([0x3E] * 33)  # 66 reply words: refused before anything is sent
        assert chip.host_time_ns == 0 and chip.cycles == 0


def test_wait_and_run_move_the_host_clock():
    with pmdfmu.Chip() as chip:  # wait works with none too
        chip.wait(0.00035)  # cycles at 0, 100, 200, 300 us
        assert (chip.cycles, chip.host_time_ns) == (4, 350_000)
        chip.wait(Fraction(1, 20000))  # to 400 us: its cycle runs
        assert (chip.cycles, chip.host_time_ns) == (5, 400_000)
        chip.wait(0)
        assert chip.cycles == 5
        chip.run(10)  # cycles 5..14: the clock moves to cycle 14's time
        assert (chip.cycles, chip.host_time_ns) == (15, 1_400_000)
        chip.wait_ns(100_000)
        assert chip.cycles == 16
        with pytest.raises(ValueError):
            chip.wait(-1e-6)
        chip.wait(0.01)  # to 11.5 ms: cycles up to 11.5 ms
        assert (chip.cycles, chip.host_time_ns) == (116, 11_500_000)
        chip.run(1)  # the cycle at 11.6 ms
        assert (chip.cycles, chip.host_time_ns) == (117, 11_600_000)
    host = HostInterface("parallel16")
    with pmdfmu.Chip(host_interface=host, cycleTime=200e-6) as chip:
        chip.run(3)  # cycles at 0, 200, 400 us
        assert chip.host_time_ns == 400_000
        assert chip.axis(0).GetTime() == 2  # 400 us + 500 ns: no new cycle
        chip.axis(0).SetSampleTime(50)  # the grid restarts at 600 us with 50 us cycles
        chip.wait(0.0006)
        t = chip.host_time_ns
        assert t == 400_000 + command_ns(host, "GetTime") + command_ns(host, "SetSampleTime") + 600_000
        assert chip.cycles == 3 + (t - 600_000) // 50_000 + 1


def test_scripts_are_not_affected():
    script = REPO / "examples" / "two_axis.script"
    names = ["axis1.commandedPosition", "axis2.commandedPosition", "axis1.activityStatus"]
    with pmdfmu.Chip(script=str(script)) as a, pmdfmu.Chip(script=str(script), host_interface="serial") as b:
        assert (a.run(3000, record=names) == b.run(3000, record=names)).all()


# ---- seed 000, 1.6: detecting the completion of motion, unchanged ----

SEGMENT_ROWS = [(0, 0x10000, 0, 0, 40), (40, 0x20000, 0, 0, 30), (100, -0x8000, 0, 0, 50), (75, 0, 0, 0, 0)]


def start_external_profile(chip, host):
    """An external profile on axis 1 (buffers 2..6 in dual-port memory, no chip time), started
    as seed 000 1.4/1.6 does; returns the host clock the test expects after it, computed from
    the command table and the transfer formula, and the cycle the profile starts in."""
    ax, clock = chip.axis(0), 0
    for f in range(5):
        ax.SetBufferStart(2 + f, 0x200 + 8 * f)
        ax.SetBufferLength(2 + f, 8)
        ax.SetBufferFunction(f, 2 + f)
        chip.write_memory(0x200 + 8 * f, [row[f] for row in SEGMENT_ROWS])
        clock += sum(command_ns(host, n) for n in ("SetBufferStart", "SetBufferLength", "SetBufferFunction"))
    # the seed's lines
    ax.SetProfileMode(PMDExternalProfile)
    ax.Update()
    clock += command_ns(host, "SetProfileMode")
    update_executes = clock + host.request_ns(1)
    clock += command_ns(host, "Update")
    assert chip.host_time_ns == clock
    return clock, grid_points_at_or_before(update_executes)


def completion_cycle(first):
    """The exact reference model: the cycle whose segment read halts the profile (segment number 0)."""
    model, k = ExternalProfile(SEGMENT_ROWS), 0
    while True:
        model.cycle()
        if not model.running:
            return first + k
        k += 1


@pytest.mark.parametrize(
    "kind,fmi", [("parallel16", 2), ("parallel16", 3), ("parallel8", 2), ("serial", 2), ("spi", 2), ("fixed", 2)]
)
def test_seed_polling_loop_ends_at_the_exact_cycle_plus_the_transfer_time(kind, fmi):
    host = HostInterface(kind)
    with pmdfmu.Chip(fmi, host_interface=host) as chip:
        hAxis = [chip.axis(n) for n in range(4)]
        clock, first = start_external_profile(chip, host)
        done = completion_cycle(first)
        polls = 0
        # seed 000, 1.6: poll the activity status until the profile segment number falls to 0
        while hAxis[0].GetActivityStatus() & PMDActivityProfileSegmentMask:
            polls += 1
        # independently: poll i executes at clock + i * period + request; the first to see it is the
        # first whose execution time is at or after the completion cycle's time
        request, period = host.request_ns(1), command_ns(host, "GetActivityStatus")
        i = max(0, ceil_div(done * CYCLE_NS - clock - request, period))
        assert polls == i > 0
        end = clock + i * period + period
        assert chip.host_time_ns == end
        assert chip.cycles == grid_points_at_or_before(clock + i * period + request)
        assert hAxis[0].GetCommandedPosition() == 75


@pytest.mark.parametrize("kind", ["parallel16", "serial"])
def test_seed_breakpoint_interrupt_ends_at_the_exact_cycle(kind):
    host = HostInterface(kind)
    with pmdfmu.Chip(host_interface=host) as chip:
        hAxis, axis = [chip.axis(n) for n in range(4)], 0
        clock, first = start_external_profile(chip, host)
        done = completion_cycle(first)
        # the seed's lines, after the start
        hAxis[0].SetInterruptMask(PMDEventBreakpoint1Mask)
        hAxis[0].SetBreakpointValue(PMDBreakpoint1, (0x2000 << 16) | 0x0000)
        hAxis[0].SetBreakpoint(PMDBreakpoint1, axis, PMDBreakpointNoAction, PMDBreakpointActivityStatus)
        clock += sum(command_ns(host, n) for n in ("SetInterruptMask", "SetBreakpointValue", "SetBreakpoint"))
        assert clock < done * CYCLE_NS
        assert chip.wait_for_interrupt()
        assert chip.host_time_ns == done * CYCLE_NS and chip.cycles == done + 1
        # the host's handler reads the status: segment 0, one transfer later
        assert field_ex(hAxis[0].GetActivityStatus(), "PMDActivityProfileSegment") == 0
        assert chip.host_time_ns == done * CYCLE_NS + command_ns(host, "GetActivityStatus")
        assert hAxis[0].GetEventStatus() & PMDEventBreakpoint1Mask
        assert chip.wait_for_interrupt()  # still high: no time passes
        hAxis[0].ResetEventStatus(~PMDEventBreakpoint1Mask & 0xFFFF)
        t = chip.host_time_ns
        assert not chip.wait_for_interrupt(timeout=0.001)
        assert chip.host_time_ns == t + 1_000_000


def test_set_state_and_reinitialize_put_the_host_clock_at_the_chip():
    with pmdfmu.Chip(host_interface="parallel16") as chip:
        start = chip.get_state()
        chip.axis(0).GetTime()
        chip.wait(0.001)
        later = chip.get_state()
        chip.set_state(start)
        assert chip.host_time_ns == 0
        chip.set_state(later)
        assert chip.host_time_ns == (chip.cycles - 1) * CYCLE_NS
        chip.reinitialize()
        assert chip.host_time_ns == 0 and chip.cycles == 0


def test_readme_example_prints_what_it_says(capsys):
    """docs/host-time.md: its example runs and prints the values its comments give."""
    section = (REPO / "docs" / "host-time.md").read_text()
    code = section.split("```python\n", 1)[1].split("```", 1)[0]
    exec(compile(code, "docs/host-time.md", "exec"), {})
    printed = capsys.readouterr().out.split("\n")
    said = [line.split("# -> ", 1)[1].strip() for line in code.split("\n") if "# -> " in line]
    assert printed[: len(said)] == said
