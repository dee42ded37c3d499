# SPDX-License-Identifier: BSD-2-Clause
"""The chip's trace, read for a person (Chip.trace): buffer 0 as the trace left it, one column per
trace variable configured (SetTraceVariable), with its name and unit, oldest sample first; and
Trace.plot, a scope view in the manner of Pro-Motion's (one panel per variable, chip time, the
trigger marked). docs/chip.md, "Reading the trace"."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Tuple, Union

import numpy as np

from . import extras, files
from .fixed import signed
from .calls import CONSTANTS

# Trace variable IDs (reference 2.6, fmu_src/chip/trace.c's trace_value): the column's name (per axis,
# `axisN.` before it, except the chip-wide ones), the raw unit, and the factor and unit a plot shows.
# Velocity and acceleration are 16.16 words; the motor command 100/2^15 % of full scale per count.
VARIABLES: Dict[int, Tuple[str, str, float, str]] = {
    1: ("positionError", "counts", 1.0, "counts"),
    2: ("commandedPosition", "counts", 1.0, "counts"),
    3: ("commandedVelocity", "16.16 counts/cycle", 2.0**-16, "counts/cycle"),
    4: ("commandedAcceleration", "16.16 counts/cycle^2", 2.0**-16, "counts/cycle^2"),
    5: ("actualPosition", "counts", 1.0, "counts"),
    6: ("actualVelocity", "16.16 counts/cycle", 2.0**-16, "counts/cycle"),
    7: ("motorCommand", "100/2^15 % of full scale", 100.0 / 2**15, "% of full scale"),
    8: ("time", "cycles", 1.0, "cycles"),
    9: ("captureValue", "counts", 1.0, "counts"),
    10: ("integral", "raw", 1.0, "raw"),
    11: ("derivative", "raw", 1.0, "raw"),
    12: ("eventStatus", "bits", 1.0, "bits"),
    13: ("activityStatus", "bits", 1.0, "bits"),
    14: ("signalStatus", "bits", 1.0, "bits"),
    15: ("phaseAngle", "counts", 1.0, "counts"),
    16: ("phaseOffset", "counts", 1.0, "counts"),
    17: ("phaseACommand", "raw", 1.0, "raw"),
    18: ("phaseBCommand", "raw", 1.0, "raw"),
    19: ("phaseCCommand", "raw", 1.0, "raw"),
    **{20 + k: (f"analogInput{k + 1}", "raw", 1.0, "raw") for k in range(8)},
}
TIME = CONSTANTS["PMDTraceTime"]
CHIP_WIDE = {TIME} | set(range(CONSTANTS["PMDTraceAnalogInput1"], CONSTANTS["PMDTraceAnalogInput8"] + 1))
SLOTS = 4
STATUS = ("eventStatus", "activityStatus", "signalStatus")  # bit fields: drawn as steps


@dataclass
class Trace:
    """What the trace buffer holds: `samples`, a structured array with a `cycle` column (chip time of
    each sample: the traced time variable, or, without one, cycles since the first sample) and one
    int32 column per trace variable, named like the FMU's outputs (`axis2.commandedPosition`,
    `time`); `units` the raw unit of each; `period` (cycles between samples), `mode` ("one-time" or
    "rolling"), `wrapped` (a rolling trace overwrote its oldest samples), `running` (still sampling),
    `trigger` (the row of the trigger: the start for a one-time trace, the stop for a rolling trace
    that stopped; None while a rolling trace runs), `chip_time` (whether `cycle` is chip time)."""

    samples: np.ndarray
    units: Dict[str, str]
    period: int
    mode: str
    wrapped: bool
    running: bool
    trigger: Optional[int]
    chip_time: bool
    cycle_time: float
    scales: Dict[str, Tuple[float, str]] = field(default_factory=dict)

    @property
    def variables(self) -> List[str]:
        """The trace variables' columns, in slot order."""
        return [n for n in self.samples.dtype.names if n != "cycle"]

    @property
    def panels(self) -> List[str]:
        """The variables a scope shows: all but the traced time when it is the time axis."""
        return [n for n in self.variables if not (self.chip_time and n == "time")] or self.variables

    def __len__(self) -> int:
        return len(self.samples)

    def plot(self, path: Union[str, Path, None] = None, title: str = "Trace"):
        """The scope view: one panel per variable over chip time, the trigger marked. path: a .html
        name writes an interactive page (the 'html' extra), anything else an image by its suffix
        (the 'plot' extra); None returns the matplotlib figure (inline in a notebook)."""
        if path is not None and Path(path).suffix.lower() in (".html", ".htm"):
            from . import html_report

            html_report.write_trace(Path(path), self, title)
            return None
        plt = (
            extras.pyplot("Trace.plot")
            if path is not None
            else extras.require("matplotlib.pyplot", "plot", "Trace.plot")
        )
        names = self.panels
        fig, panels = plt.subplots(max(len(names), 1), 1, sharex=True, figsize=(10, 2.2 * max(len(names), 1) + 0.8))
        panels = np.atleast_1d(panels)
        x = self.samples["cycle"]
        for panel, name in zip(panels, names):
            scale, unit = self.scales.get(name, (1.0, self.units[name]))
            y = self.samples[name] * scale
            draw = panel.step if name.rpartition(".")[2] in STATUS else panel.plot
            draw(x, y, linewidth=1.2, **({"where": "post"} if draw == panel.step else {}))
            panel.set_ylabel(f"{name}\n[{unit}]", fontsize=8)
            panel.grid(True, alpha=0.3)
            if self.trigger is not None and len(x):
                panel.axvline(x[self.trigger], color="tab:red", linestyle="--", linewidth=1)
        if self.trigger is not None and len(x):
            panels[0].annotate(
                "trigger",
                (x[self.trigger], 1.0),
                xycoords=("data", "axes fraction"),
                color="tab:red",
                ha="left",
                va="bottom",
                fontsize=8,
            )
        panels[-1].set_xlabel("chip time [cycles]" if self.chip_time else "cycles since the first sample")
        fig.suptitle(
            f"{title}: {len(x)} samples, every {self.period} cycles, {self.mode}"
            + (", wrapped" if self.wrapped else "")
            + (", running" if self.running else "")
        )
        fig.tight_layout()
        if path is None:
            return fig
        with files.replaced(Path(path)) as f:
            fig.savefig(f, format=Path(path).suffix[1:] or "png", dpi=100)
        plt.close(fig)
        return None


def column_name(slot_word: Tuple[int, int]) -> str:
    """A trace slot's (axis, variable ID) as a column name."""
    axis, variable = slot_word
    name = VARIABLES[variable][0]
    return name if variable in CHIP_WIDE else f"axis{axis + 1}.{name}"


def read(chip) -> Trace:
    """Chip.trace(): reads buffer 0 with the host's own commands (ReadBuffer from the oldest sample)
    on a saved FMU state, then puts the state back, so the chip is as it was (read index, chip time,
    host clock)."""
    ax = chip.axis(0)
    state, host_ns = chip.get_state(), chip._host_ns
    try:
        slots: List[Tuple[int, int]] = []
        for k in range(SLOTS):
            axis, variable = ax.GetTraceVariable(k)
            if variable == 0:  # variable 0 ends the list
                break
            slots.append((axis, variable))
        period, mode, status = ax.GetTracePeriod(), ax.GetTraceMode(), ax.GetTraceStatus()
        count, length, write = ax.GetTraceCount(), ax.GetBufferLength(0), ax.GetBufferWriteIndex(0)
        n = count // len(slots) if slots else 0
        words: List[int] = []
        if n:
            # the newest sample ends at the write index; the samples before it, oldest first
            ax.SetBufferReadIndex(0, (write - n * len(slots)) % length)
            words = [signed(ax.ReadBuffer(0)) for _ in range(n * len(slots))]
    finally:
        chip.set_state(state)
        chip._host_ns = host_ns
    names: List[str] = []
    for s in slots:
        name = column_name(s)
        names.append(name if name not in names else f"{name}#{len(names) + 1}")
    dtype = np.dtype([("cycle", np.int64)] + [(name, np.int32) for name in names])
    samples = np.zeros(n, dtype=dtype)
    values = np.array(words, dtype=np.int64).reshape(n, len(slots)) if n else np.zeros((0, len(slots)), np.int64)
    for k, name in enumerate(names):
        samples[name] = values[:, k]
    times = [k for k, s in enumerate(slots) if s[1] == TIME]
    chip_time = bool(times)
    samples["cycle"] = values[:, times[0]] & 0xFFFFFFFF if chip_time else np.arange(n, dtype=np.int64) * period
    running = bool(status & CONSTANTS["PMDTraceStatusActivity"])
    rolling = mode == CONSTANTS["PMDTraceRollingBuffer"]
    trigger = None if not n or (rolling and running) else (n - 1 if rolling else 0)
    return Trace(
        samples=samples,
        units={name: VARIABLES[s[1]][1] for name, s in zip(names, slots)},
        period=period,
        mode="rolling" if rolling else "one-time",
        wrapped=bool(status & CONSTANTS["PMDTraceStatusDataWrap"]),
        running=running,
        trigger=trigger,
        chip_time=chip_time,
        cycle_time=chip.cycle_time,
        scales={name: VARIABLES[s[1]][2:] for name, s in zip(names, slots)},
    )
