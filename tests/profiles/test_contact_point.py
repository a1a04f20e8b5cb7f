"""Rigid contact point of two profiles against closed forms: a cone on an
inclined circular crown, flange contact, a second contact zone."""
import numpy as np
import pytest

from geometry.contact_point import FlangeContact, TrackRail, rigid_contact
from geometry.profiles import build_profile

R, K = 0.3, 1 / 40  # crown radius (m), cone slope


def crown(R=R, half=0.03):
    y = np.linspace(-half, half, 601)
    return build_profile(y, np.sqrt(R**2 - y**2) - R, "rail", "crown", "circle", 0.0)


def cone(k=K, lo=-0.05, hi=0.05):
    y = np.linspace(lo, hi, 201)
    return build_profile(y, -k * y, "wheel", "cone", "cone", 0.0)


@pytest.mark.parametrize("inclination", [0.0, 1 / 30, 1 / 20])
@pytest.mark.parametrize("shift", [0.0, 0.0057])
def test_cone_on_inclined_crown(inclination, shift):
    """The contact is where the crown's slope in the track frame equals the
    cone's: track Y = R sin(a) - R k / sqrt(1 + k^2) (the turned circle's
    centre is at R sin a), i.e. at the rail point y^R = -R sin(atan k - a);
    the contact angle is atan k."""
    a = np.arctan(inclination)
    rc = rigid_contact(cone(), TrackRail(crown(), inclination), shift)
    Y = R * np.sin(a) - R * K / np.sqrt(1 + K**2)
    assert rc.y_track == pytest.approx(Y, abs=2e-7)
    assert rc.y_wheel == pytest.approx(Y - shift, abs=2e-7)
    assert rc.y_rail == pytest.approx(-R * np.sin(np.arctan(K) - a), abs=2e-7)
    assert rc.angle == pytest.approx(np.arctan(K), abs=1e-6)
    assert rc.second is None


def test_flange_contact_is_reported_not_crashed_into():
    """S1002 on a 60E1 head inclined 1:40 on standard track (gauge 1435 mm at
    14 mm below the crown, back-to-back 1360 mm, tape circle 70 mm from the
    back: the rolling circle lies 717.5 + 36 - 750 = 3.5 mm inboard of the rail
    centre): tread contact near the tape circle; moved 9.5 mm toward the
    flange, flange contact."""
    from geometry.standard_profiles import rail_head_points, s1002_points
    from pipeline.stages.rail import load_rail_params

    wheel = build_profile(*s1002_points(), "wheel", "s1002", "t", 0.0)
    rail = build_profile(*rail_head_points(load_rail_params("60e1")[0]), "rail", "60e1", "t", 0.0)
    track = TrackRail(rail, 1 / 40)
    ok = rigid_contact(wheel, track, -0.0035)
    assert abs(ok.y_wheel) < 0.01 and abs(np.degrees(ok.angle)) < 3
    with pytest.raises(FlangeContact, match=r"flange contact: the rigid contact is at y\^W = -\d\d\.\d mm"):
        rigid_contact(wheel, track, 0.006)


def test_second_zone():
    """A wheel with two raised bands (0.5 and 0.3 mm) 20 mm apart on a nearly
    flat rail (R = 2 m): the higher band carries the contact, the other is the
    second zone, 0.2 mm (less the crown drop difference, zero here by
    symmetry) further from the rail."""
    y = np.linspace(-0.05, 0.05, 2001)
    band = lambda c, d: d * np.exp(-(((y - c) / 0.004) ** 2))  # noqa: E731
    wheel = build_profile(y, band(-0.01, 0.5e-3) + band(0.01, 0.3e-3), "wheel", "two", "t", 0.0)
    rc = rigid_contact(wheel, TrackRail(crown(R=2.0, half=0.035), 0.0), 0.0)
    assert rc.y_wheel == pytest.approx(-0.01, abs=2e-4)
    y2, extra = rc.second
    assert y2 == pytest.approx(0.01, abs=2e-4) and extra == pytest.approx(0.2e-3, abs=2e-6)
