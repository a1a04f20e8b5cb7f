"""Validation of the wheel stage, written to docs/validation/20_wheel_plates.md and 21_c20_modes.md (a writer,
run by `make validate`):

1. Harmonic solver vs exact Kirchhoff plates: annular plate clamped inside
   (n = 0..3, 0 and 1 nodal circles) and the free solid disc through the axis (``plate_rows``).
2. C20 vs the reference table (source thesis Table 4.1), with a
   mesh-convergence study (element size x 2, x 1, x 0.5; P2) and a plot of
   the deviations (``c20_levels``).

The criteria they state are asserted by tests/validation/test_wheel_modes.py on ``plate_rows`` (the fast
tests/test_harmonic_plate.py and tests/test_axis_regularity.py on fewer modes) and by tests/test_c20_reference.py
(the C20 on the default mesh).
"""
from __future__ import annotations

import copy
import tempfile
import time
from pathlib import Path

import numpy as np

from postprocess.modes.reference import markdown_table, match_modes, summary

from pipeline.stages.wheel import load_wheel, modes_for_parameters, reference_rows
from pipeline.validation.references.greens import DATA
from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from pipeline.validation.references.plates import A, B, DISC_A as DA, DISC_H as DH, E, H, NU, RHO, disc_segments, plate_segments
from geometry.mesher import mesh_section, read_msh
from solvers.wheel.axisym import HarmonicSolver
from geometry.wheel import wheel_segments

REF = DATA / "c20_modes.csv"


def _scaled(p: dict, factor: float) -> dict:
    q = copy.deepcopy(p)
    for k in q["mesh"]:
        q["mesh"][k] *= factor
    return q


def plate_rows(tmp_path: Path) -> tuple[list[str], float]:
    """(table rows, worst relative deviation) of the plates' flexural modes against Kirchhoff's."""
    from pipeline.validation.references.annular_plate import annular_plate_frequencies  # lazy: brings in scipy
    from pipeline.validation.references.free_disc import free_disc_nondimensional  # lazy: brings in scipy

    rows = ["| plate | n | nodal circles | exact (Hz) | harmonic FE (Hz) | error |", "|---|---|---|---|---|---|"]
    names = mesh_section(plate_segments(), str(tmp_path / "plate.msh"))
    mesh, _, ft = read_msh(str(tmp_path / "plate.msh"))
    hs = HarmonicSolver(mesh, ft, E, NU, RHO, 2, clamped=(names["inner"],))
    worst = 0.0
    for n in range(4):
        exact = annular_plate_frequencies(A, B, H, E, NU, RHO, n, count=2)
        res = hs.solve(n, 1.25 * exact[1])
        sh = np.abs(res.shapes)
        flex = [i for i in range(len(res.freqs_hz)) if sh[i, :, 1].max() > 3 * max(sh[i, :, 0].max(), sh[i, :, 2].max())]
        for s in (0, 1):
            f = res.freqs_hz[flex[s]]
            err = (f - exact[s]) / exact[s]
            worst = max(worst, abs(err))
            rows.append(f"| annular, clamped inside (a = {A} m, b = {B} m, h = {H * 1e3:.0f} mm) | {n} | {s} | "
                        f"{exact[s]:.2f} | {f:.2f} | {100 * err:+.3f} % |")
    names = mesh_section(disc_segments(), str(tmp_path / "disc.msh"))
    mesh, _, ft = read_msh(str(tmp_path / "disc.msh"))
    hd = HarmonicSolver(mesh, ft, E, NU, RHO, 2, axis=names["axis"])
    D = E * DH**3 / (12 * (1 - NU**2))
    for n in range(4):
        fe = free_disc_nondimensional(n, NU, 1)[0] / (2 * np.pi * DA**2) * np.sqrt(D / (RHO * DH))
        res = hd.solve(n, 1.3 * fe)
        sh = np.abs(res.shapes)
        flex = [i for i in range(len(res.freqs_hz)) if sh[i, :, 1].max() > 3 * max(sh[i, :, 0].max(), sh[i, :, 2].max())]
        f = res.freqs_hz[flex[0]]
        err = (f - fe) / fe
        worst = max(worst, abs(err))
        rows.append(f"| free solid disc through the axis (a = {DA} m, h = {DH * 1e3:.0f} mm) | {n} | {1 if n < 2 else 0} | "
                    f"{fe:.2f} | {f:.2f} | {100 * err:+.3f} % |")
    return rows, worst


def write_plates(tmp_path: Path) -> str:
    rows, worst = plate_rows(tmp_path)
    return save_fragment("20_wheel_plates.md", f"""## Wheel solver: harmonic FE vs exact Kirchhoff plates

Written by `pipeline/validation/writers/wheel_modes.py` (`make validate`); asserted by
`tests/validation/test_wheel_modes.py` (fast versions with the same assertions: `tests/test_harmonic_plate.py`,
`tests/test_axis_regularity.py`). The exact solutions are
`pipeline/validation/references/annular_plate.py` (checked against Blevins/Leissa's table and an independent Rayleigh-Ritz
solution) and `pipeline/validation/references/free_disc.py` (Leissa's free-plate values 5.358, 9.003, 12.439, 20.475).
The free disc exercises the regularity conditions on the axis for every harmonic (n = 1 needs
U_r + U_phi = 0). Thin plates (h/a = 0.01), P2 triangles, 2 through the thickness; the remaining
difference is mostly Kirchhoff's own error (shear and rotary inertia, ~(kh)^2/5).

{chr(10).join(rows)}

Worst deviation {100 * worst:.2f} % (criterion 1 %).
""")


FLIP_NOTE = (" -- mixed modes, whose tyre moves about as much out of plane as in plane: the automatic class "
             "(ring theory) tips with the mesh while the frequencies do not (discretisation error above)")


def c20_levels(tmp_path: Path):
    """(levels, models): per mesh factor 2, 1, 0.5 (factor, section nodes, time, matches, summary), and the
    models."""
    p, _ = load_wheel("c20")
    ref = reference_rows(REF)
    levels, models = [], {}
    for factor in (2.0, 1.0, 0.5):
        t0 = time.perf_counter()
        model = modes_for_parameters(_scaled(p, factor), tmp_path / f"f{factor}")
        models[factor] = model
        dt = time.perf_counter() - t0
        mt = match_modes(ref, model["f_hz"], model["n"], model["m"], model["cls"])
        levels.append((factor, len(model["points"]), dt, mt, summary(mt)))
    return levels, models


def write_c20(tmp_path: Path) -> str:
    plt = pyplot()
    p, _ = load_wheel("c20")
    levels, models = c20_levels(tmp_path)
    fine = levels[-1][3]
    default = levels[1]
    conv = ["| element size | section nodes (P1) | time | found | median abs dev. | max abs dev. | max (n,0,a) dev. |",
            "|---|---|---|---|---|---|---|"]
    for factor, nodes, dt, mt, s in levels:
        conv.append(f"| x {factor:g} | {nodes} | {dt:.1f} s | {s['found']}/{s['total']} | {100 * s['median_abs']:.2f} % | "
                    f"{100 * s['max_abs']:.2f} % | {100 * s['max_abs_n0a']:.2f} % |")
    # discretisation error of the default mesh: each of its flexible modes against the finest mesh's
    # nearest mode of the same harmonic (independent of the labels, which may flip for mixed modes)
    fm, dm = models[0.5], models[1.0]
    disc = []
    for f, n in zip(dm["f_hz"][dm["kind"] == "flexible"], dm["n"][dm["kind"] == "flexible"]):
        g = fm["f_hz"][(fm["kind"] == "flexible") & (fm["n"] == n)]
        disc.append(np.abs(g - f).min() / f)
    flips = [f"({a.n},{a.m},{a.cls})" for a, b in zip(default[3], fine) if (a.f_model is None) != (b.f_model is None)]
    fig, ax = plt.subplots(figsize=(9, 4))
    mts = default[3]
    x = np.arange(len(mts))
    colors = ["tab:red" if (m.m == 0 and m.cls == "a") else "tab:blue" for m in mts]
    ax.bar(x, [100 * (m.error if m.f_model is not None else np.nan) for m in mts], color=colors)
    ax.axhline(0, color="k", lw=0.8)
    for lim in (3, -3, 10, -10):
        ax.axhline(lim, color="grey", ls=":" if abs(lim) == 3 else "--", lw=0.8)
    ax.set_xticks(x)
    ax.set_xticklabels([f"({m.n},{m.m},{m.cls})" for m in mts], rotation=90, fontsize=7)
    ax.set_ylabel("model - reference (%)")
    ax.set_title("C20 eigenfrequencies vs reference (red: (n,0,a) modes, limit 3 %)")
    fig.tight_layout()
    save_figure(fig, DOCS / "c20_modes.png", dpi=110)

    fig, ax = plt.subplots(figsize=(4.5, 6))
    for seg in wheel_segments(p):
        ax.plot(1e3 * (seg.points[:, 1] - p["axle"]["rolling_circle_z"]), 1e3 * seg.points[:, 0], lw=1.4)
    ax.set_aspect("equal")
    ax.set_xlabel("y^W (mm, + toward the field side)")
    ax.set_ylabel("r (mm)")
    ax.set_title("C20 cross-section (geometry/wheels/c20.toml)")
    fig.tight_layout()
    save_figure(fig, DOCS / "c20_section.png", dpi=100)
    s = default[4]
    return save_fragment("21_c20_modes.md", f"""## C20 wheel modes vs the reference table

Written by `pipeline/validation/writers/wheel_modes.py` (`make validate`); `tests/test_c20_reference.py` asserts
the criteria on the default mesh. Reference: the 34
modes below 7 kHz of the source thesis' Table 4.1 (`pipeline/validation/references/data/c20_modes.csv`). Matching is by label
(n, m, class) as classified automatically by `solvers/wheel/mode_labels.py`. Model: `geometry/wheels/c20.toml`
(flexible wheel clamped at the bore, P2 triangles; the three rigid half-wheelset modes below 20 Hz are not
in the table).

Default mesh: all {s['found']} of {s['total']} found, median |deviation| {100 * s['median_abs']:.2f} %, worst
{100 * s['max_abs']:.2f} %, worst (n,0,a) {100 * s['max_abs_n0a']:.2f} % (criteria: all found, 5 %, 10 %, 3 %).

{markdown_table(mts)}

![C20 deviations](validation/c20_modes.png)
![C20 cross-section](validation/c20_section.png)

Mesh convergence (all mesh sizes of the parameter file scaled):

{chr(10).join(conv)}

Discretisation error of the default mesh against the x 0.5 mesh (each mode against the nearest of the same
harmonic): median {100 * np.median(disc):.3f} %, max {100 * max(disc):.3f} % -- far below the deviations from the
reference, which are model (geometry) differences. Labels found on one of the two meshes only:
{", ".join(flips) or "none"}{FLIP_NOTE if flips else ""}.
""")


def write() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        write_plates(Path(tmp))
        write_c20(Path(tmp))


if __name__ == "__main__":
    write()
