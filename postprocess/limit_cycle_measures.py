"""What bounds a squeal limit cycle of the point-contact time loop (issue 28): measures of the
recorded slip, forces and contact state over the limit cycle, set against the regularized friction
curve mu_RF(s) (SPEC 4.4, thesis [4.36]-[4.37]) and the wheel's free modes.

The three candidate bounds, each a number here:

* saturation: the limit cycle's slip magnitude dips from the steady slip s0 = |gamma_y| V down to
  the knee s_k of mu_RF (where it reaches ``FULL_SLIP`` of its plateau; below it the curve rises
  with slope mu_RF' F3 ~ 1e5-1e6 N s/m, a strong damper on the lateral motion), so the swing of
  the slip below s0 is bounded by the margin s0 - s_k;
* slip reversal: the lateral slip changes sign (s2 >= 0 for gamma_y < 0);
* contact loss: F3 reaches 0.

Pure functions on arrays (SI units).
"""
from __future__ import annotations

import numpy as np

from solvers.contact.friction import mu_rf
from solvers.wheel.receptance import modal_frf

from solvers.radiation.thompson_jones import C0, RHO_AIR

FULL_SLIP = 0.99      # the time loop's full-slip threshold on mu_RF / plateau (solvers.timeloop.inputs)
RHO_C = RHO_AIR * C0  # characteristic impedance of air (kg/m^2/s)


def curve(s, s_nodes, mu_nodes, slopes) -> np.ndarray:
    """mu_RF at the slip velocities ``s`` (m/s, array) as the time loop evaluates it."""
    return np.array([mu_rf(float(x), s_nodes, mu_nodes, slopes) for x in np.ravel(s)]).reshape(np.shape(s))


def knee_slip(s_nodes, mu_nodes, slopes, frac: float = FULL_SLIP) -> float:
    """The smallest slip velocity (m/s) at which mu_RF reaches ``frac`` of its plateau (bisection on
    the monotone curve): the time loop's boundary between partial and full slip."""
    target = frac * float(mu_nodes[-1])
    lo, hi = 0.0, float(s_nodes[-1])
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if mu_rf(mid, s_nodes, mu_nodes, slopes) < target:
            lo = mid
        else:
            hi = mid
    return hi


def sdof_detuning(f: float, f_r: float, zeta: float) -> tuple[float, float]:
    """(detuning in half-power bandwidths (f - f_r) / (zeta f_r), response at f relative to the
    response at resonance in dB: 20 log10(2 zeta / |1 - r^2 + 2 i zeta r|), r = f / f_r) of a
    mode of damping ratio zeta driven by a force of the same amplitude."""
    h = abs(modal_frf(f, np.array([f_r]), np.ones(1), np.array([zeta]))[0, 0])
    h_r = abs(modal_frf(f_r, np.array([f_r]), np.ones(1), np.array([zeta]))[0, 0])
    return (f - f_r) / (zeta * f_r), float(20 * np.log10(h / h_r))


def face_velocity_for_level(L_W: float, sigma: float, area: float) -> float:
    """The rms normal velocity (m/s) averaged over the radiating area ``area`` (m^2) that gives the
    sound power level L_W (dB re 1e-12 W) at radiation efficiency ``sigma``:
    W = rho c sigma S <v^2> (Thompson and Jones' wheel model, thesis sec. 5.1)."""
    return float(np.sqrt(1e-12 * 10 ** (L_W / 10) / (RHO_C * sigma * area)))


def cycle_measures(F, slip, state, dt: float, *, v: float, gamma_y: float, s_nodes, mu_nodes, slopes,
                   xi=None) -> dict:
    """Measures of a limit cycle from the loop's full-rate records over its final stretch.

    F (n, 3) forces on the rail (N); slip (n, 2) = (s1, s2) (m/s); state (n,) 0/1/2 (no contact,
    partial, full slip); dt (s); v (m/s); gamma_y (< 0); the friction curve's arrays; xi (n, 2)
    the dynamic relative displacement (optional: its lateral velocity)."""
    F = np.asarray(F, float)
    s2 = np.asarray(slip, float)[:, 1]
    state = np.asarray(state).astype(int)
    s0 = abs(gamma_y) * v
    sk = knee_slip(s_nodes, mu_nodes, slopes)
    plateau = float(mu_nodes[-1])
    on = F[:, 2] > 0
    ratio = F[on, 1] / (plateau * F[on, 2]) if on.any() else np.array([np.nan])
    mag = np.abs(s2)
    out = {
        "s0": s0, "s_knee": sk, "margin": s0 - sk,
        "s2_min": float(s2.min()), "s2_max": float(s2.max()), "s2_mean": float(s2.mean()),
        "s2_rms": float(s2.std()), "s2_swing_down": float(s0 - mag.min()), "s2_swing_up": float(mag.max() - s0),
        "reversal_share": float(np.mean(s2 * np.sign(gamma_y) < 0)),
        "below_knee_share": float(np.mean(mag < sk)),
        "share_full": float(np.mean(state == 2)), "share_partial": float(np.mean(state == 1)),
        "share_loss": float(np.mean(state == 0)),
        "ratio_min": float(ratio.min()), "ratio_max": float(ratio.max()),
        "F3_min": float(F[:, 2].min()), "F3_max": float(F[:, 2].max()), "F3_mean": float(F[:, 2].mean()),
        "mu_visited_lo": float(curve(mag.min(), s_nodes, mu_nodes, slopes)),
        "mu_visited_hi": float(curve(mag.max(), s_nodes, mu_nodes, slopes)),
        "plateau": plateau,
    }
    if xi is not None:
        vx = np.diff(np.asarray(xi, float)[:, 0]) / dt
        out["xi2_velocity_rms"] = float(vx.std())
    return out


def bound_of(m: dict, min_swing: float = 1e-4, reach: float = 0.95) -> str:
    """Which bound a limit cycle sits on (``cycle_measures``): 'none' without an oscillation (slip
    swing below ``min_swing`` m/s), 'contact loss' when F3 reaches 0, 'slip reversal' when s2
    changes sign, 'saturation' when the slip dips to the knee of mu_RF (onto its rising, damping
    branch: below it, or to within ``reach`` of the margin) with neither, else 'other'."""
    if m["s2_swing_down"] < min_swing:
        return "none"
    if m["share_loss"] > 0 or m["F3_min"] <= 0:
        return "contact loss"
    if m["reversal_share"] > 0:
        return "slip reversal"
    if m["below_knee_share"] > 0 or m["s2_swing_down"] >= reach * m["margin"]:
        return "saturation"
    return "other"
