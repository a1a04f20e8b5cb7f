"""Operating points for the verdict's tests."""
from __future__ import annotations

import dataclasses

from pipeline.config.nouns import WheelOperatingPoint


def operating_point(**kw) -> WheelOperatingPoint:
    """A WheelOperatingPoint with the given fields, the others zero (profiles none): what the figure and the
    verdict row read."""
    base = {f.name: 0.0 for f in dataclasses.fields(WheelOperatingPoint)}
    base |= {"axle": 1, "side": "inner", "contact_points": 1, "friction_law": "coulomb", "wheel_file": "c20",
             "rail_file": "bv50", "wheel_profile": None, "rail_profile": None, "nadal": float("nan")}
    return WheelOperatingPoint(**(base | kw))
