"""Schemas of the TOML inputs (validated by ``pipeline.config.loader``).

Units are SI; the ranges are physical plausibility bounds for railway
wheels, wide enough for tram to freight wheels and narrow enough to catch
unit mistakes (mm typed for m, MPa for Pa).
"""
from __future__ import annotations

from pipeline.config.loader import Field, ListOf
from pipeline.caches.friction_curves import friction_schema

L = dict(kind=float, unit="m")

WHEEL = {
    "name": Field(str, doc="short name, used in build paths"),
    "description": Field(str, default=""),
    "material": {
        "E": Field(float, unit="Pa", min=50e9, max=400e9, doc="Young's modulus"),
        "nu": Field(float, min=0.0, max=0.49, doc="Poisson's ratio"),
        "rho": Field(float, unit="kg/m^3", min=1000.0, max=20000.0, doc="density"),
    },
    "tyre": {
        "rolling_radius": Field(**L, min=0.15, max=0.7, min_inclusive=False, doc="nominal rolling radius"),
        "width": Field(**L, min=0.05, max=0.2, doc="tyre width w, flange back to field face"),
        "back_offset": Field(**L, min=0.03, max=0.12, doc="rolling circle from the flange back face"),
        "depth": Field(**L, min=0.015, max=0.15, doc="radial depth of the tyre below the rolling circle, at the flange back"),
        "depth_field": Field(**L, min=0.015, max=0.15, default=None,
                             doc="the same at the field face (default: depth); the inner tyre surface is linear between"),
        "conicity": Field(float, min=0.0, max=0.1, doc="tread slope (1:40 = 0.025)"),
        "field_chamfer": Field(**L, min=0.0, max=0.02),
    },
    "flange": {
        "height": Field(**L, min=0.015, max=0.045),
        "thickness": Field(**L, min=0.015, max=0.045, doc="measured 10 mm above the rolling circle"),
        "face_angle_deg": Field(float, unit="deg", min=45.0, max=85.0),
        "root_radius": Field(**L, min=0.0, max=0.03),
        "tip_radius": Field(**L, min=0.0, max=0.02),
    },
    "web": {
        "thickness_tyre": Field(**L, min=0.008, max=0.12, doc="web thickness at the tyre"),
        "thickness_hub": Field(**L, min=0.008, max=0.15, doc="web thickness at the hub"),
        "y_tyre": Field(**L, min=-0.12, max=0.12, doc="web centre at the tyre, y^W"),
        "y_hub": Field(**L, min=-0.25, max=0.25, doc="web centre at the hub, y^W"),
        "bulge": Field(**L, min=-0.1, max=0.1, doc="lateral bulge of the web centreline (Bezier control offset)"),
        "fillet_tyre": Field(**L, min=0.0, max=0.05),
        "fillet_hub": Field(**L, min=0.0, max=0.06),
    },
    "hub": {
        "outer_radius": Field(**L, min=0.05, max=0.3),
        "bore_radius": Field(**L, min=0.03, max=0.15, min_inclusive=False),
        "y_inboard": Field(**L, min=-0.35, max=0.2),
        "y_outboard": Field(**L, min=-0.2, max=0.35),
    },
    "mount": {
        "type": Field(str, choices=["clamped", "axle"], default="clamped",
                      doc="'clamped': flexible wheel clamped at the bore plus the rigid half wheelset on the "
                          "suspension; 'axle': half axle in the section, suspension springs at the journal"),
        "midplane": Field(str, choices=["symmetric", "antisymmetric"], default="symmetric",
                          doc="condition at the wheelset centre plane (axle mount)"),
    },
    "axle": {
        "rolling_circle_z": Field(**L, min=0.4, max=1.0, default=0.75, doc="wheelset centre to rolling circle"),
        "body_radius": Field(**L, min=0.03, max=0.15, default=0.08),
        "journal_radius": Field(**L, min=0.03, max=0.15, default=0.065),
        "journal_length": Field(**L, min=0.05, max=0.4, default=0.18),
        "journal_end_z": Field(**L, min=0.6, max=1.5, default=1.08),
    },
    "suspension": {
        "k_vertical": Field(float, unit="N/m", min=1e4, max=1e9, doc="primary vertical stiffness per axle box"),
        "k_lateral": Field(float, unit="N/m", min=1e4, max=1e9, doc="primary lateral stiffness per axle box"),
        "c_vertical": Field(float, unit="N s/m", min=0.0, max=1e6, doc="primary vertical damping per axle box"),
        "c_lateral": Field(float, unit="N s/m", min=0.0, max=1e6, doc="primary lateral damping per axle box"),
        "wheelset_mass": Field(float, unit="kg", min=100.0, max=5000.0, doc="whole wheelset"),
        "wheelset_roll_inertia": Field(float, unit="kg m^2", min=10.0, max=5000.0,
                                       doc="whole wheelset about the longitudinal axis through its centre"),
        "box_half_spacing": Field(**L, min=0.5, max=1.5, doc="wheelset centre to axle-box spring, laterally"),
    },
    "modes": {
        "f_max": Field(float, unit="Hz", min=100.0, max=20000.0, default=7000.0),
        "n_max": Field(int, min=0, max=30, default=10),
        "degree": Field(int, min=1, max=3, default=2, doc="Lagrange degree of the section elements"),
    },
    "mesh": {
        "size_tread": Field(**L, min=0.0005, max=0.05),
        "size_tyre": Field(**L, min=0.0005, max=0.05),
        "size_web": Field(**L, min=0.0005, max=0.05),
        "size_hub": Field(**L, min=0.0005, max=0.1),
        "size_axle": Field(**L, min=0.001, max=0.1, default=0.02),
    },
    "running_surface": {
        "profile": Field(str, default=None, doc="tabulated tread profile geometry/profiles/<profile>.csv for the "
                                                "contact (default: the parametric cone + flange above)"),
    },
}

# the train of the pass-by (postprocess/listening/passby.py), heard at the [listener] position ([listener.passby]); speed: the case's
PASSBY = {
    "n_bogies": Field(int, min=1, max=40, default=2,
                      doc="squealing wheels passing, one per bogie (its leading wheelset's wheel on the near rail)"),
    "bogie_spacing": Field(float, unit="m", min=1.0, max=40.0, default=12.5,
                           doc="distance between consecutive squealing wheels (bogie centres; a metro car: 10-13 m)"),
    "window": Field(float, unit="m", min=5.0, max=500.0, default=30.0,
                    doc="the passage: from the first squealing wheel this far before the receiver to the last one "
                        "this far past it (L_pAeq over that time)"),
}

# the receiver of the `listen` stage (postprocess/listening/listener.py states the propagation model)
LISTENER = {
    "distance": Field(float, unit="m", min=0.0, max=1000.0, min_inclusive=False, default=7.5,
                      doc="receiver from the track centre, horizontally (ISO 3095 pass-by position: 7.5 m)"),
    "height": Field(float, unit="m", min=0.0, max=100.0, min_inclusive=False, default=1.2,
                    doc="receiver above the top of the rail (ISO 3095: 1.2 m)"),
    "ground_depth": Field(float, unit="m", min=0.0, max=5.0, default=0.2,
                          doc="reflecting ground plane below the top of the rail (ballast surface)"),
    "ground": Field(str, choices=["rigid", "none"], default="rigid",
                    doc="'rigid': image source in the ground plane; 'none': free field"),
    "directivity": Field(str, choices=["dipole", "omni"], default="dipole",
                         doc="the wheel as a dipole along the axle (axial squeal modes) or omnidirectional"),
    "passby": PASSBY,
}

CASE = {
    "name": Field(str),
    "description": Field(str, default=""),
    "wheel": Field(str, default="c20", doc="geometry/wheels/<wheel>.toml"),
    "rail": Field(str, default="bv50", doc="geometry/rails/<rail>.toml"),
    "contact": {
        "dy_wr": Field(float, unit="m", min=-0.03, max=0.03,
                       doc="wheelset lateral offset; the contact point is the rigid contact of the profiles "
                           "(SPEC 2: -0.005, -0.010, -0.015)"),
        "rolling_circle_y": Field(float, unit="m", min=-0.03, max=0.03, default=-0.0056667,
                                  doc="c: the wheel's rolling circle over the rail centre line (+ field side) for "
                                      "the centred wheelset (Y = y^W + c + dy_wr); -17/3 mm follows from the "
                                      "thesis table [4.1] with its y^W negated (solvers.constants)"),
        "wheel_profile": Field(str, default=None, doc="overrides the wheel file's running_surface.profile"),
        "rail_profile": Field(str, default=None, doc="overrides the rail file's running_surface.profile"),
        "model": Field(str, choices=["point", "kalker"], default="point",
                       doc="tangential contact: point-contact model with regularized friction, or Kalker's "
                           "transient variational theory"),
        "normal": Field(str, choices=["table", "norm"], default="table",
                        doc="normal contact from a NORM table over the approach, or NORM every step"),
        "angle": Field(str, choices=["none", "profiles"], default="none",
                       doc="contact forces in the track's directions (the reference's choice) or in the contact "
                           "plane of the profiles (normal tilted by the rigid contact's angle; solvers.contact.frame)"),
        "points": Field(int, min=1, max=2, default=1,
                        doc="contact points: 1, or 2 (the profiles' second contact zone, tread and flange or two "
                            "tread zones, each with its own patch; solvers.timeloop.two_point)"),
    },
    "friction": friction_schema(),      # law (default "coulomb") and its parameters, or a preset
    "kinematics": {
        "gamma_y": Field(float, min=-0.2, max=0.2, doc="lateral creepage"),
        "gamma_x": Field(float, min=-0.2, max=0.2, default=0.0, doc="longitudinal creepage"),
        "speed": Field(float, unit="m/s", min=0.5, max=60.0, doc="rolling speed v"),
        # issue 26 (point contact): spin beside the creepages
        "spin": Field(float, unit="1/m", min=-20.0, max=20.0, default=0.0,
                      doc="spin creepage phi (rigid slip w = (gamma_x - phi y, gamma_y + phi x) v; |phi| ~ sin|contact "
                          "angle| / rolling radius); the point contact takes it as equivalent creepages from "
                          "Kalker's linear theory (solvers.contact.spin), Kalker's TANG as it is"),
    },
    "loading": {
        "preload": Field(float, unit="N", min=1e3, max=3e5, doc="static wheel load F_L3"),
    },
    "time": {
        "dt": Field(float, unit="s", min=1e-6, max=2e-4, doc="time step; dx = v dt"),
        "duration": Field(float, unit="s", min=0.01, max=8.0, doc="at most this much rolling"),
    },
    "listener": LISTENER,
}

RAIL = {
    "name": Field(str),
    "description": Field(str, default=""),
    "reference": {  # published values the section is checked against (tests/rail/test_section.py)
        "source": Field(str),
        "area": Field(float, unit="m^2", min=2e-3, max=1.2e-2),
        "mass_per_m": Field(float, unit="kg/m", min=20.0, max=90.0),
        "I_vertical": Field(float, unit="m^4", min=5e-6, max=8e-5),
        "I_lateral": Field(float, unit="m^4", min=1e-6, max=2e-5),
        "z_centroid": Field(float, unit="m", min=0.03, max=0.12, default=None),
    },
    "material": {
        "E": Field(float, unit="Pa", min=50e9, max=400e9),
        "nu": Field(float, min=0.0, max=0.49),
        "rho": Field(float, unit="kg/m^3", min=1000.0, max=20000.0),
        "loss_factor": Field(float, min=0.0, max=0.5, doc="steel loss factor (typ. 0.01-0.02)"),
    },
    "section": {"height": Field(**L, min=0.08, max=0.25)},
    "head": {
        "width": Field(**L, min=0.03, max=0.12),
        "depth": Field(**L, min=0.02, max=0.08),
        "crown_radius": Field(**L, min=0.05, max=1.0),
        "crown_half_width": Field(**L, min=0.0, max=0.03),
        "shoulder_radius": Field(**L, min=0.01, max=0.3),
        "corner_radius": Field(**L, min=0.003, max=0.03),
        "side_taper": Field(float, min=-0.5, max=0.5),
        "underside_slope": Field(float, min=0.0, max=1.0),
        "underside_radius": Field(**L, min=0.0, max=0.02),
        "web_fillet": Field(**L, min=0.0, max=0.05),
    },
    "web": {"thickness": Field(**L, min=0.008, max=0.04)},
    "foot": {
        "width": Field(**L, min=0.06, max=0.2),
        "thickness_web": Field(**L, min=0.008, max=0.05),
        "thickness_edge": Field(**L, min=0.003, max=0.03),
        "web_fillet": Field(**L, min=0.0, max=0.05),
        "edge_radius": Field(**L, min=0.0, max=0.01),
        "bottom_radius": Field(**L, min=0.0, max=0.01),
    },
    "pad": {
        "thickness": Field(**L, min=0.002, max=0.05),
        "width": Field(**L, min=0.03, max=0.25),
        "stiffness": Field(float, unit="N/m^2", min=1e6, max=5e9,
                           doc="vertical stiffness per metre of rail (typ. 1e8-6e8)"),
        "loss_factor": Field(float, min=0.0, max=1.5, doc="typ. 0.15-0.3"),
        "poisson": Field(float, min=0.0, max=0.4999),
        "rho": Field(float, unit="kg/m^3", min=0.1, max=3000.0),
    },
    "mesh": {
        "size_head": Field(**L, min=0.0005, max=0.02),
        "size_web": Field(**L, min=0.0005, max=0.02),
        "size_foot": Field(**L, min=0.0005, max=0.02),
        "pad_layers": Field(int, min=1, max=10),
    },
    "running_surface": {
        "profile": Field(str, default=None, doc="tabulated head profile geometry/profiles/<profile>.csv for the "
                                                "contact (default: the head arcs above)"),
        "inclination": Field(float, min=0.0, max=0.1, default=0.0,
                             doc="rail inclination toward the track centre, tan (1:30 = 0.0333, 1:40 = 0.025)"),
    },
    "contact": {"y": ListOf(Field(float, unit="m", min=-0.04, max=0.04), min_len=1, max_len=10,
                            doc="rail-head points y^R where receptances are evaluated (SPEC 2)")},
}
