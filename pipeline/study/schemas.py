"""The parts every study file's schema shares (pipeline/studies/<name>.toml, validated by
pipeline.config.loader: an error names the file, the key, the value and what is allowed).  Each kind's own
schema is its module's ``SCHEMA`` (pipeline/study/kinds/<kind>.py); ``kind`` picks it."""
from __future__ import annotations

import pkgutil
from pathlib import Path

from solvers.constants import SQUEAL_LEVEL_DB

from pipeline.config.loader import Field, ListOf

# the study kinds: the modules of pipeline/study/kinds/ (found, not listed; pipeline.study.kinds imports them)
KINDS = tuple(sorted(m.name for m in pkgutil.iter_modules([str(Path(__file__).parent / "kinds")])
                     if not m.name.startswith("_")))


COMMON = {
    "name": Field(str, doc="short name; outputs in build/studies/<name>/"),
    "kind": Field(str, choices=list(KINDS), doc="which study: a module of pipeline/study/kinds/ (SPEC 7)"),
    "description": Field(str, default=""),
    "cases": ListOf(Field(str), min_len=1, max_len=10,
                    doc="case files pipeline/cases/<case>.toml: one per contact position; the wheel, rail, speed, "
                        "time step and preload are the case's; keep the list on one line (the Makefile reads it)"),
}

SIMULATION = {
    "duration": Field(float, unit="s", min=0.01, max=8.0, default=8.0, doc="at most this much rolling (SPEC 6)"),
    "early_stop": Field(bool, default=True, doc="stop at a limit cycle or after decay (solvers.timeloop.interaction.StopRule)"),
    "final": Field(float, unit="s", min=0.01, max=2.0, default=0.5, doc="stretch the measures are taken over"),
    "window": Field(float, unit="s", min=0.01, max=2.0, default=0.25,
                    doc="window of the early-stop rule (solvers.timeloop.interaction.StopRule; 0.25 s as the simulate stage)"),
    "squeal_level": Field(float, unit="dB", min=-100.0, max=200.0, default=SQUEAL_LEVEL_DB,
                          doc="squeal when L_F2 >= this; sound power only then (SPEC 6)"),
    "screen_margin": Field(float, unit="1/s", min=0.0, max=1000.0, default=None,
                           doc="map: run the stability screen first and do not simulate the cases whose fastest "
                               "pole grows slower than -screen_margin (recorded as 'screened'); unset: simulate all"),
}

GAMMA = dict(kind=float, min=-0.2, max=0.2)
MU = dict(kind=float, min=0.05, max=1.0)
STEP = dict(kind=float, min=0.0, min_inclusive=False)


OPERATING = {
    "mu": Field(float, min=0.05, max=1.0, default=None, doc="default: the case's"),
    "gamma_y": Field(float, min=-0.2, max=0.2, default=None, doc="default: the case's"),
}


