"""The study runner on a local Dask cluster, through the CLI: a small creepage/friction map is
killed (SIGKILL of the runner) after some rows are written, a torn line is appended as if the
kill had hit a write, and the study is restarted: the table equals that of an uninterrupted run
(every column but the wall time and the worker), every case appears once, the restart ran
exactly the missing cases, and the killed run's worker processes did not outlive it."""
import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
STUDY = """\
name = "tiny"
kind = "map"
cases = ["default"]
[grid]
gamma_y_first = -0.004
gamma_y_last = -0.034
gamma_y_step = 0.01
mu_first = 0.2
mu_last = 0.6
mu_step = 0.2
[quick]
gamma_y_step = 0.03
mu_step = 0.4
[simulation]
duration = 2.0
early_stop = false
"""
N = 12                        # 4 creepages x 3 friction coefficients
VOLATILE = ("wall_s", "worker")


def _cmd(out):
    return [sys.executable, "-m", "pipeline", "study", "--study", "tiny", "--workers", "2", "--out", str(out),
            "--no-progress"]


def _rows(path):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    return rows


def _stable(rows):
    return sorted(tuple((k, v) for k, v in r.items() if k not in VOLATILE) for r in rows)


def _children(pid):
    out = []
    for p in Path("/proc").iterdir():
        if p.name.isdigit():
            try:
                if int((p / "stat").read_text().split(") ", 1)[1].split()[1]) == pid:
                    out.append(int(p.name))
            except (OSError, IndexError, ValueError):
                pass
    return out


def _alive(pid):
    try:
        state = (Path("/proc") / str(pid) / "stat").read_text().split(") ", 1)[1].split()[0]
        return state != "Z"
    except OSError:
        return False


@pytest.fixture()
def env(tmp_path, default_case):
    (tmp_path / "studies").mkdir()
    (tmp_path / "studies" / "tiny.toml").write_text(STUDY)
    return dict(os.environ, SQUEAL_STUDY_DIR=str(tmp_path / "studies"), OMP_NUM_THREADS="1")


def test_killed_study_resumes_to_the_uninterrupted_table(tmp_path, env):
    ref, out = tmp_path / "ref", tmp_path / "killed"
    subprocess.run(_cmd(ref), cwd=ROOT, env=env, check=True, capture_output=True)
    reference = _rows(ref / "table.csv")
    assert len(reference) == N and len({r["key"] for r in reference}) == N

    proc = subprocess.Popen(_cmd(out), cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    table = out / "table.csv"
    children = set()
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        children |= set(_children(proc.pid))
        if table.exists() and table.read_bytes().count(b"\n") - 1 >= 3:
            break
        assert proc.poll() is None, "the study ended before it could be killed"
        time.sleep(0.02)
    else:
        proc.kill()
        pytest.fail("no rows within 120 s")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    done = table.read_bytes().count(b"\n") - 1
    assert 3 <= done < N, f"{done} rows at the kill: the test needs an interrupted study"
    # the Dask worker processes go with the runner (checked, then cleaned up by pid if not)
    t0 = time.monotonic()
    while any(_alive(c) for c in children) and time.monotonic() - t0 < 15:
        time.sleep(0.1)
    left = [c for c in children if _alive(c)]
    for c in left:
        os.kill(c, signal.SIGKILL)
    assert not left, f"worker processes {left} outlived the killed study"
    # a kill in the middle of a write leaves a torn line: simulate one
    last = table.read_bytes().rstrip(b"\n").rsplit(b"\n", 1)[1]
    with open(table, "ab") as fh:
        fh.write(b"default|gamma_y=-0.03400|mu=0.600" + last[last.index(b","):][:25])

    r = subprocess.run(_cmd(out), cwd=ROOT, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "dropped 1 torn" in r.stderr
    rows = _rows(table)
    keys = [x["key"] for x in rows]
    assert len(keys) == N and len(set(keys)) == N                     # complete, no case twice
    assert _stable(rows) == _stable(reference)                        # the same numbers, bit for bit
    run = [json.loads(line) for line in (out / "runs.jsonl").read_text().splitlines()]
    assert len(run) == 1                                              # the killed run never finished
    assert run[-1]["done_before"] == done and run[-1]["submitted"] == N - done
    # a finished study starts no cluster and runs nothing
    again = subprocess.run(_cmd(out), cwd=ROOT, env=env, capture_output=True, text=True)
    assert again.returncode == 0 and "dask:" not in again.stderr
    last = json.loads((out / "runs.jsonl").read_text().splitlines()[-1])
    assert last["submitted"] == 0 and last["done_before"] == N
    assert (out / "summary.md").exists() and (out / "map_default.png").exists() and (out / "map.csv").exists()
