# SPDX-License-Identifier: BSD-2-Clause
"""External profiles from segment tables, following seed 000: buffer set-up
(1.1), loading (1.3), the initial move and the synchronized start (1.4), and
the run until every axis's profile segment number drops to 0 (1.6)."""

from __future__ import annotations

import csv
from fractions import Fraction
from pathlib import Path
from dataclasses import dataclass
from typing import Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import extras, files, fixed, progress
from .chip import AXIS_MASKS, CONSTANTS, DEFAULT_CYCLE_TIME, Chip, FMUError, PMDError, field_ex

FUNCTIONS = ("position", "velocity", "acceleration", "jerk", "time")
Row = Tuple[int, int, int, int, int]


class TableError(ValueError):
    """A segment table that cannot be read or run as written: `file:line: reason`."""


WORD = (-(2**31), 2**32 - 1)  # a buffer word: a signed or an unsigned 32-bit value (encode's rule)


# One segment-table format (docs/scripts.md, "Segment tables"): `pmdfmu run`'s tables and a script's
# LoadSegmentTable read the same columns, optional columns, `# units:` line and decimals; a run's table
# has an `axis` column besides (absent: axis 1). What an absent column holds is what the chip reads
# without its buffer (seed 000): velocity, acceleration and jerk 0, time 1.
ABSENT = {"velocity": 0, "acceleration": 0, "jerk": 0, "time": 1}
# the fraction bits of each column's decimals under `# units: counts/cycle` (16.16 and 0.32); 0: whole
FRACTION_BITS = {"axis": 0, "position": 0, "velocity": 16, "acceleration": 16, "jerk": 32, "time": 0}
UNITS = ("raw", "counts/cycle")


def nearest_column(name: str, columns: Sequence[str]) -> str:
    """`: did you mean 'velocity'?` for a near miss, else the empty string."""
    import difflib

    close = difflib.get_close_matches(name.strip().lower(), columns, n=1, cutoff=0.6)
    return f": did you mean {close[0]!r}?" if close else ""


def read_segment_table(path: Path) -> Dict[int, List[Row]]:
    """Reads a CSV segment table: a header naming its columns -- position (required), velocity,
    acceleration, jerk, time (optional: 0, 0, 0 and 1 when absent, as the chip reads a missing buffer)
    and axis (1..4; absent: every row is axis 1) -- in any order, then a row per segment. Values are raw
    chip words (32.0, 16.16, 16.16, 0.32, cycles), decimal or 0x-hex; after a `# units: counts/cycle`
    line, velocity, acceleration and jerk are counts/cycle (decimals converted exactly, rounded to
    nearest; hex stays a raw word), as LoadSegmentTable reads them. Other lines starting with # are
    comments. Raises TableError naming the file and line of what it cannot take."""
    try:
        text = files.read_text(path)
    except (OSError, UnicodeDecodeError) as e:
        raise TableError(f"{path}: cannot read the segment table: {e}") from None
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    units = None
    for n, line in enumerate(lines, start=1):
        stripped = line.strip()
        if stripped.startswith("#") and "units:" in stripped:
            said = stripped.split("units:", 1)[1].strip()
            if said not in UNITS:
                raise TableError(f"{path}:{n}: units {files.shown(said)}: say raw or counts/cycle")
            if units is not None and said != units:
                raise TableError(f"{path}:{n}: units {files.shown(said)} contradict the units stated before")
            units = said
    # the table's lines with their numbers in the file, comments and blank lines left out
    kept = [(n, line) for n, line in enumerate(lines, start=1) if line.strip() and not line.lstrip().startswith("#")]
    reader = csv.reader([line for _, line in kept])
    columns = ("axis",) + FUNCTIONS
    tables: Dict[int, List[Row]] = {}
    header: List[str] = []
    try:
        for row in reader:
            line = kept[reader.line_num - 1][0]
            if not header:
                header = [h.strip() for h in row]
                for i, name in enumerate(header):
                    if name not in columns:
                        raise TableError(
                            f"{path}:{line}: column {i + 1}: {files.shown(name)} is not a segment column "
                            f"({', '.join(columns)}){nearest_column(name, columns)}"
                        )
                    if name in header[:i]:
                        raise TableError(f"{path}:{line}: column {files.shown(name)} named twice")
                if "position" not in header:
                    raise TableError(
                        f"{path}:{line}: no position column (the header names {', '.join(header)}; a table has "
                        f"position and any of {', '.join(c for c in columns if c != 'position')})"
                    )
                continue
            if len(row) != len(header):
                raise TableError(f"{path}:{line}: expected {len(header)} values (one per column), found {len(row)}")
            values = {**ABSENT, "axis": 1}
            values.update(
                (name, _word(path, line, name, cell, FRACTION_BITS[name] if units == "counts/cycle" else 0))
                for name, cell in zip(header, row)
            )
            if not 1 <= values["axis"] <= 4:
                raise TableError(f"{path}:{line}: axis {values['axis']} is not 1..4")
            tables.setdefault(values["axis"] - 1, []).append(tuple(values[name] for name in FUNCTIONS))
    except csv.Error as e:
        raise TableError(f"{path}:{kept[reader.line_num - 1][0]}: {e}") from None
    if not header:
        raise TableError(f"{path}:1: no header: a segment table's first line names its columns ({', '.join(columns)})")
    if not tables:
        raise TableError(f"{path}: no segment: a row per segment follows the header")
    return tables


def _word(path: Path, line: int, column: str, cell: str, fraction_bits: int = 0) -> int:
    """A table cell as a buffer word: decimal or 0x hex, in WORD; with fraction_bits (16.16, 0.32 under
    `# units: counts/cycle`) a decimal in counts/cycle, converted exactly, rounded to nearest (halves away
    from zero), into a signed word -- as the FMU's LoadSegmentTable does (fmu_src/script/script.c)."""
    text = cell.strip()
    try:
        if fraction_bits and not text.lstrip("+-").lower().startswith("0x"):
            if not text or not all(c.isdigit() or c in "+-." for c in text):
                raise ValueError(text)
            value = fixed.to_fixed(Fraction(text), "16.16" if fraction_bits == 16 else "0.32")
            return fixed.signed(value)
        value = int(text, 0)
    except (ValueError, ZeroDivisionError) as e:
        if "does not fit" in str(e):
            raise TableError(f"{path}:{line}: column {column}: {e}") from None
        raise TableError(
            f"{path}:{line}: column {column}: {files.shown(cell)} is not an integer: a table holds raw chip words "
            "(32.0, 16.16, 16.16, 0.32, cycles), decimal or 0x hex; `# units: counts/cycle` takes decimals for "
            "velocity, acceleration and jerk"
            if not fraction_bits
            else f"{path}:{line}: column {column}: {files.shown(cell)} is not a number"
        ) from None
    if not WORD[0] <= value <= WORD[1]:
        raise TableError(
            f"{path}:{line}: column {column}: {files.shown(cell)} does not fit a 32-bit buffer word "
            f"({WORD[0]}..{WORD[1]})"
        )
    return value


def write_segment_table(path: Path, tables: Dict[int, Sequence[Row]]) -> None:
    with files.replaced(path, text=True) as f:
        w = csv.writer(f)
        w.writerow(("axis",) + FUNCTIONS)
        for axis, rows in sorted(tables.items()):
            for r in rows:
                w.writerow((axis + 1,) + tuple(r))


def load_external_profile(
    chip: Chip, tables: Dict[int, Sequence[Row]], memory_start: int = 0x200, upload: str = "memory"
) -> Dict[int, List[int]]:
    """Gives each axis five buffers (IDs from 2 up, consecutive, not overlapping)
    of the table's length, assigns them to position..time and fills them:
    upload="memory" through the dual-port memory port, "command" with WriteBuffer.
    Returns the buffer IDs of each axis."""
    ids: Dict[int, List[int]] = {}
    buffer_id, address = 2, memory_start
    for axis, rows in sorted(tables.items()):
        ax = chip.axis(axis)
        length = len(rows)
        ids[axis] = []
        for variable in range(5):
            ax.SetBufferStart(buffer_id, address)
            ax.SetBufferLength(buffer_id, length)
            ax.SetBufferFunction(variable, buffer_id)
            column = [r[variable] for r in rows]
            if upload == "memory":  # write_memory takes a negative word as its two's complement, never masks
                chip.write_memory(address, column)
            else:
                for v in column:
                    ax.WriteBuffer(buffer_id, v)
            ids[axis].append(buffer_id)
            buffer_id += 1
            address += length
    return ids


def move_to(
    chip: Chip,
    positions: Dict[int, int],
    velocity: int,
    acceleration: int,
    max_cycles: int = 10_000_000,
    step: int = 256,
) -> int:
    """Trapezoidal moves of the given axes to their positions (seed 000, 1.4);
    runs until all are at rest. Returns the cycles it took; TimeoutError after
    max_cycles."""
    for axis, position in positions.items():
        ax = chip.axis(axis)
        ax.SetProfileMode(CONSTANTS["PMDTrapezoidalProfile"])
        ax.SetVelocity(velocity)
        ax.SetAcceleration(acceleration)
        ax.SetPosition(position)
        ax.Update()
    start = chip.cycles
    while any(chip.axis(a).GetActivityStatus() & CONSTANTS["PMDActivityInMotionMask"] for a in positions):
        if chip.cycles - start > max_cycles:
            targets = ", ".join(f"axis {a + 1} to {p}" for a, p in positions.items())
            raise TimeoutError(f"the initial move ({targets}) is not complete after {max_cycles} cycles")
        chip.run(step)
    return chip.cycles - start


def start_external_profile(chip: Chip, axes: Iterable[int]) -> None:
    """SetProfileMode(PMDExternalProfile) on every axis, then one MultiUpdate:
    a synchronized start (seed 000, 1.4)."""
    mask = 0
    for axis in axes:
        chip.axis(axis).SetProfileMode(CONSTANTS["PMDExternalProfile"])
        mask |= AXIS_MASKS[axis]
    chip.axis(0).MultiUpdate(mask)


def record_outputs(axes: Iterable[int]) -> List[str]:
    names = []
    for axis in axes:
        n = axis + 1
        names += [
            f"axis{n}.commandedPosition",
            f"axis{n}.commandedVelocity",
            f"axis{n}.commandedAcceleration",
            f"axis{n}.position",
            f"axis{n}.velocity",
            f"axis{n}.acceleration",
            f"axis{n}.activityStatus",
        ]
    return names


def _names(axes: Iterable[int], record: Sequence[str]) -> List[str]:
    names = record_outputs(axes)
    return names + [n for n in dict.fromkeys(record) if n not in names]


def _halted(rows: np.ndarray, axes: Sequence[int]) -> np.ndarray:
    """Per row: every axis's profile segment number is 0."""
    done = np.ones(len(rows), dtype=bool)
    for a in axes:
        done &= field_ex(rows[f"axis{a + 1}.activityStatus"], "PMDActivityProfileSegment") == 0
    return done


def run_until_halted(
    chip: Chip,
    axes: Sequence[int],
    max_cycles: int = 1_000_000,
    chunk: int = 1000,
    record: Sequence[str] = (),
    on_cycles: Optional[Callable[[int], object]] = None,
    sink=None,
) -> np.ndarray:
    """Runs and records every cycle until every axis's profile segment number
    is 0 (seed 000, 1.6), or max_cycles. record: outputs recorded besides
    record_outputs(axes) (pmdfmu verify's event status); on_cycles(n): told of every n cycles run (a
    progress bar's update). sink: a recording.NpyFile that takes the rows as they come, up to the first
    halted cycle (what this returns otherwise); then only the last rows written are returned."""
    names = _names(axes, record)
    parts = []
    total, written = 0, False
    while total < max_cycles:
        part = chip.run(min(chunk, max_cycles - total), record=names)
        total += len(part)
        if sink is None:
            parts.append(part)
        elif not written:  # the rows up to the first halted one, as the concatenation is cut below
            done = _halted(part, axes)
            written = bool(done.any())
            parts = [part[: int(np.argmax(done)) + 1] if written else part]
            sink.write(parts[0])
        if on_cycles is not None:
            on_cycles(len(part))
        last = part[-1]
        if all(field_ex(last[f"axis{a + 1}.activityStatus"], "PMDActivityProfileSegment") == 0 for a in axes):
            break
    if sink is not None:
        return parts[0]
    out = np.concatenate(parts)
    done = np.ones(len(out), dtype=bool)
    for a in axes:
        done &= field_ex(out[f"axis{a + 1}.activityStatus"], "PMDActivityProfileSegment") == 0
    end = int(np.argmax(done)) + 1 if done.any() else len(out)
    return out[:end]


def script_axes(chip: Chip) -> List[int]:
    """The axes (0..3) the chip's compiled script addresses, as the FMU reports
    them (script.axes); axis 0 alone for a script that addresses none."""
    mask = chip.get("script.axes")
    return [axis for axis, bit in enumerate(AXIS_MASKS) if mask & bit] or [0]


def run_script(
    chip: Chip,
    axes: Optional[Sequence[int]] = None,
    max_cycles: int = 1_000_000,
    chunk: int = 1000,
    record: Sequence[str] = (),
    on_cycles: Optional[Callable[[int], object]] = None,
    sink=None,
) -> np.ndarray:
    """Records a script's run (the chip was made with script=...): until the time
    of its last @ line has passed (script.lastCycle) and every axis is at rest, or
    max_cycles. axes: those to record, by default script_axes(chip); record:
    outputs recorded besides record_outputs(axes); sink: a recording.NpyFile that takes the rows as they
    come (then only the last rows are returned)."""
    axes = script_axes(chip) if axes is None else axes
    last = chip.get("script.lastCycle")
    names = _names(axes, record)
    parts, total = [], 0
    while total < max_cycles:
        part = chip.run(min(chunk, max_cycles - total), record=names)
        if sink is None:
            parts.append(part)
        else:  # written as it comes: only the last part is kept (returned)
            sink.write(part)
            parts = [part]
        total += len(part)
        if on_cycles is not None:
            on_cycles(len(part))
        at_rest = all(not part[-1][f"axis{a + 1}.activityStatus"] & CONSTANTS["PMDActivityInMotionMask"] for a in axes)
        if part["cycle"][-1] >= last and at_rest:
            break
    return np.concatenate(parts)


def run_segment_table(
    chip: Chip,
    tables: Dict[int, Sequence[Row]],
    velocity: int = 0x40000,
    acceleration: int = 0x1000,
    upload: str = "memory",
    max_cycles: int = 1_000_000,
    record: Sequence[str] = (),
    on_cycles: Optional[Callable[[int], object]] = None,
    sink=None,
) -> np.ndarray:
    """The whole of seed 000 for a table: load, move each axis to its first
    position, start all axes together, run to completion. Returns the recorded
    cycles of the external profile (record: outputs besides record_outputs)."""
    axes = sorted(tables)
    load_external_profile(chip, tables, upload=upload)
    move_to(chip, {a: tables[a][0][0] for a in axes}, velocity, acceleration)
    start_external_profile(chip, axes)
    return run_until_halted(chip, axes, max_cycles=max_cycles, record=record, on_cycles=on_cycles, sink=sink)


def write_csv(path: Path, recorded: np.ndarray, comment: Optional[str] = None) -> None:
    """A recording as CSV: a header of its column names, a row per cycle; comment: a first line (`# ...`)."""
    names = recorded.dtype.names
    with files.replaced(path, text=True) as f:
        if comment is not None:
            f.write(comment + "\n")
        w = csv.writer(f)
        w.writerow(names)
        for row in recorded:
            w.writerow([repr(float(row[n])) if recorded.dtype[n].kind == "f" else int(row[n]) for n in names])


def plot(path: Path, recorded: np.ndarray, cycle_time: float, title: str = "External profile") -> None:
    """Position, velocity and acceleration of each recorded axis over time,
    and the path of the first two axes in the plane."""
    plt = extras.pyplot("pmdfmu.profile.plot")

    axes = sorted({int(n[4]) for n in recorded.dtype.names if n.startswith("axis")})
    t = recorded["cycle"] * cycle_time
    fig, grid = plt.subplots(2, 2, figsize=(12, 8))
    for panel, quantity, unit in zip(
        grid.flat, ("position", "velocity", "acceleration"), ("counts", "counts/s", "counts/s^2")
    ):
        for n in axes:
            panel.plot(t, recorded[f"axis{n}.{quantity}"], label=f"axis {n}")
        panel.set_ylabel(f"{quantity} [{unit}]")
        panel.set_xlabel("time [s]")
        panel.legend()
    xy = grid.flat[3]
    if len(axes) >= 2:
        xy.plot(recorded[f"axis{axes[0]}.position"], recorded[f"axis{axes[1]}.position"])
        xy.set_xlabel(f"axis {axes[0]} [counts]")
        xy.set_ylabel(f"axis {axes[1]} [counts]")
        xy.set_aspect("equal", adjustable="datalim")
    else:
        xy.axis("off")
    fig.suptitle(title)
    fig.tight_layout()
    with files.replaced(path) as f:
        fig.savefig(f, format=Path(path).suffix[1:] or "png", dpi=100)
    plt.close(fig)


# ---- what `pmdfmu run FILE` runs (pmdfmu verify runs the same) ----------------------


@dataclass
class ProfileRun:
    """A run of run_profile: the recording, the axes recorded (0..3), the chip's
    cycle time (s), the FMU's log messages (warnings: refused script commands) and
    whether the profile had ended by the recording's last cycle (profile_ended):
    False when max_cycles cut the run short; window: the caller asked for such a
    cut (`pmdfmu run --cycles N`)."""

    recording: np.ndarray
    axes: List[int]
    cycle_time: float
    messages: list
    ended: bool = True
    window: bool = False  # the caller asked for the first max_cycles cycles, the profile ended or not


def profile_ended(recording: np.ndarray, axes: Sequence[int], last_script_cycle: Optional[int] = None) -> bool:
    """Whether the profile had ended at the recording's last cycle, as run_until_halted and run_script
    stop: a table's when every axis's profile segment number is 0 (seed 000, 1.6); a script's
    (last_script_cycle: script.lastCycle) when the time of its last @ line has passed and every axis
    is at rest."""
    if not len(recording):
        return False
    last = recording[-1]
    if last_script_cycle is None:
        return all(field_ex(last[f"axis{a + 1}.activityStatus"], "PMDActivityProfileSegment") == 0 for a in axes)
    at_rest = all(not last[f"axis{a + 1}.activityStatus"] & CONSTANTS["PMDActivityInMotionMask"] for a in axes)
    return bool(last["cycle"] >= last_script_cycle and at_rest)


def is_segment_table(path: Union[str, Path]) -> bool:
    """`pmdfmu run`'s rule: a .csv file is a segment table; anything else is a script."""
    return Path(path).suffix.lower() == ".csv"


def run_profile(
    source: Union[str, Path, Dict[int, Sequence[Row]]],
    fmu: Optional[str] = None,
    fmi_version: int = 2,
    cycle_time: float = DEFAULT_CYCLE_TIME,
    upload: str = "memory",
    max_cycles: int = 1_000_000,
    record: Sequence[str] = (),
    parameters: Optional[dict] = None,
    inspect: Optional[Callable[[Chip], None]] = None,
    sink=None,
) -> ProfileRun:
    """Runs a script file, a segment table file (is_segment_table) or tables
    read already, as `pmdfmu run` does: a table on a chip with no script
    (run_segment_table), a script with script=... (run_script); the FMU's
    warnings are logged. parameters: further FMU parameters (memorySize, ...);
    inspect(chip) is called after the run, before the chip closes. The first n
    rows of a run with max_cycles=n are those of any longer run. sink: a recording.NpyFile taking the rows
    as they come (`pmdfmu run --out`); the run's recording is then its last rows only."""
    params = dict(parameters or {})
    params.setdefault("cycleTime", cycle_time)
    path = Path(source) if isinstance(source, (str, Path)) else None
    table = path is None or is_segment_table(path)
    tables = (source if path is None else read_segment_table(path)) if table else None
    params["script"] = "" if table else path  # a file, never a script's text (docs/scripts.md)
    with (
        Chip(fmi_version=fmi_version, fmu=fmu, log_categories=["warnings"], **params) as chip,
        progress.bar(f"run {path.name if path is not None else 'segment tables'}") as bar,
    ):
        if table:
            axes = sorted(tables)
            try:
                rec = run_segment_table(
                    chip, tables, upload=upload, max_cycles=max_cycles, record=record, on_cycles=bar.update, sink=sink
                )
            except (PMDError, FMUError) as e:  # the chip refused the table's set-up (it does not fit, ...)
                raise TableError(f"{path or 'segment tables'}: {e}") from None
            except TimeoutError as e:  # a first row's position too far away
                raise TableError(
                    f"{path or 'segment tables'}: {e}: an axis starts at its first row's position"
                ) from None
            ended = profile_ended(rec, axes)
        else:
            axes = script_axes(chip)
            rec = run_script(chip, axes, max_cycles=max_cycles, record=record, on_cycles=bar.update, sink=sink)
            ended = profile_ended(rec, axes, chip.get("script.lastCycle"))
        if inspect is not None:
            inspect(chip)
        return ProfileRun(rec, list(axes), chip.cycle_time, list(chip.messages), ended)
