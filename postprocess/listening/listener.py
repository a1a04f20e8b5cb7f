"""What a listener hears: sound pressure at a receiver from the wheel's sound
power (SPEC 5's W per tone and per residual bin), A-weighted and in 1/3-octave
bands.

Pure functions on arrays (no file or configuration I/O); the pipeline's
``listen`` stage loads the radiate stage's artifact and calls these.

Propagation model (stated assumptions)
--------------------------------------
* Source: the squealing wheel as a point source at its centre (height
  ``h_source`` above a plane ground), radiating the Thompson-Jones sound power
  W (SPEC 5, [4.38]); the wheel is abreast of the receiver (the closest point
  of a pass-by: no Doppler shift, no change of distance during the sound).
* Directivity: ``'dipole'`` (default): the squeal modes (n, 0, a) move the
  wheel axially, so the wheel radiates like a dipole along the axle,
  intensity I = W Q / (4 pi r^2) with Q = 3 cos^2(theta), theta from the axle
  (Q integrates to 4 pi over the sphere, so W is conserved); the receiver
  beside the track is near the axis (Q close to 3, +4.8 dB).  A compact-source
  approximation: at squeal frequencies ka = 2 pi f a / c0 is ~5-10 for a
  0.39 m wheel, where a real wheel beams somewhat more along its axis.
  ``'omni'``: Q = 1, the simpler, lower bound on the axis.
* Ground: ``'rigid'``: the exact image source of a rigid plane (reflection
  factor +1; the image of a dipole along the horizontal axle is the same
  dipole).  Tones add coherently with the path difference:
  p^2 = p_d^2 + p_i^2 + 2 p_d p_i cos(k (r_i - r_d)) (+6 dB at grazing,
  interference dips elsewhere); ``incoherent`` gives p_d^2 + p_i^2 (+3 dB at
  most), the band-average of the coherent sum.  ``'none'``: free field.
* Air absorption: ISO 9613-1 (via ``pyfar.constants.air_attenuation``) at
  20 degC, 70 % relative humidity, 101.325 kPa; below 50 Hz (outside the
  standard's range) the 50 Hz value (5.7e-5 dB/m, negligible).
* No shielding by the vehicle body or the rail, no ground impedance, no
  meteorological effects.

Levels: L_p = 10 log10(p^2 / p0^2), p0 = 20 uPa; A-weighting is the IEC
61672-1 analytic curve (``pyfar.constants.frequency_weighting_curve``,
formula E.6 of the standard) evaluated at each component's own frequency;
1/3-octave bands are IEC 61260-1's base-10 bands (G = 10^(3/10), exact
mid-band and edge frequencies from ``pyfar.constants``), filled with ideal
band edges from the line spectrum (tones at their exact frequencies, the
residual per bin), so that the bands' energies add up to the overall level.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solvers.radiation.thompson_jones import C0, RHO_AIR

P_REF = 20e-6  # Pa, reference sound pressure
AIR = {"temperature": 20.0, "relative_humidity": 0.70}  # ISO 9613-1 conditions (degC, fraction)
DIRECTIVITIES = ("dipole", "omni")
GROUNDS = ("rigid", "none")


@dataclass(frozen=True)
class Geometry:
    """Source (wheel centre) and receiver in the plane through the wheel's axle,
    perpendicular to the track.

    ``distance`` (m): horizontal, from the wheel centre to the receiver, along the
    axle; ``h_source``, ``h_receiver`` (m): above the reflecting ground plane;
    ``ground`` 'rigid' or 'none'; ``directivity`` 'dipole' (along the axle) or
    'omni'; ``air`` False to leave out air absorption."""
    distance: float
    h_source: float
    h_receiver: float
    ground: str = "rigid"
    directivity: str = "dipole"
    air: bool = True

    def __post_init__(self):
        if not (self.distance > 0 and self.h_source > 0 and self.h_receiver > 0):
            raise ValueError(f"distance, h_source, h_receiver must be > 0 m, got {self.distance}, "
                             f"{self.h_source}, {self.h_receiver}")
        if self.ground not in GROUNDS or self.directivity not in DIRECTIVITIES:
            raise ValueError(f"ground in {GROUNDS}, directivity in {DIRECTIVITIES}; got {self.ground!r}, "
                             f"{self.directivity!r}")

    def paths(self):
        """((r_d, cos_d), (r_i, cos_i)): lengths (m) of the direct and image paths and the
        cosines of their angles with the axle (the image source is at -h_source)."""
        dz_d, dz_i = self.h_receiver - self.h_source, self.h_receiver + self.h_source
        r_d, r_i = np.hypot(self.distance, dz_d), np.hypot(self.distance, dz_i)
        return (float(r_d), self.distance / float(r_d)), (float(r_i), self.distance / float(r_i))


def directivity_amplitude(kind: str, cos_theta):
    """sqrt(Q) with its sign: Q = 3 cos^2(theta) for a dipole along the axle, 1 for
    'omni' (both normalised so that the mean of Q over the sphere is 1)."""
    if kind == "dipole":
        return np.sqrt(3.0) * np.asarray(cos_theta, float)
    if kind == "omni":
        return np.ones_like(np.asarray(cos_theta, float))
    raise ValueError(f"directivity: one of {DIRECTIVITIES}, got {kind!r}")


def air_attenuation(f) -> np.ndarray:
    """Pure-tone air absorption coefficient alpha(f) (dB/m), ISO 9613-1 at the AIR
    conditions (via pyfar); frequencies below 50 Hz take the 50 Hz value."""
    import pyfar as pf  # lazy: brings in pyfar

    f = np.atleast_1d(np.asarray(f, float))
    fu, inv = np.unique(np.maximum(f, 50.0), return_inverse=True)  # pyfar wants increasing frequencies
    alpha = pf.constants.air_attenuation(AIR["temperature"], fu, AIR["relative_humidity"])[0]
    return np.asarray(alpha, float).reshape(-1)[inv].reshape(f.shape)


def transfer(f, geometry: Geometry, *, c0: float = C0, rho: float = RHO_AIR):
    """Complex pressure per root watt at the receiver, H(f) (Pa / W^0.5), and the
    two paths' magnitudes |H_d|, |H_i| (the image term is 0 without ground):

        p_rms(f) = H(f) sqrt(W(f)),   H = a_d e^{-i k r_d} / r_d + a_i e^{-i k r_i} / r_i,
        a = sqrt(rho c0 / (4 pi)) sqrt(Q(theta)) 10^(-alpha r / 20),  k = 2 pi f / c0.

    The phase is relative to the source's (the same for both paths)."""
    f = np.atleast_1d(np.asarray(f, float))
    (r_d, c_d), (r_i, c_i) = geometry.paths()
    alpha = air_attenuation(f) if geometry.air else np.zeros_like(f)
    k = 2 * np.pi * f / c0
    base = np.sqrt(rho * c0 / (4 * np.pi))
    Hd = base * directivity_amplitude(geometry.directivity, c_d) * 10 ** (-alpha * r_d / 20) / r_d * np.exp(-1j * k * r_d)
    if geometry.ground == "rigid":
        Hi = base * directivity_amplitude(geometry.directivity, c_i) * 10 ** (-alpha * r_i / 20) / r_i * np.exp(-1j * k * r_i)
    else:
        Hi = np.zeros_like(Hd)
    return Hd + Hi, np.abs(Hd), np.abs(Hi)


def mean_square_pressure(f, W, geometry: Geometry, *, coherent: bool = True, c0: float = C0,
                         rho: float = RHO_AIR) -> np.ndarray:
    """Mean-square sound pressure p^2 (Pa^2) at the receiver of components of sound
    power ``W`` (W) at frequencies ``f`` (Hz): |H|^2 W (coherent, for tones), or
    (|H_d|^2 + |H_i|^2) W (incoherent: direct and image powers added)."""
    H, Hd, Hi = transfer(f, geometry, c0=c0, rho=rho)
    g = np.abs(H) ** 2 if coherent else Hd**2 + Hi**2
    return g * np.asarray(W, float)


def level(p2) -> np.ndarray:
    """Sound pressure level 10 log10(p^2 / p0^2) (dB re 20 uPa); -inf for 0."""
    with np.errstate(divide="ignore"):
        return 10 * np.log10(np.asarray(p2, float) / P_REF**2)


def a_weighting(f) -> np.ndarray:
    """A-weighting A(f) (dB), IEC 61672-1 formula E.6 (pyfar); -inf at f <= 0."""
    import pyfar as pf  # lazy: brings in pyfar

    f = np.atleast_1d(np.asarray(f, float))
    out = np.full(f.shape, -np.inf)
    pos = f > 0
    out[pos] = pf.constants.frequency_weighting_curve("A", f[pos])
    return out


@dataclass(frozen=True)
class Bands:
    """IEC 61260-1 fractional-octave bands: ``nominal`` labels, ``centre`` exact
    mid-band frequencies (base 10), ``lower``/``upper`` band edges (Hz)."""
    nominal: np.ndarray
    centre: np.ndarray
    lower: np.ndarray
    upper: np.ndarray


def third_octave_bands(f_lo: float = 10.0, f_hi: float = 20000.0) -> Bands:
    """The 1/3-octave bands (IEC 61260-1, base 10) overlapping [f_lo, f_hi] (Hz)."""
    import pyfar as pf  # lazy: brings in pyfar

    nominal = pf.constants.fractional_octave_frequencies_nominal(3, (f_lo, f_hi))
    centre, lower, upper = pf.constants.fractional_octave_frequencies_exact(3, (f_lo, f_hi))
    if len(nominal) != len(centre) or not np.allclose(nominal, centre, rtol=0.03):
        raise ValueError(f"nominal and exact band lists differ for [{f_lo}, {f_hi}] Hz")
    return Bands(np.asarray(nominal, float), np.asarray(centre, float), np.asarray(lower, float),
                 np.asarray(upper, float))


def band_sums(f, x, bands: Bands):
    """Sum the components ``x`` (e.g. p^2) at frequencies ``f`` into the bands (ideal
    edges, lower <= f < upper).  Returns (per band, the sum outside all bands)."""
    f = np.asarray(f, float)
    x = np.asarray(x, float)
    j = np.searchsorted(bands.upper, f, side="right")  # first band whose upper edge is above f
    inside = (j < len(bands.upper)) & (f >= bands.lower[np.minimum(j, len(bands.lower) - 1)])
    out = np.zeros(len(bands.centre))
    np.add.at(out, j[inside], x[inside])
    return out, float(x[~inside].sum())
