"""Frequency-domain stability screen: the time loop linearised about steady rolling.

The squeal time loop (``solvers.timeloop.interaction``, SPEC 3.5, 4.1-4.4) is a discrete-time
system.  About its steady rolling state (preload F3, rigid slip w2 = gamma_y v; first with
gamma_x = 0, so F1 = 0 throughout, both directions below) every part of it is linear in the deviations
but the friction curve and the NORM table, and those two are linearised:

* structures, [4.13]-[4.15]: xi[n] = sum_{k>=1} (g^R_mov[k] + g^W[k]) dF[n-k], with
  xi = xi^R - xi^W on directions (2, 3).  In the z domain xi = Y(z) dF with
  Y(z) = sum_k g[k] z^-k; the wheel part is the exact transform of the recursive
  modal filters (one pole pair per mode), the rail part the finite sum over the
  moving kernel's lags;
* normal contact [4.19]-[4.24]: dF3 = -k_c dxi3 (k_c = dF3/d approach of the NORM
  table at the static approach);
* tangential point contact [4.25]-[4.31] with s2 < 0 (gamma_y < 0, F2 > 0):
  F2 = mu_RF(|s2|) F3, s2 = gamma_y v + (A2 (F2[n] - F2[n-1]) + xi2[n] - xi2[n-1]) / dt, so
  dF2 = mu0 dF3 - q (A2 dF2 + F2 A2' dF3 / k_c + dxi2) with q = F3 mu_RF'(s0) (1 - z^-1) / dt
  (mu0 = mu_RF(s0), s0 = |gamma_y| v; in full slip mu_RF' = 0 and dF2 = mu0 dF3); the time loop's
  compliance A2 follows the approach (the patch grows with F3), hence the A2' = dA2/d approach term
  with F2 = mu0 F3.

So M(z) dF = 0 with

    M = [[1 + q A2 + q Y22,   -mu0 + q (Y23 + mu0 F3 A2' / k_c)],
         [k_c Y32,             1 + k_c Y33 ]]

and the closed-loop poles are the roots z = exp(s dt) of D(s) = det M.  In full
slip D = 1 + k_c (Y33 + mu0 Y32): the single-mode estimate of the interaction
validation (kappa_r = Phi3 (Phi3 + mu Phi2) < 0 destabilises) is its one-mode limit.

Both tangential directions (traction gamma_x, spin: ``linearise(..., gamma_x=, spin=)``).  With
the steady slip w = (gamma_x + L1 phi, gamma_y + L2 phi) v (spin phi as the point contact's
equivalent creepages, ``solvers.contact.spin``), sigma0 = |w|, e = w / sigma0 (e2 < 0), the force
F_tau = -F3 mu_RF(sigma) s_tau / sigma linearises to dF = -mu0 e dF3 - K ds with

    K = F3 [mu_RF'(sigma0) e e^T + (mu0 / sigma0) (I - e e^T)]

(along the slip the curve's slope, a falling curve's negative one feeding energy in; across it
the direction's stiffness mu0 / sigma0 > 0), ds_tau = D (A_tau dF_tau + F0_tau A_tau' dF3 / k_c +
delta_tau2 dxi2), D = (1 - z^-1) / dt, and no structural motion in direction 1 (the loop has
none).  Eliminating dF1 (its row has no structure: 1 + K11 D A1 is a contact-only factor, a real
pole z in (0, 1)) leaves a 2x2 M whose first row is the one above with the Schur complement
terms; for e1 = 0 (gamma_x = 0, a symmetric patch) K is diagonal and M is the matrix above.

Roots.  Near each lightly damped wheel mode r: the secant method on D times mode r's
pole pair (regular at the open-loop pole), started at the pole, with the rest of Y
(the other modes and the rail) expanded to first order about the pole (``Basis``:
computed once per structure, shared by every friction, creepage and contact
stiffness), then polished on the exact D.  The low-frequency roots of the wheelset
on the track (20-400 Hz): local minima of |D| on a grid of s (the rail's transform
along a line of constant sigma is one FFT of g[k] exp(-sigma k dt)), refined on the
exact D.  Below sigma ~ -30/s the finite kernel's transform amplifies its truncated
tail, so strongly damped track roots are not sought.  Growth rate sigma = Re s (1/s),
frequency Im s / 2 pi.
"""
from __future__ import annotations


import numpy as np

from solvers.stability.characteristic import (LinearModel, Root, _det, _det2, _filter, _modal_terms,  # noqa: F401
                                              _outer, _secant, _wheel_z, characteristic, rail_receptance_z,
                                              wheel_receptance_z)
from solvers.stability.nyquist import Contour, certify as certified


class Basis:
    """The structures' transforms, computed once and shared by every operating point (friction,
    creepage, contact stiffness): per lightly damped mode r the rest of Y (other modes + rail)
    and its s-derivative at mode r's open-loop pole; Y on the low-frequency grid."""

    def __init__(self, model: LinearModel, f_lo: float = 20.0, f_hi: float = 400.0, sigma_lo: float = -20.0,
                 sigma_hi: float = 400.0):
        self.model, self.filt = model, _filter(model)
        self.f_lo, self.f_hi, self.sigma_lo, self.sigma_hi = f_lo, f_hi, sigma_lo, sigma_hi
        dt, g = model.dt, model.rail_kernel
        self.modes = np.flatnonzero(np.asarray(model.zeta) < 0.5)
        self.s0 = np.log(self.filt.z[self.modes]) / dt
        k = np.arange(1, g.shape[0]) * dt
        E = np.exp(-np.outer(self.s0, k))                          # z^-k at each pole
        G = g[1:].reshape(len(k), 4)
        self.rail0 = (E @ G).reshape(-1, 2, 2)
        self.rail1 = (-(E * k) @ G).reshape(-1, 2, 2)              # d/ds sum g[k] exp(-s k dt)
        z0 = np.exp(self.s0 * dt)
        with np.errstate(divide="ignore", invalid="ignore"):             # mode r's own pole, dropped below
            h = _modal_terms(self.filt, z0)
            dh = (_modal_terms(self.filt, np.exp((self.s0 + 1e-3) * dt)) - h) / 1e-3
        ww = np.einsum("ri,rj->rij", self.filt.w_out, self.filt.w_in)
        for a, r in enumerate(self.modes):                          # drop mode r from its own rest
            h[a, r] = dh[a, r] = 0.0
        self.rest0 = np.einsum("ar,rij->aij", h, ww) + self.rail0
        self.rest1 = np.einsum("ar,rij->aij", dh, ww) + self.rail1
        self.ww, self.z0 = ww, z0
        self._grid()

    def _grid(self):
        m = self.model
        g = m.rail_kernel.copy()
        g[0] = 0.0
        n_fft = 1 << int(np.ceil(np.log2(max(len(g), 1.0 / (2.0 * m.dt)))))
        fb = np.fft.fftfreq(n_fft, m.dt)
        cols = np.flatnonzero((fb >= self.f_lo) & (fb <= self.f_hi))
        sg = np.arange(self.sigma_lo, self.sigma_hi + 1e-9, 10.0)
        kk = np.arange(len(g))
        self.S = sg[:, None] + 2j * np.pi * fb[cols][None, :]
        self.Z = np.exp(self.S * m.dt)
        Yr = np.stack([np.fft.fft(g * np.exp(-s * kk * m.dt)[:, None, None], n=n_fft, axis=0)[cols] for s in sg])
        Yw = np.einsum("pr,rij->pij", _modal_terms(self.filt, self.Z.ravel()), self.ww).reshape(*self.Z.shape, 2, 2)
        self.Ygrid = Yr + Yw


def wheel_roots(model: LinearModel, basis: Basis | None = None, polish: bool = True) -> list[Root]:
    """The closed-loop pole continuing each lightly damped wheel mode (zeta < 0.5)."""
    b = basis if basis is not None else Basis(model)
    out = []
    for a, r in enumerate(b.modes):
        zr, ww = b.filt.z[r], b.ww[r]

        def fun(s, exact=False, a=a, r=r, zr=zr, ww=ww):
            z = np.exp(s * model.dt)
            pp = (z - zr) * (z - np.conj(zr))
            hr = (zr * (z - np.conj(zr)) - np.conj(zr) * (z - zr)) / 2j      # mode r's term times pp
            rest = (_wheel_z(b.filt, z, skip=r) + rail_receptance_z(model.rail_kernel, z) if exact
                    else b.rest0[a] + b.rest1[a] * (s - b.s0[a]))
            return _det(model, pp * rest + hr * ww, z, pp) / pp              # = pp D(s): regular at the pole
        s = _secant(fun, complex(b.s0[a]) + complex(1e-3, 1e-3))
        if s is not None and polish:
            s = _secant(lambda x: fun(x, True), s)
        if s is not None and abs(s.imag - b.s0[a].imag) < 0.2 * abs(b.s0[a].imag) + 2 * np.pi * 5:
            out.append(Root(s.imag / (2 * np.pi), s.real, int(r)))
    return out


def track_roots(model: LinearModel, basis: Basis | None = None, polish: bool = True) -> list[Root]:
    """Closed-loop poles of the wheelset on the track inside the basis' (f, sigma) window; without
    ``polish`` one Newton step on the grid's values (D and its s-derivative by central differences
    along the frequency axis, D being analytic) instead of the secant on the exact D."""
    b = basis if basis is not None else Basis(model)
    from scipy.ndimage import minimum_filter  # lazy: brings in scipy

    D = _det(model, b.Ygrid, b.Z)
    L = np.log(np.abs(D))
    cand = L <= minimum_filter(L, size=3, mode="nearest")
    cand[:, [0, -1]] = False
    fun = lambda s: characteristic(model, s, b.filt)                                     # noqa: E731
    found = []
    for i, j in zip(*np.nonzero(cand)):
        if polish:
            s = _secant(fun, complex(b.S[i, j]), max_iter=25)
        else:
            dD = (D[i, j + 1] - D[i, j - 1]) / (b.S[i, j + 1] - b.S[i, j - 1])
            s = complex(b.S[i, j] - D[i, j] / dD)
            if abs(s - b.S[i, j]) > abs(b.S[i, j + 1] - b.S[i, j - 1]) + 10.0:
                s = None
        if (s is not None and b.f_lo <= s.imag / (2 * np.pi) <= b.f_hi
                and b.sigma_lo - 5 <= s.real <= b.sigma_hi and all(abs(s - t) > 1e-4 * abs(s) for t in found)):
            found.append(s)
    return [Root(s.imag / (2 * np.pi), s.real, -1) for s in sorted(found, key=lambda s: s.imag)]


def screen(model: LinearModel, basis: Basis | None = None, polish: bool = True,
           certify: bool | None = None) -> list[Root]:
    """All closed-loop poles the screen seeks, fastest growing first.  ``certify`` (default: with
    ``polish``): the growing ones certified by the argument principle, the missed ones added
    (``solvers.stability.nyquist``; the map's fast path, polish=False, keeps the search alone)."""
    b = basis if basis is not None else Basis(model)
    wheel = wheel_roots(model, b, polish)
    # a track root found again at a wheel root (the grid also sees the modes between 20 and 400 Hz)
    track = [t for t in track_roots(model, b, polish)
             if all(abs(complex(t.sigma, t.f_hz) - complex(w.sigma, w.f_hz)) > 1e-3 * w.f_hz + 0.5 for w in wheel)]
    roots = sorted(wheel + track, key=lambda r: -r.sigma)
    if not (polish if certify is None else certify):
        return roots
    if getattr(b, "contour", None) is None:
        b.contour = Contour(model, b.filt)                          # the structure's part, shared by operating points
    return certified(model, roots, b.contour)[0]


def operating_point(model: LinearModel, contact, *, v: float, gamma_y: float, gamma_x: float = 0.0,
                    spin: float = 0.0, spin_length=(0.0, 0.0)) -> LinearModel:
    """``model`` at another friction curve / creepage: mu0, dmu from ``contact``'s curve at the
    steady slip |w|, w = (gamma_x + L1 spin, gamma_y + L2 spin) v, and its direction (the
    structures, k_c and the compliances kept; module notes)."""
    from solvers.contact.friction import mu_and_slope  # lazy: brings in rocket_fft, scipy

    w1 = (gamma_x + spin_length[0] * spin) * v
    w2 = (gamma_y + spin_length[1] * spin) * v
    sigma0 = float(np.hypot(w1, w2))              # (the lateral slip is taken as negative: F2 > 0)
    mu0, dmu = mu_and_slope(sigma0, contact.s_nodes, contact.mu_nodes, contact.slopes)
    return model._replace(mu0=float(mu0), dmu=float(dmu), e1=float(w1 / sigma0) if sigma0 > 0 else 0.0, sigma0=sigma0)


def linearise(wheel, rail_kernel: np.ndarray, contact, *, dt: float, v: float, gamma_y: float,
              preload: float, gamma_x: float = 0.0, spin: float = 0.0) -> LinearModel:
    """The LinearModel of the time loop's steady rolling state.

    wheel: ``interaction.WheelModes``; rail_kernel: the moving Green's function (K, 2, 2);
    contact: ``interaction.ContactModel``; dt (s), v (m/s), gamma_y (< 0), preload F3 (N),
    gamma_x, spin (1/m) as in the time loop."""
    from solvers.contact.compliance import table_compliance  # lazy: brings in scipy
    from solvers.contact.norm import table_force  # lazy: brings in scipy
    from solvers.timeloop.interaction import static_approach  # lazy: brings in rocket_fft, scipy
    from solvers.timeloop.driver import spin_length  # lazy: brings in rocket_fft, scipy

    if gamma_y >= 0:
        raise ValueError(f"linearise: gamma_y = {gamma_y} must be negative (F2 > 0 on the rail)")
    app = static_approach(contact, preload)
    h = 1e-6 * app
    kc = (table_force(app + h, contact.xi3_nodes, contact.q_nodes)
          - table_force(app - h, contact.xi3_nodes, contact.q_nodes)) / (2 * h)
    A = [table_compliance(app, contact.xi3_nodes, n) for n in (contact.A1_nodes, contact.A2_nodes)]
    dA = [(table_compliance(app + h, contact.xi3_nodes, n) - table_compliance(app - h, contact.xi3_nodes, n)) / (2 * h)
          for n in (contact.A1_nodes, contact.A2_nodes)]
    base = LinearModel(np.asarray(wheel.f_r, float), np.asarray(wheel.modal_mass, float),
                       np.asarray(wheel.zeta, float), np.asarray(wheel.phi, float),
                       np.asarray(rail_kernel, float), float(dt), float(kc), 0.0, 0.0, float(preload), float(A[1]),
                       float(dA[1]), float(A[0]), float(dA[0]))
    L = spin_length(contact, app, v) if spin != 0.0 else (0.0, 0.0)
    return operating_point(base, contact, v=v, gamma_y=gamma_y, gamma_x=gamma_x, spin=spin, spin_length=L)
