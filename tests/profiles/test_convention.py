"""Thesis [4.1]'s sign convention (solvers.constants): a rigid wheelset moved by dy_WR moves every
wheel point by dy_WR over the rail, so y^R - dy_WR - y^W must be one constant c for the three
points.  The printed table fails that by tens of mm; with its y^W negated (field-positive, SPEC 2)
it holds to the table's 1 mm rounding."""
import numpy as np
import pytest

from solvers.constants import (THESIS_CONTACT_POINTS_FIELD, THESIS_CONTACT_POSITIONS, thesis_contact_point,
                               thesis_rolling_circle_offset)


def spread(table) -> float:
    c = [yr - dy - yw for dy, (yw, yr) in table.items()]
    return float(np.ptp(c))


def test_printed_y_w_is_positive_toward_the_flange():
    assert spread(THESIS_CONTACT_POSITIONS) > 0.05                       # printed: -16, -6, +59 mm
    assert spread(THESIS_CONTACT_POINTS_FIELD) < 1.01e-3                 # y^W negated: -6, -6, -5 mm
    # the other consistent reading, not used: the rail and the offset mirrored (Y = -y^R, the wheelset
    # moving the other way); it puts the default case on the gauge side of the head at the flange root
    mirrored = {-dy: (yw, -yr) for dy, (yw, yr) in THESIS_CONTACT_POSITIONS.items()}
    assert spread(mirrored) < 1.01e-3


def test_field_positive_points_and_c():
    assert thesis_contact_point(-0.015) == (0.032, 0.012)
    assert thesis_contact_point(-0.010) == (0.004, -0.012)
    assert thesis_contact_point(-0.005) == (-0.005, -0.016)
    assert thesis_rolling_circle_offset() == pytest.approx(-17 / 3 * 1e-3, abs=1e-12)
    c = thesis_rolling_circle_offset()
    for dy, (yw, yr) in THESIS_CONTACT_POINTS_FIELD.items():
        assert abs(yw + c + dy - yr) <= 2 / 3 * 1e-3 + 1e-12            # Y = y^W + c + dy_WR
