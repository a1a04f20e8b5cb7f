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

import hashlib
import logging
import time
from pathlib import Path

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.config.loader import Field, MISSING, ConfigError, config_hash

log = logging.getLogger("pipeline.caches.friction_curves")

CURVE_KIND = "friction-curve"
CURVE_FUNCTIONS = ("pipeline.caches.friction_curves:compute_curve",)  # the code they reach is in the key


# a case's resolved [friction] table: the noun of pipeline.config.nouns (law, params, preset, mu)
from pipeline.config.nouns import FrictionLaw as Friction  # noqa: E402


def as_friction(f) -> Friction:
    """A Friction from a Friction or a float (the Coulomb coefficient)."""
    return f if isinstance(f, Friction) else Friction.coulomb(float(f))


def friction_schema() -> dict:
    """The case file's ``[friction]`` table: ``law`` (a name of the registry
    ``solvers.contact.friction_laws.LAWS``; default "coulomb"), every law's parameters with their
    units and ranges from the registry (only the chosen law's may be given), or ``preset`` (a name
    of ``PRESETS``: the law and its parameters together).  ``resolve_friction`` checks which keys
    go together."""
    from solvers.contact.friction_laws import LAWS, PRESETS  # lazy: brings in numba, rocket_fft, scipy


    out = {"law": Field(str, choices=list(LAWS), default=None,
                        doc='friction law (default "coulomb"; its parameters are the other keys)'),
           "preset": Field(str, choices=list(PRESETS), default=None,
                           doc="a friction preset (law and parameters with their source) instead of law + parameters")}
    for law in LAWS.values():
        for q in law.params:
            if q.name in out:
                continue
            out[q.name] = Field(float, unit=q.unit if q.unit != "-" else "", min=q.lo, max=q.hi,
                                min_inclusive=not q.lo_open, max_inclusive=not q.hi_open, default=None,
                                doc=f"{q.doc} (law {', '.join(k for k, w in LAWS.items() if q.name in [x.name for x in w.params])})")
    return out


def resolve_friction(f: dict, source: str) -> Friction:
    """The Friction of a validated ``[friction]`` table (``friction_schema``); ConfigError (one
    line, naming ``source``, the key, its value and what is allowed) when its keys do not go
    together: a parameter of another law, a missing parameter, a preset with a law or parameters,
    or values the law refuses together (its coefficient leaving 0 < mu <= 1)."""
    from solvers.contact.friction_laws import LAWS, PRESETS, get_friction_law, preset  # lazy: brings in numba, rocket_fft, scipy


    given = {k: v for k, v in f.items() if k not in ("law", "preset") and v is not None}
    if f.get("preset") is not None:
        name = f["preset"]
        extra = (["law"] if f.get("law") is not None else []) + sorted(given)
        if extra:
            k = extra[0]
            raise ConfigError(source, [(f"friction.{k}", f[k], f"no {k} with friction.preset = {name!r} (the preset "
                                        f"sets law {PRESETS[name]['law']!r} and its parameters); remove one of them")])
        law = preset(name)
        return Friction.of(law.name, law.params, name)
    name = f.get("law") or "coulomb"
    known = [q.name for q in LAWS[name].params]
    for k in sorted(given):
        if k not in known:
            raise ConfigError(source, [(f"friction.{k}", given[k], f"not a parameter of friction law {name!r} "
                                        f"(its parameters: {', '.join(known)}; set friction.law for another law)")])
    for q in LAWS[name].params:
        if q.default is None and q.name not in given:
            raise ConfigError(source, [(f"friction.{q.name}", MISSING, f"required key is missing for friction "
                                        f"law {name!r} (expected a float{' in ' + q.unit if q.unit != '-' else ''}, "
                                        f"{q.range_text()})")])
    try:
        law = get_friction_law(name, **given)
    except ValueError as e:
        raise ConfigError(source, [("friction", given, f"not accepted together: {e}")]) from None
    return Friction.of(law.name, law.params)


def case_friction(c: dict, case: str | None = None) -> Friction:
    """The resolved friction of a validated case dict (its ``[friction]`` table); messages name
    the file of ``case`` (default: the case's ``name``)."""
    return resolve_friction(c["friction"], str(paths.case_file(case or c["name"])))


# --------------------------------------------------------------------------------------------
# curves
# --------------------------------------------------------------------------------------------

def compute_curve(p3, dx: float, dy: float, v: float, friction: Friction, E: float, nu: float) -> dict:
    """One curve, computed (no cache): ``rf_curve``'s fields as arrays (numeric fields only)."""
    from solvers.contact.friction import rf_curve  # lazy: brings in numba, rocket_fft, scipy

    curve = rf_curve(p3, dx, dy, v, friction.solver_law(), E, nu)
    out = {}
    for k, val in curve._asdict().items():
        a = np.asarray(val)
        if a.dtype.kind in "fiub":
            out[k] = a
    return out


def code_hash() -> str:
    """The key of the code a cached curve depends on: what ``compute_curve`` reaches."""
    from pipeline.store.code_hash import code_key  # here: Make's DEPS of the module's other entry points stay without it

    return code_key(*CURVE_FUNCTIONS)


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
    """The contact artifact's curve keys (docs/reference.md) for ``entries`` (label, mu, law name, curve as
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
    from solvers.timeloop.inputs import curve_labels  # lazy: brings in numba, rocket_fft, scipy

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
