"""The stability screen against the time loop over a map study (stability_agreement.md).

For each squealing case of the time loop's map (L_F2 >= the squeal level, SPEC 6) the mode it
squeals at (``solvers.study.nearest_mode`` of the dominant force frequency, fundamental or 2nd/3rd
harmonic within 5 %; 'track' below 200 Hz) against the screen's fastest-growing pole; and the
screen as a filter: the smallest largest-growth-rate among squealing cases (the margin a
screened map needs so that no squealing case is skipped) and the share of quiet cases it would skip.
"""
from __future__ import annotations

import csv

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.config.case import resolve_case
from solvers.study import nearest_mode

LF_HZ = 200.0


def _time_loop_mode(f: float, f_modes, labels) -> str:
    if not np.isfinite(f):
        return ""
    if f < LF_HZ:
        return "track"
    j = nearest_mode(f, f_modes, rel_tol=0.01, harmonics=(1, 2, 3))
    return str(labels[j]) if j is not None else f"? {f:.0f} Hz"


def agreement(rows: list[dict], table: list[dict], level: float, modes: dict) -> dict:
    """Per case (position): squealing cases, agreement share, margin, skippable quiet share."""
    screen = {(r["case"], round(r["gamma_y"], 6), round(r["mu"], 6)): r for r in rows}
    out = {}
    for case in sorted({r["case"] for r in rows}):
        f_modes, labels = modes[case]
        sq, agree, quiet_sig, sq_sig, pairs = 0, 0, [], [], {}
        for t in table:
            if t["case"] != case:
                continue
            s = screen.get((case, round(float(t["gamma_y"]), 6), round(float(t["mu"]), 6)))
            if s is None:
                continue
            if float(t["L_F2"]) >= level:
                sq += 1
                tl = _time_loop_mode(float(t["f_dominant"]), f_modes, labels)
                agree += tl == s["label_max"]
                pairs[(tl, s["label_max"])] = pairs.get((tl, s["label_max"]), 0) + 1
                sq_sig.append(s["sigma_max"])
            else:
                quiet_sig.append(s["sigma_max"])
        margin = min(sq_sig) if sq_sig else np.nan
        out[case] = {"squealing": sq, "agree": agree, "share": agree / sq if sq else np.nan, "margin": margin,
                     "quiet": len(quiet_sig),
                     "skippable": float(np.mean(np.array(quiet_sig) < margin)) if quiet_sig and sq_sig else np.nan,
                     "pairs": pairs}
    return out


def write_agreement(out, rows: list[dict], spec: dict) -> dict:
    with open(out / "map.csv", newline="") as fh:
        table = list(csv.DictReader(fh))
    modes = {}
    for case in spec["cases"]:
        c = resolve_case(case).case
        m, _ = artifacts.load_npz(paths.wheel_dir(c["wheel"]) / "modes.npz", "wheel-modes")
        modes[case] = (m["f_hz"], [f"({n},{k},{c_})" for n, k, c_ in zip(m["n"], m["m"], m["cls"])])
    res = agreement(rows, table, spec["simulation"]["squeal_level"], modes)
    lines = ["| case | squealing (time loop) | screen's fastest = time loop's mode | share | smallest sigma_max of a "
             "squealing case (1/s) | quiet cases below it |", "|---|---|---|---|---|---|"]
    for case, r in res.items():
        lines.append(f"| {case} | {r['squealing']} | {r['agree']} | {100 * r['share']:.0f} % | {r['margin']:+.2f} | "
                     f"{100 * r['skippable']:.0f} % of {r['quiet']} |")
    lines.append("")
    lines.append("Pairs (time loop's mode, screen's fastest) and their counts: " + "; ".join(
        f"{case}: " + ", ".join(f"{a} / {b}: {n}" for (a, b), n in sorted(r["pairs"].items(), key=lambda x: -x[1]))
        for case, r in res.items()))
    text = "\n".join(lines) + "\n"
    with artifacts.atomic_write(out / "stability_agreement.md") as tmp:
        tmp.write_text(text)
    return res
