"""A curve's squeal risk over a friction climate (issue 32): per wheel the probability of squeal and
its median L_pA,max at 7.5 m when it squeals; per curve the expected share of passages and of axles
that squeal.

The climate: the curve's ``[friction] climate`` when it names one (``pipeline.config.climate``), else
the shipped ``default`` climate (pipeline/climates/default.toml): a verdict always states its risk.
The curve's own ``[friction]`` level stays the single-friction verdict's (the other columns).

Per wheel, with its windows of friction where it squeals (``pipeline.curve.onset``: from the onset mu_on, the
scan continued up to the climate's highest level, ``top_level``; usually the single window (mu_on, inf), but a
wheel can be stable again above a window): p_squeal = P(mu in a window), for (a, b) P(mu > a) - P(mu > b),
P(mu > x) = sum_c share_c (1 - F_c(x)) exactly (``solvers.stability.onset.exceedance``; no sampling).  A
condition with another law than Coulomb enters with its level (static or kinetic, as its file says)
compared with the Coulomb onset: an approximation, stated in the verdict.  An onset below the
scanned range counts as the range's lower end (p_squeal a lower bound), one above it as never.

L_pAmax_7m5: the median of L_pA(mu) over the climate's levels in the windows, L_pA(mu) the wheel's
level table (time loop at a few levels above onset) interpolated linearly in mu, held constant
beyond its ends: the levels in a window (a, b) are the condition's quantiles on N_QUANTILES equal
probability steps between F_c(a) and F_c(b), weighted by share_c (F_c(b) - F_c(a)) / N_QUANTILES.

Per curve (one friction level per passage, the same on every wheel of it): a passage squeals when
mu lies in a window of any of its wheels, an axle when in a window of either of its two wheels.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pipeline.config.climate import CLIMATES, climate_file, load_climate
from pipeline.config.loader import ConfigError
from pipeline.curve.onset import MU_HI, MU_LO, MU_STEPS, level_table, save_level_table, wheel_onset
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


def windows_of(onset) -> tuple:
    """The unstable windows of an onset given as a number (mu: (mu, inf); inf: none) or as windows."""
    if isinstance(onset, tuple):
        return onset
    return ((onset, math.inf),) if math.isfinite(onset) else ()


def is_unknown(onset) -> bool:
    return not isinstance(onset, tuple) and math.isnan(onset)


def p_windows(climate, windows) -> float:
    """P(mu in one of ``windows``) (module notes): sum of P(a < mu < b), exact."""
    return sum((p_exceed(climate, a) - p_exceed(climate, b) for a, b in windows), 0.0)


def union(windows) -> tuple:
    """The union of intervals (a, b), sorted, overlapping ones merged."""
    out = []
    for a, b in sorted(windows):
        if out and a <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], b))
        else:
            out.append((a, b))
    return tuple(out)


def levels_in(climate, windows) -> tuple[np.ndarray, np.ndarray]:
    """(levels, weights): the climate's friction levels inside ``windows`` (module notes)."""
    mus, ws = [], []
    u = (np.arange(N_QUANTILES) + 0.5) / N_QUANTILES
    for c in climate.conditions:
        m, s = (c.mu_mean, c.mu_sd) if c.mu_range is None else (None, None)
        above = lambda x: 0.0 if math.isinf(x) else exceedance(  # noqa: E731
            x, [1.0], [c.lo], [c.hi], None if m is None else [m], None if s is None else [s])
        for a, b in windows:
            p, q = above(a), above(b)
            if p - q <= 0.0:
                continue
            mus.append(c.quantile(1.0 - p + (p - q) * u))
            ws.append(np.full(N_QUANTILES, c.share * (p - q) / N_QUANTILES))
    if not mus:
        return np.empty(0), np.empty(0)
    return np.concatenate(mus), np.concatenate(ws)


def median_level(climate, onset, table: list[dict]) -> float:
    """The median L_pA when squealing (module notes) over the levels in the onset's windows (``windows_of``);
    NaN without a squealing row in ``table``."""
    t = [(r["mu"], r["L_pA"]) for r in table if r["squeals"] and math.isfinite(r["L_pA"])]
    windows = () if is_unknown(onset) else windows_of(onset)
    if not t or not windows:
        return math.nan
    x, y = np.array(t).T
    mus, w = levels_in(climate, windows)
    return weighted_median(np.interp(mus, x, y), w) if mus.size else math.nan


def wheel_risk(climate, onset, table: list[dict]) -> dict:
    """{'p_squeal', 'L_pAmax_7m5'} of one wheel (its onset a number or its windows)."""
    p = math.nan if is_unknown(onset) else p_windows(climate, windows_of(onset))
    return {"p_squeal": p, "L_pAmax_7m5": median_level(climate, onset, table)}


def curve_risk(climate, onsets: dict) -> dict:
    """{'passages', 'axles'}: expected shares that squeal, from the wheels' onsets {wheel: mu or windows}
    (wheel names 'a<k><side>', axle k): a passage squeals when its friction level lies in a window of any
    wheel, an axle when in a window of either of its wheels."""
    known = {w: windows_of(v) for w, v in onsets.items() if not is_unknown(v)}
    passages = p_windows(climate, union(x for v in known.values() for x in v)) if known else math.nan
    axles = {}
    for w, v in known.items():
        axles[w[:-1]] = axles.get(w[:-1], ()) + v
    share = float(np.mean([p_windows(climate, union(v)) for v in axles.values()])) if axles else math.nan
    return {"passages": passages, "axles": share}


def highest(climate) -> float:
    """The climate's highest friction level."""
    return max(c.hi for c in climate.conditions)


def top_level(climate) -> float:
    """The first level of the onset scan's grid at or above the climate's highest friction level (inf
    when the climate reaches past the scanned range): the scan needs go no higher."""
    grid = np.linspace(MU_LO, MU_HI, MU_STEPS + 1)
    return next((float(g) for g in grid if g >= highest(climate) - 1e-12), math.inf)


def margin_text(wheel: str, on) -> str:
    """A quiet wheel's margin in words ('a1o would start at mu = 0.62 ((2,0,a), 435 Hz)')."""
    if on.onset is None:
        return f"{wheel}: onset {on.note}"
    if math.isfinite(on.mu):
        closed = any(math.isfinite(b) for _, b in on.windows)      # stable again above a window
        return (f"{wheel} would start at mu = {on.mu:.3f} ({on.mode}, {on.f_hz:.0f} Hz)"
                + (f" and squeals only for mu in {on.range_cell().replace(' ', ', ')}" if closed else ""))
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


COLUMNS = ["mu_onset", "mu_squeal_range", "f_onset", "mode_onset", "p_squeal", "L_pAmax_7m5"]
EMPTY = {"mu_onset": "", "mu_squeal_range": "", "f_onset": math.nan, "mode_onset": "", "p_squeal": math.nan,
         "L_pAmax_7m5": math.nan}


def add_risk(info, points, rows: list[dict], levels: bool = True) -> str:
    """Onset (``pipeline.curve.onset``), level table and climate risk of every wheel of a curve whose
    contact and greens stages have run (the curve stage's rows, filled in place: ``COLUMNS``); the
    level tables written to build/curves/<curve>/levels_<wheel>.csv.  Returns verdict.md's paragraph and the
    curve's expected shares of passages and axles that squeal (``curve_risk``).
    Call it inside ``pipeline.config.case.given`` of the curve's cases."""
    climate = curve_climate(info)
    top = top_level(climate)
    onsets, mus = {}, {}
    for p, row in zip(points, rows):
        case = f"{info.name}/{p.wheel}"
        models = CaseModels(case)
        on = wheel_onset(models, p.gamma_y, top=top)
        table = level_table(models, case, on) if levels else []
        if levels:
            save_level_table(info.name, p.wheel, table)
        onsets[p.wheel], mus[p.wheel] = on, on.risk_onset
        row |= ({"mu_onset": on.cell(), "f_onset": on.f_hz, "mode_onset": on.mode, "mu_squeal_range": on.range_cell()}
                | wheel_risk(climate, mus[p.wheel], table))
    shares = curve_risk(climate, mus)
    return risk_markdown(climate, rows, onsets, shares), shares
