"""The case key ``[contact] points = 2`` (issue 26): the second contact zone of the profiles as a
second contact patch -- its geometry, its NORM table, compliance and friction curve (contact
stage, keys ``b_*`` of contact.npz) and the structures at both points (greens stage: the wheel's
shapes there, the rail's 2 x 2-point moving kernel, keys ``b_*`` and ``rail_kernel_ab``,
``rail_kernel_ba``, ``rail_kernel_bb`` of greens.npz).

Second zone: ``geometry.contact_point`` reports the lowest other zone within 0.25 mm of the
rigid contact (``second_zone``: y^W, extra vertical separation e).  Its contact plane is the
common tangent there (the rail's slope, delta_b: up to ~70 deg on a flange).  The patch is a
half-space contact in that plane: the profiles are turned by -delta_b about the zone's rail
point, so that the gap is measured along its normal, and the wheel's curvature along the rolling
direction in that normal section is cos(delta_b) / r_b (Meusnier: a surface of revolution of
radius r_b, normal tilted by delta_b from the radius).  The rail profiles end at the head's widest
point, at the gauge corner, sometimes within a millimetre of a flange zone: beyond its end the
turned rail surface is continued along its end curvature (the corner arc's).  Limits (docs/validation/34_two_points.md):
the half-space model wants the patch small against the radii -- the flange's lateral radius of
a few mm is not, and conformal flange contact is outside Kalker's half-space theory; the two
patches do not interact through the half-space; the rail model takes head points on its crown
and shoulder arcs only (``geometry.rail``), so a gauge-corner point is taken at the outermost
such node of the rail file's ``contact.y`` (greens.npz ``b_y_rail_model``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from geometry.turned import turned_geometry
from pipeline.store import paths
from pipeline.config.loader import ConfigError
from pipeline.caches.friction_curves import compute_curve, curve_arrays, entries_of

TRACK_FRAME_MAX = np.radians(15.0)   # angle = "none" with a second zone steeper than this: a one-line error


@dataclass(frozen=True)
class SecondZone:
    """The second zone of a case: y^W, Y (track), y^R (rail frame), angle delta_b (rad), extra
    vertical separation e (m), rolling radius r_b (m), and ``gap_geometry`` (what
    ``stages.contact.static_contact`` needs, in the zone's turned frame)."""
    y_wheel: float
    y_track: float
    y_rail: float
    angle: float
    separation: float
    r_b: float
    gap_geometry: object


def second_zone(name: str, c: dict, geo) -> SecondZone:
    """The case's second contact zone; a one-line ConfigError when the profiles have none or the
    case asks for what the two-point loop does not have (Kalker's TANG, per-step NORM, spin)."""
    rc = geo.contact
    if c["contact"]["model"] != "point" or c["contact"]["normal"] != "table":
        raise ConfigError(str(paths.case_file(name)), detail=(
            f"contact.points = 2 needs contact.model = \"point\" and contact.normal = \"table\" (the two-point loop "
            f"has the point-contact model with NORM tables), got {c['contact']['model']!r}, {c['contact']['normal']!r}"))
    if c["kinematics"].get("spin", 0.0):
        raise ConfigError(str(paths.case_file(name)), detail=(
            f"contact.points = 2 with kinematics.spin = {c['kinematics']['spin']:g} 1/m: the two-point loop has no "
            f"spin (each patch's spin would follow from its own contact angle); use points = 1 or spin = 0"))
    if rc.second is None or not np.isfinite(rc.second[0]):
        raise ConfigError(str(paths.case_file(name)), detail=(
            f"contact.points = 2: case '{name}', dy_WR = {1e3 * c['contact']['dy_wr']:+.2f} mm: the profiles have no "
            f"second contact zone within 0.25 mm of the contact (y^W = {1e3 * rc.y_wheel:+.2f} mm); use points = 1 "
            f"or another offset"))
    y2, e = float(rc.second[0]), float(rc.second[1])
    Y2 = y2 + rc.shift
    delta = float(np.arctan(geo.rail_track.slope(Y2)))
    if abs(delta) > TRACK_FRAME_MAX and c["contact"].get("angle", "none") == "none":
        raise ConfigError(str(paths.case_file(name)), detail=(
            f"contact.points = 2: case '{name}': the second zone's contact angle is {np.degrees(delta):+.0f} deg "
            f"(y^W = {1e3 * y2:+.2f} mm); its forces cannot be taken in the track's directions (contact.angle = "
            f"\"none\", allowed up to {np.degrees(TRACK_FRAME_MAX):.0f} deg): set contact.angle = \"profiles\""))
    r_b = float(geo.r_wheel(y2))
    return SecondZone(y2, Y2, geo.rail_track.to_rail(Y2), delta, e, r_b, turned_geometry(geo, y2, Y2, delta, r_b))


def second_contact_arrays(name: str, c: dict, pw: dict, geo, F_L: float, friction, n_table: int = 41) -> dict:
    """The contact stage's arrays of the second patch (keys ``b_*``): its gap, NORM table over
    0 .. 2x the approach at which it alone would carry F_L (the first patch's static normal force:
    the range the load can move through), compliances, and the friction curve of ``friction`` (the
    case's resolved ``FrictionLaw``)."""
    from solvers.contact.compliance import compliance_table  # lazy: brings in numba
    from solvers.contact.norm import norm_table  # lazy: brings in numba

    from solvers.contact.static import DY, static_contact  # lazy: brings in numba, rocket_fft

    z = second_zone(name, c, geo)
    E, nu = pw["material"]["E"], pw["material"]["nu"]
    v, dt = c["kinematics"]["speed"], c["time"]["dt"]
    dx = v * dt
    x, y, gap, A, B, xi_static, static = static_contact(z.gap_geometry, E, nu, F_L, dx)
    xi_nodes = np.linspace(0.0, 2.0 * xi_static, n_table)
    table = norm_table(gap, xi_nodes, dx, DY, E, nu)
    A1, A2 = compliance_table(xi_nodes, table.p, dx, DY, E, nu)
    curve = curve_arrays(entries_of([friction], [compute_curve(static.p, dx, DY, v, friction, E, nu)]))
    return {"b_y_wheel": np.float64(z.y_wheel), "b_y_track": np.float64(z.y_track), "b_y_rail": np.float64(z.y_rail),
            "b_contact_angle": np.float64(z.angle), "b_separation": np.float64(z.separation),
            "b_rolling_radius": np.float64(z.r_b), "b_x": x, "b_y": y, "b_gap": gap, "b_curvature_A": np.float64(A),
            "b_curvature_B": np.float64(B), "b_xi3_full_load": np.float64(xi_static), "b_xi3_nodes": xi_nodes,
            "b_F3_nodes": table.F3, "b_q_nodes": table.q, "b_A1_nodes": A1, "b_A2_nodes": A2,
            **{f"b_{k}": a for k, a in curve.items()}}


def second_contact_model(con, friction):
    """The second patch's ContactModel from contact.npz's ``b_*`` arrays (``friction``: the case's
    ``pipeline.caches.friction_curves.Friction`` or a Coulomb mu)."""
    from solvers.timeloop.interaction import contact_model  # lazy: brings in numba, rocket_fft

    keys = ("xi3_nodes", "F3_nodes", "q_nodes", "A1_nodes", "A2_nodes", "mu_values", "rf_label", "rf_law", "rf_n",
            "rf_s", "rf_mu", "rf_slope")
    have = con.files if hasattr(con, "files") else con
    return contact_model({k: con["b_" + k] for k in keys if "b_" + k in have}, friction)
