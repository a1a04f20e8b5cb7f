"""Run the validation writers (``make validate``), then assemble docs/validation.md.

    .venv/bin/python -m pipeline.validation.writers [--jobs N] [--list] [name ...]

Each writer of ``registry.WRITERS`` runs as its own process (``python -m <module>``; no PETSc, Gmsh or
VTK state shared between them, and a numba cache of its own), ``--jobs`` at a time (default: the cores); its
output goes to build/validation/<name>.log.  A writer that fails or does not write its fragments is reported with the
end of its log and the run exits 1 (docs/validation.md is assembled from the fragments either way).
Names select writers (default: every one that ``make validate`` runs)."""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time

from pipeline.store.paths import ROOT, build
from pipeline.validation.writers import DOCS
from pipeline.validation.writers.registry import WRITERS
from pipeline.validation.docs import assemble_validation


def _start(w, logs):
    """The writer's process; its numba cache in a folder of its own (build/validation/numba/<name>, kept between
    runs).  Observed with one cache in the source tree shared by writers running side by side: the two-point
    loop compiled there raised ZeroDivisionError, in the writer and in the unit test that loaded that cache
    later, while the same calls ran with a fresh cache (most likely concurrent writes of the cache's index and
    data by two processes)."""
    log = open(logs / f"{w.name}.log", "w")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(logs / "numba" / w.name))
    proc = subprocess.Popen([sys.executable, "-m", w.module, *w.args], cwd=ROOT, stdout=log,
                            stderr=subprocess.STDOUT, env=env)
    return proc, log, time.perf_counter(), time.time()


def run(names=(), jobs: int | None = None) -> int:
    todo = [w for w in WRITERS if (w.name in names if names else w.in_validate)]
    unknown = set(names) - {w.name for w in WRITERS}
    if unknown:
        print(f"unknown writer(s): {', '.join(sorted(unknown))}; known: {', '.join(w.name for w in WRITERS)}",
              file=sys.stderr)
        return 2
    jobs = jobs or len(os.sched_getaffinity(0))
    logs = build() / "validation"
    logs.mkdir(parents=True, exist_ok=True)
    running, failed, t0 = {}, [], time.perf_counter()
    while todo or running:
        while todo and len(running) < jobs:
            w = todo.pop(0)
            running[w] = _start(w, logs)
        time.sleep(0.5)
        for w, (proc, log, t_start, wall_start) in list(running.items()):
            if proc.poll() is None:
                continue
            log.close()
            del running[w]
            stale = [f for f in w.fragments if not (DOCS / f).exists() or (DOCS / f).stat().st_mtime < wall_start]
            took = time.perf_counter() - t_start
            if proc.returncode or stale:
                failed.append(w.name)
                why = f"exit {proc.returncode}" if proc.returncode else f"did not write {', '.join(stale)}"
                tail = (logs / f"{w.name}.log").read_text(errors="replace")[-3000:]
                print(f"FAILED {w.name} ({w.module}, {took:.0f} s): {why}\n{tail}", file=sys.stderr)
            else:
                print(f"wrote {', '.join(w.fragments)} ({w.module}, {took:.0f} s)", flush=True)
    print(f"{len(failed)} writer(s) failed" if failed else "every writer wrote its fragments",
          f"in {time.perf_counter() - t0:.0f} s; logs in {logs}", flush=True)

    assemble_validation()
    print("assembled docs/validation.md")
    return 1 if failed else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.validation.writers", description=__doc__.split("\n\n")[0])
    ap.add_argument("names", nargs="*", help="writers to run (default: those of `make validate`)")
    ap.add_argument("--jobs", type=int, default=None, help="writers run side by side (default: the cores)")
    ap.add_argument("--list", action="store_true", help="list the writers and their fragments")
    a = ap.parse_args(argv)
    if a.list:
        for w in WRITERS:
            print(f"{w.name:22s} {'validate' if w.in_validate else 'by hand ':8s} {w.module:48s} {' '.join(w.fragments)}")
        return 0
    return run(a.names, a.jobs)


if __name__ == "__main__":
    sys.exit(main())
