"""Study stage (SPEC 7): ``python -m pipeline study --study NAME [--quick] [--scheduler ADDR]
[--workers N] [--out DIR]``.

A study is defined by pipeline/studies/<NAME>.toml; its ``kind`` names a module of pipeline/study/kinds/
(its schema ``SCHEMA`` and its ``run``): ``map`` (creepage/friction map), ``damping`` (wheel modal damping),
``contact`` (contact-model validation) or ``line`` (a line of curves, each curve's verdict screen first and the
noise-mapping rules beside it).  The cases run on Dask (pipeline/study/runner.py),
their rows are appended to the study's table as they finish; rerunning the command resumes an
interrupted study and only renders the outputs of a finished one.

Outputs in build/studies/<NAME>/ (``<NAME>-quick`` with --quick): the table(s) (CSV), PNG
figures, summary.md and runs.jsonl (one line per run: cases in total, already done, submitted,
wall time, workers).
"""
from __future__ import annotations

import contextlib
import fcntl
import json
import logging
import os
import shutil
import threading
import time
from pathlib import Path

from pipeline.store import artifacts, paths
from pipeline.config.loader import ConfigError
from pipeline.study.kinds import kind_module, load_study
from pipeline.study.runner import local_cluster, study_client

log = logging.getLogger("pipeline.study")


class LazyClient:
    """A Dask client made on first use (a finished study starts no cluster), or started ahead by ``start``."""

    def __init__(self, scheduler: str | None, workers: int | None):
        self.scheduler, self.workers = scheduler, workers
        self._stack = contextlib.ExitStack()
        self._client = None
        self._starting = None
        self._cluster = None                         # started by start(), not yet connected

    def start(self) -> None:
        """Start the local cluster's worker processes in a background thread (while the caller
        loads the cases' data); ``get`` connects to it (in the caller's thread: a Client is tied
        to the context it was made in).  A start that fails is made again (and its error raised)
        by ``get``."""
        if self._client is None and self._starting is None and not self.scheduler:
            self._t0 = time.perf_counter()
            self._starting = threading.Thread(target=self._start_quietly, daemon=True)
            self._starting.start()

    def _start_quietly(self) -> None:
        try:
            self._cluster = local_cluster(self.workers)
        except Exception as e:                       # noqa: BLE001 - get() starts again and raises
            log.debug("dask: background start failed (%s); starting in the foreground", e)

    def _join(self) -> None:
        if self._starting is not None:
            self._starting.join()
            self._starting = None

    def get(self):
        self._join()
        if self._client is None:
            t0 = getattr(self, "_t0", None) or time.perf_counter()
            cluster, self._cluster = self._cluster, None
            self._client = self._stack.enter_context(study_client(self.scheduler, self.workers, cluster))
            n = len(self._client.scheduler_info().get("workers", {}))
            log.info("dask: %s with %d workers (%.1f s to start)", self.scheduler or "local cluster", n,
                     time.perf_counter() - t0)
        return self._client

    def close(self):
        self._join()
        if self._cluster is not None:                # started ahead but never used (nothing to run)
            self._cluster.close()
            self._cluster = None
        self._stack.close()
        self._client = None


def log_run(out: Path, record: dict) -> None:
    """Append one JSON line to <out>/runs.jsonl (the study's run history)."""
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "runs.jsonl", "a") as fh:
        fh.write(json.dumps(record, sort_keys=True) + "\n")
        fh.flush()
        os.fsync(fh.fileno())


WAIT = "SQUEAL_STUDY_WAIT"       # "1": wait for another run of the study instead of refusing (then resume it)


def run_study(name: str, *, quick: bool = False, scheduler: str | None = None, workers: int | None = None,
              out: str | os.PathLike | None = None, progress: bool = True) -> Path:
    """Run (or resume) the study ``name``; returns the path of its summary.md."""
    spec, src = load_study(name)
    out = Path(out) if out else paths.build() / "studies" / (spec["name"] + ("-quick" if quick else ""))
    made = next((p for p in reversed([out, *out.parents]) if not p.exists()), None)   # the first folder made here
    out.mkdir(parents=True, exist_ok=True)
    mod = kind_module(spec["kind"])
    client = LazyClient(scheduler, workers)
    t0 = time.perf_counter()
    try:
        with open(out / ".lock", "w") as lock:
            try:                                     # one run per output folder at a time; SQUEAL_STUDY_WAIT=1
                fcntl.flock(lock, fcntl.LOCK_EX | (0 if os.environ.get(WAIT) == "1" else fcntl.LOCK_NB))
            except BlockingIOError:                  # (make_targets: validation writers in parallel) waits
                raise artifacts.ArtifactError(out, "another run of this study is writing here; wait for it "
                                                   "(or stop it: a rerun resumes where it stopped)") from None
            try:
                stats = mod.run(spec, src, out, quick=quick, client=client, progress=progress)
            finally:
                client.close()
    except ConfigError:                              # refused (its input): the folders made here go again
        if made is not None and {p.relative_to(made) for p in made.rglob("*") if p.is_file()} <= \
                {(out / ".lock").relative_to(made)}:
            shutil.rmtree(made, ignore_errors=True)
        raise
    record = {"time": time.strftime("%Y-%m-%dT%H:%M:%S"), "study": spec["name"], "quick": quick,
              "scheduler": scheduler or "local", "workers": workers or (os.cpu_count() if not scheduler else None),
              "wall_s": round(time.perf_counter() - t0, 3)} | stats
    log_run(out, record)
    log.info("study %s: %d cases, %d already done, %d run in %.1f s -> %s", spec["name"], stats["total"],
             stats["done_before"], stats["submitted"], record["wall_s"], out / "summary.md")
    return out / "summary.md"
