"""The line study on a multi-process Dask cluster started the standard way: ``dask scheduler`` and two
``dask worker`` processes over tcp on free ports (subprocesses of the test, torn down after), the study
run through the CLI with ``--scheduler``; its rows equal those of a run on the study's own local
cluster (issue 27, "Scale")."""
import csv
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

from tests.study.conftest import ROOT
from tests.study.test_line import _write

DASK = Path(sys.executable).with_name("dask")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _rows(path):
    with open(path, newline="") as fh:
        return sorted(tuple((k, v) for k, v in r.items() if k not in ("wall_s", "worker")) for r in csv.DictReader(fh))


def _stop(procs):
    for p in procs:
        if p.poll() is None:
            p.send_signal(signal.SIGTERM)
    for p in procs:
        try:
            p.wait(timeout=20)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


def test_line_on_dask_scheduler_and_workers(tmp_path):
    name = "t_line_cluster"
    env = _write(tmp_path, name, "A,0,300,102,100,62.6,c20_metro,dry\nB,500,500,77,160,70,c20_metro,wet\n")
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "dask.log", "w")
    procs = [subprocess.Popen([str(DASK), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"], cwd=ROOT, env=env, stdout=log, stderr=subprocess.STDOUT)]
    try:
        for _ in range(2):
            procs.append(subprocess.Popen([str(DASK), "worker", addr, "--nthreads", "1", "--nworkers", "1",
                                           "--no-dashboard", "--host", "127.0.0.1"], cwd=ROOT, env=env, stdout=log,
                                          stderr=subprocess.STDOUT))
        from distributed import Client

        with Client(addr, timeout=60) as client:
            t0 = time.time()
            while len(client.scheduler_info()["workers"]) < 2 and time.time() - t0 < 60:
                time.sleep(0.5)
            assert len(client.scheduler_info()["workers"]) == 2, (tmp_path / "dask.log").read_text()[-2000:]
            pids = {str(p) for p in client.run(os.getpid).values()}
        cmd = [sys.executable, "-m", "pipeline", "study", "--study", name, "--no-progress"]
        r = subprocess.run(cmd + ["--scheduler", addr, "--out", str(tmp_path / "remote")], cwd=ROOT, env=env,
                           capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr[-3000:]
        assert f"dask: {addr} with 2 workers" in r.stderr
    finally:
        _stop(procs[::-1])
        log.close()
    with open(tmp_path / "remote" / "table.csv", newline="") as fh:
        used = {row["worker"].split(":")[-1] for row in csv.DictReader(fh)}
    assert used <= pids and used                                     # every row on the cluster's workers
    r = subprocess.run(cmd + ["--workers", "1", "--out", str(tmp_path / "local")], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr[-3000:]
    remote, local = _rows(tmp_path / "remote" / "table.csv"), _rows(tmp_path / "local" / "table.csv")
    assert len(remote) == 2 and remote == local
    assert (tmp_path / "remote" / "line.csv").read_text() == (tmp_path / "local" / "line.csv").read_text()
