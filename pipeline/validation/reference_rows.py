"""The rows of issue 28's table (the reference's findings, thesis ch. 6) measured on this model: for
each, the measured value, which parts are reproduced, and where not, the computed reason.

Inputs are the tables of ``python -m pipeline.validation.limit_cycle_runs`` (build/studies/limit-cycle/):
slices.csv (the map's simulation at 5 creepages x 11 friction coefficients per position), growth.csv
(the screen's (2,0,a) growth rates), knees.csv (s_knee of every friction curve), coupling.csv (the
one-mode full-slip thresholds mu_c = -Phi3/Phi2).  ``evaluate`` returns the rows; the test
tests/study/test_reference_behaviour.py asserts the reproduced parts; the writer
pipeline/validation/writers/reference_behaviour.py writes them to docs/validation/81_reference_behaviour.md.
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB as SQUEAL


def read(path: Path) -> list[dict]:
    def num(v):
        try:
            return float(v)
        except ValueError:
            return v

    with open(path, newline="") as fh:
        return [{k: num(v) for k, v in r.items()} for r in csv.DictReader(fh)]


def _pos(r) -> int:
    return int(round(1e3 * r["dy_wr"]))


def _at(rows, dy, gy, mu):
    return next(r for r in rows if _pos(r) == dy and abs(r["gamma_y"] - gy) < 1e-9 and abs(r["mu"] - mu) < 1e-9)


def _sq(r) -> bool:
    return np.isfinite(r["L_F2"]) and r["L_F2"] >= SQUEAL


def _wheel_sq(r) -> bool:
    """A squeal at a wheel mode (not the ~70 Hz track root)."""
    return _sq(r) and r["f_dominant"] > 200


def _monotone(seq, tol=0.05) -> bool:
    return all(b >= a - tol for a, b in zip(seq, seq[1:]))


def evaluate(d: Path) -> list[dict]:
    sl, gr, kn, cp = (read(d / f) for f in ("slices.csv", "growth.csv", "knees.csv", "coupling.csv"))
    gammas = sorted({r["gamma_y"] for r in sl}, reverse=True)
    mus = sorted({r["mu"] for r in sl})
    knee = {(_pos(r), r["mu"]): r["s_knee"] for r in kn}
    muc = {(r["case"], r["label"]): r["mu_c"] for r in cp}
    sig = {(_pos(r), r["gamma_y"], r["mu"]): r["sigma"] for r in gr}
    v = sl[0]["s0"] / abs(sl[0]["gamma_y"])
    out = []

    # row 1: -5 mm, no squeal at low creepage and low friction; levels rise with creepage and friction
    low = _at(sl, -5, gammas[0], mus[0])
    rise_c = all(_monotone([r["L_W"] for r in (_at(sl, -5, g, mu) for g in gammas) if _wheel_sq(r)])
                 for mu in mus if mu < 0.45)
    per_mu = [[_at(sl, -5, g, mu)["L_W"] for mu in mus if mu < 0.45 and _wheel_sq(_at(sl, -5, g, mu))] for g in gammas]
    change = [p[-1] - p[0] for p in per_mu if len(p) > 1]
    out.append({"row": "-5 mm: no squeal at low creepage and low friction; levels rise with creepage and friction",
                "measured": f"squeals at |gamma_y| = {abs(gammas[0])}, mu = {mus[0]} (L_F2 {low['L_F2']:.1f} dB, L_W "
                            f"{low['L_W']:.1f} dB); L_W rises with creepage at every mu < 0.45: {'yes' if rise_c else 'no'}; "
                            f"from the smallest to the largest squealing mu < 0.45 it changes by {min(change):+.1f}.."
                            f"{max(change):+.1f} dB at fixed creepage",
                "reproduced": {"no squeal at low creepage/friction": not _sq(low), "rise with creepage": rise_c,
                               "rise with friction": min(change) > 0},
                "reason": f"(2,0,a)'s one-mode full-slip threshold at -5 mm is mu_c = -Phi3/Phi2 = "
                          f"{muc[('dy05', '(2,0,a)')]:.3f} (coupling.csv), below the lowest mu of the map; the screen gives "
                          f"sigma = {sig[(-5, gammas[0], mus[0])]:+.1f} 1/s at ({gammas[0]}, {mus[0]}); and the slip "
                          f"margin |gamma_y| V - s_knee = {abs(gammas[0]) * v:.3f} - {knee[(-5, mus[0])]:.3f} m/s > 0. The "
                          f"level falls with mu because the limit cycle is bounded by the margin (68_limit_cycle) and "
                          f"s_knee grows with mu ({knee[(-5, mus[0])]:.3f} m/s at mu = {mus[0]}, {knee[(-5, 0.45)]:.3f} at 0.45)"})

    # row 2: -5 mm L_W 100-120 dB, up to 20 dB below -10 and -15 mm for the same parameters
    common = [(g, mu) for g in gammas for mu in mus
              if all(_wheel_sq(_at(sl, dy, g, mu)) for dy in (-5, -10, -15))]
    d10 = np.array([_at(sl, -5, g, mu)["L_W"] - _at(sl, -10, g, mu)["L_W"] for g, mu in common])
    d15 = np.array([_at(sl, -5, g, mu)["L_W"] - _at(sl, -15, g, mu)["L_W"] for g, mu in common])
    lw5 = np.array([r["L_W"] for r in sl if _pos(r) == -5 and _wheel_sq(r)])
    rad = {dy: np.median([r["L_W"] - 20 * np.log10(r["s2_rms"]) for r in sl if _pos(r) == dy and _wheel_sq(r)])
           for dy in (-5, -10, -15)}
    srm = {dy: _at(sl, dy, -0.04, 0.35)["s2_rms"] for dy in (-5, -10, -15)}
    out.append({"row": "-5 mm: L_W about 100-120 dB, up to 20 dB below -10 and -15 mm for the same parameters",
                "measured": f"{100 * np.mean((lw5 >= 100) & (lw5 <= 120)):.0f} % of the squealing -5 mm runs in "
                            f"100-120 dB ({lw5.min():.0f}-{lw5.max():.0f}); where all three squeal ({len(d10)} points) "
                            f"L_W(-5) - L_W(-10) = {d10.min():+.1f}..{d10.max():+.1f} dB (median {np.median(d10):+.1f}), "
                            f"L_W(-5) - L_W(-15) = {d15.min():+.1f}..{d15.max():+.1f} dB (median {np.median(d15):+.1f})",
                "reproduced": {"below -10 mm": bool(np.all(d10 < 0)), "below -15 mm": bool(np.all(d15 < 0)),
                               "differences up to 20 dB": bool(min(d10.min(), d15.min()) <= -15)},
                "reason": f"the limit cycle's slip velocity is set by the friction curve's knee, the same at every "
                          f"position (s2 rms at (-0.04, 0.35): {srm[-5]:.3f}, {srm[-10]:.3f}, {srm[-15]:.3f} m/s at -5, "
                          f"-10, -15 mm), so positions differ only by the radiation of their mode per unit slip "
                          f"velocity: median L_W - 20 log10(s2 rms) = {rad[-5]:.1f}, {rad[-10]:.1f}, {rad[-15]:.1f} dB "
                          f"((2,0,a), (3,0,a), (2,0,a)); -5 and -15 mm squeal in the same mode and land within a few dB"})

    # row 3: -10 mm, maximum near mu = 0.25; case I (0.25) 7 dB louder than case II (0.55) at -0.04, 10 dB less force
    c1, c2 = _at(sl, -10, -0.04, 0.25), _at(sl, -10, -0.04, 0.55)
    spread = [np.ptp([_at(sl, -10, g, mu)["L_W"] for mu in mus if _wheel_sq(_at(sl, -10, g, mu))]) for g in gammas
              if sum(_wheel_sq(_at(sl, -10, g, mu)) for mu in mus) > 1]
    argmax = {g: max((mu for mu in mus if _wheel_sq(_at(sl, -10, g, mu))), key=lambda mu: _at(sl, -10, g, mu)["L_W"])
              for g in gammas if any(_wheel_sq(_at(sl, -10, g, mu)) for mu in mus)}
    out.append({"row": "-10 mm: L_W highest near mu = 0.25; case I (mu 0.25) 7 dB louder than case II (0.55) at "
                       "gamma_y = -0.04, though 10 dB lower in force",
                "measured": f"at -0.04: L_W {c1['L_W']:.1f} / {c2['L_W']:.1f} dB, L_F2 {c1['L_F2']:.1f} / {c2['L_F2']:.1f} dB "
                            f"(I - II: {c1['L_W'] - c2['L_W']:+.1f} dB sound, {c1['L_F2'] - c2['L_F2']:+.1f} dB force); spread of "
                            f"L_W over mu per creepage: " + ", ".join(f"{x:.1f}" for x in spread) + " dB; loudest mu per creepage: "
                            + ", ".join(f"{g}: {mu}" for g, mu in argmax.items()),
                "reproduced": {"case I lower in force": c1["L_F2"] < c2["L_F2"] - 5,
                               "case I louder": c1["L_W"] > c2["L_W"] + 3, "maximum near mu = 0.25":
                               all(abs(mu - 0.25) <= 0.05 for mu in argmax.values())},
                "reason": f"the detuning of case II is real (f {c2['f_dominant']:.1f} against {c1['f_dominant']:.1f} Hz, the "
                          f"free (3,0,a) at 1147.9 Hz) and costs force, but the limit cycle bounds the slip VELOCITY, not "
                          f"the force: s2 rms {c1['s2_rms']:.3f} / {c2['s2_rms']:.3f} m/s, so the wheel moves, and radiates, "
                          f"the same. A quieter case II would need a cycle bounded in force"})

    # row 4: -15 mm, like -5 mm in friction and creepage, L_W 120-140 dB, maximum near mu = 0.3
    lw15 = np.array([r["L_W"] for r in sl if _pos(r) == -15 and _wheel_sq(r)])
    rise15 = all(_monotone([r["L_W"] for r in (_at(sl, -15, g, mu) for g in gammas) if _wheel_sq(r)]) for mu in mus)
    top = max((r for r in sl if _wheel_sq(r)), key=lambda r: r["L_W"])
    out.append({"row": "-15 mm: behaves like -5 mm in friction and creepage; L_W 120-140 dB, highest near mu = 0.3",
                "measured": f"L_W {lw15.min():.0f}-{lw15.max():.0f} dB, {100 * np.mean(lw15 >= 120):.0f} % of the squealing "
                            f"runs in 120-140 dB; rises with creepage at every mu: {'yes' if rise15 else 'no'}; within "
                            f"{max(np.ptp([_at(sl, -15, g, mu)['L_W'] for mu in mus if _wheel_sq(_at(sl, -15, g, mu))]) for g in gammas if any(_wheel_sq(_at(sl, -15, g, mu)) for mu in mus)):.1f} dB over mu",
                "reproduced": {"rise with creepage": rise15, "120-140 dB": bool(np.median(lw15) >= 120)},
                "reason": f"scale: the saturation bound caps the slip velocity swing at |gamma_y| V - s_knee (< "
                          f"{0.06 * v:.2f} m/s on the map); the loudest run of all positions is {top['L_W']:.1f} dB "
                          f"(s2 rms {top['s2_rms']:.3f} m/s), and 140 dB would need several times the velocity the "
                          f"contact can drive (68_limit_cycle, 'Scale check')"})

    # row 5: -15 mm squeals at mu = 0.25 ((2,0,a) at gamma_y = -0.012 and -0.04)
    q = [_at(sl, -15, g, 0.25) for g in (-0.012, -0.04)]
    s25 = [sig[(-15, g, 0.25)] for g in (-0.012, -0.04)]
    s30 = [sig[(-15, g, 0.3)] for g in (-0.012, -0.04)]
    mu_thr = [0.25 + 0.05 * a / (a - b) for a, b in zip(s25, s30)]
    out.append({"row": "-15 mm squeals at mu = 0.25 ((2,0,a) at gamma_y = -0.012 and -0.04)",
                "measured": f"L_F2 {q[0]['L_F2']:.1f} and {q[1]['L_F2']:.1f} dB (quiet); screen sigma (2,0,a) = "
                            f"{s25[0]:+.1f}, {s25[1]:+.1f} 1/s at mu = 0.25, {s30[0]:+.1f}, {s30[1]:+.1f} at 0.30",
                "reproduced": {"squeals at mu = 0.25": all(_sq(r) for r in q)},
                "reason": f"the full-slip coupling threshold of (2,0,a) at the -15 mm contact point is mu_c = -Phi3/Phi2 = "
                          f"{muc[('default', '(2,0,a)')]:.3f} (one-mode estimate; the screen's zero crossing: mu = "
                          f"{min(mu_thr):.3f}-{max(mu_thr):.3f}): the mode shape's vertical/lateral ratio at the contact "
                          f"point (the C20 section as fitted, 'Calibration') puts it above 0.25; making it squeal would "
                          f"mean refitting that ratio to this finding"})
    return out


def markdown(rows: list[dict]) -> str:
    lines = ["| finding of the reference (ch. 6) | measured here | reproduced | reason (computed) |", "|---|---|---|---|"]
    for r in rows:
        rep = "; ".join(f"{k}: {'yes' if v else 'no'}" for k, v in r["reproduced"].items())
        lines.append(f"| {r['row']} | {r['measured']} | {rep} | {r['reason']} |")
    return "\n".join(lines)
