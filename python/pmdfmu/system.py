# SPDX-License-Identifier: BSD-2-Clause
"""The chip and a plant as one system, stepped cycle by cycle in the harness's native library
(native/system.c): pmdfmu.System(chip, plant=None, wiring=None, algorithm="gauss-seidel"), the plant a
pmdfmu.Plant (its FMU and parameters) or the plant FMU's path.
system.run(cycles, record=["chip.axis1.position", "plant.encoderCount"]) makes the calls that
examples/systems' Python master makes through FMPy (run_master: per step the connections' gets and
sets, each FMU's doStep from k * step, Gauss-Seidel or Jacobi), over both FMUs' own FMI functions, and
returns a structured array as chip.run does (docs/systems.md)."""

from __future__ import annotations

from ctypes import POINTER, c_double, c_int, c_int64, c_size_t, c_void_p
from functools import lru_cache
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import native
from .fixed import integer

# the axis-1 loop: the chip's motor command drives the plant, its encoder count is the chip's actual position
WIRING = {"chip.axis1.motorCommand": "plant.motorCommand", "plant.encoderCount": "chip.axis1.actualPosition"}
ALGORITHMS = ("gauss-seidel", "jacobi")
# an FMI type: the native loop's PmdLoopType, the FMI function's type name, the row's numpy type
TYPES = {
    2: {
        "Real": (native.DOUBLE, "Real", np.float64),
        "Integer": (native.INT32, "Integer", np.int32),
        "Boolean": (native.INT, "Boolean", np.bool_),
    },
    3: {
        "Float64": (native.DOUBLE, "Float64", np.float64),
        "Int32": (native.INT32, "Int32", np.int32),
        "UInt32": (native.UINT32, "UInt32", np.uint32),
        "Int16": (native.INT16, "Int16", np.int16),
        "UInt16": (native.UINT16, "UInt16", np.uint16),
        "Boolean": (native.BOOL, "Boolean", np.bool_),
    },
}


def _values(numpy_type) -> Optional[Tuple[int, int]]:
    """The values an integer or Boolean FMI type (its row's numpy type in TYPES) holds; None for a double."""
    if numpy_type is np.bool_:
        return 0, 1
    if np.issubdtype(numpy_type, np.integer):
        info = np.iinfo(numpy_type)
        return int(info.min), int(info.max)
    return None


def _carries(output_type, input_type) -> bool:
    """Whether every value of the output's numpy type reaches an input of input_type unchanged (an Int16 into
    an Int32, an Integer into a Real: a double holds every 32-bit integer); native/system.c would truncate a
    Real into an Integer and wrap an Int32 into an Int16, silently."""
    output, into = _values(output_type), _values(input_type)
    if into is None:
        return True
    return output is not None and into[0] <= output[0] and output[1] <= into[1]


@lru_cache(maxsize=None)
def _runner():
    run = native.library().pmd_system_run
    run.argtypes = [
        POINTER(native.SystemOp),
        c_size_t,
        POINTER(native.SystemValue),
        POINTER(native.SystemColumn),
        c_size_t,
        c_double,
        c_double,
        c_int64,
        c_size_t,
        c_void_p,
        c_size_t,
        POINTER(native.Stop),
    ]
    run.restype = c_int
    return run


class Plant:
    """The plant of a System, as Chip names the chip: its FMU and its parameters by name.
    pmdfmu.Plant(loadInertia=3e-5, encoderLines=1000) is the build's pmdplant (of the chip's FMI version,
    beside the chip's FMU) with those parameters; pmdfmu.Plant("motor.fmu", ...) another plant FMU. The
    System instantiates it, in the chip's FMI version (docs/systems.md)."""

    def __init__(self, fmu: Union[str, Path, None] = None, **parameters):
        self.fmu = Path(fmu) if fmu else None
        self.parameters = dict(parameters)

    def path(self, chip) -> Path:
        """The plant FMU's file for this chip: its own, else the build's pmdplant beside the chip's FMU."""
        return self.fmu or chip.path.with_name(f"pmdplant-fmi{chip.fmi_version}.fmu")

    def __repr__(self) -> str:
        given = [repr(str(self.fmu))] if self.fmu else []
        return f"Plant({', '.join(given + [f'{k}={v!r}' for k, v in self.parameters.items()])})"


class PlantInstance:
    """A plant FMU instance (pmdplant by default, docs/systems.md) at the chip's time, its parameters set
    and initialized, its inputs given by `inputs` before the end of initialization."""

    def __init__(self, path: Path, fmi_version: int, start: float, parameters: dict, inputs):
        from fmpy.fmi1 import FMICallException

        from .chip import FMURefusal, LogMessage, STATUS_NAMES, _Slave2, _Slave3, _unpack, _UNPACKED_LOCK

        unpacked, functions = _unpack(path, fmi_version)
        self.path, self.fmi_version, self.messages = path, fmi_version, []
        self.variables = unpacked.variables
        kwargs = dict(
            functions=functions,
            guid=unpacked.model_description.guid,
            unzipDirectory=unpacked.unzipdir,
            modelIdentifier=unpacked.model_description.coSimulation.modelIdentifier,
            instanceName="plant",
        )

        def log(status, message):
            name = STATUS_NAMES[status] if 0 <= status < 5 else str(status)
            self.messages.append(LogMessage(name, "", message.decode(errors="replace")))

        with _UNPACKED_LOCK:
            self.fmu = (_Slave2 if fmi_version == 2 else _Slave3)(**kwargs)
        if fmi_version == 2:
            from fmpy.fmi2 import fmi2CallbackFunctions, fmi2CallbackLoggerTYPE

            self._callbacks = fmi2CallbackFunctions()
            self._callbacks.logger = fmi2CallbackLoggerTYPE(lambda env, name, status, cat, msg: log(status, msg))
            self.fmu.instantiate(callbacks=self._callbacks)
            self.fmu.setupExperiment(startTime=start)
        else:
            self.fmu.instantiate(logMessage=lambda env, status, cat, msg: log(status, msg))
        try:  # a refusal says the plant's reason, as Chip's do, and frees the instance
            for name, value in parameters.items():
                self.set(name, value)
            if fmi_version == 2:
                self.fmu.enterInitializationMode()
            else:
                self.fmu.enterInitializationMode(startTime=start)
            inputs(self)
            self.fmu.exitInitializationMode()
        except BaseException as e:
            self.fmu.freeInstance()
            self.fmu = None
            if isinstance(e, FMICallException):
                refused = [m.message for m in self.messages if m.status != "OK"]
                raise FMURefusal(e.function, e.status, refused) from None
            raise

    def set(self, name: str, value) -> None:
        v = self.variables.get(name)
        if v is None:
            raise ValueError(f"plant: {name!r} is no variable of {self.path.name}")
        getattr(self.fmu, "set" + v.type)([v.valueReference], [value])

    def get(self, name: str):
        v = self.variables[name]
        return getattr(self.fmu, "get" + v.type)([v.valueReference])[0]

    def close(self) -> None:
        if self.fmu is not None:
            self.fmu.terminate()
            self.fmu.freeInstance()
            self.fmu = None


def _plant_variables(path: Path, fmi_version: int) -> dict:
    """The plant FMU's variables by name, read before it is instantiated (the wiring is checked first)."""
    from .chip import _unpack

    return _unpack(path, fmi_version)[0].variables


class System:
    """The chip and a plant, connected by `wiring` ({"chip.<output>": "plant.<input>", "plant.<output>":
    "chip.<input>"}: the axis-1 loop, WIRING, when None), stepped together one chip cycle a step:
    "gauss-seidel" steps the chip, then the plant with the chip's new outputs; "jacobi" sets every input
    from the outputs of the step before, then steps both. plant: a pmdfmu.Plant (its FMU and parameters),
    or the plant FMU's path (None: the build's pmdplant of the chip's FMI version, beside the chip's FMU)
    with plant_parameters its parameters: System(chip, Plant(path, **p)) is System(chip, path, **p).
    The communication step is the chip's cycle time when the system is made, from the chip's time then:
    a chip made for a plant (loopback=False) and not run yet is what examples/systems' master steps."""

    def __init__(
        self,
        chip,
        plant: Union[str, Path, Plant, None] = None,
        wiring: Optional[Dict[str, str]] = None,
        algorithm: str = "gauss-seidel",
        **plant_parameters,
    ):
        if algorithm not in ALGORITHMS:
            raise ValueError(f"algorithm: gauss-seidel or jacobi, not {algorithm!r}")
        self.chip, self.algorithm = chip, algorithm
        self.wiring = dict(WIRING if wiring is None else wiring)
        if isinstance(plant, Plant) and plant_parameters:
            raise TypeError("System: the plant's parameters go in its Plant, or as keywords with a path, not both")
        plant = plant if isinstance(plant, Plant) else Plant(plant, **plant_parameters)
        version = chip.fmi_version
        self.start, self.step = chip.get("time"), chip.cycle_time
        self._steps = 0
        self._plans: Dict[tuple, tuple] = {}  # run()'s operations per set of recorded names (_plan)
        for a, b in self.wiring.items():
            for end in (a, b):
                if end.split(".", 1)[0] not in ("chip", "plant") or "." not in end:
                    raise ValueError(f"wiring: {end!r} is not chip.<variable> or plant.<variable>")
        self._variables = {"chip": chip.variables, "plant": _plant_variables(plant.path(chip), version)}
        self._check_wiring()
        into_plant = [(a, b) for a, b in self.wiring.items() if b.startswith("plant.")]
        self.plant = PlantInstance(
            plant.path(chip),
            version,
            self.start,
            plant.parameters,
            lambda p: [p.set(b[6:], chip.get(a[5:])) for a, b in into_plant],
        )
        self._fmus = {"chip": chip.fmu, "plant": self.plant.fmu}

    def _check_wiring(self) -> None:
        """Each wire from an output to an input of the other FMU, of a type that carries the output's every
        value, and no input driven twice: else ValueError naming the wire (a second wire into one input
        overwrote the first silently; a Real into an Integer was truncated)."""
        driven: Dict[str, str] = {}
        for a, b in self.wiring.items():
            (source, out), (target, into) = self._variable(a), self._variable(b)
            if source == target:
                raise ValueError(f"wiring: {a} -> {b}: a wire goes from one FMU to the other")
            if out.causality != "output" or into.causality != "input":
                raise ValueError(
                    f"wiring: {a} -> {b}: a wire goes from an output to an input, not from {out.causality} "
                    f"{a} to {into.causality} {b}"
                )
            carried = TYPES[self.chip.fmi_version]
            if out.type not in carried or into.type not in carried:  # a String was a bare KeyError 'String'
                raise ValueError(
                    f"wiring: {a} -> {b}: a {out.type} output into a {into.type} input: a wire carries "
                    f"{', '.join(carried)} values"
                )
            if not _carries(carried[out.type][2], carried[into.type][2]):
                raise ValueError(
                    f"wiring: {a} -> {b}: a {out.type} does not fit a {into.type} input unchanged (it would be "
                    "truncated or wrap): wire variables of types that hold the output's values"
                )
            if b in driven:
                raise ValueError(f"wiring: {b} is driven by both {driven[b]} and {a}")
            driven[b] = a

    def close(self) -> None:
        self.plant.close()

    def __enter__(self) -> "System":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _variable(self, path: str):
        component, _, name = path.partition(".")
        v = self._variables.get(component, {}).get(name)
        if v is None or getattr(v, "dimensions", None):
            raise ValueError(f"{path!r} is no scalar variable of the {component or '?'} FMU")
        return component, v

    def _op(self, kind: int, path: str, value: int) -> native.SystemOp:
        component, v = self._variable(path)
        fmu, version = self._fmus[component], self.chip.fmi_version
        loop_type, type_name, _ = TYPES[version][v.type]
        name = f"fmi{version}{'Get' if kind == native.SYSTEM_GET else 'Set'}{type_name}"
        return native.SystemOp(
            kind, loop_type, native.address(fmu._functions[name]), fmu.component, v.valueReference, value
        )

    def _step_op(self, component: str) -> native.SystemOp:
        fmu, version = self._fmus[component], self.chip.fmi_version
        return native.SystemOp(
            native.SYSTEM_STEP, version, native.address(fmu._functions[f"fmi{version}DoStep"]), fmu.component, 0, 0
        )

    def dtype(self, record: Sequence[str]) -> np.dtype:
        """The rows' type: `step` (1, 2, ... over the system's life), then each column: a chip register at its
        width (chip.DTYPES, as chip.run records it), a plant variable at its FMI type's."""
        from .chip import DTYPES

        fields = [("step", np.int64)]
        for path in record:
            component, v = self._variable(path)
            name = path[5:]
            fields.append(
                (
                    path,
                    DTYPES[name] if component == "chip" and name in DTYPES else TYPES[self.chip.fmi_version][v.type][2],
                )
            )
        return np.dtype(fields)

    def _plan(self, names: tuple) -> tuple:
        """run(record=names)'s operations and columns, made once per set of names: (the rows' type, the ops and
        their count, the columns and their count, the values' count)."""
        dtype = self.dtype(names)
        ops: List[native.SystemOp] = []
        transfers = list(self.wiring.items())
        for a, b in transfers:
            self._variable(a), self._variable(b)
        if self.algorithm == "jacobi":
            for i, (a, b) in enumerate(transfers):
                ops += [self._op(native.SYSTEM_GET, a, i), self._op(native.SYSTEM_SET, b, i)]
        for component in ("chip", "plant"):
            if self.algorithm == "gauss-seidel":
                for i, (a, b) in enumerate(transfers):
                    if b.startswith(component + "."):
                        ops += [self._op(native.SYSTEM_GET, a, i), self._op(native.SYSTEM_SET, b, i)]
            ops.append(self._step_op(component))
        columns = []
        for j, path in enumerate(names):
            slot = len(transfers) + j
            ops.append(self._op(native.SYSTEM_GET, path, slot))
            field = dtype.fields[path]
            columns.append(native.SystemColumn(slot, field[1], field[0].itemsize, int(field[0].kind == "f")))
        return (
            dtype,
            (native.SystemOp * len(ops))(*ops),
            len(ops),
            (native.SystemColumn * max(len(columns), 1))(*columns),
            len(columns),
            len(transfers) + len(names),
        )

    def run(self, cycles: int, record: Sequence[str] = ()) -> np.ndarray:
        """Runs `cycles` steps (chip cycles); returns a row per step with the recorded outputs as the step
        left them (an empty array without record). A failed FMI call raises FMPy's FMICallException naming
        it, the steps before it run."""
        from fmpy.fmi1 import FMICallException

        from . import recording

        cycles = integer(cycles, "run: cycles")  # never rounded, nor left to ctypes to refuse
        if cycles < 0:
            raise ValueError("cycles must be >= 0")
        names = tuple(record)
        plan = self._plans.get(names)
        if plan is None:
            plan = self._plans[names] = self._plan(names)
        dtype, ops, n_ops, columns, n_columns, n_values = plan
        out = np.zeros(cycles if names else 0, dtype=dtype)
        if self.chip._recording:
            recording.close(self.chip)
        values = (native.SystemValue * n_values)()
        stop = native.Stop()
        failed = _runner()(
            ops,
            n_ops,
            values,
            columns,
            n_columns,
            self.start,
            self.step,
            self._steps,
            cycles,
            out.ctypes.data if names else None,
            dtype.itemsize,
            stop,
        )
        self._steps += stop.done if failed else cycles
        self.chip._host_ns = max(self.chip._host_ns, self.chip._last_cycle_ns())
        if failed:
            op = ops[stop.call] if 0 <= stop.call < n_ops else None
            raise FMICallException(function=_op_name(op, self.chip.fmi_version), status=stop.status)
        return out


def _op_name(op, version: int) -> str:
    if op is None:
        return "pmd_system_run"
    if op.kind == native.SYSTEM_STEP:
        return f"fmi{version}DoStep"
    return f"fmi{version}{'Get' if op.kind == native.SYSTEM_GET else 'Set'}"
