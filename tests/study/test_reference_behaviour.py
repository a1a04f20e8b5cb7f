"""The map study against the reference model's findings (issue 13): docs/validation/81_reference_behaviour.md,
from the full map's table when it exists (build/studies/map/map.csv), else the quick map's.  The
fragment states the measured behaviour; the assertions hold what the model already reproduces (the
creepage threshold rises with friction at every position, only axial modes or the track root squeal,
the reference's mode in >= 80 % of the squealing cases at each position, squeal at low friction at
-10 mm, low-frequency dominance only at -5 mm for mu >= 0.45); the L_W bands are reported.

    make study STUDY=map [QUICK=1]; .venv/bin/python -m pytest -q --validation tests/study/test_reference_behaviour.py
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from pipeline.artifacts import atomic_write

ROOT = Path(__file__).resolve().parents[2]


def _rows():
    for name in ("map", "map-quick"):
        p = ROOT / "build" / "studies" / name / "map.csv"
        if p.exists():
            with open(p, newline="") as fh:
                rows = list(csv.DictReader(fh))
            for r in rows:
                for k in ("dy_wr", "gamma_y", "mu", "L_F2", "f_dominant", "L_W"):
                    r[k] = float(r[k])
            return name, rows
    pytest.fail("run `make study STUDY=map QUICK=1` (or the full map) first")


@pytest.mark.validation
def test_reference_behaviour():
    from pipeline import artifacts, paths
    from pipeline.config import load
    from pipeline.study.reference import reference_table
    from pipeline.schemas import CASE

    name, rows = _rows()
    modes = {}
    for case in {r["case"] for r in rows}:
        m, _ = artifacts.load_npz(paths.wheel_dir(load(paths.case_file(case), CASE)["wheel"]) / "modes.npz", "wheel-modes")
        modes[case] = (m["f_hz"], [f"({n},{k},{c})" for n, k, c in zip(m["n"], m["m"], m["cls"])])
    table, summ = reference_table(rows, modes)
    for dy, s in summ.items():
        thr = [t for _, t in sorted(s["threshold"].items()) if np.isfinite(t)]
        assert thr and thr[-1] >= thr[0], (dy, s["threshold"])                 # rises (or holds) with mu
        assert all(m == "track" or m.endswith(",0,a)") or m.startswith("?") for m in s["modes"]), s["modes"]
    # what the model reproduces now (issue 13), kept from regressing: at -5 mm the reference's mode in
    # >= 80 % of the squealing cases with mu < 0.45, and low-frequency oscillations dominate nowhere
    # below mu = 0.45
    from pipeline.study.reference import REFERENCE, position_summary

    m5 = modes[next(r["case"] for r in rows if round(1e3 * r["dy_wr"]) == -5)]
    s5 = position_summary([r for r in rows if round(1e3 * r["dy_wr"]) == -5 and r["mu"] < 0.45], *m5)
    assert s5["modes"].get("(2,0,a)", 0) >= 0.8 * s5["squealing"], s5["modes"]
    assert all(mu >= 0.45 for s in summ.values() for mu in s["lf_mus"]), {d: s["lf_mus"] for d, s in summ.items()}
    assert all(not s["lf_mus"] for d, s in summ.items() if d != -5), {d: s["lf_mus"] for d, s in summ.items()}
    shares = {-5: s5["modes"].get("(2,0,a)", 0) / max(s5["squealing"], 1)}
    for dy in (-10, -15):
        shares[dy] = summ[dy]["modes"].get(REFERENCE[dy][0], 0) / max(summ[dy]["squealing"], 1)
        assert shares[dy] >= 0.8, (dy, summ[dy]["modes"])
    assert any(r["mu"] <= 0.2 and r["L_F2"] >= 10.0 for r in rows if round(1e3 * r["dy_wr"]) == -10)
    bands = []
    for dy, s in summ.items():
        lo, hi = REFERENCE[dy][2]
        lw = [r["L_W"] for r in rows if round(1e3 * r["dy_wr"]) == dy and r["L_F2"] >= 10.0 and np.isfinite(r["L_W"])]
        bands.append(f"{dy} mm: {100 * np.mean([(lo <= v <= hi) for v in lw]):.0f} % in {lo:.0f}-{hi:.0f} dB")
    bands = "; ".join(bands)
    text = f"""## The map against the reference model's findings (issue 13)

Test: `tests/study/test_reference_behaviour.py` (validation suite), from `build/studies/{name}/map.csv`
({len(rows)} cases). A squeal's mode is the (n,m,c) whose eigenfrequency, 2nd or 3rd harmonic lies within 1 %
of the dominant force frequency; below 200 Hz it is the track (the wheelset bouncing on the rail).
With the thesis' contact points read correctly (y^W flange-positive: -5, +4, +32 mm), the worn
profiles, the calibrated vertical suspension damping and the C20 section fitted to the coupling zero
points ("Calibration" above), the reference's mode squeals in {100 * shares[-5]:.0f} % of the squealing
cases at -5 mm (mu < 0.45), {100 * shares[-10]:.0f} % at -10 mm and {100 * shares[-15]:.0f} % at -15 mm
(asserted: >= 80 %). The mode selection was targeted with the linear screen in full slip; this
nonlinear time-loop map is its check. The L_W bands are not reproduced at -5 and -15 mm (below):
the sound levels are a prediction, not a target.

Share of the squealing cases in the reference's L_W band: {bands}.

{table}"""
    with atomic_write(ROOT / "docs" / "validation" / "81_reference_behaviour.md") as tmp:
        tmp.write_text(text)

