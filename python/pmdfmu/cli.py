# SPDX-License-Identifier: BSD-2-Clause
"""The pmdfmu command: a thin layer over the library.

pmdfmu build      configure and build the FMU with CMake (into build/)
pmdfmu demo       run the bundled 2-axis external profile; write CSV and PNG
pmdfmu run FILE   run a script or a segment table; write CSV and PNG
pmdfmu sweep CASES  run a table of cases on Dask; write a summary table and plot
pmdfmu verify FILE  run a script or table and check it against a golden trace and assertions
                    (exit 0 pass, 1 fail, 2 malformed input; JUnit XML, Markdown, diff plots)
pmdfmu pack SCRIPT  write a copy of the FMU that runs the script with no parameter set
pmdfmu machine --check FILE  check a machine file and say what it means (docs/machine.md)
pmdfmu serve --serial PATH | --tcp HOST:PORT  the twin as a virtual device: the chip's serial
                    packets on a pty or TCP, until Ctrl-C (docs/device.md)
pmdfmu validate   check the FMU with fmpy.validation
pmdfmu info       the FMU's variables and the chip's commands
"""

from __future__ import annotations

import _thread
import argparse
import math
import os
import select
import signal
import subprocess
import sys
import threading
import time
import zipfile
from pathlib import Path
from typing import Iterable, List, Optional, Tuple

# lxml (FMPy's XML parser, which imports it on first use) loses a KeyboardInterrupt that lands while its
# module initializes, and the command would run on to its end: it is imported with the program instead
import lxml.etree  # noqa: F401,E402

from . import __version__, extras, files, profile, progress
from .chip import COMMANDS, DEFAULT_CYCLE_TIME, REPO, FMUError, PMDError, default_fmu
from .units import unit
from .pack import PackError
from .verify import EXIT_INPUT, InputError


class CommandLineError(ValueError):
    """A file or value on the command line the harness cannot take."""


# What a user's input can make the harness raise (a file that is missing or no regular file, a script the
# FMU refuses, a table, golden, assertion file or case table that is malformed, a command the chip refuses):
# main answers each with one line, `pmdfmu CMD: file:line: reason`, and exit status 2. Anything else is a
# bug of pmdfmu and keeps its traceback.
INPUT_ERRORS = (
    CommandLineError,
    InputError,
    profile.TableError,
    PackError,
    FMUError,
    PMDError,
    OSError,
    zipfile.BadZipFile,
    extras.MissingExtra,  # --html without the 'html' extra, --plot without 'plot': which one installs it
)
EXIT_INTERRUPTED = 130  # 128 + SIGINT: what a shell reports for a command ended by Ctrl-C
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE: what a shell reports for a tool whose reader went away
# what the FMU's initialization error says after the FMI function's name (fmu_src/fmi/instance.c); its
# file:line: reason follows
_SCRIPT_REFUSED = ": script refused: "
_MACHINE_REFUSED = ": machine refused: "


def _without_function(line: str) -> str:
    """line without `fmi2ExitInitializationMode: script refused: ` (or `machine refused: `) before the
    FMU's file:line: reason."""
    head, found, reason = line.partition(_SCRIPT_REFUSED)
    if not found:
        head, found, reason = line.partition(_MACHINE_REFUSED)
    before, _, function = head.rpartition(" ")
    if not found or not function.startswith(("fmi2", "fmi3")):
        return line
    return f"{before} {reason}" if before else reason


def one_line(error: BaseException) -> str:
    """An input error as one line: an OSError as `file: reason`, the FMU's refusal of a script as its
    `file:line: reason`; the lines of a message of several joined by "; "; a line feed in a file name
    written as \\n."""
    if isinstance(error, OSError) and error.filename is not None:
        text = f"{files.shown_path(error.filename)}: {error.strerror or error}"
    else:
        text = str(error) if not isinstance(error, KeyError) else str(error.args[0])
    lines = [_without_function(line.strip()) for line in text.splitlines() if line.strip()]
    return "; ".join(lines) or type(error).__name__


def _script_file(path: Path) -> Path:
    """A script named on the command line, for the FMU's `script` parameter: a file, never text. A value
    holding a line feed is the script's text to the FMU (docs/scripts.md), so such a path cannot be
    given to it."""
    if "\n" in str(path):
        raise CommandLineError(
            f"{files.shown_path(path)}: the script's path holds a line feed; the FMU reads "
            "a `script` value holding one as the script's text, so it cannot be given this "
            "file: rename it (pmdfmu pack packs it under another name)"
        )
    return path


def _fmu_file(path: Optional[Path]) -> Optional[Path]:
    """--fmu FMU: a regular file whose model description FMPy reads (else one line, exit status 2)."""
    if path is None:
        return None
    from fmpy import read_model_description

    files.check_regular(path)
    try:
        read_model_description(str(path))
    except Exception as e:  # whatever FMPy finds wrong with the user's file
        raise CommandLineError(f"{path}: not an FMU: {one_line(e)}") from None
    return path


def _inputs(path: Optional[Path], fmu: Optional[Path], machine: Optional[Path], fmi_version: int, outputs) -> list:
    """What a run of the script or table at path reads, which no output may overwrite: path, the FMU, the
    machine file and the segment tables the script loads (the FMU's answer, pack.tables_loaded: it compiles
    the script, only when one of the outputs exists already)."""
    inputs = [path, fmu, machine]
    if path is not None and not profile.is_segment_table(path) and any(o and os.path.lexists(o) for o in outputs):
        from .pack import tables_loaded

        inputs += tables_loaded(_script_file(path), fmi_version, fmu)
    return inputs


def _refuse_overwriting(outputs: Iterable[Tuple[str, Optional[Path]]], inputs: Iterable[Optional[Path]]) -> None:
    """No output names an input (the same file: also through a symlink or a hard link), nor another output."""
    inputs = [p for p in inputs if p is not None]
    outputs = [(flag, out) for flag, out in outputs if out is not None]
    for i, (flag, out) in enumerate(outputs):
        for other_flag, other in outputs[:i]:
            if os.path.abspath(out) == os.path.abspath(other) or (
                out.exists() and other.exists() and os.path.samefile(out, other)
            ):
                raise CommandLineError(f"{flag} {out}: names the file {other_flag} writes too")
    for flag, out in outputs:
        if out is None or not out.exists():
            continue
        for path in inputs:
            if path.exists() and os.path.samefile(out, path):
                raise CommandLineError(f"{flag} {out}: names the input {path}; nothing overwrites an input")


_verbosity = 0  # -q: -1, -v: 1 (main sets it from the command line)


def _say(text: str, level: int = 0) -> None:
    """A line of standard output shown at this verbosity: level 0 unless -q, level 1 with -v."""
    if _verbosity >= level:
        print(text)


def _not_ended(run: profile.ProfileRun) -> str:
    rec = run.recording
    end = int(rec["cycle"][-1]) if len(rec) else 0
    return (
        f"the profile had not ended at cycle {end}: {len(rec)} cycles recorded, the --max-cycles limit; "
        f"nothing written: give a larger --max-cycles, or --cycles {len(rec)} to record a window of the profile"
    )


def _write_run(
    run: profile.ProfileRun,
    csv_path: Optional[Path],
    plot_path: Optional[Path],
    title: str,
    command: str = "run",
    html_path: Optional[Path] = None,
) -> int:
    """`pmdfmu run`'s outputs: the recording (CSV, or compressed numpy for a .npz name: either is a golden
    trace for `pmdfmu verify --against`; a window says so) and the plot. Exit status 1 and nothing written
    when the run stopped at --max-cycles before the profile ended (run.ended) and no window was asked for
    (window: True for --cycles)."""
    from .verify import write_recording

    rec = run.recording
    if not run.ended and not run.window:
        print(f"pmdfmu {command}: {_not_ended(run)}", file=sys.stderr)
        return 1
    if csv_path:
        write_recording(csv_path, rec, run.ended)
        _say(f"wrote {csv_path} ({len(rec)} cycles{'' if run.ended else ', a window: the profile goes on'})")
    if plot_path:
        profile.plot(plot_path, rec, run.cycle_time, title=title)
        _say(f"wrote {plot_path}")
    if html_path:
        from .html_report import write_run

        write_run(html_path, rec, title, run.cycle_time)
        _say(f"wrote {html_path}")
    return 0


def _run_table(
    source,
    fmu: Optional[Path],
    cycle_time: float,
    upload: str,
    max_cycles: int,
    csv_path: Optional[Path],
    plot_path: Optional[Path],
    title: str,
    fmi_version: int = 2,
    window: bool = False,
    command: str = "run",
    html_path: Optional[Path] = None,
) -> int:
    """source: a segment table's file, or its tables read already (profile.run_profile)."""
    run = profile.run_profile(source, fmu, fmi_version, cycle_time, upload, max_cycles)
    tables = source if isinstance(source, dict) else profile.read_segment_table(source)  # read whole before
    run.window = window
    rec = run.recording
    if len(rec):  # the move to the first rows' positions runs before the recording starts: the plot says so
        title += (
            f"\nrecorded from chip cycle {int(rec['cycle'][0])}, when the profile starts "
            "(the move to the first rows' positions comes before)"
        )
    status = _write_run(run, csv_path, plot_path, title, command, html_path)
    if status:
        return status
    _say_where_axes_ended(run, {axis: rows[-1][0] for axis, rows in tables.items()})
    return 0


def _say_where_axes_ended(run: profile.ProfileRun, last_rows: Optional[dict] = None) -> None:
    """What a run with no output asked for still says: where each axis ended (or stood at the window's
    end), and for a table whether that is its last row's position (last_rows: axis -> position)."""
    rec = run.recording
    for axis in run.axes:
        n = axis + 1
        position = int(rec[f"axis{n}.commandedPosition"][-1])
        if not run.ended:
            _say(f"axis {n}: at position {position} at the window's end, after {len(rec)} cycles")
        elif last_rows is None:
            _say(f"axis {n}: ended at position {position} after {len(rec)} cycles")
        else:
            last = last_rows[axis]
            _say(
                f"axis {n}: ended at position {position} after {len(rec)} cycles "
                f"({'as' if position == last else 'NOT as'} the table's last row, {last})"
            )


# the platforms `pmdfmu build --platforms` cross-builds (CMakeLists.txt's PMD_PLATFORMS)
CROSS_PLATFORMS = ("x86_64-windows", "aarch64-linux")


def _platforms(value: str) -> list[str]:
    names = [name.strip() for name in value.split(",") if name.strip()]
    if names == ["all"]:
        return list(CROSS_PLATFORMS)
    unknown = [name for name in names if name not in CROSS_PLATFORMS]
    if unknown or not names:
        raise argparse.ArgumentTypeError(
            f"{value!r}: not all or a comma-separated list of {', '.join(CROSS_PLATFORMS)}"
        )
    return names


def _source_folder(given: Optional[Path]) -> Path:
    """--source, else the checkout this package runs from (python/ of a checkout), else the working directory:
    an installed package (./dev's .venv) has no sources beside it."""
    for folder in [given] if given is not None else [REPO, Path.cwd()]:
        if (folder / "CMakeLists.txt").is_file() and (folder / "fmu_src").is_dir():
            return folder
    if given is not None:
        raise CommandLineError(f"--source {given}: not a pmdfmu checkout (no CMakeLists.txt and fmu_src/ there)")
    raise CommandLineError("no pmdfmu checkout to build: run pmdfmu build in its top folder, or give --source")


def cmd_build(args) -> int:
    source = _source_folder(args.source)
    build = args.build_dir if args.build_dir is not None else source / "build"
    platforms = ";".join(args.platforms)  # CMake's list; empty: this host's binaries only
    for command in (
        [
            "cmake",
            "-S",
            str(source),
            "-B",
            str(build),
            f"-DPython3_EXECUTABLE={sys.executable}",
            f"-DPMD_PLATFORMS={platforms}",
        ],
        ["cmake", "--build", str(build)],
    ):
        status = subprocess.run(command).returncode
        if status:  # cmake has said why
            print(f"pmdfmu build: {' '.join(command[:2])} ... failed with exit status {status}", file=sys.stderr)
            return 1
    _say(f"built {build / 'PMDMotionProcessor-fmi2.fmu'}")
    return 0


def cmd_demo(args) -> int:
    from .demo import circle_table, describe_demo

    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    tables = circle_table()
    _say(describe_demo(tables))
    profile.write_segment_table(out / "demo_table.csv", tables)
    _say(f"wrote {out / 'demo_table.csv'}")
    return _run_table(
        tables,
        _fmu_file(args.fmu),
        args.cycle_time,
        "memory",
        1_000_000,
        out / "demo.csv",
        out / "demo.png",
        "pmdfmu demo: 2-axis external profile (circle)",
        command="demo",
    )


def cmd_run(args) -> int:
    """A .csv file is a segment table; anything else is a script (docs/scripts.md). profile.run_profile
    runs either, as `pmdfmu verify` does. Exit status 1 when --max-cycles stopped the run before the
    profile ended, unless --cycles asked for a window."""
    path, fmu = args.file, _fmu_file(args.fmu)
    csv_path, plot_path, html_path = args.csv, args.plot, args.html
    outputs = [("--csv", csv_path), ("--plot", plot_path), ("--html", html_path), ("--out", args.out)]
    _refuse_overwriting(outputs, _inputs(path, fmu, args.machine, args.fmi_version, [o for _, o in outputs]))
    title = f"pmdfmu run {path}"
    machine = _machine_file(args.machine)
    limit = args.cycles or args.max_cycles
    table = profile.is_segment_table(path)
    if args.out is not None:
        return _stream_run(args, path if table else _script_file(path), fmu, machine, limit)
    if table and machine is None:
        return _run_table(
            path,
            fmu,
            args.cycle_time,
            args.upload,
            limit,
            csv_path,
            plot_path,
            title,
            args.fmi_version,
            bool(args.cycles),
            html_path=html_path,
        )
    run = profile.run_profile(
        path if table else _script_file(path),
        fmu,
        args.fmi_version,
        args.cycle_time,
        args.upload,
        limit,
        parameters={"machine": machine} if machine is not None else None,
    )
    run.window = bool(args.cycles)
    for m in run.messages:
        print(f"{m.status}: {m.message}", file=sys.stderr)
    status = _write_run(run, csv_path, plot_path, title, html_path=html_path)
    if status:
        return status
    _say_where_axes_ended(run)  # as for a table
    return 0


def cmd_trace(args) -> int:
    """Runs the script as `pmdfmu run` does, then reads the chip's trace (buffer 0) and shows it as a
    scope: --plot an image or an interactive .html page, --csv the samples."""
    path, fmu = args.file, _fmu_file(args.fmu)
    _refuse_overwriting(
        [("--plot", args.plot), ("--csv", args.csv)],
        _inputs(path, fmu, args.machine, args.fmi_version, [args.plot, args.csv]),
    )
    got = []
    run = profile.run_profile(
        _script_file(path),
        fmu,
        args.fmi_version,
        args.cycle_time,
        max_cycles=args.cycles or args.max_cycles,
        parameters={"machine": _machine_file(args.machine)} if args.machine is not None else None,
        inspect=lambda chip: got.append(chip.trace()),
    )
    for m in run.messages:
        print(f"{m.status}: {m.message}", file=sys.stderr)
    trace = got[0]
    if not len(trace):
        print(f"pmdfmu trace: {path}: the trace holds no sample (SetTraceVariable, SetTraceStart?)", file=sys.stderr)
        return 1
    at = f", trigger at {'chip time' if trace.chip_time else 'cycle'} {trace.samples['cycle'][trace.trigger]}"
    _say(
        f"{path}: {len(trace)} samples of {', '.join(trace.variables)}, every {trace.period} cycles "
        f"({trace.mode}{', wrapped' if trace.wrapped else ''}){at if trace.trigger is not None else ''}"
    )
    if args.csv is not None:
        from .verify import write_recording

        write_recording(args.csv, trace.samples)
        _say(f"wrote {args.csv} ({len(trace)} samples)")
    if args.plot is not None:
        trace.plot(args.plot, title=f"pmdfmu trace {path}")
        _say(f"wrote {args.plot}")  # as run says what it wrote
    return 0


class _NotEnded(Exception):
    """A streamed run that --max-cycles cut short: its file is not written (_stream_run)."""


def _stream_run(args, source, fmu: Optional[Path], machine: Optional[str], limit: int) -> int:
    """`pmdfmu run --out FILE`: the rows written as they come (recording.NpyFile: memory holds a chunk,
    whatever the run's length), a .npy, or a .npz as `--csv run.npz` writes it (the recording and
    `ended`), copied from a .npy beside it a block at a time. Nothing is written when the profile had not
    ended and no window was asked for (exit status 1), as for --csv."""
    import io
    import shutil
    import tempfile

    import numpy as np

    from .recording import NpyFile
    from .verify import NPZ_ENDED, NPZ_KEY

    out = args.out
    if args.csv is not None or args.plot is not None:
        raise CommandLineError("--out writes the rows as they come; --csv and --plot need them in memory: give one")
    if out.suffix.lower() not in (".npy", ".npz"):
        raise CommandLineError(f"--out {out}: a .npy or .npz name")
    window = bool(args.cycles)

    def run_into(f):
        sink = NpyFile(f, None, limit)
        run = profile.run_profile(
            source,
            fmu,
            args.fmi_version,
            args.cycle_time,
            args.upload,
            limit,
            parameters={"machine": machine} if machine is not None else None,
            sink=sink,
        )
        for m in run.messages:
            print(f"{m.status}: {m.message}", file=sys.stderr)
        if not run.ended and not window:
            rec = run.recording
            end = int(rec["cycle"][-1]) if len(rec) else 0
            raise _NotEnded(
                f"the profile had not ended at cycle {end}: {sink.count} cycles recorded, the --max-cycles "
                f"limit; nothing written: give a larger --max-cycles, or --cycles {sink.count} to record a window"
            )
        sink.close()
        return run, sink.count

    try:
        if out.suffix.lower() == ".npy":
            with files.replaced(out) as f:
                run, count = run_into(f)
        else:
            with tempfile.TemporaryFile(dir=out.parent if out.parent.is_dir() else None) as rows:
                run, count = run_into(rows)
                rows.seek(0)
                ended = io.BytesIO()
                np.save(ended, np.array(bool(run.ended)))
                with files.replaced(out) as f, zipfile.ZipFile(f, "w", zipfile.ZIP_DEFLATED, allowZip64=True) as z:
                    with z.open(f"{NPZ_KEY}.npy", "w", force_zip64=True) as entry:
                        shutil.copyfileobj(rows, entry, 1 << 20)
                    z.writestr(f"{NPZ_ENDED}.npy", ended.getvalue())
    except _NotEnded as e:
        print(f"pmdfmu run: {e}", file=sys.stderr)
        return 1
    _say(f"wrote {out} ({count} cycles{'' if run.ended else ', a window: the profile goes on'})")
    return 0


def _machine_file(path: Optional[Path]) -> Optional[str]:
    """--machine FILE: a regular file, for the FMU's `machine` parameter (never text)."""
    if path is None:
        return None
    if "\n" in str(path):
        raise CommandLineError(f"{files.shown_path(path)}: the machine file's path holds a line feed: rename it")
    files.check_regular(path)
    return str(files.resolved(path))


def cmd_machine(args) -> int:
    """The FMU parses the file (the one parser every surface uses) and logs what it means; a bad file is
    its file:line: reason, the path as given."""
    from .chip import Chip

    path = _machine_file(args.file)
    try:
        with Chip(fmi_version=2, fmu=_fmu_file(args.fmu), machine=path, log_categories=["machine"]) as chip:
            meaning = [m.message.partition(":\n")[2] for m in chip.messages if m.category == "machine"]
    except FMUError as e:
        raise FMUError(str(e).replace(path, str(args.file))) from None
    print(f"{args.file}: a machine")
    print("".join(meaning), end="")
    return 0


def cmd_sweep(args) -> int:
    from .sweep import refuse_writing_over_inputs, sweep
    from .verify import read_case_table

    cases = read_case_table(args.cases)[0]
    try:
        refuse_writing_over_inputs(cases, args.out, [args.cases])
    except ValueError as e:
        raise InputError(str(e)) from None
    result = sweep(cases, scheduler=args.scheduler, workers=args.workers)
    result.write(args.out)
    failed = [r for r in result.rows if r["status"] != "ok"]
    windows = {c.name: c.cycles is not None for c in cases}
    for r in result.rows:
        if r["status"] == "ok":
            _say(
                f"ok: {r['name']}: {r['cycles']} cycles"
                + ("" if r["ended"] == "yes" else ", a window" if windows[r["name"]] else ", cut short by max_cycles"),
                1,
            )
    _say(
        f"{len(result.rows) - len(failed)} of {len(result.rows)} cases ran; wrote {args.out}/summary.csv, "
        f"{args.out}/summary.png"
    )
    for r in failed:
        print(f"failed: {r['name']}: {r['reason']}")
    # a failed case is a row of the summary, not a failure of the sweep, unless the user asks
    return 1 if failed and args.fail_on_error else 0


# --limit flags of pmdfmu verify: flag -> (assertion key(s), how AXIS=VALUE's value reads)
LIMIT_FLAGS = {
    "max_velocity": ("max_velocity",),
    "max_acceleration": ("max_acceleration",),
    "max_jerk": ("max_jerk",),
    "position_window": ("position_min", "position_max"),
    "final_position": ("final_position",),
    "complete_by": ("complete_by",),
    "max_step": ("max_step",),
}


def _limit_flags(args) -> dict:
    """The command line's limits in the assertion file's shape (verify.parse_assertions checks them)."""

    def table(axis: str) -> str:
        axis = axis.strip().lower()
        if axis in ("all", "all_axes"):
            return "all_axes"
        name = axis if axis.startswith("axis") else f"axis{axis}"
        if name not in ("axis1", "axis2", "axis3", "axis4"):
            raise InputError(f"command line: {axis!r} is not an axis (1..4, axis1..axis4 or all)")
        return name

    def number(text: str, flag: str):
        try:
            return float(text) if any(c in text for c in ".eE") and not text.lower().startswith("0x") else int(text, 0)
        except ValueError:
            raise InputError(f"command line: --{flag.replace('_', '-')}: {text!r} is not a number") from None

    data: dict = {}
    for flag, keys in LIMIT_FLAGS.items():
        for item in getattr(args, flag) or ():
            axis, sep, value = item.partition("=")
            if not sep:
                raise InputError(f"command line: --{flag.replace('_', '-')} {item!r}: expected AXIS=VALUE")
            values = value.split(":") if len(keys) == 2 else [value]
            if len(values) != len(keys):
                raise InputError(f"command line: --{flag.replace('_', '-')} {item!r}: expected AXIS=MIN:MAX")
            data.setdefault(table(axis), {}).update({k: number(v, flag) for k, v in zip(keys, values)})
    for axis in args.no_events or ():
        data.setdefault(table(axis), {})["no_events"] = True
    if args.no_host_errors:
        data["no_host_errors"] = True
    if args.units:
        data["units"] = args.units
    for item in args.tolerance or ():
        column, sep, value = item.partition("=")
        if not sep:
            raise InputError(f"command line: --tolerance {item!r}: expected COLUMN=TOLERANCE")
        data.setdefault("tolerance", {})[column.strip()] = number(value, "tolerance")
    return data


def cmd_verify(args) -> int:
    """Exit status 0: every case passed; 1: a case failed (or did not run); 2: malformed input of verify's
    own (golden, assertion file, case table, flags) -- docs/verify.md."""
    from . import verify as _  # noqa: F401  (pmdfmu.verify is the function; the module is in sys.modules)

    v = sys.modules[__package__ + ".verify"]
    extra = _limit_flags(args)
    if bool(args.file) == bool(args.cases):
        raise InputError("command line: give a script or segment table, or --cases CASES.csv")
    if args.cases and args.cycles:
        raise InputError(
            "command line: --cycles checks a window of one profile; a case table asks for a case's window in "
            "its cycles column"
        )
    outputs = [
        ("--junit", args.junit),
        ("--summary", args.summary if args.summary != Path("-") else None),
        ("--html", args.html),
    ]
    inputs = _inputs(args.file, _fmu_file(args.fmu), None, args.fmi_version, [out for _flag, out in outputs])
    if args.cases and any(out and os.path.lexists(out) for _flag, out in outputs):
        from .sweep import case_inputs

        read = v.read_verify_cases(args.cases)  # the cases' goldens, assertion files, scripts and their tables
        inputs += [Path(p) for vc in read for p in (vc.golden, vc.assertions) if p]
        inputs += case_inputs([vc.case for vc in read])
    _refuse_overwriting(outputs, [*inputs, args.cases, args.against, args.assertions])
    if args.cases:
        if args.against:
            raise InputError("command line: --against names one golden; a case table has a golden column")
        result = v.verify_cases(
            args.cases,
            scheduler=args.scheduler,
            workers=args.workers,
            assertions=args.assertions,
            extra=extra,
            out=args.out,
        )
    else:
        if not (args.against or args.assertions or extra.keys() - {"units", "tolerance"}):
            raise InputError(
                "command line: nothing to verify: give --against GOLDEN, --assertions FILE "
                "or a limit (--max-velocity, ...)"
            )
        source = args.file if profile.is_segment_table(args.file) else _script_file(args.file)
        result = v.verify(
            source,
            args.against,
            v.load_assertions(args.assertions, extra),
            fmu=args.fmu,
            fmi_version=args.fmi_version,
            cycle_time=args.cycle_time,
            upload=args.upload,
            max_cycles=args.max_cycles,
            out=args.out,
            cycles=args.cycles,
        )
    if _verbosity >= 0 or not result.passed:  # -q: the report only when something failed
        print(result.report(verbose=_verbosity > 0), end="")
    if args.junit:
        args.junit.parent.mkdir(parents=True, exist_ok=True)
        with files.replaced(args.junit, text=True) as f:
            f.write(result.to_junit())
        _say(f"wrote {args.junit}")
    if args.html:
        result.to_html(args.html, title=f"pmdfmu verify {args.file or args.cases}")
        _say(f"wrote {args.html}")
    if args.summary == Path("-"):
        print(result.to_markdown(), end="")
    elif args.summary:
        with open(args.summary, "a") as f:  # GITHUB_STEP_SUMMARY is appended to, in one write
            f.write(result.to_markdown())
        _say(f"wrote {args.summary}")
    return result.exit_status


def cmd_pack(args) -> int:
    """The script and its tables inside a copy of the FMU, `script` starting at it (pack.py)."""
    from .pack import pack

    packed = pack(args.script, args.out, args.fmi_version, _fmu_file(args.fmu), args.name)
    _say(f"wrote {packed.fmu} (FMI {args.fmi_version}): script starts at {packed.start!r}")
    _say(
        f"  modelName {packed.model_name}, {'GUID' if args.fmi_version == 2 else 'instantiation token'} {packed.token}"
    )
    for name in packed.files:
        _say(f"  {name}")
    return 0


def _tcp_endpoint(text: str) -> Tuple[str, int]:
    host, colon, port = text.rpartition(":")
    if not colon or not host or not port.isdigit() or int(port) > 65535:
        raise ValueError(text)
    return host.strip("[]"), int(port)


_tcp_endpoint.__name__ = "HOST:PORT"


def _chip_count(text: str) -> int:
    value = _positive_int(text)
    if value > 32:  # the multi-drop address is 5 bits (pmd-reference 3.3)
        raise ValueError(text)
    return value


_chip_count.__name__ = "number of chips 1..32"


def cmd_serve(args) -> int:
    """Ctrl-C and SIGTERM are how a server is stopped: exit status 0, files written, the link removed
    (docs/device.md)."""
    from .serve import record_paths, serve

    fmu = _fmu_file(args.fmu)
    if args.script:
        files.check_regular(args.script)
    script = str(files.resolved(_script_file(args.script))) if args.script else None
    machine = _machine_file(args.machine)
    records = [("--record", path) for path in record_paths(args.record, args.chips)]
    outputs = [*records, ("--log", args.log)]
    _refuse_overwriting(outputs, _inputs(args.script, fmu, args.machine, args.fmi_version, [o for _, o in outputs]))
    for _, record in records:  # known now, not when the session is over
        if not record.parent.is_dir():
            raise CommandLineError(f"--record {record}: {record.parent} is no folder to write it in")
    if args.serial is not None and "\n" in str(args.serial):
        raise CommandLineError(f"--serial {files.shown_path(args.serial)}: the link's path holds a line feed")
    parameters = {"cycleTime": args.cycle_time}
    if script:
        parameters["script"] = script
    if machine:
        parameters["machine"] = machine
    return serve(
        serial=args.serial,
        tcp=args.tcp,
        chips=args.chips,
        fmi_version=args.fmi_version,
        fmu=fmu,
        realtime=args.realtime,
        reset_on_connect=args.reset_on_connect,
        record=args.record,
        log=args.log,
        monitor=args.monitor,
        **parameters,
    )


def cmd_validate(args) -> int:
    """fmpy.validation on the given FMU, or on both built ones."""
    from fmpy.validation import validate_fmu

    failed = 0
    for path in [_fmu_file(args.fmu)] if args.fmu else [default_fmu(2), default_fmu(3)]:
        problems = validate_fmu(str(path))
        for p in problems:
            print(p)
        print(f"{path}: {'valid' if not problems else f'{len(problems)} problems'}")
        failed += bool(problems)
    return 1 if failed else 0


def cmd_path(args) -> int:
    print(default_fmu(args.fmi_version, args.model))
    return 0


def cmd_info(args) -> int:
    from fmpy import read_model_description

    path = _fmu_file(args.fmu) or default_fmu()
    md = read_model_description(str(path))
    print(f"{path}\n  FMI {md.fmiVersion}, modelIdentifier {md.coSimulation.modelIdentifier}, guid {md.guid}\n")
    print("Variables (value reference, name, causality, type, start, unit, description):")
    for v in md.modelVariables:
        start = "" if v.start is None else str(v.start)
        declared = v.unit or (v.declaredType.unit if v.declaredType is not None else None) or ""
        print(
            f"  {v.valueReference:5d} {v.name:32s} {v.causality:11s} {v.type:8s} {start:>10s}  "
            f"{unit(v.name, declared) or '-':24s} {' '.join((v.description or '').split())}"
        )
    print("\nCommands (opcode, name, arguments -> reply):")
    for c in sorted(COMMANDS.values(), key=lambda c: c.opcode):
        args_ = ", ".join(f.name for f in c.args)
        reply = ", ".join(f.name for f in c.reply)
        print(f"  0x{c.opcode:02X} {c.name}({args_}){' -> ' + reply if reply else ''}")
    return 0


def _positive_int(text: str) -> int:
    value = int(text, 0)
    if value < 1:
        raise ValueError(text)
    return value


def _cycle_time(text: str) -> float:
    value = float(text)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(text)
    return value


_positive_int.__name__ = "whole number >= 1"  # argparse's message: "invalid whole number >= 1 value"
_cycle_time.__name__ = "cycle time (s, > 0)"


# the file types matplotlib writes, by suffix (a plot's format is its name's)
PLOT_SUFFIXES = (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp")


def _plot_path(value: str) -> Path:
    path = Path(value)
    if path.suffix.lower() not in PLOT_SUFFIXES:
        raise argparse.ArgumentTypeError(f"{value}: a plot is written as its suffix says: {', '.join(PLOT_SUFFIXES)}")
    return path


_plot_path.__name__ = "plot file"


def _html_path(value: str) -> Path:
    path = Path(value)
    if path.suffix.lower() not in (".html", ".htm"):
        raise argparse.ArgumentTypeError(f"{value}: the page is written to a .html name")
    return path


_html_path.__name__ = "HTML file"


def _trace_plot_path(value: str) -> Path:
    """--plot of pmdfmu trace: an image, or an interactive page."""
    path = Path(value)
    if path.suffix.lower() not in PLOT_SUFFIXES + (".html",):
        raise argparse.ArgumentTypeError(
            f"{value}: the scope is written as its suffix says: {', '.join(PLOT_SUFFIXES + ('.html',))}"
        )
    return path


_trace_plot_path.__name__ = "plot file"


class _Parser(argparse.ArgumentParser):
    """argparse, its errors on one line as every other input error's: `pmdfmu CMD: reason`."""

    def error(self, message: str):
        self.exit(EXIT_INPUT, f"{self.prog}: {message} ({self.prog} --help)\n")

    def parse_args(self, args=None, namespace=None):
        # argparse reports a subcommand's unknown option from the top parser ("pmdfmu: unrecognized
        # arguments"): the command's own parser says it, so that the line names the command and its help
        parsed, extras = self.parse_known_args(args, namespace)
        if extras:
            sub = next(a for a in self._actions if isinstance(a, argparse._SubParsersAction))
            sub.choices.get(getattr(parsed, "command", None), self).error(f"unrecognized arguments: {' '.join(extras)}")
        return parsed


def main(argv: Optional[List[str]] = None) -> int:
    """The command; exit status 0 done, 1 failed (verify: a check failed; validate: problems found), 2 an input
    error (one line: INPUT_ERRORS), 130 interrupted (one line), 141 standard output's reader went away (silent)."""
    global _verbosity
    command = "pmdfmu"
    try:
        args = _parser().parse_args(argv)
        command = f"pmdfmu {args.command}"
        _verbosity = args.verbosity
        progress.show(True if args.progress else False if _verbosity < 0 else None)
        return args.func(args)
    except INPUT_ERRORS as e:
        if isinstance(e, BrokenPipeError) and _reader_gone():
            # the reader went away (`pmdfmu info | head`): no input was bad. Stop quietly, as a tool that
            # SIGPIPE ends does, with its status; files being written are removed as for any error
            try:  # Python's own flush at exit would fail again, with a traceback
                devnull = os.open(os.devnull, os.O_WRONLY)
                os.dup2(devnull, sys.stdout.fileno())
                os.close(devnull)
            except (OSError, ValueError):  # stdout is no file (a test's capture)
                pass
            return EXIT_BROKEN_PIPE
        print(f"{command}: {one_line(e)}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        # a file being written is removed (files.replaced); what was written whole stays
        print(f"{command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    finally:
        _verbosity = 0
        progress.show(None)


def _reader_gone() -> bool:
    """Whether standard output or error is a pipe or socket its reader has closed: what a BrokenPipeError
    from a print means. One from a pipe or socket of the command's own (a device's line, a worker's) is
    an error to name, not a reason to end without a word."""
    if not hasattr(select, "poll"):  # Windows: no poll to ask, as before
        return True
    poll = select.poll()
    for stream in (sys.stdout, sys.stderr):
        try:
            poll.register(stream.fileno(), select.POLLOUT)
        except (AttributeError, OSError, ValueError):  # no file (a test's capture): no reader to lose
            pass
    return any(events & (select.POLLERR | select.POLLHUP) for _, events in poll.poll(0))


def _interrupt_again(unraisable) -> None:
    """The program's sys.unraisablehook. A Ctrl-C that lands in a weakref or garbage collector callback or a
    finalizer (matplotlib's, FMPy's) is dropped there by Python with a traceback, and the command would
    run on to its end: it is delivered again once the callback is over. A thread delivers it, since
    one raised here would land in this hook and be dropped too; as a SIGINT to the main thread, which wakes
    a wait there (on a lock, a sweep's cases) as a Ctrl-C does: interrupt_main's flag is seen only when
    the wait is over."""
    if issubclass(unraisable.exc_type, KeyboardInterrupt):
        left = threading.Event()
        threading.Thread(target=_interrupt_main, args=(left,), daemon=True).start()
        left.set()  # the last thing done here: however late the main thread runs, the signal comes after
    else:
        sys.__unraisablehook__(unraisable)


def _interrupt_main(left: threading.Event) -> None:
    left.wait()
    time.sleep(0.001)  # the hook's return
    if hasattr(signal, "pthread_kill"):
        signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)
    else:  # Windows
        _thread.interrupt_main()


def console() -> None:
    """The `pmdfmu` program: main, then exit with its status. Its files are written once main returns, so a
    Ctrl-C from then on is ignored, not left to kill Python's exit by SIGINT."""
    sys.unraisablehook = _interrupt_again
    status = main()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    sys.exit(status)


EPILOG = """exit status:
  0    done (verify: every check passed)
  1    a check failed: verify's checks, validate's problems, a run that --max-cycles stopped before
       its profile ended (give --cycles N for a window), sweep --fail-on-error with a failed case
  2    bad input: one line on standard error, `pmdfmu CMD: file:line: reason`
  130  interrupted (Ctrl-C): one line, `pmdfmu CMD: interrupted`; no partial file is left
  141  standard output closed early (`pmdfmu info | head`): nothing said, no partial file left

pmdfmu CMD --help: a command's options. docs/cli.md, docs/verify.md."""

FMI_VERSION_HELP = "FMI version of the built FMU to use: 2 or 3 (default 2)"
FMU_HELP = "the FMU to use (default: the built one)"
MACHINE_HELP = "a machine file: switches and index that follow the axes (docs/machine.md)"
MAX_CYCLES_HELP = (
    "at most this many cycles (default 1000000); a run that stops here before the profile ends is an error (exit 1)"
)
CYCLES_HELP = "record a window: the first N cycles, whether or not the profile has ended by then"


def _verbosity_options(parser: argparse.ArgumentParser, default) -> None:
    """-q/--quiet and -v/--verbose, on pmdfmu and on each command (pmdfmu -q run ... or pmdfmu run -q ...);
    a command's default is SUPPRESS so it does not undo pmdfmu's."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "-q",
        "--quiet",
        dest="verbosity",
        action="store_const",
        const=-1,
        default=default,
        help="print only what went wrong (errors, failed checks and cases)",
    )
    group.add_argument(
        "-v",
        "--verbose",
        dest="verbosity",
        action="store_const",
        const=1,
        default=default,
        help="print more: every check of verify, every case of a sweep",
    )
    parser.add_argument(
        "--progress",
        action="store_true",
        default=False if default == 0 else default,
        help="show progress bars also when standard error is no terminal (a CI log); "
        "by default only on a terminal, never with -q",
    )


def _run_limits(p: argparse.ArgumentParser) -> None:
    """--max-cycles N or --cycles N (a window), never both."""
    group = p.add_mutually_exclusive_group()
    group.add_argument("--max-cycles", type=_positive_int, default=1_000_000, metavar="N", help=MAX_CYCLES_HELP)
    group.add_argument("--cycles", type=_positive_int, metavar="N", help=CYCLES_HELP)


def _chip_options(p: argparse.ArgumentParser, fmi_version: bool = True) -> None:
    """--fmu, --fmi-version and --cycle-time: which FMU runs the chip, and its cycle."""
    p.add_argument("--fmu", type=Path, help=FMU_HELP)
    if fmi_version:
        p.add_argument("--fmi-version", type=int, choices=(2, 3), default=2, help=FMI_VERSION_HELP)
    p.add_argument(
        "--cycle-time",
        type=_cycle_time,
        default=DEFAULT_CYCLE_TIME,
        help=f"chip cycle time in s (default {DEFAULT_CYCLE_TIME:g})",
    )


def _upload_option(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--upload",
        choices=("memory", "command"),
        default="memory",
        help="fill the buffers through the dual-port memory or with WriteBuffer",
    )


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="pmdfmu", description=__doc__, epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--version", action="version", version=f"pmdfmu {__version__}", help="print the version")
    _verbosity_options(parser, 0)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    def command(name: str, help_: str, **kwargs) -> argparse.ArgumentParser:
        p = sub.add_parser(name, help=help_, epilog="exit status: pmdfmu --help", **kwargs)
        _verbosity_options(p, argparse.SUPPRESS)
        return p

    p = command("build", "build the FMU with CMake")
    p.add_argument(
        "--source",
        type=Path,
        help="the pmdfmu checkout (default: the one this package runs from, else the working directory)",
    )
    p.add_argument("--build-dir", type=Path, help="the build folder (default: SOURCE/build)")
    p.add_argument(
        "--platforms",
        type=_platforms,
        default=[],
        metavar="LIST",
        help="also cross-build these platforms' binaries into the FMUs: all, or a comma-separated list of "
        f"{', '.join(CROSS_PLATFORMS)} (default: this host's only; docs/tools.md)",
    )
    p.set_defaults(func=cmd_build)

    for name, func, help_ in (
        ("demo", cmd_demo, "run the bundled 2-axis demo"),
        ("run", cmd_run, "run a script or a segment table; write CSV and plot"),
    ):
        p = command(name, help_)
        _chip_options(p, fmi_version=name == "run")
        p.set_defaults(func=func)
        if name == "demo":
            p.add_argument("--out", type=Path, default=Path("demo-out"), help="output folder (default demo-out)")
        else:
            p.add_argument(
                "file",
                type=Path,
                help="a script, or a CSV segment table (position and optional axis, velocity, acceleration, jerk, time: docs/scripts.md)",
            )
            p.add_argument(
                "--csv",
                type=Path,
                help="write the recorded outputs here (a golden trace for pmdfmu verify; "
                "a .npz name writes compressed numpy)",
            )
            p.add_argument("--plot", type=_plot_path, help="write the plot here (PNG, or PDF, SVG ... by its suffix)")
            if name == "run":
                p.add_argument(
                    "--out",
                    type=Path,
                    help="write the recorded outputs here as they come, in constant memory (.npy, or .npz as "
                    "--csv writes it): for long runs",
                )
            p.add_argument(
                "--html",
                type=_html_path,
                metavar="FILE",
                help="write an interactive page here (zoom, pan, every column; opens offline): the 'html' extra",
            )
            _upload_option(p)
            _run_limits(p)
            p.add_argument("--machine", type=Path, help=MACHINE_HELP)

    p = command(
        "trace",
        "run a script and show the chip's trace buffer as a scope",
        description="Runs the script as `pmdfmu run` does, then reads the trace the script configured "
        "(SetTraceVariable, Period, Mode, Start, Stop) from buffer 0: one panel per variable over chip "
        'time, the trigger marked. docs/chip.md, "Reading the trace".',
    )
    p.add_argument("file", type=Path, help="the script")
    p.add_argument("--plot", type=_trace_plot_path, help="write the scope here: an image (PNG, SVG, PDF) or .html")
    p.add_argument("--csv", type=Path, help="write the samples here (a .npz name writes compressed numpy)")
    _chip_options(p)
    _run_limits(p)
    p.add_argument("--machine", type=Path, help=MACHINE_HELP)
    p.set_defaults(func=cmd_trace)

    p = command("machine", "check a machine file and say what it means")
    p.add_argument("--check", dest="file", type=Path, required=True, metavar="FILE", help="the machine file")
    p.add_argument("--fmu", type=Path, help=FMU_HELP)
    p.set_defaults(func=cmd_machine)

    p = command(
        "sweep",
        "run a table of cases on Dask",
        description="Runs every case of the table and writes summary.csv, CASE.csv and summary.png. A case "
        "that fails is a row of the summary with its reason and does not change the exit status (0) unless "
        "--fail-on-error is given.",
    )
    p.add_argument(
        "cases",
        type=Path,
        help="CSV: name, script or table, fmi_version, max_cycles or cycles (a window), FMU parameters",
    )
    p.add_argument("--out", type=Path, default=Path("sweep-out"), help="output folder (default sweep-out)")
    p.add_argument("--scheduler", help="a Dask scheduler address, or 'serial' (default: a local cluster)")
    p.add_argument("--workers", type=_positive_int, default=2, help="local cluster processes (default 2)")
    p.add_argument(
        "--fail-on-error", action="store_true", help="exit status 1 if any case failed (default: 0, the rows say)"
    )
    p.set_defaults(func=cmd_sweep)

    p = command(
        "verify",
        "check a run against a golden trace and assertions (CI)",
        description="Runs a script or segment table as `pmdfmu run` does (or a case table on Dask) "
        "and checks it; exit status 0 pass, 1 fail, 2 malformed input. docs/verify.md.",
    )
    p.add_argument("file", nargs="?", type=Path, help="a script, or a CSV segment table (as pmdfmu run)")
    p.add_argument(
        "--against", type=Path, metavar="GOLDEN", help="golden trace: `pmdfmu run --csv` output, .csv or .npz"
    )
    p.add_argument("--assertions", type=Path, metavar="FILE", help="limits on the trajectory, TOML (docs/verify.md)")
    p.add_argument(
        "--tolerance",
        action="append",
        metavar="COLUMN=TOL",
        help="absolute tolerance of a column (default: exact), e.g. axis1.velocity=1e-9",
    )
    for flag, keys in LIMIT_FLAGS.items():
        p.add_argument(
            "--" + flag.replace("_", "-"),
            action="append",
            metavar="AXIS=MIN:MAX" if len(keys) == 2 else "AXIS=VALUE",
            help=f"AXIS is 1..4 or all; the assertion file's {' and '.join(keys)}",
        )
    p.add_argument(
        "--no-events", action="append", metavar="AXIS", help="no motion error or limit event on AXIS (1..4 or all)"
    )
    p.add_argument("--no-host-errors", action="store_true", help="no command refused with a host I/O error")
    p.add_argument(
        "--units",
        choices=("counts", "raw"),
        help="units of velocity/acceleration/jerk limits (default counts: counts/s, counts/s^2, counts/s^3)",
    )
    p.add_argument("--cases", type=Path, help="a case table (pmdfmu sweep's, with golden and assertions columns)")
    p.add_argument("--scheduler", help="with --cases: a Dask scheduler address, or 'serial'")
    p.add_argument("--workers", type=_positive_int, default=2, help="with --cases: local cluster processes (default 2)")
    p.add_argument("--junit", type=Path, metavar="FILE", help="write JUnit XML here")
    p.add_argument(
        "--html",
        type=_html_path,
        metavar="FILE",
        help="write an interactive page here: each check, expected vs actual vs difference (the 'html' extra)",
    )
    p.add_argument(
        "--summary",
        type=Path,
        metavar="FILE",
        help="append a Markdown summary here ('-': print it), e.g. $GITHUB_STEP_SUMMARY",
    )
    p.add_argument(
        "--out",
        type=Path,
        default=Path("verify-out"),
        help="where a failure's diff plot and recording go (default verify-out)",
    )
    _chip_options(p)
    _upload_option(p)
    _run_limits(p)
    p.set_defaults(func=cmd_verify)

    p = command("pack", "write an FMU that runs a script profile with no parameter set")
    p.add_argument("script", type=Path, help="the script; the segment tables it loads go with it")
    p.add_argument("--out", type=Path, required=True, help="the FMU to write, e.g. my-profile.fmu")
    p.add_argument("--fmi-version", type=int, choices=(2, 3), default=2, help=FMI_VERSION_HELP)
    p.add_argument("--fmu", type=Path, help="the FMU to copy (default: the built one of that FMI version)")
    p.add_argument(
        "--name",
        help="the profile's name in the FMU's modelName (MODEL.NAME; letters, digits, _), default: the script's file name",
    )
    p.set_defaults(func=cmd_pack)

    p = sub.add_parser(
        "serve",
        help="the twin as a virtual device: the chip's serial packets on a pty or TCP (docs/device.md)",
        description="Serves the chip's serial packet protocol until Ctrl-C or SIGTERM (exit status 0). "
        "Virtual time by default: the chip runs the cycles the line's traffic takes at its baud.",
    )
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--serial", type=Path, metavar="PATH", help="make a pty and a symlink PATH to its slave side")
    where.add_argument("--tcp", type=_tcp_endpoint, metavar="HOST:PORT", help="listen on TCP (port 0: any free)")
    p.add_argument("--chips", type=_chip_count, default=1, help="chips on the line, multi-drop addresses 0..N-1")
    _chip_options(p)
    p.add_argument("--script", type=Path, help="a command script the chip runs from time 0")
    p.add_argument("--machine", type=Path, help=MACHINE_HELP)
    p.add_argument("--realtime", action="store_true", help="pace chip cycles to the wall clock")
    p.add_argument("--reset-on-connect", action="store_true", help="a new client gets chips as after power-up")
    p.add_argument("--record", type=Path, help="write the chips' cycles here when the server stops (CSV or .npz)")
    p.add_argument("--log", type=Path, help="write every packet in and out, with chip time, here")
    p.add_argument(
        "--monitor",
        type=_tcp_endpoint,
        metavar="HOST:PORT",
        help="also listen here for the twin's monitor: cycles, host time, FMU variables, dual-port memory",
    )
    p.set_defaults(func=cmd_serve)

    for name, func, help_ in (
        ("validate", cmd_validate, "validate the FMU"),
        ("info", cmd_info, "list variables and commands"),
    ):
        p = command(name, help_)
        p.add_argument(
            "fmu",
            nargs="?",
            type=Path,
            help="the FMU" + (" (default: both built ones)" if name == "validate" else " (default: the built one)"),
        )
        p.set_defaults(func=func)

    p = command("path", "print the path of a built FMU: the chip's or the plant's (pmdfmu path plant --fmi-version 3)")
    p.add_argument("model", nargs="?", choices=("chip", "plant"), default="chip", help="which FMU (default: chip)")
    p.add_argument("--fmi-version", type=int, choices=(2, 3), default=2, help=FMI_VERSION_HELP)
    p.set_defaults(func=cmd_path)

    return parser


if __name__ == "__main__":
    console()
