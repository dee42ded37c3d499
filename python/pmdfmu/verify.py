# SPDX-License-Identifier: BSD-2-Clause
"""`pmdfmu verify`: run a profile as `pmdfmu run` does and check it
against a golden trace and declarative assertions, with reports a CI pipeline
acts on (exit status, JUnit XML, Markdown, diff plots). docs/verify.md has the
formats, units and exit statuses.

    result = pmdfmu.verify("examples/two_axis.script", against="examples/ci/two_axis.golden.npz",
                           assertions="examples/ci/two_axis.toml")
    result.passed, result.failures              # Failure: check, axis, column, cycle, values, limit
    print(result.report()); result.to_junit(); result.to_markdown()

    result = pmdfmu.verify_cases("cases.csv")   # a sweep's case table + golden, assertions columns, on Dask
"""

from __future__ import annotations

import csv
import dataclasses
import io
import math
import re
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import files, profile
from .files import shown
from .chip import CONSTANTS, DEFAULT_CYCLE_TIME, DTYPES, field_ex

# what a verification found, and its reports
from .verify_report import EXIT_FAIL, EXIT_INPUT, EXIT_PASS, CaseResult, Check, Failure, VerifyResult  # noqa: F401

NPZ_KEY = "recording"  # the one array of a .npz golden: the structured array `pmdfmu run` records
NPZ_ENDED = "ended"  # beside it: whether the profile had ended by its last cycle (a 0-d bool; absent: it had)
WINDOW_COMMENT = "# pmdfmu: a window"  # a CSV golden's first line when its profile had not ended
PathLike = Union[str, Path]


class InputError(ValueError):
    """A malformed input of verify's own -- a golden trace, an assertion file, a case table, a flag --
    named with its file and line (exit status 2). The profile under test failing is a failure, not this."""


# ---- recordings: CSV (profile.write_csv) and compressed numpy ------------------------------------


def write_recording(path: PathLike, recording: np.ndarray, ended: bool = True) -> None:
    """A recording as a golden trace: a .npz name writes np.savez_compressed (the structured array, its
    column types kept, and `ended`), any other name profile.write_csv's CSV (a recording whose profile
    had not ended, a window, first says so in a comment line: WINDOW_COMMENT). ended: whether the
    profile had ended by the recording's last cycle (profile.ProfileRun.ended)."""
    path = Path(path)
    if path.suffix.lower() == ".npz":
        with files.replaced(path) as f:
            np.savez_compressed(f, **{NPZ_KEY: recording, NPZ_ENDED: np.array(bool(ended))})
    else:
        profile.write_csv(path, recording, comment=None if ended else window_comment(recording))


def window_comment(recording: np.ndarray) -> str:
    """The first line of a CSV recording cut short (read_golden knows it by WINDOW_COMMENT)."""
    end = f" at cycle {int(recording['cycle'][-1])}" if len(recording) else ""
    return f"{WINDOW_COMMENT} of {len(recording)} cycles: the profile had not ended{end}"


@dataclass
class Golden:
    """A golden trace as read_golden reads it: the recording, and whether its profile had ended by its last
    cycle (False: a window, `pmdfmu run --cycles N`; a golden written before goldens said so reads as
    ended)."""

    recording: np.ndarray
    ended: bool = True


def _read_input(path: Path, what: str) -> str:
    """A file of verify's own as text: a regular file (files.read_text), else InputError."""
    try:
        return files.read_text(path)
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot read the {what}: {e}") from None


def _range_of(name: str) -> Tuple[int, int]:
    """The values an integer column holds: its register's type; `cycle` is chip time, at least 0."""
    if name == "cycle":
        return 0, np.iinfo(np.int64).max
    dtype = np.dtype(DTYPES[name])
    return (0, 1) if dtype.kind == "b" else (int(np.iinfo(dtype).min), int(np.iinfo(dtype).max))


def read_recording(path: PathLike) -> np.ndarray:
    """A golden trace written by write_recording (or `pmdfmu run --csv`): a structured array with a `cycle`
    column. Raises InputError naming the file, line and column of what it cannot read."""
    return read_golden(path).recording


def read_golden(path: PathLike) -> Golden:
    """A golden trace (read_recording) and whether its profile had ended (a window says it had not: the
    .npz's `ended`, the CSV's first line WINDOW_COMMENT; a golden that does not say had ended)."""
    path = Path(path)
    if path.suffix.lower() == ".npz":
        return _read_npz(path)
    text = _read_input(path, "golden trace")
    # comment lines before the header: the window's, or a person's
    lines = text.split("\n")
    skipped = 0
    while skipped < len(lines) and lines[skipped].lstrip().startswith("#"):
        skipped += 1
    ended = not any(line.strip().startswith(WINDOW_COMMENT) for line in lines[:skipped])
    reader = csv.reader(io.StringIO("\n".join(lines[skipped:]), newline=""))
    try:
        rows = list(reader)
    except csv.Error as e:  # a field over csv's limit of 131072 characters, a NUL byte
        raise InputError(f"{path}:{reader.line_num + skipped}: {e}") from None
    if not rows or not rows[0]:
        raise InputError(f"{path}:{skipped + 1}: no header: a golden trace is `pmdfmu run ... --csv` output")
    header = [h.strip() for h in rows[0]]
    _check_columns(path, header, skipped + 1)
    # the chip's registers are integers: a golden's cell of one that is not, or that the register cannot
    # hold, is a malformed golden; a Real's cell is a double's text (profile.write_csv writes its repr)
    ranges = [_range_of(h) if h == "cycle" or np.dtype(DTYPES[h]).kind in "iub" else None for h in header]
    columns: List[list] = [[] for _ in header]
    for line, row in enumerate(rows[1:], start=skipped + 2):
        if len(row) != len(header):
            raise InputError(f"{path}:{line}: {len(row)} values, the header names {len(header)} columns")
        for i, cell in enumerate(row):
            text, where = cell.strip(), f"{path}:{line}: column {i + 1} ({header[i]})"
            if ranges[i] is None:
                try:
                    columns[i].append(float(text))
                except ValueError:
                    raise InputError(f"{where}: {shown(cell)} is not a number") from None
                continue
            try:
                value = int(text)
            except ValueError:  # also more digits than int() reads (sys.get_int_max_str_digits)
                try:
                    float(text)
                except ValueError:
                    raise InputError(f"{where}: {shown(cell)} is not a number") from None
                raise InputError(f"{where}: {shown(cell)} is not an integer (the FMU's register is)") from None
            low, high = ranges[i]
            if not low <= value <= high:
                raise InputError(f"{where}: {shown(cell)} is outside {low}..{high}, the values the column holds")
            columns[i].append(value)
    out = np.zeros(len(rows) - 1, dtype=[(h, np.float64 if r is None else np.int64) for h, r in zip(header, ranges)])
    for name, values in zip(header, columns):
        out[name] = values
    return Golden(out, ended)


def _read_npz(path: Path) -> Golden:
    try:
        files.check_regular(path)  # np.load would wait on a FIFO
        with np.load(path, allow_pickle=False) as data:
            if NPZ_KEY not in data.files:
                raise InputError(
                    f"{path}: no array {NPZ_KEY!r} (it holds {shown(', '.join(data.files) or 'none')}): "
                    "write goldens with `pmdfmu run ... --csv NAME.npz`"
                )
            rec = data[NPZ_KEY]
            ended = data[NPZ_ENDED] if NPZ_ENDED in data.files else np.array(True)
    except InputError:
        raise
    except Exception as e:  # a missing file, not a zip, a damaged member, a pickled array
        why = e.strerror if isinstance(e, OSError) and e.strerror else e  # not "[Errno 2] ...: 'path'" again
        raise InputError(f"{path}: cannot read the golden trace: {why}") from None
    if rec.dtype.names is None or rec.ndim != 1:
        raise InputError(f"{path}: {NPZ_KEY!r} is not a recording (a 1-d structured array)")
    if ended.shape != () or ended.dtype.kind != "b":
        raise InputError(f"{path}: {NPZ_ENDED!r} is not true or false (a 0-d bool array)")
    _check_columns(path, list(rec.dtype.names))
    for i, name in enumerate(rec.dtype.names, start=1):
        _check_npz_type(path, i, name, rec.dtype[name], rec[name])
    return Golden(rec, bool(ended))


def _check_npz_type(path: Path, i: int, name: str, dtype: np.dtype, values: np.ndarray) -> None:
    """A golden's column holds what a recording's does: integers for `cycle` and the registers (within the
    register's values), float64 for a Real (the FMU's type). float16/32 cannot hold the FMU's values;
    complex numbers, strings and sub-arrays are no recording's."""
    where = f"{path}: column {i} ({name})"
    integer = name == "cycle" or np.dtype(DTYPES[name]).kind in "iub"
    if dtype.shape or not (dtype.kind in "iub" if integer else dtype.kind == "f" and dtype.itemsize == 8):
        raise InputError(
            f"{where}: {dtype.str if not dtype.shape else dtype} is not a recording's type "
            f"({'integers' if integer else 'float64'})"
        )
    if integer and len(values):
        low, high = _range_of(name)
        lowest, highest = int(values.min()), int(values.max())
        if lowest < low or highest > high:
            raise InputError(
                f"{where}: {lowest if lowest < low else highest} is outside {low}..{high}, the values the column holds"
            )


def _check_columns(path: Path, header: Sequence[str], line: int = 1) -> None:
    if "cycle" not in header:
        raise InputError(f"{path}:{line}: no 'cycle' column: a golden trace is `pmdfmu run ... --csv` output")
    seen = set()
    for i, name in enumerate(header, start=1):
        if name in seen:
            raise InputError(f"{path}:{line}: column {i}: {shown(name)} named twice")
        seen.add(name)
        if name != "cycle" and name not in DTYPES:
            raise InputError(
                f"{path}:{line}: column {i}: {shown(name)} is not an output of the FMU (pmdfmu info lists them)"
            )


# ---- assertions ---------------------------------------------------------------------------------

EVENTS = {
    name[len("PMDEvent") : -len("Mask")]: value
    for name, value in CONSTANTS.items()
    if name.startswith("PMDEvent") and name.endswith("Mask")
}
DEFAULT_EVENTS = ("MotionError", "InPositiveLimit", "InNegativeLimit")
IN_MOTION = CONSTANTS["PMDActivityInMotionMask"]
INSTRUCTION_ERROR = CONSTANTS["PMDEventInstructionErrorMask"]
UNITS = ("counts", "raw")
# per axis: key -> (type, words for messages); the order is the order of the checks
AXIS_KEYS = {
    "max_velocity": (float, "max |velocity|"),
    "max_acceleration": (float, "max |acceleration|"),
    "max_jerk": (float, "max |jerk|"),
    "max_step": (float, "max |position step|"),
    "position_min": (int, "position >="),
    "position_max": (int, "position <="),
    "final_position": (int, "final position"),
    "complete_by": (int, "motion complete by cycle"),
    "no_events": (object, "no events"),
}
TOP_KEYS = ("units", "no_host_errors", "tolerance", "all_axes", "axis1", "axis2", "axis3", "axis4")
# the quantity each limit reads, in each unit: (register column, scale of its per-cycle difference, unit text)
QUANTITIES = {
    ("velocity", "counts"): ("velocity", None, "counts/s"),
    ("acceleration", "counts"): ("acceleration", None, "counts/s^2"),
    ("jerk", "counts"): ("acceleration", "per_s", "counts/s^3"),
    ("velocity", "raw"): ("commandedVelocity", None, "raw 16.16 counts/cycle"),
    ("acceleration", "raw"): ("commandedAcceleration", None, "raw 16.16 counts/cycle^2"),
    ("jerk", "raw"): ("commandedAcceleration", 65536, "raw 0.32 counts/cycle^3"),
}
# the same quantities from the position's own differences: (order of the difference, a raw unit's value of
# 1 count/cycle^order, what the difference is called). The position is axisN.position, the commanded
# position with its fraction (the chip's 16 fraction bits), so each difference is exact.
DIFFERENCES = {
    "velocity": (1, 65536, "difference"),
    "acceleration": (2, 65536, "second difference"),
    "jerk": (3, 2**32, "third difference"),
}
# One count of jump in the position passes: an external profile's segment starts at its row's whole count
# (32.0) while the position run up to it has a fraction, so a table that is right jumps by less than a
# count at a segment's start. A jump of e counts moves the k-th difference by at most e * C(k-1, (k-1)//2):
# 1, 1 and 2 counts per cycle^k for velocity, acceleration and jerk.
JUMP_ALLOWED = {1: 1, 2: 1, 3: 2}
RAW_UNITS = {
    "commandedVelocity": (1, "counts/cycle", "counts/s"),
    "commandedAcceleration": (2, "counts/cycle^2", "counts/s^2"),
}


def converted(column: str, value, cycle_time: Optional[float]) -> str:
    """A raw 16.16 register value's meaning, for reports: `(-2 counts/cycle = -20000 counts/s)`; the empty
    string for any other column."""
    unit = RAW_UNITS.get(column.partition(".")[2])
    if unit is None or value is None:
        return ""
    order, per_cycle, per_second = unit
    counts = float(value) / 65536
    text = f" ({counts:g} {per_cycle}"
    if cycle_time:
        text += f" = {counts / cycle_time**order:g} {per_second}"
    return text + ")"


@dataclass
class Assertions:
    """Limits on a trajectory (docs/verify.md): units "counts" or "raw"; axes maps 0..3, or None for every
    recorded axis (the file's [all_axes]), to {key of AXIS_KEYS: value}; tolerance: column -> absolute
    tolerance of the golden comparison."""

    units: str = "counts"
    no_host_errors: bool = False
    tolerance: Dict[str, float] = field(default_factory=dict)
    axes: Dict[Optional[int], Dict[str, object]] = field(default_factory=dict)

    @property
    def empty(self) -> bool:
        return not (self.no_host_errors or any(self.axes.values()))

    def for_axes(self, recorded: Sequence[int]) -> Dict[int, Dict[str, object]]:
        """Each axis's limits: [all_axes] for every recorded axis, an axis's own table over it."""
        out: Dict[int, Dict[str, object]] = {}
        for axis in sorted(set(recorded) | {a for a in self.axes if a is not None}):
            limits = dict(self.axes.get(None, {})) if axis in recorded else {}
            limits.update(self.axes.get(axis, {}))
            if limits:
                out[axis] = limits
        return out

    def columns(self) -> List[str]:
        """Outputs these assertions read besides a profile's own: the event status, of every axis."""
        if self.no_host_errors or any("no_events" in limits for limits in self.axes.values()):
            return [f"axis{n}.eventStatus" for n in range(1, 5)]
        return []


def _toml():
    try:
        import tomllib  # Python >= 3.11
    except ImportError:  # pragma: no cover - Python 3.9/3.10: pyproject's tomli
        try:
            import tomli as tomllib
        except ImportError:
            raise InputError("assertion files are TOML: Python 3.11+ reads them, or install tomli") from None
    return tomllib


def _read_assertion_file(path: Path) -> Tuple[dict, str]:
    """An assertion file's shape (a dict) and its text; InputError if it is no TOML file."""
    text = _read_input(path, "assertion file")
    tomllib = _toml()
    try:
        return tomllib.loads(text), text
    except tomllib.TOMLDecodeError as e:  # its message ends "(at line L, column C)": file:line: reason
        where = re.search(r" \(at line (\d+), column (\d+)\)$", str(e))
        if where:
            reason = f"{str(e)[: where.start()]} (column {where.group(2)})"
            raise InputError(f"{path}:{where.group(1)}: not TOML: {reason}") from None
        raise InputError(f"{path}: not TOML: {e}") from None
    except RecursionError:  # tomllib nests a Python call per [ or { of the file
        raise InputError(f"{path}: not TOML this parser reads: arrays or tables nested too deeply") from None


def read_assertions(path: PathLike) -> Assertions:
    """An assertion file (TOML, docs/verify.md); InputError with the file and line of what is wrong."""
    path = Path(path)
    data, text = _read_assertion_file(path)
    return parse_assertions(data, str(path), text)


def _line_of(text: Optional[str], key: str) -> str:
    """':L' of the line that first names key (as a key or a [table]) in text, for messages."""
    if text:
        pattern = re.compile(r'^\s*(\[\s*)?["\']?' + re.escape(key) + r'["\']?\s*(=|\])')
        for n, line in enumerate(text.splitlines(), start=1):
            if pattern.match(line):
                return f":{n}"
    return ""


LIMIT_RANGE = 2**63 - 1  # a limit is compared with int64 columns: beyond it, no column's value


def _limit_number(value) -> bool:
    """A limit or tolerance: a TOML integer or float, finite, within +-LIMIT_RANGE (TOML integers have no
    bound in tomllib: 10**400 would overflow the float a comparison makes of it; a float such as 1e300
    is no limit either)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return False
    return (isinstance(value, int) or math.isfinite(value)) and abs(value) <= LIMIT_RANGE


def parse_assertions(data: Mapping, where: str = "assertions", text: Optional[str] = None) -> Assertions:
    """Assertions from the TOML file's shape (a dict); where/text name the source in messages."""

    def bad(key, message, named=None):  # named: the key as the file writes it, to find its line
        shown = key if len(key) <= 60 else f"{key[:60]}... ({len(key)} characters)"
        return InputError(f"{where}{_line_of(text, named or key.split('.')[-1])}: {shown}: {message}")

    result = Assertions()
    for key in data:
        if key not in TOP_KEYS:
            raise bad(key, f"unknown key (known: {', '.join(TOP_KEYS)})")
    units = data.get("units", "counts")
    if units not in UNITS:
        raise bad("units", f"{shown(units)} is not one of {', '.join(UNITS)}")
    result.units = units
    if not isinstance(data.get("no_host_errors", False), bool):
        raise bad("no_host_errors", "is true or false")
    result.no_host_errors = data.get("no_host_errors", False)
    tolerance = data.get("tolerance", {})
    if not isinstance(tolerance, Mapping):
        raise bad("tolerance", 'is a table of column = tolerance ("axis1.velocity" = 1e-9)')
    for column, value in tolerance.items():
        if column != "cycle" and column not in DTYPES:
            raise bad(column, "unknown column: not an output of the FMU (pmdfmu info lists them)", column)
        if not _limit_number(value) or value < 0:
            raise bad(column, f"the tolerance {shown(value)} is not a finite number >= 0", column)
        result.tolerance[column] = float(value)
    for name in ("all_axes", "axis1", "axis2", "axis3", "axis4"):
        if name not in data:
            continue
        table = data[name]
        if not isinstance(table, Mapping):
            raise bad(name, "is a table ([" + name + "])")
        axis = None if name == "all_axes" else int(name[4]) - 1
        limits = {}
        for key, value in table.items():
            if key not in AXIS_KEYS:
                raise bad(f"{name}.{key}", f"unknown limit (known: {', '.join(AXIS_KEYS)})")
            kind = AXIS_KEYS[key][0]
            if key == "no_events":
                if value is True:
                    value = list(DEFAULT_EVENTS)
                elif value is False:
                    continue
                if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
                    raise bad(f"{name}.{key}", 'is true or a list of event names such as ["MotionError"]')
                unknown = [v for v in value if v not in EVENTS]
                if unknown:
                    raise bad(f"{name}.{key}", f"unknown event {shown(unknown[0])} (known: {', '.join(EVENTS)})")
            elif not _limit_number(value) or (kind is int and not float(value).is_integer()):
                # nan would pass every comparison, inf is no limit: both refused
                number = not isinstance(value, bool) and isinstance(value, (int, float))
                want = (
                    "a number"
                    if not number
                    else f"a finite number in {-LIMIT_RANGE}..{LIMIT_RANGE}"
                    if not _limit_number(value)
                    else "a whole number"
                )
                raise bad(f"{name}.{key}", f"{shown(value)} is not {want}")
            else:
                value = kind(value)
            limits[key] = value
        if "position_min" in limits and "position_max" in limits and limits["position_min"] > limits["position_max"]:
            raise bad(f"{name}.position_min", "is above position_max")
        result.axes[axis] = limits
    return result


def _assertion_data(assertions: Union[None, PathLike, Mapping]) -> Tuple[dict, str, Optional[str]]:
    """(the file's shape, where it came from, its text) of a file or a dict; a file's own errors raised."""
    if assertions is None:
        return {}, "command line", None
    if isinstance(assertions, Mapping):
        parse_assertions(assertions)
        return dict(assertions), "assertions", None
    path = Path(assertions)
    data, text = _read_assertion_file(path)
    parse_assertions(data, str(path), text)
    return data, str(path), text


def _merge(base: Mapping, over: Mapping) -> dict:
    """over's keys over base's; tables merge key by key."""
    out = dict(base)
    for key, value in over.items():
        out[key] = {**out[key], **value} if isinstance(value, Mapping) and isinstance(out.get(key), Mapping) else value
    return out


def load_assertions(
    assertions: Union[None, PathLike, Mapping, Assertions], extra: Optional[Mapping] = None
) -> Assertions:
    """A file, a dict of the file's shape or Assertions, with `extra` (the command line's limits, the
    file's shape) over it."""
    if isinstance(assertions, Assertions):
        if extra:
            raise TypeError("give an assertion file or a dict to merge limits into")
        return assertions
    data, where, text = _assertion_data(assertions)
    if not extra:
        return parse_assertions(data, where, text)
    return parse_assertions(
        _merge(data, extra),
        "the command line's limits" if where == "command line" else f"{where} with the command line's limits",
        text,
    )


# ---- the golden comparison ------------------------------------------------------------------------


def _axis_of(column: str) -> Optional[int]:
    m = re.match(r"axis([1-4])\.", column)
    return int(m.group(1)) if m else None


def _number(value):
    return float(value) if isinstance(value, (float, np.floating)) else int(value)


def _segment(rec: np.ndarray, axis: int, row: int) -> Optional[int]:
    column = f"axis{axis}.activityStatus"
    if rec is None or column not in (rec.dtype.names or ()) or row >= len(rec):
        return None
    return int(field_ex(int(rec[column][row]), "PMDActivityProfileSegment"))


def _values(column: str, expected, actual, cycle_time: Optional[float], named: bool = True) -> str:
    """`axis2.commandedVelocity expected -131072 (-2 counts/cycle = -20000 counts/s), actual ...` for reports."""
    return (
        f"{column + ' ' if named else ''}expected {expected!r}{converted(column, expected, cycle_time)}, "
        f"actual {actual!r}{converted(column, actual, cycle_time)} (difference {actual - expected:+g})"
    )


def compare(
    expected: np.ndarray,
    actual: np.ndarray,
    required: Sequence[str] = (),
    tolerance: Optional[Mapping[str, float]] = None,
    cycle_time: Optional[float] = None,
) -> List[Failure]:
    """The golden comparison, cycle by cycle: every column of the golden (integer columns bit-exact; Reals
    exact unless tolerance names them: |actual - expected| <= tolerance); required: the columns the run
    records that the golden must hold; different lengths fail. At most one failure each for columns and
    length; for values, the first diverging row (the first failure), then every other differing column
    at its own first row. cycle_time: raw 16.16 values are shown in counts/s too."""
    tolerance = tolerance or {}
    failures = []
    e_names, a_names = expected.dtype.names, actual.dtype.names
    lacking = [c for c in required if c not in e_names]
    if lacking:
        failures.append(
            Failure(
                "golden",
                f"the run records {', '.join(lacking)}, which the golden trace does "
                "not hold (does the profile address other axes now?)",
                column=lacking[0],
                axis=_axis_of(lacking[0]),
            )
        )
    unrecorded = [c for c in e_names if c not in a_names]
    if unrecorded:
        failures.append(
            Failure(
                "golden",
                f"the golden trace holds {', '.join(unrecorded)}, which the run did not "
                "record (does the profile address other axes now?)",
                column=unrecorded[0],
                axis=_axis_of(unrecorded[0]),
            )
        )
    n = min(len(expected), len(actual))
    first: Dict[str, Tuple[int, int]] = {}
    for c in e_names:
        if c not in a_names:
            continue
        e, a = expected[c][:n], actual[c][:n]
        if c in tolerance:
            bad = ~(np.abs(a.astype(np.float64) - e.astype(np.float64)) <= tolerance[c])
        elif e.dtype.kind == "f" or a.dtype.kind == "f":
            e64, a64 = e.astype(np.float64), a.astype(np.float64)
            bad = (e64 != a64) & ~(np.isnan(e64) & np.isnan(a64))
        else:
            bad = e.astype(np.int64) != a.astype(np.int64)
        if bad.any():
            first[c] = (int(np.argmax(bad)), int(bad.sum()))
    if first:
        row = min(i for i, _ in first.values())
        at = [c for c in e_names if c in first and first[c][0] == row]
        column = at[0]
        e, a = _number(expected[column][row]), _number(actual[column][row])
        axis = _axis_of(column)
        text = f"first difference at cycle {int(actual['cycle'][row])} (row {row}): " + _values(
            column, e, a, cycle_time
        )
        if len(at) > 1:
            text += f"; at that cycle also {', '.join(at[1:])}"
        axes = [axis] if axis else sorted({x for x in map(_axis_of, a_names) if x})
        where = []
        for x in axes:
            seg, golden_seg = _segment(actual, x, row), _segment(expected, x, row)
            if seg is not None:
                where.append(
                    f"axis {x} in profile segment {seg}"
                    + (f" (golden: {golden_seg})" if golden_seg is not None and golden_seg != seg else "")
                )
        if where:
            text += "; " + ", ".join(where)
        text += f". {column} differs in {first[column][1]} of {n} rows"
        failures.append(
            Failure(
                "golden",
                text,
                axis=axis,
                column=column,
                cycle=int(actual["cycle"][row]),
                row=row,
                expected=e,
                actual=a,
                segment=_segment(actual, axis, row) if axis else None,
            )
        )
        # every other column that differs, at its own first row: which axes and quantities diverge
        for other in sorted((c for c in first if c != column), key=lambda c: (first[c][0], e_names.index(c))):
            i, count = first[other]
            e, a = _number(expected[other][i]), _number(actual[other][i])
            failures.append(
                Failure(
                    "golden",
                    f"{other} first differs at cycle {int(actual['cycle'][i])} (row {i}): "
                    f"{_values(other, e, a, cycle_time, named=False)}; in {count} of {n} rows",
                    axis=_axis_of(other),
                    column=other,
                    cycle=int(actual["cycle"][i]),
                    row=i,
                    expected=e,
                    actual=a,
                )
            )
    if len(expected) != len(actual):

        def end(rec):
            return f"cycle {int(rec['cycle'][-1])}" if len(rec) else "no cycle"

        failures.append(
            Failure(
                "length",
                f"the run recorded {len(actual)} cycles (to {end(actual)}), the golden "
                f"trace {len(expected)} (to {end(expected)})",
                cycle=int(actual["cycle"][n - 1]) if n else None,
                row=n,
                expected=len(expected),
                actual=len(actual),
            )
        )
    return failures


# ---- the assertions -------------------------------------------------------------------------------


def _first_violation(
    key: str, n: int, values: np.ndarray, bad: np.ndarray, offset: int, rec: np.ndarray, limit, column: str
) -> Failure:
    """A Failure at the first row where bad is set; values[i] belongs to row i + offset."""
    i, peak = int(np.argmax(bad)), int(np.argmax(np.abs(values)))
    return Failure(
        key,
        "",
        axis=n,
        column=column,
        cycle=int(rec["cycle"][i + offset]),
        row=i + offset,
        value=_number(values[i]),
        limit=limit,
        peak=_number(values[peak]),
        peak_cycle=int(rec["cycle"][peak + offset]),
    )


def _register_check(key: str, n: int, limit, rec: np.ndarray, units: str, cycle_time: float) -> List[Failure]:
    """|velocity|, |acceleration| or |jerk| as the chip's registers give them (jerk: the acceleration's
    change from cycle to cycle)."""
    quantity = key[4:]
    column, scale, unit = QUANTITIES[(quantity, units)]
    values = rec[f"axis{n}.{column}"].astype(np.float64 if scale != 65536 else np.int64)
    offset = 0
    if scale is not None:  # jerk: the recorded acceleration's difference from cycle to cycle
        values = np.diff(values) * (65536 if scale == 65536 else 1 / cycle_time)
        offset = 1
    bad = np.abs(values) > limit
    if not bad.any():
        return []
    f = _first_violation(key, n, values, bad, offset, rec, limit, f"axis{n}.{column}")
    shown_value = f"{abs(f.value):g} {unit}" + (converted(f.column, abs(f.value), cycle_time) if scale is None else "")
    f.message = (
        f"axis {n}: |{quantity}| {shown_value} > {limit:g} at cycle {f.cycle} (peak {abs(f.peak):g} at cycle "
        f"{f.peak_cycle}) in the register {f.column}"
    )
    f.source = "register"
    return [f]


def _position_check(key: str, n: int, limit, rec: np.ndarray, units: str, cycle_time: float) -> List[Failure]:
    """|velocity|, |acceleration|, |jerk| or the step (max_step, counts per cycle) as the commanded
    position's own differences from cycle to cycle give them: a jump of the position that no register
    shows is caught (JUMP_ALLOWED: less than a count passes)."""
    column = f"axis{n}.position"
    position = rec[column].astype(np.float64)
    if key == "max_step":
        steps = np.diff(position)
        bad = np.abs(steps) > limit
        if not bad.any():
            return []
        f = _first_violation(key, n, steps, bad, 1, rec, limit, column)
        f.message = (
            f"axis {n}: the position moved {abs(f.value):g} counts in one cycle > {limit:g} at cycle {f.cycle} "
            f"(peak {abs(f.peak):g} at cycle {f.peak_cycle}) in the position's difference ({column})"
        )
        f.source = "position difference"
        return [f]
    quantity = key[4:]
    order, raw_scale, words = DIFFERENCES[quantity]
    unit = QUANTITIES[(quantity, units)][2]
    # the limit and the allowed jump in counts/cycle^order; values shown in the limit's unit
    to_unit = raw_scale if units == "raw" else cycle_time**-order
    differences = np.diff(position, order)
    bad = np.abs(differences) > limit / to_unit + JUMP_ALLOWED[order]
    if not bad.any():
        return []
    f = _first_violation(key, n, differences * to_unit, bad, order, rec, limit, column)
    per_cycle = abs(float(differences[f.row - order]))
    moved = (
        f"{column} moved {per_cycle:g} counts in one cycle"
        if order == 1
        else f"{per_cycle:g} counts/cycle^{order} of {column}"
    )
    f.message = (
        f"axis {n}: |{quantity}| {abs(f.value):g} {unit} > {limit:g} at cycle {f.cycle} (peak {abs(f.peak):g} "
        f"at cycle {f.peak_cycle}) in the position's {words} ({moved})"
    )
    f.source = "position difference"
    return [f]


def _limit_check(key: str, axis: int, limit, rec: np.ndarray, units: str, cycle_time: float) -> List[Failure]:
    n = axis + 1
    if key in ("max_velocity", "max_acceleration", "max_jerk"):
        # the registers, and the position's own differences: a limit holds on both
        return _register_check(key, n, limit, rec, units, cycle_time) + _position_check(
            key, n, limit, rec, units, cycle_time
        )
    if key == "max_step":
        return _position_check(key, n, limit, rec, units, cycle_time)
    position = rec[f"axis{n}.commandedPosition"].astype(np.int64)
    column = f"axis{n}.commandedPosition"
    if key in ("position_min", "position_max"):
        bad = position < limit if key == "position_min" else position > limit
        if not bad.any():
            return []
        i = int(np.argmax(bad))
        side = "below" if key == "position_min" else "above"
        return [
            Failure(
                key,
                f"axis {n}: position {int(position[i])} counts {side} the window's "
                f"{'minimum' if side == 'below' else 'maximum'} {limit} at cycle {int(rec['cycle'][i])}",
                axis=n,
                column=column,
                cycle=int(rec["cycle"][i]),
                row=i,
                value=int(position[i]),
                limit=limit,
            )
        ]
    if key == "final_position":
        if not len(rec) or position[-1] == limit:
            return []
        return [
            Failure(
                key,
                f"axis {n}: final position {int(position[-1])} counts at cycle "
                f"{int(rec['cycle'][-1])}, expected {limit}",
                axis=n,
                column=column,
                cycle=int(rec["cycle"][-1]),
                row=len(rec) - 1,
                value=int(position[-1]),
                limit=limit,
            )
        ]
    if key == "complete_by":
        if not len(rec):
            return []
        status = rec[f"axis{n}.activityStatus"].astype(np.int64)
        rest = (rec[f"axis{n}.commandedVelocity"] == 0) & ((status & IN_MOTION) == 0) & (position == position[-1])
        if not rest[-1]:
            return [
                Failure(
                    key,
                    f"axis {n}: still in motion at the end of the run (cycle {int(rec['cycle'][-1])}); "
                    f"it must be complete by cycle {limit}",
                    axis=n,
                    cycle=int(rec["cycle"][-1]),
                    row=len(rec) - 1,
                    limit=limit,
                )
            ]
        moving = np.nonzero(~rest)[0]
        i = int(moving[-1]) + 1 if len(moving) else 0
        if int(rec["cycle"][i]) <= limit:
            return []
        return [
            Failure(
                key,
                f"axis {n}: motion complete at cycle {int(rec['cycle'][i])} (at rest at {int(position[i])} "
                f"counts from then on), after cycle {limit}",
                axis=n,
                cycle=int(rec["cycle"][i]),
                row=i,
                value=int(rec["cycle"][i]),
                limit=limit,
            )
        ]
    if key == "no_events":
        column = f"axis{n}.eventStatus"
        if column not in rec.dtype.names:
            return []  # check_assertions skips the check
        mask = 0
        for name in limit:
            mask |= EVENTS[name]
        status = rec[column].astype(np.int64)
        bad = (status & mask) != 0
        if not bad.any():
            return []
        i = int(np.argmax(bad))
        names = [name for name in limit if status[i] & EVENTS[name]]
        return [
            Failure(
                key,
                f"axis {n}: event {', '.join(names)} at cycle {int(rec['cycle'][i])} "
                f"(event status 0x{int(status[i]):04X})",
                axis=n,
                column=column,
                cycle=int(rec["cycle"][i]),
                row=i,
                value=int(status[i]),
                limit=", ".join(limit),
            )
        ]
    raise KeyError(key)


def _check_name(axis: int, key: str, limit, units: str) -> str:
    words = AXIS_KEYS[key][1]
    if key in ("max_velocity", "max_acceleration", "max_jerk"):
        return f"axis{axis + 1} {words} <= {limit:g} {QUANTITIES[(key[4:], units)][2]}"
    if key == "max_step":
        return f"axis{axis + 1} {words} <= {limit:g} counts/cycle"
    if key == "no_events":
        return f"axis{axis + 1} no event {', '.join(limit)}"
    return f"axis{axis + 1} {words} {limit}"


def check_assertions(
    spec: Assertions,
    rec: Optional[np.ndarray],
    axes: Sequence[int],
    cycle_time: float,
    messages: Sequence = (),
    warnings: Optional[int] = None,
) -> List[Check]:
    """One Check per assertion and axis. messages: the FMU's log (a refused script command is a host I/O
    error); warnings: a count of warnings instead (a batch's row)."""
    checks = []
    for axis, limits in spec.for_axes(axes).items():
        for key in AXIS_KEYS:
            if key not in limits:
                continue
            check = Check(_check_name(axis, key, limits[key], spec.units))
            if axis not in axes:
                check.failures.append(
                    Failure(
                        key,
                        f"axis {axis + 1} was not recorded: the profile addresses "
                        f"axes {', '.join(str(a + 1) for a in axes)}",
                        axis=axis + 1,
                    )
                )
            elif key == "no_events" and f"axis{axis + 1}.eventStatus" not in rec.dtype.names:
                check.skipped = f"axis{axis + 1}.eventStatus was not recorded (a sweep's case records no event status)"
            else:
                check.failures += _limit_check(key, axis, limits[key], rec, spec.units, cycle_time)
            checks.append(check)
    if spec.no_host_errors:
        check = Check("no host I/O error")
        refused = [m.message for m in messages if "host I/O error" in m.message or m.status == "Error"]
        first = None
        for a in axes:
            column = f"axis{a + 1}.eventStatus"
            if rec is not None and column in rec.dtype.names:
                bad = (rec[column].astype(np.int64) & INSTRUCTION_ERROR) != 0
                if bad.any() and (first is None or int(np.argmax(bad)) < first[1]):
                    first = (a + 1, int(np.argmax(bad)))
        if refused or first:
            where = (
                (f"first at cycle {int(rec['cycle'][first[1]])} (axis {first[0]}'s event status InstructionError)")
                if first
                else "during the run"
            )
            text = f"{len(refused) or 'a'} command(s) refused with a host I/O error, {where}"
            if refused:
                text += ": " + "; ".join(refused[:5]) + ("; ..." if len(refused) > 5 else "")
            check.failures.append(
                Failure(
                    "no_host_errors",
                    text,
                    axis=first[0] if first else None,
                    cycle=int(rec["cycle"][first[1]]) if first else None,
                    row=first[1] if first else None,
                    value=len(refused),
                )
            )
        elif warnings:
            check.failures.append(
                Failure(
                    "no_host_errors",
                    f"{warnings} warning(s) logged during the run (a refused script command logs one)",
                    value=warnings,
                )
            )
        checks.append(check)
    return checks


# ---- one profile ----------------------------------------------------------------------------------


def _locate(failure: Failure, run_profile_args: dict, axes: Sequence[int]) -> None:
    """Where the profile was at the failure's row: runs the profile again up to that row (a run of n cycles
    gives the first n rows of any longer run) and asks the chip for the axis's position buffer
    (GetBufferFunction) and its read index (GetBufferReadIndex); adds them to the message."""
    found = {}

    def inspect(chip):
        for a in axes:
            ax = chip.axis(a)
            buffer = ax.GetBufferFunction(CONSTANTS["PMDBufferFunctionPosition"])
            if 0 <= buffer < 0x8000:
                found[a + 1] = (buffer, ax.GetBufferReadIndex(buffer))

    try:
        profile.run_profile(**{**run_profile_args, "max_cycles": failure.row + 1, "inspect": inspect})
    except Exception:  # the report says what it can without
        return
    wanted = [failure.axis] if failure.axis else sorted(found)
    parts = [f"axis {x} position buffer {found[x][0]} read index {found[x][1]}" for x in wanted if x in found]
    if failure.axis in found:
        failure.buffer, failure.read_index = found[failure.axis]
    if parts:
        failure.message += f"; after that cycle {', '.join(parts)}"


def _name_of(source) -> str:
    return Path(str(source)).stem if isinstance(source, (str, Path)) else "profile"


def _failure_files(name: str, out: Optional[PathLike], golden_path: Optional[PathLike]) -> List[Path]:
    """The files a golden's failure writes to out: NAME.actual.csv|npz and NAME.diff.png."""
    if out is None or golden_path is None:
        return []
    return [Path(out) / f"{name}.actual{Path(golden_path).suffix.lower()}", Path(out) / f"{name}.diff.png"]


def _refuse_writing_over_inputs(name: str, out: Optional[PathLike], inputs: Sequence[Optional[PathLike]]) -> None:
    """A failure's files must not be the golden or another input (`--out` the golden's folder and the
    golden named NAME.actual.npz, as a copied actual is): InputError before anything runs."""
    for written in _failure_files(name, out, inputs[0]):
        for path in inputs:
            if path is not None and written.exists() and Path(path).exists() and written.samefile(path):
                raise InputError(
                    f"{written}: a failure of case {name} would write its "
                    f"{'recording' if '.actual' in written.name else 'plot'} over the input {path}: "
                    "give another --out"
                )


def _finish(
    result: CaseResult,
    rec: np.ndarray,
    golden: Optional[np.ndarray],
    golden_path: Optional[Path],
    required: Sequence[str],
    out: Optional[PathLike],
    cycle_time: float,
    ended: bool = True,
) -> None:
    """On a golden's failure: the diff plot and the run's own recording, in the golden's format, to `out`."""
    failing = [f for c in result.checks if c.name == "golden trace" for f in c.failures]
    if out is None or golden is None or not failing:
        return
    from .verify_report import plot_diff

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    columns = list(dict.fromkeys([*required, *golden.dtype.names]))
    result.actual, result.plot = _failure_files(result.name, out, golden_path)
    write_recording(result.actual, rec[[c for c in columns if c in rec.dtype.names]], ended)
    plot_diff(result.plot, golden, rec, failing, cycle_time, title=f"pmdfmu verify {result.name}: {result.source}")


def verify(
    source: Union[PathLike, Dict[int, Sequence]],
    against: Optional[PathLike] = None,
    assertions: Union[None, PathLike, Mapping, Assertions] = None,
    tolerance: Optional[Mapping[str, float]] = None,
    *,
    fmu: Optional[str] = None,
    fmi_version: int = 2,
    cycle_time: float = DEFAULT_CYCLE_TIME,
    upload: str = "memory",
    max_cycles: int = 1_000_000,
    parameters: Optional[dict] = None,
    out: Optional[PathLike] = None,
    name: Optional[str] = None,
    locate: bool = True,
    cycles: Optional[int] = None,
) -> VerifyResult:
    """Runs a script or segment table (a path, or tables) exactly as `pmdfmu run` does and checks it against
    the golden trace `against` (a .csv or .npz recording) and `assertions` (a TOML file, a dict of its shape
    or Assertions); tolerance: column -> absolute tolerance (over the file's). On a golden's failure it
    writes NAME.diff.png and NAME.actual.csv|npz to `out` (None: no files). A run that max_cycles cuts
    short before the profile ends fails ("profile ended"); cycles=N checks a window instead: the first N
    cycles, the profile ended or not. Raises InputError for a malformed golden or assertion file, and for a
    golden that is a window (recorded with `pmdfmu run --cycles`) unless cycles is given; a profile that
    does not run is a failed case."""
    spec = load_assertions(assertions, {"tolerance": dict(tolerance)} if tolerance else None)
    read = read_golden(against) if against is not None else None
    golden = read.recording if read is not None else None
    if cycles is not None:
        max_cycles = cycles
    if isinstance(max_cycles, bool) or not isinstance(max_cycles, int) or max_cycles < 1:
        raise InputError(
            f"{'cycles' if cycles is not None else 'max_cycles'} {max_cycles!r}: a run records at least 1 cycle"
        )
    if read is not None and not read.ended and cycles is None:
        raise InputError(_window_golden(against, golden))
    name = name or _name_of(source)
    _refuse_writing_over_inputs(
        name,
        out,
        [
            against,
            assertions if isinstance(assertions, (str, Path)) else None,
            source if isinstance(source, (str, Path)) else None,
        ],
    )
    args = dict(
        source=source, fmu=fmu, fmi_version=fmi_version, cycle_time=cycle_time, upload=upload, parameters=parameters
    )
    extra = list(dict.fromkeys([*(golden.dtype.names[1:] if golden is not None else ()), *spec.columns()]))
    result = CaseResult(name, str(source) if isinstance(source, (str, Path)) else "segment tables")
    start = time.perf_counter()
    try:
        run = profile.run_profile(**args, max_cycles=max_cycles, record=extra)
    except Exception as e:
        result.error = " ".join(str(e).split()) or type(e).__name__
        result.seconds = time.perf_counter() - start
        return VerifyResult([result])
    result.seconds = time.perf_counter() - start
    _evaluate(
        result,
        run.recording,
        run.axes,
        run.cycle_time,
        golden,
        against,
        spec,
        messages=run.messages,
        locate_args={**args, "record": extra} if locate else None,
        out=out,
        ended=run.ended,
        window=cycles,
    )
    result.recording, result.expected = run.recording, golden
    return VerifyResult([result])


def _window_golden(path: PathLike, golden: np.ndarray, where: str = "") -> str:
    """where: how the window is asked for, after `--cycles N` (a case table's: in its cycles column)."""
    return (
        f"{path}: the golden trace is a window: its profile had not ended at its last cycle "
        f"({len(golden)} cycles, recorded with --cycles or cut short); a whole run is not compared with it: "
        f"record the golden again (a larger --max-cycles if need be), or give --cycles {len(golden)}"
        f"{' ' + where if where else ''} to check the same window"
    )


def _ended_check(rec: np.ndarray, ended: bool, window: Optional[int]) -> Check:
    """Whether the profile had ended by the run's last cycle: a run cut short by max_cycles is no run of
    the profile (its limits and final position would pass on a part of it), unless a window of so many
    cycles was asked for (window: verify's `cycles`)."""
    check = Check("profile ended")
    if ended:
        return check
    end = int(rec["cycle"][-1]) if len(rec) else 0
    if window is not None:
        check.skipped = f"a window of {window} cycles was asked for (--cycles); the profile goes on after cycle {end}"
        return check
    check.failures.append(
        Failure(
            "ended",
            f"the profile had not ended at cycle {end}: {len(rec)} cycles recorded, the --max-cycles limit; "
            f"give a larger --max-cycles, or --cycles {len(rec)} to check a window of the profile",
            cycle=end,
            row=len(rec) - 1 if len(rec) else None,
            value=len(rec),
        )
    )
    return check


def _evaluate(
    result: CaseResult,
    rec: np.ndarray,
    axes: Sequence[int],
    cycle_time: float,
    golden: Optional[np.ndarray],
    golden_path: Optional[PathLike],
    spec: Assertions,
    messages=(),
    warnings: Optional[int] = None,
    locate_args: Optional[dict] = None,
    out=None,
    ended: bool = True,
    window: Optional[int] = None,
) -> None:
    result.cycles = len(rec)
    required = ["cycle", *profile.record_outputs(axes)]
    result.checks.append(_ended_check(rec, ended, window))
    if golden is not None:
        check = Check("golden trace", compare(golden, rec, required, spec.tolerance, cycle_time))
        first = next((f for f in check.failures if f.check == "golden" and f.row is not None), None)
        if first is not None and locate_args is not None:  # the first difference only: a run each
            _locate(first, locate_args, axes)
        result.checks.append(check)
    result.checks += check_assertions(spec, rec, axes, cycle_time, messages, warnings)
    _finish(result, rec, golden, Path(golden_path) if golden_path else None, required, out, cycle_time, ended)


# ---- batches: a sweep's case table ----------------------------------------------------------------


@dataclass(frozen=True)
class VerifyCase:
    """A sweep case (pmdfmu.Case) with its golden trace and assertion file (either may be None)."""

    case: object
    golden: Optional[str] = None
    assertions: Optional[str] = None


def read_case_table(path: PathLike) -> Tuple[list, List[dict]]:
    """A case table as sweep.read_cases reads and checks it, and its rows; InputError for a table it cannot
    read or a case that cannot run as written (read_cases' checks)."""
    from .sweep import read_cases

    path = Path(path)
    try:
        text = files.read_text(path)
        cases = read_cases(path)
        rows = list(csv.DictReader(io.StringIO(text, newline="")))
    except (OSError, UnicodeDecodeError, KeyError, csv.Error) as e:
        raise InputError(f"{path}: cannot read the case table: {_one_line(e)}") from None
    except ValueError as e:  # read_cases' own file:line: reason
        raise InputError(_one_line(e)) from None
    return cases, rows


def _one_line(error: BaseException) -> str:
    """An exception's message on one line (an OSError's reason without its file, named already)."""
    text = error.strerror if isinstance(error, OSError) and error.strerror else str(error)
    return " ".join(text.split()) or type(error).__name__


def read_verify_cases(path: PathLike) -> List[VerifyCase]:
    """A case table as `pmdfmu sweep` reads it (read_case_table), with two more columns: golden and
    assertions, paths relative to the table's folder (blank: none)."""
    path = Path(path)
    cases, rows = read_case_table(path)

    def resolve(row, key):
        value = (row.get(key) or "").strip()
        return str(files.resolved(path.parent / value)) if value else None

    return [VerifyCase(case, resolve(row, "golden"), resolve(row, "assertions")) for case, row in zip(cases, rows)]


def verify_cases(
    cases: Union[PathLike, Sequence[VerifyCase]],
    scheduler=None,
    workers: int = 2,
    assertions: Union[None, PathLike, Mapping] = None,
    extra: Optional[Mapping] = None,
    out: Optional[PathLike] = None,
    locate: bool = True,
) -> VerifyResult:
    """Runs a case table (read_verify_cases) with pmdfmu.sweep (scheduler: as sweep's) and checks each case
    against its golden and assertions (the case's file, over `assertions` and `extra`, the command line's).
    One CaseResult per case; every golden and assertion file is read before anything runs."""
    from .sweep import sweep

    vcases = read_verify_cases(cases) if isinstance(cases, (str, Path)) else list(cases)
    base = _merge(_assertion_data(assertions)[0], extra or {})
    parse_assertions(base, "command line")
    specs, goldens = [], []
    for vc in vcases:
        data, where, text = _assertion_data(vc.assertions)
        specs.append(parse_assertions(_merge(base, data), where, text))  # the case's file over the common
        read = read_golden(vc.golden) if vc.golden else None
        if read is not None and not read.ended and vc.case.cycles is None:
            raise InputError(_window_golden(vc.golden, read.recording, "in its cycles column"))
        goldens.append(read.recording if read is not None else None)
        _refuse_writing_over_inputs(vc.case.name, out, [vc.golden, vc.assertions, vc.case.script or vc.case.table])
    run_cases = []
    for vc, spec, golden in zip(vcases, specs, goldens):
        extra_columns = list(dict.fromkeys([*(golden.dtype.names[1:] if golden is not None else ()), *spec.columns()]))
        run_cases.append(dataclasses.replace(vc.case, record=tuple(extra_columns)))
    start = time.perf_counter()
    swept = sweep(run_cases, scheduler=scheduler, workers=workers)
    seconds = (time.perf_counter() - start) / max(1, len(run_cases))
    results = []
    for vc, case, spec, golden, row in zip(vcases, run_cases, specs, goldens, swept.rows):
        source = case.script or case.table
        result = CaseResult(case.name, str(source), seconds=seconds)
        results.append(result)
        if row["status"] != "ok":
            result.error = row["reason"]
            continue
        rec = swept.recordings[case.name]
        params = dict(case.parameters)
        axes = [a for a in range(4) if row.get(f"axis{a + 1}.finalPosition", "") != ""]  # the profile's own
        locate_args = (
            dict(
                source=source,
                fmu=case.fmu,
                fmi_version=case.fmi_version,
                cycle_time=float(params.pop("cycleTime", DEFAULT_CYCLE_TIME)),
                upload="memory",
                parameters=params,
                record=case.record,
            )
            if locate
            else None
        )
        _evaluate(
            result,
            rec,
            axes,
            float(dict(case.parameters).get("cycleTime", DEFAULT_CYCLE_TIME)),
            golden,
            vc.golden,
            spec,
            warnings=row.get("warnings"),
            locate_args=locate_args,
            out=out,
            ended=row.get("ended") == "yes",
            window=case.cycles,
        )
        result.recording, result.expected = rec, golden
    return VerifyResult(results)
