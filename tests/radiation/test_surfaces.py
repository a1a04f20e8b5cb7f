"""Radiating surfaces [4.51]-[4.53] of a simple annular wheel (flat disc web,
rectangular tyre) against hand-computed areas, the web-thickness rule, and the
assignment of boundary nodes to the surfaces."""
import numpy as np
import pytest

from solvers.radiation.surfaces import annulus_radii, radiation_surfaces, surface_nodes, web_thickness_profile
from pipeline.validation.references.node_average import contact_node
from pipeline.validation.references.radiation import flat_disc_segments, RADII

PI = 3.141592653589793


def test_annulus_radii_divide_the_web_evenly():
    # web 0.10..0.33 in four rings of 0.0575, then the tyre 0.33..0.40
    np.testing.assert_allclose(annulus_radii(0.10, 0.33, 0.40), [0.10, 0.1575, 0.215, 0.2725, 0.33, 0.40], rtol=1e-12)
    with pytest.raises(ValueError):
        annulus_radii(0.35, 0.33, 0.40)


def test_flat_disc_surfaces_by_hand():
    s = radiation_surfaces(RADII, flat_disc_segments())
    assert s.w_web == pytest.approx(0.02, rel=1e-12)  # measured on the outline
    # both faces: S_aq = 2 pi (r_{q+1}^2 - r_q^2)
    hand = [2 * PI * (0.1575**2 - 0.10**2),    # 2 pi * 0.01480625 = 0.09303041
            2 * PI * (0.215**2 - 0.1575**2),   # 2 pi * 0.02141875 = 0.13457798
            2 * PI * (0.2725**2 - 0.215**2),   # 2 pi * 0.02803125 = 0.17612554
            2 * PI * (0.33**2 - 0.2725**2),    # 2 pi * 0.03464375 = 0.21767310
            2 * PI * (0.40**2 - 0.33**2)]      # 2 pi * 0.0511     = 0.32107077
    np.testing.assert_allclose(s.S_a, hand, rtol=1e-12)
    np.testing.assert_allclose(s.S_a, [0.09303041, 0.13457798, 0.17612554, 0.21767310, 0.32107077], rtol=1e-7)
    # total axial area = both faces of the annulus 0.10..0.40: 2 pi (0.16 - 0.01) = 0.94247780
    assert s.S_a.sum() == pytest.approx(0.94247780, rel=1e-8)
    # S_r = 2 pi [0.40 * 0.10 + 0.33 (0.10 - 0.02)] = 2 pi * 0.0664 = 0.41720350
    assert s.S_r == pytest.approx(0.41720350, rel=1e-7)
    # S_t = pi/6 [0.4 * 0.001 + 0.33 (0.001 - 0.000008) + 0.73 * 0.07^3]
    #     = pi/6 [0.0004 + 0.00032736 + 0.00025039] = pi/6 * 0.00097775 = 0.00051195
    assert s.S_t == pytest.approx(PI / 6 * (0.0004 + 0.00032736 + 0.73 * 0.000343), rel=1e-10)
    assert s.S_t == pytest.approx(0.00051195, rel=1e-4)
    # S_out = 2 pi 0.4 0.1 = 0.25132741, S_in = 2 pi 0.33 0.08 = 0.16587609
    # Gamma = sqrt(0.08545132 / 0.41720350) = sqrt(0.20481928) = 0.45256964
    assert (s.S_out, s.S_in) == (pytest.approx(0.25132741, rel=1e-7), pytest.approx(0.16587609, rel=1e-7))
    assert s.gamma == pytest.approx(0.45256964, rel=1e-6)


def test_one_face_and_web_thickness_options():
    two = radiation_surfaces(RADII, flat_disc_segments())
    one = radiation_surfaces(RADII, flat_disc_segments(), faces=1)
    np.testing.assert_allclose(one.S_a, two.S_a / 2, rtol=1e-14)
    mean = radiation_surfaces(RADII, web_thickness="mean")
    assert mean.w_web == 0.03
    # S_r = 2 pi [0.04 + 0.33 * 0.07] = 2 pi * 0.0631 = 0.39646899
    assert mean.S_r == pytest.approx(0.39646899, rel=1e-7)
    assert radiation_surfaces(RADII, web_thickness=0.025).w_web == 0.025
    with pytest.raises(ValueError):
        radiation_surfaces(RADII)  # 'tyre' needs the outline
    with pytest.raises(ValueError):
        radiation_surfaces(RADII, web_thickness=0.2)  # thicker than the tyre


def test_tapered_web_thickness_profile():
    # web 0.04 thick at the hub, 0.02 at the tyre, linear: the 'tyre' rule takes
    # the smallest axial thickness over r_4..r_5, i.e. 0.02 at r_5
    seg = flat_disc_segments()
    seg["web_gauge"] = np.array([[0.10, -0.02], [0.33, -0.01]])
    seg["web_field"] = np.array([[0.33, 0.01], [0.10, 0.02]])
    rr, t = web_thickness_profile(seg)
    np.testing.assert_allclose(t, 0.04 - 0.02 * (rr - 0.10) / 0.23, rtol=1e-12)
    assert radiation_surfaces(RADII, seg).w_web == pytest.approx(0.02, rel=1e-12)


def test_surface_nodes_binning():
    s = radiation_surfaces(RADII, flat_disc_segments())
    # nodes: 0..5 gauge web at r = 0.10 (corner), 0.12, 0.16, 0.22, 0.30, 0.33 (tyre corner)
    #        6..7 field web at 0.14, 0.28; 8..9 hub face at 0.07 (below r_1: not counted), 0.10
    #        10..11 flange back at 0.36, 0.42 (above r_6 = 0.40: outer annulus); 12 field face 0.37
    #        13..14 tread, 15 flange, 16 tyre inner
    r = [0.10, 0.12, 0.16, 0.22, 0.30, 0.33, 0.14, 0.28, 0.07, 0.10, 0.36, 0.42, 0.37, 0.40, 0.40, 0.41, 0.33]
    pts = np.column_stack([r, np.zeros(len(r))])
    bnd = {"web_gauge": [0, 1, 2, 3, 4, 5], "web_field": [6, 7], "hub_outboard": [8, 9],
           "flange_back": [10, 11], "field_face": [12], "tread": [13, 14], "flange": [15], "tyre_inner": [5, 16],
           "bore": [8]}
    nodes = surface_nodes(pts, bnd, s)
    got = [sorted(a.tolist()) for a in nodes.axial]
    # annuli [0.10, 0.1575), [0.1575, 0.215), [0.215, 0.2725), [0.2725, 0.33), [0.33, 0.40]+
    assert got == [[0, 1, 6, 9], [2], [3], [4, 7], [5, 10, 11, 12]]
    assert sorted(nodes.radial.tolist()) == [5, 13, 14, 15, 16]


def test_contact_node_nearest_on_running_surface():
    pts = np.array([[0.40, 0.70], [0.40, 0.72], [0.40, 0.75], [0.41, 0.69], [0.43, 0.68]])
    bnd = {"tread": [0, 1, 2], "flange": [3, 4], "flange_back": []}
    assert contact_node(pts, bnd, -0.032, 0.75) == 1  # Z = 0.718 -> 0.72
    assert contact_node(pts, bnd, -0.061, 0.75) == 3  # on the flange
    assert contact_node(pts, bnd, -0.061, 0.75, segments=("tread",)) == 0
