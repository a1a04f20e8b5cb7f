"""The screen's growing poles certified by the argument principle (issue 34).

``solvers.stability`` seeks each wheel mode's closed-loop pole by the secant method from the
open-loop pole.  That search can end anywhere: at r300/a2o ((6,0,a)), y25_r300/a1i ((4,0,r)) and,
with some kernels' last digits, r300/a1o ((4,0,a) or (5,0,a)) its first-order stage lands at
sigma ~ -200 1/s, where the finite kernel's transform grows as exp(-sigma K dt) ~ e^30, the exact
stage crawls back and stops after a long jump out and back (a tiny step between two iterates with
the same residual) at a point where |D| ~ 2-9: a "root" with sigma = +28 to +114 1/s that is no zero
of D, accepted because the residual test was relative to the huge value at the start.  The secant's
stop test now rejects such points (``stability._secant``); the verdict itself rests on this module:

* Count.  D(z) (``stability._det``; for gamma_x != 0 times the longitudinal row's factor
  c(z) = 1 + K11 A1 (1 - 1/z) / dt, so that P is the full 3 x 3 loop's determinant) has poles only at
  the wheel's modal filter poles p (|p| < 1) and tends to D(inf) != 0 as |z| -> inf (Y -> 0).  So

      P(z) = c(z) D(z) prod_p (1 - p / z)

  is analytic for |z| >= 1 up to infinity, with the closed-loop poles of |z| > 1 (sigma > 0) as
  its zeros, and their number is N = -(1 / 2 pi) Delta arg P around |z| = 1 counter-clockwise
  (the argument principle: Kuttler, Topics in Analysis, sec. 53.1; on the unit circle it is the
  discrete-time Nyquist criterion, Franklin, Powell & Workman 1990, Digital Control of Dynamic
  Systems, 2nd ed.).  P has real coefficients, so the upper half circle suffices:
  N = -Delta arg P (theta: 0 -> pi) / pi.  Dividing the poles out leaves no
  pole-zero pair inside one sampling step of the circle (an unstable mode's pole inside and zero
  outside would turn the phase by 2 pi between two samples, invisibly).  Samples: the rail's
  transform by one FFT (``N_FFT``), every step of the phase above ``MAX_STEP`` subdivided
  (``SUBDIV`` points, ``MAX_DEPTH`` times).
* Roots.  Each secant root with sigma > 0 is kept only if P winds once around a small circle
  about it; if fewer growing poles are kept than N (a complex pole counts with its conjugate),
  the missing ones are sought by the secant from the minima of |P| along circles |z| = e^(sigma dt)
  (``SIGMA_ROWS``, one FFT each), each kept on the same test.  A kept pole is a secant limit
  (relative step 1e-10) with a certified zero around it.
* Margin.  Rouche's theorem (Kuttler, sec. 53.1, Cor. 53.1.5: |f - g| < |f| on the contour, then f
  and g have as many zeros inside): a perturbation of the rail kernel with |dg[k]_ij| <= eps |g[k]_ij| moves
  D by at most A eps + Q eps^2 on |z| = 1 (A = sum_ij |dD/dY_ij| B_ij, Q the same with the mixed
  second derivatives, B_ij = sum_k |g[k]_ij|: D is affine in each Y_ij), so N is the same for every
  such kernel while A eps + Q eps^2 < |D| on the circle: ``eps_kernel`` (the smallest such eps over
  the samples) is the verdict's stated margin against the kernel's digits.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from solvers.stability.characteristic import Root, _det, _filter, _modal_terms, _outer, _secant

N_FFT = 1 << 16          # samples of the full circle for the rail's transform (theta step 9.6e-5 rad, 0.42 Hz at 36 us)
MAX_STEP = np.pi / 4     # largest phase step of P between neighbouring samples
SUBDIV = 16              # sub-intervals of a step above MAX_STEP
MAX_DEPTH = 8            # refinements (a step of 2.4e-5 rad down to 5.6e-15 rad)
SIGMA_ROWS = (0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0)   # 1/s: circles of the search for missed poles
SMALL = 1e-3             # relative radius of the circle about a root (times |s|, at most sigma / 2)


class Certificate(NamedTuple):
    n_unstable: int          # closed-loop poles with sigma > 0 (a complex pair counts 2)
    n_found: int             # of them located (certified zeros)
    eps_kernel: float        # Rouche margin: relative kernel perturbation that cannot change n_unstable
    min_abs_d: float         # min |D| on |z| = 1
    resolved: bool           # every phase step below MAX_STEP after refinement
    samples: int             # evaluations of P on the circle


def _pole_pairs(filt) -> np.ndarray:
    """(M, 2) poles of every mode's filter (kind 0: z, z*; kind 1: the two real poles)."""
    p = np.empty((len(filt.kind), 2), complex)
    k0 = filt.kind == 0
    p[k0, 0], p[k0, 1] = filt.z[k0], np.conj(filt.z[k0])
    p[~k0, 0], p[~k0, 1] = filt.z[~k0].real, filt.p2[~k0].real
    if np.any(np.abs(p) >= 1.0):
        raise ValueError("the screen's count needs damped wheel modes (every |pole| < 1)")
    return p.ravel()


def _contact_factor(model, z):
    """c(z) of the longitudinal row (module notes); 1 when it decouples (e1 = 0)."""
    m = model
    if m.e1 == 0.0:
        return np.ones_like(z)
    g = m.mu0 / m.sigma0
    K11 = m.F3 * (m.dmu * m.e1 * m.e1 + g * (1.0 - m.e1 * m.e1))
    return 1.0 + K11 * m.A1 * (1.0 - 1.0 / z) / m.dt


class Contour:
    """What the count needs of one structure (kernel and wheel), for any operating point: Y and the
    poles' factor on the FFT samples of the upper half circle, the kernel's bounds B_ij."""

    def __init__(self, model, filt=None):
        self.filt = filt if filt is not None else _filter(model)
        g = np.asarray(model.rail_kernel, float).copy()
        g[0] = 0.0
        self.g, self.dt = g, model.dt
        self.theta = 2 * np.pi * np.arange(N_FFT // 2 + 1) / N_FFT
        self.z = np.exp(1j * self.theta)
        self.poles = _pole_pairs(self.filt)
        self.ww = _outer(self.filt)
        self.B = np.abs(g[1:]).sum(axis=0).reshape(4)
        self.Y = np.fft.rfft(g, n=N_FFT, axis=0) + self.wheel(self.z)      # sum_k g[k] z^-k: FFT on |z| = 1
        self.W = self.pole_factor(self.z)

    def wheel(self, z):
        return (_modal_terms(self.filt, z) @ self.ww).reshape(-1, 2, 2)

    def pole_factor(self, z):
        out = np.ones(len(z), complex)
        for p in self.poles:
            out *= 1.0 - p / z
        return out

    def rail(self, z, rows: int = 512):
        """sum_k g[k] z^-k at any z (direct sums)."""
        z = np.asarray(z, complex).ravel()
        k = np.arange(len(self.g))
        G = self.g.reshape(len(self.g), 4)
        out = np.empty((len(z), 4), complex)
        for i in range(0, len(z), rows):
            out[i:i + rows] = np.exp(-np.outer(np.log(z[i:i + rows]), k)) @ G
        return out.reshape(-1, 2, 2)

    def structure(self, z):
        return self.rail(z) + self.wheel(z)

    def P(self, model, z, Y=None, W=None):
        """P(z) (module notes) at z (1-D), from Y and the poles' factor when given."""
        Y = self.structure(z) if Y is None else Y
        W = self.pole_factor(z) if W is None else W
        return _contact_factor(model, z) * _det(model, Y, z) * W


def rouche_eps(model, Y, z, B) -> np.ndarray:
    """The largest eps with A eps + Q eps^2 < |D| at each z (module notes)."""
    D0 = _det(model, Y, z)
    E = np.eye(4).reshape(4, 2, 2)
    h = np.where(B > 0, B, 1.0)
    Dp = [_det(model, Y + h[i] * E[i], z) for i in range(4)]
    Dm = [_det(model, Y - h[i] * E[i], z) for i in range(4)]
    A = sum(np.abs(Dp[i] - Dm[i]) / (2 * h[i]) * B[i] for i in range(4))
    Q = np.zeros(len(z))
    for i in range(4):
        for j in range(i + 1, 4):
            Dij = _det(model, Y + h[i] * E[i] + h[j] * E[j], z)
            Q += np.abs(Dij - Dp[i] - Dp[j] + D0) / (h[i] * h[j]) * B[i] * B[j]
    a = np.abs(D0)
    return 2 * a / (A + np.sqrt(A * A + 4 * Q * a))


def winding(fun, t: np.ndarray, values: np.ndarray) -> tuple[float, bool, np.ndarray, np.ndarray]:
    """Delta arg of fun along the path t (sampled values given), every step above MAX_STEP subdivided;
    (total phase change, resolved, the new parameters, their values)."""
    d = np.angle(values[1:] / values[:-1])
    bad = np.abs(d) > MAX_STEP
    total = d[~bad].sum()
    ta, tb, fa, fb = t[:-1][bad], t[1:][bad], values[:-1][bad], values[1:][bad]
    new_t, new_f = [], []
    u = np.linspace(0.0, 1.0, SUBDIV + 1)[1:-1]
    for _ in range(MAX_DEPTH):
        if not len(ta):
            break
        tt = ta[:, None] + (tb - ta)[:, None] * u[None, :]
        ff = fun(tt.ravel()).reshape(tt.shape)
        new_t.append(tt.ravel())
        new_f.append(ff.ravel())
        T = np.concatenate([ta[:, None], tt, tb[:, None]], axis=1)
        F = np.concatenate([fa[:, None], ff, fb[:, None]], axis=1)
        d = np.angle(F[:, 1:] / F[:, :-1])
        bad = np.abs(d) > MAX_STEP
        total += d[~bad].sum()
        ta, tb, fa, fb = T[:, :-1][bad], T[:, 1:][bad], F[:, :-1][bad], F[:, 1:][bad]
    resolved = not len(ta)
    total += np.angle(fb / fa).sum() if len(ta) else 0.0
    cat = (lambda x: np.concatenate(x) if x else np.zeros(0))
    return float(total), resolved, cat(new_t), cat(new_f)


def _winding(model, contour: Contour) -> tuple[float, bool, np.ndarray]:
    """(-Delta arg P / pi on the upper half circle, resolved, the refined angles) (module notes)."""
    c = contour
    P0 = c.P(model, c.z, c.Y, c.W)
    fun = (lambda th: c.P(model, np.exp(1j * th)))
    total, resolved, th, _ = winding(fun, c.theta, P0)
    n = -total / np.pi
    inf = np.array([np.inf])                            # D(inf) != 0: no zero at infinity (module notes)
    p_inf = abs(complex(_contact_factor(model, inf)[0] * _det(model, np.zeros((1, 2, 2)), inf)[0]))
    if abs(n - round(n)) > 1e-3 or not p_inf > 1e-9 * np.median(np.abs(P0)):
        resolved = False
    return n, resolved, th


def no_growing_pole(model, contour: Contour) -> bool:
    """N = 0: no closed-loop pole with sigma > 0, so ``certify`` keeps no growing pole (the count alone,
    without the roots or the Rouche margin: the onset scan's cheap test, ``stability.onset``)."""
    return int(round(_winding(model, contour)[0])) == 0


def count_unstable(model, contour: Contour) -> tuple[int, float, float, bool, int]:
    """(N, eps_kernel, min |D|, resolved, samples) on |z| = 1 (module notes)."""
    c = contour
    n, resolved, th = _winding(model, c)
    zz = np.concatenate([c.z, np.exp(1j * th)])
    Y = np.concatenate([c.Y, c.structure(np.exp(1j * th))]) if len(th) else c.Y
    eps = rouche_eps(model, Y, zz, c.B)
    return int(round(n)), float(eps.min()), float(np.abs(_det(model, Y, zz)).min()), resolved, len(zz)


def is_zero(model, contour: Contour, s: complex) -> bool:
    """P winds once about s on a circle of radius min(SMALL |s|, sigma / 2) (s in the right half plane)."""
    rho = min(SMALL * max(abs(s), 1.0), 0.5 * s.real)
    if rho <= 1e-9 * max(abs(s), 1.0):
        return False
    dt = contour.dt
    phi = np.linspace(0.0, 2 * np.pi, 65)
    fun = (lambda p: contour.P(model, np.exp((s + rho * np.exp(1j * p)) * dt)))
    total, resolved, _, _ = winding(fun, phi, fun(phi))
    return resolved and round(total / (2 * np.pi)) == 1


def _label(filt_f, zeta, f_hz: float) -> int:
    """The wheel mode a pole at f_hz continues: the nearest lightly damped one within the secant's
    window (``stability.wheel_roots``), else -1."""
    idx = np.flatnonzero(np.asarray(zeta) < 0.5)
    if not len(idx):
        return -1
    r = idx[np.argmin(np.abs(filt_f[idx] - f_hz))]
    return int(r) if abs(filt_f[r] - f_hz) < 0.2 * filt_f[r] + 5.0 else -1


def _weight(s: complex, dt: float) -> int:
    """How many poles of the count s stands for: 2 for a complex pole (with its conjugate), 1 on the real axis."""
    return 1 if abs(np.sin(s.imag * dt)) < 1e-9 else 2


def _search(model, contour: Contour, have: list, missing: int) -> list:
    """Up to ``missing`` further certified zeros of P with sigma > 0, by the secant from the minima of
    |P| along circles |z| = e^(sigma dt) (module notes)."""
    c, dt, found = contour, contour.dt, []
    starts = []
    for sg in SIGMA_ROWS:
        r = np.exp(sg * dt)
        z = r * c.z
        Y = np.fft.rfft(c.g * r ** -np.arange(len(c.g))[:, None, None], n=N_FFT, axis=0) + c.wheel(z)
        a = np.abs(c.P(model, z, Y))
        i = np.flatnonzero((a[1:-1] <= a[:-2]) & (a[1:-1] <= a[2:])) + 1
        starts += [(a[j] / np.median(a), complex(sg, c.theta[j] / dt)) for j in i]
    fun = (lambda s: complex(c.P(model, np.array([np.exp(s * dt)]))[0]))
    for _, s0 in sorted(starts, key=lambda q: q[0])[:200]:
        s = _secant(fun, s0)
        if s is None or s.real <= 0 or abs(s.imag) > np.pi / dt:
            continue
        s = complex(s.real, abs(s.imag))
        if any(abs(s - t) <= 1e-6 * abs(t) + 1e-6 for t in have + found) or not is_zero(model, c, s):
            continue
        found.append(s)
        missing -= _weight(s, dt)
        if missing <= 0:
            break
    return found


def certify(model, roots: list, contour: Contour | None = None) -> tuple[list, Certificate]:
    """The screen's poles ``roots`` (fastest growing first) with every growing one certified: the
    secant's growing poles that are no zero of P dropped, the ones it missed added (labelled by the
    nearest wheel mode); and the certificate (module notes)."""
    c = contour if contour is not None else Contour(model)
    n, eps, dmin, resolved, samples = count_unstable(model, c)
    kept, have, unsure = [], [], []
    for r in roots:
        if r.sigma <= 0:
            kept.append(r)
            continue
        s = complex(r.sigma, 2 * np.pi * r.f_hz)
        if n > 0 and all(abs(s - t) > 1e-6 * abs(t) for t in have) and is_zero(model, c, s):
            kept.append(r)
            have.append(s)
        else:
            unsure.append(r)
    missing = n - sum(_weight(s, c.dt) for s in have)
    if missing > 0:
        f_r = np.asarray(model.f_r, float)
        for s in _search(model, c, have, missing):
            mode = _label(f_r, model.zeta, s.imag / (2 * np.pi))
            kept = [q for q in kept if not (q.mode == mode >= 0 and q.sigma <= 0)]
            kept.append(Root(s.imag / (2 * np.pi), s.real, mode))
            have.append(s)
    found = sum(_weight(s, c.dt) for s in have)
    if found < n:           # growing poles counted, not all located to a certified zero: the secant's kept
        kept += unsure      # (a pole within ~1e-9 |s| of sigma = 0; the time loop decides)
    return sorted(kept, key=lambda r: -r.sigma), Certificate(n, found, eps, dmin, resolved, samples)
