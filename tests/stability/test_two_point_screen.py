"""The two-point stability screen (issue 26, solvers/stability/two_point.py):

* with the second point unloaded, its wheel roots are the one-point screen's
  (``solvers.stability.screen.wheel_roots``, exact polish) to 1e-7 relative;
* two identical coincident patches are one patch of twice the normal stiffness (as in the time
  loop's test): the roots agree with the one-point screen of the doubled contact;
  (every two-point root is a root of the one-point characteristic).
"""
from __future__ import annotations

import pytest

from pipeline.validation.references.two_point import (compare_roots, screen_identical_patches,
                                                      screen_unloaded_second_point, structures as two_point_structures)


@pytest.fixture(scope="module")
def structures():
    return two_point_structures()


def compare(one_model, one, two):
    common, err, stray = compare_roots(one_model, one, two)
    assert not stray, stray                  # every other root is a root of the one-point characteristic
    return common, err


def test_unloaded_second_point_gives_the_one_point_roots(structures):
    lm1, one, two = screen_unloaded_second_point(*structures)
    common, err = compare(lm1, one, two)
    assert len(common) >= 0.9 * len(one) and err < 1e-7, (len(common), len(one), err)


def test_two_identical_patches_screen_as_one_double_patch(structures):
    lm1, one, two = screen_identical_patches(*structures)
    common, err = compare(lm1, one, two)
    assert len(common) >= 0.9 * len(one) and err < 1e-9, (len(common), len(one), err)
