"""The shipped standard profiles (geometry/profiles/s1002.csv, 60e1_new.csv)
against an independent source of the same standards: the S1002 wheel and
UIC60 (60E1) rail files CONTACT ships (github.com/eve70a/CONTACT, Apache-2.0;
quoted in pipeline/validation/contact_reference.py, with the commit).
docs/validation/15_profiles.md reports the same numbers."""
import numpy as np
import pytest

from pipeline.validation import contact_reference as ref, profiles_doc as doc


@pytest.fixture(scope="module")
def pairs():
    return doc.shipped_profiles(), doc.contact_profiles()


def test_quoted_contact_points_lie_on_its_rail_arcs():
    """The quoted rail points, the cant turned back (1:40) and the frame moved
    to the centre line and crown top, lie on the quoted R300/R80/R13 arcs and
    1:20 side within 1 um: the transcription of CONTACT's file is consistent
    (a wrong cant, centre, arc or line moves points by 10 um or more)."""
    from scipy.spatial import cKDTree

    y, z = ref.uic60_contact_curve(38.0, ds_mm=0.001)
    Y, Z = ref.uic60_contact_points()
    d, _ = cKDTree(np.column_stack([y, z])).query(np.column_stack([Y, Z]))
    assert len(Y) == 59 and d.max() < 1.0e-6
    assert np.interp(0.0, y, z) == pytest.approx(0.0, abs=1e-12)
    # the head 72.000 mm wide where R13 meets the 1:20 side (EN 13674-1 60E1 head width)
    c3, r3 = ref.UIC60_ARCS["R13"]
    assert 2 * (c3[0] + r3 / np.hypot(1, ref.UIC60_SIDE[1])) == pytest.approx(72.0, abs=2e-4)


def test_heights_agree_over_the_running_band(pairs):
    """S1002 at CONTACT's points over the whole table (flange to field side,
    y = -62 ... +60 mm) and 60E1 every 0.1 mm over |y| <= 35 mm (crown,
    shoulder, gauge corner) and at CONTACT's points there: within 1 um.  Before
    the head was corrected (side narrowing downward, crown to 10 mm) the 60E1
    table was 0.11 mm off."""
    h = doc.heights(*pairs)
    assert h["wheel_points"] == 49 and h["wheel_max"] < 1e-3
    assert h["rail_points"] >= 25 and h["rail_points_max"] < 1e-3
    assert h["rail_grid_max"] < 1e-3


def test_gauge_point_lies_on_the_shipped_60e1_table(pairs):
    """The shipped 60E1 table reaches at least 20 mm below the crown top, so the
    gauge point 14 mm below it is on the table, in the rail frame and turned
    1:40 (``pipeline.curve.curving.gauge_face`` interpolates it, no fallback to the
    table's end); its gauge face is CONTACT's within 0.01 mm from 12 to 20 mm."""
    from geometry.contact_point import TrackRail

    (_, rail), _ = pairs
    assert doc.face_y(rail, 20.0) < -0.036 and 1e3 * (rail.z.max() - rail.z[0]) >= 20.0
    track = TrackRail(rail, doc.INCLINATION)
    z = track(track.y)
    assert np.nanmax(z) - z[0] > 0.014 + 0.005  # the gauge-side end lies > 5 mm below the gauge point
    h = doc.heights(*pairs)
    for depth, (shipped, contact) in h["face"].items():
        assert shipped == pytest.approx(contact, abs=0.01), depth


def test_centred_contact_agrees_with_contacts_profiles(pairs):
    """S1002 on 60E1 inclined 1:40, gauge 1435 mm (14 mm below the crown),
    flange backs 1360 mm apart, no lateral shift: the rigid contact of the
    shipped pair lies within 0.5 mm of that of CONTACT's pair, on the wheel
    and on the rail, on the tread near the tape circle (y^W ~ +3 mm); the
    gauge points agree to 0.01 mm.  (With the old table the contact jumped to
    the flange root, y^W = -7.6 mm, 10.9 mm away.)"""
    shipped, contact = pairs
    cs, cc = doc.centred_contact(*shipped), doc.centred_contact(*contact)
    assert cs["gauge_Y"] == pytest.approx(cc["gauge_Y"], abs=0.01)
    assert cs["y_wheel"] == pytest.approx(cc["y_wheel"], abs=0.5)
    assert cs["y_rail"] == pytest.approx(cc["y_rail"], abs=0.5)
    assert 0.0 < cc["y_wheel"] < 6.0 and abs(cc["angle"]) < 3.0


@pytest.mark.parametrize("inclination", [1 / 40, 1 / 30, 1 / 20, 1 / 15])
def test_turned_60e1_gauge_face_up_to_and_past_its_side_taper(pairs, inclination):
    """Turned by 1:20 the 1:20 head side is vertical, steeper it overhangs: the
    track-frame rail keeps its single-valued part (no spline through a vertical
    or overhanging side, which swung 1 m below the head), stays within the turned
    table's heights, and puts the gauge face where CONTACT's head has it (0.01 mm)."""
    from geometry.contact_point import TrackRail
    from pipeline.curve.curving import gauge_face

    (_, rail), (_, crail) = pairs
    track = TrackRail(rail, inclination)
    a = np.arctan(inclination)
    zt = rail.y * np.sin(a) + rail.z * np.cos(a)
    z = track(np.linspace(track.y[0], track.y[-1], 40001))
    assert np.all(np.diff(track.y) > 0)
    assert zt.min() - 1e-7 <= np.nanmin(z) and np.nanmax(z) <= zt.max() + 1e-7
    assert gauge_face(track) == pytest.approx(gauge_face(TrackRail(crail, inclination)), abs=1e-5)
