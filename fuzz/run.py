#!/usr/bin/env python3
"""Builds the fuzz targets with clang's libFuzzer (+ ASan + UBSan) and runs each
for a while (issue 6). A crash leaves its input in fuzz/findings/; copy it into
fuzz/regressions/TARGET/ and the test suite replays it from then on.

    python fuzz/run.py [--seconds 60] [target ...]      targets: host fmi script
"""
import argparse
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

TARGETS = ("host", "fmi", "script")


def sources(target: str, gen: Path):
    chip = sorted(str(p) for p in (ROOT / "fmu_src" / "chip").glob("*.c"))
    fmi = [str(ROOT / "fmu_src" / "fmi" / n) for n in ("instance.c", "state.c", "state_fields.c", "script.c")]
    generated = [str(gen / n) for n in ("variables.c", "command_table.c", "pmd_constants.c")]
    extra = [str(ROOT / "fmu_src" / "fmi" / "fmi2.c")] if target == "fmi" else []
    return [str(ROOT / "fuzz" / f"fuzz_{target}.c"), *chip, *fmi, *extra, *generated]


def include_flags(gen: Path):
    headers = Path(__import__("fmpy").__file__).parent / "c-code"
    return [f"-I{ROOT / 'fmu_src' / 'chip'}", f"-I{ROOT / 'fmu_src' / 'fmi'}", f"-I{gen}", f"-I{headers}"]


def generated() -> Path:
    """The generated C files, in a folder of the fuzzer's own (never the CMake build's)."""
    gen = ROOT / "build" / "fuzz" / "generated"
    subprocess.run([sys.executable, str(ROOT / "modelDescription" / "generate.py"), str(gen)], check=True)
    return gen


def build(target: str, gen: Path, out: Path) -> Path:
    exe = out / f"fuzz_{target}"
    subprocess.run(["clang", "-g", "-O1", "-std=c99", "-D_DEFAULT_SOURCE", "-fsanitize=fuzzer,address,undefined",
                    "-fno-sanitize-recover=all", *include_flags(gen), *sources(target, gen), "-lm", "-o", str(exe)],
                   check=True)
    return exe


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=int, default=60)
    parser.add_argument("targets", nargs="*", default=list(TARGETS))
    args = parser.parse_args()
    gen = generated()
    out = ROOT / "build" / "fuzz"
    out.mkdir(parents=True, exist_ok=True)
    failed = []
    for target in args.targets:
        exe = build(target, gen, out)
        corpus = out / "corpus" / target
        corpus.mkdir(parents=True, exist_ok=True)
        findings = ROOT / "fuzz" / "findings" / target
        findings.mkdir(parents=True, exist_ok=True)
        seeds = ROOT / "fuzz" / "corpus" / target
        print(f"fuzzing {target} for {args.seconds} s", flush=True)
        result = subprocess.run([str(exe), str(corpus), str(seeds), f"-max_total_time={args.seconds}",
                                 "-rss_limit_mb=2048", "-timeout=20", f"-artifact_prefix={findings}/",
                                 "-print_final_stats=1"], capture_output=True, text=True)
        tail = "\n".join(result.stderr.splitlines()[-6:])
        print(tail, flush=True)
        if result.returncode != 0:
            failed.append(target)
    print("fuzzing found problems in: " + ", ".join(failed) if failed else "fuzzing found nothing")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
