"""The two-point time loop (issue 26, solvers/timeloop/two_point.py):

* with the second point carrying no load (its zone never reached) the first point's records are
  the one-point loop's (to 1e-12; in fact bit for bit);
* two identical patches at the same place (same shapes, every rail block the same kernel, same
  tables, no separation; the runs: pipeline/validation/references/two_point.py) are one patch of twice the normal stiffness (NORM table F3 doubled, the
  tangential compliances halved): the summed forces equal the one-point loop's with that contact;
* the static state of two patches under one load against a direct solution.
"""
from __future__ import annotations

import numpy as np
import pytest

from solvers.timeloop.inputs import static_approach
from solvers.timeloop.two_point_driver import static_state
from pipeline.validation.references.interaction import PRELOAD, hertz_contact
from pipeline.validation.references.two_point import (loop_identical_patches, loop_unloaded_second_point, rel,
                                                      structures as two_point_structures)


@pytest.fixture(scope="module")
def structures():
    return two_point_structures()


def test_unloaded_second_point_reduces_to_the_one_point_loop(structures):
    one, two = loop_unloaded_second_point(*structures)     # another patch, never reached
    a, b = two.a, two.b
    assert two.N_static[1] == 0.0 and np.all(b.F == 0.0) and b.lost_steps == b.n_steps
    assert a.n_steps == one.n_steps and a.stop_reason == one.stop_reason
    errs = {k: rel(getattr(a, k), getattr(one, k)) for k in ("F", "slip", "xi", "F_final", "slip_final", "xi_final")}
    assert max(errs.values()) <= 1e-12, errs
    np.testing.assert_array_equal(a.state, one.state)
    np.testing.assert_array_equal(a.F_ref, one.F_ref)
    assert a.xi3_static == one.xi3_static
    assert a.newton == one.newton
    np.testing.assert_allclose(a.windows, one.windows, rtol=1e-12, atol=0)
    m1, m2 = one.measures(), two.measures()
    assert abs(m1["L_F2"] - m2["L_F2"]) <= 1e-9 and abs(m1["L_F2"] - m2["L_F2_a"]) <= 1e-9


def test_two_identical_patches_are_one_patch_of_double_stiffness(structures):
    one, two = loop_identical_patches(*structures)
    np.testing.assert_allclose(two.N_static, [0.5 * PRELOAD] * 2, rtol=1e-12)
    F = two.a.F + two.b.F
    e = rel(F, one.F)
    assert e < 1e-8, e
    assert rel(two.a.F, two.b.F) < 1e-12                          # the patches share the load
    m1, m2 = one.measures(), two.measures()
    assert abs(m1["L_F2"] - m2["L_F2"]) < 1e-6, (m1["L_F2"], m2["L_F2"])


def test_static_state_of_two_patches():
    ca, cb = hertz_contact(0.35), hertz_contact(0.35, F_L=30e3)
    sep = 20e-6
    ca_ = np.cos(np.radians(3.0))
    cb_ = np.cos(np.radians(40.0))
    xa, xb, Na, Nb = static_state(ca, cb, PRELOAD, sep, ca_, cb_)
    # direct: Hertz tables F = K a^1.5 (hertz_contact's K); Q = Na cos_a + Nb cos_b
    Ka = PRELOAD / 9.7e-5 ** 1.5
    Kb = 30e3 / 9.7e-5 ** 1.5
    from scipy.optimize import brentq

    d = brentq(lambda d: Ka * (d * ca_) ** 1.5 * ca_ + Kb * max((d - sep) * cb_, 0) ** 1.5 * cb_ - PRELOAD,
               0.0, 1e-3, xtol=1e-18)
    assert abs(xa - d * ca_) < 1e-12 * d and abs(xb - (d - sep) * cb_) < 1e-12 * d
    assert abs(Na * ca_ + Nb * cb_ - PRELOAD) < 1e-6 * PRELOAD and Nb > 0.05 * PRELOAD
    # beyond reach: the one-point state exactly
    xa, xb, Na, Nb = static_state(ca, cb, PRELOAD, 1e-3)
    assert xa == static_approach(ca, PRELOAD) and Nb == 0.0 and Na == PRELOAD
