"""The radiation stage against a boundary-element solution (issue 28; thesis sec. 5.1).

    .venv/bin/python -m pipeline.validation.bem_check [--modes 2 3] [--no-ground] [--solver revolution|3-D]
        [--ground-order Q] [--default-case] [--convergence N ...] [--from-csv]

For the default case's wheel (its radiation model, ``pipeline.stages.radiate.load_radiation_model``)
and each (n,0,a) mode asked for: the section's outline revolved into a triangle mesh (element size
<= lambda/6 around and along the outline, ``--ds-max`` at most along it; bore clamped: its
velocity is the shapes' zero), the outward normal velocity of harmonic n for a unit (RMS) lateral
and radial force at the contact point at the mode's eigenfrequency (``solvers.radiation.bem_surface``, the
radiation stage's modal velocities), the exterior Helmholtz problem solved by bempp-cl (Burton-Miller,
P1; ``solvers.radiation.bem_revolution`` by the mesh's rotational symmetry, or ``solvers.radiation.bem`` on the whole
mesh), free field and over a rigid ground (an image wheel in the plane ``GROUND_BELOW_CONTACT`` below
the contact point, the wheel's axis horizontal); the radiation stage's W_n at the same frequency and
force beside it.  Each mode's rows are added to build/studies/bem/wheel.csv as they come
(``pipeline.validation.bem_table``: earlier rows kept, seeded from the fragment) and docs/validation/72_bem_wheel.md
is rewritten from all of them.  Cost: bempp's numba kernels compile once per process (~1-2 min on a
loaded machine); the 3-D assembly grows with the square of the vertices, the revolution solver's free
field with (vertices along the outline) x (vertices), its ground with the square of the vertices.
"""
from __future__ import annotations

import argparse
import logging
import math
import os
import time
from pathlib import Path

import numpy as np

from pipeline.store import paths, artifacts
from pipeline.validation.bem_table import GROUND_BELOW_CONTACT
from pipeline.stages.radiate import sound_power_of_forces, load_radiation_model
from pipeline.validation import bem_table as bt
from pipeline.store.atomic import atomic_write

log = logging.getLogger("pipeline.validation.bem_check")
ROOT = Path(__file__).resolve().parents[2]


def wheel_mesh(model, n: int, f: float, ds_max: float, n_phi: int | None = None):
    """(vertices, triangles, phi per vertex, outline node indices, outline normals) for harmonic n at f
    (``n_phi``: the number of vertices around, instead of the lambda/6 rule)."""
    from solvers.radiation.bem_surface import coarsen, outline, outward_normals, revolve  # lazy: brings in scipy

    modes = model.meta["modes"]
    pts = np.asarray(modes["points"], float)
    h = model.c0 / f / 6
    loop = coarsen(pts, outline(pts, np.asarray(modes["cells"], int)), min(h, ds_max))
    rz = pts[loop]
    n_phi = n_phi or max(24, 8 * n, math.ceil(2 * np.pi * rz[:, 0].max() / h))
    V, T, phi = revolve(rz, n_phi)
    return V, T, phi, loop, outward_normals(rz)


def wheel_rows(model, harmonics, ds_max: float, ground: float | None, solver: str = "revolution",
               ground_order: int | None = None, on_row=None) -> list[dict]:
    """Per (n,0,a) mode of ``harmonics`` and force direction: L_W of harmonic n by the radiation stage
    and by the BEM (free field, ground) at the mode's eigenfrequency, unit RMS force."""
    from solvers.radiation.force_power import harmonic_power  # lazy: brings in scipy
    from solvers.radiation import bem  # lazy: brings in scipy

    rows = []
    for n in harmonics:
        i = [j for j in range(len(model.f_r)) if model.n[j] == n and model.m[j] == 0 and model.cls[j] == "a"][0]
        f = float(model.f_r[i])
        forces = ((1.0, 0.0), (0.0, 1.0))
        free, gr, nv, t_free, t_gr = _powers(model, n, f, forces, ds_max, ground, None, solver, ground_order)
        h = list(model.harmonics).index(n)
        for d, (F2, F3) in enumerate(forces):
            W_s = float(harmonic_power(model, f, F2, F3)[h, 0])
            rows.append({"mode": f"({n},0,a)", "f_hz": f, "force": ("lateral", "radial")[d], "vertices": nv,
                         "solver": solver_label(solver, ground_order if ground is not None else None),
                         "L_W_simple": bem.level(W_s), "L_W_bem_free": bem.level(free[d]),
                         "L_W_bem_ground": bem.level(gr[d]) if np.isfinite(gr[d]) else np.nan,
                         "dL_free": bem.level(free[d]) - bem.level(W_s),
                         "dL_ground": bem.level(gr[d]) - bem.level(W_s) if np.isfinite(gr[d]) else np.nan,
                         "wall_free_s": t_free, "wall_ground_s": t_gr, "load": _load()})
            log.info("%s", rows[-1])
        if on_row is not None:
            on_row(rows[-2:])
    return rows


def _powers(model, n: int, f: float, forces, ds_max: float, ground: float | None, n_phi: int | None = None,
            solver: str = "revolution", ground_order: int | None = None):
    """BEM powers (free, ground) [W] of harmonic n at f for complex RMS force pairs ``forces``, the
    mesh's vertex count and wall times: ``solver`` "revolution" (``solvers.radiation.bem_revolution``: the first
    block row per harmonic, the ground by the mirror symmetry; ``ground_order`` its cross block's
    quadrature order) or "3-D" (``solvers.radiation.bem``: the whole mesh, an image wheel for the ground)."""
    from solvers.radiation.bem_surface import normal_velocity  # lazy: brings in scipy
    from solvers.radiation import bem, bem_revolution  # lazy: brings in scipy

    modes = model.meta["modes"]
    idx = model.groups[list(model.harmonics).index(n)]
    V, T, phi, loop, nrm = wheel_mesh(model, n, f, ds_max, n_phi)
    vns = [math.sqrt(2) * normal_velocity(model, np.asarray(modes["shapes"], float), idx, loop, nrm, phi, np.pi, f,
                                          F2, F3, n)
           for F2, F3 in forces]
    k = 2 * np.pi * f / model.c0
    plane = None if ground is None else -(float(model.meta["contact"].r) + ground)
    gr, t_gr = [np.nan] * len(vns), np.nan
    t0 = time.perf_counter()
    if solver == "revolution":
        rows = bem_revolution.first_block_row(V, T, len(loop), k)
        free = bem_revolution.revolution_power(V, T, len(loop), k, vns, n, model.rho, model.c0, rows=rows)
        t_free = time.perf_counter() - t0
        if plane is not None:
            t0 = time.perf_counter()
            gr = bem_revolution.ground_power(V, T, len(loop), k, vns, 0, plane, model.rho, model.c0, rows=rows,
                                             order=ground_order)
            t_gr = time.perf_counter() - t0
    else:
        free = bem.radiated_power(bem.grid_from_arrays(V, T), k, vns, model.rho, model.c0)
        t_free = time.perf_counter() - t0
        if plane is not None:
            Vm, Tm = bem.mirrored(V, T, axis=0, plane=plane)
            t0 = time.perf_counter()
            gr = [0.5 * w for w in bem.radiated_power(bem.grid_from_arrays(Vm, Tm), k,
                                                      [np.concatenate([v, v]) for v in vns], model.rho, model.c0)]
            t_gr = time.perf_counter() - t0
    return free, gr, len(V), t_free, t_gr


CONVERGENCE = ((0.03, None), (0.03, 36), (0.015, 24), (0.015, 36), (0.03, 48), (0.015, 48))


def convergence_meshes(model, n: int):
    """The meshes of the convergence check of (n,0,a) (element size along the outline, vertices around or
    None for the lambda/6 rule): for (2,0,a) ``CONVERGENCE`` (as first measured, 3-D); then for every mode
    the lambda/6 mesh, the element size along the outline halved and quartered (if above 6 mm), every
    node of the FE section's outline (size 0: 228 nodes, about 5 mm apart) and, up to (5,0,a), that
    outline with 1.5 x the vertices around (2 x up to (3,0,a); 3 x and 4 x for (2,0,a), whose 24 around
    are the coarsest)."""
    f = float(model.f_r[[j for j in range(len(model.f_r)) if model.n[j] == n and model.m[j] == 0
                         and model.cls[j] == "a"][0]])
    h = min(model.c0 / f / 6, 0.03)
    V, _, _, loop, _ = wheel_mesh(model, n, f, 0.03)
    around = len(V) // len(loop)
    out = ([(0.03, None), (h / 2, None)] + ([(h / 4, None)] if h / 4 > 0.006 else []) + [(0.0, None)]
           + ([(0.0, round(1.5 * around))] if n <= 5 else []) + ([(0.0, 2 * around)] if n <= 3 else [])
           + ([(0.0, 3 * around), (0.0, 4 * around)] if n == 2 else []))
    return (CONVERGENCE if n == 2 else ()) + tuple(out)


def solver_label(solver: str, ground_order: int | None) -> str:
    """The table's solver column: the solver, the cross block's quadrature order if not bempp's, and
    bempp's backend if not numba."""
    from solvers.radiation.bem import device  # lazy: brings in scipy

    return (solver + ("" if ground_order is None else f", ground q{ground_order}")
            + ("" if device() == "numba" else f", {device()}"))


def _load() -> str:
    return f"{os.getloadavg()[0]:.1f}"


def convergence_rows(model, n: int = 2, meshes=CONVERGENCE, done: list[dict] = (), solver: str = "revolution") -> list[dict]:
    """Mesh convergence of the free-field Delta L_W of (n,0,a) (unit lateral force): ``meshes`` = (element
    size along the outline, vertices around or None for the lambda/6 rule); meshes in ``done`` (rows of
    an earlier run, same solver) are kept, not recomputed."""
    from solvers.radiation.force_power import harmonic_power  # lazy: brings in scipy
    from solvers.radiation import bem  # lazy: brings in scipy

    i = [j for j in range(len(model.f_r)) if model.n[j] == n and model.m[j] == 0 and model.cls[j] == "a"][0]
    f = float(model.f_r[i])
    W_s = float(harmonic_power(model, f, 1.0, 0.0)[list(model.harmonics).index(n), 0])
    rows = []
    base = lambda label: label.replace(", opencl", "")                                  # noqa: E731  (backends agree)
    have = {(r["mode"], round(float(r["ds_max"]), 4), int(float(r["n_phi"])), base(r["solver"])) for r in done}
    for ds, n_phi in meshes:
        V, _, _, loop, _ = wheel_mesh(model, n, f, ds, n_phi)
        n_around = len(V) // len(loop)
        if (f"({n},0,a)", round(ds, 4), n_around, base(solver_label(solver, None))) in have:
            continue
        free, _, nv, t_free, _ = _powers(model, n, f, [(1.0, 0.0)], ds, None, n_phi, solver)
        rows.append({"mode": f"({n},0,a)", "ds_max": ds, "n_phi": n_around, "vertices": nv,
                     "solver": solver_label(solver, None),
                     "dL_free": bem.level(free[0]) - bem.level(W_s), "wall_s": t_free, "load": _load()})
        log.info("%s", rows[-1])
    return rows


def default_case_row(model, ds_max: float, ground: float | None, solver: str = "revolution") -> dict:
    """The default case's L_W (its simulate.npz's final stretch, the radiation stage's
    ``sound_power_of_forces``) with the loudest tone's dominant harmonic replaced by the BEM's power of
    that harmonic under the tone's forces."""
    from solvers.radiation import bem  # lazy: brings in scipy


    sim, _ = artifacts.load_npz(paths.case_dir("default") / "simulate.npz", "simulate")
    t = np.asarray(sim["t_final"], float)
    s = sound_power_of_forces(model, np.asarray(sim["F_final"], float), float(t[1] - t[0]))
    d = s["decomposition"]
    j = int(np.argmax(s["W"]))
    h = int(np.argmax(s["W_n"][:, j]))
    n = int(s["harmonics"][h])
    ti = int(np.argmin(np.abs(d.tone_f - s["f"][j])))
    free, gr, nv, t_free, t_gr = _powers(model, n, float(d.tone_f[ti]), [(d.tone_F2[ti], d.tone_F3[ti])], ds_max,
                                         ground, None, solver)
    W0, Wh = s["W_total"], float(s["W_n"][h, j])
    return {"mode": f"default case: tone {d.tone_f[ti]:.2f} Hz, n = {n}", "f_hz": float(d.tone_f[ti]),
            "force": "limit cycle", "vertices": nv, "solver": solver_label(solver, None), "L_W_simple": bem.level(W0),
            "L_W_bem_free": bem.level(W0 - Wh + free[0]),
            "L_W_bem_ground": bem.level(W0 - Wh + gr[0]) if np.isfinite(gr[0]) else np.nan,
            "dL_free": bem.level(W0 - Wh + free[0]) - bem.level(W0),
            "dL_ground": bem.level(W0 - Wh + gr[0]) - bem.level(W0) if np.isfinite(gr[0]) else np.nan,
            "wall_free_s": t_free, "wall_ground_s": t_gr, "load": _load()}


def write(rows: list[dict], ground: float | None, ds_max: float, conv_rows: list[dict] = (), plan=()) -> None:
    """Merge ``rows`` / ``conv_rows`` into the CSV cache (seeded from the fragment) and rewrite the
    fragment from the whole cache."""
    out = paths.build() / "studies" / "bem"
    frag = ROOT / "docs" / "validation" / "72_bem_wheel.md"
    wheel, conv = bt.cached(out, frag)
    wheel, conv = bt.merge_wheel(wheel, list(rows)), bt.merge_conv(conv, list(conv_rows))
    if not wheel:
        raise SystemExit("no rows: run `python -m pipeline.validation.bem_check` first")
    bt.write_csv(out / "wheel.csv", wheel, bt.WHEEL_KEYS)
    if conv:
        bt.write_csv(out / "convergence.csv", conv, bt.CONV_KEYS)
    text = bt.fragment_text(wheel, conv, ds_max, plan)
    with atomic_write(frag) as tmp:
        tmp.write_text(text)


def plan_rows(model, ds_max: float) -> list[dict]:
    """Every (n,0,a) mode in the radiation stage's range: frequency, the lambda/6 mesh (vertices, along
    x around) and the memory of one dense complex matrix of the 3-D solve (free field; 4x with the
    image wheel)."""
    rows = []
    for j in np.argsort(model.f_r):
        if model.m[j] != 0 or model.cls[j] != "a" or int(model.n[j]) < 2:
            continue
        n, f = int(model.n[j]), float(model.f_r[j])
        V, _, _, loop, _ = wheel_mesh(model, n, f, ds_max)
        rows.append({"mode": f"({n},0,a)", "f_hz": f, "vertices": len(V), "along": len(loop),
                     "around": len(V) // len(loop), "dense_gb": 16 * len(V) ** 2 / 1e9})
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.validation.bem_check", description=__doc__.split("\n\n")[0])
    ap.add_argument("--modes", type=int, nargs="*", default=[2, 3], help="harmonics n of the (n,0,a) modes")
    ap.add_argument("--ds-max", type=float, default=0.03, help="largest element size along the outline (m)")
    ap.add_argument("--no-ground", action="store_true", help="free field only")
    ap.add_argument("--solver", choices=("revolution", "3-D"), default="revolution",
                    help="revolution: the symmetric solver (default); 3-D: the whole mesh")
    ap.add_argument("--ground-order", type=int, default=None,
                    help="quadrature order of the image wheel's (non-singular) cross block (default bempp's 4)")
    ap.add_argument("--device", choices=("numba", "opencl"), default="numba",
                    help="bempp-cl's backend (opencl: needs pyopencl and an OpenCL CPU driver, e.g. pocl)")
    ap.add_argument("--default-case", action="store_true", help="also the default case's limit cycle")
    ap.add_argument("--convergence", type=int, nargs="*", default=None,
                    help="only the mesh convergence of these (n,0,a) modes (free field; none given: 2)")
    ap.add_argument("--from-csv", action="store_true", help="only rewrite the fragment from build/studies/bem/*.csv")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    ground = None if a.no_ground else GROUND_BELOW_CONTACT
    if not a.from_csv:
        from solvers.radiation.bem import use_device  # lazy: brings in scipy

        try:
            use_device(a.device)
        except ValueError as e:
            raise SystemExit(f"pipeline.validation.bem_check: {e}") from None
    model = load_radiation_model("default")
    have = sorted({int(model.n[j]) for j in range(len(model.f_r)) if model.m[j] == 0 and model.cls[j] == "a"})
    bad = [n for n in (a.modes or []) + (a.convergence or []) if n not in have]
    if bad:
        raise SystemExit(f"pipeline.validation.bem_check: --modes/--convergence {bad}: the wheel's (n,0,a) modes are n = {have}")
    if a.from_csv:
        write([], ground, a.ds_max, plan=plan_rows(model, a.ds_max))
        return 0
    if a.convergence is not None:
        done = bt.cached(paths.build() / "studies" / "bem", ROOT / "docs" / "validation" / "72_bem_wheel.md")[1]
        plan = plan_rows(model, a.ds_max)
        for n in a.convergence or [2]:
            for mesh in convergence_meshes(model, n):                   # one row at a time, each written
                rows = convergence_rows(model, n, [mesh], done, a.solver)
                done = done + rows
                write([], ground, a.ds_max, rows, plan)
        return 0
    plan = plan_rows(model, a.ds_max)
    rows = wheel_rows(model, a.modes, a.ds_max, ground, a.solver, a.ground_order,
                      on_row=lambda r: write(r, ground, a.ds_max, plan=plan))
    if a.default_case:
        rows.append(default_case_row(model, a.ds_max, ground, a.solver))
        log.info("%s", rows[-1])
        write(rows[-1:], ground, a.ds_max, plan=plan)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
