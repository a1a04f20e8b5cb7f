"""The contact angle and the two contact points on the built cases (issue 26; docs/validation/34_two_points.md,
its writer's ``default_case``, ``angle_case``, ``flange_case``; the cases built through Make):

* the default case through the two-point loop with a never-reached second point is the one-point loop (to
  1e-12) and the recorded reference results (tests/reference/reference_results.json, compared as
  tests/test_reference_results.py does: bit for bit on the recording's machine, else to 1e-5 relative);
* in its contact plane the normal force carries the preload (N cos delta = Q) and the greens stage projects
  by the contact's angle; loop and screen agree on what grows, at every position;
* the flange case: Q = N_a cos delta_a + N_b cos delta_b with the flange loaded, the rail blocks reciprocal to
  1e-9, loop and screen agree."""
import math

import numpy as np
import pytest

from tests.test_reference_results import REF, same

pytestmark = pytest.mark.validation


@pytest.fixture(scope="module")
def writer():
    from pipeline.validation.writers import two_points

    two_points.build()
    return two_points


def test_default_case_through_the_two_point_loop(writer):
    d = writer.default_case()
    one, two = d["one"], d["two"]
    assert d["dmax"] <= 1e-12 and one.stop_reason == two.a.stop_reason and one.n_steps == two.a.n_steps
    m1 = d["m1"]
    same(m1["L_F2"], REF["default"]["L_F2"], "default L_F2")                 # the recorded reference
    same(m1["f_dominant"], REF["default"]["f_dominant"], "default f_dominant")


def test_contact_plane_of_the_default_case(writer):
    a = writer.angle_case()
    delta = float(a["contact"]["contact_angle"])
    assert abs(float(a["contact"]["preload_normal"]) * math.cos(delta) - a["preload"]) < 1e-6
    assert float(a["greens"]["contact_angle_wheel"]) == delta
    st, sim = a["stability"], a["simulate"]
    top = int(np.argmax(st["sigma"]))
    if str(sim["stop_reason"]) == "limit cycle":                      # screen and loop: the same root grows
        assert st["sigma"][top] > 0 and abs(float(sim["f_dominant"]) / float(st["f_hz"][top]) - 1) < 0.05


@pytest.mark.parametrize("case", ["dy05", "dy05_angle", "dy10", "dy10_angle", "default", "default_angle"])
def test_screen_and_loop_agree_at_every_position(writer, case):
    st, sim = writer.load(case, "stability"), writer.load(case, "simulate")
    assert (st["sigma"].max() > 0) == (str(sim["stop_reason"]) == "limit cycle")


def test_flange_case(writer):
    fl = writer.flange_case()
    cf, sf, stf = fl["cf"], fl["sf"], fl["stf"]
    da, db = float(cf["contact_angle"]), float(cf["b_contact_angle"])
    Na, Nb = (float(x) for x in sf["N_static"])
    assert abs(Na * math.cos(da) + Nb * math.cos(db) - fl["Q"]) < 1e-6 * fl["Q"] and Nb > 0
    assert fl["recip"] < 1e-9
    if str(sf["stop_reason"]) == "decayed":
        assert stf["sigma"].max() < 0                                # screen and loop agree: stable
