"""Generic study runner on Dask: tasks with stable keys -> a function -> one row each, appended
to the study's results table as they finish (pipeline/study/results_table.py), so an interrupted
study resumes where it stopped and never loses or repeats a finished case.

* ``study_client(scheduler, workers)``: a local cluster (one single-threaded worker process per
  core, or ``workers``) or a client of the Dask scheduler at ``scheduler`` (tcp://host:port;
  its workers need this repository on their PYTHONPATH and the same venv).
* ``run_tasks(tasks, fn, table, client, contexts)``: submits the tasks whose key is not yet in
  the table, each as one Dask task ``fn(context, params)`` with its context (the per-position
  data, scattered once to every worker, so each worker process holds it once), and appends a row
  per finished task: the key, the inputs hash, what fn returned, the task's own wall time and the
  worker.  Progress with pipeline.progress (a tqdm bar on a terminal only).  A failing task stops the study (the finished rows
  stay) with the case named.
"""
from __future__ import annotations

import contextlib
import logging
import os
import socket
import time
from dataclasses import dataclass
from typing import Any, Callable, Iterator, Mapping

from pipeline.study.results_table import INPUTS, KEY, ResultsTable
from pipeline.progress import progress as progress_bar

log = logging.getLogger("pipeline.study")

WALL, WORKER = "wall_s", "worker"


@dataclass(frozen=True)
class Task:
    """One case of a study: ``key`` its stable name, ``inputs`` the hash of everything its result
    depends on, ``context`` the name of the shared context it runs with, ``params`` its own
    parameters: a typed record of pipeline/study/tasks.py (picklable, frozen)."""
    key: str
    inputs: str
    context: str
    params: Any


@dataclass
class RunStats:
    total: int
    done_before: int
    submitted: list
    wall: float = 0.0
    workers: int = 0


def local_cluster(workers: int | None = None):
    """A started local cluster of ``workers`` (default: the machine's cores) single-threaded
    worker processes (close it, or enter it in ``study_client``, which closes it)."""
    from distributed import LocalCluster  # lazy: brings in distributed

    logging.getLogger("distributed").setLevel(logging.WARNING)    # the scheduler runs in this process
    n = workers or os.cpu_count() or 1
    return LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                        silence_logs=logging.ERROR, env={"OMP_NUM_THREADS": "1"})


@contextlib.contextmanager
def study_client(scheduler: str | None = None, workers: int | None = None, cluster=None) -> Iterator[Any]:
    """A dask.distributed Client: of the scheduler at ``scheduler``, else of ``cluster`` (one of
    ``local_cluster``, e.g. started ahead in another thread) or a new local cluster; the local
    cluster is closed on exit."""
    from distributed import Client  # lazy: brings in distributed

    logging.getLogger("distributed").setLevel(logging.WARNING)
    if scheduler:
        with Client(scheduler) as client:
            yield client
        return
    with (cluster if cluster is not None else local_cluster(workers)) as cl, Client(cl) as client:
        yield client


def _run_one(fn: Callable, context: Any, params: Any) -> dict:
    """Worker side: fn(context, params) with its wall time and the worker's identity."""
    t0 = time.perf_counter()
    row = dict(fn(context, params))
    row[WALL] = time.perf_counter() - t0
    row[WORKER] = f"{socket.gethostname()}:{os.getpid()}"
    return row


def pending(tasks: list[Task], table: ResultsTable) -> list[Task]:
    """The tasks without a row (of the same inputs) in the table (``table.open`` first)."""
    return [t for t in tasks if t.key not in table.rows or table.rows[t.key][INPUTS] != t.inputs]


def run_tasks(tasks: list[Task], fn: Callable, table: ResultsTable, client, contexts: Mapping[str, Any], *,
              desc: str = "study", progress: bool = True) -> RunStats:
    """Run the tasks not yet in ``table`` on ``client`` and append their rows as they finish.
    ``table`` must have been opened with the tasks' inputs (stale rows dropped).  ``contexts``:
    name -> object, scattered to all workers once (only those the pending tasks use)."""
    from distributed import as_completed  # lazy: brings in distributed


    keys = [t.key for t in tasks]
    if len(set(keys)) != len(keys):
        raise ValueError("study tasks must have unique keys")
    todo = pending(tasks, table)
    stats = RunStats(total=len(tasks), done_before=len(tasks) - len(todo), submitted=[t.key for t in todo])
    if not todo:
        return stats
    t0 = time.perf_counter()
    stats.workers = len(client.scheduler_info().get("workers", {}))
    shared = {name: client.scatter(contexts[name], broadcast=True, hash=False)
              for name in sorted({t.context for t in todo})}
    futures = {}
    for t in todo:
        f = client.submit(_run_one, fn, shared[t.context], t.params, key=f"{desc}-{t.key}-{t.inputs}",
                          pure=False, retries=1)
        futures[f] = t
    bar = progress_bar(total=len(tasks), initial=stats.done_before, unit="case", desc=desc, enabled=progress,
                       smoothing=0.1)
    try:
        for f in as_completed(futures):
            t = futures.pop(f)
            try:
                row = f.result()
            except Exception as e:
                raise RuntimeError(f"{desc}: case {t.key} failed: {type(e).__name__}: {e}") from e
            table.append({KEY: t.key, INPUTS: t.inputs, **row})
            bar.update(1)
            bar.set_postfix_str(f"{row[WALL]:.2f} s/case", refresh=False)
    finally:
        bar.close()
        for f in futures:
            f.cancel()
    stats.wall = time.perf_counter() - t0
    return stats
