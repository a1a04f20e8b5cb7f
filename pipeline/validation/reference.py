"""The map study side by side with the reference model's findings (thesis ch. 6, as summarised in
issue 13): per contact position the squealing mode and its share, the low-frequency (< 200 Hz)
region, the L_W band, the friction of the L_W maximum and the creepage threshold per mu.

``reference_table(rows, modes)`` turns the map's rows (map.csv as dicts) into markdown; the
writer pipeline/validation/writers/reference_behaviour.py writes it to docs/validation (the test
tests/study/test_reference_behaviour.py asserts what it states).
"""
from __future__ import annotations

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB

from pipeline.study.agreement import _time_loop_mode

# (dy_wr in mm) -> (reference mode, statement of the reference model, L_W band in dB)
REFERENCE = {
    -5: ("(2,0,a)", "(2,0,a) at its eigenfrequency or 3rd harmonic, L_W ~100-120 dB; a ~90 Hz suspension "
                    "instability only for mu > 0.45 (higher force, less sound)", (100.0, 120.0)),
    -10: ("(3,0,a)", "(3,0,a) at its eigenfrequency or 2nd harmonic, squeal even at low friction, L_W ~120-140 dB, "
                     "highest near mu = 0.25", (120.0, 140.0)),
    -15: ("(2,0,a)", "(2,0,a) in every squealing case, L_W ~120-140 dB, highest near mu = 0.3", (120.0, 140.0)),
}


def position_summary(rows: list[dict], f_modes, labels, level: float = SQUEAL_LEVEL_DB) -> dict:
    """Measured behaviour of one position's rows (floats already parsed)."""
    sq = [r for r in rows if r["L_F2"] >= level]
    modes = [_time_loop_mode(r["f_dominant"], f_modes, labels) for r in sq]
    lw = np.array([r["L_W"] for r in sq if np.isfinite(r["L_W"])])
    mus = sorted({r["mu"] for r in rows})
    thr, lf_mus, lw_by_mu = {}, [], {}
    for mu in mus:
        at = [r for r in sq if r["mu"] == mu]
        thr[mu] = min((abs(r["gamma_y"]) for r in at), default=np.nan)
        if at and sum(m == "track" for m, r in zip(modes, sq) if r["mu"] == mu) > 0.5 * len(at):
            lf_mus.append(mu)
        v = [r["L_W"] for r in at if np.isfinite(r["L_W"])]
        lw_by_mu[mu] = float(np.median(v)) if v else np.nan
    counts = {}
    for m in modes:
        counts[m] = counts.get(m, 0) + 1
    finite = {m: v for m, v in lw_by_mu.items() if np.isfinite(v)}
    return {"n": len(rows), "squealing": len(sq), "modes": counts, "lf_mus": lf_mus,
            "lw_median": float(np.median(lw)) if lw.size else np.nan,
            "lw_p10": float(np.percentile(lw, 10)) if lw.size else np.nan,
            "lw_p90": float(np.percentile(lw, 90)) if lw.size else np.nan,
            "mu_lw_max": max(finite, key=finite.get) if finite else np.nan, "threshold": thr,
            "low_mu_squeal": any(r["mu"] <= 0.2 for r in sq)}


def reference_table(rows: list[dict], modes: dict, level: float = SQUEAL_LEVEL_DB) -> tuple[str, dict]:
    """Markdown side by side per position, and the measured summaries by dy_wr (mm)."""
    out, summ = [], {}
    for dy in sorted(REFERENCE, reverse=True):
        pos = [r for r in rows if round(1e3 * r["dy_wr"]) == dy]
        if not pos:
            continue
        ref_mode, statement, band = REFERENCE[dy]
        f_modes, labels = modes[pos[0]["case"]]
        s = position_summary(pos, f_modes, labels, level)
        summ[dy] = s
        share = s["modes"].get(ref_mode, 0) / s["squealing"] if s["squealing"] else np.nan
        top = ", ".join(f"{m} {n}" for m, n in sorted(s["modes"].items(), key=lambda x: -x[1])[:4])
        thr = ", ".join(f"{mu:.2f}: {t:.3f}" for mu, t in s["threshold"].items() if np.isfinite(t))
        out.append(f"""| {dy} mm | {statement} | {s['squealing']} of {s['n']} squeal: {top}; at {ref_mode}: {100 * share:.0f} %; \
LF-dominated for mu = {', '.join(f'{m:.2f}' for m in s['lf_mus']) or 'none'}; L_W median {s['lw_median']:.0f} dB \
(10-90 %: {s['lw_p10']:.0f}-{s['lw_p90']:.0f}; reference {band[0]:.0f}-{band[1]:.0f}); L_W highest at mu = {s['mu_lw_max']}; \
squeal for mu <= 0.2: {'yes' if s['low_mu_squeal'] else 'no'} | {thr} |""")
    head = ("| position | reference model (thesis ch. 6) | this model | creepage threshold per mu (|gamma_y|) |\n"
            "|---|---|---|---|\n")
    return head + "\n".join(out) + "\n", summ
