"""A friction climate: the share of the time a rail spends in named conditions (dry, humid, wet,
friction modifier, leaves, ...), each a friction law whose level has a distribution.

    climate = load_climate("default")                  # pipeline/climates/default.toml, or a path
    index, mu = climate.sample(200, rng=1)             # each sample's condition and friction level
    law, params = climate.conditions[index[0]].law_params(mu[0])   # the law at that level

The file (TOML; docs/friction_climate.md has the shipped files' sources and the reasoning):

    name = "default"
    description = "..."                  # optional
    [[condition]]
    name = "dry"                         # an identifier, unique in the file
    share = 0.70                         # fraction of the time, 0 < share <= 1; the shares sum to 1
    law = "coulomb"                      # a law of solvers.contact.friction_laws.LAWS or a PRESETS key
    shape = {mu0 = 0.55, A = 0.4, B = 0.6}   # a LAWS law but coulomb: its parameters at any level
                                         # (CONTACT's names and units: sabsh in mm/s, B in s/m)
    level = "static"                     # the coefficient the distribution gives: "static" (mu at
                                         # zero slip speed) or "kinetic" (its limit at large slip speed)
    mu_mean = 0.29                       # normal(mu_mean, mu_sd) truncated to [mu_min, mu_max] ...
    mu_sd = 0.029
    mu_min = 0.23
    mu_max = 0.35
    # mu_range = [0.12, 0.17]            # ... or uniform on [a, b]; every level: 0 < mu < 1
    [condition.source]                   # where each number comes from; "ASSUMED ..." where none does
    share = "..."
    mu = "..."
    law = "..."                          # required unless law = "coulomb"

At a sampled level the condition's law is its reference law (the preset, or ``law`` with ``shape``)
scaled: every friction coefficient (mu, mu0, fkin and the flin/frat/fexp terms) is multiplied by
level / reference level, the slip speeds, Polach's A and B and the friction memory are kept (the
law's shape is kept, its level moves).  Errors: ``ConfigError`` (``pipeline.config.loader``), one
line per problem naming the file, the key, the value and what is allowed.
"""
from __future__ import annotations

import difflib
import math
import os
import re
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, model_validator
from pydantic_core import PydanticCustomError
from scipy.special import ndtr, ndtri

from pipeline.config.loader import MISSING, ConfigError, ConfigIssue
from solvers.contact.friction_laws import LAWS, PRESETS, get_friction_law

SHARE_TOL = 1e-6                     # |sum of the shares - 1| allowed
CLIMATES = Path(__file__).resolve().parents[1] / "climates"
COEFFICIENTS = ("mu", "mu0", "fkin", "flin1", "flin2", "frat1", "frat2", "fexp1", "fexp2")
NAME = re.compile(r"^[a-z][a-z0-9_]*$")
LEVEL = "a float, 0 < value < 1 (a friction coefficient)"
TEXT = {                             # what a key allows, in the words of the messages
    "name": "a string", "description": "a string",
    "condition": "an array of tables [[condition]] (at least one)",
    "share": "a float, 0 < value <= 1 (fraction of the time)",
    "law": f"one of {sorted(LAWS)} or a preset {sorted(PRESETS)}",
    "shape": "a table of the law's parameters (names and units of solvers.contact.friction_laws.LAWS)",
    "level": "one of ['static', 'kinetic']",
    "mu_mean": LEVEL, "mu_min": LEVEL, "mu_max": LEVEL, "mu_sd": "a float, 0 < value < 1",
    "mu_range": "an array of two floats [a, b], 0 < a < b < 1",
    "source": "a table: share, mu (and law unless law = 'coulomb'), each a non-empty string",
}


def _fail(key: str, allowed: str, value: Any = None):
    """A check's failure: ``key`` (below the model's location, '' for the model itself), the
    value and what is allowed, carried to ``_issue`` in the error's context."""
    return PydanticCustomError("climate", "{allowed}", {"allowed": allowed, "key": key, "value": value})


def _number(v):
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise PydanticCustomError("climate_type", "not a number")
    return float(v) + 0.0


def _text(v):
    if not isinstance(v, str) or not v.strip():
        raise PydanticCustomError("climate_type", "not a string")
    return v


def _pair(v):
    if not isinstance(v, (list, tuple)) or len(v) != 2:
        raise PydanticCustomError("climate_type", "not a pair")
    return (_number(v[0]), _number(v[1]))


def _shape(v):
    if not isinstance(v, dict):
        raise PydanticCustomError("climate_type", "not a table")
    return tuple(sorted((str(k), _number(x)) for k, x in v.items()))


Num = Annotated[float, BeforeValidator(_number)]
Text = Annotated[str, BeforeValidator(_text)]
Shape = Annotated[tuple[tuple[str, float], ...] | None, BeforeValidator(lambda v: None if v is None else _shape(v))]
Pair = Annotated[tuple[float, float] | None, BeforeValidator(lambda v: None if v is None else _pair(v))]


class Sources(BaseModel):
    """Where a condition's numbers come from (free text; 'ASSUMED ...' where no source fixes one)."""
    model_config = ConfigDict(frozen=True, extra="forbid")
    share: Text
    mu: Text
    law: Text | None = None


class Condition(BaseModel):
    """One rail condition: its share of the time, its law and the distribution of the law's level."""
    model_config = ConfigDict(frozen=True, extra="forbid")
    name: Text
    share: Num
    law: Text = "coulomb"
    shape: Shape = None
    level: Literal["static", "kinetic"] = "static"
    mu_mean: Num | None = None
    mu_sd: Num | None = None
    mu_min: Num | None = None
    mu_max: Num | None = None
    mu_range: Pair = None
    source: Sources

    @model_validator(mode="after")
    def _check(self):
        if not NAME.match(self.name):
            raise _fail("name", "an identifier: lower-case letters, digits, '_', starting with a letter", self.name)
        if not 0.0 < self.share <= 1.0:
            raise _fail("share", TEXT["share"], self.share)
        self._check_law()
        self._check_level()
        if self.law != "coulomb" and self.source.law is None:
            raise _fail("source.law", f"required key is missing for law = {self.law!r} (the source of the law's shape)",
                        MISSING)
        for key, level in (("mu_min", self.lo), ("mu_max", self.hi)):   # the scaled law at both ends
            try:
                self.law_params(level)
            except ValueError as e:
                ranged = self.mu_range is not None
                raise _fail("mu_range" if ranged else key, f"levels the law {self.law!r} can take (at {level:g}: {e})",
                            list(self.mu_range) if ranged else level) from None
        return self

    def _check_law(self):
        if self.law not in LAWS and self.law not in PRESETS:
            raise _fail("law", TEXT["law"], self.law)
        wants_shape = self.law in LAWS and self.law != "coulomb"
        if wants_shape and self.shape is None:
            need = [q.name for q in LAWS[self.law].params if q.default is None]
            raise _fail("shape", f"required key is missing for law = {self.law!r} (expected {TEXT['shape']}: "
                                 f"{', '.join(need)} required, the others optional)", MISSING)
        if not wants_shape and self.shape is not None:
            raise _fail("shape", f"no shape with law = {self.law!r} (a preset brings its own; coulomb has none)",
                        dict(self.shape))
        try:
            self.reference()
        except ValueError as e:
            raise _fail("shape", f"not accepted: {e}", dict(self.shape or ())) from None

    def _check_level(self):
        normal = {k: getattr(self, k) for k in ("mu_mean", "mu_sd", "mu_min", "mu_max")}
        given = [k for k, v in normal.items() if v is not None]
        if self.mu_range is not None:
            if given:
                raise _fail(given[0], "no mu_mean/mu_sd/mu_min/mu_max with mu_range (one distribution)",
                            normal[given[0]])
            a, b = self.mu_range
            if not 0.0 < a < b < 1.0:
                raise _fail("mu_range", TEXT["mu_range"], list(self.mu_range))
            return
        if not given:
            raise _fail("mu_range", "required: mu_range = [a, b] (uniform) or mu_mean, mu_sd, mu_min, mu_max "
                                    "(truncated normal)", MISSING)
        for k in normal:
            if normal[k] is None:
                raise _fail(k, f"required key is missing with {given[0]} (expected {TEXT[k]})", MISSING)
        m, s, lo, hi = normal.values()
        if not 0.0 < lo < 1.0:
            raise _fail("mu_min", LEVEL, lo)
        if not lo < hi < 1.0:
            raise _fail("mu_max", f"a float, mu_min ({lo:g}) < value < 1", hi)
        if not lo <= m <= hi:
            raise _fail("mu_mean", f"a float, mu_min ({lo:g}) <= value <= mu_max ({hi:g})", m)
        if not 0.0 < s < 1.0:
            raise _fail("mu_sd", TEXT["mu_sd"], s)

    # -- the level's distribution -------------------------------------------------------------

    @property
    def distribution(self) -> str:
        """'uniform' (mu_range) or 'truncnorm' (mu_mean, mu_sd, mu_min, mu_max)."""
        return "uniform" if self.mu_range is not None else "truncnorm"

    @property
    def lo(self) -> float:
        return self.mu_range[0] if self.mu_range is not None else self.mu_min

    @property
    def hi(self) -> float:
        return self.mu_range[1] if self.mu_range is not None else self.mu_max

    def quantile(self, p) -> np.ndarray:
        """The level's inverse distribution function at probabilities ``p`` in [0, 1] (array)."""
        p = np.asarray(p, dtype=float)
        if self.mu_range is not None:
            return self.lo + p * (self.hi - self.lo)
        pa = ndtr((self.lo - self.mu_mean) / self.mu_sd)     # <= 0.5 <= pb: mu_min <= mu_mean <= mu_max
        pb = ndtr((self.hi - self.mu_mean) / self.mu_sd)
        z = ndtri(pa + p * (pb - pa))
        return np.clip(self.mu_mean + self.mu_sd * z, self.lo, self.hi)

    # -- the law at a level -------------------------------------------------------------------

    def reference(self) -> tuple[str, dict]:
        """The law's name and its parameters as the file (or the preset) gives them."""
        if self.law in PRESETS:
            return PRESETS[self.law]["law"], dict(PRESETS[self.law]["params"])
        if self.law == "coulomb":
            return "coulomb", {"mu": 0.5}
        law = get_friction_law(self.law, **dict(self.shape))      # ValueError: not accepted
        return law.name, dict(law.params)

    def law_params(self, level: float) -> tuple[str, dict]:
        """The law (name, parameters for ``get_friction_law``) whose static or kinetic coefficient
        (``self.level``) is ``level``: the reference law with every coefficient scaled (ValueError
        when a coefficient of the scaled law leaves 0 < mu <= 1)."""
        name, params = self.reference()
        law = get_friction_law(name, **params)
        if name == "coulomb":
            ref = law.mu_static
        elif self.level == "static":
            ref = law.mu_static
        else:
            ref = params["mu0"] * params["A"] if name == "polach" else params["fkin"]
        k = float(level) / ref
        scaled = {q: v * k if q in COEFFICIENTS else v for q, v in params.items()}
        get_friction_law(name, **scaled)              # ValueError: a coefficient leaves (0, 1]
        return name, scaled


class Climate(BaseModel):
    """A friction climate: named conditions whose shares of the time sum to 1."""
    model_config = ConfigDict(frozen=True, extra="forbid", populate_by_name=True)
    name: Text
    description: Text | None = None
    conditions: tuple[Condition, ...] = Field(alias="condition")

    @model_validator(mode="after")
    def _check(self):
        if not self.conditions:
            raise _fail("condition", TEXT["condition"], [])
        names = [c.name for c in self.conditions]
        for i, n in enumerate(names):
            if n in names[:i]:
                raise _fail(f"condition[{i}].name", f"a name not used before (condition[{names.index(n)}] is {n!r})", n)
        total = math.fsum(c.share for c in self.conditions)
        if abs(total - 1.0) > SHARE_TOL:
            raise _fail("condition[*].share", f"shares summing to 1 within {SHARE_TOL:g} (they sum to {total:.6g}: "
                                              f"{', '.join(f'{c.name} {c.share:g}' for c in self.conditions)})", total)
        return self

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.conditions)

    @property
    def shares(self) -> np.ndarray:
        return np.array([c.share for c in self.conditions])

    def condition(self, name: str) -> Condition:
        return self.conditions[self.names.index(name)]

    def assumed(self) -> list[str]:
        """'<condition>.<key>' of every number whose source is an assumption ('ASSUMED ...')."""
        return [f"{c.name}.{k}" for c in self.conditions for k, v in c.source.model_dump().items()
                if v is not None and v.lstrip().upper().startswith("ASSUMED")]

    def sample(self, n: int, rng=None) -> tuple[np.ndarray, np.ndarray]:
        """``n`` independent samples: the condition index (by the shares) and its friction level
        (the condition's distribution, by its inverse distribution function).  ``rng``: a seed or
        a numpy Generator; the same seed gives the same samples."""
        rng = np.random.default_rng(rng)
        u = rng.random((2, int(n)))
        edges = np.cumsum(self.shares)
        index = np.minimum(np.searchsorted(edges / edges[-1], u[0], side="right"), len(self.conditions) - 1)
        level = np.empty(int(n))
        for i, c in enumerate(self.conditions):
            m = index == i
            level[m] = c.quantile(u[1][m])
        return index, level


def _issue(error: dict) -> ConfigIssue:
    """A pydantic error as (dotted key, value, what is allowed)."""
    loc = error["loc"]
    key = "".join(f"[{p}]" if isinstance(p, int) else (f".{p}" if i else str(p)) for i, p in enumerate(loc))
    field = str(loc[-1]) if loc and not isinstance(loc[-1], int) else "condition"
    kind, ctx, value = error["type"], error.get("ctx") or {}, error.get("input")
    in_source = "source" in loc[:-1] or field == "source"
    if kind == "climate":
        sub = ctx.get("key", "")
        return ConfigIssue(f"{key}.{sub}" if key and sub else (sub or key), ctx.get("value"), ctx["allowed"])
    if kind == "missing":
        return ConfigIssue(key, MISSING, f"required key is missing (expected {TEXT['source' if in_source else field]})")
    if kind == "extra_forbidden":
        known = (["share", "mu", "law"] if in_source else
                 [k for k in TEXT if k not in ("description", "condition")] if loc[0] == "condition" else
                 ["name", "description", "condition"])
        close = difflib.get_close_matches(field, known, n=1, cutoff=0.6)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        return ConfigIssue(key, value, f"unknown key{hint}; allowed keys here: {sorted(known)!r}")
    return ConfigIssue(key, value, TEXT["source"] if in_source else TEXT.get(field, error["msg"]))


def climate_file(name_or_path: str | os.PathLike) -> Path:
    """The file of a climate: a path as given, or a name of pipeline/climates/ ('default')."""
    p = Path(name_or_path)
    return p if p.suffix == ".toml" or len(p.parts) > 1 else CLIMATES / f"{p}.toml"


def load_climate(path: str | os.PathLike) -> Climate:
    """Read and check a climate file (a path, or a name of pipeline/climates/); ConfigError (one
    line per problem, naming the file) when it is missing, not TOML or not a valid climate."""
    source = str(climate_file(path))
    try:
        data = tomllib.loads(Path(source).read_text(encoding="utf-8"))
    except FileNotFoundError:
        known = sorted(p.stem for p in CLIMATES.glob("*.toml"))
        raise ConfigError(source, detail=f"climate file not found (shipped climates: {known})") from None
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(source, detail=f"cannot read the climate file: {e}") from None
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(source, detail=f"not valid TOML: {e}") from None
    try:
        return Climate.model_validate(data)
    except ValidationError as exc:
        raise ConfigError(source, [_issue(e) for e in exc.errors()]) from None
