"""The greens stage's part for ``[contact] points = 2`` (issue 26): the structures at both contact
points (``pipeline.stages.second_point`` has the second zone).

* Wheel: the modal shapes at the second point (the tread/flange boundary node of the wheel mesh
  at its y^W, as for the first), in its contact frame: with the first point's shapes they give
  the wheel's point and cross receptances exactly (modal sum).
* Rail: the moving kernel of all four 2 x 2 blocks g_pq (response at p to a force at q) from one
  rail model loaded at both head points (``solvers.rail.transfer.block_wave_table``: the transfer
  receptances are exact wave sums, as the point ones), on the greens stage's grid and taper,
  projected with each point's frame: g'_pq = R_p^T g_pq R_q.  The second head point is the rail
  file's ``contact.y`` node nearest to the zone's y^R (a gauge-corner zone lies beyond the rail
  model's head points, ``geometry.rail``: then the outermost shoulder node, with a warning).
"""
from __future__ import annotations

import logging
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from pipeline.store import paths
from pipeline.config.contact_plane import frame_angles
from solvers.greens.grid import RAIL_F_TAPER, RAIL_LAGS, RAIL_NT, rail_taper
from pipeline.stages.rail import rail_mesh
from geometry.wheel import tread_radius
from pipeline.config.case import resolve_case

log = logging.getLogger("pipeline.greens")

BLOCKS = ("aa", "ab", "ba", "bb")


def point_frames(c: dict, geo, zone) -> tuple[tuple[float, float], tuple[float, float]]:
    """((wheel, rail) angle of point a, (wheel, rail) angle of point b) in rad: zeros for angle =
    "none", else each zone's contact angle (rail: minus the inclination)."""
    a = frame_angles(c, geo)
    if c["contact"].get("angle", "none") == "none":
        return a, (0.0, 0.0)
    return a, (zone.angle, zone.angle - float(geo.rail_track.alpha))


def rail_node(pr: dict, y_r: float) -> float:
    """The rail file's contact.y node (signed as y_r) nearest to |y_r|."""
    ys = np.unique(np.abs(np.asarray(pr["contact"]["y"], float)))
    y = float(ys[int(np.argmin(np.abs(ys - abs(y_r))))])
    if abs(y - abs(y_r)) > 1e-3:
        log.warning("second contact point y^R = %+.2f mm: the rail model's nearest head node is |y| = %.2f mm "
                    "(%.1f mm away; the rail's receptances there stand in for it)", 1e3 * y_r, 1e3 * y,
                    1e3 * abs(y - abs(y_r)))
    return float(np.copysign(y, y_r))


def rail_blocks(pr: dict, y_a: float, y_b: float, v: float, dt: float) -> dict:
    """The four moving-kernel blocks (n_lags, 2, 2) at head points y_a, y_b (greens grid/taper)."""
    from solvers.greens.kernels import frequency_grid  # lazy: brings in numba, scipy
    from solvers.rail.moving_kernel import moving_green_waves  # lazy: brings in numba
    from solvers.rail.transfer import block_wave_table  # lazy: brings in scipy

    from pipeline.stages.rail_io import build_rail_model  # lazy: brings in scipy

    rail_mesh(pr)
    msh = paths.rail_dir(pr["name"]) / "section.msh"
    model = build_rail_model(pr, str(msh), contact_y=sorted({abs(y_a), abs(y_b)}), with_centre=False)
    f = frequency_grid(dt, RAIL_NT)
    inside = f < RAIL_F_TAPER
    pts = {"a": y_a, "b": y_b}
    pairs = [(pts[k[0]], pts[k[1]]) for k in BLOCKS]
    parts = np.array_split(np.maximum(f[inside], 1.0), 2)
    with ThreadPoolExecutor(2) as ex:
        tabs = list(ex.map(lambda fr: block_wave_table(model, fr, pairs), parts))
    k = np.concatenate([t["k"] for t in tabs], axis=0)
    a = np.concatenate([t["a"] for t in tabs], axis=0) * rail_taper(f[inside])[:, None, None, None, None]
    return {key: moving_green_waves(k, a[:, :, i], v, dt, RAIL_LAGS, RAIL_NT) for i, key in enumerate(BLOCKS)}


def second_greens(case: str, pw: dict, pr: dict, modes: dict, y_rail_a: float, dt: float, v: float) -> dict:
    """greens.npz's second-point arrays: ``b_wheel_phi`` (M, 2), ``rail_kernel_<pq>`` (blocks),
    ``b_y_wheel``, ``b_y_rail`` (the zone's), ``b_y_rail_model`` (the rail node used), the angles
    ``b_contact_angle_wheel``, ``b_contact_angle_rail``."""
    from solvers.contact.frame import project_shapes, project_transfer  # lazy: brings in numba, rocket_fft, scipy
    from solvers.wheel.receptance import contact_point, contact_shape  # lazy: brings in scipy

    from pipeline.stages.second_point import second_zone  # lazy: brings in scipy

    rc = resolve_case(case)
    c, geo = rc.case, rc.geometry
    zone = second_zone(case, c, geo)
    (wa, ra), (wb, rb) = point_frames(c, geo, zone)
    surface = np.unique(np.concatenate([modes["boundary_tread"], modes["boundary_flange"]]))
    where = contact_point(modes["points"], surface, zone.y_wheel, pw["axle"]["rolling_circle_z"],
                          r_of_y=lambda y: tread_radius(pw, y), cells=modes["cells"])
    phi_b = project_shapes(contact_shape(modes["shapes"], where), wb)
    y_b = rail_node(pr, zone.y_rail)
    g = rail_blocks(pr, y_rail_a, y_b, v, dt)
    ang = {"a": ra, "b": rb}
    out = {f"rail_kernel_{k}": project_transfer(g[k], ang[k[0]], ang[k[1]]) for k in BLOCKS}
    out.update(b_wheel_phi=phi_b, b_wheel_point_rz=np.array([where.r, where.Z]), b_y_wheel=np.float64(zone.y_wheel),
               b_y_rail=np.float64(zone.y_rail), b_y_rail_model=np.float64(y_b), b_contact_angle_wheel=np.float64(wb),
               b_contact_angle_rail=np.float64(rb), contact_angle_wheel_a=np.float64(wa))
    return out
