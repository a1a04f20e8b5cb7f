"""The headline of a case's report: does it squeal, at what frequency, which mode, how loud
(L_F2, L_W, L_pA at the case's receiver) and what the stability screen says, gathered from the
stages' artifacts (simulate, radiate, stability and listen when they exist).  ``headline(case)``
gives the numbers; ``headline_markdown`` the block at the top of the Markdown report (the HTML
report shows the same dict)."""
from __future__ import annotations

import numpy as np

from solvers.constants import SQUEAL_F_MIN_HZ, SQUEAL_LEVEL_DB

from pipeline.store import artifacts, paths
from pipeline.stages.simulate import simulate_config
from pipeline.stages.listen import load_listening


def verdict(L_F2: float, f_hz: float) -> str:
    """'squeals', 'low-frequency oscillation' (L_F2 >= 10 dB below SQUEAL_F_MIN_HZ: the wheelset on its
    suspension or the track, not squeal) or 'does not squeal' (docs/physics.md section 6)."""
    if not (np.isfinite(L_F2) and L_F2 >= SQUEAL_LEVEL_DB):
        return "does not squeal"
    return "squeals" if f_hz >= SQUEAL_F_MIN_HZ else "low-frequency oscillation"


def stability_of(case: str):
    """stability.npz when it exists and matches the case's current simulation inputs, else None."""
    path = paths.case_dir(case) / "stability.npz"
    if not path.exists():
        return None
    try:
        return artifacts.load_npz(path, "stability", {"simulate": simulate_config(case)[-1]})[0]
    except artifacts.ArtifactError:
        return None


def listening_of(case: str):
    """listen.npz (the case's own receiver) when it exists and is current, else None."""
    if not (paths.case_dir(case) / "listen.npz").exists():
        return None
    try:
        return load_listening(case)[0]
    except artifacts.ArtifactError:
        return None


def headline(case: str, sim: dict, rad: dict) -> dict:
    """The headline numbers (``sim``, ``rad``: the case's simulate and radiate artifacts, checked by
    the caller; the stability screen and the listener read here when present)."""
    L_F2, f_dom = float(sim["L_F2"]), float(sim["f_dominant"])
    h = {"case": case, "L_F2": L_F2, "f_dominant": f_dom, "stop_reason": str(sim["stop_reason"]),
         "verdict": verdict(L_F2, f_dom), "L_W": float(rad["L_W"]), "f_sound": float(rad["f_sound"]),
         "mode": str(rad["sound_mode_label"]), "mode_f": float(rad["sound_mode_f"]),
         "L_pA": None, "receiver": None, "sigma_max": None, "sigma_label": None, "sigma_f": None, "unstable": None}
    st = stability_of(case)
    if st is not None and len(st["sigma"]):
        k = int(np.argmax(st["sigma"]))
        h.update(sigma_max=float(st["sigma"][k]), sigma_label=str(st["label"][k]), sigma_f=float(st["f_hz"][k]),
                 unstable=[str(x) for x in st["label"][st["sigma"] > 0]])
    lis = listening_of(case)
    if lis is not None:
        h.update(L_pA=float(lis["L_pA"]), receiver=(float(lis["distance"]), float(lis["height"])))
    return h


def headline_markdown(h: dict) -> str:
    """The block at the top of the report."""
    squeal = h["verdict"] == "squeals"
    lines = [f"> **{'SQUEALS' if squeal else h['verdict'].upper()}**"
             + (f" at **{h['f_sound']:.1f} Hz**, the **{h['mode']}** wheel mode ({h['mode_f']:.1f} Hz)" if squeal else
                (f": F2 oscillates at {h['f_dominant']:.1f} Hz (below {SQUEAL_F_MIN_HZ:g} Hz: the wheelset, not a "
                 f"squealing wheel mode)" if h["verdict"] == "low-frequency oscillation" else
                 f": L_F2 = {h['L_F2']:.1f} dB < {SQUEAL_LEVEL_DB:g} dB")),
             ">",
             "> | L_F2 (dB re 1 N) | frequency (Hz) | mode | L_W (dB re 1e-12 W) | L_pA (dB(A)) | fastest pole |",
             "> |---:|---:|---|---:|---:|---|",
             f"> | {h['L_F2']:.1f} | {h['f_sound'] if squeal else h['f_dominant']:.1f} | {h['mode'] if squeal else '-'} | "
             f"{h['L_W']:.1f}{'' if squeal else ' (not meaningful)'} | "
             + (f"{h['L_pA']:.1f} at {h['receiver'][0]:g} m, {h['receiver'][1]:g} m" if h["L_pA"] is not None
                else "`make listen`") + " | "
             + (f"{h['sigma_label']} {h['sigma_f']:.0f} Hz, sigma = {h['sigma_max']:+.2f} 1/s" if h["sigma_max"]
                is not None else "`make stability`") + " |"]
    return "\n".join(lines) + "\n"
