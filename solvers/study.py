"""Numerics of the parameter studies (SPEC 7): grids, the squeal criterion, which wheel mode
squeals, modified wheel models, the squeal-critical damping by bisection, the prescribed
creepage and the measures the studies compare.  Functions on arrays; the pipeline
(pipeline/study_*.py) runs the simulations and stores the results.

The wheel modal damping study is written as a generator (``damping_procedure``): it yields
batches of simulation requests and receives their results, so the driver decides where and
when they run (a Dask cluster, memoised in the study's results table: a resumed study replays
the procedure from the stored results without simulating again).
"""
from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from typing import Generator, NamedTuple

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB as SQUEAL_LEVEL  # dB re 1 N: squeal when L_F2 >= this (SPEC 6)


def grid(first: float, last: float, step: float, decimals: int = 6) -> np.ndarray:
    """first, first +- step, ... up to last (inclusive, whichever direction), rounded to
    ``decimals`` so that keys and comparisons are free of floating-point noise."""
    if step <= 0:
        raise ValueError("step must be > 0")
    n = int(math.floor(abs(last - first) / step + 1e-9)) + 1
    sgn = 1.0 if last >= first else -1.0
    return np.round(first + sgn * step * np.arange(n), decimals)


def squeals(L_F2: float, level: float = SQUEAL_LEVEL) -> bool:
    """SPEC 6: a case squeals when L_F2 >= level (10 dB re 1 N); NaN/-inf never squeal."""
    return bool(np.isfinite(L_F2) and L_F2 >= level)


def nearest_mode(f: float, f_modes, candidates=None, rel_tol: float = 0.05, harmonics=(1,)) -> int | None:
    """Index of the candidate mode whose frequency is nearest to ``f`` (the dominant frequency of
    a squeal), or None when none is within ``rel_tol`` (relative) of it.  With harmonics=(1, 2, 3)
    ``f`` may also be the h-th harmonic of the mode (a strongly nonlinear limit cycle can put the
    largest F2 peak at 2 f_r); the lowest h with a match wins."""
    f_modes = np.asarray(f_modes, float)
    idx = np.arange(f_modes.size) if candidates is None else np.flatnonzero(candidates)
    if not np.isfinite(f) or idx.size == 0:
        return None
    for h in harmonics:
        j = idx[np.argmin(np.abs(h * f_modes[idx] - f))]
        if abs(h * f_modes[j] - f) <= rel_tol * h * f_modes[j]:
            return int(j)
    return None


def single_mode_damping(zeta, keep: int, flexible, zeta_kept: float = 1e-6, zeta_others: float = 1.0) -> np.ndarray:
    """Damping of the contact validation in dynamic conditions (SPEC 7): the flexible mode ``keep``
    at ``zeta_kept``, the other flexible modes at ``zeta_others``, the rigid half-wheelset
    (suspension) modes unchanged."""
    z = np.array(zeta, float)
    flex = np.asarray(flexible, bool)
    z[flex] = zeta_others
    z[keep] = zeta_kept
    return z


def periodic_creepage(gamma_0: float, amplitude: float, f: float, dt: float, n_steps: int) -> np.ndarray:
    """gamma_y(t) = gamma_0 + amplitude sin(2 pi f t) at t = n dt (SPEC 7, stand-alone
    contact validation)."""
    t = np.arange(n_steps) * dt
    return gamma_0 + amplitude * np.sin(2 * np.pi * f * t)


def harmonic_response(x, dt: float, f: float, periods: int) -> dict:
    """Mean, amplitude and phase (rad; x ~ mean + amplitude sin(2 pi f t + phase), t = 0 at the
    record's first sample) of the component at f over the last ``periods`` periods of x (the
    nearest whole number of samples), by least squares on (1, cos, sin): exact for a sinusoid
    plus a constant whatever the sampling; the harmonics of a periodic response leak only by
    the fraction of a sample the stretch misses whole periods by.  Also the peak-to-peak value."""
    x = np.asarray(x, float)
    n = int(round(periods / (f * dt)))
    if n > x.size or n < 4:
        raise ValueError(f"{periods} periods of {f} Hz need {n} samples, the record has {x.size}")
    w = 2 * np.pi * f * np.arange(x.size - n, x.size) * dt
    seg = x[-n:]
    A = np.column_stack([np.ones(n), np.sin(w), np.cos(w)])
    m, s, c = np.linalg.lstsq(A, seg, rcond=None)[0]      # s sin + c cos = hypot(s, c) sin(w + atan2(c, s))
    return {"mean": float(m), "amplitude": float(np.hypot(s, c)), "phase": float(np.arctan2(c, s)),
            "pp": float(np.ptp(seg))}


def relative_difference(a: float, reference: float) -> float:
    """(a - reference) / |reference|; NaN when the reference is 0 or not finite."""
    if not (np.isfinite(a) and np.isfinite(reference)) or reference == 0:
        return float("nan")
    return float((a - reference) / abs(reference))


# ----------------------------------------------------------------------------------------------
# squeal-critical damping (SPEC 7, wheel modal damping study)
# ----------------------------------------------------------------------------------------------

class Request(NamedTuple):
    """One simulation the damping procedure needs: the wheel model is the modes ``modes``
    (indices into the full modal set) with the damping ``zeta`` (full length; only ``modes``
    are used).  ``label``: readable identity, unique within a study (step, model, mode, zeta)."""
    label: str
    step: int
    model: str            # 'full' or 'reduced' (one flexible mode + the suspension)
    mode: int             # the mode whose damping is varied (-1: the full model's check run)
    modes: tuple
    zeta: tuple


class Outcome(NamedTuple):
    """What the procedure needs back: L_F2 (dB) and the dominant frequency of F2 (Hz)."""
    L_F2: float
    f_dominant: float


@dataclass
class DampingStep:
    """One step of the procedure: the full model's run (L_F2, f) and, when it squealed at a wheel
    mode, that mode's squeal-critical damping bracket [zeta_lo, zeta_hi] (squeals at zeta_lo, quiet
    at zeta_hi; the damping put into the full model afterwards is zeta_hi), the model the
    bisection ran in and its number of runs."""
    step: int
    L_F2: float
    f_dominant: float
    mode: int | None = None
    zeta_nominal: float = float("nan")
    zeta_lo: float = float("nan")
    zeta_hi: float = float("nan")
    bisection_model: str = ""
    runs: int = 0
    note: str = ""
    excluded: list = field(default_factory=list)   # modes taken out of a full-model bisection


@dataclass
class DampingResult:
    steps: list = field(default_factory=list)
    zeta: np.ndarray | None = None
    end: str = ""


def _zkey(z) -> str:
    return f"{z:.6e}"


def damping_procedure(zeta0, f_modes, flexible, *, level: float = SQUEAL_LEVEL, zeta_max: float = 0.1,
                      rel_tol: float = 0.05, max_steps: int = 8, mode_match: float = 0.05, harmonics=(1, 2, 3)
                      ) -> Generator[list, list, DampingResult]:
    """The wheel modal damping study of SPEC 7 as a generator of request batches.

    Repeat: run the full wheel model; if it squeals (L_F2 >= level) at a flexible mode (the
    dominant frequency within ``mode_match`` of the mode's, or of its 2nd or 3rd harmonic:
    ``harmonics``), find that mode's squeal-critical
    damping (the smallest damping at which the run no longer squeals at that mode) with a model
    of only that mode plus the suspension (rigid half-wheelset) modes, by geometric bisection
    between its present damping (must squeal) and ``zeta_max`` (must be quiet) until
    zeta_hi / zeta_lo - 1 <= rel_tol (the critical damping is then known to rel_tol); put
    zeta_hi into the full model and go on.

    Full-model bisection: when the mode does not squeal alone at its present damping (its squeal
    needs the other modes), or squeals again in the full model after its critical damping was
    applied (the other modes raise it), the bisection runs in the full model instead, the other
    modes at their present damping.  There another mode j can take the squeal over while mode i
    is still unstable (mode competition): such a run says nothing about mode i, so j is taken
    out of the model for the rest of this bisection and the run repeated (j gets its own step
    later, in the full model).  A squeal away from the wheel modes counts as quiet for mode i.

    Ends when the full model is quiet, squeals away from the wheel modes (e.g. the wheelset on
    the track), a mode still squeals at zeta_max, or after ``max_steps``.

    Yields lists of ``Request``; send back the list of ``Outcome`` in the same order.  Returns
    ``DampingResult`` (StopIteration.value)."""
    zeta = np.array(zeta0, float)
    f_modes = np.asarray(f_modes, float)
    flex = np.asarray(flexible, bool)
    rigid = tuple(int(i) for i in np.flatnonzero(~flex))
    full = tuple(range(zeta.size))
    out = DampingResult()
    damped: set[int] = set()
    for step in range(max_steps + 1):
        tag = "-".join(_zkey(z) for z in zeta[flex]) if step else "nominal"
        zhash = hashlib.sha256(tag.encode()).hexdigest()[:8]
        (r,) = yield [Request(f"s{step}-full-{zhash}", step, "full", -1, full, tuple(zeta))]
        st = DampingStep(step, r.L_F2, r.f_dominant)
        out.steps.append(st)
        if not squeals(r.L_F2, level):
            out.end = "quiet: the full model does not squeal"
            break
        i = nearest_mode(r.f_dominant, f_modes, flex, mode_match, harmonics)
        if i is None:
            st.note = (f"squeal at {r.f_dominant:.1f} Hz, not within {100 * mode_match:.0f} % of a wheel mode "
                       f"(or of harmonics {list(harmonics)} of one)")
            out.end = "squeal not at a wheel mode"
            break
        if step == max_steps:
            st.mode = i
            out.end = f"stopped after {max_steps} steps, still squealing"
            break
        st.mode, st.zeta_nominal = i, float(zeta[i])
        if abs(r.f_dominant - f_modes[i]) > mode_match * f_modes[i]:
            st.note = f"the dominant F2 peak is the {round(r.f_dominant / f_modes[i])}. harmonic of the mode"

        excluded: set[int] = set()

        def model_of(kind):
            if kind == "reduced":
                return tuple(sorted(rigid + (i,)))
            return tuple(j for j in full if j not in excluded)

        def req(kind, z):
            zz = zeta.copy()
            zz[i] = z
            mods = model_of(kind)
            tag = "" if kind == "reduced" or not excluded else "-x" + hashlib.sha256(str(mods).encode()).hexdigest()[:6]
            return Request(f"s{step}-{kind}-m{i}-z{_zkey(z)}-{zhash}{tag}", step, kind, i, mods, tuple(zz))

        def probe(kind, z):
            """One run at damping z of mode i; in the full model, repeated without any other mode
            that takes the squeal over.  Returns True when it squeals at mode i."""
            while True:
                (o,) = yield [req(kind, z)]
                st.runs += 1
                if not squeals(o.L_F2, level):
                    return False
                j = nearest_mode(o.f_dominant, f_modes, flex, mode_match, harmonics)
                if j == i:
                    return True
                if kind == "full" and j is not None and j not in excluded:
                    excluded.add(j)
                    continue
                return False

        lo, hi = float(zeta[i]), float(zeta_max)
        if lo >= hi:
            st.note = f"its damping {lo:g} is already >= zeta_max = {hi:g}"
            out.end = "a mode squeals at the largest damping tried"
            break
        kind = "full" if i in damped else "reduced"
        if kind == "reduced":
            a, b = yield [req("reduced", lo), req("reduced", hi)]
            st.runs += 2
            a_sq = squeals(a.L_F2, level) and nearest_mode(a.f_dominant, f_modes, flex, mode_match, harmonics) == i
            b_sq = squeals(b.L_F2, level) and nearest_mode(b.f_dominant, f_modes, flex, mode_match, harmonics) == i
            if not a_sq:
                st.note = (st.note + "; " if st.note else "") + \
                    "does not squeal alone at its damping: bisection in the full model"
                kind = "full"
                b_sq = yield from probe("full", hi)
        else:
            st.note = (st.note + "; " if st.note else "") + \
                "squeals again after its critical damping: bisection in the full model"
            b_sq = yield from probe("full", hi)
        st.bisection_model = kind
        if b_sq:
            st.zeta_lo, st.note = hi, (st.note + "; " if st.note else "") + f"still squeals at zeta_max = {hi:g}"
            out.end = "a mode squeals at the largest damping tried"
            break
        while hi / lo - 1.0 > rel_tol:
            z = math.sqrt(lo * hi)
            if (yield from probe(kind, z)):
                lo = z
            else:
                hi = z
        st.excluded = sorted(excluded)
        st.zeta_lo, st.zeta_hi = lo, hi
        zeta[i] = hi
        damped.add(i)
    out.zeta = zeta
    return out
