"""The over-radial note ("negative angle of attack") only where the wheelset's angle of attack is
negative (issue 33: every curve run warned it for the outer leading wheel, whose angle of attack is
+15.5 mrad).  gamma_y is in each wheel's contact frame, direction 2 toward that wheel's field side
(solvers/curving/summary.py), so an under-radial wheelset has gamma_y < 0 at its inner wheel and
gamma_y > 0 at its outer wheel: the sign of gamma_y alone does not say over-radial.  The reference is
the steady curving's own angle of attack of each wheel."""
from __future__ import annotations

import pytest

from pipeline.config.check import over_radial_note


@pytest.mark.parametrize("curve", ["r150", "r75"])
def test_note_where_the_curving_angle_of_attack_is_negative(curve):
    from pipeline.curve.curving import solve_curve
    from pipeline.curve.cases import wheel_case

    sol = solve_curve(curve)
    signs = set()
    for p in sol.wheels:
        c = wheel_case(sol.curve, p).case             # the case the curve stage hands to the stages for the wheel
        note = over_radial_note(c) or ""
        assert ("over-radial" in note) == (p.angle_of_attack < 0), (p.wheel, p.angle_of_attack, p.gamma_y, note)
        signs.add((p.wheel[-1], p.gamma_y > 0))
    # both rails and both signs of the creepage are met (r150's trailing axle is over-radial)
    assert {("o", True), ("i", False)} <= signs


def test_outer_leading_wheel_of_r150_has_no_over_radial_note():
    """The issue's example: the outer leading wheel, angle of attack > 0, gamma_y > 0."""
    c = {"name": "r150/a1o", "kinematics": {"gamma_y": 0.0113906}}
    assert over_radial_note(c) is None
    assert "over-radial" in over_radial_note({"name": "r150/a2o", "kinematics": {"gamma_y": -0.0004}})
    # an ordinary case file is the reference's inner wheel: gamma_y > 0 is over-radial, as before
    assert "over-radial" in over_radial_note({"name": "pos", "kinematics": {"gamma_y": 0.014}})
    assert over_radial_note({"name": "default", "kinematics": {"gamma_y": -0.014}}) is None
