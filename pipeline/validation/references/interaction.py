"""The in-memory cases of the interaction checks (tests/interaction/, the validation writers,
benchmarks/), independent of the pipeline's greens stage:

* ``default_contact(mu)``: the contact of the default case (build/cases/default/contact.npz, a
  friction curve at another mu through the case's curve cache) when it exists, else ``hertz_contact``: an analytic Hertzian table F3 = K approach^1.5, a
  constant compliance and a smooth friction curve of the same size (65 kN, mu_RF reaching mu
  near s = 0.1 m/s);
* ``c20_modes(select)``: the C20's modal data at y^W = -32 mm (``references.greens.wheel_case``: the
  built artifact, else the synthetic Table 4.1 set) with the damping rule [4.11];
* ``beam_kernel(dt, v)``: the rail as the analytic beams on a damped foundation of
  ``references.greens`` (moving Green's function, solvers.greens.kernels.moving_green);
* ``bv50_kernel(dt, v)``: the rail's moving Green's function from the built BV50 rail
  (build/rails/bv50/rail.npz: transfer receptances G(x, f) on 200 distances x 1000 log-spaced
  frequencies 25 Hz - 6.5 kHz, interpolated bilinearly in x and f onto Kropp's grid; zero
  above 6.5 kHz, held at the 25 Hz value below -- a test kernel: pipeline/stages/greens.py
  evaluates the exact wave sum up to 9 kHz and rolls it off smoothly above 6.5 kHz; the
  interaction report compares the two).
"""
from __future__ import annotations

import numpy as np

from solvers.constants import F_MAX_HZ

from solvers.timeloop.interaction import ContactModel, WheelModes, contact_model

from pipeline.store.paths import ROOT
from solvers.contact.friction import monotone_slopes
from pipeline.caches.friction_curves import with_curves
from pipeline.validation.references.greens import wheel_case, beam_transfer
from solvers.greens.kernels import moving_green
from solvers.contact.norm import table_force

CONTACT = ROOT / "build" / "cases" / "default" / "contact.npz"
RAIL = ROOT / "build" / "rails" / "bv50" / "rail.npz"
DT = 36e-6
V = 50 / 3.6
PRELOAD = 65e3
GAMMA_Y = -0.014
MU = 0.35


def hertz_contact(mu: float = MU, F_L: float = PRELOAD) -> ContactModel:
    """Analytic stand-in for the default contact: Hertz F3 = K a^1.5 with the static approach of
    the C20/BV50 case (97 um at 65 kN), compliance 1.2e-9 m/N, and mu_RF(s) = mu (1 - (1 - s/s_sat)^3)
    up to s_sat = 0.1 m/s (Hermite nodes)."""
    a0 = 9.7e-5
    K = F_L / a0 ** 1.5
    xs = np.linspace(0.0, 2 * a0, 41)
    F = K * xs ** 1.5
    s_sat = 0.1
    s = np.concatenate([np.linspace(0.0, s_sat, 19), [0.2, 0.7]])
    m = np.where(s < s_sat, mu * (1 - (1 - s / s_sat) ** 3), mu)
    return ContactModel(xs, F ** (2 / 3), np.full(41, 1.26e-9), np.full(41, 1.15e-9), s, m, monotone_slopes(s, m),
                        float(mu), F)


def default_contact(mu: float = MU) -> ContactModel:
    """The default case's contact at friction ``mu``: its curve from contact.npz (the case's own mu) or from
    the case's friction-curve cache (``pipeline.caches.friction_curves.with_curves``: built on the artifact's
    static contact once, then read); ``hertz_contact`` without the artifact."""
    if CONTACT.exists():
        with np.load(CONTACT) as d:
            return contact_model(with_curves("default", d, [mu]), mu)
    return hertz_contact(mu)


def c20_modes(select=None, zeta_override: dict | None = None) -> tuple[WheelModes, dict]:
    """C20 modal data at y^W = -32 mm; ``select``: indices to keep (None: all)."""
    w = wheel_case(-0.032)
    idx = np.arange(len(w["f_hz"])) if select is None else np.asarray(select)
    zeta = np.array(w["zeta"], float)
    for k, z in (zeta_override or {}).items():
        zeta[k] = z
    return WheelModes(w["f_hz"][idx], w["modal_mass"][idx], zeta[idx], w["phi"][idx]), w


def beam_kernel(dt: float = DT, v: float = V, n_lags: int | None = None, n_t: int | None = None) -> np.ndarray:
    """Moving Green's function of the analytic beams (references.greens) for the step dt: 36 ms of lags,
    N_t dt = 147 ms."""
    n_lags = n_lags or int(round(1000 * DT / dt))
    n_t = n_t or int(round(4096 * DT / dt))
    return moving_green(beam_transfer(), v, dt, n_lags, n_t)


def bv50_transfer(y_rail: float = 0.012, f_max: float = F_MAX_HZ):
    """transfer(x, f) -> (nx, nf, 2, 2) of the built BV50 rail at the head point y_rail (bilinear
    interpolation of the stored receptances, see the module notes)."""
    with np.load(RAIL) as d:
        ip = int(np.argmin(np.abs(d["point_y_m"] - y_rail)))
        G = d["G"][ip]                      # (nx, nf, 2, 2)
        xg, fg = d["x_m"], d["f_hz"]

    def transfer(x, f):
        x = np.abs(np.atleast_1d(np.asarray(x, float)))
        f = np.atleast_1d(np.asarray(f, float))
        if x.max() > xg[-1]:
            raise ValueError("distance beyond the stored transfer receptances")
        j = np.clip(np.searchsorted(xg, x) - 1, 0, len(xg) - 2)
        tx = (x - xg[j]) / (xg[j + 1] - xg[j])
        Gx = (1 - tx)[:, None, None, None] * G[j] + tx[:, None, None, None] * G[j + 1]      # (nx, nfg, 2, 2)
        fc = np.clip(f, fg[0], fg[-1])
        k = np.clip(np.searchsorted(fg, fc) - 1, 0, len(fg) - 2)
        tf = (fc - fg[k]) / (fg[k + 1] - fg[k])
        out = (1 - tf)[None, :, None, None] * Gx[:, k] + tf[None, :, None, None] * Gx[:, k + 1]
        out[:, f > f_max] = 0.0
        return out

    return transfer


def bv50_kernel(dt: float = DT, v: float = V, y_rail: float = 0.012, n_lags: int | None = None,
                n_t: int | None = None) -> np.ndarray:
    """Moving Green's function of the built BV50 rail: N_t dt = 0.295 s (df = 3.4 Hz, as the greens
    stage at 36 us) and 2048 lags (74 ms, 1 m of travel) at dt = 36 us, scaled with dt."""
    n_lags = n_lags or int(round(2048 * DT / dt))
    n_t = n_t or int(round(8192 * DT / dt))
    return moving_green(bv50_transfer(y_rail), v, dt, n_lags, n_t)


# ------------------------------------------------------------------------------ linear stability

def contact_stiffness(contact: ContactModel, approach: float) -> float:
    """dF3/d(approach) of the NORM table at the given approach (central difference)."""
    h = 1e-6 * approach
    return (table_force(approach + h, contact.xi3_nodes, contact.q_nodes)
            - table_force(approach - h, contact.xi3_nodes, contact.q_nodes)) / (2 * h)


def rail_point_receptance(y_rail: float = 0.012):
    """G^R(x = 0, f) -> (2, 2) of the built BV50 rail (linear interpolation in f)."""
    with np.load(RAIL) as d:
        ip = int(np.argmin(np.abs(d["point_y_m"] - y_rail)))
        fg, G0 = d["f_hz"], d["G"][ip, 0]

    def R(f):
        return np.array([[np.interp(f, fg, G0[:, i, j].real) + 1j * np.interp(f, fg, G0[:, i, j].imag)
                          for j in range(2)] for i in range(2)])

    return R


def single_mode_growth(wheel: WheelModes, R, kc: float, mu: float, sign_F2: float = 1.0) -> np.ndarray:
    """Linear growth rates (1/s) of the lightly damped wheel modes in full slip (F2 = sign mu F3),
    one mode at a time (frequency-domain estimate, independent of the time loop).

    Near mode r the closed loop is m_r (w_r^2 - W^2 + 2 i zeta_r w_r W) + kappa_r k_eff(W) = 0 with
    kappa_r = Phi_r3 (Phi_r3 + sign mu Phi_r2) and the dynamic contact stiffness
    k_eff = 1 / (1/kc + Y33 + sign mu Y32), Y = (wheel without mode r) + rail (R(f) at x = 0),
    so sigma_r = -zeta_r w_r - kappa_r Im(k_eff) / (2 m_r w_r) (exp(i W t) convention: Im k_eff > 0
    for a passive support; kappa_r < 0 destabilises)."""
    f_r, m_r, z_r, P = (np.asarray(a, float) for a in wheel)
    out = np.full(len(f_r), np.nan)
    for r in range(len(f_r)):
        if z_r[r] >= 0.5:
            continue
        W = 2 * np.pi * f_r[r]
        h = 1.0 / (m_r * ((2 * np.pi * f_r) ** 2 - W ** 2 + 2j * z_r * 2 * np.pi * f_r * W))
        h[r] = 0.0
        Y = np.einsum("r,ri,rj->ij", h, P, P) + R(f_r[r])
        keff = 1.0 / (1.0 / kc + Y[1, 1] + sign_F2 * mu * Y[1, 0])
        kap = P[r, 1] ** 2 + sign_F2 * mu * P[r, 0] * P[r, 1]
        out[r] = -z_r[r] * W - kap * keff.imag / (2 * m_r[r] * W)
    return out


def decay_rates(x, dt: float, freqs, t0: float = 1.0, window: float = 0.2):
    """Exponential rates (1/s) of the components of x near each frequency: complex demodulation
    at the spectral peak within +-1 % of f (Hann windows of ``window`` s, no overlap, from t0), a
    least-squares line through log|A|.  Returns (rates, peak frequencies)."""
    x = np.asarray(x, float) - np.mean(x)
    n0, nw = int(round(t0 / dt)), int(round(window / dt))
    nb = (len(x) - n0) // nw
    w = np.hanning(nw)
    t = np.arange(nw) * dt
    rates, fpk = [], []
    seg = x[n0:n0 + nw * nb].reshape(nb, nw)
    spec = np.abs(np.fft.rfft(x[n0:] * np.hanning(len(x) - n0)))
    fgrid = np.fft.rfftfreq(len(x) - n0, dt)
    for f in freqs:
        sel = (fgrid > 0.99 * f) & (fgrid < 1.01 * f)
        f0 = fgrid[sel][np.argmax(spec[sel])]
        A = np.abs((seg * w) @ np.exp(-2j * np.pi * f0 * t))
        tc = t0 + (np.arange(nb) + 0.5) * window
        rates.append(np.polyfit(tc, np.log(A), 1)[0])
        fpk.append(f0)
    return np.array(rates), np.array(fpk)


def reduced_squealer(dt: float = DT) -> tuple[WheelModes, np.ndarray]:
    """A reduced, squealing model: the C20's (2,0,a) and (3,0,a) modes with their real shapes at
    the -5 mm position's contact point (y^W = -5 mm, where Phi_3/Phi_2 = -0.07 .. -0.06 and the
    friction coupling destabilises both for F2 > 0: kappa = Phi_3 (Phi_3 + mu Phi_2) < 0),
    zeta = 1e-4 [4.11], on the analytic beam rail (kernel rebuilt for dt).  The contact tables
    are the default case's (a test model, not a case)."""
    w = wheel_case(-0.005)
    n, m, cls = w["n"], w["m"], w["cls"]
    sel = [int(np.flatnonzero((n == k) & (m == 0) & (cls == "a"))[0]) for k in (2, 3)]
    return WheelModes(w["f_hz"][sel], w["modal_mass"][sel], w["zeta"][sel], w["phi"][sel]), beam_kernel(dt)
