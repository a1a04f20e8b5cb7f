"""Rail stage: BV50 (or another rail) cross-section with the pad, waveguide FE,
dispersion, receptances at the rail-head contact points (SPEC 3.2).

Artifacts in build/rails/<name>/ (keys in docs/reference.md):
  section.msh     half cross-section (rail steel = surface 1, pad = 2)
  rail.npz        receptances G (points, distances, frequencies, 2, 2), the
                  wave table (exact G at any distance), decay rates,
                  dispersion curves with wave types, section properties
  receptance.png  point receptances (magnitude and phase), dispersion.png
"""
from __future__ import annotations

import logging
import time
import filecmp
import shutil
import tempfile

import numpy as np

from solvers.constants import F_MAX_HZ, RAIL_F_MIN_HZ

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.loader import load_geometry
from pipeline.config.input_schemas import RAIL
from geometry.rail import check_rail

log = logging.getLogger("pipeline.rail")

N_FREQ = 1000  # 25 Hz .. 6.5 kHz, log-spaced
N_DIST = 200  # 0 .. 2 m along the rail
X_MAX = 2.0


def load_rail_params(name: str) -> tuple[dict, str]:
    """Validated rail parameters (geometry checked too) and the file path."""
    path = paths.rail_file(name)
    return load_geometry(path, RAIL, check_rail, "rail", paths.available(paths.rails())), str(path)


def rail_mesh(p: dict):
    """build/rails/<rail>/section.msh of the rail parameters ``p``: meshed (``geometry.rail_mesh.mesh_rail``,
    deterministic) and written atomically unless the file there is identical, which is then left
    untouched.  The rail and greens stages both call it (they run side by side: the greens stage
    needs the mesh, not rail.npz); returns the path."""
    from geometry.rail_mesh import mesh_rail  # here: Make's DEPS of the module's other entry points stay without it

    path = paths.rail_dir(p["name"]) / "section.msh"
    with tempfile.TemporaryDirectory() as d:
        new = f"{d}/section.msh"
        mesh_rail(p, new)
        if not (path.exists() and filecmp.cmp(new, path, shallow=False)):
            with artifacts.atomic_write(path) as tmp:
                shutil.copyfile(new, tmp)
    return path


def run_rail(name: str) -> dict:
    from pipeline.stages.rail_io import build_rail_model, stage_arrays  # lazy: brings in scipy

    p, _ = load_rail_params(name)
    out = paths.rail_dir(name)
    t0 = time.perf_counter()
    model = build_rail_model(p, str(rail_mesh(p)))
    t1 = time.perf_counter()
    freqs = np.geomspace(RAIL_F_MIN_HZ, F_MAX_HZ, N_FREQ)
    arrays = stage_arrays(model, freqs, np.linspace(0.0, X_MAX, N_DIST))
    t2 = time.perf_counter()
    plot_receptances(arrays, out / "receptance.png", name)
    plot_dispersion(arrays, out / "dispersion.png", name)
    artifacts.save_npz(out / "rail.npz", "rail", p, **arrays)
    log.info("rail %s: model %.1f s, dispersion + receptances (%d frequencies x %d distances x %d points) "
             "%.1f s -> %s", name, t1 - t0, N_FREQ, N_DIST, len(arrays["point_y_m"]), t2 - t1, out / "rail.npz")
    return arrays


def plot_receptances(a: dict, path, name: str) -> None:
    """``postprocess.plots.rail.receptance_figure``, saved atomically to ``path``."""
    from postprocess.plots.rail import receptance_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(receptance_figure(a, name), path, dpi=90)


def plot_dispersion(a: dict, path, name: str) -> None:
    """``postprocess.plots.rail.dispersion_figure``, saved atomically to ``path``."""
    from postprocess.plots.rail import dispersion_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(dispersion_figure(a, name), path, dpi=90)
