"""The tram wheel's modes (geometry/wheels/tram.toml) by a second method: a full 3D model.

No published modal table of a solid tram wheel was found (docs/tram.md), so the wheel stage's
Fourier-harmonic modes of the tram wheel (``pipeline.stages.wheel.modes_for_parameters``, the modes
the verdict uses) are checked against the 3D solid of docs/validation/22_wheel_3d.md: the same
cross-section (bore clamped, polylines thinned by Douglas-Peucker to 0.75 mm so that the 3D mesh has
no sub-millimetre edges) revolved 360 degrees, P2 tetrahedra, SLEPc shift-invert
(``pipeline.validation.revolved_wheel.solve_3d``).  For each axial zero-nodal-circle mode (n, 0, a),
n = 0..N_MAX, the nearest 3D frequency is taken (a degenerate pair for n >= 1).
"""
from __future__ import annotations

import tempfile

import numpy as np

from geometry.outline import Segment
from geometry.wheel import wheel_segments
from pipeline.stages.wheel import load_wheel, modes_for_parameters
from pipeline.validation.revolved_wheel import SIMPLIFY_TOL, _douglas_peucker, solve_3d

N_MAX = 4          # (n, 0, a) compared for n = 0..N_MAX
SIZE_3D = 0.017    # m, the finest 3D size of docs/validation/22_wheel_3d.md (C20: axial modes within 1.3 %)
TOL = 0.02         # relative agreement required (the C20 study's criterion, revolved_wheel.TOL)


def tram_params() -> dict:
    """tram.toml validated as the wheel stage reads it, the wheel alone with its bore clamped."""
    p, _ = load_wheel("tram")
    p["mount"]["type"] = "clamped"
    return p


def thinned_segments(p: dict, tol: float = SIMPLIFY_TOL) -> list[Segment]:
    return [Segment(s.name, _douglas_peucker(np.asarray(s.points, float), tol), s.size) for s in wheel_segments(p)]


def axial_modes(model: dict, n_max: int = N_MAX) -> dict[int, float]:
    """(n, 0, a) frequencies of a wheel-stage modal model, n = 0..n_max."""
    f, n, m, cls = (np.asarray(model[k]) for k in ("f_hz", "n", "m", "cls"))
    return {k: float(f[(n == k) & (m == 0) & (cls == "a")][0]) for k in range(n_max + 1)}


def compare(h: float = SIZE_3D) -> list[dict]:
    """Rows n, f_harmonic (wheel stage), f_3d (nearest 3D modes), err = f_3d / f_harmonic - 1."""
    p = tram_params()
    with tempfile.TemporaryDirectory() as d:
        harm = axial_modes(modes_for_parameters(p, d))
    E, nu, rho = (p["material"][k] for k in ("E", "nu", "rho"))
    nev = 6 + 2 * (N_MAX + 1) * 3  # enough 3D modes to pass the highest (n, 0, a) compared
    sol = solve_3d(thinned_segments(p), h, E, nu, rho, nev)
    rows = []
    for n, fh in harm.items():
        k = 1 if n == 0 else 2
        f3 = np.sort(sol.freqs[np.argsort(np.abs(sol.freqs - fh))[:k]])
        rows.append(dict(n=n, f_harmonic=fh, f_3d=f3, err=f3 / fh - 1.0))
    return rows


if __name__ == "__main__":
    for r in compare():
        print(f"n={r['n']}: wheel stage {r['f_harmonic']:8.1f} Hz, 3D {np.round(r['f_3d'], 1)} Hz, "
              f"err {np.round(100 * r['err'], 2)} %")
