"""Tables of the squeal's sound power in the layouts other tools read (pure functions on arrays;
the radiate stage writes them).

* 1/3-octave band sound power (IEC 61260-1 base-10 bands, ``third_octaves``).
* NoiseModelling's railway source table LW_RAILWAY (Universite-Gustave-Eiffel/NoiseModelling,
  ``noisemodelling-jdbc/.../EmissionTableGenerator.makeTrainLWTable``, commit 35d2da1b of
  2026-07-30): columns ``PK_SECTION, THE_GEOM, DIR_ID, GS`` then one column per 1/3-octave band
  50 Hz-10 kHz and period, ``HZD50 .. HZD10000`` (day), ``HZE..`` (evening), ``HZN..`` (night)
  (the frequency prefix "HZ" that ``Railway_Emission_from_Traffic.groovy`` passes), in dB: the
  sound power per metre of track of a line source, as CNOSSOS-EU (Directive (EU) 2015/996,
  Annex II, 2.3.2, amended by 2021/1226) defines it for a steady traffic flow:

      L_W',eq,line = L_W,0,dir + 10 lg(Q / (1000 v))        (CNOSSOS-EU eq. 2.3.1)

  with Q the number of sources passing per hour and v their speed in km/h (NoiseModelling's
  ``Utils.Vperhour2NoiseLevel``).  Conventions followed here:

  - the source: CNOSSOS-EU's rolling-noise source, height A = 0.5 m above the rail head (h = 1;
    NoiseModelling writes its ROLLING/TRACTIONA/AERODYNAMICA lines at z = 0.5 m), DIR_ID = 1 (the
    rolling-noise directivity, horizontal 10 lg(0.01 + 0.99 sin^2 phi));
  - L_W,0,dir is the squealing wheel's band sound power plus the directivity index of a dipole along
    the axle on its axis, 10 lg 3 = 4.77 dB (the listen stage's Q = 3 cos^2 theta): a dipole along the
    axle radiates as 3 sin^2 phi horizontally (phi from the track direction), which CNOSSOS-EU's
    horizontal rolling directivity reproduces to within its 0.01 floor; its vertical correction for
    source A differs from the dipole's 3 cos^2 psi (stated, not corrected);
  - Q = squealing wheel passages per hour in each period; GS = 1 (NoiseModelling's default ground
    factor of the platform); THE_GEOM is the track of the curve, which a case does not know: left
    empty for the user (or the line study) to fill with the curve's geometry at z = 0.5 m.
  A band below the table's floor is written as -99 (NoiseModelling's value for no source).
"""
from __future__ import annotations

import numpy as np
from postprocess.listening.listener import Bands, band_sums

NM_BANDS_HZ = (50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000, 1250, 1600, 2000, 2500, 3150,
               4000, 5000, 6300, 8000, 10000)  # NoiseModelling's DEFAULT_FREQUENCIES_THIRD_OCTAVE
PERIODS = ("D", "E", "N")
PREFIX = "HZ"
HEAD_COLUMNS = ("PK_SECTION", "THE_GEOM", "DIR_ID", "GS")
SOURCE_HEIGHT_M = 0.5          # CNOSSOS-EU source A (h = 1), above the rail head
DIR_ID_ROLLING = 1             # NoiseModelling's directivity id of the rolling-noise line
DIPOLE_INDEX_DB = 10 * np.log10(3.0)
NO_SOURCE_DB = -99.0


def lw_railway_columns() -> list[str]:
    """The LW_RAILWAY columns in NoiseModelling's order (without its PK, added by the database)."""
    return list(HEAD_COLUMNS) + [f"{PREFIX}{p}{f}" for p in PERIODS for f in NM_BANDS_HZ]


NOMINAL_THIRDS = (10, 12.5, 16, 20, 25, 31.5, 40, 50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000,
                  1250, 1600, 2000, 2500, 3150, 4000, 5000, 6300, 8000, 10000, 12500, 16000, 20000)  # IEC 61260-1 labels


def third_octaves(f_lo: float = 10.0, f_hi: float = 20000.0):
    """The base-10 1/3-octave bands (IEC 61260-1: f_m = 1000 10^(x/10) Hz, edges f_m 10^(+-1/20)) with
    nominal labels from 10 Hz to 20 kHz overlapping [f_lo, f_hi], as ``postprocess.listening.listener.Bands``.
    Computed here rather than through pyfar: the radiate stage runs before the listening packages
    are installed (the same bands as ``listener.third_octave_bands``; tests/report/test_exports.py)."""
    x = np.arange(-20, 14)                                   # 10 Hz .. 20 kHz
    centre = 1000.0 * 10 ** (x / 10)
    lower, upper = centre * 10 ** (-1 / 20), centre * 10 ** (1 / 20)
    sel = (upper > f_lo) & (lower < f_hi)
    return Bands(np.asarray(NOMINAL_THIRDS, float)[sel], centre[sel], lower[sel], upper[sel])


def band_power(f, W, f_lo: float = 10.0, f_hi: float = 20000.0):
    """(Bands, W per band, W outside all bands): the entries W (W at frequencies f, Hz) summed into
    the 1/3-octave bands overlapping [f_lo, f_hi] (ideal edges, as the listen stage's bands)."""
    bands = third_octaves(f_lo, f_hi)
    per, out = band_sums(f, W, bands)
    return bands, per, out


def level(W) -> np.ndarray:
    """10 lg(W / 1e-12 W), -inf for 0."""
    with np.errstate(divide="ignore"):
        return 10 * np.log10(np.asarray(W, float) / 1e-12)


def nm_band_levels(nominal, L_W) -> np.ndarray:
    """The band levels L_W (dB, on the bands ``nominal``, Hz) on NoiseModelling's 24 bands."""
    lut = {int(round(float(n))): float(x) for n, x in zip(nominal, L_W)}
    missing = [f for f in NM_BANDS_HZ if f not in lut]
    if missing:
        raise ValueError(f"band levels lack NoiseModelling's bands {missing} Hz")
    return np.array([lut[f] for f in NM_BANDS_HZ])


def flow_term(Q_per_hour: float, speed_kmh: float) -> float:
    """10 lg(Q / (1000 v)) (CNOSSOS-EU eq. 2.3.1): a point source of power W passing Q times an hour
    at v km/h is a line source of W Q / (1000 v) per metre (time average)."""
    if not (Q_per_hour > 0 and speed_kmh > 0):
        raise ValueError(f"Q = {Q_per_hour} /h and v = {speed_kmh} km/h must be > 0")
    return float(10 * np.log10(Q_per_hour / (1000.0 * speed_kmh)))


def lw_railway_record(band_L_W, speed_kmh: float, flows: dict, pk_section: int = 1, geometry: str = "",
                      gs: float = 1.0) -> dict:
    """One LW_RAILWAY row {column: value}: ``band_L_W`` (24,) the squealing wheel's sound power per
    NoiseModelling band (dB re 1e-12 W), ``flows`` {'D','E','N': squealing passages per hour} (0: no
    source in that period), ``speed_kmh`` the passing speed."""
    L = np.asarray(band_L_W, float)
    if L.shape != (len(NM_BANDS_HZ),):
        raise ValueError(f"band_L_W must have {len(NM_BANDS_HZ)} values, got {L.shape}")
    row = {"PK_SECTION": int(pk_section), "THE_GEOM": geometry, "DIR_ID": DIR_ID_ROLLING, "GS": float(gs)}
    for p in PERIODS:
        q = float(flows.get(p, 0.0))
        vals = (L + DIPOLE_INDEX_DB + flow_term(q, speed_kmh)) if q > 0 else np.full(L.shape, NO_SOURCE_DB)
        for f, v in zip(NM_BANDS_HZ, vals):
            row[f"{PREFIX}{p}{f}"] = float(max(v, NO_SOURCE_DB))
    return row


def band_levels_of_record(row: dict, period: str, speed_kmh: float, Q_per_hour: float) -> np.ndarray:
    """The inverse of ``lw_railway_record`` for one period: the point source's band L_W (dB)."""
    return np.array([float(row[f"{PREFIX}{period}{f}"]) for f in NM_BANDS_HZ]) - DIPOLE_INDEX_DB - flow_term(
        Q_per_hour, speed_kmh)
