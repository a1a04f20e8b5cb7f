"""What a validation writer, a slow test or a benchmark needs built, built through Make (the
Makefile's rules and dependencies decide what is stale): ``make_targets("build/rails/bv50/rail.npz")``,
``ensure_case("dy10")`` (the case's contact and Green's functions, with the wheel modes and the rail
they need).  Each runs Make in a subprocess, so the caller keeps no PETSc or Gmsh state."""
from __future__ import annotations

import subprocess

from pipeline.store.paths import ROOT


def make_targets(*targets: str, **variables: str) -> None:
    """``make -s <targets> VAR=value ...`` at the repository's root; CalledProcessError when Make fails."""
    subprocess.run(["make", "-s", "--no-print-directory", *targets, *(f"{k}={v}" for k, v in variables.items())],
                   cwd=ROOT, check=True)


def ensure_case(case: str = "default") -> None:
    """The contact and Green's functions of ``case`` (and its wheel's modes, its rail), up to date."""
    make_targets("contact", "greens", CASE=case)
