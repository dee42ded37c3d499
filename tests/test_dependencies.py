# SPDX-License-Identifier: BSD-2-Clause
"""Dependencies that tell the truth: the dependencies both model
descriptions declare, against what the FMU does, through FMPy in FMI 2 and FMI 3.

variables.csv's `dependencies` column says, for each output, which knowns it depends on without
a step, and generate.py writes it into Outputs / <Output> (the inputs, at communication points)
and InitialUnknowns / <InitialUnknown> (the inputs, the parameters and the start time, in
Initialization Mode). A dependency is FMI's: the output a get returns as a function of the knowns
set before it (the get's feedthrough). At communication points a get executes a pending host
batch, then a pending memory write (instance.c, pmd_commit_ports): whatever a batch can change
depends on the host port, and host.reply on what a command reads at once: GetSignalStatus the
switches, ReadAnalog `analog`, ReadIO `io.input`. The memory write comes after the batch, so no
reply of the get that writes it sees it; a later batch's ReadBuffer reads it as state, as it reads
what a doStep left. In Initialization Mode a get executes nothing (the writes wait for the first
get or doStep after it), so the initial values depend on parameters and the start time alone. The
encoder input `axisN.actualPosition` is read by the chip's cycles only (Reset keeps the count the
last cycle sampled: chip.c, pmd_chip_reset), so no output depends on it.

Here the FMU is brought into states where things can happen (batches of every kind pending, an
axis accelerating, an open-loop motor command, switches and peripheral inputs set, a memory
write pending, events latched, the time between two cycles), each input alone (and in
Initialization Mode each parameter and the start time) takes other values before a get, and
every output that get shows moved must be declared; and, row by row of variables.csv, every declared
dependency is seen to move its output in one of those states: the declarations are exact, not
merely safe. The plant-facing outputs (motorCommand, motorOutput) depend on no plant input, so
chip + plant form no algebraic loop. Both XMLs pass FMPy's validation (schema and model
structure) and fmu-manipulation-toolbox's checker; FMI 2 keeps the explicit `time` the standard
describes (tools' FMI Library finding: its start-attribute message is an FMI Library defect)."""

import copy
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from fmpy.validation import validate_fmu

import pmdfmu
from pmdfmu import PMDAbruptStopMode, PMDBufferFunctionPosition, PMDExternalProfile, PMDMotorOff
from states import command

pytestmark = pytest.mark.slow  # tests/README.md: compiles programs or runs the CLI; -m "not slow" leaves it out

ROOT = Path(__file__).resolve().parent.parent
FMI_VERSIONS = (2, 3)
START_TIME = 2.5e-4  # Initialization Mode: between two cycles for 1e-4 and 2e-4 s
PLANT_INPUTS = (
    "axis{axis}.actualPosition",
    "axis{axis}.positiveLimit",
    "axis{axis}.negativeLimit",
    "axis{axis}.index",
    "axis{axis}.home",
    "analog",
    "io.input",
)
PLANT_FACING = ("axis{axis}.motorCommand", "axis{axis}.motorOutput")


def row(name: str) -> str:
    """The row of variables.csv a variable comes from: axis2.home -> axis{axis}.home, host.word[3] -> host.word."""
    return re.sub(r"^axis\d\.", "axis{axis}.", name.split("[")[0])


def declared(md, mode):
    """{output: set of the knowns it depends on} as a model description declares them, for
    `step` (Outputs) or `init` (InitialUnknowns)."""
    unknowns = md.outputs if mode == "step" else md.initialUnknowns
    assert all(u.dependencies is not None for u in unknowns), "every unknown declares its dependencies"
    return {u.variable.name: {d.name for d in u.dependencies} for u in unknowns}


# ---- driving the FMU below the Chip API -------------------------------------------------------


def words(*commands):
    """Host words of several commands: each a (name, *args) tuple, with axis=n as a last dict."""
    out = []
    for c in commands:
        kwargs = c[-1] if isinstance(c[-1], dict) else {}
        out += command(*(c[:-1] if kwargs else c), **kwargs)
    return out


class Probe:
    """An FMU instance read and written in raw FMI calls: every output in one call per type, and
    inputs and parameters element by element from a copy of their values (a get would execute a
    pending batch), each run starting from one saved FMU state."""

    def __init__(self, chip, knowns):
        self.chip, self.fmu, self.version = chip, chip.fmu, chip.fmi_version
        variables = chip.model_description.modelVariables
        self.by_name = {v.name: v for v in variables}
        self.outputs = {}
        for v in variables:
            if v.causality == "output":
                self.outputs.setdefault(v.type, []).append(v)
        self.knowns = [self.by_name[n] for n in knowns]
        # read now, with nothing pending: every known's value, FMI 3 arrays whole
        self.saved_values = {v.name: chip.get(v.name) for v in self.knowns}
        self.values = copy.deepcopy(self.saved_values)
        self.state = self.fmu.getFMUState()

    def size(self, v):
        return int(v.dimensions[0].start) if getattr(v, "dimensions", None) else 1

    def elements(self):
        """The knowns one by one: FMI 2 scalars, FMI 3 array elements as name[i]."""
        for v in self.knowns:
            n = self.size(v)
            yield from ([f"{v.name}[{i + 1}]" for i in range(n)] if n > 1 else [v.name])

    def variable_of(self, element):
        """(variable, element index or None) of a scalar or element name (host.word[3] in FMI 3)."""
        if element in self.by_name:
            return self.by_name[element], None
        base, index = re.fullmatch(r"(.*)\[(\d+)\]", element).groups()
        return self.by_name[base], int(index) - 1

    def write(self, sets):
        """Sets elements (FMI 2 or FMI 3 names alike) with one raw call per variable."""
        changed = {}
        for element, value in sets.items():
            v, i = self.variable_of(element)
            if i is None:
                self.values[v.name] = value
            else:
                self.values[v.name][i] = value
            changed[v.name] = v
        for v in changed.values():
            value = self.values[v.name]
            getattr(self.fmu, "set" + v.type)([v.valueReference], list(value) if isinstance(value, list) else [value])

    def read(self):
        """Every output: {name: value}, FMI 3 arrays as tuples."""
        out = {}
        for kind, vs in self.outputs.items():
            if kind == "Binary":  # record.data: empty, whether a buffer exists or not
                for v in vs:
                    out[v.name] = self.fmu.getBinary([v.valueReference])[0] or b""
                continue
            vrs = [v.valueReference for v in vs]
            if self.version == 2:
                values = getattr(self.fmu, "get" + kind)(vrs)
            else:
                values = getattr(self.fmu, "get" + kind)(vrs, nValues=sum(self.size(v) for v in vs))
            i = 0
            for v in vs:
                n = self.size(v)
                out[v.name] = tuple(values[i : i + n]) if n > 1 else values[i]
                i += n
        return out

    def restore(self):
        self.fmu.setFMUState(self.state)
        strings = [v for v in self.knowns if v.type == "String" and self.values[v.name] != self.saved_values[v.name]]
        self.values = copy.deepcopy(self.saved_values)
        self.write({v.name: self.values[v.name] for v in strings})  # not in the FMU state: the path is the shell's

    def run(self, phases, vary=None):
        """The outputs after each phase (its sets, then every output read), from the saved state;
        vary = (phase, element, value) replaces one set."""
        self.restore()
        out = []
        for k, sets in enumerate(phases):
            sets = dict(sets)
            if vary and vary[0] == k:
                sets[vary[1]] = vary[2]
            self.write(sets)
            out.append(self.read())
        return out

    def alternatives(self, element, phases, k):
        """Other valid values of an element in phase k: each known's own kind of change."""
        start = self.saved_values
        v, i = self.variable_of(element)
        before = start[v.name] if i is None else start[v.name][i]
        now = before
        for sets in phases[: k + 1]:
            now = sets.get(element, now)
        name = row(element)
        if v.type == "Boolean":
            return [not now]
        if name in ("host.strobe", "memory.strobe"):  # the value seen (cancels a pending one), a new one
            return [x for x in (before, now + 1) if x != now]
        if name in ("host.wordCount", "memory.count"):
            return [x for x in (now - 1, now + 1) if 0 <= x <= 64]
        if name in ("host.word", "analog", "io.input"):
            return [(now + 1) & 0xFFFF, now ^ 0x5A5A]
        if name == "memory.data":
            return [(now + 1) & 0x7FFFFFFF, now ^ 0x5A5A5A5A]
        if name == "cycleTime":
            return [2e-4 if now != 2e-4 else 1e-4]
        if name == "memorySize":
            return [0x200]
        if name == "record.capacity":
            return [16]
        if name == "script":
            return ["no-such.script"]
        if name == "machine":
            return ["[axis1]\nhome = [1, 2]\n"]
        if name == "record.columns":
            return ["axis1.activityStatus,axis2.position"]
        if name == "axis{axis}.actualPosition":  # 0: where a Reset puts the commanded position too
            return [x for x in (now + 1000, 0) if x != now]
        return [now + 1000]  # memory.address


def observe(probe, phases):
    """{(output, known)}: each known element alone takes other values in each phase, and every
    output that the phase's get then shows differing from the plain run is recorded (FMI 3 arrays
    by their name). What a later get sees is state the earlier get left (test_a_memory_write_...)."""
    plain = probe.run(phases)
    seen = set()
    for k in range(len(phases)):
        for element in probe.elements():
            known = probe.variable_of(element)[0].name
            for value in probe.alternatives(element, phases, k):
                got = probe.run(phases, (k, element, value))
                seen |= {(out, known) for out, x in got[k].items() if x != plain[k][out]}
    return seen


# ---- the states ------------------------------------------------------------------------------


def batch(strobe, *commands):
    """A phase that leaves a batch pending: its words, count and strobe."""
    w = words(*commands)
    return {**{f"host.word[{i + 1}]": x for i, x in enumerate(w)}, "host.wordCount": len(w), "host.strobe": strobe}


def memory_write(strobe, address, value):
    return {"memory.address": address, "memory.count": 1, "memory.data[1]": value, "memory.strobe": strobe}


SENSORS = (
    [("GetSignalStatus", {"axis": n}) for n in range(4)]
    + [("ReadAnalog", c) for c in range(8)]
    + [("ReadIO", a) for a in range(16)]
)
ENCODER = (
    [("Reset",)]
    + [("GetActualPosition", {"axis": n}) for n in range(4)]
    + [("GetActualVelocity",), ("GetPositionError",)]
    + [("SetActualPosition", 100 * n, {"axis": n}) for n in range(4)]
)
EXTERNAL_UPDATE = [
    ("Reset",),
    ("SetBufferStart", 2, 0),
    ("SetBufferLength", 2, 0x400),
    ("SetBufferFunction", PMDBufferFunctionPosition, 2, {"axis": 0}),
    ("SetProfileMode", PMDExternalProfile, {"axis": 0}),
    ("ClearPositionError",),
    ("Update",),
    ("SetInterruptMask", 0xFFFF),
    ("GetBufferLength", 2),
    ("ReadBuffer", 2),
]


def batches(s, buffer_address, m=0):
    """The pending batches every state is probed with, s and m being the host and memory strobes
    seen: name -> phases (the sets of each get)."""
    return {
        "nothing pending": [{}],
        "Reset": [batch(s + 1, ("Reset",))],
        "SetSampleTime": [batch(s + 1, ("SetSampleTime", 200))],
        "abrupt stop": [batch(s + 1, ("SetStopMode", PMDAbruptStopMode), ("Update",))],
        "a move on axis 3": [
            batch(
                s + 1,
                ("SetPosition", 1000, {"axis": 2}),
                ("SetVelocity", 0x10000, {"axis": 2}),
                ("SetAcceleration", 0x100, {"axis": 2}),
                ("Update", {"axis": 2}),
            )
        ],
        "events and the interrupt": [
            batch(s + 1, ("ResetEventStatus", 0, {"axis": 1}), ("SetInterruptMask", 0xFFFF), ("GetEventStatus",))
        ],
        "a refusal": [batch(s + 1, ("SetBufferLength", 40, 1), ("GetTime",))],
        "WriteIO": [batch(s + 1, ("WriteIO", 3, 0x1234))],
        "the sensors": [batch(s + 1, *SENSORS)],
        "the encoder": [batch(s + 1, *ENCODER)],
        "an external profile's Update": [batch(s + 1, *EXTERNAL_UPDATE)],
        # the write first (one get), then the batch that reads it (a later get at the same time)
        "a memory write, then ReadBuffer": [
            memory_write(m + 1, buffer_address, 0xABCD),
            batch(s + 1, ("ReadBuffer", 2)),
        ],
        # both in one get: the batch runs before the write
        "a batch and a write at once": [
            {**memory_write(m + 1, buffer_address, 0xABCD), **batch(s + 1, ("ReadBuffer", 2))}
        ],
    }


def plant_inputs(chip):
    for n in range(1, 5):
        chip.set(f"axis{n}.actualPosition", 400 + 100 * n)
    chip.set("axis4.positiveLimit", True)
    chip.set("axis2.negativeLimit", True)
    chip.set("axis3.home", True)
    chip.set("analog", [1000 + i for i in range(8)])
    chip.set("io.input", [0xF00 + i for i in range(16)])


def step_mode_state(chip):
    """Axis 1 accelerating in a trapezoid, axis 2 in open loop at 777, an instruction error
    latched, buffer 2 at 0x300, the plant's inputs set, the time half a cycle past a cycle."""
    plant_inputs(chip)
    a1, a2 = chip.axis(0), chip.axis(1)
    a1.SetPosition(100000)
    a1.SetVelocity(0x40000)
    a1.SetAcceleration(0x1000)
    a1.Update()
    a2.SetMotorMode(PMDMotorOff)
    a2.SetMotorCommand(777)
    a2.Update()
    a1.SetBufferStart(2, 0x300)
    a1.SetBufferLength(2, 4)
    chip.batch(command("SetBufferLength", 40, 1))  # refused: an instruction-error event
    chip.run(20)
    t = chip.get("time")
    chip.fmu.doStep(t, 0.5 * chip.get("activeCycleTime"))


def initialization_mode(chip, start_time=START_TIME):
    """The instance again in Initialization Mode from `start_time`, loopback off, the plant's
    inputs set."""
    chip.fmu.reset()
    if chip.fmi_version == 2:
        chip.fmu.setupExperiment(startTime=start_time)
        chip.fmu.enterInitializationMode()
    else:
        chip.fmu.enterInitializationMode(startTime=start_time)
    chip.set("loopback", False)
    plant_inputs(chip)


def observed_dependencies(fmi_version, mode):
    """Every (output, known) seen to move, over every state and pending batch; in Initialization
    Mode the parameters are probed too."""
    causalities = ("input",) if mode == "step" else ("input", "parameter")
    seen = set()
    for name in batches(0, 0):
        with pmdfmu.Chip(fmi_version=fmi_version, loopback=False) as chip:
            if mode == "step":
                step_mode_state(chip)
                address = 0x300
            else:
                initialization_mode(chip)
                address = 0x100
            probe = Probe(chip, [v.name for v in chip.model_description.modelVariables if v.causality in causalities])
            try:
                strobe, memory = probe.saved_values["host.strobe"], probe.saved_values["memory.strobe"]
                assert strobe == chip.get("host.ack")
                phases = batches(strobe, address, memory)[name]
                if mode == "init" and "write" in name:
                    # the buffer the memory write fills: set up by a first get, inside the smallest
                    # memory probed (memorySize 0x200)
                    phases = [batch(strobe + 1, ("SetBufferStart", 2, address), ("SetBufferLength", 2, 4))] + batches(
                        strobe + 1, address, memory
                    )[name]
                seen |= observe(probe, phases)
            finally:
                chip.fmu.freeFMUState(probe.state)
    return seen


_observed = {}


@pytest.fixture(scope="module")
def observed():
    """observed(fmi_version, mode): the (output, known) pairs seen to move, computed once."""

    def get(fmi_version, mode):
        if (fmi_version, mode) not in _observed:
            _observed[fmi_version, mode] = observed_dependencies(fmi_version, mode)
        return _observed[fmi_version, mode]

    return get


def model_description(fmi_version):
    return pmdfmu.chip.read_model_description(str(pmdfmu.chip.default_fmu(fmi_version)))


MODES = {"step": "Outputs at communication points", "init": "InitialUnknowns in Initialization Mode"}


# ---- the declarations against the FMU ---------------------------------------------------------


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_every_output_that_moves_without_a_step_is_declared_to_depend_on_what_moved_it(observed, fmi_version, mode):
    deps = declared(model_description(fmi_version), mode)
    undeclared = sorted((out, known) for out, known in observed(fmi_version, mode) if known not in deps[out])
    assert not undeclared, f"{MODES[mode]}: outputs moved by knowns they are not declared to depend on: {undeclared}"


@pytest.mark.parametrize("mode", MODES)
@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_every_declared_dependency_is_seen_to_move_its_output(observed, fmi_version, mode):
    """Row by row of variables.csv (every axis and element stands for its row): no dependency is
    declared that no state shows; with the test above, the declarations are exact."""
    deps = declared(model_description(fmi_version), mode)
    rows_declared = {(row(out), row(known)) for out, knowns in deps.items() for known in knowns}
    rows_seen = {(row(out), row(known)) for out, known in observed(fmi_version, mode)}
    if mode == "init":
        rows_seen |= {(row(out), "time") for out in start_time_moves(fmi_version)}
    assert rows_declared - rows_seen == set(), f"{MODES[mode]}: declared but never seen"
    assert rows_seen - rows_declared == set()


def start_time_moves(fmi_version):
    """The outputs two instances show in Initialization Mode that differ only in the start time."""
    got = []
    for start_time in (0.0, START_TIME):
        with pmdfmu.Chip(fmi_version=fmi_version) as chip:
            initialization_mode(chip, start_time)
            probe = Probe(chip, [])
            got.append(probe.read())
            chip.fmu.freeFMUState(probe.state)
    return {out for out, x in got[0].items() if x != got[1][out]}


def set_port(chip, sets):
    """Sets host and memory port elements (FMI 2 names, host.word[3]) without a get."""
    arrays = {}
    for name, value in sets.items():
        if "[" in name and chip.fmi_version == 3:
            base, index = re.fullmatch(r"(.*)\[(\d+)\]", name).groups()
            arrays.setdefault(base, {})[int(index) - 1] = value
        else:
            chip.set(name, value)
    for base, elements in arrays.items():
        values = [0] * 64
        for i, x in elements.items():
            values[i] = x
        chip.set(base, values)


@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_a_memory_write_is_state_for_a_later_batch_never_feedthrough_to_the_reply_of_its_own_get(fmi_version):
    """Why host.reply declares no memory port: the get that executes a batch and a write runs the
    batch first (CONTRACT 2.2), so its ReadBuffer reads the word as it was; the next batch reads
    the word written, as it would after a doStep."""
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        ax = chip.axis(0)
        ax.SetBufferStart(2, 0x300)
        ax.SetBufferLength(2, 4)
        ax.WriteBuffer(2, 0x1111)
        ax.SetBufferReadIndex(2, 0)
        strobe, memory = chip.get("host.ack"), chip.get("memory.strobe")
        set_port(chip, {**memory_write(memory + 1, 0x300, 0xABCD), **batch(strobe + 1, ("ReadBuffer", 2))})
        assert chip.get("host.replyCount") == 2
        assert chip.get("host.reply")[:2] == [0, 0x1111]  # ReadBuffer's 32 bits, high word first
        set_port(chip, batch(strobe + 2, ("SetBufferReadIndex", 2, 0), ("ReadBuffer", 2)))
        assert chip.get("host.reply")[:2] == [0, 0xABCD]


@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_a_batch_written_in_initialization_mode_executes_at_the_first_get_after_it(fmi_version):
    """Initialization Mode's gets execute nothing, so the initial values are the parameters' alone
    (the InitialUnknowns declare no port); the batch runs at the start time, before cycle 0."""
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        initialization_mode(chip, 0.0)
        strobe = chip.get("host.ack")
        set_port(chip, batch(strobe + 1, ("SetPosition", 1000, {"axis": 0}), ("Update",), ("GetTime",)))
        assert (chip.get("host.ack"), chip.get("host.replyCount")) == (strobe, 0)
        chip.fmu.exitInitializationMode()
        assert chip.get("host.ack") == strobe + 1
        assert (chip.get("host.replyCount"), chip.get("host.reply")[:2], chip.get("host.error")) == (2, [0, 0], 0)


@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_the_start_time_moves_only_the_grid_and_is_declared_so(fmi_version):
    moved = start_time_moves(fmi_version)
    assert moved == {"nextCycle", "nextCycleTime"}
    deps = declared(model_description(fmi_version), "init")
    assert {out for out, knowns in deps.items() if "time" in knowns} == moved


@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_the_plant_facing_outputs_depend_on_no_plant_input_so_chip_and_plant_make_no_algebraic_loop(fmi_version):
    """A plant takes axisN.motorCommand or motorOutput and gives axisN.actualPosition (and the
    switches, analog, io.input): neither output depends on any of them, in either list."""
    md = model_description(fmi_version)
    for mode in MODES:
        for out, knowns in declared(md, mode).items():
            if row(out) in PLANT_FACING:
                assert not {k for k in knowns if row(k) in PLANT_INPUTS}, (mode, out, knowns)


@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_the_plant_inputs_reach_only_what_a_batch_reads_at_once(fmi_version):
    """The switches, analog and io.input reach host.reply only (GetSignalStatus, ReadAnalog, ReadIO), at
    communication points (in Initialization Mode no batch runs); no output depends on the encoder input
    axisN.actualPosition, which only a cycle reads."""
    md = model_description(fmi_version)
    for mode in MODES:
        reached = {}
        for out, knowns in declared(md, mode).items():
            for k in knowns:
                if row(k) in PLANT_INPUTS:
                    reached.setdefault(row(k), set()).add(row(out))
        assert "axis{axis}.actualPosition" not in reached, (mode, reached)
        assert all(outs == {"host.reply"} for outs in reached.values()), (mode, reached)
        assert set(reached) == (set(PLANT_INPUTS) - {"axis{axis}.actualPosition"} if mode == "step" else set())


def test_both_fmi_versions_declare_the_same_dependencies():
    """FMI 2's scalars and FMI 3's whole arrays name the same rows, element for element where both have them."""

    def by_variable(md, mode):
        return {(out.split("[")[0], k.split("[")[0]) for out, knowns in declared(md, mode).items() for k in knowns}

    md2, md3 = model_description(2), model_description(3)
    for mode in MODES:
        assert by_variable(md2, mode) == by_variable(md3, mode), mode


# ---- the XML ---------------------------------------------------------------------------------


@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_the_model_descriptions_are_valid_and_list_knowns_only(fmi_version):
    """FMPy's validation (the schema, the model structure, dependencies against dependenciesKind);
    every dependency "dependent", dependenciesKind's default, so left out (FMI allows the other kinds
    only for floating-point unknowns as a linear factor, and not "fixed", "tunable" or "discrete" in
    Initialization Mode); Outputs list
    inputs, InitialUnknowns inputs, parameters and time; FMI 2's indices ascend."""
    path = pmdfmu.chip.default_fmu(fmi_version)
    assert validate_fmu(str(path)) == []
    md = model_description(fmi_version)
    for mode, unknowns in (("step", md.outputs), ("init", md.initialUnknowns)):
        allowed = {"input"} if mode == "step" else {"input", "parameter", "independent"}
        for u in unknowns:
            assert u.dependenciesKind is None
            assert {d.causality for d in u.dependencies} <= allowed, (mode, u.variable.name)
            if fmi_version == 2:
                indices = [md.modelVariables.index(d) for d in u.dependencies]
                assert indices == sorted(set(indices))


def fmutool():
    tool = Path(sys.executable).parent / "fmutool"
    return tool if tool.exists() else shutil.which("fmutool")


@pytest.mark.skipif(not fmutool(), reason="fmu-manipulation-toolbox is not installed (helper tools installs it)")
@pytest.mark.parametrize("fmi_version", FMI_VERSIONS, ids=["fmi2", "fmi3"])
def test_fmu_manipulation_toolbox_checks_the_model_structure_without_an_error(fmi_version):
    path = pmdfmu.chip.default_fmu(fmi_version)
    run = subprocess.run([str(fmutool()), "-input", str(path), "-check"], capture_output=True, text=True, timeout=120)
    log = run.stdout + run.stderr
    assert run.returncode == 0, log
    assert f"No semantic error against the FMI-{fmi_version} standard." in log, log
    assert "ERROR" not in log.upper().replace("NO SEMANTIC ERROR", ""), log


def test_fmi2_declares_time_as_the_standard_says_which_fmi_library_misreads():
    """tools' finding: libcosim's FMI Library logs "Start attribute is required" for `time`. FMI
    2.0.5, 2.2.7: an independent variable "must be defined as Real without a start attribute"
    (and no initial): the FMU keeps it so, since InitialUnknowns name it (nextCycle and
    nextCycleTime depend on the start time); FMI Library's check is its defect (fmi-library
    reported and fixed upstream), docs/tools.md says so."""
    md = model_description(2)
    time = md.modelVariables[0]
    assert (time.name, time.causality, time.variability, time.type) == ("time", "independent", "continuous", "Real")
    assert time.start is None and time.initial is None
    text = (Path(pmdfmu.chip.extract(str(pmdfmu.chip.default_fmu(2)))) / "modelDescription.xml").read_text()
    assert re.search(
        r'<ScalarVariable name="time" valueReference="0" causality="independent" '
        r'variability="continuous" description="[^"]*">\s*<Real declaredType="Time" unit="s"/>',
        text,
    )


def test_fmi3_parameters_are_types_every_tool_knows():
    """tools' finding: Maestro 3.1.1's FMI 3 initializer knows Boolean, Float64, Int32 and String
    parameters only. memorySize (<= 2^26) and record.capacity (<= 2^24) fit Int32, which FMI 3
    allows for any parameter; FMI 2 has them as Integer."""
    v = {x.name: x for x in model_description(3).modelVariables}
    assert {n: v[n].type for n in v if v[n].causality == "parameter"} == {
        "cycleTime": "Float64",
        "memorySize": "Int32",
        "loopback": "Boolean",
        "script": "String",
        "machine": "String",
        "record.capacity": "Int32",
    }


# ---- the generator's rule --------------------------------------------------------------------


def generator():
    import importlib.util

    spec = importlib.util.spec_from_file_location("generate", ROOT / "modelDescription" / "generate.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize(
    "cell, message",
    [
        ("", "an output says what it depends on"),
        ("host.nothing", "names no input, parameter or independent variable"),
        ("cycleTime", "changes in Initialization Mode only"),
        ("step:cycleTime", "changes in Initialization Mode only"),
        ("later:host.strobe", "the mode is step: or init:"),
        ("axis{axis}.home", "names the output's own axis; it has none"),
    ],
)
def test_the_generator_refuses_a_dependency_it_cannot_write_truthfully(tmp_path, cell, message):
    gen = generator()
    table = (ROOT / "modelDescription" / "variables.csv").read_text().splitlines()
    header = table[0].split(",")
    at = header.index("dependencies")
    lines = [table[0]]
    for line in table[1:]:
        if line.startswith("host.ack,"):
            fields = line.split(",")
            fields[at] = cell
            line = ",".join(fields)
        lines.append(line)
    path = tmp_path / "variables.csv"
    path.write_text("\n".join(lines) + "\n")
    variables = gen.tables.read_variables(path)
    with pytest.raises(SystemExit, match=re.escape(message)):
        gen.resolve_dependencies(variables, gen.read_dependencies(path))
