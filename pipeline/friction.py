"""The friction of a case and its regularized friction curves, built per law and value.

``Friction`` is a case's resolved ``[friction]`` table: the law's name, its parameters (for the
Coulomb law, ``mu``) and the preset it came from, if any.  Its ``label``
(``solvers.timeloop.inputs.curve_label``) names its curve in contact.npz and in the cache.

The curves mu_RF(s) (``solvers.contact.friction.rf_curve``, thesis [4.36-4.37]) are built for
the values asked -- the case's friction in the contact stage, a study's grid when its context is
loaded, another mu of the stability screen -- and cached by value:
``build/cases/<case>/friction/<key>.npz``, key = the hash of the contact the curve is computed on
(its static pressure field ``p3_static``, grid ``dx``, ``dy``, speed, elastic constants), the law
and its parameters, and the code of ``solvers/contact/``.  A new value costs one curve (one TANG
solve per creepage node, ~0.1-0.3 s), a value met before costs a file read.
"""
from __future__ import annotations

import functools
import hashlib
import logging
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import artifacts, paths

log = logging.getLogger("pipeline.friction")

CURVE_CODE = ("solvers/contact/*.py",)      # the code a cached curve depends on (its bytes are hashed)
CURVE_KIND = "friction-curve"


@dataclass(frozen=True)
class Friction:
    """A resolved friction law: ``name`` ('coulomb', ...), ``params`` ((name, value), ... sorted)
    in the units of the registry (``solvers.contact.friction_laws.LAWS``), ``preset``: the
    friction-modifier preset it came from (or None)."""
    name: str = "coulomb"
    params: tuple = ()
    preset: str | None = None

    @classmethod
    def coulomb(cls, mu: float) -> "Friction":
        return cls("coulomb", (("mu", float(mu)),))

    @classmethod
    def of(cls, name: str, params: dict, preset: str | None = None) -> "Friction":
        return cls(name, tuple(sorted((k, float(v)) for k, v in params.items())), preset)

    @property
    def label(self) -> str:
        from solvers.timeloop.inputs import curve_label

        return curve_label(self)

    @property
    def mu(self) -> float:
        """The Coulomb coefficient; for another law its local coefficient at zero slip speed
        (the static coefficient)."""
        p = dict(self.params)
        if self.name == "coulomb":
            return float(p["mu"])
        return float(np.asarray(self.law().mu(np.zeros(1)), float).ravel()[0])

    def law(self):
        """The solver's argument: the float mu for the Coulomb law (today's call of ``rf_curve``,
        bit for bit), else the registry's ``FrictionLaw``."""
        if self.name == "coulomb":
            return float(dict(self.params)["mu"])
        from solvers.contact.friction_laws import get_friction_law

        return get_friction_law(self.name, **dict(self.params))

    def config(self) -> dict:
        """JSON-able form, for configuration hashes."""
        return {"law": self.name, "params": dict(self.params), "preset": self.preset}


def as_friction(f) -> Friction:
    """A Friction from a Friction or a float (the Coulomb coefficient)."""
    return f if isinstance(f, Friction) else Friction.coulomb(float(f))


def case_friction(c: dict) -> Friction:
    """The resolved friction of a validated case dict (its ``[friction]`` table)."""
    return Friction.coulomb(c["friction"]["mu"])


# --------------------------------------------------------------------------------------------
# curves
# --------------------------------------------------------------------------------------------

def compute_curve(p3, dx: float, dy: float, v: float, friction: Friction, E: float, nu: float) -> dict:
    """One curve, computed (no cache): ``rf_curve``'s fields as arrays (numeric fields only)."""
    from solvers.contact.friction import rf_curve

    curve = rf_curve(p3, dx, dy, v, friction.law(), E, nu)
    out = {}
    for k, val in curve._asdict().items():
        a = np.asarray(val)
        if a.dtype.kind in "fiub":
            out[k] = a
    return out


def code_hash() -> str:
    files = tuple(p for pattern in CURVE_CODE for p in sorted(paths.ROOT.glob(pattern)))
    return _code_hash(tuple((p, p.stat().st_mtime_ns, p.stat().st_size) for p in files))


@functools.lru_cache(maxsize=8)
def _code_hash(files: tuple) -> str:
    h = hashlib.sha256()
    for p, _, _ in files:
        h.update(p.relative_to(paths.ROOT).as_posix().encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:16]


def contact_key(p3, dx: float, dy: float, v: float, E: float, nu: float) -> str:
    """Hash of what a curve is computed on besides the law: the pressure field and grid."""
    h = hashlib.sha256(np.ascontiguousarray(np.asarray(p3, np.float64)).tobytes())
    h.update(repr((np.shape(p3), float(dx), float(dy), float(v), float(E), float(nu))).encode())
    return h.hexdigest()[:16]


class CurveCache:
    """Friction curves of one contact, cached by value in ``folder`` (one npz per curve).
    Call it like ``compute_curve``; ``built`` / ``reused`` count what it did."""

    def __init__(self, folder: Path | None):
        self.folder = None if folder is None else Path(folder)
        self.built = self.reused = 0
        self.wall = 0.0

    def __call__(self, p3, dx, dy, v, friction: Friction, E, nu) -> dict:
        if self.folder is None:
            return self._build(p3, dx, dy, v, friction, E, nu)
        from .config import config_hash

        cfg = {"contact": contact_key(p3, dx, dy, v, E, nu), "law": friction.label, "code": code_hash()}
        path = self.folder / f"{config_hash(cfg)}.npz"
        cfg = cfg | {"friction": friction.config()}
        if path.exists():
            try:
                arrays, _ = artifacts.load_npz(path, CURVE_KIND, cfg)
                self.reused += 1
                return arrays
            except artifacts.ArtifactError:
                pass                                            # unreadable or stale: build it again
        curve = self._build(p3, dx, dy, v, friction, E, nu)
        artifacts.save_npz(path, CURVE_KIND, cfg, **curve)
        return curve

    def _build(self, p3, dx, dy, v, friction, E, nu) -> dict:
        t0 = time.perf_counter()
        curve = compute_curve(p3, dx, dy, v, friction, E, nu)
        self.wall += time.perf_counter() - t0
        self.built += 1
        return curve

    def summary(self) -> str:
        return (f"{self.built} friction curve{'s' if self.built != 1 else ''} built in {self.wall:.2f} s, "
                f"{self.reused} from the cache")


def curve_arrays(entries) -> dict:
    """The contact artifact's curve keys (README) for ``entries`` (label, mu, law name, curve as
    given by ``compute_curve``), padded to a common length with their last value: ``mu_values``,
    ``rf_label``, ``rf_law``, ``rf_n``, ``rf_s``, ``rf_mu``, ``rf_slope``, ``rf_gamma_sat``."""
    curves = [e[3] for e in entries]
    ns = max(len(k["s"]) for k in curves)

    def pad(key):
        return np.array([np.pad(np.asarray(k[key], float), (0, ns - len(k[key])), mode="edge") for k in curves])

    return {"mu_values": np.array([e[1] for e in entries], float), "rf_label": np.array([e[0] for e in entries]),
            "rf_law": np.array([e[2] for e in entries]), "rf_n": np.array([len(k["s"]) for k in curves]),
            "rf_s": pad("s"), "rf_mu": pad("mu_rf"), "rf_slope": pad("slope"),
            "rf_gamma_sat": np.array([float(k["gamma_sat"]) for k in curves])}


def entries_of(frictions, curves) -> list[tuple]:
    """``curve_arrays``' entries of curves computed for ``frictions``."""
    return [(f.label, f.mu, f.name, k) for f, k in zip(frictions, curves)]


def stored_entries(con) -> list[tuple]:
    """``curve_arrays``' entries of the curves held in a contact artifact's arrays."""
    from solvers.timeloop.inputs import curve_labels

    labels = curve_labels(con)
    laws = [str(x) for x in con["rf_law"]] if "rf_law" in con else [lab.split("(")[0] for lab in labels]
    out = []
    for i, lab in enumerate(labels):
        n = int(con["rf_n"][i])
        curve = {"s": np.asarray(con["rf_s"])[i, :n], "mu_rf": np.asarray(con["rf_mu"])[i, :n],
                 "slope": np.asarray(con["rf_slope"])[i, :n], "gamma_sat": float(np.asarray(con["rf_gamma_sat"])[i])}
        out.append((lab, float(con["mu_values"][i]), laws[i], curve))
    return out


def contact_curve_cache(case: str) -> CurveCache:
    """The curve cache of a case: build/cases/<case>/friction/."""
    return CurveCache(paths.case_dir(case) / "friction")


def with_curves(case: str, con, frictions) -> dict:
    """The contact artifact's arrays ``con`` (dict or NpzFile of contact.npz) as a dict that also
    holds the curves of ``frictions`` (each a Friction or a float mu) it lacks, built on its static
    contact through the case's curve cache."""
    con = {k: con[k] for k in (con.files if hasattr(con, "files") else con)}
    have = stored_entries(con)
    labels = {e[0] for e in have}
    want = []
    for f in map(as_friction, frictions):
        if f.label not in labels:
            labels.add(f.label)
            want.append(f)
    if not want:
        return con
    cache = contact_curve_cache(case)
    p3, dx, dy = con["p3_static"], float(con["dx"]), float(con["dy"])
    v, E, nu = float(con["speed"]), float(con["material_E"]), float(con["material_nu"])
    new = [cache(p3, dx, dy, v, f, E, nu) for f in want]
    log.info("friction curves of %s: %s", case, cache.summary())
    return con | curve_arrays(have + entries_of(want, new))
