"""Determinism (issue 6): the same scripted profile run 10 times, and through
FMI 2 and FMI 3, gives byte-identical CSVs."""
import hashlib
import shutil
import subprocess
from pathlib import Path

import pytest

from pmdfmu.cli import main

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "examples" / "two_axis.script"


def test_ten_runs_through_fmi2_and_fmi3_write_identical_csvs(tmp_path):
    digests = set()
    for k in range(10):
        out = tmp_path / f"run{k}.csv"
        assert main(["run", str(SCRIPT), "--csv", str(out), "--fmi-version", str(2 + k % 2)]) == 0
        digests.add(hashlib.sha256(out.read_bytes()).hexdigest())
    assert len(digests) == 1


@pytest.mark.skipif(not shutil.which("cc"), reason="no C compiler")
def test_saved_fuzz_inputs_replay_without_failure(tmp_path):
    """Every input in fuzz/corpus and fuzz/regressions runs through its target,
    built with the ordinary compiler and a replay driver (fuzz/replay.c)."""
    import sys
    sys.path.insert(0, str(ROOT / "fuzz"))
    import run as fuzz
    gen = fuzz.generated()
    for target in fuzz.TARGETS:
        inputs = sorted(p for d in ("corpus", "regressions") for p in (ROOT / "fuzz" / d / target).glob("*")
                        if p.is_file())
        if not inputs:
            continue
        exe = tmp_path / f"replay_{target}"
        subprocess.run(["cc", "-O1", "-std=c99", "-D_DEFAULT_SOURCE", *fuzz.include_flags(gen),
                        str(ROOT / "fuzz" / "replay.c"), *fuzz.sources(target, gen), "-lm", "-o", str(exe)],
                       check=True)
        out = subprocess.run([str(exe), *map(str, inputs)], capture_output=True, text=True, timeout=300)
        assert out.returncode == 0, out.stderr[-2000:]
        assert f"replayed {len(inputs)} inputs" in out.stdout
