"""The map study against the reference model's findings (issue 13): docs/validation/81_reference_behaviour.md,
from the full map's table when it exists (build/studies/map/map.csv), else the quick map's.  The
fragment states the measured behaviour; the assertions hold what the model already reproduces (the
creepage threshold rises with friction at every position, only axial modes or the track root squeal,
the reference's mode in >= 80 % of the squealing cases at each position, squeal at low friction at
-10 mm, low-frequency dominance only at -5 mm for mu >= 0.45); the L_W bands are reported.

    make study STUDY=map [QUICK=1]; .venv/bin/python -m pytest -q --validation tests/study/test_reference_behaviour.py

``test_reference_rows`` (issue 28): every row of the issue's table measured on the map's simulation at
5 creepages x 11 friction coefficients per position (``python -m pipeline.validation.limit_cycle_runs``:
build/studies/limit-cycle/), with its verdict and computed reason (``pipeline.validation.reference_rows``);
it writes its own section at the end of the fragment (kept when the map's part is rewritten) and
asserts the parts reproduced.
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

from pipeline.store.artifacts import atomic_write

ROOT = Path(__file__).resolve().parents[2]
FRAGMENT = ROOT / "docs" / "validation" / "81_reference_behaviour.md"
ROWS_MARK = "\n### The reference's findings row by row (issue 28)\n"


def _kept_rows_section() -> str:
    old = FRAGMENT.read_text() if FRAGMENT.exists() else ""
    return old[old.index(ROWS_MARK):] if ROWS_MARK in old else ""


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
    from pipeline.store import artifacts, paths
    from pipeline.config.loader import load
    from pipeline.validation.reference import reference_table
    from pipeline.config.input_schemas import CASE

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
    from pipeline.validation.reference import REFERENCE, position_summary

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
    text = text.rstrip("\n") + "\n" + _kept_rows_section()
    with atomic_write(FRAGMENT) as tmp:
        tmp.write_text(text)


@pytest.mark.validation
def test_reference_rows():
    from pipeline.validation.reference_rows import evaluate, markdown

    d = ROOT / "build" / "studies" / "limit-cycle"
    if not (d / "slices.csv").exists():
        pytest.fail("run `.venv/bin/python -m pipeline.validation.limit_cycle_runs` first")
    rows = evaluate(d)
    assert len(rows) == 5
    rep = {r["row"].split(":")[0] + ": " + k: v for r in rows for k, v in r["reproduced"].items()}
    # what the model reproduces (measured on the slices): the level rises with creepage at -5 and -15 mm,
    # -5 mm is quieter than -10 mm wherever both squeal, and the reference's case I (-10 mm, mu 0.25) needs
    # less force than its case II (mu 0.55) at gamma_y = -0.04
    for key in ("-5 mm: rise with creepage", "-15 mm: rise with creepage", "-5 mm: below -10 mm",
                "-10 mm: case I lower in force"):
        assert rep[key], (key, rep)
    # and what it does not (each with its computed reason in the fragment): kept honest, so that a model
    # change that reproduces one shows up here
    for key in ("-5 mm: no squeal at low creepage/friction", "-5 mm: rise with friction", "-5 mm: below -15 mm",
                "-10 mm: case I louder", "-15 mm squeals at mu = 0.25 ((2,0,a) at gamma_y = -0.012 and -0.04): "
                "squeals at mu = 0.25"):
        assert not rep[key], (key, rep)
    section = f"""{ROWS_MARK}
Test: `tests/study/test_reference_rows` (validation suite), from `python -m pipeline.validation.limit_cycle_runs`
(build/studies/limit-cycle/: the map's simulation and measures at gamma_y = -0.004, -0.012, -0.02,
-0.04, -0.06 and mu = 0.10 ... 0.60 at each position; the screen; the friction curves' knees; the
wheel's modal coupling at the contact points). The mechanism behind every reason is in "The limit
cycle: what bounds it": the cycle is bounded by the saturation of the regularized friction curve,
so the slip velocity, not the force, is what the contact fixes. No model change was made for these rows.

{markdown(rows)}
"""
    old = FRAGMENT.read_text() if FRAGMENT.exists() else ""
    head = old[:old.index(ROWS_MARK)] if ROWS_MARK in old else old
    with atomic_write(FRAGMENT) as tmp:
        tmp.write_text(head.rstrip("\n") + "\n" + section)

