"""A curve's squeal risk over a friction climate (issue 32): per wheel the probability of squeal and
its median L_pA,max at 7.5 m when it squeals; per curve the expected share of passages and of axles
that squeal.

The climate: the curve's ``[friction] climate`` when it names one (``pipeline.config.climate``), else
the shipped ``default`` climate (pipeline/climates/default.toml): a verdict always states its risk.
The curve's own ``[friction]`` level stays the single-friction verdict's (the other columns).

Per wheel, with its onset mu_on (``pipeline.curve.onset``): p_squeal = P(mu > mu_on) =
sum_c share_c (1 - F_c(mu_on)) exactly (``solvers.stability.onset.exceedance``; no sampling).  A
condition with another law than Coulomb enters with its level (static or kinetic, as its file says)
compared with the Coulomb onset: an approximation, stated in the verdict.  An onset below the
scanned range counts as the range's lower end (p_squeal a lower bound), one above it as never.

L_pAmax_7m5: the median of L_pA(mu) over the climate's levels above the onset, L_pA(mu) the wheel's
level table (time loop at a few levels above onset) interpolated linearly in mu, held constant
beyond its ends: the levels above onset are the condition's quantiles on N_QUANTILES equal
probability steps, weighted by share_c (1 - F_c(mu_on)) / N_QUANTILES.

Per curve (one friction level per passage, the same on every wheel of it): a passage squeals when
mu exceeds the smallest onset of its wheels, an axle when mu exceeds the smaller of its two wheels'.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pipeline.config.climate import CLIMATES, climate_file, load_climate
from pipeline.config.loader import ConfigError
from pipeline.curve.onset import level_table, save_level_table, wheel_onset
from pipeline.curve.what_ifs import CaseModels
from solvers.stability.onset import exceedance, weighted_median

DEFAULT_CLIMATE = "default"
N_QUANTILES = 200


def curve_climate(info):
    """The Climate of a curve: its ``[friction] climate`` (a name of pipeline/climates/, or a path,
    relative to the curve file) or the default one (module notes); ConfigError naming the file."""
    name = (info.data.get("friction") or {}).get("climate") or DEFAULT_CLIMATE
    f = climate_file(name)
    if f.parent != CLIMATES and not f.is_absolute() and getattr(info, "source", None) is not None:
        f = Path(info.source).parent / f
    if not f.is_file():                  # named with the curve file and its key, not the climate's path alone
        known = sorted(p.stem for p in CLIMATES.glob("*.toml"))
        raise ConfigError(str(getattr(info, "source", "curve")), [
            ("friction.climate", name, f"a climate of pipeline/climates/ ({', '.join(known)}) or a climate file's "
                                       f"path beside the curve file ({f} does not exist)")])
    return load_climate(f)


def _params(climate):
    cs = climate.conditions
    nan = float("nan")
    return ([c.share for c in cs], [c.lo for c in cs], [c.hi for c in cs],
            [c.mu_mean if c.mu_range is None else nan for c in cs], [c.mu_sd if c.mu_range is None else nan for c in cs])


def p_exceed(climate, mu_on: float) -> float:
    """P(mu > mu_on) over the climate (0 for an infinite onset, NaN for an unknown one)."""
    if math.isnan(mu_on):
        return math.nan
    if math.isinf(mu_on):
        return 0.0
    return exceedance(mu_on, *_params(climate))


def levels_above(climate, mu_on: float) -> tuple[np.ndarray, np.ndarray]:
    """(levels, weights): the climate's friction levels above ``mu_on`` (module notes)."""
    mus, ws = [], []
    u = (np.arange(N_QUANTILES) + 0.5) / N_QUANTILES
    for c in climate.conditions:
        m, s = (c.mu_mean, c.mu_sd) if c.mu_range is None else (None, None)
        p = exceedance(mu_on, [1.0], [c.lo], [c.hi], None if m is None else [m], None if s is None else [s])
        if p <= 0.0:
            continue
        mus.append(c.quantile(1.0 - p + p * u))
        ws.append(np.full(N_QUANTILES, c.share * p / N_QUANTILES))
    if not mus:
        return np.empty(0), np.empty(0)
    return np.concatenate(mus), np.concatenate(ws)


def median_level(climate, mu_on: float, table: list[dict]) -> float:
    """The median L_pA when squealing (module notes); NaN without a squealing row in ``table``."""
    t = [(r["mu"], r["L_pA"]) for r in table if r["squeals"] and math.isfinite(r["L_pA"])]
    if not t or not math.isfinite(mu_on):
        return math.nan
    x, y = np.array(t).T
    mus, w = levels_above(climate, mu_on)
    return weighted_median(np.interp(mus, x, y), w) if mus.size else math.nan


def wheel_risk(climate, mu_on: float, table: list[dict]) -> dict:
    """{'p_squeal', 'L_pAmax_7m5'} of one wheel."""
    return {"p_squeal": p_exceed(climate, mu_on), "L_pAmax_7m5": median_level(climate, mu_on, table)}


def curve_risk(climate, onsets: dict) -> dict:
    """{'passages', 'axles'}: expected shares that squeal, from the wheels' onsets {wheel: mu} (wheel
    names 'a<k><side>', axle k)."""
    finite = [v for v in onsets.values() if not math.isnan(v)]
    passages = p_exceed(climate, min(finite)) if finite else math.nan
    axles = {}
    for w, v in onsets.items():
        if not math.isnan(v):
            axles[w[:-1]] = min(axles.get(w[:-1], math.inf), v)
    share = float(np.mean([p_exceed(climate, v) for v in axles.values()])) if axles else math.nan
    return {"passages": passages, "axles": share}


def margin_text(wheel: str, on) -> str:
    """A quiet wheel's margin in words ('a1o would start at mu = 0.62 ((2,0,a), 435 Hz)')."""
    if on.onset is None:
        return f"{wheel}: onset {on.note}"
    if math.isfinite(on.mu):
        return f"{wheel} would start at mu = {on.mu:.3f} ({on.mode}, {on.f_hz:.0f} Hz)"
    return f"{wheel} does not start below mu = {on.onset.hi:g}" + (f" ({on.note})" if on.note else "")


def risk_markdown(climate, rows: list[dict], onsets: dict, curve: dict) -> str:
    """verdict.md's paragraph on onset and risk."""
    quiet = not any(r["squeals"] for r in rows)
    parts = [margin_text(w, on) for w, on in onsets.items()]
    head = ("**Margin.** " if quiet else "**Onset.** ") + "; ".join(parts) + ".  "
    law = [c.name for c in climate.conditions if c.law != "coulomb"]
    risk = (f"Over the friction climate `{climate.name}` ({', '.join(f'{c.name} {c.share:g}' for c in climate.conditions)}): "
            f"squeal in {100 * curve['passages']:.1f} % of the passages and {100 * curve['axles']:.1f} % of the axles "
            "(leading bogie; one friction level per passage); per wheel `p_squeal` and the median level when "
            "squealing `L_pAmax_7m5` in verdict.csv, the level against friction in `levels_<wheel>.csv`."
            + (f"  Conditions {', '.join(law)} enter with their level against the Coulomb onset (an approximation)."
               if law else "") + "\n\n")
    return head + risk


COLUMNS = ["mu_onset", "f_onset", "mode_onset", "p_squeal", "L_pAmax_7m5"]
EMPTY = {"mu_onset": "", "f_onset": math.nan, "mode_onset": "", "p_squeal": math.nan, "L_pAmax_7m5": math.nan}


def add_risk(info, points, rows: list[dict], levels: bool = True) -> str:
    """Onset (``pipeline.curve.onset``), level table and climate risk of every wheel of a curve whose
    contact and greens stages have run (the curve stage's rows, filled in place: ``COLUMNS``); the
    level tables written to build/curves/<curve>/levels_<wheel>.csv.  Returns verdict.md's paragraph and the
    curve's expected shares of passages and axles that squeal (``curve_risk``).
    Call it inside ``pipeline.config.case.given`` of the curve's cases."""
    climate = curve_climate(info)
    onsets, mus = {}, {}
    for p, row in zip(points, rows):
        case = f"{info.name}/{p.wheel}"
        models = CaseModels(case)
        on = wheel_onset(models, p.gamma_y)
        table = level_table(models, case, on) if levels else []
        if levels:
            save_level_table(info.name, p.wheel, table)
        onsets[p.wheel], mus[p.wheel] = on, on.mu
        row |= {"mu_onset": on.cell(), "f_onset": on.f_hz, "mode_onset": on.mode} | wheel_risk(climate, on.mu, table)
    shares = curve_risk(climate, mus)
    return risk_markdown(climate, rows, onsets, shares), shares
