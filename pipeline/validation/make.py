"""What a validation writer, a slow test or a benchmark needs built, built through Make (the
Makefile's rules and dependencies decide what is stale): ``make_targets("build/rails/bv50/rail.npz")``,
``ensure_case("dy10")`` (the case's contact and Green's functions, with the wheel modes and the rail
they need).  Each runs Make in a subprocess, so the caller keeps no PETSc or Gmsh state."""
from __future__ import annotations

import os
import subprocess

from pipeline.store.paths import ROOT


def make_targets(*targets: str, **variables: str) -> None:
    """``make -s <targets> VAR=value ...`` at the repository's root; CalledProcessError when Make fails.
    Writers run in parallel and may ask for the same study: a second run waits for the first's lock and
    then finds it done (``pipeline.study.stage.WAIT``) instead of being refused."""
    subprocess.run(["make", "-s", "--no-print-directory", *targets, *(f"{k}={v}" for k, v in variables.items())],
                   cwd=ROOT, check=True, env=dict(os.environ, SQUEAL_STUDY_WAIT="1"))


def ensure_case(case: str = "default") -> None:
    """The contact and Green's functions of ``case`` (and its wheel's modes, its rail), up to date."""
    make_targets("contact", "greens", CASE=case)
