# SPDX-License-Identifier: BSD-2-Clause
"""Helpers for tests that work below the Chip API (a helper module, not a test
file: see conftest.py): the FMU state as bytes (a refused call changes nothing),
raw host words, host batches left pending, value references for raw FMI calls,
an instance left in initialization mode."""

from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from fmpy.fmi3 import FMU3Slave

import pmdfmu
from pmdfmu.chip import COMMANDS, encode, instruction_word


def snapshot(chip) -> bytes:
    """The serialized FMU state of a pmdfmu.Chip (or anything with an FMPy slave as .fmu)."""
    state = chip.fmu.getFMUState()
    try:
        return bytes(chip.fmu.serializeFMUState(state))
    finally:
        chip.fmu.freeFMUState(state)


def command(name, *args, axis=0):
    """A command's host words, as Chip.command sends them (a chip-wide one with axis field 0)."""
    c = COMMANDS[name]
    return [instruction_word(c.opcode, 0 if c.scope == "chip" else axis)] + encode(c, args)


def op(name, axis=0):
    """The instruction word alone, with any axis number in its axis field (scope not applied)."""
    return instruction_word(COMMANDS[name].opcode, axis)


def vr(chip, name):
    """A variable's value reference, for raw FMI calls."""
    return chip.variables[name].valueReference


def pend_batch(chip, words):
    """Writes a host batch and a new strobe without reading anything: it executes at the next get or doStep."""
    if chip.fmi_version == 2:
        for i, w in enumerate(words):
            chip.set(f"host.word[{i + 1}]", w)
    else:
        chip.set("host.word", list(words) + [0] * (64 - len(words)))
    chip.set("host.wordCount", len(words))
    chip.set("host.strobe", chip.get("host.ack") + 1)


class InitializationChip:
    """An instance left in initialization mode (pmdfmu.Chip initializes at once),
    with Chip's own set and get, beside a Chip of the same unzipped FMU."""

    def __init__(self, fmi_version):
        self._proto = pmdfmu.Chip(fmi_version=fmi_version)
        desc = self._proto.model_description
        self.fmi_version, self.variables, self.messages = fmi_version, self._proto.variables, []
        kwargs = dict(
            guid=desc.guid,
            unzipDirectory=self._proto._unzipdir,
            modelIdentifier=desc.coSimulation.modelIdentifier,
            instanceName="init",
        )

        def record(status, message):
            self.messages.append(pmdfmu.chip.LogMessage(pmdfmu.chip.STATUS_NAMES[status], "", message.decode()))

        if fmi_version == 2:
            self.fmu = FMU2Slave(**kwargs)
            self._callbacks = fmi2CallbackFunctions()
            self._callbacks.logger = fmi2CallbackLoggerTYPE(lambda env, name, status, cat, msg: record(status, msg))
            self.fmu.instantiate(callbacks=self._callbacks)
            self.fmu.setupExperiment(startTime=0.0)
            self.fmu.enterInitializationMode()
            types = ("Real", "Integer", "Boolean")
        else:
            self.fmu = FMU3Slave(**kwargs)
            self.fmu.instantiate(logMessage=lambda env, status, cat, msg: record(status, msg))
            self.fmu.enterInitializationMode(startTime=0.0)
            types = ("Float64", "Int32", "UInt32", "UInt16", "Int16", "Boolean")
        self._setters = {t: getattr(self.fmu, "set" + t) for t in types}
        self._getters = {t: getattr(self.fmu, "get" + t) for t in types}

    set = pmdfmu.Chip.set
    get = pmdfmu.Chip.get
    _size = pmdfmu.Chip._size
    _variable = pmdfmu.Chip._variable
    _nearest = pmdfmu.Chip._nearest

    def reply(self):
        n = self.get("host.replyCount")
        if self.fmi_version == 2:
            return [self.get(f"host.reply[{i + 1}]") for i in range(n)]
        return self.get("host.reply")[:n]

    def free(self):
        self.fmu.freeInstance()
        self._proto.close()
