"""Green's functions (impulse responses) of the wheel and the rail, and the
convolutions of the time loop (SPEC 3.3-3.5; thesis [4.3]-[4.15]).

Units and conventions
---------------------
A discrete kernel g[k] (m/N) maps a force sample to a displacement:
xi(t_d) = sum_tau F(tau) g(t_d - tau), i.e. g[k] = dt * g_c(k dt) with g_c the
continuous impulse response (m/(N s)).  Matrix kernels have shape
(n_lags, 2, 2), index 0 = direction 2 (lateral, toward the field side),
1 = direction 3 (vertical, toward the ground), g[k, i, j] = response in i to a
force in j (so g[:, 0, 1] is g23), the same layout as the receptances of
``solvers.receptance`` and ``solvers.rail_response``.

Every convolution here excludes the instantaneous term g[0] (SPEC 3.5, [4.13],
[4.15]): the displacement at step n depends on forces at steps <= n - 1,

    xi[n] = sum_{k=1}^{n} g[k] @ F[n - k].

The per-step objects (``ModalFilter``, ``RingConvolver``) therefore take the
force of the current step and return the displacement of the NEXT step:
``xi_next = obj.step(F2, F3)``; before the first call the displacement is 0.
The kernels are the plain Green's functions: the wheel stage applies the minus
sign of [4.13] (the wheel receives -F), the rail stage uses them as they are;
both convolve force deviations from the static preload (SPEC 3.5).

Kropp's method [4.3]-[4.5]
--------------------------
S(f_k) = 2 Re G(f_k) on f_k = k / (N_t dt), k = 0..N_t/2, is the spectrum of
the EVEN extension g_c(|t|) of the causal response (2 Re G = G + G*).  Its
continuous inverse transform sampled at n dt, approximated by the sum over the
grid (df = 1/(N_t dt)), is

    s(n dt) = df sum_k S_k exp(2 pi i k n / N_t) = N_t df ifft(S)[n] = ifft(S)[n] / dt,

so the thesis' g(n dt) = dt s(n dt) [4.5] is simply ``ifft(S)[n]`` (numpy's
``ifft`` divides by N_t) for n = 1..N_t/2 and half of it at n = 0.  The SDOF
test (tests/greens/test_green.py) confirms it: g[k] = ifft(S)[k] matches
dt * exp(-zeta w t) sin(w_d t) / (m w_d) to < 1e-4 of the peak beyond the first
20 samples; ifft(S)/dt or dt * ifft(S) would be off by factors 1/dt^2, dt^2.
Because g is the causal half of the even sequence ifft(S), Re(DFT g) = S/2 =
Re G exactly on the grid; the imaginary part is the discrete Hilbert transform
of Re G, which lacks the spectrum above the Nyquist frequency (the mass-line
tails): that is the only approximation besides the decay by N_t/2 dt.  In time
it is an error of the first samples, 2 f0 dt / pi of the peak at k = 0 and
~ 8 f0 dt / (pi^3 k^2) after; in frequency an absolute Im error growing ~ f
(a few 1e-12 m/N at 6 kHz for the C20, of the sign of negative damping: the
kernel is slightly non-passive off-resonance above ~2.6 kHz).  The sampled
modal kernel of the filters below has a passive Im instead and a constant real
offset -C dt^2/12, C = sum phi phi^T / m_r (docs/validation/50_greens.md).
A second, smaller Im error is the truncation at N_t/2: 2 sum_{n > N_t/2}
g_c(n dt) sin(2 pi f_k n dt), alternating in sign from one grid point to the
next (it is what the folded tail leaves); it falls with the decay reached at
N_t/2 dt (``choose_grid(.., decay_db)``).

Band-limited correction (``band_limit``, SPEC 3.3)
---------------------------------------------------
Kropp's Im error is harmless against the level of the receptance but not
pointwise at deep antiresonances (|G22| ~ 7e-13 m/N between the sparse C20
peaks: tens to hundreds of % there).  Only the band up to ``band_limit`` (the
6.5 kHz of the models) has to be right; the spectrum between band_limit and
the Nyquist frequency 1/(2 dt) is free.  The error lives in the first
samples (above), so ``green_from_receptance(.., band_limit=f_b)`` refits the
first ``taps`` samples g[0..taps-1] (g[0] included): a correction h with

    sum_{k < taps} h[k] exp(-2 pi i f k dt) = G(f) - DFT(g)(f),  0 < f <= f_b,

by weighted least squares relative to |G| (weights 1/min|G| over each fit
segment, so antiresonances count as much as peaks), on ~2000 frequencies
(each the mean of two neighbouring grid points, which averages the
alternating truncation error out), Tikhonov-regularised to the smallest
correction that reaches ``fit_tol`` (discrepancy principle).  The error
against f is smooth (a trigonometric polynomial of degree ~ taps fits it to
1e-4 relative over 47 % of the circle), the band above f_b absorbs the rest.
Nothing beyond lag taps - 1 changes (the SDOF and modal-kernel comparisons
beyond 20 samples are untouched); Re DFT(g) is then exact only to the fit
tolerance instead of to rounding.  The corrected kernel is real, causal and
decays as before, and passive in the band; the band above f_b pays for it:
there its spectrum departs from G by a few |G| and is non-passive in places
(C20: -Im DFT(g) down to -7e-11 m/N, plain Kropp -6e-12), so a corrected
kernel convolved in a time loop could feed spurious growth above f_b.  The
greens stage corrects the wheel kernel, which the time loop does not use
(it uses the modal filters below); the rail kernel it convolves is plain
Kropp.  The correction assumes a causal receptance: for one with hysteretic
(constant loss factor) damping, Im G(0+) != 0 and no causal kernel reproduces
it (the BV50 rail, see pipeline/greens_stage.py); the fit would chase the
non-causal part and is not used there.

Wheel: exact recursive modal filters
------------------------------------
The wheel receptance is a modal sum [4.10], so its sampled impulse response is
a sum of damped sinusoids,

    g_r[k] = dt Phi_ri Phi_rj / m_r * h_r(k dt),
    h_r(t) = exp(-sigma t) sinh(mu t) / mu,  sigma = zeta w,  mu = w sqrt(zeta^2 - 1),

(mu = i w_d for zeta < 1: exp(-zeta w t) sin(w_d t) / w_d; t exp(-w t) at
zeta = 1; two real exponentials for zeta > 1).  The discrete convolution of a
force history with it is reproduced EXACTLY (to rounding) by one recursion per
mode on the modal force P_r = Phi_r2 F2 + Phi_r3 F3:

* zeta < 1: complex one-pole form, z = exp((-sigma + i w_d) dt),
  q[n+1] = z (q[n] + P[n]),  xi_i[n] += Phi_ri dt / (m_r w_d) Im q[n]
  (q[n] = sum_{k>=1} z^k P[n-k]; better conditioned than the real
  two-term recursion for the low-frequency rigid modes, whose poles are
  close to z = 1);
* zeta >= 1: real poles p1,2 = exp((-sigma +- mu) dt), divided-difference
  states a[n] = sum p2^k P[n-k], v[n] = sum d_k P[n-k] with
  d_k = (p1^k - p2^k)/(p1 - p2) (= k p^(k-1) at zeta = 1, no cancellation):
  v[n+1] = P[n] + p1 v[n] + a[n],  a[n+1] = p2 (a[n] + P[n]),
  xi_i[n] += Phi_ri / m_r * dt * (p1 - p2)/(s1 - s2) * v[n]
  with (p1 - p2)/(s1 - s2) = dt exp(-sigma dt) sinh(mu dt)/(mu dt).

The kernel these filters reproduce is ``modal_kernel`` (the sampled modal
impulse response), not Kropp's g (plain or band-limited): the two differ only
in the first samples (Kropp's band limit, or the correction) and by time
aliasing (documented in 50_greens.md).

Rail
----
The rail kernel (a few thousand lags, fast pad-damped decay) is convolved
directly (``convolve_direct``; per step with ``RingConvolver``) or by
overlap-add FFT over a whole history (``convolve_fft``).  The moving Green's
function (SPEC 3.4) g_mov[k] = g^R(x_k = v k dt, k dt) is Kropp's construction
evaluated at the single lag k from the transfer receptance at x_k
(``moving_green``).
"""
from __future__ import annotations

import math
from typing import Callable, NamedTuple

import numba
import numpy as np
import scipy.fft as sfft


class GreenDecayError(ValueError):
    """The Green's function has not decayed by N_t/2 dt: the frequency grid is too coarse."""


# ----------------------------------------------------------------------------------------------
# Kropp's method and the frequency grid
# ----------------------------------------------------------------------------------------------

def frequency_grid(dt: float, n_t: int) -> np.ndarray:
    """f_k = k / (N_t dt), k = 0..N_t/2 (Hz)."""
    return np.arange(n_t // 2 + 1) / (n_t * dt)


class BandFit(NamedTuple):
    """What the band-limited correction did (``green_from_receptance(.., info=True)``)."""
    band_limit: float       # Hz: top of the band where DFT(g) = G is fitted
    taps: int               # g[0..taps-1] were corrected
    correction: np.ndarray  # (taps, ...) m/N, added to Kropp's g[:taps]
    fit_error: np.ndarray   # (...) max |DFT(g) - G| / min|G| over the fit segments, per component
    n_fit: int              # number of fit frequencies


def _kropp(S: np.ndarray, n_t: int) -> np.ndarray:
    """g[0..N_t/2] = causal half of ifft(S) with g[0] halved ([4.5])."""
    s = sfft.irfft(S, n=n_t, axis=0)  # = ifft of the even (real, symmetric) spectrum
    g = s[: n_t // 2 + 1].copy()
    g[0] *= 0.5
    return g


def _band_index(band_limit: float, dt: float, n_t: int) -> int:
    """Last grid index k with f_k <= band_limit (checked against the Nyquist frequency)."""
    if not 0.0 < band_limit < 0.5 / dt:
        raise ValueError(f"band_limit = {band_limit} Hz must lie between 0 and the Nyquist frequency {0.5 / dt:.0f} Hz")
    kb = int(math.floor(band_limit * n_t * dt + 1e-9))
    if kb < 3:
        raise ValueError(f"band_limit = {band_limit} Hz holds fewer than 3 grid points (df = {1 / (n_t * dt):.3g} Hz)")
    return kb


def _fit_first_taps(G_band: np.ndarray, g: np.ndarray, dt: float, n_t: int, taps: int, fit_tol: float,
                    n_fit: int = 2000):
    """The correction h of g[:taps] (module notes: band-limited correction).
    G_band: the receptance on grid points 0..kb (kb + 1, ...); g: Kropp's kernel
    (N_t/2 + 1, ...).  Returns h (taps, ...), the reached max weighted residual
    per component (...), the number of fit frequencies."""
    kb = G_band.shape[0] - 1
    if not 1 <= taps <= g.shape[0]:
        raise ValueError(f"taps = {taps} must lie in 1..N_t/2 + 1")
    comp = G_band.shape[1:]
    Gb = G_band.reshape(kb + 1, -1)
    E = Gb - sfft.rfft(g, n=n_t, axis=0)[: kb + 1].reshape(kb + 1, -1)   # what is missing in band
    # fit segments [e_i, e_i+1]: the pair (e_i, e_i + 1) is the fit point, min |G| over the segment its weight
    edges = np.unique(np.linspace(1, kb, min(n_fit, kb // 2) + 1).round().astype(np.int64))
    k0 = edges[:-1]
    Gmin = np.minimum.reduceat(np.abs(Gb[: edges[-1] + 1]), edges, axis=0)[:-1]
    Em = 0.5 * (E[k0] + E[k0 + 1])
    lags = np.arange(taps)
    ph = (2 * np.pi / n_t) * lags[None, :]
    X = 0.5 * (np.exp(-1j * ph * k0[:, None]) + np.exp(-1j * ph * (k0[:, None] + 1)))  # DFT of the taps, same means
    h = np.zeros((taps, Gb.shape[1]))
    err = np.zeros(Gb.shape[1])
    for c in range(Gb.shape[1]):
        top = np.abs(Gb[:, c]).max()
        if top == 0.0:
            continue
        W = 1.0 / np.maximum(Gmin[:, c], 1e-9 * top)
        A = np.vstack([W[:, None] * X.real, W[:, None] * X.imag])
        y = np.concatenate([W * Em[:, c].real, W * Em[:, c].imag])
        U, sv, Vt = np.linalg.svd(A, full_matrices=False)
        uy = U.T @ y

        def solve(lam):
            return Vt.T @ (sv * uy / (sv ** 2 + lam ** 2))

        def resid(x):
            return float(np.abs(W * (X @ x - Em[:, c])).max())

        # discrepancy principle: the largest lambda (smallest correction) that reaches fit_tol
        lo, hi = -12.0, 2.0
        if resid(solve(10 ** lo * sv[0])) <= fit_tol:
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                if resid(solve(10 ** mid * sv[0])) <= fit_tol:
                    lo = mid
                else:
                    hi = mid
        h[:, c] = solve(10 ** lo * sv[0])
        err[c] = resid(h[:, c])
    return h.reshape((taps,) + comp), err.reshape(comp), len(k0)


def green_from_receptance(G_of_f, dt: float, n_t: int, chunk: int = 1 << 16, band_limit: float | None = None,
                          taps: int = 16, fit_tol: float = 1e-3, info: bool = False):
    """Kropp's method [4.3]-[4.5]: the discrete Green's function g[k], k = 0..N_t/2.

    ``G_of_f``: a callable f (nf,) -> complex receptance (nf, ...) in m/N, or the
    receptance already sampled on ``frequency_grid(dt, n_t)``.  N_t must be even.
    Returns g (N_t/2 + 1, ...) in m/N: g[0] = 0.5 ifft(S)[0], g[k] = ifft(S)[k]
    (= dt s(k dt) of [4.5], see the module notes), S = 2 Re G.  The callable is
    evaluated in chunks of ``chunk`` frequencies.

    ``band_limit`` (Hz, default None = plain Kropp): refit g[:taps] so that the DFT
    of g reproduces G pointwise up to band_limit, to ``fit_tol`` relative to |G|
    (module notes: band-limited correction; for causal receptances only).
    ``info``: also return a ``BandFit`` (None without band_limit).
    """
    n_t = int(n_t)
    if n_t < 2 or n_t % 2:
        raise ValueError(f"n_t must be even and >= 2, got {n_t}")
    f = frequency_grid(dt, n_t)
    kb = _band_index(band_limit, dt, n_t) if band_limit is not None else -1
    if callable(G_of_f):
        first = np.asarray(G_of_f(f[:1]))
        S = np.empty((len(f),) + first.shape[1:])
        G_band = np.empty((kb + 1,) + first.shape[1:], complex)
        for a in range(0, len(f), chunk):
            Gc = np.asarray(G_of_f(f[a:a + chunk]))
            S[a:a + chunk] = 2.0 * np.real(Gc)
            m = min(len(Gc), kb + 1 - a)
            if m > 0:
                G_band[a:a + m] = Gc[:m]
    else:
        G = np.asarray(G_of_f)
        if G.shape[0] != len(f):
            raise ValueError(f"sampled receptance has {G.shape[0]} frequencies, the grid N_t/2 + 1 = {len(f)}")
        S = 2.0 * np.real(G)
        G_band = G[: kb + 1]
    g = _kropp(S, n_t)
    fit = None
    if band_limit is not None:
        h, err, n_fit = _fit_first_taps(G_band, g, dt, n_t, int(taps), float(fit_tol))
        g[:taps] += h
        fit = BandFit(float(band_limit), int(taps), h, err, n_fit)
    return (g, fit) if info else g


def _slowest_decay(w, zeta):
    """Decay rate (1/s) of the slowest exponential of each mode."""
    w, zeta = np.asarray(w, float), np.asarray(zeta, float)
    over = zeta >= 1.0
    rate = zeta * w
    rate[over] = w[over] * (zeta[over] - np.sqrt(zeta[over] ** 2 - 1.0))
    return rate


def _even_fast_len(n: int) -> int:
    n = sfft.next_fast_len(int(n), real=True)
    while n % 2:
        n = sfft.next_fast_len(n + 1, real=True)
    return n


def choose_grid(f_r, zeta_r, dt: float, points_per_band: float = 6, decay_db: float = 60) -> int:
    """N_t for Kropp's method: the frequency step df = 1/(N_t dt) puts about
    ``points_per_band`` grid points inside the -3 dB band (width 2 zeta f_r) of the
    narrowest resonance, and N_t/2 dt is at least the time in which the slowest
    mode decays by ``decay_db``.  Rounded up to an even fast FFT length (a few %
    more points at most).  With zeta < 1 the band criterion governs for
    decay_db < ~82 dB at 6 points per band: N_t/2 dt = p / (4 zeta f_r) for p
    points per band, by which that mode has decayed by exp(-pi p / 2), 82 dB at
    p = 6.
    Modes with f_r <= 0 or zeta <= 0 are ignored.
    """
    f_r = np.atleast_1d(np.asarray(f_r, float))
    zeta_r = np.broadcast_to(np.asarray(zeta_r, float), f_r.shape)
    ok = (f_r > 0) & (zeta_r > 0) & np.isfinite(f_r) & np.isfinite(zeta_r)
    if not ok.any():
        raise ValueError("choose_grid needs at least one mode with f_r > 0 and zeta > 0")
    f_r, zeta_r = f_r[ok], zeta_r[ok]
    band = 2.0 * zeta_r * f_r
    df = band.min() / float(points_per_band)
    n_band = math.ceil(1.0 / (df * dt))
    t_decay = math.log(10.0 ** (decay_db / 20.0)) / _slowest_decay(2 * np.pi * f_r, zeta_r).min()
    n_decay = 2 * math.ceil(t_decay / dt)
    return _even_fast_len(max(n_band, n_decay, 2))


def points_in_band(f_r: float, zeta_r: float, dt: float, n_t: int) -> int:
    """Number of grid points f_k = k/(N_t dt) inside the -3 dB band
    [f_r (1 - zeta), f_r (1 + zeta)] of one resonance."""
    df = 1.0 / (n_t * dt)
    lo, hi = f_r * (1.0 - zeta_r), f_r * (1.0 + zeta_r)
    return int(math.floor(hi / df) - math.ceil(lo / df) + 1)


class DecayCheck(NamedTuple):
    ok: bool
    level_db: float   # max |g| over the tail relative to max |g| (all components), dB


def decayed(g: np.ndarray, decay_db: float = 60.0, tail: float = 0.05, strict: bool = False) -> DecayCheck:
    """Has the Green's function g[0..N_t/2] (any trailing component axes) decayed
    by ``decay_db`` at its end?  Compares max |g| over the last ``tail`` fraction
    of the lags with max |g| over all lags and components.  If N_t is too short
    the periodic inverse transform folds the undecayed response back (the end
    of g then holds about twice the true g(N_t/2 dt)), so this catches a grid
    that is too coarse.  ``strict``: raise GreenDecayError instead of returning
    ok = False."""
    a = np.abs(np.asarray(g)).reshape(len(g), -1).max(axis=1)
    m = max(1, int(round(tail * len(a))))
    peak = a.max()
    level = 20 * np.log10(max(a[-m:].max(), 1e-300) / peak) if peak > 0 else -np.inf
    res = DecayCheck(bool(level <= -decay_db), float(level))
    if strict and not res.ok:
        raise GreenDecayError(f"Green's function decayed only by {-level:.1f} dB at N_t/2 dt "
                              f"(needs {decay_db:.0f} dB): use a larger N_t (choose_grid)")
    return res


# ----------------------------------------------------------------------------------------------
# Wheel: sampled modal kernel and exact recursive modal filters
# ----------------------------------------------------------------------------------------------

def modal_impulse(t, f_r: float, zeta: float) -> np.ndarray:
    """h(t) = exp(-sigma t) sinh(mu t) / mu of one mode per unit modal mass
    (displacement impulse response of x'' + 2 zeta w x' + w^2 x = delta(t)),
    for any zeta >= 0: exp(-zeta w t) sin(w_d t)/w_d (zeta < 1), t exp(-w t)
    (zeta = 1), the over-damped pair (zeta > 1)."""
    t = np.asarray(t, float)
    w = 2 * np.pi * f_r
    sig = zeta * w
    if zeta < 1.0:
        wd = w * math.sqrt(1.0 - zeta * zeta)
        return np.exp(-sig * t) * np.sin(wd * t) / wd
    mu = w * math.sqrt(zeta * zeta - 1.0)
    x = mu * t
    small = x < 1e-3
    out = np.empty_like(t)
    xs = x[small]
    out[small] = t[small] * np.exp(-sig * t[small]) * (1.0 + xs * xs / 6.0 + xs ** 4 / 120.0)
    tb = t[~small]
    out[~small] = (np.exp((mu - sig) * tb) - np.exp(-(mu + sig) * tb)) / (2.0 * mu)
    return out


def modal_kernel(n_lags: int, dt: float, f_r, modal_mass, zeta, phi) -> np.ndarray:
    """The sampled modal impulse response g[k] = dt sum_r phi_r phi_r^T h_r(k dt)/m_r,
    k = 0..n_lags-1, (n_lags, 2, 2) in m/N; phi (M, 2) = (Phi_2, Phi_3) at the contact
    point.  This is the kernel ``ModalFilter`` reproduces exactly (g[0] = 0)."""
    f_r, modal_mass, zeta = (np.atleast_1d(np.asarray(a, float)) for a in (f_r, modal_mass, zeta))
    phi = np.asarray(phi, float).reshape(len(f_r), 2)
    t = np.arange(n_lags) * dt
    g = np.zeros((n_lags, 2, 2))
    for r in range(len(f_r)):
        h = dt * modal_impulse(t, f_r[r], zeta[r]) / modal_mass[r]
        g += h[:, None, None] * np.outer(phi[r], phi[r])[None]
    return g


class ModalFilter(NamedTuple):
    """Exact recursive form of the wheel's modal kernel (see the module notes).
    Coefficients (per mode r): kind 0 (zeta < 1, complex one-pole) or 1 (zeta >= 1,
    real poles); z = pole / first pole, p2 = second pole; w_in (M, 2): modal force
    P_r = w_in[r] . (F2, F3); w_out (M, 2): xi_i += w_out[r, i] * y_r.  State: q, a (kind 1).
    The time loop runs the kind-0 modes from real, mode-contiguous copies (a loop without
    branches or complex types, which the compiler vectorises): u_coef (6, M0) = Re z, Im z,
    w_in[:, 0], w_in[:, 1], w_out[:, 0], w_out[:, 1]; their state u_state (2, M0) = Re q, Im q;
    ``over`` (M1,) the indices of the kind-1 modes.
    Pass the whole tuple to the njit functions (``filter_step``,
    ``filter_history``) from inside a numba time loop."""
    kind: np.ndarray
    z: np.ndarray
    p2: np.ndarray
    w_in: np.ndarray
    w_out: np.ndarray
    q: np.ndarray
    a: np.ndarray
    u_coef: np.ndarray
    u_state: np.ndarray
    over: np.ndarray

    def step(self, F2: float, F3: float) -> tuple[float, float]:
        """Record the force at the current step; return (xi2, xi3) at the next step."""
        return filter_step(self, F2, F3)

    def reset(self) -> None:
        self.q[:] = 0.0
        self.a[:] = 0.0
        self.u_state[:] = 0.0

    def copy(self) -> "ModalFilter":
        return ModalFilter(*(np.array(x, copy=True) for x in self))

    def response(self, F: np.ndarray) -> np.ndarray:
        """Whole history from rest (the state is not touched): xi (nt, 2)."""
        return filter_history(self.copy_reset(), np.ascontiguousarray(F, dtype=float))

    def copy_reset(self) -> "ModalFilter":
        c = self.copy()
        c.reset()
        return c


def modal_filter(dt: float, f_r, modal_mass, zeta, phi) -> ModalFilter:
    """Build the recursive modal filters of the kernel ``modal_kernel(.., dt, f_r,
    modal_mass, zeta, phi)``: f_r (M,) Hz, modal_mass (M,) kg, zeta (M,) (any
    value >= 0; zeta >= 1 gives the critically / over-damped forms), phi (M, 2) =
    (Phi_2, Phi_3) at the contact point.  State at rest."""
    f_r, modal_mass, zeta = (np.atleast_1d(np.asarray(a, float)) for a in (f_r, modal_mass, zeta))
    phi = np.asarray(phi, float).reshape(len(f_r), 2)
    M = len(f_r)
    if np.any(zeta < 0) or np.any(f_r <= 0) or np.any(modal_mass <= 0):
        raise ValueError("modal_filter needs f_r > 0, modal_mass > 0, zeta >= 0")
    kind = np.zeros(M, np.int64)
    z = np.zeros(M, complex)
    p2 = np.zeros(M, complex)
    gain = np.zeros(M)
    for r in range(M):
        w = 2 * np.pi * f_r[r]
        sig = zeta[r] * w
        if zeta[r] < 1.0:
            wd = w * math.sqrt(1.0 - zeta[r] ** 2)
            z[r] = math.exp(-sig * dt) * complex(math.cos(wd * dt), math.sin(wd * dt))
            gain[r] = dt / wd
        else:
            kind[r] = 1
            mu = w * math.sqrt(zeta[r] ** 2 - 1.0)
            z[r] = math.exp((mu - sig) * dt)
            p2[r] = math.exp(-(mu + sig) * dt)
            x = mu * dt
            shc = 1.0 + x * x / 6.0 + x ** 4 / 120.0 if x < 1e-3 else math.sinh(x) / x
            gain[r] = dt * dt * math.exp(-sig * dt) * shc
    w_in = np.ascontiguousarray(phi)
    w_out = np.ascontiguousarray(phi * (gain / modal_mass)[:, None])
    under = kind == 0
    u_coef = np.ascontiguousarray(np.vstack([z.real, z.imag, w_in.T, w_out.T])[:, under])
    return ModalFilter(kind, z, p2, w_in, w_out, np.zeros(M, complex), np.zeros(M, complex), u_coef,
                       np.zeros((2, int(under.sum()))), np.flatnonzero(~under).astype(np.int64))


@numba.njit(cache=True)
def filter_step(filt, F2, F3):
    """njit: push the force (F2, F3) of step n into the modal filters, return the
    displacement (xi2, xi3) at step n + 1 (forces up to step n only, g[0] excluded)."""
    kind, z, p2, w_in, w_out, q, a, uc, us, over = filt
    x2 = 0.0
    x3 = 0.0
    for j in range(uc.shape[1]):                    # zeta < 1: q <- z (q + P), y = Im q
        ur = us[0, j] + uc[2, j] * F2 + uc[3, j] * F3
        ui = us[1, j]
        nr = uc[0, j] * ur - uc[1, j] * ui
        ni = uc[0, j] * ui + uc[1, j] * ur
        us[0, j] = nr
        us[1, j] = ni
        x2 += uc[4, j] * ni
        x3 += uc[5, j] * ni
    for i in range(over.shape[0]):                  # zeta >= 1: divided-difference states
        r = over[i]
        P = w_in[r, 0] * F2 + w_in[r, 1] * F3
        v = P + z[r] * q[r] + a[r]
        a[r] = p2[r] * (a[r] + P)
        q[r] = v
        y = v.real
        x2 += w_out[r, 0] * y
        x3 += w_out[r, 1] * y
    return x2, x3


@numba.njit(cache=True)
def filter_history(filt, F):
    """njit: xi[n] = sum_{k>=1} g[k] F[n-k] for a whole force history F (nt, 2),
    starting from the filter's current state (at rest: xi[0] = 0)."""
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    for n in range(nt - 1):
        x2, x3 = filter_step(filt, F[n, 0], F[n, 1])
        xi[n + 1, 0] = x2
        xi[n + 1, 1] = x3
    return xi


# ----------------------------------------------------------------------------------------------
# Direct and FFT convolution (rail kernel; reference for the wheel filters)
# ----------------------------------------------------------------------------------------------

@numba.njit(cache=True)
def convolve_direct(g, F):
    """Reference discrete convolution without the instantaneous term:
    xi[n] = sum_{k=1}^{min(n, K-1)} g[k] @ F[n-k]; g (K, 2, 2), F (nt, 2) -> (nt, 2)."""
    K = g.shape[0]
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    for n in range(1, nt):
        x2 = 0.0
        x3 = 0.0
        kmax = min(n, K - 1)
        for k in range(1, kmax + 1):
            f2 = F[n - k, 0]
            f3 = F[n - k, 1]
            x2 += g[k, 0, 0] * f2 + g[k, 0, 1] * f3
            x3 += g[k, 1, 0] * f2 + g[k, 1, 1] * f3
        xi[n, 0] = x2
        xi[n, 1] = x3
    return xi


def convolve_fft(g: np.ndarray, F: np.ndarray) -> np.ndarray:
    """The same as ``convolve_direct`` by overlap-add FFT convolution
    (scipy.signal.oaconvolve picks the block length): exact to rounding."""
    from scipy.signal import oaconvolve

    g = np.asarray(g, float)
    F = np.asarray(F, float)
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    if nt < 2 or g.shape[0] < 2:
        return xi
    for i in range(2):
        acc = np.zeros(nt - 1)
        for j in range(2):
            acc += oaconvolve(F[: nt - 1, j], g[1:, i, j], mode="full")[: nt - 1]
        xi[1:, i] = acc
    return xi


class RingConvolver(NamedTuple):
    """Per-step direct convolution with a ring buffer of past forces (rail).
    g (K, 2, 2) the kernel (g[0] unused), buf (2K, 2) the doubled ring of forces,
    pos (1,) the write position.  ``step(F2, F3)`` records the force of step n and
    returns the displacement at step n + 1."""
    g: np.ndarray
    buf: np.ndarray
    pos: np.ndarray

    def step(self, F2: float, F3: float) -> tuple[float, float]:
        return ring_step(self, F2, F3)

    def reset(self) -> None:
        self.buf[:] = 0.0
        self.pos[0] = 0


def ring_convolver(g: np.ndarray) -> RingConvolver:
    g = np.ascontiguousarray(g, dtype=float)
    K = g.shape[0]
    return RingConvolver(g, np.zeros((2 * K, 2)), np.zeros(1, np.int64))


@numba.njit(cache=True)
def ring_step(rc, F2, F3):
    """njit: record (F2, F3) of step n, return (xi2, xi3) at step n + 1 =
    sum_{k=1}^{K-1} g[k] @ F[n+1-k]."""
    g, buf, pos = rc
    K = g.shape[0]
    p = pos[0]
    buf[p, 0] = F2
    buf[p, 1] = F3
    buf[p + K, 0] = F2
    buf[p + K, 1] = F3
    x2 = 0.0
    x3 = 0.0
    j = p + K
    for k in range(1, K):     # F[n+1-k] sits at j = p + K - (k - 1)
        f2 = buf[j, 0]
        f3 = buf[j, 1]
        x2 += g[k, 0, 0] * f2 + g[k, 0, 1] * f3
        x3 += g[k, 1, 0] * f2 + g[k, 1, 1] * f3
        j -= 1
    pos[0] = p + 1 if p + 1 < K else 0
    return x2, x3


# ----------------------------------------------------------------------------------------------
# Rail: moving Green's function
# ----------------------------------------------------------------------------------------------

def moving_green(transfer: Callable, v: float, dt: float, n_k: int, n_t: int, chunk: int = 16,
                 band_limit: float | None = None, taps: int = 16, fit_tol: float = 1e-3, info: bool = False):
    """Moving Green's function of a translation-invariant rail (SPEC 3.4):
    g_mov[k] = g^R(x_k = v k dt, k dt), k = 0..n_k-1, (n_k, 2, 2) in m/N.

    ``transfer(x (nx,), f (nf,)) -> complex (nx, nf, 2, 2)``: the transfer
    receptance at distance x >= 0 (m/N, components 2, 3 as in the module notes).
    Each lag is Kropp's construction (``green_from_receptance``) evaluated at the
    single time k dt with the receptance at x_k:

        g_mov[k] = 1/N_t [S_0 + 2 sum_{m=1}^{N_t/2-1} S_m cos(2 pi m k/N_t) + S_{N_t/2} (-1)^k],
        S_m = 2 Re G^R(x_k, f_m),  f_m = m/(N_t dt),

    halved at k = 0.  v = 0 gives exactly the fixed-point Green's function at x = 0.
    Cost: n_k evaluations of the transfer receptance on N_t/2 + 1 frequencies
    (``chunk`` distances per call).  n_k <= N_t/2 + 1; the fixed-point response
    must have decayed by N_t/2 dt (check with ``decayed`` on the x = 0 function).

    ``band_limit``: the lags k < taps take the band-limited correction of the
    fixed-x kernel of G^R(x_k, .) (``green_from_receptance``), so that each
    g^R(x_k, .) reproduces its receptance up to band_limit; v = 0 then equals
    ``green_from_receptance(G^R(0, .), band_limit=..)``.  For causal receptances
    only (not the hysteretic BV50 model).  ``info``: also return a ``BandFit``
    (correction = the values added at lags 0..taps-1, fit_error = the worst over
    those lags; None without band_limit).
    """
    n_t, n_k = int(n_t), int(n_k)
    if n_t % 2 or n_t < 2:
        raise ValueError(f"n_t must be even, got {n_t}")
    if not 1 <= n_k <= n_t // 2 + 1:
        raise ValueError(f"n_k = {n_k} must lie in 1..N_t/2 + 1 = {n_t // 2 + 1}")
    f = frequency_grid(dt, n_t)
    nf = len(f)
    kb = _band_index(band_limit, dt, n_t) if band_limit is not None else -1
    taps = min(int(taps), n_k)
    wts = np.full(nf, 2.0)
    wts[0] = 1.0
    wts[-1] = 1.0
    m = np.arange(nf, dtype=np.int64)
    g = np.zeros((n_k, 2, 2))
    corr = np.zeros((taps, 2, 2))
    err = np.zeros((2, 2))
    n_fit = 0
    for a in range(0, n_k, chunk):
        ks = np.arange(a, min(n_k, a + chunk), dtype=np.int64)
        x = v * ks * dt
        G = np.asarray(transfer(x, f))
        if G.shape != (len(ks), nf, 2, 2):
            raise ValueError(f"transfer returned shape {G.shape}, expected {(len(ks), nf, 2, 2)}")
        C = np.cos((2 * np.pi / n_t) * ((ks[:, None] * m[None, :]) % n_t)) * (wts / n_t)
        g[ks] = np.einsum("km,kmij->kij", C, 2.0 * G.real)
        if band_limit is not None:
            for i, k in enumerate(ks[ks < taps]):    # lags with a correction: the whole kernel of G(x_k, .)
                gx = _kropp(2.0 * G[i].real, n_t)
                h, e, n_fit = _fit_first_taps(G[i, : kb + 1], gx, dt, n_t, taps, float(fit_tol))
                corr[k] = h[k]
                err = np.maximum(err, e)
    g[0] *= 0.5
    g[:taps] += corr if band_limit is not None else 0.0
    if not info:
        return g
    return g, (BandFit(float(band_limit), taps, corr, err, n_fit) if band_limit is not None else None)
