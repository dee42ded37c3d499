# SPDX-License-Identifier: BSD-2-Clause
"""Parameter and profile studies on Dask.

A sweep runs a table of cases - FMU parameters, a script or a segment table,
an FMI version - and collects each case's recorded outputs and summary figures
(final position, peak velocity and acceleration per axis, time to finish,
errors) into one result table, with a summary plot.

    result = pmdfmu.sweep(pmdfmu.read_cases("cases.csv"))           # a local cluster, for this call
    result = pmdfmu.sweep(cases, scheduler=client)                   # a running cluster: its Client
    result = pmdfmu.sweep(cases, scheduler="tcp://10.0.0.5:8786")    # any Dask scheduler
    result = pmdfmu.sweep(cases, scheduler="serial")                 # in this process
    result.write("out/")            # summary.csv, one CSV per case, summary.png

Each Dask worker keeps its FMU instances (one per FMU file, FMI version and
thread running cases) and reuses them across cases, and across sweeps on the
same cluster: fmiReset, the case's parameters, a new initialization. A case
that fails (a bad script, a refused initialization, a run that raises) becomes
a failed row with its reason; the sweep goes on.

Cases go to the workers in batches of consecutive cases, a few batches per
worker thread (BATCHES_PER_THREAD): one task per case would cost the
scheduler more than a short case itself. A worker on this machine hands a
large recording back through a file in a folder the sweep made (/dev/shm where
there is one): through Dask it would cross a socket, copied on both sides, in CPU
time the workers need on a small machine (docs/performance.md, "Instances and
sweeps").
"""

from __future__ import annotations

import contextlib
import csv
import difflib
import io
import logging
import os
import secrets
import shutil
import signal
import tempfile
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import extras, files, profile, progress
from .chip import Chip, _identity, default_fmu

PARAMETERS = ("cycleTime", "memorySize", "loopback", "record.capacity")
# a case table's columns: the case's own, the FMU parameters, and pmdfmu verify's (which a sweep leaves to it)
COLUMNS = ("name", "script", "table", "fmi_version", "max_cycles", "cycles", *PARAMETERS, "golden", "assertions")
BATCHES_PER_THREAD = 4  # tasks per worker thread: enough to even out cases of unequal length
HANDOFF_BYTES = 1 << 20  # a recording this large, or larger, is handed back through a file (when it can be)
HANDOFF_PREFIX = "pmdfmu-sweep-"
TOKENLESS_AGE = 60  # s: a handoff folder this old with no token file is an orphan (_remove_orphans)  # the handoff folders: pmdfmu-sweep-<pid of the sweep>-<random>


@dataclass(frozen=True)
class Case:
    """One run: a script or a segment table (CSV), parameters, an FMI version."""

    name: str
    script: Optional[str] = None
    table: Optional[str] = None
    parameters: Tuple[Tuple[str, object], ...] = ()
    fmi_version: int = 2
    max_cycles: int = 1_000_000
    fmu: Optional[str] = None
    # FMU outputs recorded after the profile's own columns (pmdfmu verify asks for what its golden and
    # assertions need, e.g. axisN.eventStatus)
    record: Tuple[str, ...] = ()
    # a window: the first `cycles` cycles, whether or not the profile has ended by then (`pmdfmu run
    # --cycles`), instead of the whole profile up to max_cycles
    cycles: Optional[int] = None

    @property
    def limit(self) -> int:
        """The cycles the case's run may record: its window's, else max_cycles."""
        return self.cycles if self.cycles is not None else self.max_cycles


NOT_A_FILE_NAME = "not a file name for its files in the output folder (NAME.csv; summary.csv is the sweep's own)"


def is_file_name(name: str) -> bool:
    """Whether a case's name can name its files (NAME.csv, verify's NAME.actual.npz) inside a folder, beside
    the sweep's own summary.csv (compared as a case-insensitive file system would)."""
    return name not in ("", ".", "..") and name.lower() != "summary" and not any(c in name for c in "/\\\0")


def read_cases(path: Union[str, Path]) -> List[Case]:
    """A case table: columns name, script or table (paths relative to the
    table's folder), optional fmi_version, max_cycles or cycles (a window: the
    first N cycles, as `pmdfmu run --cycles N`), and any of the FMU parameters
    cycleTime, memorySize, loopback, record.capacity (blank: default), and pmdfmu
    verify's golden and assertions. ValueError with `file:line: reason` for a table
    that cannot be read or a case that cannot run as written: no case, a column of
    no such name (a misspelt one would be left out silently), a case with no script
    or table or both, a name given twice or one that is no file name (its recording
    is NAME.csv in the output folder), an FMI version other than 2 or 3, max_cycles
    or cycles below 1, both in one case, a script path holding a line feed (the FMU
    reads a `script` value holding one as the script's text)."""
    path = Path(path)
    try:
        cases = _cases(path, files.read_text(path))
    except csv.Error as e:
        raise ValueError(f"{path}: not a CSV table: {e}") from None
    if not cases:
        raise ValueError(f"{path}: no case (a header and one row per case)")
    first_line = {}
    for line, case in enumerate(cases, start=2):
        what = f"{path}:{line}: case {files.shown(case.name)}"
        if case.name in first_line:
            raise ValueError(f"{what}: the name of line {first_line[case.name]} again (names are unique)")
        first_line[case.name] = line
        if not is_file_name(case.name):
            raise ValueError(f"{what}: {NOT_A_FILE_NAME}")
        if bool(case.script) == bool(case.table):
            raise ValueError(f"{what}: a case names a script or a table")
        if case.fmi_version not in (2, 3):
            raise ValueError(f"{what}: fmi_version {case.fmi_version} is not 2 or 3")
        if case.max_cycles < 1:
            raise ValueError(f"{what}: max_cycles {case.max_cycles}: a run records at least 1 cycle")
        if case.cycles is not None and case.cycles < 1:
            raise ValueError(f"{what}: cycles {case.cycles}: a window records at least 1 cycle")
        if case.script and "\n" in case.script:
            raise ValueError(
                f"{what}: the script's path holds a line feed; the FMU reads such a `script` value "
                "as the script's text, so it cannot be given this file: rename it"
            )
    return cases


def _cases(path: Path, text: str) -> List[Case]:
    """read_cases' rows, each made a Case; ValueError naming the row for a value that is no number."""
    cases = []
    reader = csv.DictReader(io.StringIO(text, newline=""))
    for column in reader.fieldnames or ():
        if column not in COLUMNS:
            near = difflib.get_close_matches(column, COLUMNS, n=1, cutoff=0.6)
            raise ValueError(
                f"{path}:1: column {files.shown(column)} is not a case column"
                + (f" (did you mean {near[0]}?)" if near else f" ({', '.join(COLUMNS)})")
            )
    for n, row in enumerate(reader, start=2):

        def resolve(key, row=row):
            value = (row.get(key) or "").strip()
            return str(files.resolved(path.parent / value)) if value else None

        if not (row.get("name") or "").strip():
            raise ValueError(f"{path}:{n}: a case needs a name")
        window = (row.get("cycles") or "").strip()
        if window and (row.get("max_cycles") or "").strip():
            # as --max-cycles and --cycles: a limit on a whole run, or a window, never both
            raise ValueError(f"{path}:{n}: case {files.shown(row['name'].strip())}: max_cycles or cycles, not both")
        try:
            params = []
            for name in PARAMETERS:
                value = (row.get(name) or "").strip()
                if value:
                    params.append(
                        (
                            name,
                            value.lower() in ("1", "true", "yes")
                            if name == "loopback"
                            else float(value)
                            if name == "cycleTime"
                            else int(value, 0),
                        )
                    )
            cases.append(
                Case(
                    row["name"].strip(),
                    resolve("script"),
                    resolve("table"),
                    tuple(params),
                    _whole(row, "fmi_version", 2),
                    _whole(row, "max_cycles", 1_000_000),
                    cycles=_whole(row, "cycles", None),
                )
            )
        except ValueError as e:
            raise ValueError(f"{path}:{n}: {e}") from None
    return cases


def _whole(row: dict, column: str, default: Optional[int]) -> Optional[int]:
    """A column's whole number (default when blank); ValueError naming the column and the value."""
    value = (row.get(column) or "").strip()
    if not value:
        return default
    try:
        return int(value)
    except ValueError:
        raise ValueError(f"{column} {files.shown(value)} is not a whole number") from None


# ---- one case, in a worker -----------------------------------------------------

# this process's idle instances, reused across cases: by FMU file (its identity: a rewritten file is
# another FMU) and FMI version; a case takes one for itself (a worker may run cases in several threads)
_idle: Dict[Tuple[tuple, int], List[Chip]] = {}
_idle_lock = threading.Lock()


def _instance(case: Case, parameters: dict) -> Tuple[Tuple[tuple, int], Chip]:
    """An instance for the case, initialized with its parameters, and its key (to give it back)."""
    key = (_identity(Path(case.fmu) if case.fmu else default_fmu(case.fmi_version)), case.fmi_version)
    with _idle_lock:
        idle = _idle.get(key)
        chip = idle.pop() if idle else None
    if chip is None:
        chip = Chip(fmi_version=case.fmi_version, fmu=case.fmu, log_categories=["warnings"], **parameters)
    else:
        try:
            chip.reinitialize(**parameters)
        except Exception:
            _give_back(key, chip)
            raise
    return key, chip


def _give_back(key: Tuple[tuple, int], chip: Chip) -> None:
    with _idle_lock:
        _idle.setdefault(key, []).append(chip)


def _summary(case: Case, rec: np.ndarray, axes: Sequence[int], messages, ended: bool) -> dict:
    row = {
        "name": case.name,
        "status": "ok",
        "reason": "",
        "cycles": len(rec),
        "ended": "yes" if ended else "no",  # no: max_cycles cut the run short, or a window (profile.profile_ended)
        "warnings": sum(m.status == "Warning" for m in messages),
    }
    for a in range(4):
        n = a + 1
        if a in axes and len(rec):
            row[f"axis{n}.finalPosition"] = int(rec[f"axis{n}.commandedPosition"][-1])
            row[f"axis{n}.peakVelocity"] = float(np.abs(rec[f"axis{n}.velocity"]).max())
            row[f"axis{n}.peakAcceleration"] = float(np.abs(rec[f"axis{n}.acceleration"]).max())
        else:
            row[f"axis{n}.finalPosition"] = row[f"axis{n}.peakVelocity"] = row[f"axis{n}.peakAcceleration"] = ""
    return row


def run_case(case: Case) -> Tuple[dict, Optional[np.ndarray]]:
    """Runs one case; never raises: a failure is a row with status "failed"."""
    parameters = dict(case.parameters)
    try:
        if bool(case.script) == bool(case.table):
            raise ValueError("a case names a script or a table")
        parameters["script"] = Path(case.script) if case.script else ""  # a file, never text
        key, chip = _instance(case, parameters)
        try:
            if case.script:
                axes = profile.script_axes(chip)
                rec = profile.run_script(chip, axes, max_cycles=case.limit, record=case.record)
                ended = profile.profile_ended(rec, axes, chip.get("script.lastCycle"))
            else:
                tables = profile.read_segment_table(Path(case.table))
                axes = sorted(tables)
                rec = profile.run_segment_table(chip, tables, max_cycles=case.limit, record=case.record)
                ended = profile.profile_ended(rec, axes)
            return _summary(case, rec, axes, chip.messages, ended), rec
        finally:
            _give_back(key, chip)
    except Exception as e:  # the sweep goes on: the row says why
        reason = " ".join(str(e).split()) or type(e).__name__
        row = {"name": case.name, "status": "failed", "reason": reason, "cycles": 0, "ended": "", "warnings": 0}
        row.update(
            {f"axis{n}.{q}": "" for n in range(1, 5) for q in ("finalPosition", "peakVelocity", "peakAcceleration")}
        )
        return row, None


# ---- the sweep --------------------------------------------------------------------


def written_files(cases: Sequence[Case], out: Union[str, Path]) -> List[Path]:
    """What SweepResult.write(out) writes: summary.csv, summary.png, NAME.csv per case that runs."""
    out = Path(out)
    return [out / "summary.csv", out / "summary.png"] + [out / f"{c.name}.csv" for c in cases]


def case_inputs(cases: Sequence[Case]) -> List[Path]:
    """What the cases read: their scripts, tables and FMUs, and the segment tables their scripts load (the
    FMU's answer, pack.tables_loaded: each script compiled once, as a sweep's cases mostly share one)."""
    from .pack import tables_loaded

    inputs = [Path(p) for p in [*(c.script or c.table for c in cases), *(c.fmu for c in cases)] if p]
    for script, version, fmu in dict.fromkeys((c.script, c.fmi_version, c.fmu) for c in cases if c.script):
        inputs += tables_loaded(Path(script), version, Path(fmu) if fmu else None)
    return inputs


def refuse_writing_over_inputs(cases: Sequence[Case], out: Union[str, Path], inputs: Sequence[Path] = ()) -> None:
    """ValueError before anything runs if a file the sweep writes to `out` is one of its inputs (the case
    table, case_inputs: asked only when a file the sweep writes exists already): `--out` the table's folder
    and a case named after a table, say."""
    if not any(written.exists() for written in written_files(cases, out)):
        return
    inputs_by_file = {}  # each file stat'ed once: by its device and inode, as samefile compares them
    for source in [*(Path(p) for p in inputs), *case_inputs(cases)]:
        try:
            st = source.stat()
        except OSError:
            continue
        inputs_by_file.setdefault((st.st_dev, st.st_ino), source)
    for written in written_files(cases, out):
        try:
            st = written.stat()
        except OSError:
            continue
        source = inputs_by_file.get((st.st_dev, st.st_ino))
        if source is not None:
            raise ValueError(f"{written}: the sweep would write over its input {source}: give another --out")


@dataclass
class SweepResult:
    rows: List[dict]
    recordings: Dict[str, np.ndarray] = field(default_factory=dict)
    cycle_times: Dict[str, float] = field(default_factory=dict)  # each case's chip cycle (s), for the plot

    def write(self, out: Union[str, Path]) -> None:
        """summary.csv, CASE.csv per successful case, summary.png."""
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        with files.replaced(out / "summary.csv", text=True) as f:
            w = csv.DictWriter(f, fieldnames=list(self.rows[0]))
            w.writeheader()
            w.writerows(self.rows)
        for name, rec in self.recordings.items():
            profile.write_csv(out / f"{name}.csv", rec)
        self.plot(out / "summary.png")

    def plot(self, path: Union[str, Path]) -> None:
        plt = extras.pyplot("SweepResult.plot")
        ok = [r for r in self.rows if r["status"] == "ok"]
        fig, (top, bottom) = plt.subplots(2, 1, figsize=(10, 8))
        # cases that coincide stay apart: each its own dash and marker, drawn wider first, so a line on
        # top of another leaves the one below visible at its edges
        styles = [(d, m) for m in ("o", "s", "^", "v", "D", "x") for d in ("-", "--", "-.", ":")]
        # seconds when the cases' cycle times differ (the same cycle is not the same time), else cycles
        times = {self.cycle_times.get(r["name"]) for r in ok}
        seconds = len(times) > 1 and None not in times
        for k, r in enumerate(ok):
            rec = self.recordings[r["name"]]
            first = next(n for n in rec.dtype.names if n.endswith(".position"))  # the case's first axis
            x = rec["cycle"] - rec["cycle"][0]
            if seconds:
                x = x * self.cycle_times[r["name"]]
            dash, marker = styles[k % len(styles)]
            top.plot(
                x,
                rec[first],
                linestyle=dash,
                marker=marker,
                markevery=max(len(x) // 12, 1),
                markersize=5,
                linewidth=max(3.0 - 0.4 * k, 1.0),
                alpha=0.85,
                label=f"{r['name']} ({first.split('.')[0]})",
            )
        top.set_xlabel("time [s]" if seconds else "cycles")
        top.set_ylabel("position [counts]")
        top.legend(fontsize="small")
        names = [r["name"] for r in self.rows]
        peaks = [max((r[f"axis{n}.peakVelocity"] or 0) for n in range(1, 5)) for r in self.rows]
        colors = ["tab:blue" if r["status"] == "ok" else "tab:red" for r in self.rows]
        bottom.bar(names, peaks, color=colors)
        for x, r in enumerate(self.rows):
            if r["status"] != "ok":
                bottom.annotate("failed", (x, 0), ha="center", va="bottom", color="tab:red")
        bottom.set_ylabel("peak velocity [counts/s] (red: failed)")
        fig.suptitle(f"pmdfmu sweep: {len(ok)} of {len(self.rows)} cases ran")
        fig.tight_layout()
        with files.replaced(path) as f:
            fig.savefig(f, format=Path(path).suffix[1:] or "png", dpi=100)
        plt.close(fig)


@dataclass(frozen=True)
class _Handed:
    """A recording a worker wrote to the sweep's handoff folder, its raw bytes, instead of returning it."""

    path: str
    dtype: np.dtype
    rows: int


def _handoff_folder(handoff: Optional[Tuple[str, str]]) -> Optional[str]:
    """The sweep's handoff folder if this process sees it (the same machine): its token file holds
    the token the sweep passed."""
    if handoff is None:
        return None
    folder, token = handoff
    try:
        return folder if Path(folder, "token").read_text() == token else None
    except OSError:
        return None


def _hand(folder: Optional[str], rec: Optional[np.ndarray]):
    """rec, or where it was written for the sweep's process to read (a large one, when it can be)."""
    if folder is None or rec is None or rec.nbytes < HANDOFF_BYTES:
        return rec
    path = os.path.join(folder, uuid.uuid4().hex + ".rec")
    try:
        np.ascontiguousarray(rec).tofile(path)
    except OSError:  # e.g. the folder is full: through Dask then
        try:
            os.unlink(path)
        except OSError:
            pass
        return rec
    return _Handed(path, rec.dtype, len(rec))


def _received(result: Tuple[dict, object], folder: str) -> Tuple[dict, Optional[np.ndarray]]:
    """A result as the worker made it: a handed recording mapped (copy-on-write, no copy made: reading
    it back would cost this process, on a small machine the workers' CPU) and its file unlinked; its
    pages are freed with the array. Only a file of the sweep's own folder is taken."""
    row, rec = result
    if isinstance(rec, _Handed):
        if os.path.dirname(rec.path) != folder or not os.path.basename(rec.path).endswith(".rec"):
            raise RuntimeError(f"a worker handed back {rec.path!r}, not a recording of the sweep's folder {folder}")
        mapped = np.memmap(rec.path, dtype=rec.dtype, mode="c", shape=(rec.rows,))
        os.unlink(rec.path)
        rec = mapped.view(np.ndarray)
    return row, rec


def run_cases(cases: Sequence[Case], handoff: Optional[Tuple[str, str]] = None) -> List[Tuple[dict, object]]:
    """run_case for each case, in order: one Dask task of a sweep. handoff: the sweep's (folder,
    token) for large recordings (_hand)."""
    folder = _handoff_folder(handoff)
    results = []
    # a bar in this process only (scheduler="serial", no handoff): never a worker's
    with progress.bar("cases", total=len(cases), unit="cases", enabled=handoff is None) as bar:
        for case in cases:
            row, rec = run_case(case)
            results.append((row, _hand(folder, rec)))
            bar.update(1)
    return results


def _batches(cases: Sequence[Case], threads: int) -> List[List[Case]]:
    """The cases in consecutive batches, at most BATCHES_PER_THREAD per thread, of sizes differing by
    one at most (8 cases on 2 threads: 8 batches of one; 64: 8 of 8)."""
    count = max(1, min(len(cases), BATCHES_PER_THREAD * threads))
    return [list(cases[i * len(cases) // count : (i + 1) * len(cases) // count]) for i in range(count)]


def _on(client, cases: Sequence[Case]) -> List[Tuple[dict, Optional[np.ndarray]]]:
    """The cases' results, run on the client's cluster; each batch's taken as soon as it is done."""
    as_completed = extras.require("distributed", "sweep", "a sweep on a cluster").as_completed
    threads = sum(client.nthreads().values()) or 1
    root = handoff_root()
    _remove_orphans(root)
    folder = tempfile.mkdtemp(prefix=f"{HANDOFF_PREFIX}{os.getpid()}-", dir=root)
    futures: list = []
    lock = None
    try:
        token = f"{os.getpid()}-{secrets.token_hex(16)}"
        lock = _hold(Path(folder, "token"), token)
        futures = client.map(run_cases, _batches(cases, threads), handoff=(folder, token), pure=False)
        where = {future.key: i for i, future in enumerate(futures)}
        batches: List[list] = [[] for _ in futures]
        with progress.bar("cases", total=len(cases), unit="cases") as bar:
            for future, batch in as_completed(futures, loop=client.loop, with_results=True):
                batches[where[future.key]] = [_received(result, folder) for result in batch]
                bar.update(len(batch))
        return [result for batch in batches for result in batch]
    except BaseException:
        client.cancel(futures)  # no worker goes on writing into the folder removed below
        raise
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        if lock is not None:
            os.close(lock)


def _hold(path: Path, token: str) -> Optional[int]:
    """The sweep's token file, made new and locked before the token is written into it, so that another
    sweep's _remove_orphans never finds it unlocked while this sweep runs; the lock lasts as long as the
    returned descriptor stays open. Without flock (not POSIX): written, no lock."""
    fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL, 0o600)
    if os.name == "posix":
        import fcntl

        fcntl.flock(fd, fcntl.LOCK_EX)
    os.write(fd, token.encode())
    if os.name != "posix":
        os.close(fd)
        return None
    return fd


def handoff_root() -> str:
    """Where sweeps make their handoff folders: /dev/shm where there is one (RAM, no disk), else the
    temporary folder. A sweep killed outright leaves its folder there; the next sweep removes it, or by
    hand when no sweep runs: rm -rf /dev/shm/pmdfmu-sweep-*."""
    shm = "/dev/shm"
    return shm if os.path.isdir(shm) and os.access(shm, os.W_OK) else tempfile.gettempdir()


def _remove_orphans(root: str) -> None:
    """Removes the handoff folders of sweeps that are gone (killed: SIGKILL runs no cleanup), which would
    hold their RAM in /dev/shm until a reboot. A running sweep holds a lock (flock) on its folder's token
    file for as long as it runs; the kernel drops it when the process ends, however it ends. So a folder
    whose token file this process can lock is an orphan, whatever process ids mean on this machine (a
    /dev/shm shared across containers). A folder of another user, or a link, is left alone. POSIX only."""
    if os.name != "posix":
        return
    import fcntl

    try:
        entries = list(os.scandir(root))
    except OSError:
        return
    for entry in entries:
        if not entry.name.startswith(HANDOFF_PREFIX):
            continue
        status = None
        try:
            status = entry.stat(follow_symlinks=False)
            if status.st_uid != os.getuid() or not entry.is_dir(follow_symlinks=False):
                continue
            fd = os.open(os.path.join(entry.path, "token"), os.O_RDONLY | os.O_NOFOLLOW)
        except FileNotFoundError:
            # no token: a sweep killed between making its folder and its token (microseconds apart), once
            # the folder is older than any sweep takes to get there
            if status is not None and time.time() - status.st_mtime > TOKENLESS_AGE:
                shutil.rmtree(entry.path, ignore_errors=True)
            continue
        except OSError:
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:  # held: its sweep runs
            continue
        finally:
            os.close(fd)
        shutil.rmtree(entry.path, ignore_errors=True)


def _current_client(address: str):
    """This process's default distributed.Client if it is connected to the scheduler at address
    (e.g. one the user made with Client(address)), else None."""
    Client = extras.require("distributed", "sweep", "a sweep on a scheduler's address").Client
    from distributed.comm import resolve_address

    try:
        current = Client.current()
    except ValueError:  # no client in this process
        return None
    return current if current.status == "running" and current.scheduler.address == resolve_address(address) else None


@contextlib.contextmanager
def _interrupt_deferred():
    """A Ctrl-C while a local cluster starts is delivered once it has started, so that the `with` that closes it
    holds it: interrupted half-way, its workers would be left to Dask's exit handler, which fails on them
    with a traceback (distributed's close_clusters: "AssertionError: Status.init"). Main thread only (where
    Python's signal handlers run); elsewhere nothing is deferred."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught = []
    previous = signal.signal(signal.SIGINT, lambda number, frame: caught.append(number))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
    if caught:  # delivered again, to the handler there was (Python's: KeyboardInterrupt)
        signal.raise_signal(signal.SIGINT)


def sweep(cases: Sequence[Case], scheduler=None, workers: int = 2) -> SweepResult:
    """Runs the cases; scheduler says where:

    - None: a local cluster of `workers` processes, started for this call and closed after it (where
      progress is shown, its Dask dashboard too, the link printed with the bar: pmdfmu.progress);
    - "serial": in this process;
    - a distributed.Client (of a LocalCluster, SLURMCluster, ...): its cluster, reused as it is
      (the client stays open; its workers keep their FMU instances from sweep to sweep);
    - a scheduler address ("tcp://10.0.0.5:8786"): that cluster, through this process's default
      Client if it is connected there, else through a client opened for this call.

    A running cluster saves each call the cluster's start (seconds) and the workers' first FMU
    instance: pass its Client (or its address) for repeated sweeps."""
    names = [c.name for c in cases]
    if len(set(names)) != len(names):
        raise ValueError("case names must be unique")  # read_cases names the line of a table's
    for name in names:
        if not is_file_name(name):
            raise ValueError(f"case {files.shown(name)}: {NOT_A_FILE_NAME}")
    if isinstance(scheduler, str) and scheduler == "serial":
        results = run_cases(cases)
    elif scheduler is None:
        distributed = extras.require("distributed", "sweep", "a sweep on a local cluster (scheduler=None)")
        Client, LocalCluster = distributed.Client, distributed.LocalCluster
        # Dask's dashboard when progress is shown (its link goes with the bar); where nobody sees the link (a
        # pipe, --quiet) none, and no bokeh loaded. The scheduler's web server (the dashboard's, or its bare
        # routes: Dask starts one either way, dashboard_address=None meaning port 8787) on a free port of
        # this machine only: never "Port 8787 is already in use" beside another cluster
        dashboard = progress.wanted()
        with _interrupt_deferred():
            # the cluster's own warnings (a task cancelled by Ctrl-C, say) are not the user's: errors only
            cluster = LocalCluster(
                n_workers=workers,
                threads_per_worker=1,
                processes=True,
                dashboard_address="127.0.0.1:0",
                scheduler_kwargs={"dashboard": dashboard},
                silence_logs=logging.ERROR,
            )
        with cluster, Client(cluster) as client:
            if dashboard:
                progress.note(f"sweep: Dask dashboard at {client.dashboard_link}")
            results = _on(client, cases)
    elif isinstance(scheduler, str):
        current = _current_client(scheduler)
        if current is not None:
            results = _on(current, cases)
        else:
            Client = extras.require("distributed", "sweep", "a sweep on a scheduler's address").Client
            with Client(scheduler, set_as_default=False) as client:
                results = _on(client, cases)
    else:
        results = _on(scheduler, cases)
    return SweepResult(
        [row for row, _ in results],
        {row["name"]: rec for row, rec in results if rec is not None},
        {c.name: float(dict(c.parameters).get("cycleTime", profile.DEFAULT_CYCLE_TIME)) for c in cases},
    )
