"""Mitigation what-ifs of one squealing case (a curve's wheel, or any case): the friction
coefficient below which it stops squealing and the modal damping its squealing modes need.

* Friction: bisection over mu of the stability screen's verdict (a growing pole at a wheel
  mode), the friction curve at any mu scaled exactly from the contact stage's nearest curve
  (``solvers.stability.mitigation.coulomb_curve_at``), confirmed by one time-loop run on each side of the
  threshold (``CONFIRM_MARGIN`` below and above it: right at the threshold the growth rate is
  zero and 8 s of rolling cannot tell).
* Damping: the project's damping procedure (``solvers.study.damping_procedure``, SPEC 7: find
  the squealing mode, bisect its squeal-critical damping with that mode alone plus the
  suspension, put it in, repeat while the squeal moves on), each of its runs answered by the
  stability screen instead of an 8 s simulation (``solvers.stability.mitigation.screen_outcome``); the
  damped wheel is then confirmed quiet by one time-loop run.

The screen of a wheel whose lateral creepage is positive (F2 < 0 on the rail: the outer wheel
of an under-radial wheelset) is that of its mirror image y -> -y: gamma_y, F2, xi2 and the
modal and rail cross receptances (2-3) change sign, the rest of the point-contact loop is
unchanged (the friction curve is odd in the slip), so the linearised loop of SPEC 3.5 applies.

Reads the case's contact.npz and greens.npz (``pipeline.study.context.load_context``).
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB
from solvers.stability.mitigation import threshold, screen_outcome, coulomb_curve_at, growing_wheel_root
from solvers.study import damping_procedure, squeals
from pipeline.study.context import load_context
from pipeline.caches.friction_curves import stored_entries

log = logging.getLogger("pipeline.curve")

MU_MIN = 0.02            # lowest friction coefficient the bisection tries
MU_TOL = 0.005           # the threshold to +- MU_TOL / 2
CONFIRM_MARGIN = 0.05    # time-loop confirmations at threshold -+ this
DURATION = 8.0           # s of rolling at most for a confirmation (SPEC 6), early stop at a limit cycle
ZETA_MAX = 0.1           # damping bracket's upper end (as the damping study)
ZETA_TOL = 0.05          # critical damping to 5 %


def mirrored(gamma_y: float, wheel, kernel, spin: float):
    """The screen's inputs for a positive lateral creepage as the mirror image y -> -y of a negative one:
    the lateral mode shapes, the cross receptances and the spin change sign (module notes)."""
    if gamma_y <= 0:
        return wheel, kernel, spin
    phi = np.array(wheel.phi, float)
    phi[:, 0] *= -1.0
    kernel = kernel.copy()
    kernel[:, 0, 1] *= -1.0
    kernel[:, 1, 0] *= -1.0
    return wheel._replace(phi=phi), kernel, -spin


class CaseModels:
    """One case's linearised and time-domain models at any friction coefficient and wheel damping."""

    def __init__(self, case: str):
        self._setup(load_context(case, radiation=False))

    @classmethod
    def of_context(cls, ctx) -> "CaseModels":
        """The models of a CaseContext built in memory (``pipeline.curve.screen_first``: no artifacts)."""
        self = cls.__new__(cls)
        self._setup(ctx)
        return self

    def _setup(self, ctx) -> None:
        self.ctx = ctx
        self.spin = float(ctx.spin)                           # 1/m
        self.friction = ctx.friction                          # the case's own law (its curve is in contact.npz)
        # the Coulomb curves the contact artifact holds, by coefficient (its mu_values, law by law)
        self.mus = np.array([mu for _, mu, law, _ in stored_entries(ctx.contact) if law == "coulomb"], float)

    @property
    def coulomb(self) -> bool:
        """Coulomb friction: the what-ifs over mu apply (they scale a Coulomb curve)."""
        return self.friction.name == "coulomb" and self.mus.size > 0

    def contact(self, mu: float):
        """The case's ContactModel with the Coulomb friction curve at ``mu`` (any value), scaled from
        the nearest curve the contact artifact holds (exact: ``solvers.stability.mitigation``)."""
        from solvers.timeloop.interaction import contact_model  # lazy: brings in numba, rocket_fft, scipy

        if not self.coulomb:                                  # another law: its own curve, at its own mu only
            if abs(mu - self.ctx.mu) > 1e-12:
                raise ValueError(f"friction law {self.friction.name}: curves at another mu are not scaled")
            return contact_model(self.ctx.contact, self.friction)
        i = int(np.argmin(np.abs(self.mus - mu)))
        cm = contact_model(self.ctx.contact, float(self.mus[i]))
        if abs(self.mus[i] - mu) <= 1e-12:
            return cm
        s, m, k = coulomb_curve_at(cm.s_nodes, cm.mu_nodes, cm.slopes, float(self.mus[i]), mu)
        return cm._replace(s_nodes=s, mu_nodes=m, slopes=k, mu=float(mu))

    def wheel(self, zeta=None, modes=None):
        from pipeline.study.worker import _wheel  # lazy: brings in numba, rocket_fft, scipy

        return _wheel(self.ctx, zeta, modes)

    def roots(self, mu: float, zeta=None, modes=None):
        """The stability screen's closed-loop poles (fastest growing first); pole ``mode`` indices
        refer to the full modal set."""
        from solvers.stability.screen import linearise, screen  # lazy: brings in numba

        c = self.ctx
        idx = np.arange(len(c.wheel["f"])) if modes is None else np.asarray(modes, int)
        wheel, kernel, spin = mirrored(c.gamma_y, self.wheel(zeta, idx), np.asarray(c.rail_kernel, float), self.spin)
        lm = linearise(wheel, kernel, self.contact(mu), **c.loop.linearise(gamma_y=-abs(c.gamma_y), spin=spin))
        return [r._replace(mode=int(idx[r.mode]) if r.mode >= 0 else -1) for r in screen(lm)]

    def unstable(self, mu: float) -> bool:
        return growing_wheel_root(self.roots(mu)) is not None

    def simulate(self, mu: float, zeta=None) -> dict:
        """One time-loop run as the simulate stage's (SPEC 6: at most 8 s, early stop at a limit cycle,
        the case's creepages and spin): L_F2, f_dominant, squeals."""
        from solvers.timeloop.interaction import StopRule, simulate  # lazy: brings in numba, rocket_fft, scipy

        ctx = self.ctx
        res = simulate(self.wheel(zeta), ctx.rail_kernel, self.contact(mu),
                       **ctx.loop.simulate(spin=self.spin, duration=DURATION, stop=StopRule(window=0.25),
                                           store_every=max(1, int(round(0.01 / ctx.dt))), final=0.5))
        m = res.measures()
        return {"mu": mu, "L_F2": float(m["L_F2"]), "f": float(m["f_dominant"]),
                "squeals": squeals(m["L_F2"], SQUEAL_LEVEL_DB)}


@dataclass
class FrictionWhatIf:
    mu_case: float
    mu_quiet: float = math.nan        # screen quiet here ...
    mu_squeal: float = math.nan       # ... and unstable here (threshold in between)
    screens: int = 0
    below: dict = field(default_factory=dict)    # time-loop run at threshold - margin
    above: dict = field(default_factory=dict)    # time-loop run at threshold + margin
    note: str = ""

    @property
    def threshold(self) -> float:
        return 0.5 * (self.mu_quiet + self.mu_squeal)

    @property
    def confirmed(self) -> bool:
        return bool(self.below) and bool(self.above) and not self.below["squeals"] and self.above["squeals"]


def friction_what_if(models: CaseModels, *, tol: float = MU_TOL, confirm: bool = True) -> FrictionWhatIf:
    """The friction coefficient below which the case stops squealing (module notes)."""
    mu = float(models.ctx.mu)
    out = FrictionWhatIf(mu)
    if not models.coulomb:
        out.note = f"not computed for the friction law {models.friction.name} (the threshold scales a Coulomb curve)"
        return out
    try:
        b = threshold(models.unstable, MU_MIN, mu, tol)
    except ValueError as e:
        out.note = f"no threshold below the case's mu = {mu:g}: {e}"
        return out
    out.mu_quiet, out.mu_squeal, out.screens = b.quiet, b.squeal, b.evaluations
    if confirm:
        lo = max(MU_MIN, out.threshold - CONFIRM_MARGIN)
        hi = min(out.threshold + CONFIRM_MARGIN, mu)      # the case's own mu squeals (the bracket's top)
        out.below, out.above = models.simulate(lo), models.simulate(hi)
        if not out.confirmed:
            out.note = (f"the time loop does not confirm the screen: mu = {lo:.3f} "
                        f"{'squeals' if out.below['squeals'] else 'quiet'}, mu = {hi:.3f} "
                        f"{'squeals' if out.above['squeals'] else 'quiet'}")
    return out


@dataclass
class DampingWhatIf:
    modes: list = field(default_factory=list)   # [(label, f_hz, zeta_nominal, zeta_needed)]
    end: str = ""
    screens: int = 0
    confirm: dict = field(default_factory=dict)  # time-loop run with the damping applied


def damping_what_if(models: CaseModels, *, confirm: bool = True) -> DampingWhatIf:
    """The modal damping the squealing mode(s) need at the case's operating point (module notes)."""
    ctx = models.ctx
    w = ctx.wheel
    gen = damping_procedure(w["zeta"], w["f"], ctx.flexible, level=SQUEAL_LEVEL_DB, zeta_max=ZETA_MAX,
                            rel_tol=ZETA_TOL)
    out = DampingWhatIf()
    answers = None
    try:
        while True:
            requests = gen.send(answers)
            answers = []
            for rq in requests:
                roots = models.roots(ctx.mu, zeta=np.asarray(rq.zeta, float), modes=rq.modes)
                answers.append(screen_outcome(roots, SQUEAL_LEVEL_DB))
                out.screens += 1
    except StopIteration as stop:
        res = stop.value
    out.end = res.end
    for st in res.steps:
        if st.mode is not None and math.isfinite(st.zeta_hi):
            out.modes.append((ctx.label(st.mode), float(w["f"][st.mode]), float(st.zeta_nominal), float(st.zeta_hi)))
    if confirm and out.modes and res.zeta is not None:
        out.confirm = models.simulate(ctx.mu, zeta=res.zeta)
    return out
