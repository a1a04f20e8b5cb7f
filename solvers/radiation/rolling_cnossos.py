"""CNOSSOS-EU railway rolling noise: the sound power of one vehicle per 1/3-octave band.

Directive 2002/49/EC Annex II section 2.3.2 as replaced by Commission Directive (EU) 2015/996
(corrigendum OJ L 5, 10.1.2018) and amended by Commission Delegated Directive (EU) 2021/1226; the
equation numbers are those of that consolidated Annex II.  Pure functions on arrays (levels in dB):
the tables (Appendix G, as NoiseModelling ships them) are read by ``pipeline.config.cnossos``.

Chain, for a vehicle of N_a axles at speed v on one track:

* roughness is tabulated per wavelength lambda on the 35 1/3-octave wavelengths
  ``WAVELENGTH_MM`` (2000 mm ... 0.8 mm, exact base-10 values 10^(m/10) mm, m = 33 ... -1):
  wheel L_r,VEH (Table G-1), rail L_r,TR (Table G-1), impact L_R,IMPACT (Table G-4) and the
  contact filter A_3 (Table G-2);
* total effective roughness (2.3.7), with the impact roughness of joints/switches added energetically
  (2.3.12, scaled by the joint density n_l as 10 lg(n_l / 0.01)):
  L_R,TOT(lambda) = 10 lg(10^(L_r,TR/10) + 10^(L_r,VEH/10) [+ 10^(L_R,IMPACT/10)]) + A_3;
  as NoiseModelling does, the contact filter is applied to the impact part too;
* wavelength to frequency with f = v / lambda, v in m/s (the 2018 corrigendum): the energy
  10^(L_R,TOT/10) is interpolated linearly against lg f onto the 24 exact 1/3-octave midbands
  10^(k/10) Hz, k = 17 ... 40 (50 Hz ... 10 kHz); NoiseModelling's ``RailwayCnossos.getLWRoughness``;
* sound power per vehicle of the track (2.3.8), the vehicle/wheel (2.3.9) and, for freight wagons
  only, the superstructure (2.3.10): L_W,0,x,i = L_R,TOT,i + L_H,x,i + 10 lg(N_a), with the
  transfer functions L_H (Table G-3) per axle; rolling noise is their energy sum, radiated by
  source A (h = 1, 0.5 m above the rail head, (2.3.1));
* per metre of line for a flow of Q vehicles per hour (2.3.2): + 10 lg(Q / (1000 v)), v in km/h;
* directivity of source A (optional): horizontal dipole (2.3.15), vertical (2.3.16) in its 2021
  form (zero for psi <= 0), as NoiseModelling's ``RailWayCnossosParameters.getDirectionAttenuation``.

Outside the table (f < v / 2000 mm or f > v / 0.8 mm: below ~29 km/h at 10 kHz, above ~360 km/h at
50 Hz) the end energies are held (``np.interp``); NoiseModelling returns NaN there (copying a
neighbour at low frequency, leaving NaN at the top), so the two differ only in such bands.
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "BAND_EXPONENTS",
    "F_CENTRE_EXACT",
    "F_CENTRE_NOMINAL",
    "WAVELENGTH_MM",
    "N_BANDS",
    "N_WAVELENGTHS",
    "SOURCE_HEIGHT_M",
    "db_sum",
    "total_roughness_wavelength",
    "roughness_to_frequency",
    "rolling_power",
    "line_power_per_metre",
    "directivity_source_a",
]

BAND_EXPONENTS = np.arange(17, 41)                         # 10 lg f of the 24 bands
F_CENTRE_EXACT = 10.0 ** (BAND_EXPONENTS / 10.0)           # Hz, 50.12 ... 10000
F_CENTRE_NOMINAL = np.array([50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000, 1250,
                             1600, 2000, 2500, 3150, 4000, 5000, 6300, 8000, 10000], dtype=float)
WAVELENGTH_MM = 10.0 ** (np.arange(33, -2, -1) / 10.0)     # 1995.3 ... 0.794 mm (nominal 2000 ... 0.8)
N_BANDS = F_CENTRE_EXACT.size                              # 24
N_WAVELENGTHS = WAVELENGTH_MM.size                         # 35
SOURCE_HEIGHT_M = 0.5                                      # source A (h = 1), (2.3.1)
REFERENCE_JOINT_DENSITY = 0.01                             # 1/m: Table G-4 is for one joint per 100 m


def db_sum(*levels, axis=None) -> np.ndarray:
    """Energy sum of levels in dB: 10 lg(sum 10^(L/10)) over the arguments (or over ``axis``)."""
    if axis is not None:
        return 10.0 * np.log10(np.sum(10.0 ** (np.asarray(levels[0], float) / 10.0), axis=axis))
    return 10.0 * np.log10(sum(10.0 ** (np.asarray(x, float) / 10.0) for x in levels))


def _check(name: str, a, n: int) -> np.ndarray:
    a = np.asarray(a, dtype=float)
    if a.shape[-1:] != (n,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: expected {n} finite values (last axis), got shape {a.shape}")
    return a


def total_roughness_wavelength(rail_db, wheel_db, contact_filter_db, impact_db=None,
                               joint_density_per_m: float = REFERENCE_JOINT_DENSITY) -> np.ndarray:
    """L_R,TOT(lambda) in dB re 1 um on ``WAVELENGTH_MM``: (2.3.7) with the impact roughness of
    (2.3.12) (``impact_db`` for one joint per 100 m, scaled to ``joint_density_per_m``) added to the
    rail and wheel roughness before the contact filter A_3 (NoiseModelling's order)."""
    rail = _check("rail roughness", rail_db, N_WAVELENGTHS)
    wheel = _check("wheel roughness", wheel_db, N_WAVELENGTHS)
    a3 = _check("contact filter", contact_filter_db, N_WAVELENGTHS)
    parts = [rail, wheel]
    if impact_db is not None:
        if not joint_density_per_m > 0.0:
            raise ValueError(f"joint density {joint_density_per_m!r} 1/m: must be > 0 (omit impact_db for none)")
        parts.append(_check("impact roughness", impact_db, N_WAVELENGTHS)
                     + 10.0 * np.log10(joint_density_per_m / REFERENCE_JOINT_DENSITY))
    return db_sum(*parts) + a3


def roughness_to_frequency(level_lambda_db, speed_kmh: float) -> np.ndarray:
    """A level tabulated on ``WAVELENGTH_MM`` read on the 24 bands ``F_CENTRE_EXACT`` at speed v:
    f = v / lambda (v in m/s), energy interpolated linearly in lg f, end values held."""
    level = _check("roughness", level_lambda_db, N_WAVELENGTHS)
    if not (np.isfinite(speed_kmh) and speed_kmh > 0.0):
        raise ValueError(f"speed {speed_kmh!r} km/h: must be > 0")
    lg_f = np.log10(speed_kmh / 3.6 / (WAVELENGTH_MM * 1e-3))   # increasing with the table index
    energy = 10.0 ** (level / 10.0)
    out = np.empty(level.shape[:-1] + (N_BANDS,))
    for idx in np.ndindex(level.shape[:-1]):
        out[idx] = np.interp(BAND_EXPONENTS / 10.0, lg_f, energy[idx])
    return 10.0 * np.log10(out)


def rolling_power(roughness_f_db, track_transfer_db, vehicle_transfer_db, n_axles: float,
                  superstructure_transfer_db=None) -> dict[str, np.ndarray]:
    """Rolling sound power per vehicle per band (dB re 1 pW), source A.

    ``roughness_f_db``: L_R,TOT,i on the 24 bands; transfer functions L_H per axle (24 values).
    Returns ``track`` (2.3.8), ``vehicle`` (2.3.9), ``superstructure`` (2.3.10, only if its transfer
    function is given: freight wagons) and ``total``, their energy sum."""
    r = _check("total roughness", roughness_f_db, N_BANDS)
    if not (np.isfinite(n_axles) and n_axles > 0.0):
        raise ValueError(f"axles per vehicle {n_axles!r}: must be > 0")
    axles = 10.0 * np.log10(n_axles)
    out = {"track": r + _check("track transfer", track_transfer_db, N_BANDS) + axles,
           "vehicle": r + _check("vehicle transfer", vehicle_transfer_db, N_BANDS) + axles}
    if superstructure_transfer_db is not None:
        out["superstructure"] = r + _check("superstructure transfer", superstructure_transfer_db, N_BANDS) + axles
    out["total"] = db_sum(*out.values())
    return out


def line_power_per_metre(power_per_vehicle_db, vehicles_per_hour: float, speed_kmh: float) -> np.ndarray:
    """(2.3.2): L_W',eq,line = L_W,0 + 10 lg(Q / (1000 v)), Q vehicles per hour, v in km/h: the
    time-averaged sound power per metre of line (dB re 1 pW/m)."""
    if not (vehicles_per_hour > 0.0 and speed_kmh > 0.0):
        raise ValueError(f"flow {vehicles_per_hour!r} /h and speed {speed_kmh!r} km/h: both must be > 0")
    return np.asarray(power_per_vehicle_db, float) + 10.0 * np.log10(vehicles_per_hour / (1000.0 * speed_kmh))


def directivity_source_a(phi_rad: float, psi_rad: float, f_hz=F_CENTRE_EXACT) -> np.ndarray:
    """Directivity of source A per band (dB): horizontal (2.3.15) 10 lg(0.01 + 0.99 sin^2 phi), phi
    from the direction of travel, plus vertical (2.3.16) 40/3 (2/3 sin 2psi - sin psi)
    lg((f + 600)/200) for psi > 0 (0 below the horizontal), f the band's midband frequency."""
    f = np.asarray(f_hz, dtype=float)
    hor = 10.0 * np.log10(0.01 + 0.99 * np.sin(phi_rad) ** 2)
    psi = min(max(psi_rad, -np.pi / 2), np.pi / 2)
    ver = (40.0 / 3.0) * (2.0 / 3.0 * np.sin(2 * psi) - np.sin(psi)) * np.log10((f + 600.0) / 200.0) if psi > 0 \
        else np.zeros_like(f)
    return hor + ver
