# SPDX-License-Identifier: BSD-2-Clause
"""Upload: write_memory's strobes run in C (native/memory_port.c)
and leave the FMU exactly as the harness's Python loop did (stepwise.write_memory_stepwise,
kept as the reference): the same FMU state byte for byte (memory, the port's
variables), the same messages, and where an FMI call is refused part-way the same
blocks written and the same exception. The segment-table loader reads a row of
plain integers in place and any other row cell by cell: both readings store the
same words."""

import ctypes

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import FMUError
from states import snapshot
from stepwise import write_memory_stepwise

VERSIONS = pytest.mark.parametrize("version", [2, 3])
SIZE = 0x400  # memorySize of the chips below


def pair(version):
    """Two chips alike: one written the native way, one the Python way."""
    return pmdfmu.Chip(version, memorySize=SIZE), pmdfmu.Chip(version, memorySize=SIZE)


def memory(chip) -> np.ndarray:
    """The chip's memory words: the serialized FMU state ends with them."""
    return np.frombuffer(snapshot(chip)[-4 * chip.get("memorySize") :], dtype=np.uint32)


def words(n, seed):
    rng = np.random.default_rng(seed)
    return rng.integers(0, 2**32, n, dtype=np.uint64).astype(np.uint32)


@VERSIONS
@pytest.mark.parametrize("n", [0, 1, 63, 64, 65, 129, SIZE - 0x100])
def test_native_and_python_writes_leave_the_same_fmu_state(version, n):
    native, python = pair(version)
    with native, python:
        for k, (address, kind) in enumerate([(0x100, np.uint32), (SIZE - n, np.int64), (0, list)]):
            data = words(n, seed=k)
            given = [int(w) - (1 << 32) if w >> 31 else int(w) for w in data] if kind is list else data.astype(kind)
            native.write_memory(address, given)
            write_memory_stepwise(python, address, given)
            assert snapshot(native) == snapshot(python)
            assert np.array_equal(memory(native)[address : address + n], data)
        assert native.messages == python.messages
        assert native.get("memory.strobe") == python.get("memory.strobe") == (0 if n == 0 else 3 * (-(-n // 64)))


@VERSIONS
def test_the_strobe_wraps_at_2_to_the_31_as_before(version):
    native, python = pair(version)
    with native, python:
        for chip in (native, python):
            chip.set_state(chip.get_state())  # the same start for both
        start = snapshot(native)
        assert start == snapshot(python)
        data = words(200, seed=7)
        native.write_memory(5, data)
        write_memory_stepwise(python, 5, data)
        assert snapshot(native) == snapshot(python)


class FailingCall:
    """One of the FMU's FMI functions, refusing (fmi2Error / fmi3Error, 3) its `fail`-th call of a
    strobe (a get: of host.ack) and passing every call on otherwise; put where FMPy and the native
    loop both take it from."""

    def __init__(self, fmu, name, fail, prototype, ack):
        self.real, self.count, self.fail, self.ack = fmu._functions[name], 0, fail, ack if "Get" in name else None
        self.function = prototype(self.call)
        self.function.restype = ctypes.c_int  # what FMPy's check looks at
        self.function.argtypes = prototype._argtypes_

    def call(self, *args):
        if self.ack is None or args[1][0] == self.ack:
            self.count += 1
            if self.count == self.fail:
                return 3
        return self.real(*args)


PROTOTYPES = {
    "fmi2SetInteger": ctypes.CFUNCTYPE(
        ctypes.c_int, ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint), ctypes.c_size_t, ctypes.POINTER(ctypes.c_int)
    ),
    "fmi2GetInteger": ctypes.CFUNCTYPE(
        ctypes.c_int, ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint), ctypes.c_size_t, ctypes.POINTER(ctypes.c_int)
    ),
    "fmi3SetUInt32": ctypes.CFUNCTYPE(
        ctypes.c_int,
        ctypes.c_void_p,
        ctypes.POINTER(ctypes.c_uint),
        ctypes.c_size_t,
        ctypes.POINTER(ctypes.c_uint32),
        ctypes.c_size_t,
    ),
    "fmi3SetInt32": ctypes.CFUNCTYPE(
        ctypes.c_int,
        ctypes.c_void_p,
        ctypes.POINTER(ctypes.c_uint),
        ctypes.c_size_t,
        ctypes.POINTER(ctypes.c_int32),
        ctypes.c_size_t,
    ),
    "fmi3GetInt32": ctypes.CFUNCTYPE(
        ctypes.c_int,
        ctypes.c_void_p,
        ctypes.POINTER(ctypes.c_uint),
        ctypes.c_size_t,
        ctypes.POINTER(ctypes.c_int32),
        ctypes.c_size_t,
    ),
}


@pytest.mark.parametrize(
    "name,fail",
    [
        ("fmi2SetInteger", 1),
        ("fmi2SetInteger", 3),
        ("fmi2GetInteger", 4),
        ("fmi3SetUInt32", 2),
        ("fmi3SetInt32", 3),
        ("fmi3GetInt32", 4),
    ],
)
def test_a_call_refused_part_way_leaves_what_the_python_loop_left_and_raises_the_same(monkeypatch, name, fail):
    """The FMU refuses the `fail`-th call of `name` during a write of 5 blocks: the blocks before it
    are written, none after (a refused fmi3SetInt32 leaves its block's data and address set)."""
    version = int(name[3])
    native, python = pair(version)
    with native, python:
        data = words(300, seed=3)
        raised = []
        for chip, write in ((native, native.write_memory), (python, lambda a, w: write_memory_stepwise(python, a, w))):
            failing = FailingCall(chip.fmu, name, fail, PROTOTYPES[name], chip.variables["host.ack"].valueReference)
            with monkeypatch.context() as m:
                m.setitem(chip.fmu._functions, name, failing.function)
                with pytest.raises(FMICallException) as info:
                    write(0x10, data)
            raised.append((type(info.value), str(info.value), info.value.status))
            chip.messages.clear()
        assert raised[0] == raised[1] and raised[0][2] == 3
        assert snapshot(native) == snapshot(python)


@VERSIONS
def test_a_write_the_fmu_refuses_raises_the_fmi_error_and_writes_nothing(version):
    """A terminated instance refuses the port's set: the Python loop's exception, no word written."""
    native, python = pair(version)
    with native, python:
        raised = []
        for chip, write in ((native, native.write_memory), (python, lambda a, w: write_memory_stepwise(python, a, w))):
            chip.fmu.terminate()
            with pytest.raises(FMICallException) as info:
                write(0, [1, 2, 3])
            raised.append((str(info.value), info.value.status))
            chip.fmu.freeInstance()  # close() would terminate it again
            chip.fmu = None
        assert raised[0] == raised[1]
        assert native.messages == python.messages


@VERSIONS
def test_bad_words_and_addresses_are_refused_before_anything_is_written(version):
    with pmdfmu.Chip(version, memorySize=SIZE) as chip:
        before = snapshot(chip)
        for call, message in [
            (
                lambda: chip.write_memory(0, np.array([1, 2**32], dtype=np.int64)),
                r"write_memory: words\[1\] = 4294967296",
            ),
            (
                lambda: chip.write_memory(SIZE - 64, np.zeros(65, dtype=np.uint32)),
                f"write_memory: 65 words at address {SIZE - 64} leave the {SIZE}-word memory",
            ),
            (lambda: chip.write_memory(-1, np.zeros(1, dtype=np.int32)), "address -1"),
        ]:
            with pytest.raises(ValueError, match=message):
                call()
            assert snapshot(chip) == before
        chip.write_memory(SIZE - 64, np.arange(64, dtype=np.int32))  # a block that ends at memorySize
        assert np.array_equal(memory(chip)[-64:], np.arange(64))


# ---- the segment-table loader: a row in place, or cell by cell ----


def loaded(tmp_path, version, text, size=0x1000):
    """The table's words as LoadSegmentTable leaves them in memory at 0x100, column after column."""
    (tmp_path / "t.csv").write_text(text)
    script = tmp_path / "s.script"
    script.write_text('LoadSegmentTable(Axis1, "t.csv", 0x100, 2)\n')
    with pmdfmu.Chip(version, memorySize=size, script=script) as chip:
        chip.run(1)
        return memory(chip)[0x100:]


EDGE = [
    "0",
    "-0",
    "+7",
    "  12  ",
    "\t-5\t",
    "007",
    "999999999",
    "2147483647",
    "-2147483648",
    "4294967295",
    "123456789012",
    "000000000000000001",
]


@VERSIONS
@pytest.mark.parametrize("units", ["raw", "counts/cycle"])
def test_rows_read_in_place_store_what_the_cell_by_cell_reading_stores(tmp_path, version, units):
    """Each row twice: plain integers (read in place), and with its position written in hex (which
    sends the row to the cell-by-cell reading); every other column must hold the same words. Cells
    that fit no column (12 digits) or no 16.16 value send both rows to the cell-by-cell reading,
    whose refusal the test then expects in both."""
    cells = {"raw": EDGE[:10], "counts/cycle": ["0", "-0", "+7", " 32767 ", "-32768", "\t1\t", "007"]}[units]
    rows = []
    for k, cell in enumerate(cells):
        velocity, acceleration = cell, cells[(k + 3) % len(cells)]
        time = cell if units == "raw" and not cell.strip().startswith("-") else str(k + 1)
        rows.append((k, velocity, acceleration, "0", time))
    plain = "".join(f"{k},{v},{a},{j},{t}\n" for k, v, a, j, t in rows)
    hexed = "".join(f"0x{k:X},{v},{a},{j},{t}\n" for k, v, a, j, t in rows)
    header = f"# units: {units}\nposition,velocity,acceleration,jerk,time\n"
    a, b = loaded(tmp_path, version, header + plain), loaded(tmp_path, version, header + hexed)
    n = len(rows)
    assert np.array_equal(a[: 5 * n], b[: 5 * n])
    assert list(a[:n]) == list(range(n))
    scale = 16 if units == "counts/cycle" else 0
    assert [int(w) for w in a[n : 2 * n]] == [(int(r[1]) << scale) & 0xFFFFFFFF for r in rows]


BAD_ROWS = {
    "19 digits": ("1234567890123456789", "t.csv:3: '1234567890123456789' is not a number (at most 18 digits)"),
    "33 bits": ("4294967296", "t.csv:3: position 4294967296 does not fit 32 bits"),
    "below -2^31": ("-2147483649", "t.csv:3: position -2147483649 does not fit 32 bits"),
    "a blank inside": ("1 2", "t.csv:3: '1 2' is not a number"),
    "a sign alone": ("-", "t.csv:3: '-' is not a number"),
}


@VERSIONS
@pytest.mark.parametrize("case", BAD_ROWS)
def test_a_row_the_in_place_reading_leaves_is_refused_as_before(tmp_path, version, case):
    cell, expected = BAD_ROWS[case]
    (tmp_path / "t.csv").write_text(f"position,time\n1,1\n{cell},1\n")
    script = tmp_path / "s.script"
    script.write_text('LoadSegmentTable(Axis1, "t.csv", 0x100, 2)\n')
    with pytest.raises(FMUError, match="script refused") as info:
        pmdfmu.Chip(version, script=script)
    assert expected in str(info.value)


@VERSIONS
def test_a_time_column_refuses_a_negative_time_and_counts_cycle_a_16_16_overflow(tmp_path, version):
    for table, expected in [
        ("position,time\n1,-1\n", "t.csv:2: time -1 does not fit 32 bits"),
        ("# units: counts/cycle\nposition,velocity\n1,32768\n", "t.csv:3: '32768' does not fit a 16.16 value"),
    ]:
        (tmp_path / "t.csv").write_text(table)
        script = tmp_path / "s.script"
        script.write_text('LoadSegmentTable(Axis1, "t.csv", 0x100, 2)\n')
        with pytest.raises(FMUError, match="script refused") as info:
            pmdfmu.Chip(version, script=script)
        assert expected in str(info.value)
