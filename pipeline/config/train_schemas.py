"""Schemas of the train's keys (issue 32 "the whole train", issue 33 "the pass-by from the vehicle"):
a vehicle file's ``[train]`` and ``[cnossos]`` tables, a curve file's ``receivers_m`` and ``[cnossos]``
(the track's CNOSSOS-EU type).  Read by ``pipeline.config.curve_inputs`` (the noun ``Train``) and
``pipeline.curve.train``.  The CNOSSOS entries are keys of NoiseModelling's RailwayCnossosEU_2020.json
(Directive (EU) 2015/996 Appendix G numbered as NoiseModelling numbers it; pipeline/config/cnossos.py).
"""
from __future__ import annotations

from pipeline.config.loader import Field
from pipeline.config.schema import ListOf

TRAIN = {
    "cars": Field(int, min=1, max=60, default=1, doc="number of identical cars (two bogies each) in the train"),
    "car_length_m": Field(float, unit="m", min=5.0, max=60.0, default=None,
                          doc="a bogie of one car to the same bogie of the next (coupled length); required when "
                              "cars > 1, at least bogie_spacing_m + wheelbase_m"),
}

CNOSSOS_VEHICLE = {
    "wheel_roughness": Field(str, default="5", doc="Vehicle.WheelRoughness entry (3 cast iron, 4 composite, 5 disc)"),
    "contact_filter": Field(str, default="4", doc="Vehicle.ContactFilter entry (3-7: wheel load and diameter)"),
    "transfer": Field(str, default="4", doc="Vehicle.Transfer entry (3 920 mm, 4 840 mm, 5 680 mm, 6 1200 mm wheel)"),
}

CNOSSOS_TRACK = {
    "track_transfer": Field(str, default="4", doc="Track.TrackTransfer entry (3-5 mono-block, 6-8 bi-block sleepers on "
                                                  "soft/medium/hard pads, 9 wooden, 10 direct fastening)"),
    "rail_roughness": Field(str, default="4", doc="Track.RailRoughness entry (3 EN ISO 3095, 4 average network)"),
    "impact": Field(str, default="", doc="Track.ImpactNoise entry ('' none, 3 one joint/switch per 100 m)"),
}

RECEIVERS = ListOf(Field(float, unit="m", min=1.0, max=300.0), min_len=1, max_len=8, default=[7.5],
                   doc="receivers' horizontal distances from the track centre line (m), 1.2 m above the rail head "
                       "(ISO 3095:2013's position at 7.5 m); the pass-by's L_pA,max and L_pAeq at each")
