"""A study on an existing Dask cluster (`--scheduler tcp://...`): the cluster here is a local one
started by the test (its workers are not the runner's children), the study runs through the
CLI in another process and fills the same table as with its own local cluster."""
import csv
import os
import subprocess
import sys

from tests.study.conftest import ROOT

STUDY = """name = "sched"
kind = "map"
cases = ["default"]
[grid]
gamma_y_first = -0.01
gamma_y_last = -0.02
gamma_y_step = 0.01
mu_first = 0.3
mu_last = 0.4
mu_step = 0.1
[quick]
gamma_y_step = 0.01
mu_step = 0.1
[simulation]
duration = 0.3
"""


def _rows(path):
    with open(path, newline="") as fh:
        return sorted(tuple((k, v) for k, v in r.items() if k not in ("wall_s", "worker")) for r in csv.DictReader(fh))


def test_study_on_an_existing_scheduler(tmp_path, default_case):
    from distributed import Client, LocalCluster

    (tmp_path / "studies").mkdir()
    (tmp_path / "studies" / "sched.toml").write_text(STUDY)
    env = dict(os.environ, SQUEAL_STUDY_DIR=str(tmp_path / "studies"), OMP_NUM_THREADS="1")
    cmd = [sys.executable, "-m", "pipeline", "study", "--study", "sched", "--no-progress"]
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None,
                      scheduler_kwargs={"host": "127.0.0.1"}) as cluster, Client(cluster) as client:
        addr = cluster.scheduler_address
        assert addr.startswith("tcp://")
        r = subprocess.run(cmd + ["--scheduler", addr, "--out", str(tmp_path / "remote")], cwd=ROOT, env=env,
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        assert f"dask: {addr} with 1 workers" in r.stderr
        pids = {str(p) for p in client.run(os.getpid).values()}
    with open(tmp_path / "remote" / "table.csv", newline="") as fh:
        used = {row["worker"].split(":")[-1] for row in csv.DictReader(fh)}
    assert used == pids                                                # every case on the cluster's worker
    r = subprocess.run(cmd + ["--workers", "1", "--out", str(tmp_path / "local")], cwd=ROOT, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert _rows(tmp_path / "remote" / "table.csv") == _rows(tmp_path / "local" / "table.csv")
