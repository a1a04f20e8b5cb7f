"""The two-point stability screen (issue 26, solvers/stability/two_point.py):

* with the second point unloaded, its wheel roots are the one-point screen's
  (``solvers.stability.screen.wheel_roots``, exact polish) to 1e-7 relative;
* two identical coincident patches are one patch of twice the normal stiffness (as in the time
  loop's test): the roots agree with the one-point screen of the doubled contact;
  (every two-point root is a root of the one-point characteristic).
"""
from __future__ import annotations

import numpy as np
import pytest

from solvers.wheel.modal_filter import modal_filter
from solvers.stability.screen import characteristic, linearise, wheel_roots
from solvers.stability.two_point import linearise_two, wheel_roots as wheel_roots_two
from solvers.timeloop.two_point_driver import SecondPoint
from pipeline.validation.references.interaction import DT, GAMMA_Y, PRELOAD, V, beam_kernel, c20_modes, hertz_contact
from tests.interaction.test_two_point import doubled


@pytest.fixture(scope="module")
def structures():
    wheel, _ = c20_modes()
    g = beam_kernel(DT, V, n_lags=1024, n_t=4096)
    return wheel, g


def by_mode(roots):
    return {r.mode: complex(r.sigma, 2 * np.pi * r.f_hz) for r in roots}


def compare(one_model, one, two):
    """Roots continuing the same mode agree (max relative difference over them, and their count);
    every other two-point root is a root of the one-point characteristic (|D(s)| against |D| 0.1 %
    away; the continuation of two close modes may pick either of two roots) or the open-loop pole of
    a mode the contact does not move."""
    common = [r for r in sorted(set(one) & set(two)) if abs(two[r] - one[r]) <= 1e-6 * abs(one[r])]
    err = max(abs(two[r] - one[r]) / abs(one[r]) for r in common)
    poles = np.log(modal_filter(one_model.dt, one_model.f_r, one_model.modal_mass, one_model.zeta, one_model.phi).z)
    poles /= one_model.dt
    for r, s in two.items():
        if abs(s - poles[r]) <= 1e-9 * abs(s):
            continue                                  # a mode the contact does not move (shape ~0 there)
        d0 = abs(characteristic(one_model, s))
        d1 = abs(characteristic(one_model, s + 1e-3 * abs(s)))
        assert d0 < 1e-6 * d1, (r, s, d0, d1)
    return common, err


def test_unloaded_second_point_gives_the_one_point_roots(structures):
    wheel, g = structures
    ca, cb = hertz_contact(0.35), hertz_contact(0.3, F_L=40e3)
    lm1 = linearise(wheel, g, ca, dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)
    one = by_mode(wheel_roots(lm1))
    lm2 = linearise_two(wheel, (g, 0.6 * g, 0.6 * g, 1.2 * g), ca,
                        SecondPoint(cb, np.ascontiguousarray(wheel.phi[:, ::-1]), separation=1e-3),
                        dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)
    two = by_mode(wheel_roots_two(lm2))
    common, err = compare(lm1, one, two)
    assert len(common) >= 0.9 * len(one) and err < 1e-7, (len(common), len(one), err)
    test_unloaded_second_point_gives_the_one_point_roots.numbers = dict(roots=len(common), max_rel=err)


def test_two_identical_patches_screen_as_one_double_patch(structures):
    wheel, g = structures
    c = hertz_contact(0.35)
    lm1 = linearise(wheel, g, doubled(c), dt=DT, v=V, gamma_y=GAMMA_Y, preload=PRELOAD)
    one = by_mode(wheel_roots(lm1))
    lm2 = linearise_two(wheel, (g, g, g, g), c, SecondPoint(c, wheel.phi, separation=0.0), dt=DT, v=V,
                        gamma_y=GAMMA_Y, preload=PRELOAD)
    two = by_mode(wheel_roots_two(lm2))
    common, err = compare(lm1, one, two)
    assert len(common) >= 0.9 * len(one) and err < 1e-9, (len(common), len(one), err)
    test_two_identical_patches_screen_as_one_double_patch.numbers = dict(roots=len(common), max_rel=err)
