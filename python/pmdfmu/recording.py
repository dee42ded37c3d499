# SPDX-License-Identifier: BSD-2-Clause
"""How Chip.run(cycles, record=names) records (docs/performance.md, "Recording"):
a Recorder, made per run by Chip.run (Chip.recorder: the class, another one for
a test's oracle).

In bulk, the FMU's way: the FMU writes each cycle's row into record.data itself
(record.columns names the columns), one doStep and one read per record.capacity
cycles (per COPIED_CHUNK_BYTES of rows where they are copied); the harness has the
FMU write the rows straight into the result, lent for one doStep inside one native
call (`lent_stepper`: the FMU's extension pmdfmu_fmi2SetRecordBuffer or
pmdfmu_fmi3SetRecordBuffer), or copies them out of record.data (`record_data`:
fmi3GetBinary, FMI 2's extension pmdfmu_fmi2GetRecordData).

Cycle by cycle in the harness's native library (native/record_loop.c), for an FMU
without bulk recording of the columns (an older build) or a run that records
`time`: per cycle one doStep to the next cycle of the FMU's grid and one get per
FMI type, through the FMU's own FMI functions, with the arguments a Python loop
over FMPy passes (tests/stepwise.py, the reference)."""

from __future__ import annotations

import struct
from ctypes import POINTER, byref, c_char, c_double, c_int, c_size_t, c_uint32, c_void_p
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
from fmpy.fmi1 import FMICallException

from . import native

# record.data's default row after the chip time: the commanded outputs (Chip.run records them fastest)
RECORDED = [
    f"axis{n}.{q}" for n in range(1, 5) for q in ("commandedPosition", "commandedVelocity", "commandedAcceleration")
]

# the C type of a getter's values (native.py's PmdLoopType), by the FMU's type (FMI 2 and FMI 3 names), and
# a row's numpy type of each
SOURCE = {
    2: {"Real": native.DOUBLE, "Integer": native.INT32, "Boolean": native.INT},
    3: {
        "Float64": native.DOUBLE,
        "Int32": native.INT32,
        "UInt32": native.UINT32,
        "UInt16": native.UINT16,
        "Int16": native.INT16,
        "Boolean": native.BOOL,
    },
}
CTYPE = {
    native.DOUBLE: np.float64,
    native.INT32: np.int32,
    native.UINT32: np.uint32,
    native.UINT16: np.uint16,
    native.INT16: np.int16,
    native.INT: np.intc,
    native.BOOL: np.bool_,
}
GRID = ("time", "nextCycleTime", "activeCycleTime")
# the rows of a chunk the harness copies out of record.data: at most this many bytes, so that they are still in the
# core's L2 cache when the copy reads them (docs/performance.md, "Recording"); rows lent to the FMU are not copied
COPIED_CHUNK_BYTES = 1 << 20


def _function(fmu, name: str):
    """The ctypes function of the FMU's FMI function `name` that FMPy's own wrapper calls."""
    return fmu._functions[name]


class Plan:
    """What run(record=names) reads each cycle: one get per FMI type in the harness's order (its
    getters'), each of its variables once (an FMI 3 array whole), the grid (time, nextCycleTime,
    activeCycleTime) first among the Reals, the chip time among its type's; and where each row field
    comes from. Built once per run call; holds the buffers the native loop uses."""

    def __init__(self, chip, where: Dict[str, Tuple[str, int]], dtype: np.dtype):
        version = chip.fmi_version
        self.version = version
        variables = chip.variables
        wanted = [("cycle", ("chipTime", 0))] + list(where.items())
        real = "Real" if version == 2 else "Float64"
        self.names: List[str] = []
        self._keep = []
        groups, columns = [], []
        for t in chip._getters:
            fields = [(f, w) for f, w in wanted if variables[w[0]].type == t]
            read = ([*GRID] if t == real else []) + [w[0] for _f, w in fields]
            if not fields and t != real:
                continue
            read = list(dict.fromkeys(read))
            sizes = [chip._size(r) if version == 3 else 1 for r in read]
            offsets = np.cumsum([0] + sizes)
            vrs = (c_uint32 * len(read))(*[chip._vr[r] for r in read])
            values = np.zeros(int(offsets[-1]), dtype=CTYPE[SOURCE[version][t]])
            self._keep += [vrs, values]
            name = f"fmi{version}Get{t}"
            if t == real:
                self.grid_group = len(groups)
            for f, (var, element) in fields:
                # the field's bytes: a float64 of a Real; the low bytes of an integer as wide or wider (the
                # Python loop's masks: FMI 2 reads UInt32 and UInt16 as signed Integers); a bool of a bool,
                # or of an fmi2Boolean (an int: the field is value != 0)
                field_type, offset = dtype.fields[f][:2]
                source = values.ctypes.data + values.itemsize * (int(offsets[read.index(var)]) + element)
                columns.append(
                    native.Column(
                        source, offset, field_type.itemsize, int(values.dtype != field_type and field_type.kind == "b")
                    )
                )
            groups.append(
                native.Group(
                    native.address(_function(chip.fmu, name)),
                    vrs,
                    len(read),
                    int(offsets[-1]),
                    SOURCE[version][t],
                    values.ctypes.data,
                )
            )
            self.names.append(name)
        self.groups = (native.Group * len(groups))(*groups)
        self.columns = (native.Column * len(columns))(*columns)
        self.do_step = f"fmi{version}DoStep"


def record(chip, plan: Plan, out: np.ndarray) -> None:
    """Runs len(out) cycles, each one's row into out; raises as FMPy would for a call that failed
    (FMICallException naming it: the FMU's messages are in chip.messages), the rows before it lost
    with the array, as in the Python loop."""
    lib = native.library()
    fn = lib.pmd_record_fmi2 if plan.version == 2 else lib.pmd_record_fmi3
    fn.restype = c_int
    fn.argtypes = [
        c_void_p,
        c_void_p,
        POINTER(native.Group),
        c_size_t,
        c_size_t,
        c_size_t,
        POINTER(native.Column),
        c_size_t,
        c_void_p,
        c_size_t,
        c_size_t,
        POINTER(native.Stop),
    ]
    stop = native.Stop()
    if fn(
        native.address(_function(chip.fmu, plan.do_step)),
        chip.fmu.component,
        plan.groups,
        len(plan.groups),
        plan.grid_group,
        0,
        plan.columns,
        len(plan.columns),
        out.ctypes.data,
        out.dtype.itemsize,
        len(out),
        stop,
    ):
        if stop.call == native.LOOP_FIELD_SIZE:
            raise ValueError(f"run: a row field of {out.dtype} is not 1, 2, 4 or 8 bytes wide")
        raise FMICallException(function=plan.do_step if stop.call < 0 else plan.names[stop.call], status=stop.status)


def extension(chip, name: str, argtypes: list):
    """The FMU's function `name` beside the FMI ones (returning an fmi2Status), or None where the
    FMU has none (an older build): looked up once per FMU file, in the library its Chips share (an
    instance's own lookup costs ~10 us, as long as 200 recorded cycles)."""
    if name not in chip._extensions:
        function = getattr(chip._library, name, None)
        if function is not None:
            function.restype, function.argtypes = c_int, argtypes
        chip._extensions[name] = function
    return chip._extensions[name]


def record_data(chip) -> Optional[Callable[[], Tuple[int, int]]]:
    """A function returning where record.data's rows lie after a doStep, (address, size in bytes), in the
    FMU's own buffer (valid until its next call), or None: an FMI 2 FMU without pmdfmu_fmi2GetRecordData (an older
    build)."""
    if chip.fmi_version == 3:
        from fmpy.fmi3 import fmi3Binary, fmi3ValueReference

        vrs, size, value = (fmi3ValueReference * 1)(chip._vr["record.data"]), (c_size_t * 1)(), (fmi3Binary * 1)()

        def read3() -> Tuple[int, int]:
            chip.fmu.fmi3GetBinary(chip.fmu.component, vrs, 1, size, value, 1)
            return c_void_p.from_buffer(value).value or 0, size[0]

        return read3
    get = extension(chip, "pmdfmu_fmi2GetRecordData", [c_void_p, POINTER(c_void_p), POINTER(c_size_t)])
    if get is None:
        return None
    data, nbytes = c_void_p(), c_size_t()

    def read2() -> Tuple[int, int]:
        status = get(chip.fmu.component, byref(data), byref(nbytes))
        if status > 1:  # as FMPy raises for an FMI function
            raise FMICallException(function="pmdfmu_fmi2GetRecordData", status=status)
        return data.value or 0, nbytes.value

    return read2


def lent_stepper(chip) -> Optional[Callable[[int, int, float, float], Tuple[int, int]]]:
    """A function running one recording doStep (from `now`, of `step` s) into (address, size in bytes) of the
    caller's memory, returning (doStep's status, the bytes of rows recorded there): the memory is lent
    (pmdfmu_fmi2SetRecordBuffer, pmdfmu_fmi3SetRecordBuffer), the step run and the loan ended in one native
    call (native pmd_record_step_lent), so no Python code, a KeyboardInterrupt included, runs while the FMU
    holds a pointer into the caller's memory. Spares the copy of record.data into the result. None where
    the FMU has no such function (an older build)."""
    version = chip.fmi_version
    lend = extension(chip, f"pmdfmu_fmi{version}SetRecordBuffer", [c_void_p, c_void_p, c_size_t])
    if version == 2:
        # record.data: FMI 2's extension; FMI 3's Binary getter of its value reference
        get_name = "pmdfmu_fmi2GetRecordData"
        get = extension(chip, get_name, [c_void_p, POINTER(c_void_p), POINTER(c_size_t)])
    else:
        get_name = "fmi3GetBinary"
        get = _function(chip.fmu, get_name)
    if lend is None or get is None:
        return None
    fn = native.library().pmd_record_step_lent
    fn.restype = c_int
    fn.argtypes = [
        c_int,
        c_void_p,
        c_void_p,
        c_uint32,
        c_void_p,
        c_void_p,
        c_double,
        c_double,
        c_void_p,
        c_size_t,
        POINTER(c_size_t),
        POINTER(c_int),
    ]
    do_step = f"fmi{version}DoStep"
    functions = (
        int(version == 3),
        native.address(lend),
        native.address(get),
        chip._vr["record.data"] if version == 3 else 0,
        native.address(_function(chip.fmu, do_step)),
    )
    recorded, call = c_size_t(), c_int()
    names = {
        native.STEP_LEND: f"pmdfmu_fmi{version}SetRecordBuffer",
        native.STEP_DO_STEP: do_step,
        native.STEP_GET_DATA: get_name,
        native.STEP_END_LOAN: f"pmdfmu_fmi{version}SetRecordBuffer",
    }

    def step_into(address: int, size: int, now: float, step: float) -> Tuple[int, int]:
        status = fn(*functions, chip.fmu.component, now, step, address, size, byref(recorded), byref(call))
        if status > 1:  # as FMPy raises for an FMI function
            raise FMICallException(function=names[call.value], status=status)
        return status, recorded.value

    return step_into


class _Commanded:
    """The result of a run recording commanded outputs only: record.data's default rows of 32-bit words
    (the chip time, then RECORDED) go into a table of 32-bit words whose rows are the result's records."""

    lendable = False

    def __init__(self, names: Sequence[str], dtype: np.dtype, cycles: int, out: Optional[np.ndarray]):
        self.dtype, self.cycles, self.out = dtype, cycles, out
        # every field is 32 bits wide: the result's rows are the table's, in the caller's array if given
        if out is None:
            self.table = np.empty((cycles, 1 + len(names)), dtype=np.int32)
        else:
            self.table = out.view(np.int32).reshape(cycles, 1 + len(names))
        self.row = np.dtype((np.int32, 1 + len(RECORDED)))
        # the wanted columns as runs of adjacent ones (table column, record column, width): whole runs copy
        # as blocks, and all of record.data as one
        columns, self.runs = [0] + [1 + RECORDED.index(n) for n in names], []
        for i, c in enumerate(columns):
            if self.runs and self.runs[-1][1] + self.runs[-1][2] == c:
                self.runs[-1][2] += 1
            else:
                self.runs.append([i, c, 1])

    def put(self, done: int, rows: np.ndarray) -> None:
        for at, column, width in self.runs:
            self.table[done : done + len(rows), at : at + width] = rows[:, column : column + width]

    def put_records(self, done: int, part: np.ndarray) -> None:
        """Records of the result's type (the native loop's): the same 32-bit fields as the table's row."""
        self.table[done : done + len(part)] = part.view(np.int32).reshape(len(part), self.table.shape[1])

    def result(self) -> np.ndarray:
        return self.out if self.out is not None else self.table.view(self.dtype).reshape(self.cycles)


class _Columns:
    """The result of a run recording record.columns: the FMU's packed little-endian row is the result's
    record (the chip time, then each column in its FMI 3 type's width), whole rows copied as one block,
    or written in place by the FMU (lendable)."""

    lendable = True

    def __init__(self, dtype: np.dtype, cycles: int, out: Optional[np.ndarray]):
        self.out = np.empty(cycles, dtype=dtype) if out is None else out  # every byte of every row is written
        self.row = np.dtype((np.uint8, dtype.itemsize))

    def address(self, done: int) -> int:
        return self.out.ctypes.data + done * self.row.itemsize

    def put(self, done: int, rows: np.ndarray) -> None:
        self.out.view(self.row)[done : done + len(rows)] = rows

    def put_records(self, done: int, part: np.ndarray) -> None:
        self.out[done : done + len(part)] = part

    def result(self) -> np.ndarray:
        return self.out


class Recorder:
    """One Chip.run(cycles, record=names), after Chip._columns's checks (where: each column's variable and
    element, dtype: the rows' type). In bulk through record.data where the FMU records the columns (the
    commanded outputs always, any others with record.columns, not `time`: the same for all the cycles of a
    doStep), else cycle by cycle in the native loop."""

    def __init__(self, chip, names: Sequence[str], where: Dict[str, Tuple[str, int]], dtype: np.dtype):
        self.chip, self.names, self.where, self.dtype = chip, list(names), where, dtype
        self.commanded = set(self.names) <= set(RECORDED)
        self.record_data = record_data(chip)
        self.bulk = bool(self.record_data) and (
            self.commanded or ("record.columns" in chip.variables and "time" not in self.names)
        )

    def run(self, cycles: int, out: Optional[np.ndarray] = None) -> np.ndarray:
        """The rows of the next `cycles` cycles, in `out` if given (Chip.run checked it: the rows' type and
        length, writeable, contiguous), else in a new array."""
        if not self.bulk:
            return self.stepwise(cycles, out)
        return self._bulk(cycles, out)

    def stepwise(self, cycles: int, out: Optional[np.ndarray] = None) -> np.ndarray:
        """`cycles` rows as a master stepping cycle by cycle reads them (the native loop)."""
        out = np.empty(cycles, dtype=self.dtype) if out is None else out  # every field of every row is written
        record(self.chip, Plan(self.chip, self.where, self.dtype), out)
        return out

    def _bulk(self, cycles: int, out: Optional[np.ndarray]) -> np.ndarray:
        """One doStep and one read per chunk of record.capacity cycles (COPIED_CHUNK_BYTES of rows at most where
        they are copied out of record.data) instead of FMI calls every cycle. A
        chunk in which a script step may change the grid (SetSampleTime) starts from a saved FMU state and is
        redone cycle by cycle if it did, so that its rows are those of a master stepping cycle by cycle."""
        chip = self.chip
        capacity = chip.get("record.capacity")
        if capacity == 0:  # the FMU records nothing: cycle by cycle, as a master would
            return self.stepwise(cycles, out)
        if "record.columns" in chip.variables:
            chip.set("record.columns", "" if self.commanded else ",".join(self.names))
        rows = _Commanded(self.names, self.dtype, cycles, out) if self.commanded else _Columns(self.dtype, cycles, out)
        if not self.commanded and rows.row.itemsize != chip.get("record.rowSize"):
            raise RuntimeError(
                f"record.rowSize is {chip.get('record.rowSize')}, not the {rows.row.itemsize} "
                f"bytes of a row of {len(self.names)} columns: the FMU's record.columns is another"
            )
        # the script's steps run up to its last @ line: past it no step can change the grid; a chip without a
        # script's call (script.axes 0) has no step at all, and its chunks need no saved FMU state
        script_end = float("inf")
        if "script.lastCycle" in chip.variables:
            script_end = chip.get("script.lastCycle") if chip.get("script.axes") else -1
        # the FMU writes the rows straight into the result, lent for one doStep at a time, no copy
        step_into = lent_stepper(chip) if rows.lendable else None
        # rows copied out of record.data: chunks the cache holds (docs/performance.md, "Against a bare C loop")
        chunk = capacity if step_into else min(capacity, max(1, COPIED_CHUNK_BYTES // rows.row.itemsize))
        # record.enabled stays on for the run: close() turns it off on every way out, interrupts included
        chip._recording = True
        try:
            chip.set("record.enabled", True)
            done = 0
            while done < cycles:
                n = min(chunk, cycles - done)
                before = chip.cycles if script_end >= 0 else None
                state = chip._fmu_state()
                try:
                    if before is not None and before <= script_end:
                        chip._save_fmu_state(state)
                    logged = len(chip.messages)
                    if step_into:
                        status, lent = step_into(rows.address(done), n * rows.row.itemsize, *chip._step_span(n))
                    else:
                        status = chip._do_step(n)  # Warning if the step's cycles changed
                    redo = bool(state.value) and chip.cycles - before != n
                    if status and not redo:
                        # a grid change with no saved state to redo the chunk from (or a Warning the harness
                        # does not know): the rows would not be a stepping master's
                        raise RuntimeError(
                            f"the recording step of {n} cycles ran other cycles than its rows "
                            f"(doStep's Warning: {chip.messages[-1].message if chip.messages else ''})"
                        )
                    if redo:
                        # the grid changed in the chunk: back to its start, and the chunk runs as a master
                        # stepping cycle by cycle runs it
                        chip.fmu.setFMUState(state)
                        del chip.messages[logged:]
                        chip.set("record.enabled", False)
                        rows.put_records(done, self.stepwise(n))
                        chip.set("record.enabled", True)
                finally:  # a failed redo, or an interrupt, keeps no FMU state alive
                    chip._free_fmu_state(state)
                if not redo and step_into:
                    if lent != n * rows.row.itemsize:
                        raise RuntimeError(
                            f"the lent memory holds {lent // rows.row.itemsize} cycles, not {n}: "
                            f"{lent} bytes, rows of {rows.row.itemsize} bytes"
                        )
                elif not redo:
                    # record.data is the FMU's own buffer, valid until the next call: read in place, once, as
                    # many whole rows as it holds, never more
                    address, size = self.record_data()
                    if size != n * rows.row.itemsize:
                        # the step ran its cycles, but record.data does not hold their rows: never read past it
                        raise RuntimeError(
                            f"record.data holds {size // rows.row.itemsize} cycles, not {n}: "
                            f"{size} bytes, rows of {rows.row.itemsize} bytes"
                        )
                    rows.put(done, np.frombuffer((c_char * size).from_address(address), dtype=rows.row))
                done += n
        except BaseException:
            close(chip, quiet=True)  # the error that stopped the run is the one to see
            raise
        close(chip)
        return rows.result()


def close(chip, quiet: bool = False) -> None:
    """Turns record.enabled off once a recording run ends, on every way out of it: retried until it has run
    through when a KeyboardInterrupt lands in it (raised after), and, should one land where no retry can
    catch it, by the chip's next doStep (Chip._step). quiet: an FMU that refuses is left for that next
    doStep to try again, with no exception of its own (another one is on its way)."""
    interrupted: Optional[BaseException] = None
    while chip._recording:
        try:
            chip.set("record.enabled", False)
            chip._recording = False
        except KeyboardInterrupt as e:
            interrupted = e
        except Exception:
            if not quiet:
                raise
            break
    if interrupted is not None:
        raise interrupted


class NpyFile:
    """Rows written to an open binary file as a .npy array as they come (Chip.run(to=...), `pmdfmu run
    --out`): a header for `room` rows first, the rows after it, then close() writes the header again for
    the rows written (spaces pad it to its first length: the numpy format allows them), so that memory
    holds one chunk of rows, never the run."""

    def __init__(self, f, dtype: Optional[np.dtype], room: int):
        """dtype None: the first rows' (the header is written with them)."""
        self.f, self.dtype, self.room, self.count, self.length = f, dtype, room, 0, 0
        if dtype is not None:
            self._start(dtype)

    def _start(self, dtype: np.dtype) -> None:
        self.dtype = dtype
        self.length = len(self._header(self.room))
        self.f.write(self._header(self.room))

    def _header(self, rows: int, length: int = 0) -> bytes:
        text = "{'descr': %r, 'fortran_order': False, 'shape': (%d,), }" % (
            np.lib.format.dtype_to_descr(self.dtype),
            rows,
        )
        version, size = ((1, 0), "<H") if len(text) + 12 < 65535 else ((2, 0), "<I")
        prefix = len(b"\x93NUMPY") + 2 + struct.calcsize(size)
        total = length or -(-(prefix + len(text) + 1) // 64) * 64  # aligned to 64 bytes, as numpy's own
        text = text + " " * (total - prefix - len(text) - 1) + "\n"
        return b"\x93NUMPY" + bytes(version) + struct.pack(size, len(text)) + text.encode("latin1")

    def write(self, rows: np.ndarray) -> None:
        if self.dtype is None:
            self._start(rows.dtype)
        rows.tofile(self.f)
        self.count += len(rows)

    def close(self) -> None:
        """The header says how many rows were written."""
        if self.dtype is None:
            self._start(np.dtype([("cycle", np.uint32)]))
        self.f.seek(0)
        self.f.write(self._header(self.count, self.length))
        self.f.seek(0, 2)
