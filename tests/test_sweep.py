# SPDX-License-Identifier: BSD-2-Clause
"""Sweeps on Dask: a 2-worker local cluster gives exactly the serial
run, row for row; failing cases are rows with their reasons; a local cluster takes a free port."""

import socket
import warnings
from pathlib import Path

import numpy as np
import pytest

import pmdfmu
from pmdfmu.cli import main

pytestmark = pytest.mark.slow  # tests/README.md: ./dev test -m "not slow" leaves them out

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_a_two_worker_local_cluster_equals_the_serial_run_row_for_row(cases, serial):
    parallel = pmdfmu.sweep(cases, workers=2)
    assert parallel.rows == serial.rows
    assert set(parallel.recordings) == set(serial.recordings)
    for name, rec in serial.recordings.items():
        assert np.array_equal(parallel.recordings[name], rec), name


def test_figures_and_a_failed_case(serial):
    rows = {r["name"]: r for r in serial.rows}
    assert rows["script-fmi2"] == {**rows["script-fmi3"], "name": "script-fmi2"}  # FMI 2 = FMI 3
    assert rows["script-fmi2"]["axis1.finalPosition"] == 750 and rows["square"]["axis2.finalPosition"] == 0
    assert rows["script-slow-clock"]["axis1.peakVelocity"] == pytest.approx(
        rows["script-fmi2"]["axis1.peakVelocity"] / 2
    )
    assert rows["square"]["cycles"] == rows["square-small-memory"]["cycles"] == 2001
    broken = rows["broken-script"]
    assert broken["status"] == "failed" and "missing.script: cannot open the script" in broken["reason"]
    assert "broken-script" not in serial.recordings


def test_any_scheduler_address(cases):
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        result = pmdfmu.sweep(cases[:2], scheduler=cluster.scheduler_address)
    assert [r["status"] for r in result.rows] == ["ok", "ok"]


def test_a_local_cluster_takes_a_free_port_beside_another_clusters_8787(cases):
    """Dask's web server listens on 8787 unless told otherwise, and warns when it is taken; a sweep's asks for a
    free port."""
    taken = socket.socket()
    try:
        taken.bind(("127.0.0.1", 8787))
        taken.listen()
    except OSError:  # another cluster has it: the case in point
        pass
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            result = pmdfmu.sweep(cases[:1], workers=1)
    finally:
        taken.close()
    assert result.rows[0]["status"] == "ok"


def test_pmdfmu_sweep_writes_the_table_the_recordings_and_the_plot(tmp_path, capsys):
    assert main(["sweep", str(EXAMPLES / "cases.csv"), "--out", str(tmp_path), "--scheduler", "serial"]) == 0
    assert (tmp_path / "summary.csv").read_text().splitlines()[0].startswith("name,status,reason,cycles")
    assert (tmp_path / "summary.png").stat().st_size > 10_000 and (tmp_path / "square.csv").exists()
    assert "5 of 6 cases ran" in capsys.readouterr().out
