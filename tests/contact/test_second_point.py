"""The second contact patch's geometry (issue 26, pipeline/stages/second_point.py): the profiles turned
into the zone's contact plane, against two circles touching at a 35 deg tangent (the gap along
the common normal is known exactly), the rolling-direction curvature cos(delta) / r_b, and the
one-line errors of `[contact] points = 2`."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from pipeline.config.loader import ConfigError
from pipeline.stages.second_point import second_zone, turned_geometry
from solvers.contact.surfaces import contact_gap, curvatures

DELTA = math.radians(35.0)
RR, RW = 0.013, 0.030        # rail corner radius, wheel flange-root radius (m)


def circles():
    """Rail top arc z(Y) and wheel lower arc h(Y) touching at Y = 0 with slope tan(DELTA)."""
    yc, zc = RR * math.sin(DELTA), -RR * math.cos(DELTA)
    yw, zw = -RW * math.sin(DELTA), RW * math.cos(DELTA)
    def arc(R, c):
        def f(Y):
            q = R ** 2 - (np.asarray(Y, float) - c) ** 2
            return np.where(q >= 0, np.sqrt(np.abs(q)), np.nan)
        return f
    rail = lambda Y: zc + arc(RR, yc)(Y)                                                       # noqa: E731
    hw = lambda Y: zw - arc(RW, yw)(Y)                                                         # noqa: E731
    wheel = lambda y: -hw(y)                                                                   # noqa: E731 z_W = -height
    return SimpleNamespace(rail_track=rail, wheel=wheel)


def test_turned_gap_of_two_circles():
    geo = circles()
    r_b = 0.45
    t = turned_geometry(geo, 0.0, 0.0, DELTA, r_b)
    eta = np.linspace(-3e-3, 3e-3, 61)
    h = contact_gap(t.r_wheel, t.z_rail, 0.0, 0.0, np.array([0.0]), eta)[0]
    exact = (RW - np.sqrt(RW ** 2 - eta ** 2)) + (RR - np.sqrt(RR ** 2 - eta ** 2))
    assert np.abs(h - exact).max() < 1e-9, np.abs(h - exact).max()           # vs 0.5 mm of gap at the ends
    A, B = curvatures(t.r_wheel, t.z_rail, 0.0, 0.0)
    assert abs(A - math.cos(DELTA) / (2 * r_b)) < 1e-12
    assert abs(B - 0.5 * (1 / RR + 1 / RW)) < 1e-3 * B


def test_points_two_errors():
    from pipeline.config.case_profiles import case_contact

    c, _, _, geo = case_contact("default")
    c = {**c, "contact": {**c["contact"], "points": 2}}
    with pytest.raises(ConfigError) as e:
        second_zone("default", c, geo)
    assert "no second contact zone" in str(e.value) and "\n" not in str(e.value)
    c2, _, _, geo2 = case_contact("flange")
    z = second_zone("flange", c2, geo2)
    assert 1e-6 < z.separation < 0.25e-3 and math.degrees(z.angle) > 60
    with pytest.raises(ConfigError) as e:
        second_zone("flange", {**c2, "contact": {**c2["contact"], "model": "kalker"}}, geo2)
    assert "contact.model" in str(e.value) and "\n" not in str(e.value)
    with pytest.raises(ConfigError) as e:
        second_zone("flange", {**c2, "contact": {**c2["contact"], "angle": "none"}}, geo2)
    assert "contact.angle" in str(e.value) and "\n" not in str(e.value)
