"""Wheel stages: mesh (Gmsh section), modes (dolfinx + SLEPc per harmonic,
classified, plus the rigid half wheelset), shapes (pyvista renders).

Artifacts in build/wheels/<name>/ (docs/reference.md, 'Artifacts'):
  section.msh   the cross-section mesh with physical curve names
  mesh.json     provenance + physical names + element counts
  modes.npz     modal artifact (keys in ``save_modes``)
  modes.csv     mode table: f_hz, n, m, class, modal_mass_kg, kind, m_counted
  shapes/       one PNG per mode and gallery.png
"""
from __future__ import annotations

import logging
import os
import time
from concurrent.futures import ProcessPoolExecutor
from multiprocessing import get_context
import csv

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.config.loader import load_geometry
from pipeline.config.input_schemas import WHEEL
from geometry.wheel import wheel_segments, tyre_inner_radius, web_centreline
from pipeline.store.atomic import save_figure, save_image
from pathlib import Path

log = logging.getLogger("pipeline.wheel")


def load_wheel(name: str) -> tuple[dict, str]:
    """Validated wheel parameters (geometry checked too) and the file path."""
    path = paths.wheel_file(name)
    return load_geometry(path, WHEEL, wheel_segments, "wheel", paths.available(paths.wheels())), str(path)


def run_mesh(name: str) -> None:
    from geometry.mesher import mesh_section  # here: Make's DEPS of the module's other entry points stay without it

    p, src = load_wheel(name)
    out = paths.wheel_dir(name)
    t0 = time.perf_counter()
    with artifacts.atomic_write(out / "section.msh") as tmp:
        names = mesh_section(wheel_segments(p), str(tmp))
    counts = _msh_counts(out / "section.msh")
    artifacts.save_json(out / "mesh.json", "wheel-mesh", p, {"physical_curves": names, **counts})
    log.info("mesh %s: %d nodes, %d triangles in %.1f s -> %s", name, counts["nodes"], counts["triangles"],
             time.perf_counter() - t0, out / "section.msh")


def _msh_counts(path) -> dict:
    import gmsh  # lazy: brings in gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(path))
        tags, _, _ = gmsh.model.mesh.getNodes()
        types, elems, _ = gmsh.model.mesh.getElements(2)
        return {"nodes": int(len(tags)), "triangles": int(sum(len(e) for e in elems))}
    finally:
        gmsh.finalize()


def _solver(p: dict, names: dict, msh: str):
    from geometry.mesher import read_msh  # here: Make's DEPS of the module's other entry points stay without it
    from solvers.wheel.axisym import HarmonicSolver, SpringSupport  # here: Make's DEPS of the module's other entry points stay without it

    mesh, _, ft = read_msh(msh)
    m = p["material"]
    springs, clamped = [], []
    if p["mount"]["type"] == "clamped":
        clamped = [names["bore"]]
    else:
        ax, s = p["axle"], p["suspension"]
        area = 2 * np.pi * ax["journal_radius"] * ax["journal_length"]
        springs = [SpringSupport(names["journal"], s["k_vertical"] / area, s["k_lateral"] / area)]
    return HarmonicSolver(mesh, ft, m["E"], m["nu"], m["rho"], p["modes"]["degree"], clamped=clamped,
                          axis=names.get("axis"), plane=names.get("midplane"),
                          plane_type=p["mount"]["midplane"], springs=springs)


def _solve_harmonics(p: dict, names: dict, msh: str, ns: list[int]) -> list:
    """Worker: (n, freqs, shapes, masses) for each n in ns, plus the mesh."""
    hs = _solver(p, names, msh)
    out = [(n, *_unpack(hs.solve(n, p["modes"]["f_max"]))) for n in ns]
    return out, hs.points, hs.cells()


def _unpack(res):
    return res.freqs_hz, res.shapes, res.modal_mass


def solve_all(p: dict, names: dict, msh: str, workers: int | None = None, progress=None):
    """All harmonics 0..n_max, split over separate processes (one solver per
    process: for small 2D problems this beats MPI ranks)."""
    ns = list(range(p["modes"]["n_max"] + 1))
    workers = workers or min(len(ns), os.cpu_count() or 1)
    if workers == 1:
        res, pts, cells = _solve_harmonics(p, names, msh, ns)
        return res, pts, cells
    chunks = [ns[i::workers] for i in range(workers)]
    with ProcessPoolExecutor(workers, mp_context=get_context("spawn")) as ex:
        futs = [ex.submit(_solve_harmonics, p, names, msh, c) for c in chunks]
        results = []
        for f in futs:
            r, pts, cells = f.result()
            results += r
            if progress:
                progress(len(r))
    return sorted(results, key=lambda t: t[0]), pts, cells


def modal_model(p: dict, results, pts, cells) -> dict:
    """Classify the flexible modes, add the rigid half wheelset, and pack
    the arrays of the modal artifact (sorted by frequency)."""
    from solvers.wheel.mode_labels import classify_modes, order_nodal_circles  # here: Make's DEPS of the module's other entry points stay without it
    from solvers.wheel.wheelset import rigid_modes  # here: Make's DEPS of the module's other entry points stay without it

    tyre = pts[:, 0] > tyre_inner_radius(p, pts[:, 1] - p["axle"]["rolling_circle_z"]) - 1e-9
    line = web_centreline(p)
    rows = []
    for n, freqs, shapes, masses in results:
        counted = classify_modes(pts, cells, shapes, n, tyre, line)
        labels, fixed = order_nodal_circles(freqs, counted)
        for f, U, mr, (m, c), (mc, _) in zip(freqs, shapes, masses, labels, counted):
            rows.append((f, n, m, c, mr, "flexible", mc, U, np.nan))
    if p["mount"]["type"] == "clamped":
        for rm in rigid_modes(pts, p["axle"]["rolling_circle_z"], p["suspension"]):
            rows.append((rm["f_hz"], rm["n"], 0, "s", rm["modal_mass"], rm["name"], 0, rm["shape"], rm["zeta"]))
    rows.sort(key=lambda t: t[0])
    return {
        "f_hz": np.array([r[0] for r in rows]),
        "n": np.array([r[1] for r in rows], dtype=np.int64),
        "m": np.array([r[2] for r in rows], dtype=np.int64),
        "cls": np.array([r[3] for r in rows]),
        "modal_mass": np.array([r[4] for r in rows]),
        "kind": np.array([r[5] for r in rows]),
        "m_counted": np.array([r[6] for r in rows], dtype=np.int64),
        "shapes": np.array([r[7] for r in rows]),
        "zeta_suspension": np.array([r[8] for r in rows]),
        "points": pts,
        "cells": np.asarray(cells, dtype=np.int64),
    }


def run_modes(name: str, workers: int | None = None) -> dict:
    from pipeline.progress import progress  # here: Make's DEPS of the module's other entry points stay without it

    p, _ = load_wheel(name)
    out = paths.wheel_dir(name)
    meta, _ = artifacts.load_json(out / "mesh.json", "wheel-mesh", p, make_target=f"mesh WHEEL={name}")
    names = meta["physical_curves"]
    t0 = time.perf_counter()
    n_h = p["modes"]["n_max"] + 1
    with progress(total=n_h, desc=f"modes {name}", unit="harmonic") as bar:
        results, pts, cells = solve_all(p, names, str(out / "section.msh"), workers, bar.update)
    model = modal_model(p, results, pts, cells)
    model["boundary_names"] = np.array(list(names))
    for nm, tag in names.items():
        model[f"boundary_{nm}"] = _boundary_nodes(pts, cells, out / "section.msh", tag)
    artifacts.save_npz(out / "modes.npz", "wheel-modes", p, **model)
    rows = [(f"{f:.2f}", n, m, c, f"{mr:.4g}", k, mc) for f, n, m, c, mr, k, mc in
            zip(model["f_hz"], model["n"], model["m"], model["cls"], model["modal_mass"], model["kind"],
                model["m_counted"])]
    artifacts.save_csv(out / "modes.csv", ["f_hz", "n", "m", "class", "modal_mass_kg", "kind", "m_counted"], rows)
    log.info("modes %s: %d modes (n = 0..%d, f <= %.0f Hz) in %.1f s -> %s", name, len(rows), n_h - 1,
             p["modes"]["f_max"], time.perf_counter() - t0, out / "modes.npz")
    return model


def _boundary_nodes(pts, cells, msh, tag) -> np.ndarray:
    """Indices of the output nodes on the physical curve ``tag`` (matched by
    coordinates to the Gmsh nodes of that group)."""
    import gmsh  # lazy: brings in gmsh
    from scipy.spatial import cKDTree  # lazy: brings in scipy

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(msh))
        _, xyz = gmsh.model.mesh.getNodesForPhysicalGroup(1, int(tag))
    finally:
        gmsh.finalize()
    d, idx = cKDTree(pts).query(np.asarray(xyz).reshape(-1, 3)[:, :2])
    return np.unique(idx[d < 1e-9])


def run_shapes(name: str) -> None:
    """One PNG per mode (3D wheel, swept section) and a gallery."""
    from postprocess.modes.geometry import boundary_edges_from_triangles  # lazy: brings in pyvista
    from postprocess.modes.shapes import gallery_figure, render_mode  # lazy: brings in pyvista

    from pipeline.progress import progress  # here: Make's DEPS of the module's other entry points stay without it

    p, _ = load_wheel(name)
    out = paths.wheel_dir(name)
    a, _ = artifacts.load_npz(out / "modes.npz", "wheel-modes", p, make_target=f"modes WHEEL={name}")
    edges = boundary_edges_from_triangles(a["cells"])
    folder = out / "shapes"
    folder.mkdir(parents=True, exist_ok=True)
    images, labels = [], []
    for i in progress(range(len(a["f_hz"])), desc=f"shapes {name}", unit="mode"):
        lab = f"({a['n'][i]}, {a['m'][i]}, {a['cls'][i]})" if a["kind"][i] == "flexible" else str(a["kind"][i])
        path = folder / f"mode_{i:03d}_n{a['n'][i]}_{a['kind'][i]}.png"
        image = render_mode(a["points"], edges, a["shapes"][i], int(a["n"][i]), lab, float(a["f_hz"][i]))
        save_image(image, path)
        images.append(np.divide(image, 255, dtype=np.float32))  # as matplotlib reads the PNG back
        labels.append(f"{lab} {a['f_hz'][i]:.1f} Hz")
    save_figure(gallery_figure(images, labels, ncols=5), folder / "gallery.png", format="png", facecolor="white")
    log.info("shapes %s: %d renders -> %s", name, len(images), folder)


def modes_for_parameters(p: dict, workdir, workers: int | None = None) -> dict:
    """Mesh and solve a wheel given as validated parameters, without touching
    the build folder (for studies, validation and benchmarks)."""
    from geometry.mesher import mesh_section  # here: Make's DEPS of the module's other entry points stay without it

    Path(workdir).mkdir(parents=True, exist_ok=True)
    msh = str(Path(workdir) / "section.msh")
    names = mesh_section(wheel_segments(p), msh)
    results, pts, cells = solve_all(p, names, msh, workers)
    return modal_model(p, results, pts, cells)


def reference_rows(path) -> list[tuple[float, int, int, str]]:
    """(f_hz, n, m, class) rows of a reference mode table (CSV with a header)."""
    with open(path, newline="") as fh:
        return [(float(r["f_hz"]), int(r["n"]), int(r["m"]), r["class"]) for r in csv.DictReader(fh)]
