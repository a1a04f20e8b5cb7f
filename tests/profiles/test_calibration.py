"""The calibrated worn pair (geometry/profiles/c20_worn.csv, bv50_worn.csv):
thesis [4.1] as a check of the pipeline's contact points, the checks the
calibration was not fitted to, and the files' consistency with their headers."""
import re

import numpy as np
import pytest

from geometry.calibration import THESIS_POSITIONS, rolling_circle_offset
from solvers.constants import THESIS_CONTACT_POSITIONS

CASES = {"dy05": -0.005, "dy10": -0.010, "default": -0.015}


def sweep(case="default", offsets=()):
    """y^W of the case's rigid contact at other offsets (None for flange contact)."""
    from geometry.contact_point import contact_sweep
    from pipeline.config.case_profiles import case_contact

    _, _, _, geo = case_contact(case)
    c = geo.config["rolling_circle_y"]
    return [None if r is None else r.y_wheel for r in contact_sweep(geo.wheel, geo.rail_track, c, offsets)]


def test_c_is_the_thesis_table_value():
    """c from the printed table with its y^W negated: y^R - dy - y^W = -6, -6, -5 mm."""
    from pipeline.config.input_schemas import CASE

    assert rolling_circle_offset() == pytest.approx(-17 / 3 * 1e-3, abs=1e-12)
    assert CASE["contact"]["rolling_circle_y"].default == pytest.approx(rolling_circle_offset(), abs=1e-7)


@pytest.mark.parametrize("case", CASES)
def test_contact_points_of_the_cases_reproduce_thesis_table(case):
    """The contact stage's point (rigid contact of the case's profiles)
    against thesis [4.1] in the project's convention: y^W within 1 mm of the
    printed value negated (the calibration's target); y^R, not fitted,
    within 1 mm of the printed value."""
    from pipeline.config.case_profiles import case_contact

    c, _, _, geo = case_contact(case)
    dy = c["contact"]["dy_wr"]
    assert dy == CASES[case]
    yw, yr = THESIS_POSITIONS[dy]
    assert geo.contact.y_wheel == pytest.approx(yw, abs=1e-3)
    assert yw == -THESIS_CONTACT_POSITIONS[dy][0] and yr == THESIS_CONTACT_POSITIONS[dy][1]
    assert geo.contact.y_rail == pytest.approx(yr, abs=1e-3)
    assert abs(np.degrees(geo.contact.angle)) < 10


def test_intermediate_offsets_and_the_jump():
    """Not fitted: as the wheelset moves from -5 to -15 mm (toward the gauge
    side) the contact moves monotonically toward the field side of the
    tread, -7.5 and -12.5 mm lie between their neighbours, and the contact
    jumps once (to the field-side flank of the hollow), between -10 and
    -12.5 mm; the flange only touches when the wheelset moves the other way
    (toward the field side), from about +18 mm, not from -30 to +17.5 mm
    (the onset is a prediction of the calibrated pair: +17.75..+18 mm for the
    pair fitted to the refitted C20 section, beyond +20 mm for the earlier one)."""
    dys = np.round(np.arange(-0.005, -0.01501, -0.00025), 6)
    ys = np.array(sweep(offsets=dys))
    assert np.all(np.diff(ys) >= -1e-6)
    y = dict(zip(dys, ys))
    assert y[-0.005] < y[-0.0075] < y[-0.01] < y[-0.0125] < y[-0.015]
    jumps = np.flatnonzero(np.diff(ys) > 2e-3)
    assert len(jumps) == 1 and -0.0125 <= dys[jumps[0] + 1] and dys[jumps[0]] <= -0.010
    assert all(v is not None for v in sweep(offsets=np.arange(-0.03, 0.0176, 0.0025)))
    assert sweep(offsets=[0.0185])[0] is None


def test_worn_files_are_the_new_profiles_worn_as_their_headers_say():
    from geometry.profiles import build_profile
    from geometry.standard_profiles import rail_head_curve, wheel_tread_points
    from geometry.wear import RailWear, WheelWear, worn_rail, worn_wheel
    from pipeline.config.case_profiles import read_profile
    from pipeline.stages.rail import load_rail_params
    from pipeline.stages.wheel import load_wheel

    w, _ = read_profile("c20_worn")
    r, _ = read_profile("bv50_worn")
    assert w.meta["calibrated_to"] == r.meta["calibrated_to"] and "NOT to patch sizes" in w.meta["calibrated_to"]
    par = {k: 1e-3 * float(v) for k, v in re.findall(r"(\w+) = ([-\d.]+) mm", w.meta["wear_parameters"])}
    new = build_profile(*wheel_tread_points(load_wheel("c20")[0]), "wheel", "c20_new", "t", 0.0)
    yw, zw = worn_wheel(new.y, new.z, WheelWear(*(par[k] for k in ("hollow_depth", "hollow_centre",
                                                                   "hollow_half_width"))))
    inner = (yw > w.y[0] + 1e-3) & (yw < w.y[-1] - 1e-3)
    assert np.abs(w(yw[inner]) - zw[inner]).max() < 5e-6  # header parameters rounded to 1 um
    yr, zr = worn_rail(rail_head_curve(load_rail_params("bv50")[0]),
                       RailWear(*(par[k] for k in ("top_depth", "top_centre", "top_half_width", "gauge_depth",
                                                   "gauge_start"))))
    inner = (yr > r.y[0] + 1e-3) & (yr < r.y[-1] - 1e-3)
    assert np.abs(r(yr[inner]) - zr[inner]).max() < 5e-6
