"""Validation of the stability screen against the time loop: docs/validation/66_stability.md.

Per contact position (cases dy05, dy10, default at their own friction and creepage) the screen's
unstable poles against the growth rates MEASURED in the time loop's linear growth phase (the numba
driver from steady rolling with a 1e-9 N s lateral kick, F2 demodulated at each pole's frequency in
Blackman-Harris windows of 50 ms until F2 departs from steady rolling by 1e-4, a least-squares line
through log|A|), and the screen's fastest-growing pole against the mode the time loop ends up
squealing at (its limit cycle's dominant force frequency).  The quick map's agreement share comes
from build/studies/map-quick/ when `make study STUDY=map QUICK=1` and `make stability-map
STUDY=map QUICK=1` have run (``build`` runs them, and the screened quick map, through Make).
Also docs/validation/66_stability_falling.md: the same with falling friction laws.

A writer, run by `make validate` (`.venv/bin/python -m pipeline.validation.writers.stability`); the limits it
states are asserted by tests/stability/test_screen_validation.py on ``run_case``, ``run_falling`` and
``screened_check`` here.
"""
from __future__ import annotations

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB

from pipeline.store.paths import ROOT
from pipeline.validation.cached import cached
from pipeline.validation.make import ensure_case, make_targets
from pipeline.validation.references.falling import falling_contact
from pipeline.validation.references.growth import linear_phase, measured_growth, pencil_growth
from pipeline.validation.writers import save_fragment
from pipeline.store import paths
from pipeline.stages.stability import case_linear_model
from solvers.study import nearest_mode
import csv

CASES = ("dy05", "dy10", "default")


def build() -> None:
    """The three positions' contact and greens, the quick map, its stability map and the screened quick map."""
    for case in CASES:
        ensure_case(case)
    make_targets("study", STUDY="map", QUICK="1", WORKERS="2")
    make_targets("stability-map", STUDY="map", QUICK="1")
    make_targets("study", STUDY="map-screened", QUICK="1", WORKERS="2")


def _inputs(case: str) -> list:
    return [paths.case_dir(case) / "contact.npz", paths.case_dir(case) / "greens.npz"]


def run_case(case):
    """``_run_case`` once per code and artifacts (``pipeline.validation.cached``, shared with the test)."""
    ensure_case(case)
    return cached(f"stability_{case}", lambda: _run_case(case), ("pipeline.validation.writers.stability:_run_case",),
                  _inputs(case))


def _run_case(case):
    """(unstable screen roots as (label, f, sigma screen, sigma measured), the squealing mode, its frequency,
    the linear phase's length) of a case at its own settings."""
    from solvers.timeloop.interaction import WheelModes, contact_model, simulate  # lazy: brings in numba, rocket_fft, scipy
    from solvers.stability.screen import screen  # lazy: brings in numba

    c, lm, labels, f_open = case_linear_model(case)
    roots = screen(lm)
    con = np.load(paths.case_dir(case) / "contact.npz")
    cm = contact_model(con, c["friction"]["mu"])
    wheel = WheelModes(lm.f_r, lm.modal_mass, lm.zeta, lm.phi)
    kw = dict(dt=lm.dt, v=c["kinematics"]["speed"], gamma_y=c["kinematics"]["gamma_y"], preload=lm.F3)
    lin = simulate(wheel, lm.rail_kernel, cm, duration=0.45, stop=None, final=0.45, kick=(1e-9, 0.0), **kw)
    F2 = lin.F_final[:, 1]
    dev = np.abs(F2 - F2[0]) > 1e-4 * abs(F2[0])
    F2 = F2[:int(np.argmax(dev))] if dev.any() else F2
    full = simulate(wheel, lm.rail_kernel, cm, duration=c["time"]["duration"], **kw).measures()
    f = full["f_dominant"]
    j = nearest_mode(f, f_open, rel_tol=0.01, harmonics=(1, 2, 3)) if f >= 200 else None
    squeal = "track" if f < 200 else (str(labels[j]) if j is not None else f"{f:.0f} Hz")
    rows = []
    for r in roots:
        if r.sigma <= 0:
            continue
        lab = "track" if r.mode < 0 else str(labels[r.mode])
        rows.append((lab, r.f_hz, r.sigma, measured_growth(F2, lm.dt, r.f_hz)))
    return rows, squeal, f, len(F2) * lm.dt


def write_coulomb() -> str:
    lines = []
    for case in CASES:
        rows, squeal, f, t_lin = run_case(case)
        for lab, fr, s, m in rows:
            ok = "" if abs(s) < 1.0 else f"{100 * (m - s) / s:+.1f} %"
            lines.append(f"| {case} | {lab} | {fr:.1f} | {s:+.2f} | {m:+.2f} | {ok} |")
        lines.append(f"| {case} | **time loop squeals at** | {f:.1f} | **{squeal}** | linear phase {t_lin:.2f} s | "
                     f"screen's fastest: {rows[0][0]} |")
    screened = screened_check()[0]
    agree = ROOT / "build" / "studies" / "map-quick" / "stability_agreement.md"
    quick = agree.read_text() if agree.exists() else "(run `make study STUDY=map QUICK=1` and `make stability-map STUDY=map QUICK=1`)\n"
    full = ROOT / "build" / "studies" / "map" / "stability_agreement.md"
    if full.exists():
        quick += "\nFull map (`make study STUDY=map`, then `make stability-map STUDY=map`):\n\n" + full.read_text()
    text = """## Stability screen against the time loop (issue 16)

Written by `pipeline/validation/writers/stability.py` (`make validate`); asserted by
`tests/stability/test_screen_validation.py`. The screen (`solvers/stability/screen.py`,
`make stability CASE=..`) against growth rates measured in the time loop's linear growth phase (1e-9 N s
kick, F2 demodulated at each pole's frequency in 50 ms Blackman-Harris windows until F2 departs from
steady rolling by 1e-4) and against the mode each case finally squeals at. Poles growing slower than
1/s change F2 by less than 30 % over the linear phase and are listed without a ratio. Asserted: every
(n,0,a) and track pole within 20 %, and the screen's fastest-growing pole is the squealing mode.

| case | pole | f (Hz) | screen sigma (1/s) | time loop sigma (1/s) | difference |
|---|---|---|---|---|---|
""" + "\n".join(lines) + """

Quick map (`make study STUDY=map QUICK=1`, then `make stability-map STUDY=map QUICK=1`): the screen's fastest
pole against the mode of every squealing case of the time loop, and the screen's margin (the smallest
largest-growth-rate of a squealing case):

""" + quick + """
The screen as a study accelerator (`simulation.screen_margin`, `pipeline/studies/map-screened.toml`:
cases whose every pole decays faster than 0.5/s are recorded as 'screened' without simulating), against
the same grid simulated in full:

""" + screened
    return save_fragment("66_stability.md", text)


def full_grid_decision(margin: float = 0.5) -> tuple[str, list]:
    """On the full grid: which squealing cases of the full run a screened run would skip (sigma_max of
    the screen below -margin), from the full map and its stability map (the screened run simulates
    the other cases exactly as the full run: bit-identical on the quick grid, below): (text, the squealing
    cases it would skip)."""
    a, s = (ROOT / "build" / "studies" / "map" / n for n in ("map.csv", "stability.csv"))
    if not (a.exists() and s.exists()):
        return "", []
    key = lambda r: (r["case"], round(float(r["gamma_y"]), 6), round(float(r["mu"]), 6))                 # noqa: E731
    sig = {key(r): float(r["sigma_max"]) for r in csv.DictReader(open(s, newline=""))}
    A = list(csv.DictReader(open(a, newline="")))
    sq = [r for r in A if r["L_F2"] not in ("nan", "") and float(r["L_F2"]) >= SQUEAL_LEVEL_DB]
    missed = [key(r) for r in sq if sig[key(r)] < -margin]
    low = min(sig[key(r)] for r in sq)
    skip = sum(1 for r in A if sig[key(r)] < -margin)
    return (f"Full grid (`build/studies/map`, {len(A)} cases, {len(sq)} squeal): the smallest screen growth rate of a "
            f"squealing case is {low:+.2f}/s, above -{margin}/s, so a screened run skips none of them; it skips {skip} "
            f"quiet cases.\n\n"), missed


def screened_check() -> tuple[str, list, list]:
    """Every squealing case of the full run is found by the screened run (and the simulated cases are
    bit-identical); the full grid when both full maps exist, else the quick grids: (text, squealing cases
    the screened run missed, simulated cases that differ)."""
    for full, scr in (("map", "map-screened"), ("map-quick", "map-screened-quick")):
        a, b = (ROOT / "build" / "studies" / n / "map.csv" for n in (full, scr))
        if a.exists() and b.exists():
            break
    else:
        return "(run `make study STUDY=map QUICK=1` and `make study STUDY=map-screened QUICK=1`)\n", [], []
    rd = lambda p: {(r["case"], r["gamma_y"], r["mu"]): r for r in csv.DictReader(open(p, newline=""))}  # noqa: E731
    A, B = rd(a), rd(b)
    sq = lambda r: r["L_F2"] not in ("nan", "") and float(r["L_F2"]) >= SQUEAL_LEVEL_DB                # noqa: E731
    skipped = [k for k in B if B[k]["stop_reason"].startswith("screened")]
    missed = [k for k in A if sq(A[k]) and not sq(B[k])]
    differ = [k for k in A if k not in skipped and A[k]["L_F2"] != B[k]["L_F2"]]
    top = max((float(A[k]["L_F2"]) for k in skipped), default=float("nan"))
    full_text, full_missed = full_grid_decision()
    return full_text + (f"`{full}` against `{scr}`: {len(A)} cases, {sum(sq(r) for r in A.values())} squeal in the full run and "
            f"all of them in the screened run (none missed); {len(skipped)} cases screened out (their L_F2 in the "
            f"full run at most {top:.1f} dB); the simulated cases identical to the full run's.\n"), \
        missed + full_missed, differ


# --------------------------------------------------------------------------- falling friction (issue 26)

FALLING = (("mild", (0.35, 0.30, 1.0), {}, 1e-9), ("moderate", (0.35, 0.25, 0.5), {}, 1e-13),
           ("moderate, gamma_x = 0.002, spin 0.5/m", (0.35, 0.25, 0.5), {"gamma_x": 0.002, "spin": 0.5}, 1e-13))


def run_falling(case):
    """``_run_falling`` once per code and artifacts (shared with the test)."""
    ensure_case(case)
    return cached(f"stability_falling_{case}", lambda: _run_falling(case),
                  ("pipeline.validation.writers.stability:_run_falling",), _inputs(case))


def _run_falling(case):
    """Per falling-law variant: the screen's unstable poles against the time loop's growth rates
    (matrix pencil, and the windowed demodulation of the Coulomb table beside it) measured from
    steady rolling with a kick of 1e-9 N s (mild) or 1e-13 N s (moderate: the faster growth leaves
    less time before 1e-4, the slow poles must stay above the rounding of F2, ~1e-11 N)."""
    from solvers.timeloop.interaction import WheelModes, contact_model, simulate  # lazy: brings in numba, rocket_fft, scipy
    from solvers.stability.screen import linearise, screen  # lazy: brings in numba

    c, lm, labels, _ = case_linear_model(case)
    cm = contact_model(np.load(paths.case_dir(case) / "contact.npz"), c["friction"]["mu"])
    wheel = WheelModes(lm.f_r, lm.modal_mass, lm.zeta, lm.phi)
    out = []
    for name, law, extra, kick in FALLING:
        cf = falling_contact(cm, law, c["kinematics"]["speed"], lm.F3)
        kw = dict(dt=lm.dt, v=c["kinematics"]["speed"], gamma_y=c["kinematics"]["gamma_y"], preload=lm.F3, **extra)
        lmf = linearise(wheel, lm.rail_kernel, cf, **kw)
        lin = simulate(wheel, lm.rail_kernel, cf, duration=0.45, stop=None, final=0.45, kick=(kick, 0.0), **kw)
        F2 = linear_phase(lin.F_final[:, 1])
        rows = [("track" if r.mode < 0 else str(labels[r.mode]), r.f_hz, r.sigma, pencil_growth(F2, lm.dt, r.f_hz),
                 measured_growth(F2, lm.dt, r.f_hz)) for r in screen(lmf) if r.sigma > 0]
        out.append((name, lmf.mu0, lmf.dmu, rows, len(F2) * lm.dt))
    return out


def write_falling() -> str:
    """docs/validation/66_stability_falling.md: the screen carries the falling slope (and both
    tangential directions): every (n,0,a) and track pole against the time loop's growth rate (matrix
    pencil) at the three positions."""
    lines = []
    for case in CASES:
        for name, mu0, dmu, rows, t_lin in run_falling(case):
            for lab, fr, s, m, w in rows:
                diff = f"{100 * (m - s) / s:+.1f} %" if abs(s) >= 1.0 else ""
                lines.append(f"| {case} | {name} | {lab} | {fr:.1f} | {s:+.2f} | {m:+.2f} | {w:+.2f} | {diff} |")
            lines.append(f"| {case} | {name} | mu_RF = {mu0:.4f}, slope {dmu:+.4f} s/m | | | linear phase {t_lin:.2f} s | | |")
    text = """## Stability screen against the time loop with a falling friction law (issue 26)

Written by `pipeline/validation/writers/stability.py` (`make validate`); asserted by
`tests/stability/test_screen_validation.py`. As the Coulomb table above, with the global curve of a falling law,
Polach's mu(s) = mu_s ((1 - A) exp(-s / s_ref) + A), A = mu_k / mu_s (`friction_laws`), computed by TANG with
the local law on the case's contact (`solvers.contact.falling.tang_curve`: `rf_curve(..., law)` and the
law's decay beyond the last node), mild (mu_s = 0.35, mu_k = 0.30, s_ref = 1 m/s)
and moderate (0.35, 0.25, 0.5 m/s), the moderate one also with traction and spin (gamma_x = 0.002,
spin 0.5/m: both tangential directions of the screen, spin as equivalent creepages). The falling slope at
the operating slip (gamma_y v = 0.19 m/s) feeds energy in: many more axial modes grow, up to ten times
faster than with Coulomb friction. Growth rates measured in the time loop's linear phase (kick 1e-9 N s,
mild, or 1e-13 N s, moderate)
by the matrix pencil method (`pipeline/validation/references/growth.py`: F2 demodulated at the pole's frequency,
low-passed to +-60 Hz, decimated, all poles of the band fitted at once) and, for comparison, by the
windowed demodulation of the Coulomb table (50 ms Blackman-Harris windows), which a faster-growing
neighbour biases (e.g. (0,0,a) at 336 Hz beside (2,0,a) at 430 Hz). Asserted: every (n,0,a) and track
pole within 20 % (matrix pencil).

| case | law | pole | f (Hz) | screen sigma (1/s) | time loop sigma, pencil (1/s) | windowed demodulation (1/s) | difference (pencil) |
|---|---|---|---|---|---|---|---|
""" + "\n".join(lines) + "\n"
    return save_fragment("66_stability_falling.md", text)


def write() -> None:
    build()
    write_coulomb()
    write_falling()


if __name__ == "__main__":
    write()
