"""Validation of the studies (pipeline/study/, solvers/study.py): measured numbers and a plot for
docs/validation/80_studies.md and docs/validation/studies_damping.png.

    OMP_NUM_THREADS=1 .venv/bin/python -m pipeline.validation.writers.studies   # a few min

A writer, run by `make validate`; the limits it states are asserted by tests/study/test_studies_validation.py
on ``map_vs_simulate`` and ``damping_vs_linear`` here.  The three positions' case artifacts are built
through Make.

1. The study runner against the simulate stage: a one-point map per contact position at the
   case's own operating point, run as a study (Dask workers, the results table, the CSV round
   trip), against `make simulate` of the same case (build/cases/<case>/simulate.npz).
2. The squeal-critical damping by bisection (the damping study's procedure on the time loop)
   against an independent linear estimate: one lightly damped axial mode on the analytic beam
   rail with the analytic Hertz contact, where the single-mode growth rate in full slip
   (``references.interaction.single_mode_growth``, frequency domain) crosses zero.
"""
from __future__ import annotations

import csv
import math
import tempfile
from pathlib import Path
import os

import numpy as np

from pipeline.validation.make import ensure_case, make_targets
from pipeline.validation.references.damping import linear_critical_damping, run_procedure
from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from pipeline.store import artifacts, paths
from pipeline.study import stage as study_stage
from pipeline.config.loader import load
from pipeline.config.input_schemas import CASE
from pipeline.stages.simulate import simulate_config
from pipeline.validation.references.interaction import DT, V, beam_kernel, hertz_contact

CASES = ("dy05", "dy10", "default")
VARIANTS = [  # (label, f_r Hz, modal mass kg, (Phi_2, Phi_3), mu)
    ("(3,0,a)-like, Phi_3/Phi_2 = -0.15, mu = 0.35", 1161.0, 35.0, (1.0, -0.15), 0.35),
    ("same, mu = 0.6", 1161.0, 35.0, (1.0, -0.15), 0.6),
    ("Phi_3/Phi_2 = -0.10, mu = 0.35", 1161.0, 35.0, (1.0, -0.10), 0.35),
    ("(2,0,a)-like, 438 Hz, 41 kg, Phi_3/Phi_2 = -0.2", 438.0, 41.0, (1.0, -0.2), 0.35),
]


def map_vs_simulate() -> tuple[list, list]:
    sims, lines = {}, []
    for case in CASES:
        ensure_case(case)
        cfg = simulate_config(case)[-1]
        path = paths.case_dir(case) / "simulate.npz"
        try:
            sims[case] = artifacts.load_npz(path, "simulate", cfg)[0]
        except artifacts.ArtifactError:
            make_targets("simulate", CASE=case)
            sims[case] = artifacts.load_npz(path, "simulate", cfg)[0]
    rows = []
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for case in CASES:
            c = load(paths.case_file(case), CASE)
            gy, mu = c["kinematics"]["gamma_y"], c["friction"]["mu"]
            (tmp / f"one_{case}.toml").write_text(
                f'name = "one_{case}"\nkind = "map"\ncases = ["{case}"]\n[grid]\ngamma_y_first = {gy}\n'
                f"gamma_y_last = {gy}\ngamma_y_step = 0.002\nmu_first = {mu}\nmu_last = {mu}\nmu_step = 0.05\n"
                f"[quick]\ngamma_y_step = 0.002\nmu_step = 0.05\n[simulation]\nduration = {c['time']['duration']}\n")
            old = os.environ.get("SQUEAL_STUDY_DIR")
            os.environ["SQUEAL_STUDY_DIR"] = str(tmp)  # this test's own study files
            try:
                study_stage.run_study(f"one_{case}", workers=1, out=tmp / case, progress=False)
            finally:
                if old is None:
                    os.environ.pop("SQUEAL_STUDY_DIR")
                else:
                    os.environ["SQUEAL_STUDY_DIR"] = old
            with open(tmp / case / "map.csv", newline="") as fh:
                (row,) = list(csv.DictReader(fh))
            s = sims[case]
            same = all(float(row[k]) == float(s[k]) or (math.isnan(float(row[k])) and not np.isfinite(float(s[k])))
                       for k in ("L_F2", "f_dominant")) and row["stop_reason"] == str(s["stop_reason"])
            rows.append(same)
            lines.append(f"| {case} | {1e3 * c['contact']['dy_wr']:.0f} | {mu:g} | {gy:g} | {float(row['L_F2']):.6f} | "
                         f"{float(s['L_F2']):.6f} | {float(row['f_dominant']):.3f} | {float(s['f_dominant']):.3f} | "
                         f"{row['stop_reason']} / {s['stop_reason']} | {'identical' if same else '**differ**'} |")
    return rows, lines


def damping_vs_linear(plot: bool = True) -> tuple[list, list]:
    g = beam_kernel(DT, V)
    out, lines, logs = [], [], []
    for label, f, m, phi, mu in VARIANTS:
        c = hertz_contact(mu)
        zc = linear_critical_damping(c, f, m, phi, mu)
        res, log = run_procedure(c, g, 0.02, f, m, phi)
        s = res.steps[0]
        mid = math.sqrt(s.zeta_lo * s.zeta_hi) if np.isfinite(s.zeta_hi) else float("nan")
        out.append(dict(label=label, zc=zc, lo=s.zeta_lo, hi=s.zeta_hi, dev=mid / zc - 1, runs=s.runs,
                        end=res.end, L0=s.L_F2, f0=s.f_dominant))
        logs.append(log)
        lines.append(f"| {label} | {s.L_F2:.1f} dB at {s.f_dominant:.0f} Hz | {zc:.3e} | {s.zeta_lo:.3e} .. "
                     f"{s.zeta_hi:.3e} | {100 * (mid / zc - 1):+.1f} % | {s.runs} | {res.end} |")
    if plot:
        plt = pyplot()
        fig, ax = plt.subplots(figsize=(8, 4))
        for k, (o, log) in enumerate(zip(out, logs)):
            z = [x[0] for x in log[1:]]            # the bisection runs (the first is the nominal full model)
            L = [x[1] if np.isfinite(x[1]) else -60 for x in log[1:]]
            ax.semilogx(z, np.maximum(L, -60), "o", color=f"C{k}", ms=4, label=o["label"])
            ax.axvline(o["zc"], color=f"C{k}", ls="--", lw=1)
        ax.axhline(10, color="k", lw=0.8)
        ax.set(xlabel="damping ratio of the mode", ylabel="L_F2 (dB re 1 N), floored at -60",
               title="bisection runs; dashed: linear estimate of the critical damping")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, which="both")
        fig.tight_layout()
        save_figure(fig, DOCS / "studies_damping.png", dpi=90)
    return out, lines


def write_report() -> tuple[str, list, list]:
    same, mlines = map_vs_simulate()
    damp, dlines = damping_vs_linear()
    text = f"""## Studies (SPEC 7)

Written by `pipeline/validation/writers/studies.py` (`make validate`; asserted by
`tests/study/test_studies_validation.py`). Modules: `pipeline/study/` (runner, study
kinds), `solvers/study.py` (procedure, numerics); fast tests in `tests/study/` (among them the kill/restart test of
the runner: a study killed with SIGKILL mid-way and restarted gives the table of an uninterrupted run, every case
once); timings in docs/benchmarks.md ("Studies").

### The study runner reproduces the simulate stage

A one-point creepage/friction map per contact position at the case's own operating point, run as a study (a
local Dask worker, the results table written and read back as CSV), against `make simulate` of the same case
(build/cases/<case>/simulate.npz):

| case | dy_WR (mm) | mu | gamma_y | L_F2 study (dB) | L_F2 simulate (dB) | f study (Hz) | f simulate (Hz) | ended | |
|---|---:|---:|---:|---:|---:|---:|---:|---|---|
{chr(10).join(mlines)}

Identical to the last bit: the study cases run the same model from the same artifacts (the float values
round-trip through the table at repr precision).

### Squeal-critical damping: bisection vs the linear estimate

The damping study's procedure (`solvers.study.damping_procedure`) on the time loop, for one lightly damped axial
mode on the analytic beam rail with the analytic Hertz contact (`pipeline/validation/references/damping.py`), gamma_y = -0.014 (full
slip): squeal = L_F2 >= 10 dB within 8 s of rolling from the default kick; geometric bisection from the mode's
damping 1e-4 to 0.1 until zeta_hi / zeta_lo - 1 <= 0.02. The independent estimate: the damping at which the
single-mode linear growth rate in full slip (`references.interaction.single_mode_growth`, frequency domain, rail point
receptance and contact stiffness at the mode's frequency) crosses zero.

| mode | nominal run (zeta = 1e-4) | linear estimate | bisection bracket | bracket vs estimate | runs | procedure ended |
|---|---|---:|---|---:|---:|---|
{chr(10).join(dlines)}

![bisection runs](validation/studies_damping.png)

The time loop's boundary agrees with the linear estimate to within {max(abs(d['dev']) for d in damp) * 100:.0f} %
(criterion 15 %). The estimate is a first-order one: the closed loop evaluated at the mode's own frequency with
the rail's point receptance, while the squeal runs a little below the mode (the frequencies above) where the
rail's and the contact's dynamic stiffness differ. The finite-time criterion biases the bracket the other way:
just below the critical damping the motion grows too slowly to reach 10 dB within 8 s.
"""
    return text, same, damp


def write() -> str:
    return save_fragment("80_studies.md", write_report()[0])


if __name__ == "__main__":
    write()
