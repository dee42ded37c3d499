# SPDX-License-Identifier: BSD-2-Clause
"""The chip, as host code sees it: the FMU loaded through FMPy, C-Motion calls
on axis handles, and cycle-exact runs recorded into numpy arrays."""

from __future__ import annotations

import atexit
import difflib
import functools
import operator
import os
import re
import shutil
import tempfile
import threading
from ctypes import POINTER, Array, byref, c_double, c_int32, c_uint32
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2FMUstate,
    fmi2True,
    fmi2ValueReference,
)
from fmpy.fmi3 import FMU3Slave, fmi3Boolean, fmi3Float64, fmi3FMUState, fmi3True, fmi3ValueReference

from . import calls, files, host_port, hosttime, memory_port, native, progress, recording, tables

# the calls' layer, re-exported here where users and docs have named it (pmdfmu.chip.COMMANDS ...)
from .calls import (  # noqa: F401
    AXIS_MASKS,
    BATCH_WORDS,
    COMMANDS,
    CONSTANTS,
    ERROR_NAMES,
    FIELDS,
    OPCODES,
    Axis,
    PMDError,
    axis_number,
    decode,
    encode,
    field_dp,
    field_ex,
    SEND_SHAPES,
    instruction_word,
    sent_name,
    sent_words,
    tables_dir,
)
from .recording import RECORDED  # noqa: F401  (chip.RECORDED, as users and docs name it)
from .fixed import integer, to_word
from .hosttime import HostInterface
from .tables import Command

from .calls import PACKAGE, REPO

STATUS_NAMES = ["OK", "Warning", "Discard", "Error", "Fatal"]


def default_fmu(fmi_version: Union[int, str] = 2, model: str = "chip") -> Path:
    """The built FMU: $PMDFMU_FMU_DIR, the installed package's, or the source tree's build/. model is
    "chip" (PMDMotionProcessor) or "plant" (pmdplant, the DC motor of docs/systems.md);
    default_fmu("plant") is the FMI 2 plant, default_fmu(3, "plant") the FMI 3 one."""
    if fmi_version in ("chip", "plant"):
        fmi_version, model = 2, str(fmi_version)
    if model not in ("chip", "plant"):
        raise ValueError(f"model = {model!r}: the FMUs are 'chip' and 'plant'")
    name = f"{'PMDMotionProcessor' if model == 'chip' else 'pmdplant'}-fmi{fmi_version}.fmu"
    candidates = [Path(os.environ["PMDFMU_FMU_DIR"]) / name] if "PMDFMU_FMU_DIR" in os.environ else []
    candidates += [PACKAGE / "fmus" / name, REPO / "build" / name]
    for path in candidates:
        if path.is_file():
            return path
    raise FileNotFoundError(
        f"{name} not found in {', '.join(map(str, candidates))}: build it first "
        "(pip install . or cmake -S . -B build && cmake --build build)"
    )


# run()'s columns have each register's own width (variables.csv's FMI 3 type), in FMI 2 as well;
# `cycle` is the 32-bit chip time (GetTime)
DTYPES: Dict[str, np.dtype] = {
    v.name: np.dtype(
        {
            "Float64": np.float64,
            "Int32": np.int32,
            "UInt32": np.uint32,
            "UInt16": np.uint16,
            "Int16": np.int16,
            "Boolean": np.bool_,
        }[v.fmi3Type]
    )
    for v in tables.read_variables(tables_dir() / "variables.csv")
    if v.fmi3Type not in ("String", "Binary")
}
CYCLE = ("cycle", np.uint32)
_VARIABLES = {v.name: v for v in tables.read_variables(tables_dir() / "variables.csv")}
# the cycle time an FMU starts with: variables.csv's
DEFAULT_CYCLE_TIME = float(_VARIABLES["cycleTime"].start)
# the width of each integer variable's word (FMI 3 type), by FMI 2 name and by FMI 3 array name: set()
# takes -2^(w-1) .. 2^w-1 for it, in both FMI versions
WIDTHS: Dict[str, int] = {}
SIGNED = set()  # of those, the signed ones (Int32, Int16): set() sends their bits as a signed value
for _v in tables.read_variables(tables_dir() / "variables.csv"):
    if _v.fmi3Type in ("Int32", "UInt32", "UInt16", "Int16"):
        WIDTHS[_v.name] = WIDTHS[_v.name.split("[")[0]] = 16 if _v.fmi3Type.endswith("Int16") else 32
        if _v.fmi3Type.startswith("Int"):
            SIGNED.update((_v.name, _v.name.split("[")[0]))
del _v
_ELEMENT = re.compile(r"(.+)\[(\d+)\]")


def _boolean(value, what: str) -> bool:
    """A Boolean variable's value: True, False, 1 or 0. Anything else raises ValueError naming what: FMPy
    took Python's truth value, so that FMI 3 set 0.5, "no" and 5 to True and None to False."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    try:
        n = operator.index(value)
    except TypeError:
        n = None
    if n not in (0, 1):
        raise ValueError(f"{what} = {files.shown(value)} is not a Boolean (True, False, 1 or 0)")
    return bool(n)


def _real(value, what: str) -> float:
    """A Real variable's value: a number a double holds (int, float, Fraction, Decimal); a string, a bool
    (cycleTime=True was 1 s) or one too large raises ValueError naming what, not ctypes' TypeError or
    float's OverflowError."""
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise ValueError(f"{what} = {files.shown(value)} is not a number")
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{what} = {files.shown(value)} is not a number a double holds") from None


def _array_element(variables, name: str) -> Optional[Tuple[str, int]]:
    """FMI 3 keeps arrays whole: "analog[2]" there is element 1 of the array
    "analog" (None for a name that is a variable, or no array's element)."""
    m = _ELEMENT.fullmatch(name)
    if name in variables or not m or m.group(1) not in variables:
        return None
    v, i = variables[m.group(1)], int(m.group(2))
    size = int(v.dimensions[0].start) if getattr(v, "dimensions", None) else 1
    return (m.group(1), i - 1) if 1 <= i <= size else None


def _array_elements(variables, name: str) -> List[str]:
    """FMI 2 has an array's elements only: "analog" there is analog[1] .. analog[8]
    (empty for a name that is a variable, or no array)."""
    if name in variables:
        return []
    out: List[str] = []
    while f"{name}[{len(out) + 1}]" in variables:
        out.append(f"{name}[{len(out) + 1}]")
    return out


class FMUError(RuntimeError):
    """The FMU refused a call; the message is what it logged (e.g. a script's file:line: reason)."""


class FMURefusal(FMUError, FMICallException):
    """An FMI call the FMU refused: FMPy's FMICallException (.function, .status) with what the FMU logged
    for it (.messages: warnings and errors, as chip.messages holds them), which its text ends with."""

    def __init__(self, function: str, status: int, messages: Sequence[str]):
        FMICallException.__init__(self, function, status)
        self.messages = list(messages)
        if self.messages:
            self.args = (f"{self.args[0][:-1]}: " + "; ".join(self.messages),)


class UnknownVariable(KeyError):
    """A name that is no variable of the FMU (a KeyError, as a dict lookup gives): the message says so and
    names the nearest variables."""

    def __str__(self) -> str:
        return self.args[0]


def _refusals(method):
    """Chip's public calls: an FMI call the FMU refuses inside raises FMURefusal, carrying the FMU's
    messages logged during the call (FMPy's FMICallException names only the function and status)."""

    @functools.wraps(method)
    def call(self, *args, **kwargs):
        logged = len(self.messages)
        try:
            return method(self, *args, **kwargs)
        except FMICallException as e:
            if isinstance(e, FMURefusal):
                raise
            raise FMURefusal(
                e.function, e.status, [m.message for m in self.messages[logged:] if m.status not in ("OK", "Pending")]
            ) from None

    return call


@dataclass
class LogMessage:
    status: str
    category: str
    message: str


# ---- an FMU file, unpacked once per process: every Chip of the file shares it ----


class _SharedPrototypes:
    """FMPy's slave classes with the FMI functions' ctypes prototypes taken from the FMU file's
    _Unpacked.prototypes: FMPy declares them in every constructor by introspecting each of its
    fmi* methods, which costs about as much as all the rest of a Chip()."""

    def __init__(self, functions: dict, **kwargs):
        self._shared_functions = functions
        super().__init__(**kwargs)

    def _loadFunctions(self) -> None:
        self._functions = self._shared_functions


class _Slave2(_SharedPrototypes, FMU2Slave):
    pass


class _Slave3(_SharedPrototypes, FMU3Slave):
    pass


@dataclass
class _Unpacked:
    """What every instance of one FMU file shares, made by its first: the folder the file is
    extracted to (removed when the interpreter exits, never by an instance: the FMU only reads
    its resources), the model description, the variables by name and their value references,
    and per FMI version an FMPy slave never instantiated whose library stays loaded for the
    process, with the FMI functions' prototypes declared on it (an instance's own dlopen and
    dlclose keep their count, so these function pointers stay valid; the FMU's library holds
    no mutable static data: every instance's state is its own allocation)."""

    unzipdir: str
    model_description: object
    variables: Dict[str, object]
    vr: Dict[str, int]
    prototypes: Dict[int, object]
    # Chip._columns' checks and row types per (FMI version, names): a few sets at most
    recorded: Dict[tuple, tuple] = field(default_factory=dict)
    # the FMU's own functions beside the FMI ones (pmdfmu.recording.extension), looked up once
    extensions: Dict[str, object] = field(default_factory=dict)


_UNPACKED: Dict[tuple, _Unpacked] = {}  # by the FMU file's identity (_identity)
# sweeps may make Chips in several threads: the lock guards the cache, and FMPy's slave constructor,
# which changes the process's working directory while it loads the library
_UNPACKED_LOCK = threading.Lock()
_unpack_root: List[str] = []  # this process's folder of extracted FMU files, once made


def _identity(path: Path) -> tuple:
    """An FMU file as the cache knows it: a file rewritten in place or replaced (pmdfmu pack
    writes FMUs) is another file, extracted anew."""
    resolved = files.resolved(path)
    st = resolved.stat()
    return str(resolved), st.st_size, st.st_mtime_ns, st.st_ino, st.st_dev


def _remove_unpack_root(pid: int) -> None:
    if os.getpid() == pid and _unpack_root:  # not from a forked child: the folder is its parent's
        shutil.rmtree(_unpack_root[0], ignore_errors=True)


def _forget_unpacked() -> None:
    """A forked child starts its own cache (its parent removes the parent's folder at exit)."""
    global _UNPACKED_LOCK
    _UNPACKED.clear()
    _unpack_root.clear()
    _UNPACKED_LOCK = threading.Lock()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_unpacked)


def _unpack(path: Path, fmi_version: int) -> Tuple[_Unpacked, dict]:
    """The FMU file's shared part, extracted and read at its first use in this process, and the
    FMI functions' prototypes for fmi_version."""
    key = _identity(path)
    with _UNPACKED_LOCK:
        unpacked = _UNPACKED.get(key)
        if unpacked is None:
            if not _unpack_root:
                _unpack_root.append(tempfile.mkdtemp(prefix="pmdfmu-fmus-"))
                atexit.register(_remove_unpack_root, os.getpid())
            for old in [k for k in _UNPACKED if k[0] == key[0]]:
                del _UNPACKED[old]  # the file was rewritten; its folder stays until exit (instances use it)
            description = read_model_description(key[0])
            unzipdir = extract(key[0], tempfile.mkdtemp(prefix=Path(key[0]).stem + "-", dir=_unpack_root[0]))
            variables = {v.name: v for v in description.modelVariables}
            unpacked = _UNPACKED[key] = _Unpacked(
                str(unzipdir), description, variables, {name: v.valueReference for name, v in variables.items()}, {}
            )
        prototype = unpacked.prototypes.get(fmi_version)
        if prototype is None:
            prototype = unpacked.prototypes[fmi_version] = (FMU2Slave if fmi_version == 2 else FMU3Slave)(
                guid=unpacked.model_description.guid,
                unzipDirectory=unpacked.unzipdir,
                modelIdentifier=unpacked.model_description.coSimulation.modelIdentifier,
                instanceName="pmd",
            )
    return unpacked, prototype._functions


def _check_out(out, cycles: int, dtype: np.dtype) -> None:
    """run(out=)'s checks: the recorder writes every byte of `cycles` rows of `dtype` straight into it."""
    why = None
    if not isinstance(out, np.ndarray):
        why = f"is a {type(out).__name__}, not a numpy array"
    elif out.dtype != dtype:
        why = f"has dtype {out.dtype}, not the rows' {dtype}"
    elif out.shape != (cycles,):
        why = f"has shape {out.shape}, not ({cycles},)"
    elif not (out.flags.c_contiguous and out.flags.writeable and out.flags.aligned):
        why = "is not a writeable, aligned, contiguous array"
    if why:
        raise ValueError(f"run: out= {why}")


class Chip:
    """A motion processor in an FMU instance: Chip(fmi_version=2, fmu=None, **parameters).

    parameters are the FMU's (cycleTime, memorySize, loopback, script, machine: a machine
    file's path or TOML text, docs/machine.md). log_categories
    enables FMU logging (True for all, or a list such as ["warnings", "events"]);
    messages collect in chip.messages, errors always.

    host_interface turns on host time (docs/host-time.md): None (the default, the
    kind "none") sends commands in no chip time, as before; a kind's name
    ("parallel16", "parallel8", "serial", "spi", "fixed", with the defaults of
    modelDescription/host_interfaces.csv) or a pmdfmu.HostInterface makes each
    command take its transfer time, the chip running the cycles that fall due.

    device="serial:PATH" or "tcp:HOST:PORT" (keywords address=, baud=) returns a chip reached
    over its serial packet protocol instead (pmdfmu serve's twin or a real chip: line.LineChip,
    docs/device.md): the same Axis methods, and command, send and batch; monitor="tcp:HOST:PORT"
    (pmdfmu serve --monitor's) adds run, get, write_memory, wait and the host clock; the calls that
    need the FMU in-process (recording, set, FMU states; without a monitor those too) raise
    line.NeedsFMU."""

    def __new__(cls, *args, device: Optional[str] = None, **kwargs):
        # device="serial:PATH" or "tcp:HOST:PORT": the chip over its serial packets (line.py), commands only
        if device is not None and device != "fmu":
            from .line import LineChip

            return LineChip(device, **kwargs)
        return super().__new__(cls)

    # how run(record=...) records: a class made per run with (chip, names, where, dtype), whose run(cycles)
    # returns the rows (a test sets another on an instance: its oracle)
    recorder = recording.Recorder

    def __init__(
        self,
        fmi_version: int = 2,
        fmu: Union[str, Path, None] = None,
        *,
        log_categories: Union[bool, Iterable[str]] = False,
        host_interface: Union[None, str, HostInterface] = None,
        device: Optional[str] = None,
        **parameters,
    ):
        if fmi_version not in (2, 3):
            raise ValueError(f"fmi_version is 2 or 3, not {fmi_version}")
        # the host port of the native commands (host_port.py): the FMU's functions once instantiated; _fast is
        # it when the Axis methods may use it (an FMU that is open, a class whose _step is Chip's)
        self._port = native.HostPort()
        self._fast = None
        self.host_interface = hosttime.host_interface(host_interface)
        self._recording = False  # a recording run has turned record.enabled on (recording.close)
        self._host_ns = 0  # the host clock, whole ns since the chip's time 0
        self.fmi_version = fmi_version
        self.path = Path(fmu) if fmu else default_fmu(fmi_version)
        # shared by every Chip of this FMU file in the process: read-only
        unpacked, functions = _unpack(self.path, fmi_version)
        self.model_description = unpacked.model_description
        self.variables = unpacked.variables
        self._vr = unpacked.vr
        self._recorded = unpacked.recorded
        self._extensions = unpacked.extensions
        self._library = unpacked.prototypes[fmi_version].dll  # loaded for the process (_Unpacked)
        self.messages: List[LogMessage] = []
        self._unzipdir = unpacked.unzipdir
        kwargs = dict(
            functions=functions,
            guid=self.model_description.guid,
            unzipDirectory=self._unzipdir,
            modelIdentifier=self.model_description.coSimulation.modelIdentifier,
            instanceName="pmd",
        )
        if fmi_version == 2:
            with _UNPACKED_LOCK:
                self.fmu = _Slave2(**kwargs)
            self._callbacks = fmi2CallbackFunctions()
            # Not FMPy's logger proxy: it keeps one process-wide pointer to the last
            # logger, which would dangle once this Chip is gone. The FMU passes no
            # printf arguments; it escapes '%' as "%%" (see _log).
            self._callbacks.logger = fmi2CallbackLoggerTYPE(
                lambda env, name, status, category, message: self._record(
                    status, category, message.decode(errors="replace").replace("%%", "%")
                )
            )
            self.fmu.instantiate(callbacks=self._callbacks, loggingOn=bool(log_categories))
            self.fmu.setupExperiment(startTime=0.0)
        else:
            with _UNPACKED_LOCK:
                self.fmu = _Slave3(**kwargs)
            self.fmu.instantiate(
                loggingOn=bool(log_categories),
                logMessage=lambda env, status, category, message: self._record(
                    status, category, message.decode(errors="replace")
                ),
            )
        types = (
            ("Real", "Integer", "Boolean", "String")
            if fmi_version == 2
            else ("Float64", "Int32", "UInt32", "UInt16", "Int16", "Boolean", "String")
        )
        self._getters = {t: getattr(self.fmu, "get" + t) for t in types}
        self._setters = {t: getattr(self.fmu, "set" + t) for t in types}
        self._getters.pop("String")  # run() records numbers; get() reads the script path below
        try:
            if log_categories and log_categories is not True:
                self._set_debug_logging(list(log_categories))
            self._initialize(parameters)
        except BaseException:  # a refused category, an unknown or bad parameter: no instance is left behind
            self.fmu.freeInstance()
            self.fmu = None
            raise
        # where the FMU's grid stands, read before every doStep (once a cycle while recording): its last
        # communication point, the next cycle's time and the cycle time, into arrays made once
        self._grid_vrs = (c_uint32 * 3)(*[self._vr[n] for n in ("time", "nextCycleTime", "activeCycleTime")])
        self._grid = (c_double * 3)()
        self._memory_vrs: Dict[int, Array] = {}  # write_memory (FMI 2): value references per word count
        host_port.fill(self._port, self)
        calls._FAST_GLOBALS["_COMMAND"] = self._command = host_port.functions()[1]
        if type(self)._step is Chip._step and type(self)._send is Chip._send:
            self._fast = byref(self._port)  # as the Axis methods pass it (host_port.h: no argtypes)
        # fmi3DoStep's outputs (_step): event handling needed, terminate, early return, last successful time
        self._step_out = (byref(fmi3Boolean()), byref(fmi3Boolean()), byref(fmi3Boolean()), byref(fmi3Float64()))

    # ---- life cycle ----

    @_refusals
    def _set_debug_logging(self, categories: List[str]) -> None:
        """The FMU's categories to log (its own message names an unknown one and lists the rest)."""
        self.fmu.setDebugLogging(True, categories)

    def _script_value(self, value, name: str = "script") -> str:
        """What the `script` parameter (or `machine`, taken the same way) gets: a script's text (a value
        holding a line feed) as it is; a
        relative path the FMU holds in its resources folder as it is (the FMU looks there first); any
        other path resolved from the user's working directory, so that it means the same file whatever
        directory the FMU or a sweep's worker runs in. A Path is a file, never text: one holding a line
        feed, which the FMU would read as text, is refused (ValueError)."""
        if isinstance(value, os.PathLike):
            text = os.fspath(value)
            if "\n" in text:
                raise ValueError(
                    f"{name}: the path {text!r} holds a line feed, and the FMU reads a {name} value "
                    f"holding one as the {name}'s text (docs/scripts.md): rename the file or its folder"
                )
        text = str(value) if value else ""
        if not text or "\n" in text:
            return text
        path = Path(text)
        if not path.is_absolute() and not Path(self._unzipdir, "resources", text).exists():
            return str(files.resolved(path))
        return text

    def _initialize(self, parameters) -> None:
        for name, value in parameters.items():
            if name in ("script", "machine"):
                value = self._script_value(value, name)
            self.set(name, value)
        try:
            if self.fmi_version == 2:
                self.fmu.enterInitializationMode()
            else:
                self.fmu.enterInitializationMode(startTime=0.0)
            self.fmu.exitInitializationMode()
        except Exception:
            errors = [m.message for m in self.messages if m.status == "Error"]
            raise FMUError("\n".join(errors) or "initialization failed") from None

    @_refusals
    def reinitialize(self, **parameters) -> None:
        """The same instance as new: fmiReset, then these parameters and a new
        initialization (a sweep reuses one instance per worker this way)."""
        self.fmu.reset()
        self._recording = False  # the reset turned record.enabled off
        self.messages.clear()
        self._host_ns = 0
        if self.fmi_version == 2:
            self.fmu.setupExperiment(startTime=0.0)
        self._initialize(parameters)

    def close(self) -> None:
        self._fast = None
        self._port.instance = None
        if self.fmu is not None:
            self.fmu.terminate()
            self.fmu.freeInstance()
            self.fmu = None

    def __enter__(self) -> "Chip":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _record(self, status: int, category: bytes, message: str) -> None:
        self.messages.append(
            LogMessage(STATUS_NAMES[status] if 0 <= status < 5 else str(status), category.decode(), message)
        )

    # ---- variables ----

    def _size(self, name: str) -> int:
        """Elements of a variable: FMI 3 keeps the ports' arrays whole."""
        v = self.variables[name]
        return int(v.dimensions[0].start) if getattr(v, "dimensions", None) else 1

    def _variable(self, name: str, fn: str):
        """The model variable of this name, or UnknownVariable naming the call and the nearest names."""
        v = self.variables.get(name)
        if v is None:
            raise UnknownVariable(f"{fn}: {name!r} is not a variable of the FMU{self._nearest(name)}")
        return v

    def _nearest(self, name: str) -> str:
        """The end of a message for a name that is no variable: the nearest names set() and get() take."""
        names = set(self.variables)
        for n in self.variables:  # arrays as a whole (FMI 2) and their elements (FMI 3)
            m = _ELEMENT.fullmatch(n)
            if m:
                names.add(m.group(1))
            names.update(f"{n}[{i + 1}]" for i in range(self._size(n) if self.fmi_version == 3 else 0))
        near = difflib.get_close_matches(name, sorted(names), n=3, cutoff=0.7)
        return f": did you mean {' or '.join(near)}?" if near else " (pmdfmu info lists them)"

    @_refusals
    def set(self, name: str, value) -> None:
        """Sets an FMU input or parameter by name (an FMI 3 array takes a list).

        An array's element and a whole array have the same names in FMI 2 and FMI 3:
        chip.set("analog[1]", 512) sets one element (in FMI 3, the array with that
        element changed, in one call), chip.set("io.input", [...16 values...]) all of
        them (in FMI 2, its elements in one call).

        An integer variable of w bits (variables.csv's FMI 3 type: Int32, UInt32,
        UInt16) takes an integer from -2^(w-1) to 2^w-1, its signed or unsigned
        reading of the same bits, through FMI 2 and FMI 3 alike; anything else (a
        value that does not fit, a float) raises ValueError before anything is set.
        The FMU then checks the value's meaning (memorySize, host.wordCount, ...)."""
        element = _array_element(self.variables, name) if self.fmi_version == 3 else None
        if element:
            base, i = element
            values = self.get(base)
            values[i] = value
            self.set(base, values)  # a bad value raises naming base[i + 1], i.e. `name`
            return
        elements = _array_elements(self.variables, name) if self.fmi_version == 2 else []
        v = self._variable(elements[0] if elements else name, "set")
        count = len(elements) or self._size(name)
        values = list(value) if count > 1 else [value]
        if len(values) != count:
            raise ValueError(f"set: {name} has {count} elements, {len(values)} values given; nothing was set")
        if name in WIDTHS:
            bits = WIDTHS[name]
            values = [
                to_word(x, bits, f"set: {name}" + (f"[{i + 1}]" if len(values) > 1 else ""))
                for i, x in enumerate(values)
            ]
            if (self.fmi_version == 2 and bits == 32) or name in SIGNED:  # the same bits, signed
                values = [x - (1 << bits) if x >> (bits - 1) else x for x in values]
        elif v.type in ("Boolean", "Real", "Float64"):
            check = _boolean if v.type == "Boolean" else _real
            values = [
                check(x, f"set: {name}" + (f"[{i + 1}]" if len(values) > 1 else "")) for i, x in enumerate(values)
            ]
        elif v.type == "String":  # FMPy encodes a str: a path is its text
            if not all(isinstance(x, (str, os.PathLike)) for x in values):
                raise ValueError(f"set: {name} = {files.shown(value)} is not a str (or a path)")
            values = [os.fspath(x) for x in values]
        vrs = [self.variables[e].valueReference for e in elements] if elements else [v.valueReference]
        self._setters[v.type](vrs, values)

    @_refusals
    def get(self, name: str):
        """Reads an FMU variable by name (an array reads as a list, an element
        such as "io.output[3]" as a number, in FMI 2 and FMI 3 alike)."""
        element = _array_element(self.variables, name) if self.fmi_version == 3 else None
        if element:
            return self.get(element[0])[element[1]]
        elements = _array_elements(self.variables, name) if self.fmi_version == 2 else []
        if elements:
            return list(
                self._getters[self.variables[elements[0]].type]([self.variables[e].valueReference for e in elements])
            )
        v = self._variable(name, "get")
        if v.type == "String":
            value = self.fmu.getString([v.valueReference])[0]
            return value.decode() if isinstance(value, bytes) else value
        if self._size(name) > 1:
            return list(self._getters[v.type]([v.valueReference], nValues=self._size(name)))
        return self._getters[v.type]([v.valueReference])[0]

    # ---- the time grid: the FMU's (activeCycleTime, nextCycleTime, nextCycle); the harness keeps no copy ----

    @property
    def time(self) -> float:
        """Simulation time of the next cycle (the FMU's nextCycleTime)."""
        return self.get("nextCycleTime")

    @property
    def cycle_time(self) -> float:
        """The cycle time of the grid now, s (the FMU's activeCycleTime: the sample
        time register, which SetSampleTime changes)."""
        return self.get("activeCycleTime")

    @property
    def cycles(self) -> int:
        """Chip cycles run since initialization: the grid index of the next cycle
        (the FMU's nextCycle; an FMU state restores it)."""
        return int(self.get("nextCycle"))

    def _step(self, cycles: int) -> int:
        """One doStep that runs the next `cycles` cycles of the FMU's grid: from its
        last communication point to the time of the cycle after them. Returns its
        status (OK, or Warning: a grid change inside a recording step); FMPy raises
        for an Error. A recording run an interrupt left open is closed first."""
        if self._recording:
            recording.close(self)
        return self._do_step(cycles)

    def _step_span(self, cycles: int) -> Tuple[float, float]:
        """The doStep that runs the next `cycles` cycles of the FMU's grid: its start (the
        last communication point) and its size (to the time of the cycle after them)."""
        if self.fmi_version == 2:
            self.fmu.fmi2GetReal(self.fmu.component, self._grid_vrs, 3, self._grid)
        else:
            self.fmu.fmi3GetFloat64(self.fmu.component, self._grid_vrs, 3, self._grid, 3)
        now, next_time, cycle_time = self._grid
        return now, (next_time - now) + cycles * cycle_time

    def _do_step(self, cycles: int) -> int:
        """_step's doStep itself."""
        now, step = self._step_span(cycles)
        if self.fmi_version == 2:  # FMPy's doStep returns no status: the FMI call does
            return self.fmu.fmi2DoStep(self.fmu.component, now, step, fmi2True)
        return self.fmu.fmi3DoStep(self.fmu.component, now, step, fmi3True, *self._step_out)

    # ---- FMU state ----

    def _fmu_state(self):
        """An empty FMU state pointer for the FMU to fill (through byref, before Python runs again): the
        frame holding it frees it on every way out, an interrupt landing as the C call returns included
        (FMPy's getFMUState holds the pointer in a local of its own until it returns)."""
        return fmi2FMUstate() if self.fmi_version == 2 else fmi3FMUState()

    def _save_fmu_state(self, state) -> None:
        (self.fmu.fmi2GetFMUstate if self.fmi_version == 2 else self.fmu.fmi3GetFMUState)(
            self.fmu.component, byref(state)
        )

    def _free_fmu_state(self, state) -> None:
        if state.value:
            self.fmu.freeFMUState(state)

    @_refusals
    def get_state(self) -> bytes:
        """The whole chip as bytes: the FMU's serialized FMU state, as it is (the
        time grid is in it). Restorable with set_state in any Chip of the same FMU
        build, in this process or another."""
        if self._recording:  # a recording an interrupt left open: not part of the chip
            recording.close(self)
        state = self._fmu_state()
        try:
            self._save_fmu_state(state)
            return bytes(self.fmu.serializeFMUState(state))
        finally:
            self._free_fmu_state(state)

    @_refusals
    def set_state(self, data: bytes) -> None:
        """Restores a get_state snapshot; the FMU refuses a corrupted or foreign one."""
        state = self._fmu_state()
        try:
            self.fmu.deserializeFMUState(data, state)
            self.fmu.setFMUState(state)
            self._recording = False  # the restored chip's record.enabled is its own
        finally:
            self._free_fmu_state(state)
        # the host clock is the harness's, not in the bytes: it goes to the restored chip's last cycle
        self._host_ns = self._last_cycle_ns() if self.cycles else 0

    # ---- host port ----

    def axis(self, n: int) -> Axis:
        """Axis handle n = 0..3 (C-Motion's PMDAxis1..PMDAxis4)."""
        return Axis(self, n)

    @_refusals
    def batch(self, words: Sequence[int]) -> Tuple[int, List[int]]:
        """Sends raw host words (whole commands) as one batch; returns
        (host.error, reply words). It executes now, before the next cycle.

        A word is an integer 0 .. 0xFFFF, or -32768 .. -1 for its two's complement
        (-1 sends 0xFFFF), through FMI 2 and FMI 3 alike. Anything else (0x10010, a
        float) raises ValueError naming the word and its index before anything is
        sent."""
        if len(words) > BATCH_WORDS:
            raise ValueError(f"a batch holds at most {BATCH_WORDS} words, not {len(words)}")
        try:
            words = [to_word(w, 16, f"batch: word {i}") for i, w in enumerate(words)]
        except ValueError as e:
            raise ValueError(f"{e}; nothing was sent") from None
        if self.host_interface.kind != "none":
            return self._timed_batch(words)
        return self._send(words)

    def _send(self, words: List[int]) -> Tuple[int, List[int]]:
        """One batch through the host port, executed now (checked words): the FMI calls of a get of
        host.strobe, a set of the words, host.wordCount and a new strobe, and a get of the ack, error
        and reply, in one native call (native/host_port.c; tests/stepwise.py send_stepwise is the
        Python path it replaces)."""
        port = self._port
        port.in_[: len(words)] = words
        logged = len(self.messages)
        r = host_port.functions()[0](port, len(words), BATCH_WORDS)
        if r & host_port.FAILED:
            self._fast_trouble(r, None, logged)
        return (r >> 32) & 0xFFFF, port.out[: (r >> 48) & 0xFF]

    def _fast_trouble(self, r: int, command: Optional[Command], logged: int):
        """A native command's result word that is not the plain reply the caller expected: raises as the
        Python path did (FMURefusal for a refused FMI call, FMUError for an unexecuted batch, PMDError
        for host.error), else returns the reply decoded from all its words."""
        port = self._port
        if r & host_port.FAILED:
            if port.stop.call == native.HOST_ACK:
                raise FMUError(
                    f"host.ack is {port.ack_word}, not the strobe {port.strobe_sent}: the FMU did not execute the batch"
                )
            raise FMURefusal(
                host_port.CALLS[self.fmi_version][port.stop.call],
                port.stop.status,
                [m.message for m in self.messages[logged:] if m.status not in ("OK", "Pending")],
            )
        error = (r >> 32) & 0xFFFF
        if error:
            raise PMDError(error, command.name)
        values = decode(command.reply, port.out[: (r >> 48) & 0xFF])
        return None if not values else values[0] if len(values) == 1 else tuple(values)

    @property
    def host_interface(self) -> HostInterface:
        """The host interface (docs/host-time.md); assigning one takes effect from the next command."""
        return self._host_interface

    @host_interface.setter
    def host_interface(self, value) -> None:
        self._host_interface = hosttime.host_interface(value)
        host_port.time_port(self._port, self._host_interface)

    @property
    def _host_ns(self) -> int:
        """The host clock: its one copy is the native port's (host_port.py), which native commands move."""
        return self._port.host_ns

    @_host_ns.setter
    def _host_ns(self, ns: int) -> None:
        self._port.host_ns = ns

    @_refusals
    def command(self, axis: int, command: Union[str, Command], args: Sequence[int] = ()):
        """Executes one C-Motion call; raises PMDError if the chip refuses it.
        Returns None, the reply value, or a tuple of reply values."""
        if isinstance(command, str):
            command = COMMANDS[command]
        axis = axis_number(axis)
        instruction = instruction_word(command.opcode, 0 if command.scope == "chip" else axis)
        error, reply = self.batch([instruction] + encode(command, args))
        if error:
            raise PMDError(error, command.name)
        values = decode(command.reply, reply)
        return None if not values else values[0] if len(values) == 1 else tuple(values)

    def send(self, instruction: int, *data: int) -> Tuple[int, ...]:
        """One command as a host writes it on the chip's port: the instruction word (the opcode and the
        axis field, pmd-reference 2.1; pmdfmu.instruction_word(opcode, axis)) and the command's data
        words; returns its reply words. The raw form of an Axis method, for host code written in words
        (a port of C-Motion's transport, a recorded bus trace, a test of the chip's own checks):
        chip.send(instruction_word(0x11, 0), 0x0001, 0x0000) is chip.axis(0).SetVelocity(0x10000).

        A word is 0 .. 0xFFFF, or -32768 .. -1 for its two's complement; a known command takes its
        own number of data words. Anything else raises ValueError before anything is sent. An
        opcode no command has is sent as it is (the chip refuses it). Raises PMDError (.code: the
        host I/O error) if the chip refuses the command. On the native path as the Axis methods are,
        with the host interface's time."""
        shape = SEND_SHAPES.get(instruction) if type(instruction) is int else None
        port = self._fast
        if shape is None or port is None or self._recording:
            return self._send_words(instruction, data)
        n, call, ok, command = shape
        if len(data) != n:
            return self._send_words(instruction, data)
        for w in data:
            if type(w) is not int or not 0 <= w <= 0xFFFF:
                return self._send_words(instruction, data)
        # the words packed as pmd_host_command takes them (host_port.h): word 0 in the low bits
        lo = instruction | data[0] << 16 if n else instruction
        hi = (data[1] | data[2] << 16 if n > 2 else data[1]) if n > 1 else 0
        logged = len(self.messages)
        r = self._command(port, call, lo, hi)
        if r >> 32 == ok:  # done, the reply words the command returns: in the result word
            count = ok >> 16
            return () if not count else (r >> 16 & 0xFFFF,) if count == 1 else (r >> 16 & 0xFFFF, r & 0xFFFF)
        if r & host_port.FAILED:
            self._fast_trouble(r, command, logged)  # raises
        if r >> 32 & 0xFFFF:
            raise PMDError(r >> 32 & 0xFFFF, command.name)
        return tuple(self._port.out[: r >> 48 & 0xFF])

    @_refusals
    def _send_words(self, instruction, data: Sequence) -> Tuple[int, ...]:
        """send() off the native path: the words checked (calls.sent_words), then one batch."""
        words, command = sent_words(instruction, data)
        error, reply = self.batch(words)
        if error:
            raise PMDError(error, sent_name(command, words[0]))
        return tuple(reply)

    # ---- the trace ----

    def trace(self):
        """The trace buffer as a scope reads it (pmdfmu.trace.Trace): one column per trace variable
        configured (SetTraceVariable), named like the FMU's outputs, with its unit; the samples oldest
        first (a rolling trace that wrapped too), their chip time, period, mode and trigger.
        chip.trace().plot() draws it. The chip is left as it was: the read runs on a saved FMU state."""
        from .trace import read

        return read(self)

    # ---- dual-port memory ----

    @_refusals
    def write_memory(self, address: int, words: Sequence[int]) -> None:
        """Writes 32-bit words straight into external memory (the seed's dual-port
        upload, bypassing the processor), 64 words per strobe.

        A word is an integer from -2^31 to 2^32-1, its signed or unsigned reading
        (-1 and 0xFFFFFFFF store the same word); the words must fit the memory
        (0 <= address, address + len(words) <= memorySize). Anything else (a value
        that does not fit 32 bits, a float, a negative address, a block leaving the
        memory) raises ValueError naming it before anything is written.

        The strobes run in C (the harness's native library, native/memory_port.c), each
        one the FMI calls a master makes; a call the FMU refuses raises FMPy's
        FMICallException, the blocks before it written (docs/performance.md,
        "Upload and streaming")."""
        data = self._memory_words(words)
        address = integer(address, "write_memory: address")
        # memorySize and memory.strobe read in one get, the fit checked (_memory_fits), then the strobes
        memory_port.write(self, address, data)

    @staticmethod
    def _memory_fits(address: int, n: int, size: int) -> None:
        """write_memory's check that n words at address fit the memory of size words."""
        if address < 0 or address + n > size:
            raise ValueError(
                f"write_memory: {n} words at address {address} leave the {size}-word memory "
                f"(memorySize; addresses 0 .. {size - 1}); nothing was written"
            )

    @staticmethod
    def _memory_words(words: Sequence[int]) -> np.ndarray:
        """write_memory's words as uint32, checked: integers from -2^31 to 2^32-1."""
        array = np.asarray(words)
        if array.ndim != 1:
            raise ValueError(f"write_memory: words must be a sequence of integers, not {words!r}")
        if array.dtype == np.uint32:  # every value a word: nothing to check
            return array
        if array.dtype == np.int32:
            return array.view(np.uint32)
        try:
            if array.dtype.kind in "iub":  # numpy integers: the whole array checked at once
                wide = array.astype(np.int64) if array.dtype.kind != "u" else array
                bad = np.flatnonzero((wide > 0xFFFFFFFF) | ((wide < -(1 << 31)) if wide.dtype.kind == "i" else False))
                if len(bad):
                    to_word(int(array[bad[0]]), 32, f"write_memory: words[{bad[0]}]")  # raises, naming it
            else:  # Python ints beyond int64, floats, anything else: one by one,
                items = words.tolist() if isinstance(words, np.ndarray) else list(words)  # as the caller wrote them
                array = np.array(
                    [to_word(w, 32, f"write_memory: words[{i}]") for i, w in enumerate(items)], dtype=np.int64
                )
        except ValueError as e:
            raise ValueError(f"{e}; nothing was written") from None
        return (array.astype(np.int64) & 0xFFFFFFFF).astype(np.uint32)

    def _memory_strobe(self, address: int, chunk: np.ndarray, strobe: int) -> None:
        """Sets memory.data, .address, .count and .strobe for one write, each value
        array passed to the FMI function as it lies in memory."""
        n, vr = len(chunk), self._vr
        if self.fmi_version == 2:  # all Integer: one call, the data words first
            if n not in self._memory_vrs:
                self._memory_vrs[n] = (fmi2ValueReference * (n + 3))(
                    *[vr[f"memory.data[{i + 1}]"] for i in range(n)],
                    vr["memory.address"],
                    vr["memory.count"],
                    vr["memory.strobe"],
                )
            values = np.concatenate([chunk.view(np.int32), np.array([address, n, strobe], dtype=np.int32)])
            self.fmu.fmi2SetInteger(
                self.fmu.component, self._memory_vrs[n], n + 3, values.ctypes.data_as(POINTER(c_int32))
            )
        else:  # memory.data[64] and memory.address are UInt32
            words = np.zeros(BATCH_WORDS + 1, dtype=np.uint32)
            words[:n], words[BATCH_WORDS] = chunk, address
            vrs = (fmi3ValueReference * 2)(vr["memory.data"], vr["memory.address"])
            self.fmu.fmi3SetUInt32(self.fmu.component, vrs, 2, words.ctypes.data_as(POINTER(c_uint32)), BATCH_WORDS + 1)
            self.fmu.setInt32([vr["memory.count"], vr["memory.strobe"]], [n, strobe])

    # ---- host time (docs/host-time.md, docs/decisions.md "Host time") ----

    def _grid_ns(self) -> Tuple[int, int]:
        """(the next cycle's time, the cycle time) in whole ns. The grid's times are whole
        microseconds (the sample time register is, and the grid starts at 0 and restarts
        only at its own cycles), so rounding the FMU's doubles to the microsecond is exact."""
        if self.fmi_version == 2:
            self.fmu.fmi2GetReal(self.fmu.component, self._grid_vrs, 3, self._grid)
        else:
            self.fmu.fmi3GetFloat64(self.fmu.component, self._grid_vrs, 3, self._grid, 3)
        return round(self._grid[1] * 1e6) * 1000, round(self._grid[2] * 1e6) * 1000

    def _last_cycle_ns(self) -> int:
        """The time of the last cycle run: the next one's less a cycle."""
        next_ns, cycle_ns = self._grid_ns()
        return max(next_ns - cycle_ns, 0)

    def _run_due(self) -> None:
        """Runs every cycle of the grid whose time is at or before the host clock."""
        while True:
            due = hosttime.cycles_due(self._host_ns, *self._grid_ns())
            if not due:
                return
            # one step; if a script's SetSampleTime moved the grid inside it, the loop runs what is still due
            self._step(due)

    def _timed_batch(self, words: List[int]) -> Tuple[int, List[int]]:
        """batch() with host time: each command of the batch is a transfer of its own, split as the
        FMU's dispatcher splits a batch (an unknown opcode, or a command short of data words, ends it
        with the words after it). Per command: the request's time passes, the cycles due run, the
        command executes, the reply's time passes. Returns the first error and the replies, as the
        batch would."""
        parts, i = [], 0
        while i < len(words):
            c = OPCODES.get(field_ex(words[i], "PMDInstructionOpcode"))
            end = len(words) if c is None or len(words) - i - 1 < c.arg_words else i + 1 + c.arg_words
            parts.append((words[i:end], c))
            i = end
        room = sum(c.reply_words for _w, c in parts if c)
        if room > BATCH_WORDS:
            raise ValueError(
                f"a timed batch's replies may pass host.reply[{BATCH_WORDS}] ({room} words): each "
                "command is its own transfer, so the FMU cannot refuse the one that passes; split the "
                "batch; nothing was sent"
            )
        first, replies = 0, []
        for part, _c in parts:
            self._host_ns += self.host_interface.request_ns(len(part))
            self._run_due()
            error, reply = self._send(part)
            self._host_ns += self.host_interface.reply_ns(len(reply), error != 0)
            first = first or error
            replies += reply
        return first, replies

    @property
    def host_time_ns(self) -> int:
        """The host clock: whole ns since the chip's time 0. Commands (with a host interface
        other than none), wait() and run() move it."""
        return self._host_ns

    @property
    def host_time(self) -> float:
        """The host clock in s (host_time_ns / 1e9, for printing: the clock itself is whole ns)."""
        return self._host_ns / hosttime.NS_PER_S

    @_refusals
    def wait(self, seconds) -> None:
        """Host time passes without a command (a host program's sleep): the host clock moves on
        by `seconds` (an int, float or Fraction; rounded to the nearest ns) and the chip runs
        every cycle now due. Works with every host interface, none included."""
        self.wait_ns(hosttime.ns_of(seconds, "wait: seconds"))

    @_refusals
    def wait_ns(self, nanoseconds: int) -> None:
        """wait() in whole ns."""
        ns = integer(nanoseconds, "wait_ns: nanoseconds")
        if ns < 0:
            raise ValueError(f"wait_ns: {ns} ns is negative")
        self._host_ns += ns
        self._run_due()

    @_refusals
    def wait_for_interrupt(self, timeout=None) -> bool:
        """Waits for the host interrupt line (host.interrupt), as a host's interrupt handler
        would: the chip runs cycle by cycle until one raises it, and the host clock moves to
        that cycle's time (the host sees the line at once). True at once if it is already
        high; False if `timeout` s (None: no limit) of host time pass first."""
        limit = None if timeout is None else self._host_ns + hosttime.ns_of(timeout, "wait_for_interrupt: timeout")
        while not self.get("host.interrupt"):
            next_ns, _cycle_ns = self._grid_ns()
            if limit is not None and next_ns > limit:
                self._host_ns = max(self._host_ns, limit)
                self._run_due()
                return False
            self._step(1)
            self._host_ns = max(self._host_ns, next_ns)
        return True

    @_refusals
    def wait_for(self, mask: int, axis: int = 0, timeout=None) -> Optional[int]:
        """Polls GetEventStatus on `axis` until a bit of `mask` is set, as a C-Motion host loop does
        (while not (status & mask): status = GetEventStatus), natively (host_port.c): each poll a
        command with its host time, so a polled move costs about its chip cycles. With the host
        interface none, commands take no chip time: one cycle runs after each unsatisfied poll (as
        chip.run(1)). Returns the event status that had a bit of mask; None if `timeout` s (None: no
        limit) of host time passed first. A refused poll raises PMDError."""
        mask = integer(mask, "wait_for: mask")
        if not 0 < mask <= 0xFFFF:
            raise ValueError(f"wait_for: mask {mask} is not a 16-bit event mask")
        axis = axis_number(axis)
        limit = -1 if timeout is None else self._host_ns + hosttime.ns_of(timeout, "wait_for: timeout")
        if limit >= 1 << 63:  # the native loop's int64 ns would wrap: 2^64 ns + 1 ms timed out after 1 ms
            raise ValueError(f"wait_for: timeout = {timeout!r} s reaches past the host clock's 2^63 ns")
        if self._recording:
            recording.close(self)
        get = COMMANDS["GetEventStatus"]
        logged = len(self.messages)
        r = host_port.functions()[2](self._port, 1, instruction_word(get.opcode, axis), mask, limit)
        if r & host_port.TIMEOUT and not r & host_port.FAILED:
            return None
        if r >> 32 != 1 << 16:
            return self._fast_trouble(r, get, logged)
        return (r >> 16) & 0xFFFF

    def wait_for_motion_complete(self, axis: int = 0, timeout=None) -> Optional[int]:
        """wait_for(PMDEventMotionCompleteMask, axis, timeout): polls until the axis's motion is complete."""
        return self.wait_for(CONSTANTS["PMDEventMotionCompleteMask"], axis, timeout)

    # ---- time ----

    @_refusals
    def run(
        self,
        cycles: int,
        record: Sequence[str] = (),
        out: Optional[np.ndarray] = None,
        to: Union[str, Path, None] = None,
        chunk: int = 1 << 16,
    ) -> Optional[np.ndarray]:
        """Advances the chip by `cycles` cycles. With record, returns a structured
        array: row i holds the outputs as the i-th cycle left them, in a `cycle`
        column (chip time) and one field per requested FMU variable, of its width
        (variables.csv's FMI 3 type: axis1.motorCommand int16, io.output[3] uint16);
        an array's element goes by its FMI 2 name ("io.output[3]") in FMI 3 too.

        The FMU records the rows itself (record.data, record.columns: one doStep per
        record.capacity cycles, written straight into the result where it lends the
        memory for them: pmdfmu_fmi2SetRecordBuffer, pmdfmu_fmi3SetRecordBuffer);
        the rows are what a master stepping cycle by cycle would read, also where a
        script's SetSampleTime changes the grid (that chunk is redone cycle by cycle
        from a saved FMU state). Recording `time`, or an FMU without record.columns,
        runs the harness's native loop (native/record_loop.c: per cycle one doStep and one
        get per FMI type of the FMU's own functions). Commanded positions, velocities
        and accelerations only (chip.RECORDED) are fastest; docs/performance.md,
        "Recording" (pmdfmu.recording.Recorder).
        A failed FMI call raises FMURefusal (FMPy's FMICallException, with the FMU's
        messages); a name given twice or not an FMU variable raises ValueError
        before any cycle runs. Interrupted (Ctrl-C), the chip stays exact: its next
        run records what a fresh chip at the same cycle records.

        out: the array to record into, returned (a result of a former run with the
        same `record`, or np.empty(cycles, dtype=its dtype)): a long recording that
        reuses its array spares the page faults of a fresh one (docs/performance.md,
        "Recording"). Its rows are overwritten whole; one of another type or length,
        or read-only, raises ValueError before any cycle runs.

        A run of 200 000 cycles or more shows a progress bar on standard error when it
        lasts over a second and standard error is a terminal (pmdfmu.progress.show:
        always or never); it then runs in parts, which record the same rows.

        to: a .npy file's path to write the rows to as they come, `chunk` rows at a time through one
        array of chunk rows, so that memory stays that chunk whatever `cycles` (docs/performance.md,
        "Recording to disk"); returns None, and np.load(to) (mmap_mode="r" for a long run) gives what
        run(cycles, record) would have returned. The file appears whole when the run ends (written
        beside it and renamed, files.replaced); a run that fails or is interrupted leaves none."""
        cycles = integer(cycles, "run: cycles")  # never rounded: run(2.5) used to run 2 cycles
        if cycles < 0:
            raise ValueError("cycles must be >= 0")
        if out is not None and not record:
            raise ValueError("run: out= needs record=: the array receives the recorded rows")
        if to is not None and (out is not None or not record or chunk < 1):
            raise ValueError("run: to= needs record=, no out=, and a chunk of at least 1 row")
        try:
            if to is not None:
                return self._run_to(cycles, list(record), Path(to), int(chunk))
            if cycles >= progress.CHIP_RUN_CYCLES and progress.wanted():
                return self._run_in_parts(cycles, record, out)
            return self._run(cycles, record, out)
        finally:
            if cycles:  # the host clock moves up to the last cycle run
                self._host_ns = max(self._host_ns, self._last_cycle_ns())

    def _run_in_parts(self, cycles: int, record: Sequence[str], out: Optional[np.ndarray]) -> np.ndarray:
        """run() with a progress bar: about a hundred runs into one array (a run split anywhere records
        what one run does: docs/performance.md)."""
        if record:
            _where, dtype = self._columns(list(record))
            if out is not None:
                _check_out(out, cycles, dtype)
            else:
                out = np.empty(cycles, dtype=dtype)
        part, done = max(cycles // 100, 50_000), 0
        with progress.bar("chip.run", total=cycles) as bar:
            while done < cycles:
                n = min(part, cycles - done)
                self._run(n, record, out[done : done + n] if record else None)
                done += n
                bar.update(n)
        return out if record else np.zeros(0, dtype=[CYCLE])

    def _run_to(self, cycles: int, names: List[str], path: Path, chunk: int) -> None:
        """run(to=path): the .npy header for `cycles` rows, then the rows a chunk at a time, recorded into one
        array of `chunk` rows (the recorder's out=) and written from it."""
        from .files import replaced

        where, dtype = self._columns(names)
        buffer = np.empty(min(chunk, max(cycles, 1)), dtype=dtype)
        with replaced(path) as f:  # the file appears whole, or not at all
            rows = recording.NpyFile(f, dtype, cycles)
            while rows.count < cycles:
                n = min(chunk, cycles - rows.count)
                rows.write(self.recorder(self, names, where, dtype).run(n, buffer[:n]))
            rows.close()

    def _run(self, cycles: int, record: Sequence[str], out: Optional[np.ndarray]) -> np.ndarray:
        if not record:
            if cycles:
                self._step(cycles)
            return np.zeros(0, dtype=[CYCLE])
        names = list(record)
        where, dtype = self._columns(names)
        if out is not None:
            _check_out(out, cycles, dtype)
        return self.recorder(self, names, where, dtype).run(cycles, out)

    def _columns(self, names: List[str]) -> Tuple[Dict[str, Tuple[str, int]], np.dtype]:
        """run(record=names)'s checks, before any cycle runs: where each column is read (variable,
        element: in FMI 3 an array's element, "io.output[3]", is read with its whole array) and the
        rows' type (a name given twice is numpy's ValueError). Kept per set of names for every Chip of
        the FMU file: making the row type again costs as long as 150 recorded cycles."""
        key = (self.fmi_version,) + tuple(names)
        known = self._recorded.get(key)  # one read: another thread may clear the dict
        if known is not None:
            return known
        where = {}
        for name in names:
            element = _array_element(self.variables, name) if self.fmi_version == 3 else None
            if name not in DTYPES or (name not in self.variables and not element):
                raise ValueError(f"run: record={name!r} is not a variable of the FMU{self._nearest(name)}")
            where[name] = element or (name, 0)
        known = where, np.dtype([CYCLE] + [(n, DTYPES[n]) for n in names])
        if len(self._recorded) >= 16:
            self._recorded.clear()
        self._recorded[key] = known
        return known
