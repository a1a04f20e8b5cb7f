"""verdict.md (what a person reads first) and the CSV cells of verdict.csv."""
from __future__ import annotations

import math

import numpy as np

from pipeline.config.nouns import Curve


def cell(v):
    """A CSV cell: floats to 6 significant digits, booleans as 0/1; a value that does not exist (NaN: not
    computed, e.g. a quiet wheel's frequency; -inf dB: a band without sound) an empty cell, never 'nan' or
    '-inf'."""
    if isinstance(v, (bool, np.bool_)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return f"{float(v):.6g}" if math.isfinite(v) else ""
    return v


def loudest(rows: list[dict]) -> dict | None:
    """The squealing wheel with the highest L_pA (L_F2 where L_pA is missing), or None."""
    sq = [r for r in rows if r["squeals"]]
    if not sq:
        return None
    return max(sq, key=lambda r: (r["L_pA"] if math.isfinite(r["L_pA"]) else -1e9, r["L_F2"]))


def _f(x, fmt=".1f", unit=""):
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f"{x:{fmt}}{unit}"


def verdict_markdown(info: Curve, points, rows: list[dict], wall: float) -> str:
    """The verdict in words, then the table per wheel and the mitigation what-ifs."""
    loud = loudest(rows)
    head = (f"# Curve {info.name}: {info.vehicle.name}, R = {info.radius:g} m, {info.speed_kmh:g} km/h, "
            f"cant {1e3 * info.cant:g} mm\n\n")
    if loud is None:
        unstable = [r["wheel"] for r in rows if math.isfinite(r["screen_sigma"])]
        verdict = ("**No squeal.** No wheel of the leading bogie squeals: " +
                   (f"the stability screen finds growing modes at {', '.join(unstable)}, but the time loop's "
                    "motion stays below L_F2 = 10 dB re 1 N" if unstable else
                    "the stability screen finds every wheel mode decaying, and the time loop confirms it "
                    "(L_F2 < 10 dB re 1 N at every wheel with lateral creepage)") + ".\n\n")
    else:
        verdict = (f"**Squeal.** Loudest: wheel **{loud['wheel']}** at **{loud['f_squeal']:.0f} Hz** (wheel mode "
                   f"{loud['mode'] or '-'}), L_pA = **{_f(loud['L_pA'])} dB(A)** at 7.5 m from the track centre, "
                   f"1.2 m above the rail (ISO 3095 position; the case's `[listener]`), L_W = {_f(loud['L_W'])} dB, "
                   f"L_F2 = {_f(loud['L_F2'])} dB re 1 N.  Listen: `{loud['wav']}`.\n\n")
        fr, dm = loud.get("friction_what_if"), loud.get("damping_what_if")
        stops = []
        if fr is not None and math.isfinite(fr.threshold):
            conf = ("confirmed by the time loop: quiet at mu = {:.3f}, squeals at mu = {:.3f}".format(
                fr.below["mu"], fr.above["mu"]) if fr.confirmed else (fr.note or "not confirmed"))
            stops.append(f"friction below **mu = {fr.threshold:.3f}** (now {fr.mu_case:g}; {conf})")
        elif fr is not None:
            stops.append(f"friction: {fr.note}")
        if dm is not None and dm.modes:
            need = {}
            for lab, f, z0, z in dm.modes:              # a mode damped twice: its first nominal, its last need
                need[lab] = (f, need.get(lab, (f, z0, z))[1], z)
            txt = ", ".join(f"{lab} ({f:.0f} Hz) from {z0:.2g} to **{z:.2g}**" for lab, (f, z0, z) in need.items())
            ok = dm.confirm and not dm.confirm.get("squeals", True)
            stops.append(f"modal damping of {txt} ({dm.end}{'; the time loop confirms: quiet' if ok else ''})")
        mod = loud.get("modifier_what_if")
        if mod is not None:
            stops.append(mod.text())
        if stops:
            verdict += "What would stop it: " + "; or ".join(stops) + ".\n\n"
    lines = ["| wheel | dy_wr (mm) | AoA (mrad) | gamma_y | gamma_x | y^W / y^R (mm) | contact angle (deg) | "
             "load (kN) | points | screen | squeals | f (Hz) | mode | L_F2 | L_W | L_pA | mu stop | zeta needed |",
             "|" + "---|" * 18]
    for r in rows:
        scr = (f"{r['screen_mode']} {r['screen_sigma']:+.1f}/s" if math.isfinite(r["screen_sigma"]) else "stable")
        lines.append(
            f"| {r['wheel']} | {1e3 * r['dy_wr']:+.1f} | {1e3 * r['angle_of_attack']:+.2f} | {r['gamma_y']:+.4f} | "
            f"{r['gamma_x']:+.4f} | {1e3 * r['y_wheel']:+.1f} / {1e3 * r['y_rail']:+.1f} | "
            f"{math.degrees(r['contact_angle']):.1f} | {r['wheel_load'] / 1e3:.1f} | {r['contact_points']} | {scr} | "
            f"{'yes' if r['squeals'] else 'no'} | {_f(r['f_squeal'], '.0f')} | {r['mode'] or '-'} | "
            f"{_f(r['L_F2'])} | {_f(r['L_W'])} | {_f(r['L_pA'])} | {_f(r['mu_threshold'], '.3f')} | "
            f"{r['zeta_needed'] or '-'} |")
    tail = (f"\n\nFriction {info.friction.text}; wheel {info.wheel}, rail {info.rail}, gauge {1e3 * info.gauge:.0f} mm.  "
            "Screen: the fastest growing closed-loop pole at a wheel mode (growth rate, 1/s); squeal is the time "
            "loop's verdict (L_F2 >= 10 dB re 1 N, SPEC 6).  Artifacts of each wheel: "
            f"`build/cases/{info.name}/<wheel>/`; its case file: `build/curves/{info.name}/cases/<wheel>.toml`.  "
            f"Plot: `bogie.png`.  {wall:.0f} s.\n")
    return head + verdict + "\n".join(lines) + tail
