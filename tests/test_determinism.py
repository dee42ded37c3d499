# SPDX-License-Identifier: BSD-2-Clause
"""Determinism: the same scripted profile run 10 times, and through
FMI 2 and FMI 3, gives byte-identical CSVs."""

import hashlib
import importlib.util
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from pmdfmu.cli import main

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "examples" / "two_axis.script"


@pytest.mark.slow
def test_ten_runs_through_fmi2_and_fmi3_write_identical_csvs(tmp_path):
    digests = set()
    for k in range(10):
        out = tmp_path / f"run{k}.csv"
        assert main(["run", str(SCRIPT), "--csv", str(out), "--fmi-version", str(2 + k % 2)]) == 0
        digests.add(hashlib.sha256(out.read_bytes()).hexdigest())
    assert len(digests) == 1


SANITIZERS = ["-fsanitize=address,undefined,float-cast-overflow", "-fno-sanitize-recover=all"]


def sanitizers_available(tmp_path) -> bool:
    """Whether cc can build and run an ASan + UBSan program here."""
    probe = tmp_path / "probe.c"
    probe.write_text("int main(void) { return 0; }\n")
    built = subprocess.run(["cc", *SANITIZERS, str(probe), "-o", str(tmp_path / "probe")], capture_output=True)
    return built.returncode == 0 and subprocess.run([str(tmp_path / "probe")], capture_output=True).returncode == 0


def fuzz_driver():
    """fuzz/run.py, the fuzzers' own list of targets and how each is built"""
    import sys

    sys.path.insert(0, str(ROOT / "fuzz"))
    import run as fuzz

    return fuzz


def replayer(tmp_path, fuzz, gen, target, flags=()):
    """TARGET built with the fuzz build's invariant checks and fuzz/replay.c as its main, with FLAGS."""
    exe = tmp_path / f"replay_{target}"
    subprocess.run(
        [
            "cc",
            "-g",
            "-O1",
            "-std=c99",
            "-D_DEFAULT_SOURCE",
            *fuzz.CHECKS,
            *flags,
            *fuzz.include_flags(gen),
            str(ROOT / "fuzz" / "replay.c"),
            *fuzz.sources(target, gen),
            "-lm",
            "-o",
            str(exe),
        ],
        check=True,
    )
    return exe


@pytest.mark.slow
@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
def test_saved_fuzz_inputs_replay_without_failure(tmp_path):
    """Every input in fuzz/corpus and fuzz/regressions runs through its target,
    built with the ordinary compiler and a replay driver (fuzz/replay.c), with
    the fuzz build's invariant checks and, where cc has them, ASan and UBSan
    (some regression inputs fail only under a sanitizer). Each input runs on its
    own, so that a failure names every input that fails."""
    fuzz = fuzz_driver()
    gen = fuzz.generated()
    sanitize = SANITIZERS if sanitizers_available(tmp_path) else []
    env = {**os.environ, "ASAN_OPTIONS": "detect_leaks=0", "UBSAN_OPTIONS": "print_stacktrace=1"}
    failed = []
    for target in fuzz.TARGETS:
        inputs = sorted(
            p for d in ("corpus", "regressions") for p in (ROOT / "fuzz" / d / target).glob("*") if p.is_file()
        )
        if not inputs:
            continue
        exe = replayer(tmp_path, fuzz, gen, target, sanitize)
        for path in inputs:
            out = subprocess.run([str(exe), str(path)], capture_output=True, text=True, timeout=300, env=env)
            if out.returncode != 0 or "replayed 1 inputs" not in out.stdout:
                failed.append(f"{path.relative_to(ROOT)}:\n{out.stderr[-1500:]}")
    assert not failed, f"{len(failed)} saved fuzz inputs fail:\n" + "\n".join(failed)


@pytest.mark.slow
@pytest.mark.sanitize
@pytest.mark.skipif(not (shutil.which("cc") and shutil.which("valgrind")), reason="no C compiler or valgrind")
def test_regression_inputs_run_clean_under_valgrind(tmp_path):
    """Every regression input (the legal-call findings of the attacks and the fuzzers) once more under
    valgrind, with a build without sanitizers: no invalid access, no uninitialized
    value used, no leak."""
    fuzz = fuzz_driver()
    gen = fuzz.generated()
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}  # ./dev sanitize preloads ASan
    failed = []
    for target in fuzz.TARGETS:
        inputs = sorted(p for p in (ROOT / "fuzz" / "regressions" / target).glob("*") if p.is_file())
        if not inputs:
            continue
        exe = replayer(tmp_path, fuzz, gen, target)
        for path in inputs:
            out = subprocess.run(
                [
                    "valgrind",
                    "-q",
                    "--error-exitcode=99",
                    "--leak-check=full",
                    "--errors-for-leak-kinds=definite",
                    str(exe),
                    str(path),
                ],
                capture_output=True,
                text=True,
                timeout=600,
                env=env,
            )
            if out.returncode != 0:
                failed.append(f"{path.relative_to(ROOT)}:\n{out.stderr[-1500:]}")
    assert not failed, f"{len(failed)} regression inputs fail under valgrind:\n" + "\n".join(failed)


def load_sequence_inputs():
    spec = importlib.util.spec_from_file_location("sequence_inputs", ROOT / "fuzz" / "sequence_inputs.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_every_sequence_fuzzer_operation_has_an_encoder_and_a_saved_input_that_uses_it(monkeypatch):
    """fuzz/sequence_inputs.py reads the operations from fuzz_sequence.c's OPS[]: each needs a Seq method of
    its name (the bytes it reads), and some seed or regression input must run it; the saved files are the
    ones the script writes."""
    inputs = load_sequence_inputs()
    ops = inputs.read_ops()
    assert ops == inputs.OPS and len(ops) == len(set(ops))
    missing = [name for name in ops if not callable(getattr(inputs.Seq, name, None))]
    assert not missing, f"operations of fuzz_sequence.c's OPS[] without a Seq method: {missing}"
    used = set()
    real_op = inputs.Seq.op
    monkeypatch.setattr(inputs.Seq, "op", lambda self, name: (used.add(name), real_op(self, name))[1])
    written = {("corpus", name): s for name, s in inputs.seeds().items()}
    written.update({("regressions", name): s for name, s in inputs.regressions().items()})
    assert not set(ops) - used, f"operations no saved input runs: {sorted(set(ops) - used)}"
    for (folder, name), seq in written.items():
        path = ROOT / "fuzz" / folder / "sequence" / name
        assert path.read_bytes() == seq.bytes(), f"{path.relative_to(ROOT)}: run fuzz/sequence_inputs.py"
