"""Schemas of the vehicle files (``geometry/vehicles/<name>.toml``) and the curve files
(``pipeline/curves/<name>.toml``, or a user's anywhere), validated by ``pipeline.config.loader`` like
every input; ``pipeline.config.curve_inputs`` reads them into the nouns ``Vehicle`` and ``Curve``.

Engineers' units, each in its key's name (kN, mm, m, km/h, MN/m, kN m/rad); the pipeline
converts to SI (``pipeline.curve.curving``).  The ranges are plausibility bounds from trams to
heavy-haul freight, narrow enough to catch a unit mistake (N typed for kN, m for mm).
"""
from __future__ import annotations

from pipeline.config.loader import Field
from pipeline.config.train_schemas import CNOSSOS_TRACK, CNOSSOS_VEHICLE, RECEIVERS, TRAIN
from pipeline.caches.friction_curves import friction_schema

VEHICLE = {
    "name": Field(str, doc="short name, used in build paths"),
    "description": Field(str, default=""),
    "wheel": Field(str, doc="geometry/wheels/<wheel>.toml: rolling radius and flange-back offset of the wheel"),
    "wheel_profile": Field(str, default=None,
                           doc="running-surface profile geometry/profiles/<name>.csv (default: the wheel file's "
                               "running_surface.profile)"),
    "category": Field(str, choices=["railway", "tram"], default="railway",
                      doc="which part of Schall 03 (16. BImSchV Anlage 2) rates its curves: railway (section 4.9, "
                          "K_L 8 dB r < 300 m, 3 dB to < 500 m) or tram (section 5.3.2: 4 dB r < 200 m)"),
    "bogie": {
        "wheelbase_m": Field(float, unit="m", min=1.0, max=4.0, doc="distance between the bogie's two axles"),
        "bogie_spacing_m": Field(float, unit="m", min=3.0, max=30.0, doc="distance between the car's bogie centres"),
        "back_to_back_mm": Field(float, unit="mm", min=1300.0, max=1400.0,
                                 doc="distance between the wheels' flange back faces (standard gauge 1360 mm)"),
    },
    "load": {
        "wheel_load_kN": Field(float, unit="kN", min=10.0, max=200.0,
                               doc="static vertical load per wheel (give this or axle_load_kN)", default=None),
        "axle_load_kN": Field(float, unit="kN", min=20.0, max=400.0,
                              doc="static vertical load per axle (give this or wheel_load_kN)", default=None),
        "cg_height_m": Field(float, unit="m", min=0.5, max=3.0,
                             doc="centre of gravity of the sprung mass above the top of the rail (load transfer)"),
    },
    "wheelset": {
        "mass_kg": Field(float, unit="kg", min=300.0, max=4000.0, doc="whole wheelset (its own lateral inertia force)"),
        "yaw_inertia_kgm2": Field(float, unit="kg m^2", min=50.0, max=5000.0,
                                  doc="about the vertical axis; recorded with the vehicle, not used by the "
                                      "quasi-static equilibrium (no yaw acceleration in steady curving)"),
    },
    "primary": {
        "kx_MN_per_m": Field(float, unit="MN/m", min=0.05, max=500.0,
                             doc="longitudinal stiffness per axle box (yaw stiffness 2 kx b^2 per wheelset)"),
        "ky_MN_per_m": Field(float, unit="MN/m", min=0.05, max=500.0, doc="lateral stiffness per axle box"),
        "box_half_spacing_m": Field(float, unit="m", min=0.5, max=1.5,
                                    doc="b: wheelset centre to the axle-box springs, laterally"),
    },
    "secondary": {
        "yaw_stiffness_kNm_per_rad": Field(float, unit="kN m/rad", min=0.0, max=1e5, default=0.0,
                                           doc="bogie to car body rotational stiffness (0: free to turn)"),
    },
    "train": TRAIN,
    "cnossos": CNOSSOS_VEHICLE,
}

# the case file's [friction] table (issue 33): law (default "coulomb") with its parameters, or a preset; and the
# friction climate of the risk verdict (issue 32)
FRICTION = friction_schema() | {
    "climate": Field(str, default=None, doc="friction climate of the risk verdict: pipeline/climates/<name>.toml or a path "
                                            "(default: 'default'; docs/friction_climate.md)"),
}

CURVE = {
    "name": Field(str, doc="short name, used in build paths"),
    "description": Field(str, default=""),
    "vehicle": Field(str, doc="<vehicle>.toml beside the curve file, else geometry/vehicles/<vehicle>.toml"),
    "rail": Field(str, default="bv50", doc="geometry/rails/<rail>.toml (inclination, head profile)"),
    "rail_profile": Field(str, default=None,
                          doc="head profile geometry/profiles/<name>.csv (default: the rail file's running_surface)"),
    "radius_m": Field(float, unit="m", min=15.0, max=20000.0, doc="curve radius (track centre line)"),
    "cant_mm": Field(float, unit="mm", min=-200.0, max=200.0, default=0.0, doc="superelevation of the outer rail"),
    "gauge_mm": Field(float, unit="mm", min=1000.0, max=1700.0, default=1435.0,
                      doc="nominal track gauge between the gauge faces"),
    "gauge_widening_mm": Field(float, unit="mm", min=0.0, max=30.0, default=0.0,
                               doc="gauge widening in the curve (added to the gauge)"),
    "speed_kmh": Field(float, unit="km/h", min=2.0, max=200.0, doc="vehicle speed"),
    "friction": FRICTION,
    "traction": {
        "force_kN": Field(float, unit="kN", min=-100.0, max=100.0, default=0.0,
                          doc="longitudinal force per axle of the leading bogie: + traction, - braking, 0 coasting"),
    },
    "receivers_m": RECEIVERS,
    "cnossos": CNOSSOS_TRACK,
}
