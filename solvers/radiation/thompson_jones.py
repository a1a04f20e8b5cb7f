"""Sound radiation of the wheel: the Thompson-Jones model as used in TWINS
(SPEC section 5; thesis section 4.4, equations [4.38]-[4.57]).

Pure functions on arrays: no file or configuration I/O.  The pipeline loads
the wheel's modal artifact and geometry and calls these.

Model
-----
Sound power per frequency, summed over the harmonics n (nodal diameters)
[4.38]::

    W(f) = rho c0 sum_n [ sigma_a(n,f) sum_q S_aq <v_aq^2>(n,f)
                          + sigma_r(n,f) S_r <v_r^2>(n,f)
                          (+ sigma_t(f) S_t <v_t^2>(n,f), neglected by default) ]

* radiation efficiencies [4.39]-[4.50]: ``sigma_axial``, ``sigma_radial``,
  ``sigma_torsion`` (vectorised over n and f by broadcasting), here;
* surfaces [4.51]-[4.53] and which boundary nodes make up each surface:
  ``solvers.radiation.surfaces``;
* velocities [4.54]-[4.57] and the sound power of force spectra (Gram-matrix
  form, per harmonic): ``solvers.radiation.force_power``; the modal sum is
  ``solvers.wheel.receptance.modal_frf`` with the damping rule
  ``solvers.wheel.receptance.modal_damping``;
* ``frequency_grid``: frequencies resolving the wheel's narrow peaks for
  unit-force curves (the curve a designer compares wheels with).

Choices (documented where they are made)
----------------------------------------
* Axial annuli: BOTH faces of the wheel are counted, S_aq = 2 pi (r_{q+1}^2 -
  r_q^2) (``faces=2``).  The axial motion of web and tyre moves both the
  gauge-side and the field-side faces, each radiating into its own half
  space; in the high-frequency limit sigma_a -> 1 each face radiates
  rho c0 S_face <v^2> independently, so the radiating area is that of both
  faces (counting one face would lose 3 dB).  The mean square <v_aq^2> is
  averaged over the nodes of both faces in the annulus.  [4.51] prints
  2 pi (r_{q+1} - r_q), which has the dimension of a length; SPEC 5 asks for the
  annulus area.
* Annulus radii: r_1 = hub outer radius, r_5 = inner tyre radius (from the
  radii dict), r_6 = r the nominal rolling radius; r_2, r_3, r_4 divide the
  web r_1..r_5 into four rings of equal radial width (the web is where the
  axial velocity changes most; the fifth annulus r_5..r_6 is the tyre's side
  faces, as in the thesis' Fig. 4.14).  The disc r < r_1 (hub, axle) is not
  counted [4.57].  Flange-back nodes above r_6 (the flange) are put in the
  outer annulus.
* Web thickness w_web in S_r, S_t and Gamma (a tapered web): by default the
  axial thickness of the web where it meets the tyre, measured on the outline
  (the smallest axial web thickness over the outer quarter of the web,
  r_4 <= r <= r_5, i.e. just below the tyre fillets).  w - w_web is the part of
  the tyre's inner surface the web does not cover, so the web's root, not its
  mean, is what matters.  ``web_thickness='mean'`` takes the dict's value
  (``surface_radii``: mean of hub and tyre thickness), a float is used as is.
* Rigid half-wheelset modes (kind bounce/roll/lateral, 7-15 Hz on the C20):
  included by default with their own damping ``zeta_suspension``: they are
  real motion of the wheel surfaces (a rigid axial translation radiates as
  an n = 0 axial motion, bounce/roll as n = 1), and below ~300 Hz their
  mass-line receptance is comparable to the flexible modes' stiffness line.
  ``rigid=False`` drops them.
* Modal damping [4.11]: one rule, ``solvers.wheel.receptance.modal_damping``.
* Directions at the contact point (phi = 0, the cos twin of each harmonic):
  2 = lateral = +U_z (toward the field side), 3 = vertical = +U_r (radially
  outward = toward the ground at the contact).  The wheel receives -F
  (SPEC 2); the common sign does not change mean squares, so it is left out.
* Force amplitudes: <v^2> follows [4.56] literally (|v|^2 for n = 0, 0.5 |v|^2
  for n > 0; the 0.5 is the circumferential mean of cos^2 n phi).  That is a
  time mean square only if |F| (hence |v|) is an RMS amplitude, so
  the sound power expects RMS force amplitudes.  The unit-force power is per N^2 (RMS): W / F_rms^2.
* Frequency resolution: the wheel's narrow peaks (zeta = 1e-4: -3 dB band
  2 zeta f_r, 0.09 Hz at 434 Hz) make G(f) F(f) on FFT bins (1/T apart)
  sensitive to where the bins fall relative to the modes; for unit-force
  curves use ``frequency_grid``, for a squeal tone evaluate at the
  interpolated tone frequency (``spectra.dominant_frequency``) as well.
"""
from __future__ import annotations

import numpy as np

RHO_AIR = 1.21  # kg/m3 (SPEC 5)
C0 = 343.0  # m/s (SPEC 5)
W_REF = 1e-12  # W, reference sound power


# --------------------------------------------------------------------------
# radiation efficiencies [4.39]-[4.50]
# --------------------------------------------------------------------------
def kappa(n):
    """kappa(n) = 1.9 + 1.015 n - 0.0189 n^2 [4.41]."""
    n = np.asarray(n, dtype=float)
    return 1.9 + 1.015 * n - 0.0189 * n**2


def f_ca(n, r, c0=C0):
    """Axial critical frequency f_ca(n) = c0 kappa(n) / (2 pi r) [4.40]; r the nominal rolling radius."""
    return c0 * kappa(n) / (2 * np.pi * r)


def _ratio_pow(fc, f, p):
    """(fc / f)^p with f = 0 -> inf (efficiency 0 there), fc = 0 -> 0."""
    f = np.asarray(f, dtype=float)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        x = np.where(f > 0, fc / np.where(f > 0, f, 1.0), np.inf)
        return np.where(np.asarray(fc) == 0, 0.0, x**p)


def sigma_axial(n, f, r, c0=C0):
    """Axial radiation efficiency sigma_a = 1 / (1 + (f_ca(n)/f)^(2n+4)) [4.39].
    n and f broadcast against each other (e.g. n[:, None], f[None, :])."""
    n = np.asarray(n)
    return 1.0 / (1.0 + _ratio_pow(f_ca(n, r, c0), f, 2 * n + 4))


def radial_frequencies(n, r):
    """(f_r1(n), f_r2, f_r3(n)) = (120 n, 800, 280 + 150 n) / sqrt(r / 0.42) [4.43]-[4.45]."""
    n = np.asarray(n, dtype=float)
    s = np.sqrt(r / 0.42)
    return 120.0 * n / s, 800.0 / s + 0.0 * n, (280.0 + 150.0 * n) / s


def gamma_cancellation(r, w, r_in, w_web):
    """Gamma = sqrt((S_out - S_in) / (S_out + S_in)) with S_out = 2 pi r w,
    S_in = 2 pi r_in (w - w_web) [4.46]-[4.48]: cancellation between the tread and
    the tyre's inner surface (applies below f_r3)."""
    s_out, s_in = 2 * np.pi * r * w, 2 * np.pi * r_in * (w - w_web)
    return float(np.sqrt((s_out - s_in) / (s_out + s_in)))


def sigma_radial(n, f, r, gamma):
    """Radial radiation efficiency [4.42] with Gamma [4.46]:
    n = 0: Gamma / (1 + (f_r2/f)^2); n > 0: Gamma / (1 + (f_r1/f)^(2n)) / (1 + (f_r2/f)^2),
    where Gamma is the cancellation factor for f < f_r3(n) and 1 above.
    ``gamma`` from ``gamma_cancellation`` (or ``Surfaces.gamma``)."""
    n = np.asarray(n)
    f = np.asarray(f, dtype=float)
    fr1, fr2, fr3 = radial_frequencies(n, r)
    g = np.where(f < fr3, gamma, 1.0)
    t1 = np.where(n == 0, 1.0, 1.0 / (1.0 + _ratio_pow(fr1, f, 2 * n)))
    return g * t1 / (1.0 + _ratio_pow(fr2, f, 2))


def f_ct(w, c0=C0):
    """Torsional critical frequency f_ct = 2 c0 / (pi w) [4.50]; w the tyre width."""
    return 2 * c0 / (np.pi * w)


def sigma_torsion(f, w, c0=C0):
    """Torsional radiation efficiency sigma_t = 1 / (1 + (f_ct/f)^4) [4.49] (independent of n)."""
    return 1.0 / (1.0 + _ratio_pow(f_ct(w, c0), f, 4))


# --------------------------------------------------------------------------
# frequencies and levels
# --------------------------------------------------------------------------
def frequency_grid(f_min: float, f_max: float, f_modes=(), zeta=(), *, per_decade: int = 400,
                   per_peak: int = 41, span: float = 50.0) -> np.ndarray:
    """Frequencies for unit-force curves: a log grid plus, around each mode
    inside the band, ``per_peak`` points spread over f_r (1 +- span zeta_r)
    (denser at the peak, through f_r itself), so the narrow peaks (zeta = 1e-4:
    -3 dB band 2 zeta f_r) are resolved and integrable."""
    f = [np.geomspace(f_min, f_max, int(round(per_decade * np.log10(f_max / f_min))) + 1)]
    x = np.sinh(np.linspace(-np.arcsinh(span), np.arcsinh(span), per_peak))  # offsets in units of zeta
    for fr, z in zip(np.atleast_1d(f_modes), np.atleast_1d(zeta)):
        if f_min <= fr <= f_max:
            f.append(fr * (1 + min(z, 0.02) * x))
    f = np.unique(np.concatenate(f))
    return f[(f >= f_min) & (f <= f_max)]


def level_db(W):
    """10 log10(W / 1e-12) elementwise (dB re 1e-12 W)."""
    W = np.asarray(W, float)
    with np.errstate(divide="ignore"):
        return 10 * np.log10(W / W_REF)
