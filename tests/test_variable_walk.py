# SPDX-License-Identifier: BSD-2-Clause
"""Every variable through every getter and setter: for each row
of modelDescription/variables.csv (every axis, every array element in FMI 2, every
array whole in FMI 3), through FMI 2 and FMI 3, a get and a set of EVERY type. The
variable's own type works (the get answers the documented value, the set works
for inputs, and for parameters until initialization ends); every other type,
and a set of an output or of a parameter after initialization, is refused with
Error and a message naming the function and the value reference, and changes
nothing (the serialized FMU state is the same before and after)."""

from pathlib import Path

import pytest
from fmpy.fmi1 import FMICallException

import pmdfmu
from pmdfmu import tables
from states import InitializationChip, snapshot

CSV = Path(__file__).resolve().parent.parent / "modelDescription" / "variables.csv"
FMI2_TYPES = ("Real", "Integer", "Boolean", "String")
FMI3_TYPES = ("Float64", "Int32", "UInt32", "UInt16", "Int16", "Boolean", "String", "Binary")


def start(v):
    """A variable's documented start value, as its type reads it."""
    kind = getattr(v, "fmi3Type", None) or v.type
    if kind in ("Real", "Float64"):
        return float(v.start)
    if kind == "Boolean":
        return v.start == "true"
    if kind == "String":
        return v.start
    return int(v.start)


def outputs_of_a_new_chip(fmi_version):
    """What the outputs of an instance just initialized (time 0, nothing run, no
    script) are: the registers as a chip reset leaves them, read through the
    chip's own commands where they are status words, on a second instance."""
    with pmdfmu.Chip(fmi_version=fmi_version) as other:
        statuses = {
            f"axis{n + 1}.{name}": getattr(other.axis(n), command)()
            for n in range(4)
            for name, command in (("activityStatus", "GetActivityStatus"), ("eventStatus", "GetEventStatus"))
        }
    cycle_time = float(next(v.start for v in tables.read_variables(CSV) if v.name == "cycleTime"))
    known = {
        "time": 0.0,
        "activeCycleTime": cycle_time,
        "nextCycleTime": 0.0,
        "nextCycle": 0.0,
        "script.axes": 0,
        "script.lastCycle": 0.0,
        "host.interrupt": False,
        "record.data": None,
        "record.rowSize": 4 + 12 * 4,
        **statuses,
    }  # record.columns "": the chip time, 12 commanded words
    return lambda name: known.get(name, 0)  # every other output (positions, replies, counts) is 0


def another_value(v, value):
    """A valid value other than `value` for an input or parameter."""
    kind = getattr(v, "fmi3Type", None) or v.type
    if kind == "Boolean":
        return not value
    if kind in ("Real", "Float64"):
        return value * 2  # cycleTime: 2e-4 s, whole microseconds still
    if kind == "String" and v.name == "record.columns":
        return value + "axis1.position"  # names checked when set: a variable's
    if kind == "String":
        return value + "walk.pmd"  # the script is compiled only at the end of initialization
    return value + 1  # every Integer input and parameter takes start + 1


def decoded(values):
    """A get's values as a list, strings as str whichever way FMPy hands them out."""
    return [x.decode() if isinstance(x, bytes) else x for x in values]


def values_for(kind, count):
    """Any values of an FMI type, for a call that must be refused before it looks at them."""
    value = {"Real": 0.0, "Float64": 0.0, "Boolean": False, "String": "", "Binary": b""}.get(kind, 0)
    return [value] * count


class Walker:
    """Raw FMI calls on one instance (a pmdfmu.Chip in step mode, or an
    InitializationChip), by type name."""

    def __init__(self, chip):
        self.chip, self.fmu, self.version = chip, chip.fmu, chip.fmi_version

    def function(self, op, kind):
        return f"fmi{self.version}{op}{kind}"

    def get(self, kind, vr, count):
        if self.version == 2:
            return getattr(self.fmu, "get" + kind)([vr])
        return getattr(self.fmu, "get" + kind)([vr], nValues=count) if kind != "Binary" else self.fmu.getBinary([vr])

    def set(self, kind, vr, values):
        getattr(self.fmu, "set" + kind)([vr], values)

    def refused(self, op, kind, vr, count, values=None):
        """Calls op (Get or Set) of kind on vr: it must fail with Error, log a message
        naming the function and the value reference, and change nothing."""
        before = snapshot(self.chip)
        self.chip.messages.clear()
        with pytest.raises(FMICallException):
            if op == "Get":
                self.get(kind, vr, count)
            else:
                self.set(kind, vr, values if values is not None else values_for(kind, count))
        errors = [m.message for m in self.chip.messages if m.status == "Error"]
        fn = self.function(op, kind)
        assert any(fn in m and f"value reference {vr}" in m for m in errors), (fn, vr, errors)
        assert snapshot(self.chip) == before, f"{fn} on value reference {vr} changed the FMU state"


def variables(fmi_version):
    if fmi_version == 2:
        return [v for v in tables.read_variables(CSV) if v.type != "Binary"], FMI2_TYPES
    return tables.read_variables3(CSV), FMI3_TYPES


def count_of(v):
    return getattr(v, "count", 1)


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_every_variable_through_every_getter_and_setter_in_step_mode(fmi_version):
    rows, types = variables(fmi_version)
    expected_output = outputs_of_a_new_chip(fmi_version)
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        w = Walker(chip)
        for v in rows:
            mine, n = v.type, count_of(v)  # Variable3.type is the FMI 3 type
            for kind in types:
                if kind != mine:
                    w.refused("Get", kind, v.vr, n)
                    w.refused("Set", kind, v.vr, n)
                    continue
                got = decoded(w.get(kind, v.vr, n))
                want = start(v) if v.causality in ("parameter", "input") else expected_output(v.name)
                assert got == [want] * n, (v.name, got)
                if v.causality == "input":  # the value it has: works, and changes nothing
                    before = snapshot(chip)
                    w.set(kind, v.vr, got)
                    assert snapshot(chip) == before, v.name
                else:  # outputs, time, and parameters after initialization
                    w.refused("Set", kind, v.vr, n, values=got if kind != "Binary" else [b""])


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_parameters_and_inputs_are_set_in_initialization_mode_and_wrong_types_refused(fmi_version):
    rows, types = variables(fmi_version)
    chip = InitializationChip(fmi_version)
    try:
        w = Walker(chip)
        for v in rows:
            mine, n = v.type, count_of(v)  # Variable3.type is the FMI 3 type
            if v.causality not in ("parameter", "input"):
                continue
            got = w.get(mine, v.vr, n)
            assert decoded(got) == [start(v)] * n, (v.name, got)
            w.set(mine, v.vr, decoded(got))  # a parameter may be set until initialization ends
            assert decoded(w.get(mine, v.vr, n)) == decoded(got), v.name
            other = [another_value(v, x) for x in decoded(got)]
            w.set(mine, v.vr, other)  # and takes a new value
            assert decoded(w.get(mine, v.vr, n)) == other, v.name
            for kind in types:
                if kind != mine:
                    w.refused("Set", kind, v.vr, n)
                    w.refused("Get", kind, v.vr, n)
    finally:
        chip.free()


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_value_references_of_no_variable_are_refused_by_every_type(fmi_version):
    """Between the rows (5, 14, 99) and past the last: no variable, whatever the type."""
    rows, types = variables(fmi_version)
    used = {v.vr + e for v in rows for e in range(count_of(v))}
    free = [vr for vr in (5, 14, 23, 99, 1000, max(used) + 1) if vr not in used]
    with pmdfmu.Chip(fmi_version=fmi_version) as chip:
        w = Walker(chip)
        for vr in free:
            for kind in types:
                for op in ("Get", "Set"):
                    before = snapshot(chip)
                    chip.messages.clear()
                    with pytest.raises(FMICallException):
                        w.get(kind, vr, 1) if op == "Get" else w.set(kind, vr, values_for(kind, 1))
                    errors = [m.message for m in chip.messages if m.status == "Error"]
                    assert any(w.function(op, kind) in m and f"value reference {vr}" in m for m in errors), errors
                    assert snapshot(chip) == before
