"""Kalker's linear-theory creepage coefficients (pipeline/validation/references/data/kalker_creep_coefficients.csv,
Kalker's Table E.3) interpolated to a Poisson ratio and semi-axis ratio.

Per the file header: quadratic in 1/C through nu = 0, 0.25, 0.5; between the
tabulated semi-axis ratios linear interpolation (rows 'a/b' for a <= b, 'b/a'
for a >= b, a = semi-axis in the rolling direction)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

CSV = Path(__file__).resolve().parent / "data" / "kalker_creep_coefficients.csv"


def _rows():
    with open(CSV) as f:
        lines = [ln for ln in f if not ln.startswith("#")]
    return list(csv.DictReader(lines))


def _nu_interp(c0, c25, c50, nu):
    inv = np.polyfit([0.0, 0.25, 0.5], [1 / c0, 1 / c25, 1 / c50], 2)
    return 1.0 / np.polyval(inv, nu)


def creep_coefficient(name: str, a: float, b: float, nu: float = 0.3) -> float:
    """C11, C22 or C23 for semi-axes a (rolling direction) and b (lateral)."""
    kind, ratio = ("a/b", a / b) if a <= b else ("b/a", b / a)
    rows = [r for r in _rows() if r["ratio_kind"] == kind]
    g = np.array([float(r["ratio"]) for r in rows])
    c = np.array([_nu_interp(float(r[f"{name}_nu0"]), float(r[f"{name}_nu025"]), float(r[f"{name}_nu05"]), nu)
                  for r in rows])
    if not g[0] - 1e-12 <= ratio <= g[-1] + 1e-12:
        raise ValueError(f"semi-axis ratio {ratio} outside Kalker's table")
    return float(np.interp(ratio, g, c))
