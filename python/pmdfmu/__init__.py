# SPDX-License-Identifier: BSD-2-Clause
"""pmdfmu: a cycle-exact software twin of a PMD Navigator/Pilot-class motion
processor's trajectory side, as an FMI co-simulation FMU, driven from Python
the way C-Motion drives the chip.

    with pmdfmu.Chip() as chip:
        ax = chip.axis(pmdfmu.PMDAxis1)
        ax.SetBufferStart(2, 0x200)
        ...

Every C-Motion constant of modelDescription/constants.csv is a module
attribute (PMDExternalProfile, PMDAbruptStop, PMDEventBreakpoint1Mask, ...);
each *Mask constant also declares a register field, read with field_ex:

    pmdfmu.field_ex(ax.GetActivityStatus(), "PMDActivityProfileSegment")
"""

from .chip import (
    COMMANDS,
    CONSTANTS,
    FIELDS,
    Axis,
    Chip,
    FMUError,
    FMURefusal,
    LogMessage,
    PMDError,
    default_fmu,
    field_dp,
    field_ex,
    instruction_word,
    tables_dir,
)
from .hosttime import HostInterface
from .sweep import Case, SweepResult, read_cases, sweep
from .system import Plant, System
from .verify import VerifyResult, verify, verify_cases
from .fixed import fixed_0_32, fixed_16_16, fixed_32_0, from_fixed, signed, to_fixed

globals().update(CONSTANTS)

__version__ = "0.1.0"
__all__ = [
    "Chip",
    "Axis",
    "HostInterface",
    "Plant",
    "System",
    "PMDError",
    "FMUError",
    "FMURefusal",
    "LogMessage",
    "Case",
    "SweepResult",
    "read_cases",
    "sweep",
    "verify",
    "verify_cases",
    "VerifyResult",
    "COMMANDS",
    "CONSTANTS",
    "FIELDS",
    "field_ex",
    "field_dp",
    "instruction_word",
    "default_fmu",
    "tables_dir",
    "to_fixed",
    "from_fixed",
    "signed",
    "fixed_16_16",
    "fixed_0_32",
    "fixed_32_0",
    *CONSTANTS,
]
