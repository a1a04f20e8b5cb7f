"""The 'axle' mount: half axle in the section (regularity on the axis), the
primary suspension as ring springs on the journal.  Its lowest n = 1 mode is
the half wheelset bouncing on the vertical suspension: the ring spring's
n = 1 resultant must be k_vertical, so f = sqrt(k_v / m_half) / (2 pi) with
m_half the mass of the revolved section (computed here by quadrature,
independently of the eigensolver)."""
import copy

import numpy as np
import pytest

from pipeline.stages.wheel import load_wheel


@pytest.fixture(scope="module")
def axle_model(tmp_path_factory):
    from geometry.mesher import mesh_section, read_msh
    from geometry.wheel import wheel_segments
    from pipeline.stages.wheel import _solver

    p, _ = load_wheel("c20")
    p = copy.deepcopy(p)
    p["mount"]["type"] = "axle"
    msh = str(tmp_path_factory.mktemp("axle") / "section.msh")
    names = mesh_section(wheel_segments(p), msh)
    return p, _solver(p, names, msh)


def test_bounce_on_suspension(axle_model):
    p, hs = axle_model
    pts, cells = hs.points, hs.cells()
    tri = pts[cells]
    area = 0.5 * np.abs(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]))
    r_mid = tri[:, :, 0].mean(axis=1)
    mass = 2 * np.pi * p["material"]["rho"] * np.sum(area * r_mid)  # exact for linear r on each triangle
    f_expected = np.sqrt(p["suspension"]["k_vertical"] / mass) / (2 * np.pi)
    res = hs.solve(1, 200.0)
    assert res.freqs_hz[0] == pytest.approx(f_expected, rel=0.01), (res.freqs_hz[:3], f_expected, mass)
    # the mode is a rigid translation: U_r = -U_phi, U_z ~ 0 everywhere
    U = res.shapes[0]
    assert np.allclose(U[:, 0], -U[:, 2], atol=0.02) and np.abs(U[:, 1]).max() < 0.05


def test_wheel_modes_survive_the_axle(axle_model):
    """n >= 2 modes hardly see the axle: the (2,0,a) frequency of the axle
    model is within 2 % of the clamped-bore model's."""
    from pipeline.stages.wheel import modes_for_parameters

    p, hs = axle_model
    f_axle = hs.solve(2, 600.0).freqs_hz[0]
    q = copy.deepcopy(p)
    q["mount"]["type"] = "clamped"
    q["modes"]["n_max"] = 2
    import tempfile

    m = modes_for_parameters(q, tempfile.mkdtemp(), workers=1)
    f_clamped = m["f_hz"][(m["n"] == 2) & (m["kind"] == "flexible")][0]
    assert f_axle == pytest.approx(f_clamped, rel=0.02)
