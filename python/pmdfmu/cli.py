"""The pmdfmu command: a thin layer over the library.

  pmdfmu build      configure and build the FMU with CMake (into build/)
  pmdfmu demo       run the bundled 2-axis external profile; write CSV and PNG
  pmdfmu run FILE   run a script or a segment table; write CSV and PNG
  pmdfmu sweep CASES  run a table of cases on Dask; write a summary table and plot
  pmdfmu pack SCRIPT  write a copy of the FMU that runs the script with no parameter set
  pmdfmu validate   check the FMU with fmpy.validation
  pmdfmu info       the FMU's variables and the chip's commands
"""
from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path
from typing import List, Optional

from . import profile
from .chip import COMMANDS, REPO, Chip, default_fmu


def _run_table(tables, fmu: Optional[str], cycle_time: float, upload: str, max_cycles: int,
               csv_path: Optional[Path], plot_path: Optional[Path], title: str) -> None:
    with Chip(fmu=fmu, cycleTime=cycle_time) as chip:
        rec = profile.run_segment_table(chip, tables, upload=upload, max_cycles=max_cycles)
    if csv_path:
        profile.write_csv(csv_path, rec)
        print(f"wrote {csv_path} ({len(rec)} cycles)")
    if plot_path:
        profile.plot(plot_path, rec, cycle_time, title=title)
        print(f"wrote {plot_path}")
    for axis in sorted(tables):
        n = axis + 1
        print(f"axis {n}: ended at position {int(rec[f'axis{n}.commandedPosition'][-1])} "
              f"after {len(rec)} cycles")


def cmd_build(args) -> int:
    source = Path(args.source)
    build = Path(args.build_dir)
    subprocess.run(["cmake", "-S", str(source), "-B", str(build), f"-DPython3_EXECUTABLE={sys.executable}"],
                   check=True)
    subprocess.run(["cmake", "--build", str(build)], check=True)
    print(f"built {build / 'PMDMotionProcessor-fmi2.fmu'}")
    return 0


def cmd_demo(args) -> int:
    from .demo import circle_table
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    tables = circle_table()
    profile.write_segment_table(out / "demo_table.csv", tables)
    print(f"wrote {out / 'demo_table.csv'}")
    _run_table(tables, args.fmu, args.cycle_time, "memory", 1_000_000, out / "demo.csv", out / "demo.png",
               "pmdfmu demo: 2-axis external profile (circle)")
    return 0


def cmd_run(args) -> int:
    """A .csv file is a segment table; anything else is a script (README, "Scripts")."""
    path = Path(args.file)
    csv_path, plot_path = (Path(args.csv) if args.csv else None), (Path(args.plot) if args.plot else None)
    if path.suffix.lower() == ".csv":
        _run_table(profile.read_segment_table(path), args.fmu, args.cycle_time, args.upload, args.max_cycles,
                   csv_path, plot_path, f"pmdfmu run {args.file}")
        return 0
    with Chip(fmi_version=args.fmi_version, fmu=args.fmu, cycleTime=args.cycle_time, script=path,
              log_categories=["warnings"]) as chip:
        rec = profile.run_script(chip, max_cycles=args.max_cycles)
        for m in chip.messages:
            print(f"{m.status}: {m.message}", file=sys.stderr)
        cycle_time = chip.cycle_time
    if csv_path:
        profile.write_csv(csv_path, rec)
        print(f"wrote {csv_path} ({len(rec)} cycles)")
    if plot_path:
        profile.plot(plot_path, rec, cycle_time, title=f"pmdfmu run {args.file}")
        print(f"wrote {plot_path}")
    return 0


def cmd_sweep(args) -> int:
    from .sweep import read_cases, sweep
    result = sweep(read_cases(args.cases), scheduler=args.scheduler, workers=args.workers)
    result.write(args.out)
    failed = [r for r in result.rows if r["status"] != "ok"]
    print(f"{len(result.rows) - len(failed)} of {len(result.rows)} cases ran; wrote {args.out}/summary.csv, "
          f"{args.out}/summary.png")
    for r in failed:
        print(f"failed: {r['name']}: {r['reason']}")
    return 0


def cmd_pack(args) -> int:
    """The script and its tables inside a copy of the FMU, `script` starting at it (pack.py)."""
    from .pack import PackError, pack
    try:
        packed = pack(args.script, args.out, args.fmi_version, args.fmu)
    except PackError as e:
        print(f"pmdfmu pack: {e}", file=sys.stderr)
        return 1
    print(f"wrote {packed.fmu} (FMI {args.fmi_version}): script starts at {packed.start!r}")
    for name in packed.files:
        print(f"  {name}")
    return 0


def cmd_validate(args) -> int:
    """fmpy.validation on the given FMU, or on both built ones."""
    from fmpy.validation import validate_fmu
    failed = 0
    for path in [args.fmu] if args.fmu else [str(default_fmu(2)), str(default_fmu(3))]:
        problems = validate_fmu(path)
        for p in problems:
            print(p)
        print(f"{path}: {'valid' if not problems else f'{len(problems)} problems'}")
        failed += bool(problems)
    return 1 if failed else 0


def cmd_info(args) -> int:
    from fmpy import read_model_description
    path = args.fmu or str(default_fmu())
    md = read_model_description(path)
    print(f"{path}\n  FMI {md.fmiVersion}, modelIdentifier {md.coSimulation.modelIdentifier}, guid {md.guid}\n")
    print("Variables:")
    for v in md.modelVariables:
        start = f" = {v.start}" if v.start is not None else ""
        print(f"  {v.valueReference:5d} {v.name:32s} {v.causality:9s} {v.type:8s}{start}")
    print("\nCommands (opcode, name, arguments -> reply):")
    for c in sorted(COMMANDS.values(), key=lambda c: c.opcode):
        args_ = ", ".join(f.name for f in c.args)
        reply = ", ".join(f.name for f in c.reply)
        print(f"  0x{c.opcode:02X} {c.name}({args_}){' -> ' + reply if reply else ''}")
    return 0


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="pmdfmu", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("build", help="build the FMU with CMake")
    p.add_argument("--source", default=str(REPO))
    p.add_argument("--build-dir", default=str(REPO / "build"))
    p.set_defaults(func=cmd_build)

    for name, func, help_ in (("demo", cmd_demo, "run the bundled 2-axis demo"),
                              ("run", cmd_run, "run a segment table")):
        p = sub.add_parser(name, help=help_)
        p.add_argument("--fmu", help="FMU to use (default: the built one)")
        p.add_argument("--cycle-time", type=float, default=1e-4, help="chip cycle time in s (default 1e-4)")
        p.set_defaults(func=func)
        if name == "demo":
            p.add_argument("--out", default="demo-out", help="output folder (default demo-out)")
        else:
            p.add_argument("file", help="a script, or a CSV segment table (axis,position,velocity,acceleration,"
                                        "jerk,time in raw units)")
            p.add_argument("--fmi-version", type=int, choices=(2, 3), default=2)
            p.add_argument("--csv", help="write the recorded outputs here")
            p.add_argument("--plot", help="write a PNG plot here")
            p.add_argument("--upload", choices=("memory", "command"), default="memory",
                           help="fill the buffers through the dual-port memory or with WriteBuffer")
            p.add_argument("--max-cycles", type=int, default=1_000_000)

    p = sub.add_parser("sweep", help="run a table of cases on Dask")
    p.add_argument("cases", help="CSV: name, script or table, fmi_version, max_cycles, FMU parameters")
    p.add_argument("--out", default="sweep-out", help="output folder (default sweep-out)")
    p.add_argument("--scheduler", help="a Dask scheduler address, or 'serial' (default: a local cluster)")
    p.add_argument("--workers", type=int, default=2, help="local cluster processes (default 2)")
    p.set_defaults(func=cmd_sweep)

    p = sub.add_parser("pack", help="write an FMU that runs a script profile with no parameter set")
    p.add_argument("script", help="the script; the segment tables it loads go with it")
    p.add_argument("--out", required=True, help="the FMU to write, e.g. my-profile.fmu")
    p.add_argument("--fmi", "--fmi-version", dest="fmi_version", type=int, choices=(2, 3), default=2,
                   help="FMI version (default 2)")
    p.add_argument("--fmu", help="the FMU to copy (default: the built one of that FMI version)")
    p.set_defaults(func=cmd_pack)

    for name, func, help_ in (("validate", cmd_validate, "validate the FMU"),
                              ("info", cmd_info, "list variables and commands")):
        p = sub.add_parser(name, help=help_)
        p.add_argument("fmu", nargs="?")
        p.set_defaults(func=func)

    args = parser.parse_args(argv)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
