# SPDX-License-Identifier: BSD-2-Clause
"""Sweeps on a running cluster: a Client passed in is used as it is and
stays open, its workers keep their FMU instances from sweep to sweep; an address goes through
this process's client of it; cases in batches and in several threads of a worker give exactly
the serial run; a rewritten FMU file is a new instance. docs/sweeps.md: its example runs."""

import importlib
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import dask.distributed
import numpy as np
import pytest
from dask.distributed import Client, LocalCluster

import pmdfmu
from pmdfmu.sweep import Case

pytestmark = pytest.mark.slow  # tests/README.md: ./dev test -m "not slow" leaves them out

sweeps = importlib.import_module("pmdfmu.sweep")  # the module (pmdfmu.sweep is also the function)

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"


@pytest.fixture(scope="module")
def cluster():
    """One worker process running cases in two threads at once."""
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=True, dashboard_address=None) as c:
        yield c


def same(result, expected):
    assert result.rows == expected.rows
    assert set(result.recordings) == set(expected.recordings)
    for name, rec in expected.recordings.items():
        assert np.array_equal(result.recordings[name], rec), name


def idle_instances():
    """This worker's idle instances: (FMU file, FMI version) -> their FMU instance pointers."""
    sweeps = importlib.import_module("pmdfmu.sweep")
    return {(key[0][0], key[1]): {chip.fmu.component for chip in chips} for key, chips in sweeps._idle.items()}


def test_a_client_is_reused_as_it_is_and_its_workers_keep_their_instances(cluster, cases, serial):
    with Client(cluster, set_as_default=False) as client:
        same(pmdfmu.sweep(cases, scheduler=client), serial)
        assert client.status == "running"
        (first,) = client.run(idle_instances).values()
        for _ in range(3):
            same(pmdfmu.sweep(cases, scheduler=client), serial)
            assert client.status == "running"
        (later,) = client.run(idle_instances).values()
        # the later sweeps took the first one's instances; at most one more per thread running cases
        assert first.keys() == later.keys() and all(first[k] <= later[k] for k in first)
        assert all(1 <= len(pointers) <= 2 for pointers in later.values())


def test_an_address_goes_through_the_default_client_connected_there(cluster, cases, serial, monkeypatch):
    with Client(cluster.scheduler_address) as client:  # this process's default client

        def no_new_client(*args, **kwargs):
            raise AssertionError("the sweep opened a client of its own")

        monkeypatch.setattr(dask.distributed, "Client", no_new_client)
        same(pmdfmu.sweep(cases, scheduler=cluster.scheduler_address), serial)
        assert client.status == "running"


def test_an_address_without_a_client_of_it_gets_one_for_the_call(cluster, cases, serial):
    same(pmdfmu.sweep(cases, scheduler=cluster.scheduler_address), serial)


def test_many_cases_in_batches_in_two_threads_equal_the_serial_run(cluster, cases):
    many = [
        Case(f"{c.name}-{k}", c.script, c.table, c.parameters, c.fmi_version, c.max_cycles, c.fmu)
        for k in range(4)
        for c in cases
    ]
    with Client(cluster, set_as_default=False) as client:
        same(pmdfmu.sweep(many, scheduler=client), pmdfmu.sweep(many, scheduler="serial"))


@pytest.mark.parametrize(
    "n,threads,sizes",
    [(8, 2, [1] * 8), (64, 2, [8] * 8), (10, 2, [1, 1, 1, 2, 1, 1, 1, 2]), (3, 4, [1, 1, 1]), (1, 1, [1]), (0, 2, [0])],
)
def test_batches_are_consecutive_cases_a_few_per_thread(n, threads, sizes):
    batches = sweeps._batches(list(range(n)), threads)
    assert [len(b) for b in batches] == sizes
    assert [c for b in batches for c in b] == list(range(n))


def test_a_rewritten_fmu_file_is_a_new_instance(tmp_path):
    fmu = Path(shutil.copy(pmdfmu.default_fmu(2), tmp_path / "copy.fmu"))
    case = Case("copy", script=str(EXAMPLES / "two_axis.script"), fmu=str(fmu))
    before = pmdfmu.sweep([case], scheduler="serial")
    folders = {c._unzipdir for chips in sweeps._idle.values() for c in chips}
    with zipfile.ZipFile(fmu, "a") as z:  # the same path, another file
        z.writestr("resources/marker.txt", "rewritten")
    after = pmdfmu.sweep([case], scheduler="serial")
    same(after, before)
    used = [c for key, chips in sweeps._idle.items() if key[0][0] == str(fmu.resolve()) for c in chips]
    assert len(used) == 2
    new = [c for c in used if c._unzipdir not in folders]
    assert len(new) == 1 and (Path(new[0]._unzipdir) / "resources" / "marker.txt").exists()


def test_readme_reuse_example_prints_what_it_says(tmp_path):
    """Run as a user runs it, a script file: Dask spawns its workers, which import that file again, so a
    cluster started at the top of it fails (a page of tracebacks) where exec() of the text passed."""
    section = (REPO / "docs" / "sweeps.md").read_text()
    code = next(block.split("```", 1)[0] for block in section.split("```python\n")[1:] if "LocalCluster" in block)
    script = tmp_path / "reuse.py"
    script.write_text(code)
    done = subprocess.run([sys.executable, str(script)], cwd=REPO, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    said = [line.split("# -> ", 1)[1].strip() for line in code.split("\n") if "# -> " in line]
    assert done.stdout.splitlines()[: len(said)] == said


# ---- large recordings: handed back through a file on the same machine ----


def long_move(path: Path, cycles: int) -> Path:
    """Axis 1 in a trapezoidal move for `cycles` cycles: a recording of about 42 bytes a cycle."""
    path.write_text(
        "@ 0\nSetProfileMode(Axis1, PMDTrapezoidalProfile);\nSetPosition(Axis1, 2000000000);\n"
        "SetVelocity(Axis1, 0x10000);\nSetAcceleration(Axis1, 0x100);\nUpdate(Axis1);\n"
        f"@ {cycles}\nSetStopMode(Axis1, PMDAbruptStop);\nUpdate(Axis1);\n"
    )
    return path


@pytest.fixture(scope="module")
def large(tmp_path_factory):
    script = long_move(tmp_path_factory.mktemp("large") / "long.script", 60_000)
    cases = [Case(f"long{k}", script=str(script), fmi_version=2 + k % 2) for k in range(4)]
    expected = pmdfmu.sweep(cases, scheduler="serial")
    assert all(rec.nbytes >= sweeps.HANDOFF_BYTES for rec in expected.recordings.values())
    return cases, expected


def test_a_worker_hands_a_large_recording_back_through_the_sweeps_folder(cluster, large, tmp_path):
    cases, expected = large
    (tmp_path / "token").write_text("the token")
    with Client(cluster, set_as_default=False) as client:
        ((row, handed),) = client.submit(
            sweeps.run_cases, cases[:1], handoff=(str(tmp_path), "the token"), pure=False
        ).result()
        assert isinstance(handed, sweeps._Handed) and Path(handed.path).parent == tmp_path
        assert row == expected.rows[0]
        with pytest.raises(RuntimeError, match="not a recording of the sweep's folder"):
            sweeps._received((row, handed), str(tmp_path / "elsewhere"))  # only the sweep's own files
        rec = sweeps._received((row, handed), str(tmp_path))[1]
        assert not Path(handed.path).exists()
        assert type(rec) is np.ndarray and rec.dtype == expected.recordings["long0"].dtype
        assert np.array_equal(rec, expected.recordings["long0"])
        rec["axis1.position"] += 1  # the caller's own array: writable, shared with nothing
        assert np.array_equal(rec["axis1.position"], expected.recordings["long0"]["axis1.position"] + 1)
        # another token (another machine's folder): the recording comes through Dask
        ((_, rec),) = client.submit(
            sweeps.run_cases, cases[:1], handoff=(str(tmp_path), "another"), pure=False
        ).result()
        assert isinstance(rec, np.ndarray) and np.array_equal(rec, expected.recordings["long0"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["token"]


def test_a_recording_that_cannot_be_written_comes_through_dask(large, tmp_path):
    rec = large[1].recordings["long0"]
    assert sweeps._hand(str(tmp_path / "missing"), rec) is rec
    assert sweeps._hand(None, rec) is rec
    small = rec[:100]
    assert sweeps._hand(str(tmp_path), small) is small


def test_large_recordings_on_a_cluster_equal_the_serial_run_and_leave_no_file(cluster, large, monkeypatch):
    cases, expected = large
    made = []
    mkdtemp = sweeps.tempfile.mkdtemp

    def recorded(*args, **kwargs):
        made.append(mkdtemp(*args, **kwargs))
        return made[-1]

    monkeypatch.setattr(sweeps.tempfile, "mkdtemp", recorded)
    with Client(cluster, set_as_default=False) as client:
        same(pmdfmu.sweep(cases, scheduler=client), expected)
    assert len(made) == 1 and not Path(made[0]).exists()


def test_a_killed_sweeps_folder_is_removed_by_the_next_sweep(cluster, tmp_path):
    """A sweep killed outright (SIGKILL: no cleanup runs) leaves its handoff folder, holding RAM in
    /dev/shm; the next sweep removes it, as no process holds the lock on its token any more. A folder
    whose lock is held (a running sweep's) is left."""
    import glob
    import os
    import signal
    import subprocess
    import sys
    import time

    script = long_move(tmp_path / "long.script", 2_000_000)
    code = (
        "import pmdfmu\nfrom pmdfmu.sweep import Case\n"
        f"pmdfmu.sweep([Case(f'long{{k}}', script={str(script)!r}) for k in range(4)], workers=1)\n"
    )
    process = subprocess.Popen(
        [sys.executable, "-c", code], start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
    )
    pattern = os.path.join(sweeps.handoff_root(), f"{sweeps.HANDOFF_PREFIX}{process.pid}-*")
    try:
        deadline = time.monotonic() + 120
        while not glob.glob(pattern) and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.05)
        left = glob.glob(pattern)
        assert left, "the sweep made no handoff folder"
    finally:
        process.kill()  # the sweep's process alone: its workers see it gone and end
        process.wait()
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            try:
                os.killpg(process.pid, 0)
            except ProcessLookupError:
                break
            time.sleep(0.1)
        else:
            os.killpg(process.pid, signal.SIGKILL)
    assert Path(left[0], "token").exists()  # nothing removed it
    alive = Path(sweeps.handoff_root(), f"{sweeps.HANDOFF_PREFIX}{os.getpid()}-test")
    alive.mkdir()
    held = sweeps._hold(alive / "token", f"{os.getpid()}-abc")  # as a running sweep holds it
    # a sweep killed between its folder and its token: removed once older than any sweep takes to write it,
    # a young one (a sweep starting now) left alone
    tokenless, young = (Path(sweeps.handoff_root(), f"{sweeps.HANDOFF_PREFIX}{os.getpid()}-{n}") for n in "ty")
    for folder in (tokenless, young):
        folder.mkdir()
    old = time.time() - 2 * sweeps.TOKENLESS_AGE
    os.utime(tokenless, (old, old))
    try:
        with Client(cluster, set_as_default=False) as client:
            pmdfmu.sweep([Case("short", script=str(long_move(tmp_path / "short.script", 100)))], scheduler=client)
        assert not Path(left[0]).exists() and alive.exists()
        assert not tokenless.exists() and young.exists()
    finally:
        os.close(held)
        for folder in (alive, tokenless, young):
            shutil.rmtree(folder, ignore_errors=True)


def test_a_sweep_interrupted_at_random_times_leaves_no_folder(tmp_path):
    """Ctrl-C (SIGINT) at random times while a sweep runs on its local cluster: the sweep raises
    KeyboardInterrupt, its cluster closes, and its handoff folder is gone with it."""
    import glob
    import os
    import random
    import signal
    import subprocess
    import sys
    import time

    script = long_move(tmp_path / "long.script", 1_000_000)
    code = (
        "import signal\nsignal.signal(signal.SIGINT, signal.default_int_handler)\n"  # a background job ignores it
        "import pmdfmu\nfrom pmdfmu.sweep import Case\ntry:\n"
        f"    pmdfmu.sweep([Case(f'long{{k}}', script={str(script)!r}) for k in range(4)], workers=1)\n"
        "except KeyboardInterrupt:\n    print('interrupted', flush=True)\n"
    )
    rng = random.Random(7)
    for _ in range(2):
        process = subprocess.Popen(
            [sys.executable, "-c", code],
            start_new_session=True,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        pattern = os.path.join(sweeps.handoff_root(), f"{sweeps.HANDOFF_PREFIX}{process.pid}-*")
        try:
            deadline = time.monotonic() + 120
            while not glob.glob(pattern) and time.monotonic() < deadline and process.poll() is None:
                time.sleep(0.02)
            time.sleep(rng.random() * 0.5)
            process.send_signal(signal.SIGINT)
            out, _ = process.communicate(timeout=120)
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
        assert out == "interrupted\n" and not glob.glob(pattern)
