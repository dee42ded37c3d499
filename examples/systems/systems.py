# SPDX-License-Identifier: BSD-2-Clause
"""The chip and the plant as one system (docs/systems.md), from one description,
SystemStructure.ssd beside this file, in three forms and four masters:

  (a) an SSP: the .ssd, the two FMI 2 FMUs (the chip's with the profile
      move.script packed into it, so no tool has to set a String) and the chip's
      parameter set (loopback false) zipped into one .ssp, run by FMPy's SSP
      support (fmpy.ssp) or by libcosim (libcosimpy);
  (b) a container FMU (fmpy.container_fmu, FMI 3, the two FMI 3 FMUs inside)
      that any tool importing one FMU runs, here FMPy's simulate_fmu;
  (c) a plain master in Python on FMPy's FMU classes, FMI 2 or 3, stepping
      Gauss-Seidel (the chip, then the plant with the chip's new command) or
      Jacobi (both on the values of the step before).

Every run returns the same table: one row per communication step (one chip
cycle), `step` 1..N and the value of each output connector of the .ssd after
that step, named `component.connector`.

    python examples/systems/systems.py ssp --out move.ssp
    python examples/systems/systems.py container --out move-container.fmu
    python examples/systems/systems.py run {gauss-seidel,jacobi,fmpy-ssp,libcosim,container} [--fmi-version 2|3]

The .ssd wires the chip's Real axis1.motorOutput to the plant's Real
motorOutput; motor="motorCommand" (run --motor motorCommand) wires the Integer
motor command of a 16-bit bus instead, for the plain master.
"""

import argparse
import atexit
import contextlib
import shutil
import tempfile
import uuid
import zipfile
from pathlib import Path
from typing import Dict, List, NamedTuple, Tuple

import numpy as np
from lxml import etree

import pmdfmu

HERE = Path(__file__).resolve().parent
SSD = HERE / "SystemStructure.ssd"
SCRIPT = HERE / "move.script"
NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
}
MASTERS = ("gauss-seidel", "jacobi", "fmpy-ssp", "libcosim", "container")


MOTOR_WIRES = {  # the motor's connection: the .ssd's Real one, or the Integer one of a 16-bit bus
    "motorOutput": ("axis1.motorOutput", "motorOutput"),
    "motorCommand": ("axis1.motorCommand", "motorCommand"),
}


def script_value() -> str:
    """The chip's `script` parameter for the profile, for a chip FMU without it packed: move.script's
    text (a value holding a line feed is the script itself, docs/scripts.md)."""
    return SCRIPT.read_text()


def parameters() -> Dict[str, Dict[str, object]]:
    """Component -> parameter -> value: what the .ssp's parameter set sets (the profile is packed
    into the chip's FMU)."""
    return {"chip": {"loopback": False}}


_PACKED: Dict[int, Path] = {}


def profile_fmu(fmi_version: int) -> Path:
    """The chip's FMU with move.script packed into it (pmdfmu pack, docs/scripts.md): the .ssd's
    resources/move.fmu; made once per process, in a temporary folder removed at exit."""
    if fmi_version not in _PACKED:
        from pmdfmu.pack import pack

        folder = Path(tempfile.mkdtemp(prefix="pmdfmu-systems-"))
        atexit.register(shutil.rmtree, folder, True)
        _PACKED[fmi_version] = pack(SCRIPT, folder / f"move-fmi{fmi_version}.fmu", fmi_version).fmu
    return _PACKED[fmi_version]


# ---- the system description -------------------------------------------------------


class Connector(NamedTuple):
    component: str
    name: str
    kind: str  # input or output

    @property
    def path(self) -> str:
        return f"{self.component}.{self.name}"


class System(NamedTuple):
    components: Dict[str, str]  # name -> source inside the .ssp
    connectors: List[Connector]
    connections: List[Tuple[Connector, Connector]]  # (from an output, to an input)
    stop_time: float
    step_size: float

    @property
    def outputs(self) -> List[Connector]:
        return [c for c in self.connectors if c.kind == "output"]

    @property
    def steps(self) -> int:
        return round(self.stop_time / self.step_size)


def read_system(ssd: Path = SSD, motor: str = "motorOutput") -> System:
    """The system the .ssd describes; motor="motorCommand" wires the Integer motor command instead of
    the Real motorOutput (MOTOR_WIRES)."""
    if motor not in MOTOR_WIRES:
        raise ValueError(f"motor: {' or '.join(MOTOR_WIRES)}, not {motor!r}")
    root = etree.parse(str(ssd)).getroot()
    components, connectors = {}, []
    for c in root.iterfind("ssd:System/ssd:Elements/ssd:Component", NS):
        components[c.get("name")] = c.get("source")
        connectors += [
            Connector(c.get("name"), k.get("name"), k.get("kind"))
            for k in c.iterfind("ssd:Connectors/ssd:Connector", NS)
        ]
    wired, wire = MOTOR_WIRES["motorOutput"], MOTOR_WIRES[motor]
    connectors = [Connector("plant", wire[1], k.kind) if k == ("plant", wired[1], "input") else k for k in connectors]
    by_path = {k.path: k for k in connectors}
    connections = []
    for c in root.iterfind("ssd:System/ssd:Connections/ssd:Connection", NS):
        start, end = c.get("startConnector"), c.get("endConnector")
        if (c.get("startElement"), start, c.get("endElement"), end) == ("chip", wired[0], "plant", wired[1]):
            start, end = wire
        connections.append((by_path[f"{c.get('startElement')}.{start}"], by_path[f"{c.get('endElement')}.{end}"]))
    experiment = root.find("ssd:DefaultExperiment", NS)
    step = experiment.find(".//osp:FixedStepAlgorithm", NS).get("baseStepSize")
    return System(components, connectors, connections, float(experiment.get("stopTime")), float(step))


def fmu_of(source: str, fmi_version: int) -> Path:
    """The FMU a component's source names: resources/pmdplant.fmu is pmdplant-fmi2.fmu beside
    pmdfmu.default_fmu(2), and so on; resources/move.fmu the chip's with move.script packed
    (profile_fmu)."""
    if Path(source).stem == SCRIPT.stem:
        return profile_fmu(fmi_version)
    return pmdfmu.default_fmu(fmi_version).with_name(f"{Path(source).stem}-fmi{fmi_version}.fmu")


def following_error(result: np.ndarray) -> np.ndarray:
    """For steps 2..N: the chip's commanded position minus the encoder count its
    cycle sampled, that of the step before (the chip reads its input as the
    cycle starts)."""
    return result["chip.axis1.commandedPosition"][1:] - result["plant.encoderCount"][:-1]


def motion_complete(result: np.ndarray):
    """The first step after which axis 1's motion-complete event is set, or None."""
    done = np.flatnonzero(result["chip.axis1.eventStatus"] & pmdfmu.PMDEventMotionCompleteMask)
    return int(result["step"][done[0]]) if len(done) else None


def result_table(system: System, rows: List[Dict[str, object]]) -> np.ndarray:
    """The common result: step 1..N and every output connector."""

    def dtype(value):
        return np.float64 if isinstance(value, float) else np.int64

    fields = [("step", np.int64)] + [(c.path, dtype(rows[0][c.path])) for c in system.outputs]
    return np.array([(k, *(row[c.path] for c in system.outputs)) for k, row in enumerate(rows, start=1)], dtype=fields)


# ---- (a) the SSP ----------------------------------------------------------------------


def ssv(name: str, values: Dict[str, object]) -> bytes:
    """An SSP parameter set; a string keeps its newlines (as &#10;)."""
    root = etree.Element(f"{{{NS['ssv']}}}ParameterSet", nsmap={"ssv": NS["ssv"]}, version="1.0", name=name)
    params = etree.SubElement(root, f"{{{NS['ssv']}}}Parameters")
    for key, value in values.items():
        p = etree.SubElement(params, f"{{{NS['ssv']}}}Parameter", name=key)
        if isinstance(value, bool):
            etree.SubElement(p, f"{{{NS['ssv']}}}Boolean", value="true" if value else "false")
        elif isinstance(value, int):
            etree.SubElement(p, f"{{{NS['ssv']}}}Integer", value=str(value))
        elif isinstance(value, float):
            etree.SubElement(p, f"{{{NS['ssv']}}}Real", value=repr(value))
        else:
            etree.SubElement(p, f"{{{NS['ssv']}}}String", value=str(value))
    return etree.tostring(root, xml_declaration=True, encoding="UTF-8", pretty_print=True)


def build_ssp(out: Path) -> Path:
    """The .ssp: SystemStructure.ssd, the FMI 2 FMUs and each component's
    parameter values, at the paths the .ssd names."""
    system = read_system()
    root = etree.parse(str(SSD)).getroot()
    bindings = {
        c.get("name"): c.find("ssd:ParameterBindings/ssd:ParameterBinding", NS)
        for c in root.iterfind("ssd:System/ssd:Elements/ssd:Component", NS)
    }
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        z.write(SSD, "SystemStructure.ssd")
        for source in system.components.values():
            z.write(fmu_of(source, 2), source)
        for name, values in parameters().items():
            z.writestr(bindings[name].get("source"), ssv(name, values))
    return out


@contextlib.contextmanager
def _fmpy_ssp_parameters():
    """FMPy's SSP master (fmpy.ssp.simulation) applies the parameter set it is
    given by `component.name` prefixes and compares a Boolean value with 0.0, so
    the text "false" sets true (docs/tools.md, FMPy): while the block runs, its
    set_value sets Booleans from their text."""
    from fmpy.ssp import simulation

    original = simulation.set_value

    def set_value(component, name, value):
        variable = component.variables[name]
        if variable.type == "Boolean":
            component.fmu.setBoolean([variable.valueReference], [value in (True, "true", "1")])
        else:
            original(component, name, value)

    simulation.set_value = set_value
    try:
        yield simulation
    finally:
        simulation.set_value = original


def run_fmpy_ssp(ssp: Path) -> np.ndarray:
    """(a) in FMPy's SSP support: a Jacobi master (every component steps on its
    inputs of the step before, then the connections pass the new outputs on)."""
    from fmpy.ssp.ssd import ParameterSet, Parameter, find_components, read_ssd

    system = read_system()
    ssd = read_ssd(str(ssp))
    merged = ParameterSet(name="bindings")
    for component in find_components(ssd.system):  # each component's own bindings, as its path
        for binding in component.parameterBindings:
            for parameter_set in binding.parameterValues:
                merged.parameters += [
                    Parameter(name=f"{component.name}.{p.name}", type=p.type, value=p.value)
                    for p in parameter_set.parameters
                ]
    with _fmpy_ssp_parameters() as simulation:
        out = simulation.simulate_ssp(
            str(ssp),
            stop_time=system.stop_time - system.step_size / 2,
            step_size=system.step_size,
            parameter_set=merged,
        )
    return result_table(system, [{c.path: out[c.path][k].item() for c in system.outputs} for k in range(len(out))])


def run_libcosim(ssp: Path) -> np.ndarray:
    """(a) in libcosim (libcosimpy): its fixed-step algorithm is Jacobi too."""
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    system = read_system()
    log_output_level(CosimLogLevel.WARNING)
    execution = CosimExecution.from_ssp_file(str(ssp))
    index = {s.name.decode(): s.index for s in execution.slave_infos()}
    variables = {name: {v.name.decode(): v for v in execution.slave_variables(i)} for name, i in index.items()}
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    rows = []
    for _ in range(system.steps):
        if not execution.step():
            raise RuntimeError("libcosim: a step failed")
        row = {}
        for c in system.outputs:
            v = variables[c.component][c.name]
            if v.type == CosimVariableType.REAL.value:
                row[c.path] = observer.last_real_values(index[c.component], [v.reference])[0]
            else:
                row[c.path] = observer.last_integer_values(index[c.component], [v.reference])[0]
        rows.append(row)
    execution.stop()
    return result_table(system, rows)


# ---- (b) the container FMU ----------------------------------------------------------


def build_container(out: Path) -> Path:
    """An FMI 3 container FMU (fmpy.container_fmu) of the .ssd's system with the
    FMI 3 FMUs: the chip's parameter values are its parameters' start values,
    the .ssd's output connectors its outputs. Its master is Jacobi (it steps
    every component, then passes the connections on)."""
    from fmpy import read_model_description
    from fmpy.container_fmu.cli import create_container_fmu
    from fmpy.container_fmu.config import Component, Configuration, Connection
    from fmpy.model_description import CoSimulation, DefaultExperiment, ModelDescription, ModelVariable, Unknown

    system = read_system()
    components, variables = {}, {}
    for name, source in system.components.items():
        filename = fmu_of(source, 3)
        md = read_model_description(filename)
        components[name] = Component(name=name, filename=filename, modelDescription=md)
        variables[name] = {v.name: v for v in md.modelVariables}
    model_variables = [ModelVariable(type="Float64", variability="continuous", causality="independent", name="time")]
    mappings = {}
    for name, values in parameters().items():
        for key, value in values.items():
            inner = variables[name][key]
            start = ("true" if value else "false") if isinstance(value, bool) else str(value)
            v = ModelVariable(
                type=inner.type,
                variability="fixed",
                causality="parameter",
                initial="exact",
                name=f"{name}.{key}",
                start=start,
            )
            model_variables.append(v)
            mappings[v] = [(components[name], inner)]
    outputs = []
    for c in system.outputs:
        inner = variables[c.component][c.name]
        v = ModelVariable(
            type=inner.type, variability=inner.variability, causality="output", initial="calculated", name=c.path
        )
        model_variables.append(v)
        mappings[v] = [(components[c.component], inner)]
        outputs.append(v)
    # the same system, FMUs and parameter values make the same token
    identity = "\n".join(
        [SSD.read_text(), repr(parameters())] + [components[n].modelDescription.instantiationToken for n in components]
    )
    md = ModelDescription(
        fmiVersion="3.0",
        modelName="servoLoop",
        instantiationToken=f"{{{uuid.uuid5(uuid.NAMESPACE_URL, identity)}}}",
        description="PMD motion processor (axis 1) and a DC motor with encoder, examples/systems/SystemStructure.ssd",
        defaultExperiment=DefaultExperiment(
            startTime="0", stopTime=str(system.stop_time), stepSize=str(system.step_size)
        ),
        coSimulation=CoSimulation(fixedInternalStepSize=system.step_size),
        modelVariables=model_variables,
    )
    md.outputs = [Unknown(variable=v, dependencies=[]) for v in outputs]
    md.initialUnknowns = [Unknown(variable=v, dependencies=[]) for v in outputs]
    connections = [
        Connection(
            components[a.component],
            [variables[a.component][a.name]],
            components[b.component],
            [variables[b.component][b.name]],
        )
        for a, b in system.connections
    ]
    configuration = Configuration(
        parallelDoStep=False,
        modelDescription=md,
        components=list(components.values()),
        connections=connections,
        variableMappings=mappings,
    )
    out = Path(out).resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as unzipdir:
        create_container_fmu(configuration, Path(unzipdir), out)
    _string_starts_as_elements(out)
    return out


def _string_starts_as_elements(fmu: Path) -> None:
    """FMPy's model description writer gives an FMI 3 String its start as an
    attribute; FMI 3 has it as <Start value=.../> elements (its schema refuses the
    attribute): rewrite the container's modelDescription.xml so."""
    with zipfile.ZipFile(fmu) as z:
        entries = {i.filename: z.read(i) for i in z.infolist()}
    root = etree.fromstring(entries["modelDescription.xml"])
    for v in root.iterfind("ModelVariables/String"):
        if "start" in v.attrib:
            etree.SubElement(v, "Start", value=v.attrib.pop("start"))
    entries["modelDescription.xml"] = etree.tostring(root, xml_declaration=True, encoding="UTF-8", pretty_print=True)
    with zipfile.ZipFile(fmu, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in entries.items():
            z.writestr(name, data)


def run_container(fmu: Path, log=None) -> np.ndarray:
    """(b) in FMPy, as one FMU. `log(instance, status, message)` receives the
    container's log messages (its components' among them)."""
    from fmpy import simulate_fmu

    system = read_system()
    logger = None
    if log:

        def logger(env, status, category, message):
            log("container", status, message.decode(errors="replace"))

    out = simulate_fmu(
        str(fmu),
        stop_time=system.stop_time,
        output_interval=system.step_size,
        output=[c.path for c in system.outputs],
        logger=logger,
    )
    rows = [{c.path: out[c.path][k].item() for c in system.outputs} for k in range(1, len(out))]  # row 0: start
    return result_table(system, rows[: system.steps])


# ---- (c) a plain FMPy master ----------------------------------------------------------


class _Instance:
    """One FMU of the system through FMPy's FMU2Slave / FMU3Slave, variables by name."""

    def __init__(self, name: str, filename: Path, fmi_version: int, logger):
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
        from fmpy.fmi3 import FMU3Slave

        md = read_model_description(filename)
        self.variables = {v.name: v for v in md.modelVariables}
        self.unzipdir = extract(filename)
        kwargs = dict(
            guid=md.guid,
            unzipDirectory=self.unzipdir,
            modelIdentifier=md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        if fmi_version == 2:
            self.fmu = FMU2Slave(**kwargs)
            self._callbacks = fmi2CallbackFunctions()  # the FMUs pass no printf arguments, '%' as "%%"
            self._callbacks.logger = fmi2CallbackLoggerTYPE(
                lambda env, instance, status, category, message: logger(
                    name, status, message.decode(errors="replace").replace("%%", "%")
                )
            )
            self.fmu.instantiate(callbacks=self._callbacks)
            self.fmu.setupExperiment(startTime=0.0)
        else:
            self.fmu = FMU3Slave(**kwargs)
            self.fmu.instantiate(
                logMessage=lambda env, status, category, message: logger(name, status, message.decode(errors="replace"))
            )
        self.fmi_version = fmi_version

    def set(self, name: str, value) -> None:
        v = self.variables[name]
        getattr(self.fmu, "set" + v.type)([v.valueReference], [value])

    def get(self, name: str):
        v = self.variables[name]
        return getattr(self.fmu, "get" + v.type)([v.valueReference])[0]

    def initialize(self) -> None:
        if self.fmi_version == 2:
            self.fmu.enterInitializationMode()
        else:
            self.fmu.enterInitializationMode(startTime=0.0)

    def close(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.unzipdir, ignore_errors=True)


def run_master(
    algorithm: str = "gauss-seidel", fmi_version: int = 2, log=None, values=None, motor: str = "motorOutput"
) -> np.ndarray:
    """(c) a plain master: one communication step per chip cycle, communication
    points n * step. "gauss-seidel" steps the components in the .ssd's order
    and sets each one's inputs just before its step (the plant integrates the
    cycle with the command the chip computed in it, as examples/closed_loop.py
    does); "jacobi" sets every input from the outputs of the step before, then
    steps all (the plant's command is one cycle older). `log(instance, status,
    message)` receives the FMUs' log messages; `values` replaces parameters()
    (component -> parameter -> value); motor: the motor's wire (read_system)."""
    if algorithm not in ("gauss-seidel", "jacobi"):
        raise ValueError(f"algorithm: gauss-seidel or jacobi, not {algorithm!r}")
    system = read_system(motor=motor)
    log = log or (lambda instance, status, message: print(f"[{instance}] {message}"))
    instances = {}
    try:
        for name, source in system.components.items():
            instances[name] = _Instance(name, fmu_of(source, fmi_version), fmi_version, log)
        for name, given in (parameters() if values is None else values).items():
            for key, value in given.items():
                instances[name].set(key, value)
        for instance in instances.values():
            instance.initialize()

        def transfer(into=None):  # connections into one component (or all), from the outputs as they are
            for a, b in system.connections:
                if into is None or b.component == into:
                    instances[b.component].set(b.name, instances[a.component].get(a.name))

        transfer()  # the start values, as initialization leaves them
        for instance in instances.values():
            instance.fmu.exitInitializationMode()
        rows = []
        for k in range(system.steps):
            t = k * system.step_size
            if algorithm == "jacobi":
                transfer()
            for name, instance in instances.items():
                if algorithm == "gauss-seidel":
                    transfer(into=name)
                instance.fmu.doStep(t, system.step_size)
            rows.append({c.path: instances[c.component].get(c.name) for c in system.outputs})
        return result_table(system, rows)
    finally:
        for instance in instances.values():
            instance.close()


def run(master: str, fmi_version: int = 2, workdir: Path = None, motor: str = "motorOutput") -> np.ndarray:
    """Any of the masters, building what it needs in workdir (motor: the plain master's motor wire)."""
    if master in ("gauss-seidel", "jacobi"):
        return run_master(master, fmi_version, motor=motor)
    with tempfile.TemporaryDirectory() as tmp:
        workdir = Path(workdir or tmp)
        if master == "container":
            return run_container(build_container(workdir / "servoLoop.fmu"))
        ssp = build_ssp(workdir / "servoLoop.ssp")
        return run_fmpy_ssp(ssp) if master == "fmpy-ssp" else run_libcosim(ssp)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("ssp", help="build the .ssp").add_argument("--out", type=Path, default=Path("servoLoop.ssp"))
    sub.add_parser("container", help="build the container FMU").add_argument(
        "--out", type=Path, default=Path("servoLoop.fmu")
    )
    r = sub.add_parser("run", help="run the system and print what it did")
    r.add_argument("master", choices=MASTERS)
    r.add_argument("--fmi-version", type=int, choices=(2, 3), default=2, help="FMI version of the plain master's FMUs")
    r.add_argument("--csv", type=Path, help="also write every step to this CSV file")
    r.add_argument(
        "--motor",
        choices=tuple(MOTOR_WIRES),
        default="motorOutput",
        help="the plain master's motor wire: the Real motorOutput (the .ssd's) or a 16-bit bus's Integer motorCommand",
    )
    args = parser.parse_args(argv)
    if args.command == "ssp":
        print(build_ssp(args.out))
    elif args.command == "container":
        print(build_container(args.out))
    else:
        if args.motor != "motorOutput" and args.master not in ("gauss-seidel", "jacobi"):
            parser.error("--motor: the .ssp and the container wire the .ssd's motorOutput")
        result = run(args.master, args.fmi_version, motor=args.motor)
        print(
            f"{args.master}: {len(result)} cycles; motion complete after cycle {motion_complete(result)}; "
            f"encoder {result['plant.encoderCount'][-1]} counts (commanded "
            f"{result['chip.axis1.commandedPosition'][-1]}); largest following error "
            f"{np.abs(following_error(result)).max()} counts"
        )
        if args.csv:
            np.savetxt(
                args.csv,
                result,
                delimiter=",",
                header=",".join(result.dtype.names),
                comments="",
                fmt=["%d" if result.dtype[n].kind == "i" else "%.17g" for n in result.dtype.names],
            )


if __name__ == "__main__":
    main()
