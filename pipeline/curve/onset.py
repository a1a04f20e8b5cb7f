"""Onset of squeal for every wheel of a curve (issue 32): the friction level at which it starts to
squeal, the mode and frequency it starts at, and its level L_pA at 7.5 m against friction above it.

* Onset: ``solvers.stability.onset.find_onset`` on the stability screen's largest wheel-mode growth
  rate sigma(mu) (``what_ifs.CaseModels.roots``: the contact stage's Coulomb curve scaled exactly to
  any mu, ``solvers.stability.mitigation.coulomb_curve_at``; a wheel with positive lateral creepage
  as its mirror image), scanned over [MU_LO, MU_HI] in MU_STEPS steps, then Brent's method.  The
  mode and frequency are the fastest growing wheel-mode pole just above it (onset + XTOL).  A wheel
  without lateral creepage (pure rolling) has nothing to drive squeal: '>MU_HI'.  Another law than
  Coulomb (a falling law): mu is its static level with the law's shape kept -- every coefficient
  scaled by mu / mu_static, slip speeds and Polach's A, B kept (``pipeline.config.climate``'s rule,
  ``COEFFICIENTS``) -- its regularized curve built by TANG through the case's curve cache
  (``pipeline.caches.friction_curves.with_curves``).
* Level against friction: the time loop (as the friction what-if's confirmation,
  ``CaseModels.simulate``'s settings: at most 8 s, early stop at a limit cycle) at onset + LEVEL_STEPS (0.02, 0.05, 0.15, 0.3)
  (capped at MU_HI), the radiate stage's sound power of its final forces
  (``stages.radiate.sound_power_of_forces``) and the listen stage's transfer to the case's
  ``[listener]`` (7.5 m, 1.2 m: ``postprocess.listening.listener.transfer``, A-weighted): the same
  L_pA the listen stage computes from the same forces.  Stored as
  build/curves/<curve>/levels_<wheel>.csv.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from pipeline.caches.friction_curves import with_curves
from pipeline.config.climate import COEFFICIENTS
from pipeline.config.nouns import FrictionLaw
from pipeline.store import paths
from pipeline.store.artifacts import save_csv
from pipeline.stages.radiate import load_radiation_model, sound_power_of_forces
from pipeline.stages.listen import listener_inputs
from pipeline.curve.what_ifs import mirrored
from postprocess.listening import listener as L
from solvers.constants import SQUEAL_LEVEL_DB
from solvers.stability.onset import Onset, find_onset, unstable_windows
from solvers.study import squeals

MU_LO, MU_HI, MU_STEPS = 0.1, 0.8, 7      # the scanned range (step 0.1)
XTOL = 1e-3                                # brentq's tolerance on mu
LEVEL_STEPS = (0.02, 0.05, 0.15, 0.3)     # the time loop's friction levels above onset
DURATION = 8.0                             # s of rolling at most (SPEC 6)


class WheelOnset(NamedTuple):
    onset: Onset | None      # None: not computed (note says why)
    f_hz: float              # frequency of the growing pole just above onset
    mode: str                # its wheel mode label
    note: str = ""
    scanned: tuple | None = None   # the unstable windows up to the climate's top (``wheel_onset``'s ``top``)

    @property
    def windows(self) -> tuple:
        """The friction intervals (a, b) where the wheel squeals: the scanned ones, else (onset, inf)
        (b = inf: up to the scan's top and, unscanned, beyond); () without an onset."""
        if self.scanned is not None:
            return self.scanned
        return ((self.mu, math.inf),) if math.isfinite(self.mu) else ()

    def range_cell(self) -> str:
        return range_text(self.windows)

    @property
    def risk_onset(self) -> "tuple | float":
        """What ``risk.curve_risk`` takes: the windows, or NaN when the onset was not computed."""
        return math.nan if math.isnan(self.mu) else self.windows

    @property
    def mu(self) -> float:
        """The onset as a number (the scan's lower end for '<lo', inf for '>hi', NaN if not computed)."""
        if self.onset is None:
            return math.nan
        if self.onset.below:
            return self.onset.lo
        return self.onset.mu if math.isfinite(self.onset.mu) else math.inf

    def cell(self) -> str:
        return "" if self.onset is None else self.onset.text()


def range_text(windows) -> str:
    """verdict.csv's ``mu_squeal_range``: the windows as 'a-b' ('a-' when open), space separated."""
    return " ".join(f"{a:.4g}-" + (f"{b:.4g}" if math.isfinite(b) else "") for a, b in windows)


def range_windows(text: str) -> tuple:
    """The windows of a ``mu_squeal_range`` cell (``range_text``'s inverse, to its 4 digits)."""
    out = []
    for part in text.split():
        a, b = part.split("-")
        out.append((float(a), float(b) if b else math.inf))
    return tuple(out)


def cell_onset(mu: float, text: str) -> "tuple | float":
    """``WheelOnset.risk_onset`` from a table's cells: the onset as a number and ``mu_squeal_range`` (empty in
    a table written before the windows: the onset's own, (mu, inf))."""
    if not math.isfinite(mu):
        return mu
    return range_windows(text) if text else ((mu, math.inf),)


def law_at(law: FrictionLaw, level: float) -> FrictionLaw:
    """The law with its static coefficient moved to ``level``, its shape kept (module notes)."""
    if law.law == "coulomb":
        return FrictionLaw.coulomb(level)
    k = float(level) / law.mu
    return FrictionLaw.of(law.law, {q: v * k if q in COEFFICIENTS else v for q, v in law.params.items()})


def contact_at(models, mu: float):
    """The case's ContactModel at static level ``mu`` (Coulomb: ``CaseModels.contact``, exact
    scaling; another law: ``law_at`` and its TANG curve)."""
    from solvers.timeloop.interaction import contact_model  # lazy: brings in numba, rocket_fft, scipy

    if models.coulomb:
        return models.contact(mu)
    f = law_at(models.friction, mu)
    return contact_model(with_curves(models.ctx.case, models.ctx.contact, [f]), f)


class Screen:
    """``CaseModels.roots`` at any mu with the structures' transforms (``screen.Basis``, and the
    argument principle's contour shared by it and ``quiet``) built once: the same poles, without
    rebuilding the mu-independent part per friction level; each level's linear model and growth rate
    kept (brentq evaluates its bracket's ends again)."""

    def __init__(self, models):
        c = models.ctx
        wheel, kernel, spin = mirrored(c.gamma_y, models.wheel(), np.asarray(c.rail_kernel, float), models.spin)
        self.models, self.wheel, self.kernel = models, wheel, kernel
        self.args = c.loop.linearise(gamma_y=-abs(c.gamma_y), spin=spin)
        self.basis = self.contour = None
        self.models_at, self.growth_at = {}, {}

    def linear(self, mu: float):
        from solvers.stability.screen import linearise  # lazy: brings in numba

        if mu not in self.models_at:
            self.models_at[mu] = linearise(self.wheel, self.kernel, contact_at(self.models, mu), **self.args)
        return self.models_at[mu]

    def roots(self, mu: float):
        from solvers.stability.screen import Basis, screen  # lazy: brings in numba

        lm = self.linear(mu)
        if self.basis is None:
            self.basis = Basis(lm)
            self.basis.contour = self.contour        # the same Contour the screen builds (structure only)
        roots = screen(lm, self.basis)
        self.contour = self.basis.contour
        return roots

    def quiet(self, mu: float) -> bool:
        """No pole grows at ``mu`` (the argument principle's count alone: ``nyquist.no_growing_pole``)."""
        from solvers.stability.characteristic import _filter  # lazy: brings in numba
        from solvers.stability.nyquist import Contour, no_growing_pole  # lazy: brings in numba

        lm = self.linear(mu)
        if self.contour is None:
            self.contour = Contour(lm, _filter(lm))
        return no_growing_pole(lm, self.contour)


def growth(scr: Screen, mu: float) -> float:
    """The largest growth rate (1/s) of the wheel-mode poles at ``mu`` (-1e3 when none is found)."""
    if mu not in scr.growth_at:
        s = [r.sigma for r in scr.roots(mu) if r.mode >= 0]
        scr.growth_at[mu] = float(max(s)) if s else -1e3
    return scr.growth_at[mu]


class _Above(Exception):
    """The scan asked for a level above ``wheel_onset``'s ``above``: no onset at or below it."""


def wheel_onset(models, gamma_y: float, lo: float = MU_LO, hi: float = MU_HI, steps: int = MU_STEPS,
                above: float = math.inf, top: float | None = None) -> WheelOnset:
    """The onset of one wheel (module notes) from its ``what_ifs.CaseModels``.  ``above``: stop the scan
    where it would go past this level (the same grid and bracket, so an onset below it is the full
    scan's, bit for bit); quiet up to there: '>' the last level scanned (the line study's fast path).
    ``top``: the scan continued from the onset up to this level for the windows where the wheel squeals
    (``solvers.stability.onset.unstable_windows``; it may be stable again above a window)."""
    if gamma_y == 0.0:
        return WheelOnset(Onset(math.nan, False, lo, hi, (hi - lo) / steps, 0), math.nan, "",
                          "pure rolling: no lateral creep force")
    if not models.coulomb:             # the scaled law's coefficients stay <= 1: the range ends there
        top = max(v for q, v in models.friction.params.items() if q in COEFFICIENTS)
        hi = min(hi, math.floor(1e3 * models.friction.mu / top) / 1e3)
    scr = Screen(models)
    seen = [lo]

    def g(mu):
        if mu > above + 1e-9:
            raise _Above
        seen.append(mu)
        return growth(scr, mu)

    def quiet(mu):               # a quiet level is seen here, another one by ``g`` next
        if mu > above + 1e-9:
            raise _Above
        q = scr.quiet(mu)
        if q:
            seen.append(mu)
        return q

    try:
        on = find_onset(g, lo, hi, steps, XTOL, quiet=quiet)
    except _Above:
        return WheelOnset(Onset(math.nan, False, lo, max(seen), (hi - lo) / steps, len(seen) - 1), math.nan, "")
    if on.below or not math.isfinite(on.mu):
        at = lo if on.below else math.nan
    else:
        at = on.mu + XTOL
    if not math.isfinite(at):
        return WheelOnset(on, math.nan, "")
    wheel = [r for r in scr.roots(at) if r.mode >= 0]
    r = max(wheel, key=lambda r: r.sigma)
    scanned = None
    if top is not None and (on.lo if on.below else on.mu) <= top:
        scanned = unstable_windows(lambda mu: growth(scr, mu), on, min(top, above), steps, XTOL, quiet=scr.quiet)
    return WheelOnset(on, float(r.f_hz), models.ctx.label(r.mode), "", scanned)


def run_time_loop(models, mu: float):
    """One time-loop run at ``mu`` (``CaseModels.simulate``'s settings); the SimResult."""
    from solvers.timeloop.interaction import StopRule, simulate  # lazy: brings in numba, rocket_fft, scipy

    ctx = models.ctx
    return simulate(models.wheel(), ctx.rail_kernel, contact_at(models, mu),
                    **ctx.loop.simulate(spin=models.spin, duration=DURATION, stop=StopRule(window=0.25),
                                        store_every=max(1, int(round(0.01 / ctx.dt))), final=0.5))


class Listener:
    """The case's radiation model and listener transfer, loaded once per wheel."""

    def __init__(self, case: str):
        self.model = load_radiation_model(case)
        self.geo = listener_inputs(case)[3]

    def L_pA(self, res) -> float:
        """L_pA (dB(A) re 20 uPa) at the case's listener of a run's final forces (listen stage's sum)."""
        F = np.asarray(res.F_final, float)
        dt = float(res.dt_final or res.dt)
        pw = sound_power_of_forces(self.model, F, dt)
        H = L.transfer(pw["f"], self.geo)[0]
        p2 = np.abs(H) ** 2 * pw["W"]
        return float(L.level((p2 * 10 ** (L.a_weighting(pw["f"]) / 10)).sum()))


def level_row(models, mu: float, listener: "Listener | None") -> dict:
    """{mu, L_F2, f, squeals, L_pA} of one time-loop run (L_pA only when it squeals and ``listener``)."""
    res = run_time_loop(models, mu)
    m = res.measures()
    sq = bool(squeals(m["L_F2"], SQUEAL_LEVEL_DB))
    lpa = listener.L_pA(res) if (sq and listener is not None) else math.nan
    return {"mu": float(mu), "L_F2": float(m["L_F2"]), "f": float(m["f_dominant"]) if sq else math.nan,
            "squeals": sq, "L_pA": lpa}


def level_table(models, case: str, on: WheelOnset, steps=LEVEL_STEPS, hi: float = MU_HI) -> list[dict]:
    """The time loop at onset + ``steps`` (capped at ``hi``, duplicates dropped): rows of
    ``level_row``; [] when the wheel has no onset in the scanned range."""
    mu0 = on.mu
    if not math.isfinite(mu0):
        return []
    mus = sorted({round(min(mu0 + s, hi), 4) for s in steps})
    lis = Listener(case)
    return [level_row(models, mu, lis) for mu in mus]


LEVEL_COLUMNS = ["mu", "squeals", "f_hz", "L_F2", "L_pA_7m5"]


def save_level_table(curve: str, wheel: str, rows: list[dict]) -> None:
    """build/curves/<curve>/levels_<wheel>.csv (atomic)."""
    out = paths.curve_dir(curve) / f"levels_{wheel}.csv"
    fmt = lambda x: "" if isinstance(x, float) and not math.isfinite(x) else (f"{x:.6g}" if isinstance(x, float) else x)  # noqa: E731
    save_csv(out, LEVEL_COLUMNS, ([fmt(r["mu"]), int(r["squeals"]), fmt(r["f"]), fmt(r["L_F2"]), fmt(r["L_pA"])]
                                  for r in rows))
