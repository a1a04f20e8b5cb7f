"""A static two-patch normal problem (two contact zones on one grid, interacting through the
half-space) against CONTACT: the project's NORM at the same total load gives each patch's
normal force within 1 % (it agrees to about 1e-6).  Inputs and CONTACT's numbers:
pipeline/validation/references/contact_peer.py."""
import numpy as np
import pytest

from solvers.contact.norm import norm
from pipeline.validation.references.contact_peer import CONTACT_TWO_PATCH, E30, NU30, PATCH_GRID, patch_forces, two_lobe_gap


@pytest.mark.parametrize("key", list(CONTACT_TWO_PATCH))
def test_patch_forces_match_contact(key):
    left, right, n, xi = patch_forces(*key)
    c_left, c_right, c_n, c_xi = CONTACT_TWO_PATCH[key]
    assert left == pytest.approx(c_left, rel=0.01) and right == pytest.approx(c_right, rel=0.01)
    assert left == pytest.approx(c_left, rel=1e-5) and right == pytest.approx(c_right, rel=1e-5)   # as measured
    assert n == c_n                                        # the same contact elements
    assert 1e3 * xi == pytest.approx(c_xi, abs=1e-5)       # approach, CONTACT prints 4 digits [mm]


def test_the_patches_interact():
    # each lobe alone at the two-patch approach carries more than in the pair (the other patch's
    # pressure lifts its surface): the coupling the comparison above resolves exceeds its 1 %
    geometry, F3 = "two tread lobes", 65e3
    left, right, _, xi = patch_forces(geometry, F3)
    X, Y, h = two_lobe_gap(geometry)
    d = PATCH_GRID[2]
    alone_left = norm(np.where(Y < 0, h, 1.0), xi, d, d, E30, NU30).F3
    alone_right = norm(np.where(Y > 0, h, 1.0), xi, d, d, E30, NU30).F3
    assert alone_left > 1.01 * left and alone_right > 1.01 * right
