"""What a study's cases run with, loaded once on the client from a case's artifacts (checked
against the case's configuration like every stage does) and scattered to the Dask workers:
the contact tables and friction curves, the wheel's modal data at the contact point with the
mode labels, the rail's moving Green's function, the case settings and the wheel's radiation
model (radiate stage).  ``inputs`` hashes all of it plus the code that computes a
case (its syntax tree: docstrings and comments do not count), so a study's stored rows go stale
when any of it changes.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.code_hash import code_key
from pipeline.config.case import LoopArguments, loop_arguments, resolve_case
from pipeline.config.loader import config_hash
from pipeline.caches.friction_curves import with_curves
from pipeline.stages.greens import greens_inputs
from pipeline.stages.radiate import load_radiation_model

# the functions that compute a study's rows, and the context they run in (its objects' methods run in the
# rows: the case's friction law, for one): the code they reach is hashed into a row's inputs
ROW_FUNCTIONS = ("pipeline.study.context:load_context",
                 *(f"pipeline.study.worker:{f}" for f in ("map_case", "damping_case", "mode_case", "creepage_case",
                                                          "contact_case")))


def code_hash() -> str:
    """Hash of the code a study row depends on (its syntax trees: documentation does not count)."""
    return code_key(*ROW_FUNCTIONS, ignore_docs=True)


@dataclass(frozen=True)
class CaseContext:
    """One contact position's data for the workers (picklable; SI units).  ``loop``: the case's time-loop
    arguments (``pipeline.config.case.loop_arguments``), read through dt, v, preload, gamma_x, gamma_y,
    spin, tangential, normal."""
    case: str
    inputs: str
    dy_wr: float
    loop: LoopArguments
    mu: float
    contact: dict
    wheel: dict            # f, mass, zeta, phi (modes, 2), n, m, cls, kind
    rail_kernel: np.ndarray
    radiation: Any = None  # pipeline.stages.radiate.load_radiation_model(case), or None (not requested)
    radiation_note: str = ""
    extra: dict = field(default_factory=dict)
    friction: Any = None   # the case's resolved FrictionLaw (pipeline.config.nouns); mu: its coefficient

    dt = property(lambda self: self.loop.dt)                  # s
    v = property(lambda self: self.loop.v)                    # m/s
    preload = property(lambda self: self.loop.preload)        # N, static normal force
    gamma_x = property(lambda self: self.loop.gamma_x)
    gamma_y = property(lambda self: self.loop.gamma_y)
    spin = property(lambda self: self.loop.spin)              # 1/m
    tangential = property(lambda self: self.loop.tangential)
    normal = property(lambda self: self.loop.normal)

    @property
    def flexible(self) -> np.ndarray:
        return np.asarray(self.wheel["kind"]).astype(str) == "flexible"

    def label(self, i: int) -> str:
        w = self.wheel
        return f"({int(w['n'][i])},{int(w['m'][i])},{w['cls'][i]})"


def load_context(case: str, *, radiation: bool = True, zeta_overrides: dict | None = None,
                 mus=()) -> CaseContext:
    """The CaseContext of ``case`` from build/cases/<case>/contact.npz, greens.npz and the wheel's
    modes.npz (ArtifactError when missing or stale, naming the make target).  ``zeta_overrides``
    {mode: zeta} only for the radiation model (the simulation's damping is set per task).  ``mus``:
    the friction coefficients the study runs besides the case's own; their curves are built on the
    case's contact (``pipeline.caches.friction_curves.with_curves``, cached by value)."""
    from pipeline.stages.contact import contact_inputs  # lazy: brings in numba, rocket_fft, scipy

    c, _, _, ccfg = contact_inputs(case)
    _, _, _, modes, _, gcfg = greens_inputs(case)      # the wheel modes, checked against the wheel file
    cdir = paths.case_dir(case)
    con, cprov = artifacts.load_npz(cdir / "contact.npz", "contact", ccfg, make_target=f"contact CASE={case}")
    gr, gprov = artifacts.load_npz(cdir / "greens.npz", "greens", gcfg, make_target=f"greens CASE={case}")
    con = with_curves(case, con, [float(m) for m in mus])
    if len(modes["f_hz"]) != len(gr["wheel_f"]) or not np.allclose(modes["f_hz"], gr["wheel_f"]):
        raise artifacts.ArtifactError(cdir / "greens.npz", f"its wheel modes are not those of "
                                      f"{paths.wheel_dir(c['wheel']) / 'modes.npz'}; run `make greens CASE={case}`")
    wheel = {"f": gr["wheel_f"], "mass": gr["wheel_mass"], "zeta": gr["wheel_zeta"], "phi": gr["wheel_phi"],
             "n": modes["n"], "m": modes["m"], "cls": modes["cls"].astype(str), "kind": modes["kind"].astype(str)}

    model = load_radiation_model(case, zeta_overrides) if radiation else None
    note = "" if radiation else "not requested"
    inputs = config_hash({"contact": cprov["config_hash"], "greens": gprov["config_hash"],
                         "code": code_hash(), "radiation": model is not None,
                         "zeta_overrides": {str(k): float(v) for k, v in (zeta_overrides or {}).items()}})
    rc = resolve_case(case)
    return CaseContext(case=case, inputs=inputs, dy_wr=c["contact"]["dy_wr"], loop=loop_arguments(rc, con),
                       mu=rc.friction.mu, friction=rc.friction, contact=con, wheel=wheel,
                       rail_kernel=gr["rail_kernel"], radiation=model, radiation_note=note)
