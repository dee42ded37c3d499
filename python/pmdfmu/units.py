# SPDX-License-Identifier: BSD-2-Clause
"""The unit of each of the chip FMU's outputs, by the name after `axisN.` (the model description gives
them in its descriptions: variables.csv), for the HTML reports' axis titles and `pmdfmu info`."""

from __future__ import annotations

UNITS = {
    "commandedPosition": "counts",
    "commandedVelocity": "raw 16.16 counts/cycle",
    "commandedAcceleration": "raw 16.16 counts/cycle^2",
    "position": "counts",
    "velocity": "counts/s",
    "acceleration": "counts/s^2",
    "activityStatus": "bits",
    "eventStatus": "bits",
    "motorCommand": "100/2^15 % of full scale",
    "motorOutput": "fraction of full scale",
    "actualPosition": "counts",
    "cycle": "cycles",
    "chipTime": "cycles",
    "time": "s",
    "cycleTime": "s",
    "activeCycleTime": "s",
    "nextCycleTime": "s",
    "memorySize": "32-bit words",
}


def unit(name: str, declared: str = "") -> str:
    """A variable's unit: the model description's own (declared), else by its name."""
    return declared or UNITS.get(name.rpartition(".")[2], "")
