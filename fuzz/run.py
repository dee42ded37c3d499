#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-2-Clause
"""Builds the fuzz targets with clang's libFuzzer (+ ASan + UBSan) and runs each
for a while. A crash leaves its input in fuzz/findings/; copy it into
fuzz/regressions/TARGET/ and the test suite replays it from then on.

    python fuzz/run.py [--seconds 60] [--out DIR] [target ...]
                       targets: host fmi script sequence script_text resource_uri machine_text serial

sequence (fuzz_sequence.c) decodes its input as a sequence of legal
operations through FMI 2 or 3 and checks properties after every call (see the
head of that file: the input format, the properties, FUZZ_SEQUENCE_TRACE=1 to
print a crash file's calls); fuzz/sequence_inputs.py writes its hand-built
seeds and regression inputs.

serial (fuzz_serial.c) feeds any byte stream to the C library's serial packet
codec (host/c/PMDserial.c), the chip's decoder and the host's reply parser.

machine_text (fuzz_machine_text.c) parses machine files given as text and checks
what they mean against the inputs the chip then gets.

script_text (fuzz_script_text.c) compiles a script given as text
(the script parameter's value holding a line feed) with a resources folder,
and checks it against the same bytes compiled as a file there; resource_uri
(fuzz_resource_uri.c) decodes FMI 2's fmuResourceLocation against a reference
reading of file URIs and follows a URI of its own folder through
fmi2Instantiate to the script and tables found there. The head of each file
gives its input format and properties.
"""

import argparse
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

TARGETS = ("host", "fmi", "script", "sequence", "script_text", "resource_uri", "machine_text", "serial")


def sources(target: str, gen: Path):
    chip = sorted(str(p) for p in (ROOT / "fmu_src" / "chip").glob("*.c"))
    fmi = [
        str(ROOT / "fmu_src" / "fmi" / n) for n in ("instance.c", "messages.c", "record.c", "state.c", "state_fields.c")
    ]
    script = [
        str(ROOT / "fmu_src" / "script" / "script.c"),
        str(ROOT / "fmu_src" / "machine" / "machine_toml.c"),
        str(ROOT / "fmu_src" / "plant" / "plant.c"),  # a machine's servo = "plant"
    ]
    generated = [
        str(gen / n)
        for n in ("variables.c", "command_table.c", "register_table.c", "pmd_constants.c", "log_categories.c")
    ] + [str(gen / "plant" / "plant_variables.c")]
    # fuzz_resource_uri.c includes fmi2.c itself (its URI decoder is static there)
    extra = {
        "resource_uri": ["fmi_common/token.c"],
        "serial": ["../host/c/PMDserial.c"],
        "fmi": ["fmi_common/fmi2.c", "fmi_common/fmi2_not_provided.c", "fmi_common/token.c", "fmi/record_fmi2.c"],
        "sequence": [
            "fmi_common/fmi2.c",
            "fmi_common/fmi2_not_provided.c",
            "fmi/record_fmi2.c",
            "fmi_common/fmi3.c",
            "fmi_common/fmi3_not_provided.c",
            "fmi_common/token.c",
            "fmi/model3.c",
            "fmi/record_fmi3.c",
        ],
    }.get(target, [])
    extra = [str(ROOT / "fmu_src" / n) for n in extra]
    if target == "sequence":
        generated.append(str(gen / "variables3.c"))
    return [str(ROOT / "fuzz" / f"fuzz_{target}.c"), *chip, *script, *fmi, *extra, *generated]


def include_flags(gen: Path):
    headers = Path(__import__("fmpy").__file__).parent / "c-code"
    return [f"-I{ROOT / 'fmu_src' / d}" for d in ("chip", "script", "machine", "plant", "fmi", "fmi_common")] + [
        f"-I{ROOT / 'host' / 'c'}",
        f"-I{gen}",
        f"-I{gen / 'plant'}",
        f"-I{headers}",
    ]


def generated(gen: Path = ROOT / "build" / "fuzz" / "generated") -> Path:
    """The generated C files, in a folder of the fuzzer's own (never the CMake build's)."""
    subprocess.run([sys.executable, str(ROOT / "modelDescription" / "generate.py"), str(gen)], check=True)
    subprocess.run(
        [sys.executable, str(ROOT / "modelDescription" / "generate_plant.py"), str(gen / "plant")], check=True
    )
    return gen


# PMD_CHECK_INVARIANTS: the chip's invariant checks (pmd_memory_store) abort instead of refusing quietly
CHECKS = ["-DPMD_CHECK_INVARIANTS"]


def build(target: str, gen: Path, out: Path) -> Path:
    exe = out / f"fuzz_{target}"
    subprocess.run(
        [
            "clang",
            "-g",
            "-O1",
            "-std=c99",
            "-D_DEFAULT_SOURCE",
            *CHECKS,
            "-fsanitize=fuzzer,address,undefined,float-cast-overflow",
            "-fno-sanitize-recover=all",
            f"-fsanitize-coverage-ignorelist={ROOT / 'fuzz' / 'coverage_ignore.txt'}",
            *include_flags(gen),
            *sources(target, gen),
            "-lm",
            "-o",
            str(exe),
        ],
        check=True,
    )
    return exe


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=int, default=60)
    parser.add_argument(
        "--out",
        type=Path,
        default=ROOT / "build" / "fuzz",
        help="where the targets and their growing corpora go (default: build/fuzz)",
    )
    parser.add_argument("targets", nargs="*", default=list(TARGETS))
    args = parser.parse_args()
    out = args.out.resolve()
    gen = generated(out / "generated-fuzz")  # not generated/: --out may be a CMake build folder, whose differs
    out.mkdir(parents=True, exist_ok=True)
    failed = []
    for target in args.targets:
        exe = build(target, gen, out)
        corpus = out / "corpus" / target
        corpus.mkdir(parents=True, exist_ok=True)
        findings = ROOT / "fuzz" / "findings" / target
        findings.mkdir(parents=True, exist_ok=True)
        # seeds: the saved corpus and the regression inputs (deep states, already minimal)
        seeds = [
            str(d) for d in (ROOT / "fuzz" / "corpus" / target, ROOT / "fuzz" / "regressions" / target) if d.is_dir()
        ]
        print(f"fuzzing {target} for {args.seconds} s", flush=True)
        result = subprocess.run(
            [
                str(exe),
                str(corpus),
                *seeds,
                f"-max_total_time={args.seconds}",
                "-rss_limit_mb=2048",
                "-timeout=20",
                f"-artifact_prefix={findings}/",
                "-print_final_stats=1",
            ],
            capture_output=True,
            text=True,
        )
        lines = result.stderr.splitlines()
        # what went wrong (sanitizer, property, crash file), then libFuzzer's final stats
        said = [
            line
            for line in lines
            if any(
                k in line
                for k in ("ERROR:", "runtime error", "property violated", "the FMU's last error", "Test unit written")
            )
        ]
        print("\n".join(said[:8] + lines[-6:]), flush=True)
        if result.returncode != 0:
            failed.append(target)
    print("fuzzing found problems in: " + ", ".join(failed) if failed else "fuzzing found nothing")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
