"""The SPEC's numbers that more than one stage needs: one home for each.

Every module that uses one of these imports it from here (``tests/test_layering``
greps for copies).  Units SI unless the name says otherwise.
"""
from __future__ import annotations

# SPEC 3.2 / thesis 4.2: the band of the structural models (the rail's WFE model
# stops at 6.5 kHz; the wheel's Green's functions are band-limited to the same top).
F_MAX_HZ = 6500.0
# SPEC 3.2: the lowest frequency of the rail receptance table (thesis Fig. 4.6).
RAIL_F_MIN_HZ = 25.0
# SPEC 6 ([6.3]-[6.4]): a case squeals when the lateral force level L_F2 >= this (dB re 1 N).
SQUEAL_LEVEL_DB = 10.0
# SPEC 2 (thesis [4.1]): wheelset lateral offset dy_WR -> (y^W, y^R) AS PRINTED in the thesis (m).
# Kept verbatim for reference; the pipeline uses THESIS_CONTACT_POINTS_FIELD below.
THESIS_CONTACT_POSITIONS = {-0.005: (0.005, -0.016), -0.010: (-0.004, -0.012),
                            -0.015: (-0.032, 0.012)}
# The printed points are kinematically consistent -- a rigid wheelset moved by dy_WR moves the wheel's
# points by dy_WR over the rail, so y^R = dy_WR + y^W + c with ONE constant c for all three offsets --
# only if the printed y^W is positive toward the FLANGE while y^R is positive toward the field side
# (printed y^R - dy - y^W = -16, -6, +59 mm: no common c; with y^W negated: -6, -6, -5 mm).  In the
# project's convention (SPEC 2: y^W and y^R both + toward the field side, the flange at negative y^W)
# the wheel points are therefore y^W = -printed: -5, +4, +32 mm, the rail points as printed, and
# c = mean(y^R - dy - y^W) = -17/3 mm (residuals 1/3, 1/3, 2/3 mm; docs/validation/31_contact_positions.md).
# This is the table the calibration fits and the checks compare with (geometry.calibration).
THESIS_CONTACT_POINTS_FIELD = {dy: (-yw, yr) for dy, (yw, yr) in THESIS_CONTACT_POSITIONS.items()}


def thesis_contact_point(dy_wr: float) -> tuple[float, float]:
    """(y^W, y^R) in m, both + toward the field side (SPEC 2), of thesis [4.1]
    for the wheelset offset dy_WR (m; one of -0.005, -0.010, -0.015): the
    printed y^W negated (see THESIS_CONTACT_POINTS_FIELD); KeyError otherwise."""
    return THESIS_CONTACT_POINTS_FIELD[round(float(dy_wr), 3)]


def thesis_rolling_circle_offset() -> float:
    """c (m): the wheel's rolling circle (y^W = 0) over the rail centre line
    (+ field side) for the centred wheelset, from the table itself:
    mean of y^R - dy_WR - y^W over THESIS_CONTACT_POINTS_FIELD (= -17/3 mm)."""
    pts = THESIS_CONTACT_POINTS_FIELD
    return sum(yr - dy - yw for dy, (yw, yr) in pts.items()) / len(pts)
# Below this frequency a self-excited oscillation is the wheelset on its suspension or the track (e.g. the
# ~70-90 Hz vertical suspension mode at high friction), not squeal (a wheel's (n,0,a) modes lie above).
SQUEAL_F_MIN_HZ = 200.0
