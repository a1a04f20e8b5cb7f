"""The references of the wheel receptance and Green's function checks (tests/greens/, the validation
writers, benchmarks/greens.py), independent of the solvers:

* ``sdof_receptance`` / ``sdof_impulse``: the single-degree-of-freedom
  receptance 1/(m (w0^2 - W^2 + 2 i zeta w0 W)) and its exact impulse response;
* ``beam_transfer``: closed-form transfer receptance of an Euler-Bernoulli beam
  on a viscously damped Winkler foundation (the rail as a beam), vertical and an
  uncoupled lateral beam, as the ``transfer(x, f) -> (nx, nf, 2, 2)`` callable of
  ``solvers.greens.kernels.moving_green``;
* ``beam_impulse``: the same beam's impulse response g(x, t) in the time domain
  by a wavenumber integral over per-wavenumber oscillators (an independent check
  of the moving Green's function);
* ``beam_moving_receptance``: the spectrum of g(v t, t), the receptance the
  moving Green's function stands for, as a wavenumber integral;
* ``wheel_case``: the C20 modal data at a contact point -- from the built
  artifact build/wheels/c20/modes.npz when it exists, else a synthetic modal
  set with the reference frequencies of the thesis (Table 4.1) and realistic
  modal masses.
"""
from __future__ import annotations

import csv
from pathlib import Path
import json
import tomllib

import numpy as np

from solvers.constants import F_MAX_HZ, THESIS_CONTACT_POINTS_FIELD

from pipeline.store.paths import ROOT
from geometry.wheel import tread_radius

DATA = Path(__file__).resolve().parent / "data"
ARTIFACT = ROOT / "build" / "wheels" / "c20" / "modes.npz"
WHEEL_FILE = ROOT / "geometry" / "wheels" / "c20.toml"
DT = 36e-6
V = 50 / 3.6
Z_RC = 0.75
# dy_WR (mm) -> y^W (m), SPEC 2: thesis [4.1] field-positive (its printed y^W negated, solvers.constants)
Y_CONTACT = {round(1e3 * dy): yw for dy, (yw, _) in THESIS_CONTACT_POINTS_FIELD.items()}


# ------------------------------------------------------------------------------------- SDOF

def sdof_receptance(f, m, f0, zeta):
    """x/F of m x'' + c x' + k x = F at W = 2 pi f: 1 / (k - m W^2 + i W c), k = m (2 pi f0)^2, c = 2 zeta m 2 pi f0
    (the equation of motion, not the solvers' modal FRF)."""
    W = 2 * np.pi * np.asarray(f, float)
    k = m * (2 * np.pi * f0) ** 2
    c = 2 * zeta * m * 2 * np.pi * f0
    return 1.0 / (k - m * W ** 2 + 1j * W * c)


def sdof_impulse(t, m, f0, zeta):
    """Continuous displacement impulse response (m/(N s)), zeta < 1."""
    w0 = 2 * np.pi * f0
    wd = w0 * np.sqrt(1 - zeta ** 2)
    return np.exp(-zeta * w0 * t) * np.sin(wd * t) / (m * wd)


def bandlimit_error(k, dt, m):
    """Leading-order error of Kropp's g[k] for a mass-line tail -1/(m W^2) cut at the
    Nyquist frequency: 2 dt^2/(pi^2 m) [cos(pi k) - pi k (pi/2 - Si(pi k))], halved at k = 0."""
    from scipy.special import sici  # lazy: brings in scipy

    k = np.asarray(k, float)
    a = np.pi * k
    e = 2 * dt ** 2 / (np.pi ** 2 * m) * (np.cos(a) - a * (np.pi / 2 - sici(a)[0]))
    return np.where(k == 0, 0.5 * e, e)


# ------------------------------------------------------------------- beam on a damped foundation

# rail-like parameters (UIC60-size beam, pad stiffness and damping per metre)
VERTICAL = dict(EI=6.42e6, m=60.0, k_s=3.3e8, c_s=3.5e4)
LATERAL = dict(EI=1.07e6, m=60.0, k_s=1.5e8, c_s=2.0e4)


def beam_receptance(x, f, EI, m, k_s, c_s):
    """(nx, nf) transfer receptance of EI w'''' + m w_tt + c_s w_t + k_s w = F delta(x):
    G(x) = beta / (2 K) exp(-beta |x|) (cos beta |x| + sin beta |x|),
    K = k_s + i W c_s - m W^2, beta = (K / (4 EI))^(1/4) (principal root: arg in
    [0, pi/4), the waves decaying away from the load).  Static limit beta/(2 k_s)."""
    x = np.abs(np.atleast_1d(np.asarray(x, float)))[:, None]
    W = 2 * np.pi * np.atleast_1d(np.asarray(f, float))[None, :]
    K = k_s + 1j * W * c_s - m * W ** 2
    beta = (K / (4 * EI)) ** 0.25
    bx = beta * x
    return beta / (2 * K) * np.exp(-bx) * (np.cos(bx) + np.sin(bx))


def beam_transfer(vertical=VERTICAL, lateral=LATERAL):
    """transfer(x, f) -> (nx, nf, 2, 2): [.., 0, 0] lateral beam (G22), [.., 1, 1]
    vertical beam (G33), no coupling."""

    def transfer(x, f):
        x = np.atleast_1d(x)
        f = np.atleast_1d(f)
        out = np.zeros((len(x), len(f), 2, 2), complex)
        out[..., 0, 0] = beam_receptance(x, f, **lateral)
        out[..., 1, 1] = beam_receptance(x, f, **vertical)
        return out

    return transfer


def beam_impulse(x, t, EI, m, k_s, c_s, k_max=None, n_k=400001):
    """Impulse response g(x, t) (m/(N s)) of the same beam, by superposing the
    damped oscillators of each wavenumber: omega(k)^2 = (EI k^4 + k_s)/m,
    sigma = c_s/(2m) (the same for every k),
    g = exp(-sigma t)/(pi m) int_0^inf cos(k x) sin(w_d t)/w_d dk,
    w_d = sqrt(omega^2 - sigma^2) (needs sigma^2 < k_s/m).  Trapezoidal rule
    up to ``k_max`` (default: where the phase oscillates 500 times)."""
    sig = c_s / (2 * m)
    if sig ** 2 >= k_s / m:
        raise ValueError("beam_impulse assumes every wavenumber under-damped")
    a = np.sqrt(EI / m)
    if k_max is None:
        k_max = np.sqrt(2 * np.pi * 500 / (a * t))
    k = np.linspace(0.0, k_max, n_k)
    wd = np.sqrt((EI * k ** 4 + k_s) / m - sig ** 2)
    y = np.cos(k * x) * np.sin(wd * t) / wd
    return np.exp(-sig * t) / (np.pi * m) * np.trapz(y, k)


def beam_moving_receptance(f, v, EI, m, k_s, c_s, k_max=100.0, n_k=50001):
    """(nf,) spectrum of the moving impulse response, G_mov(W) = int_0^inf g(v t, t) exp(-i W t) dt
    = 1/(2 pi) int_0^inf [B(k, W + k v) + B(k, W - k v)] dk, B(k, W) = 1/(EI k^4 + k_s + i W c_s - m W^2)
    (g(x, t) = 1/(2 pi) int exp(-i k x) b(k, t) dk with b the impulse response of the
    oscillator of wavenumber k, whose transform is B).  v = 0: the point receptance
    beta/(2K).  Trapezoidal rule on [0, k_max] (the integrand is even in k and
    smooth: the peaks at the propagating wavenumber are ~0.04 rad/m wide at 6.5 kHz)
    plus the tail 1/(3 pi EI k_max^3)."""
    W = 2 * np.pi * np.atleast_1d(np.asarray(f, float))
    k = np.linspace(0.0, k_max, n_k)
    wt = np.full(n_k, k[1])
    wt[[0, -1]] *= 0.5
    out = np.empty(len(W), complex)
    for a in range(0, len(W), 32):
        Wc = W[a:a + 32, None]
        tot = 0.0
        for sgn in (1.0, -1.0):
            Om = Wc + sgn * v * k[None, :]
            tot = tot + 1.0 / (EI * k ** 4 + k_s + 1j * Om * c_s - m * Om ** 2)
        out[a:a + 32] = (tot @ wt) / (2 * np.pi) + 1.0 / (3 * np.pi * EI * k_max ** 3)
    return out


# ------------------------------------------------------------------------------ C20 modal data

def _synthetic_c20():
    """Reference frequencies (Table 4.1) + the rigid half-wheelset, masses 10-100 kg,
    contact values typical of a tread point (axial modes mostly lateral, radial
    modes mostly vertical)."""
    rows = list(csv.DictReader(open(DATA / "c20_modes.csv")))
    f = [6.8, 9.7, 15.3] + [float(r["f_hz"]) for r in rows]
    n = [1, 1, 0] + [int(r["n"]) for r in rows]
    m = [0, 0, 0] + [int(r["m"]) for r in rows]
    cls = ["s", "s", "s"] + [r["class"] for r in rows]
    kind = ["bounce", "roll", "lateral"] + ["flexible"] * len(rows)
    rng = np.random.default_rng(20)
    mass = np.concatenate([[1300.0, 1007.0, 1300.0], np.clip(120.0 * np.exp(-np.arange(len(rows)) / 12.0), 10, 100)])
    phi = np.zeros((len(f), 2))
    phi[:3] = [[0.0, 1.0], [-0.5, 0.9], [1.0, 0.0]]
    for i, c in enumerate(cls[3:], start=3):
        main, cross = (0, 1) if c == "a" else (1, 0)
        phi[i, main] = rng.uniform(0.5, 1.0) * rng.choice([-1, 1])
        phi[i, cross] = rng.uniform(0.0, 0.3) * rng.choice([-1, 1])
        if c == "c":
            phi[i] *= 0.05
    zs = np.array([0.18, 0.25, 0.08] + [np.nan] * len(rows))
    return dict(f_hz=np.array(f), n=np.array(n), m=np.array(m), cls=np.array(cls), kind=np.array(kind),
                modal_mass=mass, zeta_suspension=zs, phi=phi, source="synthetic (Table 4.1 frequencies)")


def wheel_case(y=-0.032):
    """Modal data of the C20 at the contact point y^W: dict with f_hz, n, m, cls,
    kind, modal_mass, zeta_suspension, zeta ([4.11]), phi (M, 2) and source."""
    from solvers.wheel.receptance import contact_point, contact_shape, modal_damping  # lazy: brings in scipy

    if ARTIFACT.exists():
        d = np.load(ARTIFACT)
        out = {k: d[k] for k in ("f_hz", "n", "m", "cls", "kind", "modal_mass", "zeta_suspension")}
        surf = np.concatenate([d["boundary_tread"], d["boundary_flange"]])
        cp = contact_point(d["points"], surf, y, Z_RC, r_of_y=tread_radius_function())
        out["phi"] = contact_shape(d["shapes"], cp)
        out["contact"] = cp
        out["source"] = "build/wheels/c20/modes.npz"
    else:
        out = _synthetic_c20()
    out["zeta"] = modal_damping(out["n"], out["m"], out["cls"], out["kind"], out["zeta_suspension"])
    return out


def tread_radius_function():
    """r(y^W) of the C20 running surface (geometry.wheel.tread_radius) with the wheel
    parameters the artifact was built from (its provenance), else the wheel file."""
    p = None
    if ARTIFACT.exists():
        with np.load(ARTIFACT) as d:
            if "__provenance__" in d.files:
                p = json.loads(str(d["__provenance__"])).get("config")
    if p is None:
        p = tomllib.loads(WHEEL_FILE.read_text())
    return lambda y: tread_radius(p, y)


# ------------------------------------------------------------------------------ spectra of kernels

def kernel_spectrum(g, n_t):
    """DFT of a kernel g[0..L-1] zero-padded to n_t, on f_k = k/(n_t dt), k = 0..n_t/2:
    sum_k g[k] exp(-2 pi i f k dt)."""
    import scipy.fft as sfft  # lazy: brings in scipy

    return sfft.rfft(np.asarray(g), n=n_t, axis=0)


def pointwise_error(f, Gd, G, bands=((5.0, 2000.0), (5.0, F_MAX_HZ))):
    """max |Gd - G| / |G| over each frequency band (lo, hi) and where it sits: [(max, f), ...]."""
    with np.errstate(divide="ignore", invalid="ignore"):     # G = 0 outside the bands is allowed
        e = np.abs(Gd - G) / np.abs(G)
    out = []
    for lo, hi in bands:
        sel = (f >= lo) & (f <= hi)
        i = int(np.argmax(e[sel]))
        out.append((float(e[sel][i]), float(f[sel][i])))
    return out


def passivity(G):
    """Smallest eigenvalue of -(G - G^H)/(2i) per frequency (G (nf, 2, 2)): >= 0 where the
    kernel dissipates (passive), < 0 = negative damping."""
    A = -(G - np.conj(np.swapaxes(G, -1, -2))) / 2j
    return np.linalg.eigvalsh(A)[..., 0]


def band_rms(f, A, octave_fraction=1 / 3):
    """RMS of |A| over the fractional-octave band [f 2^(-b/2), f 2^(b/2)] around each f
    (f uniform and increasing): the level a band analysis shows."""
    c = np.concatenate([[0.0], np.cumsum(np.abs(A) ** 2)])
    h = 2 ** (octave_fraction / 2)
    lo = np.searchsorted(f, f / h)
    hi = np.searchsorted(f, f * h, side="right")
    return np.sqrt((c[hi] - c[lo]) / np.maximum(hi - lo, 1))


def participating_peaks(w, i, j, G_at_peaks, f_lo=100.0, f_hi=F_MAX_HZ, share=0.5):
    """Indices of the modes between f_lo and f_hi whose resonant term
    |Phi_i Phi_j| / (2 zeta m w^2) is at least ``share`` of |G_ij| at f_r."""
    phi, m, z, fr = w["phi"], w["modal_mass"], w["zeta"], w["f_hz"]
    peak = np.abs(phi[:, i] * phi[:, j]) / (2 * z * m * (2 * np.pi * fr) ** 2)
    return np.flatnonzero((fr > f_lo) & (fr < f_hi) & (peak >= share * np.abs(G_at_peaks)))
