"""Output of the time loop: the buffers the loop records into, the ``InteractionResult`` built
from them, and the squeal measures [6.3]-[6.4] of a force history (SPEC 6)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numba
import numpy as np

from solvers.spectra import amplitude_spectrum, dominant_frequency, force_level
from solvers.timeloop.stop import STOP_REASONS, Windows

# columns of the stored histories
COLUMNS = ("F1", "F2", "F3", "s1", "s2", "xi2", "xi3", "state")


class Record(NamedTuple):
    """Where the loop records a run; the arrays are WRITTEN in place by the loop.
    store_every: decimation of hist; hist (ceil(n_steps / store_every), 8): every store_every-th
    step (columns ``COLUMNS``); fin (n_final, 8): ring of the last n_final steps at full rate;
    counters (4,) int: Newton iterations, max per step, bisection fallbacks, steps without contact."""
    store_every: int
    hist: np.ndarray
    fin: np.ndarray
    counters: np.ndarray


def record(n_steps: int, n_final: int, store_every: int) -> Record:
    """Empty buffers for a run of at most n_steps steps."""
    return Record(int(store_every), np.zeros(((n_steps + store_every - 1) // store_every, 8)),
                  np.zeros((n_final, 8)), np.zeros(4, np.int64))


@numba.njit(cache=True)
def store(n, row, rec):
    """Record step n (``row`` (8,)): every store_every-th step into rec.hist, every step into the
    ring rec.fin."""
    hist = rec.hist
    fin = rec.fin
    if n % rec.store_every == 0:
        j = n // rec.store_every
        if j < hist.shape[0]:
            for c in range(row.shape[0]):
                hist[j, c] = row[c]
    nf = fin.shape[0]
    if nf > 0:
        j = n % nf
        for c in range(row.shape[0]):
            fin[j, c] = row[c]


@dataclass
class InteractionResult:
    """Histories of a run (SI units).  Forces on the rail F (n, 3) = (F1, F2, F3) [N]; slip of the
    rail relative to the wheel (s1, s2) [m/s] (point model: the global slip of [4.29]-[4.30];
    Kalker: the mean over the contact elements, zero in stick); xi (n, 2) = xi^R - xi^W, the
    dynamic relative displacement (deviation from the reference state) in directions 2, 3 [m];
    state: 0 no contact, 1 partial slip (point model: mu_RF(s) < 0.99 of its plateau; Kalker:
    some elements stick), 2 full slip.
    ``t, F, slip, xi, state``: every ``store_every``-th step; ``*_final``: the last ``final`` s at
    full rate (all of the run if shorter)."""
    dt: float
    v: float
    t: np.ndarray
    F: np.ndarray
    slip: np.ndarray
    xi: np.ndarray
    state: np.ndarray
    t_final: np.ndarray
    F_final: np.ndarray
    slip_final: np.ndarray
    xi_final: np.ndarray
    state_final: np.ndarray
    n_steps: int
    stop_reason: str
    F_ref: np.ndarray
    xi3_static: float
    windows: np.ndarray           # per window: t_end, mean F2, rms F2, zero-crossing freq of F2, rms F3
    newton: dict
    lost_steps: int
    wall: float
    settings: dict = field(default_factory=dict)
    dt_final: float = 0.0         # sample interval of the *_final arrays (dt, or store_every dt without them)

    @property
    def duration(self) -> float:
        return self.n_steps * self.dt

    def measures(self, final: float | None = None, f_min: float = 20.0) -> dict:
        """Squeal measures [6.3]-[6.4] over the final stretch (the full-rate part, or its last
        ``final`` s): see ``squeal_measures``."""
        F = self.F_final
        h = self.dt_final or self.dt
        if final is not None:
            F = F[-max(1, int(round(final / h))):]
        out = squeal_measures(F[:, 1], h, f_min=f_min)
        out.update(F3_mean=float(F[:, 2].mean()), F3_rms=float(F[:, 2].std()),
                   contact_loss_share=float(np.mean(self.state_final == 0)),
                   stop_reason=self.stop_reason, t_end=self.duration)
        return out


def squeal_measures(F2, dt: float, f_min: float = 20.0) -> dict:
    """L_F2 = 20 log10(rms(F2 - mean) / 1 N) [6.3]-[6.4] and the dominant frequency of F2
    (largest peak above f_min of the Hann-windowed amplitude spectrum, ``solvers.spectra``) of
    the given stretch sampled at dt [s].  L_F2 = -inf for a constant force."""
    F2 = np.asarray(F2, float)
    L = force_level(F2)
    out = {"L_F2": L, "F2_mean": float(F2.mean()), "F2_rms": float(F2.std()), "F2_pp": float(np.ptp(F2)),
           "f_dominant": float("nan"), "F2_amplitude": 0.0}
    if np.isfinite(L) and F2.size > 8:
        f, X = amplitude_spectrum(F2, dt)
        fd, amp = dominant_frequency(f, X, f_min=f_min)
        out["f_dominant"], out["F2_amplitude"] = fd, amp
    return out


def assemble(rec: Record, win: Windows, done: int, reason: int, p, wall: float, settings: dict) -> InteractionResult:
    """The result of a run of ``done`` steps that stopped for ``reason`` (STOP_REASONS), from its
    buffers and its LoopParams ``p`` (with the reference state the run used); wall [s]."""
    hist, fin, counters, store_every, dt = rec.hist, rec.fin, rec.counters, rec.store_every, p.dt
    nh = (done + store_every - 1) // store_every
    h = hist[:nh]
    nf = fin.shape[0]
    if nf:
        m = min(done, nf)
        idx = (np.arange(done - m, done) % nf)
        f = fin[idx]
        tf = np.arange(done - m, done) * dt
    else:
        f = hist[:nh]
        tf = np.arange(nh) * store_every * dt
    win_stats = win.stats
    nwin = int(np.count_nonzero(win_stats[:, 0])) if win_stats.size else 0
    steps = max(done - int(counters[3]), 1)
    return InteractionResult(
        dt=float(dt), v=float(p.v), t=np.arange(nh) * store_every * dt, F=h[:, 0:3].copy(),
        slip=h[:, 3:5].copy(), xi=h[:, 5:7].copy(), state=h[:, 7].astype(np.int8), t_final=tf,
        F_final=f[:, 0:3].copy(), slip_final=f[:, 3:5].copy(), xi_final=f[:, 5:7].copy(),
        state_final=f[:, 7].astype(np.int8), n_steps=int(done), stop_reason=STOP_REASONS[int(reason)],
        F_ref=np.asarray(p.F_ref, float), xi3_static=float(p.xi3_static), windows=win_stats[:nwin].copy(),
        newton={"iterations_mean": float(counters[0]) / steps, "iterations_max": int(counters[1]),
                "bisections": int(counters[2])},
        lost_steps=int(counters[3]), wall=wall, settings=settings,
        dt_final=float(dt if nf else store_every * dt))
