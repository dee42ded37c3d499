#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-2-Clause
"""Hand-built inputs of the sequence fuzzer (fuzz/fuzz_sequence.c):
seeds that reach deep states (fuzz/corpus/sequence/), one regression input
per bug reached by legal calls (fuzz/regressions/sequence/), and the bad
script and table files the attack with legal calls found, for fuzz_script.c (fuzz/regressions/script/). The test suite
replays both folders (tests/test_determinism.py).

    python fuzz/sequence_inputs.py        (re)writes the files named below

Seq mirrors the byte layout that fuzz_sequence.c decodes, operation by
operation: change both together. The list of operations is read from
fuzz_sequence.c's OPS[] (read_ops); tests/test_determinism.py checks that Seq
encodes each of them and that a seed or regression input uses each. To see what an input does, run it traced:
FUZZ_SEQUENCE_TRACE=1 build/fuzz/fuzz_sequence FILE.
"""

import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "modelDescription"))
from generating import harness_tables  # noqa: E402  (the interface tables' reader, by path)

tables = harness_tables()

COMMANDS = tables.read_commands(HERE.parent / "modelDescription" / "commands.csv")
COMMAND_INDEX = {c.name: i for i, c in enumerate(COMMANDS)}


def read_ops(source: Path = HERE / "fuzz_sequence.c"):
    """The names of the rows of OPS[] in fuzz_sequence.c, in order (each row {"name", op_name})."""
    text = source.read_text()
    table = text[text.index("static const Operation OPS[] = {") :]
    rows = re.findall(r'\{"(\w+)", op_(\w+)\}', table[: table.index("};")])
    assert rows and all(name == function for name, function in rows), rows
    return [name for name, _ in rows]


# the rows of OPS[] in fuzz_sequence.c, in order: an operation's byte is its index
OPS = read_ops()

# value(): selector bytes for symbolic values (M is the memory size)
SYMBOLS = {"lo": 0, "lo+1": 1, "hi": 2, "hi-1": 3, "zero": 4, "one": 5, "M": 6, "M-1": 7, "M+1": 8}
EXACT = 11

# the variables a record.columns column may name, in variables.csv's order (fuzz_sequence.c's recordable[])
RECORDABLE = [
    v.name
    for v in tables.read_variables(HERE.parent / "modelDescription" / "variables.csv")
    if v.type not in ("String", "Binary") and v.name != "time"
]

CYCLE_TIMES = [1e-4, 1e-6, 0.065535, 1e-3, 2.5e-5, 3e-4, 0.065534, 2e-6]
# fuzz_sequence.c's MACHINE_NUMBERS (op_machine), and the plant's variables in plant.csv's order
# (plant_variables[], which op_machine indexes: a row that is no parameter is refused by the parser)
MACHINE_NUMBERS = re.findall(
    r'"([^"]*)"', re.search(r"MACHINE_NUMBERS\[\] = \{(.*?)\};", (HERE / "fuzz_sequence.c").read_text(), re.S).group(1)
)
PLANT_PARAMETERS = [
    line.split(",", 1)[0] for line in (HERE.parent / "modelDescription" / "plant.csv").read_text().splitlines()[1:]
]
START_TIMES = [0, 1, 0.5, -1, 1e3, 1e-4]


class Seq:
    """An input: the FMI version, then operations."""

    def __init__(self, fmi3=False):
        self.data = bytearray([1 if fmi3 else 0])

    def bytes(self) -> bytes:
        return bytes(self.data)

    # -- the byte reader's vocabulary ---------------------------------------------------

    def byte(self, x):
        self.data.append(x & 0xFF)

    def value(self, x):
        """An exact value (int, within the field's range), a symbol of SYMBOLS, or ("M-", k):
        a selector byte and a 4-byte payload."""
        if isinstance(x, str):
            self.byte(SYMBOLS[x])
            payload = 0
        elif isinstance(x, tuple):
            self.byte(9)
            payload = x[1]
        else:
            self.byte(EXACT)
            payload = x & 0xFFFFFFFF
        self.data += payload.to_bytes(4, "big")

    def op(self, name):
        self.byte(OPS.index(name))

    def flags(self, axis=0, pending=False, bits=0):
        self.byte(axis | (4 if pending else 0) | bits << 3)

    # -- operations ---------------------------------------------------------------------

    def command(self, name, *args, axis=0, pending=False):
        self.op("command")
        self.flags(axis, pending)
        self.byte(COMMAND_INDEX[name])
        assert len(args) == len(COMMANDS[COMMAND_INDEX[name]].args), name
        for a in args:
            self.value(a)
        return self

    def buffer(self, id, start, length, function=None, length_first=False, unassign=False, axis=0, pending=False):
        self.op("buffer")
        self.flags(axis, pending, (1 if length_first else 0) | (2 if unassign else 0))
        self.value(id)
        self.value(start)
        self.value(length)
        self.byte(5 if function is None else function)
        return self

    def write_buffer(self, id, values, axis=0, pending=False):
        assert 1 <= len(values) <= 32
        self.op("write_buffer")
        self.flags(axis, pending)
        self.value(id)
        self.byte(len(values) - 1)
        for v in values:
            self.value(v)
        return self

    def buffer_index(self, kind, id, index, axis=0, pending=False):
        """kind: "write" (SetBufferWriteIndex), "read" (SetBufferReadIndex), "readbuffer" (index % 8 + 1 reads)."""
        self.op("buffer_index")
        self.flags(axis, pending, ["write", "read", "readbuffer"].index(kind))
        self.value(id)
        self.value(index)
        return self

    def external_profile(self, start, rows, functions=(0, 4), axis=0, pending=False):
        """rows: one dict per segment, function number -> value; buffers 2+f hold function f,
        at start + f * len(rows)."""
        mask = sum(1 << f for f in functions) | 1
        assert 1 <= len(rows) <= 8
        self.op("external_profile")
        self.flags(axis, pending, mask)
        self.byte(len(rows) - 1)
        self.value(start)
        for f in range(5):
            if mask >> f & 1:
                for row in rows:
                    self.value(row.get(f, 0 if f != 4 else 1))
        return self

    def move(
        self,
        mode,
        position,
        velocity,
        acceleration,
        deceleration=0,
        jerk=None,
        gear=None,
        multi=None,
        axis=0,
        pending=False,
    ):
        """mode 0 trapezoidal, 1 velocity, 2 S-curve (jerk), 3 gear (gear = (master, ratio, source)),
        4 external; multi: a MultiUpdate mask instead of Update."""
        self.op("move")
        self.flags(axis, pending, 1 if multi is not None else 0)
        self.byte(mode)
        for v in (position, velocity, acceleration, deceleration):
            self.value(v)
        if mode == 2:
            self.value(jerk)
        if mode == 3:
            master, ratio, source = gear
            self.byte(master)
            self.value(ratio)
            self.byte(source)
        if multi is not None:
            self.value(multi)
        return self

    def trace(
        self, start_address, length, variables, mode, period, start, stop=None, start_first=True, axis=0, pending=False
    ):
        """variables: (axis, variable ID) per slot; start, stop: (axis, condition, bit, state)."""
        self.op("trace")
        self.flags(axis, pending, (1 if start_first else 0) | (2 if stop else 0))
        self.byte(len(variables))
        self.value(start_address)
        self.value(length)
        for a, v in variables:
            self.byte(a)
            self.byte(v)
        self.byte(mode)
        self.value(period)
        for word in (start, stop or (0, 0, 0, 0)):
            for x in word:
                self.byte(x)
        return self

    def breakpoint(self, bp, source, action, trigger, value, axis=0, pending=False):
        self.op("breakpoint")
        self.flags(axis, pending)
        for x in (bp, source, action, trigger):
            self.byte(x)
        self.value(value)
        return self

    def sample_time(self, us, pending=False):
        self.op("sample_time")
        self.flags(0, pending)
        self.value(us)
        return self

    def stop(self, smooth=False, multi=False, axis=0, pending=False):
        self.op("stop")
        self.flags(axis, pending, (1 if smooth else 0) | (2 if multi else 0))
        return self

    def chip_reset(self, read_error=True, pending=False):
        self.op("chip_reset")
        self.flags(0, pending, 1 if read_error else 0)
        return self

    def memory(self, kind, address=0, count=0, seed=0, pending=False):
        """kind: "write" (address, count, data seed, seed+1, ..., new strobe), or "address", "count",
        "strobe" alone."""
        self.op("memory")
        self.byte(["write", "address", "count", "strobe"].index(kind) | (4 if pending else 0))
        self.value(address)
        self.value(count)
        self.value(seed)
        return self

    def _cycles(self, cycles):
        """A kind byte and a 2-byte payload: 1, 2..9, 10..999, 1000 + 2k (k < 65536), n + 0.5 (n < 8),
        "capacity-1/0/+1", ("huge", e) for 2^e cycles (40 <= e < 64), ("fraction", k) for k/256 of a cycle."""
        if cycles == 1:
            kind, p = 0, 0
        elif isinstance(cycles, int) and 2 <= cycles <= 9:
            kind, p = 1, cycles - 2
        elif isinstance(cycles, int) and 10 <= cycles < 1000:
            kind, p = 2, cycles - 10
        elif isinstance(cycles, int) and cycles >= 1000 and (cycles - 1000) % 2 == 0:
            kind, p = 3, (cycles - 1000) // 2
        elif isinstance(cycles, float):
            kind, p = 4, int(cycles)
        elif isinstance(cycles, str) and cycles.startswith("capacity"):
            kind, p = 5, {"capacity-1": 0, "capacity": 1, "capacity+1": 2}[cycles]
        elif cycles[0] == "huge":
            kind, p = 6, (1 | (53 - cycles[1]) << 1) if cycles[1] in (52, 53) else (cycles[1] - 40) << 1
        else:
            kind, p = 7, cycles[1] - 1
        self.byte(kind)
        self.data += p.to_bytes(2, "big")

    def step(self, cycles=1):
        self.op("step")
        self._cycles(cycles)
        return self

    def replay(self, *steps, via_bytes=False):
        assert 1 <= len(steps) <= 4
        self.op("replay")
        self.byte(len(steps) - 1)
        self.byte(1 if via_bytes else 0)
        for c in steps:
            self._cycles(c)
        return self

    def save(self, slot=0):
        self.op("save")
        self.byte(slot)
        return self

    def restore(self, slot=0, via_bytes=False):
        self.op("restore")
        self.byte(slot)
        self.byte(1 if via_bytes else 0)
        return self

    def reinitialize(
        self,
        memory=0x4000,
        capacity=65536,
        cycle_time=1e-4,
        start=0,
        loopback=True,
        record=False,
        terminate=False,
        early=False,
        bad_cycle_time=None,
        start_in_cycles=False,
    ):
        bits = (
            (1 if terminate else 0)
            | (2 if early else 0)
            | (0 if loopback else 4)
            | (8 if record else 0)
            | (32 if start_in_cycles else 0)
        )
        if bad_cycle_time is not None:
            bits |= 16 | bad_cycle_time << 6
        self.op("reinitialize")
        self.byte(bits)
        self.value(memory)
        self.value(capacity)
        self.byte(CYCLE_TIMES.index(cycle_time))
        self.byte(START_TIMES.index(start))
        return self

    def input(self, axis, kind, value):
        """kind: "actualPosition" (int), "positiveLimit", "negativeLimit", "home" (bool)."""
        self.op("input")
        self.byte(axis)
        k = ["actualPosition", "positiveLimit", "negativeLimit", "home"].index(kind)
        self.byte(k)
        if k == 0:
            self.value(value)
        else:
            self.byte(1 if value else 0)
        return self

    def record(self, on=True):
        self.op("record")
        self.byte(1 if on else 0)
        return self

    def logging(self, on=True):
        self.op("logging")
        self.byte(1 if on else 0)
        return self

    def refused(self, kind, *extra):
        """kind 0 unknown vr, 1 wrong type, 2 memorySize, 3 cycleTime in step mode, 4 step off the
        communication point, 5 bad step size (extra: 0..3 for 0, -1, NaN, inf), 6 wordCount 65,
        7 memory.count (extra: 1 for -1), 8 corrupted state (extra: 4-byte offset, xor-1)."""
        self.op("refused")
        self.byte(kind)
        if kind == 8:
            offset, xor = extra
            self.data += offset.to_bytes(4, "big")
            self.byte(xor - 1)
        else:
            for x in extra:
                self.byte(x)
        return self

    def script(self, lines, capacity=65536, cycle_time=1e-4, record=False):
        """lines: (cycle delta, axis, command name, args...) each; a new initialization runs them."""
        assert 1 <= len(lines) <= 8
        self.op("script")
        self.byte(1 if record else 0)
        self.byte(len(lines) - 1)
        self.value(capacity)
        self.byte(CYCLE_TIMES.index(cycle_time))
        for delta, axis, name, *args in lines:
            self.byte(delta)
            self.byte(axis)
            self.byte(COMMAND_INDEX[name])
            assert len(args) == len(COMMANDS[COMMAND_INDEX[name]].args), name
            for a in args:
                self.value(a)
        return self

    def enter_initialization(self, start=0, terminate=False, start_in_cycles=False):
        """Reset and initialization mode, until exit_initialization."""
        self.op("enter_initialization")
        self.byte((1 if terminate else 0) | (2 if start_in_cycles else 0))
        self.byte(START_TIMES.index(start))
        return self

    def parameter(self, name, value):
        """name: "memorySize" (value), "cycleTime" (one of CYCLE_TIMES), "badCycleTime" (index 0..3),
        "loopback" (bool), "record.capacity" (value)."""
        self.op("parameter")
        k = ["memorySize", "cycleTime", "badCycleTime", "loopback", "record.capacity"].index(name)
        self.byte(k)
        if k == 1:
            self.byte(CYCLE_TIMES.index(value))
        elif k in (2, 3):
            self.byte(int(value))
        else:
            self.value(value)
        return self

    def exit_initialization(self):
        self.op("exit_initialization")
        return self

    def machine(self, axes, cycle_time=1e-4, loopback=True):
        """A new initialization with a machine (op_machine): axes, up to 4 dicts (or None: no table) of
        the keys servo_plant (bool), home ((lo, width)), positive_limit, negative_limit, index (K or a
        list of 1..4 positions), signal_sense, plant (1..4 (parameter, number) pairs, number one of
        MACHINE_NUMBERS)."""
        self.op("machine")
        self.byte(0 if loopback else 1)
        self.byte(CYCLE_TIMES.index(cycle_time))
        for n in range(4):
            a = axes[n] if n < len(axes) and axes[n] else {}
            index = a.get("index")
            keys = (
                (1 if a.get("servo_plant") else 0)
                | (2 if "home" in a else 0)
                | (4 if "positive_limit" in a else 0)
                | (8 if "negative_limit" in a else 0)
                | (16 if isinstance(index, int) else 32 if index else 0)
                | (64 if "signal_sense" in a else 0)
                | (128 if a.get("plant") else 0)
            )
            self.byte(keys)
            if "home" in a:
                self.value(a["home"][0])
                self.value(a["home"][1])
            for key in ("positive_limit", "negative_limit"):
                if key in a:
                    self.value(a[key])
            if isinstance(index, int):
                self.value(index)
            elif index:
                assert 1 <= len(index) <= 4
                self.byte(len(index) - 1)
                for p in index:
                    self.value(p)
            if "signal_sense" in a:
                self.value(a["signal_sense"])
            if a.get("plant"):
                assert 1 <= len(a["plant"]) <= 4
                self.byte(len(a["plant"]) - 1)
                for name, number in a["plant"]:
                    self.byte(PLANT_PARAMETERS.index(name))
                    self.byte(MACHINE_NUMBERS.index(number))
        return self

    def columns(self, kind, *lists, check=True):
        """record.columns: kind "valid" (lists[0]: names, blanks as (name, before, after)), "empty", "bad"
        (lists[0]: names, lists[1]: (position, bad_columns index)), "two" (lists: two values, each a list of
        names, [] for "", or ("bad", names, position, bad index)), "many" (4097 empty columns); check: read
        record.columns and record.rowSize back."""
        self.op("columns")
        self.byte(["valid", "empty", "bad", "two", "many"].index(kind))
        self.byte(1 if check else 0)
        if kind == "valid":
            self._column_list(lists[0])
        elif kind == "bad":
            self._column_list(lists[0], *lists[1])
        elif kind == "two":
            for value in lists:
                if value == []:
                    self.byte(1)
                elif value[0] == "bad":
                    self.byte(2)
                    self._column_list(value[1], value[2], value[3])
                else:
                    self.byte(0)
                    self._column_list(value)
        return self

    def _column_list(self, names, at=0, bad=0):
        """column_list(): the count, the bad name's position and index, then per name its index among the
        recordable variables (RECORDABLE) and its blanks byte."""
        assert 1 <= len(names) <= 8
        self.byte(len(names) - 1)
        self.byte(at)
        self.byte(bad)
        for name in names:
            blanks = 0
            if isinstance(name, tuple):
                name, before, after = name
                blanks = (1 if before else 0) | (2 if after else 0)
            self.data += RECORDABLE.index(name).to_bytes(2, "big")
            self.byte(blanks)

    def lend(self, kind, rows_or_bytes=0, offset=0):
        """FMI 2's pmdfmu_fmi2SetRecordBuffer: kind "rows" (whole rows of record.columns as they stand),
        "bytes", "null", "empty" (0 bytes), at offset 0..7 into the fuzzer's lend area."""
        self.op("lend")
        self.byte(["rows", "bytes", "null", "empty"].index(kind))
        self.byte(offset)
        self.data += rows_or_bytes.to_bytes(2, "big")
        return self

    def record_data(self):
        self.op("record_data")
        return self

    def memory_block(
        self,
        first=0,
        n=64,
        seed=1,
        check=True,
        prefix=None,
        prefix_value=0,
        gap=False,
        again=False,
        fmi3_kind=None,
        more=False,
    ):
        """memory.data as a block: FMI 2 the run memory.data[first + 1] .. [first + n] (first 0..63, n 1..65),
        prefix "count" or "address" (prefix_value) first, gap: without its middle element, again: its first
        element once more at the end; FMI 3 (fmi3_kind): "array", "address" (memory.address first), "twice",
        "count" (a wrong nValues: 65 with more, else 63)."""
        bits = (1 if check else 0) | (16 if again else 0) | (8 if gap else 0) | (32 if more else 0)
        if fmi3_kind is not None:
            bits |= ["array", "address", "twice", "count"].index(fmi3_kind) << 1
            if fmi3_kind == "address":
                prefix = "address"
        elif prefix is not None:
            bits |= 2 | (4 if prefix == "count" else 0)
        self.op("memory_block")
        self.byte(bits)
        self.byte(first)
        self.byte(n - 1)
        self.data += (seed & 0xFFFFFFFF).to_bytes(4, "big")
        self.value(prefix_value)
        return self

    def axis_setup(
        self,
        error_limit,
        settle_time,
        settle_window,
        tracking_window,
        signal_sense,
        interrupt_mask,
        auto_stop=False,
        settled_complete=False,
        limits=True,
        capture_home=False,
        motor_off=False,
        axis=0,
        pending=False,
    ):
        self.op("axis_setup")
        self.flags(
            axis,
            pending,
            (1 if auto_stop else 0)
            | (2 if settled_complete else 0)
            | (4 if limits else 0)
            | (8 if capture_home else 0)
            | (16 if motor_off else 0),
        )
        for v in (error_limit, settle_time, settle_window, tracking_window, signal_sense, interrupt_mask):
            self.value(v)
        return self


# ---- seeds: short sequences into deep states ---------------------------------------------


def lent_sequence(fmi3, wide):
    """Memory lent for the rows and taken back every way (seeds())."""
    return (
        Seq(fmi3=fmi3)
        .record(True)
        .move(1, 0, 0x20000, 0x800, axis=1)
        .lend("rows", 100)
        .step(50)
        .record_data()
        .columns("valid", ["axis2.velocity", "axis2.commandedPosition"])
        .step(60)
        .record_data()
        .columns("valid", wide)
        .step(90)
        .sample_time(10, pending=True)
        .step(5)
        .record_data()
        .save(1)
        .step(3)
        .restore(1, via_bytes=True)
        .record_data()
        .step(2)
        .record_data()
        .replay(2, 1)
        .lend("bytes", 12, offset=3)
        .step(3)
        .columns("empty")
        .step(1)
        .lend("bytes", 1000, offset=2)
        .step(1)
        .lend("empty")
        .step(1)
        .lend("null")
        .step(20)
        .record_data()
        .lend("rows", 300, offset=4)
        .step(10)
        .reinitialize(capacity=200, record=True)
        .step(10)
        .record_data()
    )


def seeds():
    out = {}
    # a trace armed to start on the next Update, buffer 0 then changed, then Update (the first legal-call finding's shape)
    out["trace-start-on-update-then-buffer0-changes"] = (
        Seq()
        .trace(0x100, 8, [(0, 2), (0, 3)], 1, 1, (0, 1, 0, 0))
        .buffer(0, 0x200, 3)
        .move(0, 1000, 0x10000, 0x1000)
        .step(5)
        .replay(3, 1, via_bytes=True)
    )
    # every trace start and stop condition on a moving axis
    s = Seq(fmi3=True)
    for cond in range(5):
        s.trace(
            0,
            16,
            [(1, 8), (1, 13), (1, 12)],
            cond % 2,
            1 + cond,
            (1, cond, 10, 1),
            stop=(1, 4 - cond, 3, 0),
            start_first=bool(cond % 2),
        )
        s.move(0, 5000 * (cond + 1), 0x20000, 0x800, axis=1).step(20)
        s.command("GetTraceStatus").command("GetTraceCount")
    out["trace-every-condition"] = s.replay(10, 7)
    # FMI 3 recording, then the sample time changes while recording
    out["record-then-sample-time-changes"] = (
        Seq(fmi3=True)
        .reinitialize(capacity=1000, record=True)
        .move(1, 0, 0x30000, 0x1000, axis=2)
        .step(100)
        .sample_time(50)
        .step(10)
        .sample_time(200, pending=True)
        .step(3)
        .record(False)
        .step(2000)
        .replay(5, 1, via_bytes=True)
    )
    # an external profile over all five functions, saved, run, restored through bytes
    rows = [{0: 10 * k, 1: 0x8000 * k, 2: 0x100, 3: 1 << k, 4: 2 + k} for k in range(6)]
    out["external-profile-five-functions"] = (
        Seq()
        .external_profile(0x40, rows, functions=(0, 1, 2, 3, 4))
        .save(0)
        .step(30)
        .replay(4, 9, via_bytes=True)
        .restore(0, via_bytes=True)
        .step(7)
    )
    # streaming: WriteBuffer into a running profile, indexes, ReadBuffer, dual-port memory writes
    out["streamed-profile-and-memory-port"] = (
        Seq()
        .buffer(2, 0x300, 4, function=0)
        .buffer(3, 0x304, 4, function=4)
        .write_buffer(2, [1, 2, 3, 4])
        .write_buffer(3, [3, 3, 3, 3])
        .move(4, 0, 0, 0)
        .step(6)
        .buffer_index("read", 2, 3)
        .buffer_index("write", 3, 1)
        .memory("write", 0x300, 4, 77)
        .memory("write", ("M-", 64), 64, 5, pending=True)
        .step(9)
        .buffer_index("readbuffer", 2, 5)
        .replay(8)
    )
    # the four axes in four profile modes, a breakpoint, stops
    out["four-axes-moves-breakpoint-stop"] = (
        Seq()
        .move(0, 100000, 0x50000, 0x2000, 0x1000)
        .move(1, 0, -0x40000, 0x3000, axis=1)
        .move(2, -20000, 0x40000, 0x4000, jerk=0x10000, axis=2)
        .move(3, 0, 0, 0, gear=(0, 0x20000, 1), axis=3)
        .breakpoint(0, 0, 2, 1, 50000, axis=0)
        .step(500)
        .stop(smooth=True, axis=1)
        .stop(multi=True, axis=2)
        .step(3000)
        .replay(1000, 20)
    )
    # other parameters: a small memory, 1 us cycles, no loopback, switches and encoder inputs
    out["small-memory-no-loopback-switches"] = (
        Seq(fmi3=True)
        .reinitialize(memory=64, cycle_time=1e-6, loopback=False, start=1e3, early=True)
        .input(0, "actualPosition", 12345)
        .input(0, "positiveLimit", True)
        .input(1, "home", True)
        .command("SetCaptureSource", 1, axis=1)
        .move(0, 1 << 20, 0x10000, 0x100)
        .step(50)
        .input(0, "positiveLimit", False)
        .command("ResetEventStatus", 0)
        .step(10)
        .buffer(2, "M-1", 1)
        .write_buffer(2, [9])
        .replay(3)
    )
    # the refusals, in states with pending writes
    out["refused-calls-in-deep-states"] = (
        Seq()
        .move(0, 1000, 0x10000, 0x100)
        .sample_time(10, pending=True)
        .refused(4)
        .refused(5, 2)
        .memory("write", 0, 64, 1, pending=True)
        .refused(7, 1)
        .refused(6)
        .refused(2)
        .refused(3)
        .refused(8, 4096, 0x80)
        .step(3)
        .refused(0)
        .refused(1)
    )
    # a chip Reset between moves, logging on, save and restore across a re-initialization
    out["reset-logging-restore-across-reinit"] = (
        Seq(fmi3=True)
        .logging(True)
        .move(0, 500, 0x10000, 0x100)
        .step(10)
        .save(1)
        .chip_reset()
        .step(2)
        .reinitialize(memory=0x1000, cycle_time=1e-3, capacity=10, record=True)
        .step("capacity")
        .step("capacity+1")
        .restore(1)
        .step(20)
        .logging(False)
    )
    # a script that moves, traces and changes the sample time while the host steps and records
    out["script-moves-and-sample-time"] = (
        Seq(fmi3=True)
        .script(
            [
                (0, 0, "SetBufferLength", 0, 32),
                (0, 0, "SetTraceVariable", 0, 0, 8),
                (0, 0, "SetTraceStart", 0, 1, 0, 0),
                (3, 0, "SetVelocity", 0x30000),
                (0, 0, "SetProfileMode", 1),
                (0, 0, "Update"),
                (20, 0, "SetSampleTime", 7),
                (40, 0, "SetSampleTime", 100),
            ],
            capacity=1000,
            record=True,
        )
        .step(30)
        .step(50)
        .record(False)
        .step(1)
        .replay(100, 3)
    )
    # commands and memory writes in initialization mode, then memorySize changes (keeping the registers)
    out["initialization-mode-commands-then-memory-size"] = (
        Seq(fmi3=True)
        .enter_initialization(start=1, start_in_cycles=True)
        .buffer(2, 0x10, 8, function=0)
        .memory("write", 0x10, 8, 3)
        .parameter("memorySize", 0x18)
        .parameter("memorySize", 0x17)
        .parameter("memorySize", 0x8000)
        .parameter("cycleTime", 2.5e-5)
        .parameter("badCycleTime", 1)
        .memory("write", 0x7FF0, 16, 9, pending=True)
        .parameter("memorySize", 0x7FF8)
        .step(1)
        .exit_initialization()
        .move(4, 0, 0, 0)
        .step(20)
        .replay(5)
    )
    # an axis whose position error trips auto stop, settles, meets a limit
    out["auto-stop-settle-limit"] = (
        Seq()
        .reinitialize(loopback=False)
        .axis_setup(10, 5, 2, 3, 0, 0xFFFF, auto_stop=True, settled_complete=True)
        .move(0, 100000, 0x20000, 0x1000)
        .step(3)
        .input(0, "actualPosition", 1000)
        .step(10)
        .command("ResetEventStatus", 0)
        .command("SetMotorMode", 1)
        .move(0, 0, 0x20000, 0x1000)
        .step(5)
        .input(0, "actualPosition", 5)
        .step(40)
        .input(0, "negativeLimit", True)
        .step(2)
        .move(0, -100, 0x10000, 0x1000)
        .refused(9)
        .refused(10)
        .replay(4)
    )
    # record.columns as users set them: valid lists (blanks around names), "", refused names, two values in
    # one call, too many columns; recording steps in between, record.data read after each, FMI 2 and 3
    wide = [
        "axis1.position",
        "axis1.velocity",
        "axis1.acceleration",
        "axis1.motorOutput",
        "nextCycleTime",
        "axis2.activityStatus",
        "io.output[3]",
        "host.interrupt",
    ]
    for fmi3 in (False, True):
        out[f"record-columns-set-refused-and-read-fmi{3 if fmi3 else 2}"] = (
            Seq(fmi3=fmi3)
            .reinitialize(capacity=500, record=True)
            .move(1, 0, 0x30000, 0x1000, axis=1)
            .columns("valid", ["axis2.commandedPosition", ("axis2.velocity", True, True), "host.interrupt"])
            .step(40)
            .record_data()
            .columns("bad", ["axis1.commandedPosition", "axis1.velocity"], (1, 1))
            .record_data()
            .columns("two", ["axis1.motorCommand"], wide)
            .step(30)
            .record_data()
            .columns("two", wide, ("bad", ["axis1.position"], 0, 8))
            .columns("many")
            .step(3)
            .record_data()
            .columns("empty")
            .sample_time(20, pending=True)
            .step(10)
            .record_data()
            .columns("valid", wide)
            .save(0)
            .step(5)
            .restore(0)
            .record_data()
            .step(7)
            .replay(4, 2)
        )
    # lent memory (FMI 2, and FMI 3's pmdfmu_fmi3SetRecordBuffer): lent while recording, columns widened while
    # lent, the grid made finer, a state saved and restored while lent, memory too small (refused), misaligned
    # (default rows), 0 bytes, NULL, then lent again and forgotten by a reset
    for fmi3 in (False, True):
        out["record-buffer-lent-widened-restored-reset" + ("-fmi3" if fmi3 else "")] = lent_sequence(fmi3, wide)

    # memory.data as a block: FMI 2 runs from any element, past memory.data[64], split, with an element
    # twice, after memory.count or memory.address; FMI 3 the array, after memory.address, twice, a wrong
    # nValues; a write of the block's words after each
    s = Seq().memory_block(0, 64, 7).memory_block(5, 10, 9).memory_block(60, 5, 1).memory_block(63, 1, 3)
    s.memory_block(40, 30, 5, gap=True).memory_block(3, 20, 6, again=True).memory_block(
        0, 64, 8, prefix="count", prefix_value=64
    )
    s.memory_block(0, 16, 2, prefix="address", prefix_value=0x100, check=False).memory("strobe").step(1)
    s.memory_block(10, 12, 4, gap=True, again=True).memory("write", 0x200, 64, 11).step(1)
    out["memory-data-blocks-fmi2"] = s
    # a machine: axis 1 closes its loop through the motor (a lighter one, a coarser integration), axis 2
    # meets its home switch, index pulses and limits, both moving; a state saved and replayed mid-move
    gains = [("SetKp", 100), ("SetKd", 4000), ("SetDerivativeTime", 4), ("SetKvff", 164), ("SetKaff", 32768)]
    for fmi3 in (False, True):
        s = Seq(fmi3=fmi3).machine(
            [
                {"servo_plant": True, "plant": [("loadInertia", "7.2e-6"), ("internalStep", "2e-6")]},
                {
                    "home": (1000, 500),
                    "positive_limit": 30000,
                    "negative_limit": -30000,
                    "index": [0, 2000, -7],
                    "signal_sense": 0x08,
                },
            ],
            loopback=fmi3,
        )
        for name, value in gains:
            s.command(name, value)
        s.command("Update").command("SetMotorMode", 1)
        s.move(0, 5000, 0x50000, 0x1000).move(1, 0, 0x80000, 0x2000, axis=1).step(300)
        s.save().step(1200).replay(100, 2.5, ("fraction", 7)).restore(via_bytes=True).step(40)
        out[f"machine-plant-and-switches-fmi{3 if fmi3 else 2}"] = s
    out["memory-data-blocks-fmi3"] = (
        Seq(fmi3=True)
        .memory_block(fmi3_kind="array", seed=7)
        .memory_block(fmi3_kind="twice", seed=9)
        .memory_block(fmi3_kind="address", seed=2, prefix_value=0x80)
        .memory_block(fmi3_kind="count", seed=3)
        .memory_block(fmi3_kind="count", more=True, seed=4)
        .memory("strobe")
        .step(2)
        .memory_block(fmi3_kind="array", seed=5, check=False)
        .memory("write", ("M-", 64), 64, 1)
        .step(1)
    )
    return out


# ---- regressions: the legal-call bugs an attack found ---------------------------------------


def regressions():
    out = {}
    # 1. A trace armed to start on the next Update (buffer 0 of length 1, rolling), then buffer 0
    #    set to length 0 and moved to the end of the memory (accepted: the trace only waits), then
    #    Update: the trace's first sample was written at address 0x4000, past the memory.
    out["trace-start-after-buffer0-moved-past-memory"] = (
        Seq()
        .trace(0, 1, [(0, 2)], 1, 1, (0, 1, 0, 0))
        .buffer(0, "M", 0, length_first=True)
        .command("Update")
        .step(1)
        .step(3)
    )
    # 2. FMI 3, record.capacity 100, recording; a host batch SetSampleTime(1) left pending; one doStep
    #    of 100 cycles at the old cycle time: the grid restarted inside the step, which ran 10 000
    #    cycles and wrote them past record.data.
    out["recording-step-across-sample-time-change"] = (
        Seq(fmi3=True)
        .reinitialize(capacity=100, record=True)
        .move(1, 0, 0x10000, 0)
        .sample_time(1, pending=True)
        .step(100)
        .step(1)
    )
    #    The same through a script: SetSampleTime(1) at cycle 0 of a 100-cycle recording step.
    out["recording-step-across-script-sample-time"] = (
        Seq(fmi3=True)
        .script(
            [(0, 0, "SetSampleTime", 1), (5, 1, "SetVelocity", 0x10000), (0, 1, "SetProfileMode", 1), (0, 1, "Update")],
            capacity=100,
            record=True,
        )
        .step(100)
        .step(1)
    )
    # 3. A valid 64-word memory write pending, then memory.address set to 0x3FF0 (the write would
    #    leave the memory): refused, yet the new address stayed (and the pending write was dropped).
    out["refused-memory-address-keeps-pending-write"] = (
        Seq().memory("write", 0, 64, 1, pending=True).memory("address", ("M-", 16)).step(1)
    )
    out["refused-memory-address-keeps-pending-write-fmi3"] = (
        Seq(fmi3=True).memory("write", 0, 64, 1, pending=True).memory("address", ("M-", 16)).step(1)
    )
    # 4. cycleTime 0.065535, SetSampleTime(1) pending, doStep(t, 2^52 * 0.065535): accepted on the old
    #    grid, the new one's cycle index overflowed a float-to-int conversion.
    out["huge-step-after-pending-sample-time"] = (
        Seq().reinitialize(cycle_time=0.065535).sample_time(1, pending=True).step(("huge", 52)).step(1)
    )
    # 5. (found by this fuzzer) A state the FMU saved itself is refused on restore. A one-time trace
    #    fills buffer 0 (length 1) and stops; buffer 0 is then set to length 0 (allowed: no trace
    #    runs); GetFMUState, SetFMUState: "chip.s.trace.count = 1 is more than trace buffer 0 holds".
    out["restore-refuses-trace-count-after-buffer0-shrinks"] = (
        Seq().trace(0x100, 1, [(0, 2)], 0, 1, (0, 0, 0, 0)).step(3).buffer(0, 0x100, 0, length_first=True).replay(1)
    )
    #    The same with the countdown: a trace of period 6 samples once (countdown 5), is stopped, and
    #    the period set to 5: "chip.s.trace.countdown = 5 is not below the period 5".
    out["restore-refuses-trace-countdown-after-period-shrinks"] = (
        Seq()
        .trace(0x100, 8, [(0, 2)], 1, 6, (0, 0, 0, 0))
        .step(1)
        .command("SetTraceStop", 0, 0, 0, 0)
        .command("SetTracePeriod", 5)
        .replay(1)
    )
    # 6. (found by this fuzzer) SetFMUState does not restore record.data's row count (recordCount,
    #    part of the serialized state): after save, restore, the state differs from the saved one
    #    and, in FMI 3, record.data is empty where it held the last step's rows.
    out["restore-resets-record-count"] = (
        Seq(fmi3=True).reinitialize(capacity=1, record=True).step(1).replay("capacity+1")
    )
    # 7. (found by this fuzzer) The FMU state holds uninitialized bytes: pmd_update copies its local
    #    PmdSCurve plan, padding and all, into the axis (profile.c, ax->scurve = plan), so an S-curve
    #    Update executed in a step leaves different state bytes in a run and in its replay.
    out["scurve-update-copies-uninitialized-padding-into-the-state"] = (
        Seq().move(2, 1000, 0x10000, 0x100, 0, jerk=0x1000, pending=True).replay(1)
    )
    # 8. (found by this fuzzer) A state the FMU saved is refused on restore: an S-curve Update to the
    #    current position with jerk 0: "chip.s.axis[0].scurve: step 0, p6 0, v2 0 or a 0 is not on
    #    the unit curve".
    out["restore-refuses-zero-distance-scurve"] = Seq().move(2, 0, 0x4000, 1, 0, jerk=0).replay(1)
    # 9. (found by this fuzzer) A state the FMU saved is refused on restore: initialization at a
    #    negative start time (legal: -1 s) leaves time before the grid's anchor (0), which the state
    #    check refuses: "time -1 is not within 2^53 cycles after anchorTime 0".
    out["restore-refuses-negative-start-time"] = Seq().reinitialize(start=-1).replay(1)
    # The other findings of that attack, so that the fuzzer starts from each of them:
    # 4b. A memory write leaving the memory asked for by the strobe alone: refused, the old strobe stays.
    out["refused-memory-strobe-keeps-its-value"] = (
        Seq().memory("address", ("M-", 16)).memory("count", 0, 64).memory("strobe").step(1)
    )
    # 4c. In initialization mode, a write pending at 0x1000 and memorySize 0x800: refused, nothing reset.
    out["refused-memory-size-in-initialization-keeps-everything"] = (
        Seq()
        .enter_initialization()
        .memory("write", 0x1000, 8, 1, pending=True)
        .parameter("memorySize", 0x800)
        .exit_initialization()
        .step(1)
    )
    # 9. memorySize set to its own value in initialization (used to wipe memory and registers), and a
    #    cycle time the sample time register cannot hold (refused, not rounded).
    out["memory-size-set-to-itself-keeps-everything"] = (
        Seq()
        .enter_initialization()
        .command("SetPosition", 1234)
        .buffer(2, 0x10, 8, function=0)
        .parameter("memorySize", 0x4000)
        .parameter("badCycleTime", 0)
        .exit_initialization()
        .replay(1)
    )
    # 7. Legal extremes: acceleration 0x7FFFFFFF for 11 500 cycles (the 64-bit state wrapped at 10 923),
    #    and a gear of ratio 0x40000000 behind a master jumping 65536 counts (signed overflow).
    out["external-segment-at-full-acceleration"] = (
        Seq()
        .external_profile(0x200, [{0: 0, 2: 0x7FFFFFFF, 4: 11500}, {4: 0}], functions=(0, 2, 4))
        .step(11500)
        .step(2)
    )
    out["gear-behind-a-jumping-master"] = (
        Seq()
        .move(3, 0, 0, 0, gear=(1, 0x40000000, 1))
        .external_profile(0x200, [{0: 0, 4: 2}, {0: 65536, 4: 2}, {4: 0}], axis=1)
        .step(8)
    )
    # 10. A get refused for an unknown value reference while a batch is pending executes nothing.
    out["refused-get-keeps-the-pending-batch"] = Seq().command("SetPosition", 99, pending=True).refused(0).step(1)
    # 11. cycleTime 65.535 ms, record.capacity N, recording, SetSampleTime(1) pending, a doStep of N cycles:
    #    it passed the capacity check and ran N * 65 535 cycles of 1 us, those past the N rows kept one by
    #    one (N = 100 000: 6.6 * 10^9 cycles, hours) where an unrecorded step fast-forwards them.
    out["recording-coarse-step-made-finer-past-capacity"] = (
        Seq()
        .reinitialize(cycle_time=0.065535, capacity=100_000, record=True)
        .sample_time(1, pending=True)
        .step("capacity")
        .record_data()
        .step(1)
    )
    out["recording-coarse-step-made-finer-past-capacity-columns-fmi3"] = (
        Seq(fmi3=True)
        .reinitialize(cycle_time=0.065535, capacity=100_000, record=True)
        .columns("valid", ["axis1.commandedPosition", "host.interrupt"])
        .sample_time(1, pending=True)
        .step("capacity")
        .record_data()
        .step(1)
    )
    #    The same with FMI 2's lent memory as the limit: 6552 rows of 5 bytes lent, a step of 6552 cycles.
    out["recording-coarse-step-made-finer-past-lent-memory"] = (
        Seq()
        .reinitialize(cycle_time=0.065535, record=True)
        .columns("valid", ["loopback"])
        .lend("bytes", 6552 * 5)
        .sample_time(1, pending=True)
        .step(6552)
        .record_data()
        .step(1)
    )
    # 12. (found by this fuzzer's columns) In initialization mode, record.enabled set, then record.capacity 0:
    #    a valid record.columns was refused ("record.enabled: record.capacity is 0"), the buffer sized as if
    #    a step recorded now.
    for fmi3 in (False, True):
        out[f"record-columns-in-initialization-with-capacity-0{'-fmi3' if fmi3 else ''}"] = (
            Seq(fmi3=fmi3)
            .enter_initialization()
            .record(True)
            .parameter("record.capacity", 0)
            .columns("valid", ["loopback", "axis1.commandedPosition"])
            .parameter("record.capacity", 10)
            .exit_initialization()
            .step(10)
            .record_data()
        )
    # 13. (found by this fuzzer in CI) The same set-up, then an FMU state taken in initialization mode and
    #    restored: the restore was refused ("record.capacity is 0"), the buffer sized as if it were step mode.
    for fmi3 in (False, True):
        out[f"restore-in-initialization-with-capacity-0{'-fmi3' if fmi3 else ''}"] = (
            Seq(fmi3=fmi3)
            .enter_initialization()
            .record(True)
            .parameter("record.capacity", 0)
            .replay(1)
            .replay(1, via_bytes=True)
            .parameter("record.capacity", 10)
            .exit_initialization()
            .step(10)
            .record_data()
        )
    # 14. (found by this fuzzer) Under a machine with a home switch and limits on axis 1, setting axis1.home
    #    or a limit is refused (the machine drives them every cycle); axis 2's, which it leaves alone, is set.
    out["machine-driven-inputs-are-refused"] = (
        Seq()
        .machine([{"home": (100, 100), "positive_limit": 5000, "negative_limit": -5000}])
        .input(0, "home", True)
        .input(0, "positiveLimit", True)
        .input(0, "negativeLimit", True)
        .input(1, "home", True)
        .step(10)
    )
    return out


# ---- script regressions: the file findings of that attack (fuzz_script.c: the first half of an
# input is the script, the second half the table t.csv it may load) --------------------------


def script_input(script: str, table: str = "") -> bytes:
    body, rest = script.encode(), table.encode()
    pad = max(len(body), len(rest))
    return body.ljust(pad, b"\n") + rest.ljust(pad, b"\n")


def script_regressions():
    load = '@0\nLoadSegmentTable(Axis1, "t.csv", 0x200, 2);\n'
    return {
        "table-comment-longer-than-a-line": script_input(load, "# " + "x" * 5000 + "\nposition,time\n1,2\n"),
        "table-with-17-columns": script_input(load, "position," * 16 + "time\n" + "1," * 16 + "1\n"),
        "table-column-named-twice": script_input(load, "position,time,position\n1,2,3\n"),
        "hex-with-a-blank": script_input("@0\nSetPosition(Axis1, 0x 5);\n"),
        "hex-with-a-sign": script_input("@0\nSetPosition(Axis1, 0x+7);\n"),
        "nul-in-a-script-line": script_input("@0\nSetPosition(Axis1,\0 5);\n"),
    }


def main():
    for folder, target, inputs in (
        ("corpus", "sequence", seeds()),
        ("regressions", "sequence", regressions()),
        ("regressions", "script", script_regressions()),
    ):
        d = HERE / folder / target
        d.mkdir(parents=True, exist_ok=True)
        for name, data in inputs.items():
            data = data if isinstance(data, bytes) else data.bytes()
            (d / name).write_bytes(data)
            print(f"{d.relative_to(HERE.parent)}/{name}: {len(data)} bytes")


if __name__ == "__main__":
    main()
