"""Friction laws by name: the local coefficient of friction mu(s) at slip speed |s|.

One registry, like ``scipy.signal.get_window``: ``get_friction_law("exponential",
fkin=0.14, fexp1=0.19, sabsh1=1250.0)`` returns a ``FrictionLaw`` whose ``mu(s)`` and
``dmu(s)`` take the slip speed |s| in m/s (arrays), and whose ``code`` and ``array``
are the numba form read by the kernels (``mu_of(code, array, s)``), as CONTACT selects
a friction law by one method code with its parameter array (``cntc_setfrictionmethod``).

Laws (codes are CONTACT's L-digit, Vollebregt, User guide for CONTACT, sec. "Friction
law", eqs. coulomb_law, linear_law, rational_law, exponential_law, polach_law):

    coulomb      (L=0)  mu(s) = mu
    linear       (L=2)  mu(s) = fkin + flin1 max(0, 1 - s/(2 sabsh1)) + flin2 max(0, 1 - s/(2 sabsh2))
    rational     (L=3)  mu(s) = fkin + frat1 / (1 + s/sabsh1) + frat2 / (1 + (s/sabsh2)^2)
    exponential  (L=4)  mu(s) = fkin + fexp1 2^(-s/sabsh1) + fexp2 2^(-s/sabsh2)
    polach       (L=5)  mu(s) = mu0 ((1 - A) exp(-B s) + A)          (Polach 2005)

CONTACT's parameter names and units are kept: sabsh1, sabsh2 in mm/s (the slip speed at
which a term is halved), Polach's B in s/m as in Polach's paper (CONTACT's L=5 converts it:
fkin = A mu0, fexp1 = (1 - A) mu0, sabsh1 = ln 2 / B).  ``FrictionLaw.array`` holds them in
SI (m/s).  A negative flin/frat/fexp term gives a rising ("positive") friction
characteristic, as friction modifiers show; mu stays positive and at most MU_MAX.

CONTACT applies the falling laws through a friction memory (relaxation over a sliding
distance MEMDST, user guide "Friction memory"): the optional parameters memdst [mm] (default 0:
the instantaneous law) and mem_s0 [mm/s] (default 10, CONTACT's) of every law but coulomb; steady
TANG applies it (``tang.falling``), the global curves' point contact does not need it.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

MU_MAX = 1.0            # the project's range of a friction coefficient (pipeline.config.loader: 0 < mu <= 1)
COULOMB, LINEAR, RATIONAL, EXPONENTIAL, POLACH = 0, 2, 3, 4, 5
LN2 = math.log(2.0)


class Param(NamedTuple):
    """One parameter of a law: name, unit, allowed range (lo, hi; open ends flagged), doc,
    default (None: required)."""
    name: str
    unit: str
    lo: float
    hi: float
    lo_open: bool
    hi_open: bool
    doc: str
    default: float | None = None

    def range_text(self) -> str:
        return f"{self.lo:g} {'<' if self.lo_open else '<='} {self.name} {'<' if self.hi_open else '<='} {self.hi:g}"

    def admits(self, value: float) -> bool:
        lo_ok = value > self.lo if self.lo_open else value >= self.lo
        hi_ok = value < self.hi if self.hi_open else value <= self.hi
        return bool(np.isfinite(value)) and lo_ok and hi_ok


class Law(NamedTuple):
    """A registered law: its code (CONTACT's L-digit), parameters, formula, doc, reference."""
    name: str
    code: int
    params: tuple
    formula: str
    doc: str
    reference: str


def _coef(name, doc):
    return Param(name, "-", -MU_MAX, MU_MAX, False, False, doc, 0.0 if name.endswith("2") else None)


def _sabsh(name, doc, default=None):
    return Param(name, "mm/s", 0.0, 1e7, True, False, doc, default)


_FKIN = Param("fkin", "-", 0.0, MU_MAX, True, False, "kinetic coefficient: the limit at large slip speed")
_CONTACT_UG = ("E.A.H. Vollebregt, User guide for CONTACT, Vtech CMCC (github.com/eve70a/CONTACT, "
               "doc/user-guide.tex), section 'Slip velocity dependent friction'; source m_friclaw.f90 "
               "(fric_veldep_mu_steady); E.A.H. Vollebregt, Numerical modeling of measured railway creep "
               "versus creep-force curves with CONTACT, Wear 314 (2014) 87-95")


_MEMORY = (Param("memdst", "mm", 0.0, 1e3, False, False, "friction memory: characteristic sliding distance d_c "
                 "(CONTACT's MEMDST; 0: the instantaneous law; steady TANG only)", 0.0),
           Param("mem_s0", "mm/s", 0.0, 1e6, True, False, "friction memory: minimum velocity s_0 (CONTACT's MEM_S0)",
                 10.0))


def _two_terms(prefix, what):
    return (_FKIN,
            _coef(f"{prefix}1", f"size of the first {what} term (negative: rising friction)"),
            _sabsh("sabsh1", "slip speed at which the first term is halved"),
            _coef(f"{prefix}2", f"size of the second {what} term (default 0: off)"),
            _sabsh("sabsh2", "slip speed at which the second term is halved", 10000.0)) + _MEMORY


LAWS: dict[str, Law] = {
    "coulomb": Law("coulomb", COULOMB,
                   (Param("mu", "-", 0.0, MU_MAX, True, False, "Coulomb coefficient of friction"),),
                   "mu(s) = mu", "Coulomb friction, one coefficient (CONTACT L=0 with fstat = fkin)",
                   _CONTACT_UG),
    "linear": Law("linear", LINEAR, _two_terms("flin", "linear"),
                  "mu(s) = fkin + flin1 max(0, 1 - s/(2 sabsh1)) + flin2 max(0, 1 - s/(2 sabsh2))",
                  "CONTACT's linear falling law (L=2): linear decrease to fkin at s = 2 sabsh", _CONTACT_UG),
    "rational": Law("rational", RATIONAL, _two_terms("frat", "rational"),
                    "mu(s) = fkin + frat1 / (1 + s/sabsh1) + frat2 / (1 + (s/sabsh2)^2)",
                    "CONTACT's rational falling law (L=3)", _CONTACT_UG),
    "exponential": Law("exponential", EXPONENTIAL, _two_terms("fexp", "exponential"),
                       "mu(s) = fkin + fexp1 exp(-ln2 s/sabsh1) + fexp2 exp(-ln2 s/sabsh2)",
                       "CONTACT's exponential falling law (L=4)", _CONTACT_UG),
    "polach": Law("polach", POLACH,
                  (Param("mu0", "-", 0.0, MU_MAX, True, False, "maximum (static) coefficient, at s = 0"),
                   Param("A", "-", 0.0, 1.0, True, False, "ratio of the limit at infinite slip speed to mu0"),
                   Param("B", "s/m", 0.0, 1e3, False, False, "coefficient of the exponential decrease")) + _MEMORY,
                  "mu(s) = mu0 ((1 - A) exp(-B s) + A)",
                  "Polach's exponential falling law (CONTACT L=5 converts it to L=4)",
                  "O. Polach, Creep forces in simulations of traction vehicles running on adhesion limit, "
                  "Wear 258 (2005) 992-1000; CONTACT user guide eq. polach_law"),
}


PRESETS: dict[str, dict] = {
    "dry": {"law": "coulomb", "params": {"mu": 0.5},
            "source": "dry rail-wheel steel, the thesis' reference range (Zenzerovic 2014 uses mu = 0.1-0.6); "
                      "level only (assumed value)", "assumed": True},
    "polach_dry": {"law": "polach", "params": {"mu0": 0.55, "A": 0.40, "B": 0.60},
                   "source": "Polach 2005 (Wear 258), parameters for dry conditions (quoted from the paper's "
                             "table; not re-checked against the paper in this repository)", "assumed": False},
    "polach_wet": {"law": "polach", "params": {"mu0": 0.30, "A": 0.40, "B": 0.20},
                   "source": "Polach 2005 (Wear 258), parameters for wet conditions (quoted from the paper's "
                             "table; not re-checked against the paper in this repository)", "assumed": False},
    "contact_tractcurv": {"law": "exponential", "params": {"fkin": 0.14, "fexp1": 0.19, "sabsh1": 1250.0},
                          "source": "CONTACT user guide, traction curve example (tractcurv.inp, case 31 on: "
                                    "exponential falling friction, fstat = 0.33; after Vollebregt 2014, Wear 314)",
                          "assumed": False},
    "contact_polach": {"law": "exponential", "params": {"fkin": 0.1368, "fexp1": 0.2232, "sabsh1": 990.0},
                       "source": "CONTACT user guide, tractcurv.inp cases 91 on: Polach's law with mu_stat = 0.36, "
                                 "A = 0.38, B = 0.7 s/m written as L=4", "assumed": False},
    "wet": {"law": "exponential", "params": {"fkin": 0.15, "fexp1": 0.10, "sabsh1": 500.0},
            "source": "wet rail: lower level and a marked fall with slip speed, as Polach 2005's wet set "
                      "(mu0 = 0.30, A = 0.40 shape) with a faster decay; values assumed", "assumed": True},
    "hpf": {"law": "linear", "params": {"fkin": 0.35, "flin1": -0.10, "sabsh1": 250.0},
            "source": "top-of-rail friction modifier, 'high positive friction' (HPF): an intermediate level "
                      "(about 0.35) that rises with creepage (positive slope) after Eadie, Santoro, Kalousek "
                      "(Wear 2008, top of rail friction control) and Suda et al. (Wear 2005, onboard friction "
                      "control), as used for squeal by Meehan and Liu (JSV 2018); the level and slope here are "
                      "assumed (mu 0.25 -> 0.35 over 0.5 m/s of slip)", "assumed": True},
    "vhpf": {"law": "linear", "params": {"fkin": 0.45, "flin1": -0.10, "sabsh1": 250.0},
             "source": "friction modifier 'very high positive friction' (VHPF), level about 0.45 with a "
                       "positive slope (Eadie et al. 2008; Meehan and Liu, JSV 2018); level and slope assumed "
                       "(mu 0.35 -> 0.45 over 0.5 m/s of slip)", "assumed": True},
}


@numba.njit(cache=True)
def mu_of(code, array, s):
    """Local coefficient mu at slip speed |s| [m/s] for law `code` with SI parameter `array`."""
    s = abs(s)
    if code == 0:
        return array[0]
    if code == 2:
        return (array[0] + array[1] * max(0.0, 1.0 - 0.5 * s / array[2])
                + array[3] * max(0.0, 1.0 - 0.5 * s / array[4]))
    if code == 3:
        r2 = s / array[4]
        return array[0] + array[1] / (1.0 + s / array[2]) + array[3] / (1.0 + r2 * r2)
    if code == 4:
        return array[0] + array[1] * math.exp(-LN2 * s / array[2]) + array[3] * math.exp(-LN2 * s / array[4])
    if code == 5:
        return array[0] * ((1.0 - array[1]) * math.exp(-array[2] * s) + array[1])
    return np.nan


@numba.njit(cache=True)
def dmu_of(code, array, s):
    """d mu / d|s| [s/m] at slip speed |s| (the linear law: its slope below the kink at
    s = 2 sabsh, 0 from there on)."""
    s = abs(s)
    if code == 0:
        return 0.0
    if code == 2:
        d = 0.0
        if s < 2.0 * array[2]:
            d -= 0.5 * array[1] / array[2]
        if s < 2.0 * array[4]:
            d -= 0.5 * array[3] / array[4]
        return d
    if code == 3:
        q1 = 1.0 + s / array[2]
        r2 = s / array[4]
        q2 = 1.0 + r2 * r2
        return -array[1] / (array[2] * q1 * q1) - 2.0 * array[3] * r2 / (array[4] * q2 * q2)
    if code == 4:
        return (-LN2 / array[2] * array[1] * math.exp(-LN2 * s / array[2])
                - LN2 / array[4] * array[3] * math.exp(-LN2 * s / array[4]))
    if code == 5:
        return -array[0] * (1.0 - array[1]) * array[2] * math.exp(-array[2] * s)
    return np.nan


@numba.njit(cache=True)
def _map(fun_code, code, array, s):
    out = np.empty(s.size)
    flat = s.ravel()
    for i in range(flat.size):
        out[i] = mu_of(code, array, flat[i]) if fun_code == 0 else dmu_of(code, array, flat[i])
    return out


def _si_array(code, p):
    """The numba form in SI: the law's coefficients, then (not coulomb) memdst [m], mem_s0 [m/s]."""
    if code == COULOMB:
        return np.array([p["mu"]])
    memory = [1e-3 * p["memdst"], 1e-3 * p["mem_s0"]]
    if code in (LINEAR, RATIONAL, EXPONENTIAL):
        prefix = {LINEAR: "flin", RATIONAL: "frat", EXPONENTIAL: "fexp"}[code]
        return np.array([p["fkin"], p[prefix + "1"], 1e-3 * p["sabsh1"], p[prefix + "2"], 1e-3 * p["sabsh2"]]
                        + memory)
    return np.array([p["mu0"], p["A"], p["B"]] + memory)


class FrictionLaw:
    """A friction law with its parameters: ``mu(s)``, ``dmu(s)`` at slip speed |s| [m/s];
    ``name``, ``params`` (as given, CONTACT's units), ``code``, ``array`` (SI, for ``mu_of``)."""

    def __init__(self, name: str, params: dict):
        self.name = name
        self.params = dict(params)
        self.code = LAWS[name].code
        self.array = _si_array(self.code, self.params)

    def mu(self, s):
        """Local coefficient of friction at slip speed |s| [m/s] (scalar or array)."""
        a = np.asarray(s, dtype=float)
        return _map(0, self.code, self.array, a).reshape(a.shape)

    def dmu(self, s):
        """d mu / d|s| [s/m] at slip speed |s| [m/s]."""
        a = np.asarray(s, dtype=float)
        return _map(1, self.code, self.array, a).reshape(a.shape)

    @property
    def mu_static(self) -> float:
        """mu at zero slip speed (CONTACT's fstat)."""
        return float(mu_of(self.code, self.array, 0.0))

    @property
    def memory(self) -> tuple[float, float]:
        """CONTACT's friction memory (d_c [m], s_0 [m/s]); d_c = 0: the instantaneous law."""
        if self.code == COULOMB:
            return 0.0, 0.0
        return float(self.array[-2]), float(self.array[-1])

    @property
    def is_coulomb(self) -> bool:
        return self.code == COULOMB

    def __eq__(self, other):
        return isinstance(other, FrictionLaw) and self.name == other.name and self.params == other.params

    def __hash__(self):
        return hash((self.name, tuple(sorted(self.params.items()))))

    def __repr__(self):
        return f"FrictionLaw({self.name!r}, {', '.join(f'{k}={v:g}' for k, v in self.params.items())})"


def _bounds(law: Law, p: dict):
    """mu at s = 0 and its limit: both must lie in (0, MU_MAX] (every law here is monotone
    between them, so mu(s) does too)."""
    if law.code == COULOMB:
        return
    terms = [p[k] for k in p if k[:4] in ("flin", "frat", "fexp") and k[-1] in "12"]
    first = p["mu0"] if law.code == POLACH else p["fkin"] + sum(terms)
    if not 0.0 < first <= MU_MAX:
        raise ValueError(f"friction law '{law.name}': mu(0) = {first:g} out of range 0 < mu <= {MU_MAX:g}")
    if law.code != POLACH:
        lo = p["fkin"] + sum(min(t, 0.0) for t in terms)
        hi = p["fkin"] + sum(max(t, 0.0) for t in terms)
        if lo <= 0.0 or hi > MU_MAX:
            raise ValueError(f"friction law '{law.name}': mu(s) reaches {lo if lo <= 0 else hi:g}, outside "
                             f"0 < mu <= {MU_MAX:g} (fkin plus the terms)")


def get_friction_law(name: str, **params) -> FrictionLaw:
    """The friction law `name` (a key of LAWS) with its parameters (names and units of LAWS),
    or, without parameters, the preset `name` (a key of PRESETS).  Raises ValueError (one line)
    for an unknown law or parameter, a missing one or one out of its range."""
    if name not in LAWS and name in PRESETS and not params:
        return preset(name)
    if name not in LAWS:
        raise ValueError(f"unknown friction law {name!r}; known: {', '.join(sorted(LAWS))} "
                         f"(presets: {', '.join(sorted(PRESETS))})")
    law = LAWS[name]
    known = {p.name: p for p in law.params}
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise ValueError(f"friction law '{name}': unknown parameter {unknown[0]!r}; its parameters: "
                         f"{', '.join(known)}")
    values = {}
    for p in law.params:
        if p.name not in params:
            if p.default is None:
                raise ValueError(f"friction law '{name}': missing parameter '{p.name}' [{p.unit}] "
                                 f"({p.doc}; {p.range_text()})")
            values[p.name] = float(p.default)
            continue
        val = params[p.name]
        if isinstance(val, bool) or not isinstance(val, (int, float, np.floating, np.integer)):
            raise ValueError(f"friction law '{name}': {p.name} = {val!r} is not a number ({p.range_text()})")
        if not p.admits(float(val)):
            raise ValueError(f"friction law '{name}': {p.name} = {val!r} out of range {p.range_text()} [{p.unit}]")
        values[p.name] = float(val)
    _bounds(law, values)
    return FrictionLaw(name, values)


def preset(key: str) -> FrictionLaw:
    """The friction law of preset `key` (see PRESETS for its source)."""
    if key not in PRESETS:
        raise ValueError(f"unknown friction preset {key!r}; known: {', '.join(sorted(PRESETS))}")
    return get_friction_law(PRESETS[key]["law"], **PRESETS[key]["params"])


def as_law(law_or_mu) -> FrictionLaw:
    """A FrictionLaw from a FrictionLaw or a float (Coulomb)."""
    if isinstance(law_or_mu, FrictionLaw):
        return law_or_mu
    return get_friction_law("coulomb", mu=float(law_or_mu))


def from_table(table: dict) -> FrictionLaw:
    """The law of a case file's ``[friction]`` table (BRIEF's interface): ``preset = "<name>"``
    alone, or ``law = "<name>"`` (default "coulomb", then ``mu`` as before) with the law's
    parameters as keys (names of LAWS).  Raises ValueError (one line) as get_friction_law."""
    t = dict(table)
    if "preset" in t:
        key = t.pop("preset")
        if t:
            raise ValueError(f"[friction] preset = {key!r} stands alone; remove {', '.join(sorted(t))}")
        return preset(key)
    name = t.pop("law", "coulomb")
    if not isinstance(name, str):
        raise ValueError(f"[friction] law = {name!r} is not a name; known: {', '.join(sorted(LAWS))}")
    return get_friction_law(name, **t)
