"""How Chip.run(cycles, record=names) records (docs/performance.md, "Recording").

In bulk, the FMU's way (Chip._run_recorded): the FMU writes each cycle's row into
record.data itself (record.columns names the columns), one doStep and one read
per record.capacity cycles; FMI 2 reads record.data through the FMU's extension
function pmdfmu_fmi2GetRecordData. `lender` finds how an FMU lends it.

Cycle by cycle in the harness's native library (native/record.c), for an FMU
without bulk recording of the columns (an older build) or a run that records
`time`: per cycle one doStep to the next cycle of the FMU's grid and one get per
FMI type, through the FMU's own FMI functions with the arguments the harness's
Python loop passed (Chip._run_stepwise, kept as the reference), the columns
converted as that loop converted them."""
from __future__ import annotations

from ctypes import POINTER, Structure, byref, c_double, c_int, c_size_t, c_uint32, c_void_p
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
from fmpy.fmi1 import FMICallException

from . import native

# False: every recording runs cycle by cycle in the native loop (tests pin that loop with it)
BULK = True

# record.h's PmdRecordType, by the FMU's type (FMI 2 and FMI 3 names) and by a row's numpy type
DOUBLE, INT32, UINT32, UINT16, INT16, INT, BOOL = range(7)
SOURCE = {2: {"Real": DOUBLE, "Integer": INT32, "Boolean": INT},
          3: {"Float64": DOUBLE, "Int32": INT32, "UInt32": UINT32, "UInt16": UINT16, "Int16": INT16,
              "Boolean": BOOL}}
CTYPE = {DOUBLE: np.float64, INT32: np.int32, UINT32: np.uint32, UINT16: np.uint16, INT16: np.int16,
         INT: np.intc, BOOL: np.bool_}
GRID = ("time", "nextCycleTime", "activeCycleTime")


class Group(Structure):
    _fields_ = [("get", c_void_p), ("vrs", POINTER(c_uint32)), ("n_vrs", c_size_t), ("n_values", c_size_t),
                ("type", c_int), ("values", c_void_p)]


class Column(Structure):
    _fields_ = [("source", c_void_p), ("offset", c_size_t), ("size", c_size_t), ("truth", c_int)]


class Stop(Structure):
    _fields_ = [("cycles", c_size_t), ("call", c_int), ("status", c_int)]


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
                columns.append(Column(source, offset, field_type.itemsize,
                                      int(values.dtype != field_type and field_type.kind == "b")))
            groups.append(Group(native.address(_function(chip.fmu, name)), vrs, len(read), int(offsets[-1]),
                                SOURCE[version][t], values.ctypes.data))
            self.names.append(name)
        self.groups = (Group * len(groups))(*groups)
        self.columns = (Column * len(columns))(*columns)
        self.do_step = f"fmi{version}DoStep"


def record(chip, plan: Plan, out: np.ndarray) -> None:
    """Runs len(out) cycles, each one's row into out; raises as FMPy would for a call that failed
    (FMICallException naming it: the FMU's messages are in chip.messages), the rows before it lost
    with the array, as in the Python loop."""
    lib = native.library()
    fn = lib.pmd_record_fmi2 if plan.version == 2 else lib.pmd_record_fmi3
    fn.restype = c_int
    fn.argtypes = [c_void_p, c_void_p, POINTER(Group), c_size_t, c_size_t, c_size_t, POINTER(Column), c_size_t,
                   c_void_p, c_size_t, c_size_t, POINTER(Stop)]
    stop = Stop()
    if fn(native.address(_function(chip.fmu, plan.do_step)), chip.fmu.component, plan.groups, len(plan.groups),
          plan.grid_group, 0, plan.columns, len(plan.columns), out.ctypes.data, out.dtype.itemsize, len(out), stop):
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


def lender(chip) -> Optional[Callable[[], Tuple[int, int]]]:
    """A function returning record.data's (address, size in bytes) as the FMU lends it after a doStep
    (valid until its next call), or None: an FMI 2 FMU without pmdfmu_fmi2GetRecordData (an older
    build), or BULK off."""
    if not BULK:
        return None
    if chip.fmi_version == 3:
        from fmpy.fmi3 import fmi3Binary, fmi3ValueReference
        vrs, size, value = (fmi3ValueReference * 1)(chip._vr["record.data"]), (c_size_t * 1)(), (fmi3Binary * 1)()

        def lend3() -> Tuple[int, int]:
            chip.fmu.fmi3GetBinary(chip.fmu.component, vrs, 1, size, value, 1)
            return c_void_p.from_buffer(value).value or 0, size[0]
        return lend3
    get = extension(chip, "pmdfmu_fmi2GetRecordData", [c_void_p, POINTER(c_void_p), POINTER(c_size_t)])
    if get is None:
        return None
    data, nbytes = c_void_p(), c_size_t()

    def lend2() -> Tuple[int, int]:
        status = get(chip.fmu.component, byref(data), byref(nbytes))
        if status > 1:                                  # as FMPy raises for an FMI function
            raise FMICallException(function="pmdfmu_fmi2GetRecordData", status=status)
        return data.value or 0, nbytes.value
    return lend2


def lent_stepper(chip) -> Optional[Callable[[int, int, float, float], Tuple[int, int]]]:
    """A function running one recording doStep (from `now`, of `step` s) of an FMI 2 FMU into (address, size
    in bytes) of the caller's memory, returning (doStep's status, the bytes of rows recorded there): the
    memory is lent (pmdfmu_fmi2SetRecordBuffer), the step run and the loan ended in one native call
    (native pmd_record_step_lent), so no Python code, a KeyboardInterrupt included, runs while the FMU
    holds a pointer into the caller's memory. Spares the copy of record.data into the result. None where
    the FMU has no such function (FMI 3: its binary exports the FMI 3 functions only) or BULK is off."""
    if not BULK or chip.fmi_version != 2:
        return None
    pointers = [c_void_p, c_void_p, c_size_t]
    lend = extension(chip, "pmdfmu_fmi2SetRecordBuffer", pointers)
    get = extension(chip, "pmdfmu_fmi2GetRecordData", [c_void_p, POINTER(c_void_p), POINTER(c_size_t)])
    if lend is None or get is None:
        return None
    fn = native.library().pmd_record_step_lent
    fn.restype = c_int
    fn.argtypes = [c_void_p, c_void_p, c_void_p, c_void_p, c_double, c_double, c_void_p, c_size_t,
                   POINTER(c_size_t), POINTER(c_int)]
    functions = native.address(lend), native.address(get), native.address(_function(chip.fmu, "fmi2DoStep"))
    recorded, call = c_size_t(), c_int()
    names = ("pmdfmu_fmi2SetRecordBuffer", "fmi2DoStep", "pmdfmu_fmi2GetRecordData", "pmdfmu_fmi2SetRecordBuffer")

    def step_into(address: int, size: int, now: float, step: float) -> Tuple[int, int]:
        status = fn(*functions, chip.fmu.component, now, step, address, size, byref(recorded), byref(call))
        if status > 1:                                  # as FMPy raises for an FMI function
            raise FMICallException(function=names[call.value], status=status)
        return status, recorded.value
    return step_into
