"""Contact stage: everything the time loop needs about the contact of a case
(SPEC 4), computed with Kalker's discretised half-space theory.

The contact point is the rigid contact of the case's wheel and rail profiles
at its wheelset offset (``pipeline.config.case.resolve_case``, which every stage
reads).  Around it the stage builds the
undeformed gap from the profiles on the grid dx = v dt (the potential area
from the gap itself, enlarged until the static patch stays inside), the NORM
table F3(xi3) with pressures (and its measured interpolation error), the
tangential compliance A_tau over the approach, and the regularized friction
curve mu_RF(s) of the case's friction at the static preload (``pipeline.caches.friction_curves``: built
per law and value and cached by value, so that a study or another stage adds the curves of
other values to the same contact at one curve each).

Artifact: build/cases/<case>/contact.npz (keys in docs/reference.md) and
contact_rf.png.
"""
from __future__ import annotations

import logging
import time

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.case import resolve_case
from pipeline.stages.second_point import second_zone, second_contact_arrays
from solvers.contact.compliance import compliance_table
from solvers.contact.norm import norm_table, table_midpoint_error
from pipeline.caches.friction_curves import as_friction, case_friction, compute_curve, curve_arrays, entries_of
from solvers.contact.surfaces import patch_metrics
from pipeline.config.contact_plane import normal_preload
from pipeline.config.check import outer_wheel_note, over_radial_note
from pipeline.config.loader import ConfigError

log = logging.getLogger("pipeline.contact")

from solvers.contact.static import DY, ConformalContact, static_contact  # noqa: F401  (the stage's grid and errors)


def contact_setup(case: str) -> tuple[dict, dict, dict, object, dict]:
    """(case, wheel, rail, ContactGeometry, resolved config) of a case (``pipeline.config.case.resolve_case``)."""
    rc = resolve_case(case)
    cfg = dict(rc.config, friction=rc.friction.config(), dy=DY)
    if rc.case["contact"].get("points", 1) == 2:  # [contact] points = 2: the second zone must exist (one-line error)

        second_zone(case, rc.case, rc.geometry)
    return rc.case, rc.wheel, rc.rail, rc.geometry, cfg


def contact_inputs(case: str) -> tuple[dict, dict, dict, dict]:
    """(case, wheel, rail, resolved config) of a case: the contact artifact's
    configuration (for staleness checks of the stages that load it)."""
    c, pw, pr, _, cfg = contact_setup(case)
    return c, pw, pr, cfg


def build_contact(c: dict, pw: dict, geo, n_table: int = 41, frictions=None, curve=None,
                  diagnostics: bool = True) -> dict:
    """The contact arrays of one case; ``geo`` is the case's ContactGeometry (profiles and rigid
    contact point).  Friction curves for ``frictions`` (Friction or float mu each; default: the
    case's friction), each by ``curve`` (``pipeline.caches.friction_curves.compute_curve`` without I/O, the
    default, or a ``CurveCache``).  ``diagnostics``: the NORM table's measured interpolation error
    (``table_error_*``, a NORM solve per interval: about a third of the stage; no solver reads it;
    empty arrays without)."""
    E, nu = pw["material"]["E"], pw["material"]["nu"]

    v, dt = c["kinematics"]["speed"], c["time"]["dt"]
    F_L = normal_preload(c, geo)  # [contact] angle: the preload resolved in the contact plane
    dx = v * dt  # SPEC 4.1: the contact moves one element per step
    x, y, gap, A, B, xi_static, static = static_contact(geo, E, nu, F_L, dx)
    xi_nodes = np.linspace(0.0, 2.0 * xi_static, n_table)
    table = norm_table(gap, xi_nodes, dx, DY, E, nu)
    err = (table_midpoint_error(table, gap, dx, DY, E, nu) if diagnostics
           else {k: np.zeros(0) for k in ("xi3", "force", "pressure")})
    A1_nodes, A2_nodes = compliance_table(xi_nodes, table.p, dx, DY, E, nu)
    frictions = [case_friction(c)] if frictions is None else [as_friction(f) for f in frictions]
    curves = [(curve or compute_curve)(static.p, dx, DY, v, f, E, nu) for f in frictions]
    patch = patch_metrics(static.p, x, y)
    rc = geo.contact
    second = rc.second if rc.second is not None else (np.nan, np.nan)

    return {
        "x": x, "y": y, "dx": np.float64(dx), "dy": np.float64(DY), "gap": gap,
        "y_wheel": np.float64(rc.y_wheel), "y_rail": np.float64(rc.y_rail), "y_track": np.float64(rc.y_track),
        "contact_angle": np.float64(rc.angle), "second_zone": np.array(second, float),
        "curvature_A": np.float64(A), "curvature_B": np.float64(B),
        "curvature_wheel": np.float64(geo.wheel.curvature(rc.y_wheel)),
        "curvature_rail": np.float64(geo.rail_track.curvature(rc.y_track)),
        "patch_area": np.float64(patch["area"]), "patch_length": np.float64(patch["length"]),
        "patch_width": np.float64(patch["width"]),
        "xi3_static": np.float64(xi_static), "p3_static": static.p, "preload_normal": np.float64(F_L),
        "xi3_nodes": xi_nodes, "F3_nodes": table.F3, "q_nodes": table.q, "pressure_nodes": table.p,
        "table_error_xi3": err["xi3"], "table_error_F3": err["force"], "table_error_p": err["pressure"],
        "A1_nodes": A1_nodes, "A2_nodes": A2_nodes,
        "speed": np.float64(v), "material_E": np.float64(E), "material_nu": np.float64(nu),
    } | curve_arrays(entries_of(frictions, curves))


def run_contact(case: str) -> dict:
    from pipeline.caches.friction_curves import contact_curve_cache  # here: Make's DEPS of the module's other entry points stay without it


    c, pw, pr, geo, cfg = contact_setup(case)
    friction = resolve_case(case).friction                # resolved once, with the case
    if over_radial_note(c):
        log.warning("note: case %s: %s", case, over_radial_note(c))
    elif outer_wheel_note(c):
        log.info("note: case %s: %s", case, outer_wheel_note(c))
    t0 = time.perf_counter()
    cache = contact_curve_cache(case)
    try:
        arrays = build_contact(c, pw, geo, frictions=[friction], curve=cache)
        if c["contact"].get("points", 1) == 2:  # [contact] points = 2: the second patch (pipeline/stages/second_point.py)

            arrays.update(second_contact_arrays(case, c, pw, geo, float(arrays["preload_normal"]), friction))
    except ConformalContact as e:                      # a contact of the case's input: one line, no traceback

        raise ConfigError(str(paths.case_file(case)), [("contact.dy_wr", c["contact"]["dy_wr"], f"not a contact "
                                                        f"this model can solve: {e}")]) from None
    out = paths.case_dir(case)
    plot_rf(arrays, out / "contact_rf.png", f"{case}: dy_WR = {1e3 * c['contact']['dy_wr']:.0f} mm")
    artifacts.save_npz(out / "contact.npz", "contact", cfg, **arrays)
    err = np.nanmax(arrays["table_error_F3"][arrays["table_error_xi3"] > 0.5 * arrays["xi3_static"]])
    log.info("contact %s: contact point y^W = %+.2f mm, y^R = %+.2f mm (angle %+.1f deg); grid %d x %d (dx = %.3g mm), "
             "patch %.0f mm^2 (%.1f x %.1f mm), static approach %.1f um, NORM table error %.2g %% near the working "
             "point, friction %s (%s) in %.1f s -> %s", case, 1e3 * arrays["y_wheel"], 1e3 * arrays["y_rail"],
             np.degrees(arrays["contact_angle"]), len(arrays["x"]), len(arrays["y"]), 1e3 * arrays["dx"],
             1e6 * arrays["patch_area"], 1e3 * arrays["patch_length"], 1e3 * arrays["patch_width"],
             1e6 * arrays["xi3_static"], 100 * err, ", ".join(arrays["rf_label"]), cache.summary(),
             time.perf_counter() - t0, out / "contact.npz")
    return arrays


def plot_rf(a: dict, path, title: str) -> None:
    """``postprocess.plots.contact.friction_curves_figure``, saved atomically to ``path``."""
    from postprocess.plots.contact import friction_curves_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(friction_curves_figure(a, title), path, dpi=100)
