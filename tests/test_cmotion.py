# SPDX-License-Identifier: BSD-2-Clause
"""C-Motion in C: the library of host/c over the FMU runs seed 000's
sample code, sections 1.1-1.6, compiled as printed (tests/c/seed_1_*.c), and examples/c.

Each seed program prints the chip's outputs after every cycle (tests/c/seed_support.h); here
the same calls go through the Python harness (a transcription of each program, call for call,
below) and must give the same lines, cycle by cycle; where the profile is an external one, the
exact reference model (reference.py) too. The programs are the CMake build's
($PMDFMU_FMU_DIR/cmotion) when there is one, else compiled here with cc from the same sources;
they load the FMU the suite tests (pmdfmu.default_fmu(2))."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

import pmdfmu
from pmdfmu import (
    PMDActivityInMotionMask,
    PMDAxis1Mask,
    PMDAxis2Mask,
    PMDAxis3Mask,
    PMDExternalProfile,
    PMDTrapezoidal,
    field_ex,
)
from pmdfmu.chip import COMMANDS, encode, instruction_word
from cmotion_build import compile_program, generate
from reference import ExternalProfile

pytestmark = pytest.mark.slow  # tests/README.md: compiles programs or runs the CLI; -m "not slow" leaves it out

ROOT = Path(__file__).resolve().parent.parent
PROGRAMS = ["seed_1_1", "seed_1_2", "seed_1_3", "seed_1_4", "seed_1_5", "seed_1_6", "cmotion_example"]
SEGMENT_CYCLES, ENTRIES, VARIABLES = 64, 5, 5
MEMORY_START, MEMORY_SIZE = 0x200, 0x4000
MAX_VEL, MAX_ACC = 0x20000, 0x800
COLUMNS = [
    f"axis{a}.{q}"
    for a in range(1, 5)
    for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration", "activityStatus", "eventStatus")
] + ["host.interrupt"]


def source_of(name: str) -> Path:
    return ROOT / ("examples" if name == "cmotion_example" else "tests") / "c" / f"{name}.c"


@pytest.fixture(scope="module")
def programs(tmp_path_factory):
    """name -> executable: the CMake build's, or compiled here like CMakeLists.txt builds them."""
    built = Path(os.environ.get("PMDFMU_FMU_DIR", ROOT / "build")) / "cmotion"
    if all((built / p).is_file() for p in PROGRAMS):
        return {p: built / p for p in PROGRAMS}
    if not shutil.which("cc"):
        pytest.skip("no CMake build of the C-Motion programs and no C compiler")
    tmp = tmp_path_factory.mktemp("cmotion")
    generated = generate(tmp / "generated")
    return {p: compile_program(source_of(p), tmp / p, generated) for p in PROGRAMS}


def run_c(programs, name, *args, host="none"):
    """The program's output: (cycle lines as tuples, R lines as lists, E lines)."""
    env = dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)))
    if host is not None:
        env["PMDFMU_HOST_INTERFACE"] = host
    out = subprocess.run([str(programs[name]), *args], capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    lines = [line.split() for line in out.stdout.splitlines()]
    cycles = [tuple(int(x) for x in line[1:]) for line in lines if line[0] == "C"]
    results = [line[1:] for line in lines if line[0] == "R"]
    errors = [line[1:] for line in lines if line[0] == "E"]
    return cycles, results, errors


def entry(axis, variable, index):
    """seed_support.h's seed_entry: the scenario's tables."""
    waypoints = [400 * (axis + 1), 1200 + 100 * axis, 800, 1600 - 200 * axis, 0]
    if index >= ENTRIES - 1:
        return 0
    return {
        0: waypoints[index],
        1: int((waypoints[index + 1] - waypoints[index]) * 65536 / SEGMENT_CYCLES),
        4: SEGMENT_CYCLES,
    }.get(variable, 0)


class Transcription:
    """The programs' calls through the Python harness, recording the same columns every cycle."""

    def __init__(self, chip):
        self.chip = chip
        self.hAxis = [chip.axis(n) for n in range(4)]
        self.cycles = []
        self.results = []

    def run(self, n):
        rec = self.chip.run(n, record=COLUMNS)
        self.cycles += [tuple(int(row[c]) for c in ["cycle"] + COLUMNS) for row in rec]

    def setup_buffers(self, num_axes):
        length = (MEMORY_SIZE - MEMORY_START) // (num_axes * VARIABLES)
        buffer_id = 2
        for axis in range(num_axes):
            for variable in range(VARIABLES):
                self.hAxis[axis].SetBufferStart(buffer_id, MEMORY_START + axis * variable * length)
                self.hAxis[axis].SetBufferLength(buffer_id, length)
                self.hAxis[axis].SetBufferFunction(variable, buffer_id)
                buffer_id += 1
        return length

    def populate(self, num_axes):
        for axis in range(num_axes):
            for variable in range(VARIABLES):
                for index in range(ENTRIES):
                    self.hAxis[axis].WriteBuffer(2 + axis * VARIABLES + variable, entry(axis, variable, index))

    def initial_moves(self, axes):
        for axis in axes:
            ax = self.hAxis[axis]
            ax.SetProfileMode(PMDTrapezoidal)
            ax.SetVelocity(MAX_VEL)
            ax.SetAcceleration(MAX_ACC)
            ax.SetPosition(entry(axis, 0, 0))
            ax.Update()

    def wait_at_rest(self, num_axes):
        while any(self.hAxis[a].GetActivityStatus() & PMDActivityInMotionMask for a in range(num_axes)):
            self.run(64)

    def start_external(self, num_axes):
        for axis in range(num_axes):
            self.hAxis[axis].SetProfileMode(PMDExternalProfile)
        self.hAxis[0].MultiUpdate((1 << num_axes) - 1)

    def write_buffers(self, writes):
        """WriteBuffer (buffer, value) pairs sent as raw batches of 16 commands (the refill's 79 000)."""
        command = COMMANDS["WriteBuffer"]
        for start in range(0, len(writes), 16):
            words = []
            for buffer_id, value in writes[start : start + 16]:
                words += [instruction_word(command.opcode, 0)] + encode(command, [buffer_id, value])
            error, _ = self.chip.batch(words)
            assert error == 0


def signed(x):
    return x - (1 << 32) if x >> 31 else x


def test_seed_1_1_sets_up_the_buffers_as_the_python_transcription(programs):
    cycles, results, errors = run_c(programs, "seed_1_1")
    assert not errors and not cycles
    with pmdfmu.Chip() as chip:
        t = Transcription(chip)
        length = t.setup_buffers(2)  # 1.1 sets num_axes = 2
        expected = [["buffer_length", str(length)]]
        expected += [
            ["buffer", str(i), str(chip.axis(0).GetBufferStart(i)), str(chip.axis(0).GetBufferLength(i))]
            for i in range(2, 12)
        ]
        expected += [
            ["function", str(a), str(f), str(chip.axis(a).GetBufferFunction(f))] for a in range(2) for f in range(5)
        ]
    assert results == expected
    # the seed's own formula: axis 1's five buffers and axis 2's position buffer start at 0x200
    assert [int(r[2]) for r in results[1:7]] == [0x200] * 6


def test_seed_1_2_velocity_profiles_run_as_the_reference_model(programs):
    cycles, _, errors = run_c(programs, "seed_1_2")
    assert not errors
    rows = [tuple(entry(0, v, i) for v in range(VARIABLES)) for i in range(ENTRIES)]
    with pmdfmu.Chip() as chip:
        t = Transcription(chip)
        for v in range(VARIABLES):
            t.hAxis[0].SetBufferStart(2 + v, 0x200 + 16 * v)
            t.hAxis[0].SetBufferLength(2 + v, 16)
            t.hAxis[0].SetBufferFunction(v, 2 + v)
        for row in rows:
            for v in range(VARIABLES):
                t.hAxis[0].WriteBuffer(2 + v, row[v])
        t.hAxis[0].SetProfileMode(PMDExternalProfile)
        t.hAxis[0].Update()
        t.run(ENTRIES * SEGMENT_CYCLES)
    assert cycles == t.cycles
    assert [c[1:4] for c in cycles] == ExternalProfile(rows).run(len(cycles))
    assert field_ex(cycles[-1][4], "PMDActivityProfileSegment") == 0  # ended at the time-0 row


@pytest.mark.parametrize("mode", ["writebuffer", "dpram", "refill"])
def test_seed_1_3_uploads_run_as_the_python_transcription_and_the_reference(programs, mode):
    cycles, results, errors = run_c(programs, "seed_1_3", mode)
    assert not errors
    with pmdfmu.Chip() as chip:
        t = Transcription(chip)
        length = t.setup_buffers(3)
        memory = {}
        for axis in range(3):
            for variable in range(VARIABLES):
                data = [entry(axis, variable, i) for i in range(ENTRIES)]
                if mode == "dpram":
                    # as printed: the offset is axis*variable*buffer_length, without memory_start
                    chip.write_memory(axis * variable * length, [d & 0xFFFFFFFF for d in data])
                    offset = axis * variable * length
                else:
                    for d in data:
                        t.hAxis[axis].WriteBuffer(2 + axis * VARIABLES + variable, d)
                    offset = MEMORY_START + axis * variable * length
                memory.update({offset + i: d for i, d in enumerate(data)})
        indexes = [str(t.hAxis[0].GetBufferReadIndex(2)), str(t.hAxis[0].GetBufferWriteIndex(2))]
        t.results.append(["indexes"] + indexes)
        t.initial_moves(range(3))
        t.wait_at_rest(3)
        t.start_external(3)
        started = len(t.cycles)
        if mode == "refill":
            t.run(100)
            read, write = t.hAxis[0].GetBufferReadIndex(2), t.hAxis[0].GetBufferWriteIndex(2)
            free = read - write if read > write else ((MEMORY_SIZE - MEMORY_START) - (write - read)) & 0xFFFFFFFF
            t.write_buffers([(2 + v, entry(0, v, i % ENTRIES)) for v in range(VARIABLES) for i in range(free)])
            t.results.append(["refill", str(read), str(write), str(free)])
        t.run(1500)
    assert results == t.results
    assert cycles == t.cycles
    if mode != "refill":
        # every axis runs the table the writes left in memory (its buffers overlap as the seed sets them)
        for axis in range(3):
            starts = [MEMORY_START + axis * v * length for v in range(VARIABLES)]
            rows = [tuple(signed(memory.get(s + i, 0) & 0xFFFFFFFF) for s in starts) for i in range(length)]
            got = [c[1 + 5 * axis : 4 + 5 * axis] for c in cycles[started:]]
            assert got == ExternalProfile(rows).run(len(got)), f"axis {axis + 1}"


@pytest.mark.parametrize("mode", ["update", "multiupdate"])
def test_seed_1_4_start_runs_as_the_python_transcription(programs, mode):
    cycles, _, errors = run_c(programs, "seed_1_4", mode)
    assert not errors
    with pmdfmu.Chip() as chip:
        t = Transcription(chip)
        t.setup_buffers(3)
        t.populate(3)
        t.initial_moves([0, 1])  # as printed: axes 1 and 2 only
        t.wait_at_rest(3)
        if mode == "update":
            t.hAxis[0].SetProfileMode(PMDExternalProfile)
            t.hAxis[0].Update()
        else:
            for axis in range(3):
                t.hAxis[axis].SetProfileMode(PMDExternalProfile)
            t.hAxis[0].MultiUpdate(PMDAxis1Mask + PMDAxis2Mask + PMDAxis3Mask)
        started = len(t.cycles)
        t.run(1500)
    assert cycles == t.cycles
    segments = [field_ex(cycles[started][5 * a + 4], "PMDActivityProfileSegment") for a in range(3)]
    assert segments[0] == 1  # axis 1 reads its first row in the first cycle
    if mode == "update":
        assert segments[1:] == [0, 0]  # Update starts axis 1 alone


@pytest.mark.parametrize("mode", ["single", "multi"])
def test_seed_1_5_stop_runs_as_the_python_transcription(programs, mode):
    cycles, results, errors = run_c(programs, "seed_1_5", mode)
    assert not errors
    with pmdfmu.Chip() as chip:
        t = Transcription(chip)
        t.setup_buffers(3)
        t.populate(3)
        t.initial_moves(range(3))
        t.wait_at_rest(3)
        t.start_external(3)
        t.run(300)
        stopped = [0] if mode == "single" else [0, 1, 2]
        for axis in stopped:
            t.hAxis[axis].SetStopMode(pmdfmu.PMDAbruptStop)
        if mode == "single":
            t.hAxis[0].Update()
        else:
            t.hAxis[0].MultiUpdate(PMDAxis1Mask + PMDAxis2Mask + PMDAxis3Mask)
        t.run(50)
        t.results += [["stopmode", str(a), str(t.hAxis[a].GetStopMode())] for a in range(3)]
    assert cycles == t.cycles and results == t.results
    for axis in stopped:  # held where the stop found it, in one cycle
        assert len({c[1 + 5 * axis] for c in cycles[-50:]}) == 1
        assert all(c[2 + 5 * axis] == 0 for c in cycles[-50:])


def transcribe_1_6(chip, cycles=5000):
    t = Transcription(chip)
    t.setup_buffers(3)
    t.populate(3)
    t.initial_moves(range(3))
    t.wait_at_rest(3)
    ax = t.hAxis[0]
    ax.SetProfileMode(PMDExternalProfile)
    ax.Update()
    ax.SetInterruptMask(pmdfmu.PMDEventBreakpoint1Mask)
    ax.SetBreakpointValue(pmdfmu.PMDBreakpoint1, (0x2000 << 16) | 0x0000)
    ax.SetBreakpoint(pmdfmu.PMDBreakpoint1, 0, pmdfmu.PMDBreakpointNoAction, pmdfmu.PMDBreakpointActivityStatus)
    started = len(t.cycles)
    t.run(cycles)
    t.results.append(["breakpoint", *map(str, ax.GetBreakpoint(pmdfmu.PMDBreakpoint1))])
    return t, started


def test_seed_1_6_breakpoint_interrupt_at_completion_as_the_python_transcription(programs):
    """With the Update the text means (`meant`), between the snippet's two paragraphs."""
    cycles, results, errors = run_c(programs, "seed_1_6", "meant")
    assert errors == [["PMDUpdate(PMDAxis1)", "0x1106"]]
    with pmdfmu.Chip() as chip:
        t, started = transcribe_1_6(chip)
    assert cycles == t.cycles and results == t.results == [["breakpoint", "0", "0", "0"]]
    segment = [field_ex(c[4], "PMDActivityProfileSegment") for c in cycles[started:]]
    done = segment.index(0)
    interrupt = [c[-1] for c in cycles[started:]]
    assert done > 0 and not any(interrupt[:done]) and all(interrupt[done:])


def test_seed_1_6_polling_loop_ends_at_completion_plus_the_transfer_time(programs):
    """The completion poll of 1.6's text, unchanged C, on the library's default host interface
    (parallel16): it ends with the first GetActivityStatus whose request arrives at or after the
    completing cycle; the chip's cycles are those of the run without polling."""
    from pmdfmu.hosttime import HostInterface

    cycles, results, errors = run_c(programs, "seed_1_6", "meant", "poll", host=None)
    assert errors == [["PMDUpdate(PMDAxis1)", "0x1106"]]
    start, end, polls = (int(x) for x in results[0][1:])
    host = HostInterface("parallel16")
    per_poll = host.request_ns(1) + host.reply_ns(1)
    assert end == start + polls * per_poll
    # the completing cycle: the first whose profile segment number is 0 after the start
    started = next(i for i, c in enumerate(cycles) if field_ex(c[4], "PMDActivityProfileSegment"))
    done = next(c[0] for c in cycles[started:] if field_ex(c[4], "PMDActivityProfileSegment") == 0)
    t_done = done * 100_000  # the default cycle time, 100 us, from time 0
    last_request = start + (polls - 1) * per_poll + host.request_ns(1)
    assert last_request >= t_done > last_request - per_poll
    # host time moves the start (the set-up's commands took time), not the profile: from its first
    # cycle on, every output equals the run of the Python transcription (no host time), cycle by cycle
    with pmdfmu.Chip() as chip:
        t, t_started = transcribe_1_6(chip)
    polled = [c[1:] for c in cycles[started:]]
    assert polled == [c[1:] for c in t.cycles[t_started : t_started + len(polled)]]
    assert field_ex(polled[-1][3], "PMDActivityProfileSegment") == 0 and polled[-1][-1] == 1  # interrupt


@pytest.mark.parametrize("mode", [[], ["poll"]])
def test_seed_1_6_as_printed_its_update_of_an_axis_number_is_refused_unsent(programs, mode):
    """PMDUpdate(PMDAxis1) hands the library a null handle: PMD_ERR_InvalidHandle, no crash, and
    the chip never sees an Update, so the external profile never starts: no cycle shows a profile
    segment, and the chip's cycles are the transcription's without the Update (whose breakpoint,
    "bit 13 low", then fires at once)."""
    cycles, results, errors = run_c(programs, "seed_1_6", *mode)
    assert errors == [["PMDUpdate(PMDAxis1)", "0x1106"]]
    assert not any(field_ex(c[4], "PMDActivityProfileSegment") for c in cycles)
    if not mode:
        with pmdfmu.Chip() as chip:
            t = Transcription(chip)
            t.setup_buffers(3)
            t.populate(3)
            t.initial_moves(range(3))
            t.wait_at_rest(3)
            ax = t.hAxis[0]
            ax.SetProfileMode(PMDExternalProfile)
            ax.SetInterruptMask(pmdfmu.PMDEventBreakpoint1Mask)
            ax.SetBreakpointValue(pmdfmu.PMDBreakpoint1, (0x2000 << 16) | 0x0000)
            ax.SetBreakpoint(pmdfmu.PMDBreakpoint1, 0, pmdfmu.PMDBreakpointNoAction, pmdfmu.PMDBreakpointActivityStatus)
            t.run(5000)
            t.results.append(["breakpoint", *map(str, ax.GetBreakpoint(pmdfmu.PMDBreakpoint1))])
        assert cycles == t.cycles and results == t.results


def test_the_example_host_program_runs_to_completion(programs):
    out = subprocess.run(
        [str(programs["cmotion_example"])],
        capture_output=True,
        text=True,
        timeout=300,
        env=dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2))),
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert "profile complete" in out.stdout


@pytest.mark.parametrize("host", ["parallel16", "serial"])
def test_seed_1_5_under_host_time_runs_as_the_python_harness_with_the_same_interface(programs, host):
    """With host time, the C library and the Python harness (Chip(host_interface=...)) run the
    same cycles between the same commands: the same lines, cycle by cycle."""
    cycles, results, errors = run_c(programs, "seed_1_5", "multi", host=host)
    assert not errors
    with pmdfmu.Chip(host_interface=host) as chip:
        t = Transcription(chip)
        t.setup_buffers(3)
        t.populate(3)
        t.initial_moves(range(3))
        t.wait_at_rest(3)
        t.start_external(3)
        t.run(300)
        for axis in range(3):
            t.hAxis[axis].SetStopMode(pmdfmu.PMDAbruptStop)
        t.hAxis[0].MultiUpdate(PMDAxis1Mask + PMDAxis2Mask + PMDAxis3Mask)
        t.run(50)
        t.results += [["stopmode", str(a), str(t.hAxis[a].GetStopMode())] for a in range(3)]
        last = chip.get("chipTime")
    # the cycles the commands ran are printed by C, not recorded by Python's run(): compare C's
    # lines at the cycles Python recorded, and the chip time at the end
    by_cycle = {c[0]: c for c in cycles}
    assert all(by_cycle[c[0]] == c for c in t.cycles)
    assert results == t.results
    assert cycles[-1][0] == last


SANITIZERS = {"thread": "thread", "address": "address,undefined"}
SANITIZED = [s for s in os.environ.get("PMDFMU_C_SANITIZERS", "").split(",") if s]  # ./dev sanitize


@pytest.mark.sanitize
@pytest.mark.skipif(not SANITIZED, reason="PMDFMU_C_SANITIZERS names no sanitizer (./dev sanitize does)")
@pytest.mark.parametrize("flavour", SANITIZED)
@pytest.mark.parametrize(
    "name, args", [(p, ()) for p in PROGRAMS] + [("seed_1_3", ("dpram",)), ("seed_1_6", ("meant", "poll"))]
)
def test_the_programs_under_a_sanitizer_print_what_they_print_plain(programs, tmp_path, flavour, name, args):
    """The seed's programs and the example built with ThreadSanitizer or ASan + UBSan: no report, and the
    same output, line for line, as the plain build's."""
    if flavour not in SANITIZERS:
        pytest.fail(f"PMDFMU_C_SANITIZERS: unknown sanitizer {flavour!r} (thread, address)")
    exe = compile_program(source_of(name), tmp_path / name, generate(tmp_path / "generated"), SANITIZERS[flavour])
    # as run_c runs them: no host time, but a polling loop's (its wait ends only as chip time passes)
    env = dict(os.environ, PMDFMU_FMU=str(pmdfmu.default_fmu(2)))
    if "poll" not in args:
        env["PMDFMU_HOST_INTERFACE"] = "none"
    env.pop("LD_PRELOAD", None)  # ./dev sanitize's runtimes for Python, not for these
    outputs = [
        subprocess.run([str(e), *args], capture_output=True, text=True, env=env, timeout=600)
        for e in (programs[name], exe)
    ]
    for out in outputs:
        assert out.returncode == 0 and "Sanitizer" not in out.stderr, out.stderr[-3000:]
    assert outputs[1].stdout == outputs[0].stdout
