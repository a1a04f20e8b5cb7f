"""A train passage past a receiver: the sound of the squealing wheels moving along the track
(distance, directivity, Doppler, ground reflection, air absorption), its A-weighted equivalent level
over the passage L_pAeq,T, the sound exposure level L_AE and the maximum F-weighted level L_AFmax
(IEC 61672-1).  Pure functions on arrays; the listen stage writes the results.

Geometry.  The track runs along x; the train moves at the constant speed v toward +x; the squealing
wheels are point sources (one per bogie: the leading wheelset's wheel on the rail nearer the
receiver, as in the listen stage) at x_k(t) = v t - k s (k = 0..n-1, s the bogie spacing), at the
height h_source above a plane ground; the receiver is ``distance`` m from the source line
horizontally, at h_receiver (``postprocess.listening.listener.Geometry``).  Each source radiates the radiate
stage's components (tones and the strongest residual bins) with power W_c at f_c; each bogie's
wheel squeals with its own phase (independent sources).

Propagation, per source and path (direct; with a rigid ground also the image source at
-h_source, the same dipole), at the emission time t_e of the sound heard at t, exactly
t = t_e + r(t_e) / c0 (a quadratic in t_e for uniform motion; the retarded time gives the Doppler
shift f_c / (1 - M cos alpha) by itself):

    p(t) = sum sqrt(rho c0 / (4 pi)) sqrt(Q) / r * sqrt(2 W_c) 10^(-alpha(f_c) r / 20) cos(2 pi f_c t_e + phi)

with Q = 3 cos^2 theta for the dipole along the axle (theta from the lateral axis: cos theta = the
lateral distance / r) or 1 ('omni').  The convective amplification of a moving source
((1 - M cos alpha)^-n, M = v / c0 = 0.04 at 50 km/h) is left out: over a symmetric passage it changes
the energy by O(M^2).  A-weighting: each component weighted at its instantaneous received frequency
f_c dt_e/dt (IEC 61672-1, ``postprocess.listening.listener.a_weighting``).

Levels.  L_pAeq,T = 10 lg(mean p_A^2 / p0^2) over the passage window T (from the first squealing
wheel ``window`` m before the receiver to the last one ``window`` m past it); L_AE = L_pAeq,T + 10 lg(T /
1 s); L_AFmax: the maximum of the exponential time weighting F (tau = 125 ms) of p_A^2 (IEC 61672-1,
5.8: L_AF(t) = 10 lg((1/tau) int p_A^2(xi) e^{-(t - xi)/tau} dxi / p0^2)), run as its exact
first-order recursion on the samples.

Closed forms (the tests' references) for one steady tone of power W passing at the closest distance
d = sqrt(distance^2 + (h_r - h_s)^2), free field, over |v t| <= X (u = X / d):

    monopole: int p^2 dt = rho c0 W / (4 pi) * int dt / (d^2 + v^2 t^2)
                         = rho c0 W / (4 pi) * 2 arctan(u) / (v d)
    dipole:   int p^2 dt = rho c0 W / (4 pi) * 3 y^2 int dt / (d^2 + v^2 t^2)^2
                         = rho c0 W / (4 pi) * 3 y^2 (u / (1 + u^2) + arctan u) / (v d^3)

(y = the lateral distance; as X -> infinity: rho c0 W / (4 v d) and 3 rho c0 W y^2 / (8 v d^3)).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.signal import lfilter

from postprocess.listening.listener import P_REF, Geometry, a_weighting, air_attenuation, directivity_amplitude
from solvers.radiation.thompson_jones import C0, RHO_AIR

TAU_F = 0.125  # s, IEC 61672-1 time weighting F (fast)
MAX_COMPONENTS = 64  # tones plus the strongest residual bins
RESIDUAL_SHARE = 0.999  # of the residual's power kept (at most MAX_COMPONENTS in all)


@dataclass(frozen=True)
class Train:
    """``n_bogies`` squealing wheels (one per bogie), ``bogie_spacing`` (m) between consecutive ones,
    ``speed`` (m/s), ``window`` (m): the passage runs from the first squealing wheel this far before
    the receiver to the last one this far past it."""
    n_bogies: int
    bogie_spacing: float
    speed: float
    window: float = 30.0

    def __post_init__(self):
        if not (self.n_bogies >= 1 and self.bogie_spacing >= 0 and self.speed > 0 and self.window > 0):
            raise ValueError(f"n_bogies >= 1, bogie_spacing >= 0, speed > 0 and window > 0; got {self}")

    @property
    def duration(self) -> float:
        """T (s): the passage window."""
        return (2 * self.window + (self.n_bogies - 1) * self.bogie_spacing) / self.speed


def components(f, W, is_tone, max_components: int = MAX_COMPONENTS, share: float = RESIDUAL_SHARE):
    """(f, W, kept share of the total power): every tone and the strongest residual entries carrying
    ``share`` of the residual's power, at most ``max_components`` in all."""
    f, W, tone = np.asarray(f, float), np.asarray(W, float), np.asarray(is_tone, bool)
    keep = list(np.flatnonzero(tone & (W > 0)))
    res = np.flatnonzero(~tone & (W > 0))
    order = res[np.argsort(W[res])[::-1]]
    if order.size:
        cum = np.cumsum(W[order]) / W[order].sum()
        n = int(np.searchsorted(cum, share) + 1)
        keep += list(order[: max(0, min(n, max_components - len(keep)))])
    keep = np.array(sorted(keep), int)
    total = W.sum()
    return f[keep], W[keep], float(W[keep].sum() / total) if total > 0 else 1.0


def emission_time(t, a: float, rho2: float, v: float, c0: float = C0) -> np.ndarray:
    """t_e with t = t_e + r(t_e)/c0, r^2 = (v t_e - a)^2 + rho2 (source at x = v t_e - a, receiver at
    x = 0 at the squared distance rho2 from the source line): the root of
    (c0^2 - v^2) t_e^2 - 2 (c0^2 t - a v) t_e + c0^2 t^2 - a^2 - rho2 = 0 with t_e < t."""
    b = c0 * c0 * t - a * v
    disc = b * b - (c0 * c0 - v * v) * (c0 * c0 * t * t - a * a - rho2)
    return (b - np.sqrt(disc)) / (c0 * c0 - v * v)


def passby_signal(f, W, train: Train, geo: Geometry, fs: float = 44100.0, weighted: bool = True,
                  seed: int = 0, c0: float = C0, rho: float = RHO_AIR):
    """(t, p): the sound pressure (Pa) at the receiver over the passage window, sampled at fs;
    A-weighted when ``weighted``.  ``f``, ``W``: the components (Hz, W per source)."""
    t, (p,) = passby_signals(f, W, train, geo, fs, (weighted,), seed, c0, rho)
    return t, p


def passby_signals(f, W, train: Train, geo: Geometry, fs: float = 44100.0, weightings=(True, False),
                   seed: int = 0, c0: float = C0, rho: float = RHO_AIR):
    """(t, [p for each of ``weightings``]): ``passby_signal`` A-weighted (True) or not (False), every
    signal from one evaluation of the components' phases (the costly part), each the same to the bit
    as alone."""
    f, W = np.asarray(f, float), np.asarray(W, float)
    T = train.duration
    t = np.arange(int(np.ceil(T * fs))) / fs - train.window / train.speed  # t = 0: first wheel abreast
    alpha = air_attenuation(f) if geo.air else np.zeros_like(f)
    rng = np.random.default_rng(seed)
    phases = rng.uniform(0, 2 * np.pi, (train.n_bogies, f.size))
    paths = [(geo.h_receiver - geo.h_source)]
    if geo.ground == "rigid":
        paths.append(geo.h_receiver + geo.h_source)
    base = np.sqrt(rho * c0 / (4 * np.pi))
    M = train.speed / c0
    ps = [np.zeros_like(t) for _ in weightings]
    for k in range(train.n_bogies):
        a = k * train.bogie_spacing
        for dz in paths:
            rho2 = geo.distance**2 + dz**2
            te = emission_time(t, a, rho2, train.speed, c0)
            r = np.sqrt((train.speed * te - a) ** 2 + rho2)
            amp = base * directivity_amplitude(geo.directivity, geo.distance / r) / r
            dop = 1.0 / (1.0 - train.speed * (a - train.speed * te) / (c0 * r))  # dt_e/dt = 1/(1 - M cos alpha)
            for c in range(f.size):
                g = 10 ** (-alpha[c] * r / 20) * np.sqrt(2 * W[c])
                wave = np.cos(2 * np.pi * f[c] * te + phases[k, c])
                for p, weighted in zip(ps, weightings):
                    gw = g
                    if weighted:
                        grid = f[c] * np.linspace(1 / (1 + 1.5 * M), 1 / (1 - 1.5 * M), 64)
                        gw = g * 10 ** (np.interp(f[c] * dop, grid, a_weighting(grid)) / 20)
                    p += amp * gw * wave
    return t, ps


def f_weighted(p2, fs: float, tau: float = TAU_F) -> np.ndarray:
    """The exponential time weighting of p^2 (IEC 61672-1): (1/tau) int p^2(xi) e^{-(t-xi)/tau} dxi,
    as the exact recursion for a p^2 held over each sample: y_n = e^{-dt/tau} y_{n-1} + (1 - e^{-dt/tau}) x_n."""
    k = np.exp(-1.0 / (fs * tau))
    return lfilter([1 - k], [1, -k], np.asarray(p2, float))


def levels(p_A, fs: float) -> dict:
    """L_pAeq (over the whole signal), L_AE (re 1 s), L_AFmax and its time (s from the start), dB re 20 uPa."""
    p2 = np.asarray(p_A, float) ** 2
    T = p2.size / fs
    Leq = 10 * np.log10(p2.mean() / P_REF**2)
    LF = f_weighted(p2, fs)
    i = int(np.argmax(LF))
    return {"L_Aeq": float(Leq), "L_AE": float(Leq + 10 * np.log10(T)), "L_AFmax": float(10 * np.log10(LF[i] / P_REF**2)),
            "t_AFmax": float(i / fs), "T": float(T)}


def exposure_monopole(W: float, d: float, v: float, X: float, rho: float = RHO_AIR, c0: float = C0) -> float:
    """int p^2 dt (Pa^2 s) of a monopole of power W passing at closest distance d, over |v t| <= X."""
    return rho * c0 * W / (4 * np.pi) * 2 * np.arctan(X / d) / (v * d)


def exposure_dipole(W: float, d: float, y: float, v: float, X: float, rho: float = RHO_AIR,
                    c0: float = C0) -> float:
    """The same for a dipole along the lateral axis (Q = 3 cos^2 theta, cos theta = y / r)."""
    u = X / d
    return rho * c0 * W / (4 * np.pi) * 3 * y * y * (u / (1 + u * u) + np.arctan(u)) / (v * d**3)
