"""Self-checks of the analytic beam references (pipeline/validation/references/beam.py)."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.validation.references import beam

EI, KGA, M, RHOI, KS = 4.07e6, 2.1e8, 50.0, 0.155, 2.0e8


@pytest.mark.parametrize("f,x", [(50.0, 0.0), (318.0, 0.0), (318.0, 0.7), (1500.0, 0.0), (1500.0, 0.35)])
def test_tboef_residues_vs_numerical_integral(f, x):
    res = beam.tboef_receptance([f], [x], EI, KGA, M, RHOI, KS, 0.02, 0.25)[0, 0]
    num = beam.tboef_numeric(f, x, EI, KGA, M, RHOI, KS, 0.02, 0.25, kmax=2000.0, n=2_000_001)
    assert res == pytest.approx(num, rel=2e-4)


def test_euler_bernoulli_static_limit():
    """Winkler beam under a static point load: w(x) = F beta / (2 k) e^{-beta x} (cos + sin)."""
    beta = (KS / (4 * EI)) ** 0.25
    x = np.array([0.0, 0.3, 1.0, 2.0])
    w = beam.tboef_receptance([1e-3], x, EI, None, M, 0.0, KS)[:, 0]
    ref = beta / (2 * KS) * np.exp(-beta * x) * (np.cos(beta * x) + np.sin(beta * x))
    assert np.allclose(w.real, ref, rtol=1e-6, atol=1e-6 * ref[0])
    # Timoshenko with a very stiff shear and no rotary inertia -> Euler-Bernoulli
    wt = beam.tboef_receptance([1e-3], x, EI, 1e16, M, 0.0, KS)[:, 0]
    assert np.allclose(wt, w, rtol=1e-6, atol=1e-9 * abs(w[0]))


def test_lateral_torsion_decouples():
    """With the shear centre at the foot (z_s = 0), the centroid on it and
    the load at the shear centre, the lateral model is a Winkler beam on k_y."""
    p = dict(EI_l=6.7e5, GJ=1.5e5, EGamma=2e3, m=50.0, rhoI_l=0.0, rhoI_pc=0.18, z_c=0.0, z_s=0.0,
             k_y=2e7, k_r=2.4e5)
    f = [20.0, 150.0, 900.0]
    g = beam.lateral_torsion_receptance(f, [0.0, 0.5], p, out=("lateral", "lateral"), z_h=0.0)
    ref = beam.tboef_receptance(f, [0.0, 0.5], 6.7e5, None, 50.0, 0.0, 2e7)
    assert np.allclose(g, ref, rtol=1e-9)
    # reciprocity of the coupled model: lateral response to a vertical force = twist-mediated vertical
    # response to a lateral force
    p.update(z_c=0.08, z_s=0.056)
    a = beam.lateral_torsion_receptance(f, [0.3], p, out=("lateral", "vertical"), z_h=0.155, y_h=0.012)
    b = beam.lateral_torsion_receptance(f, [0.3], p, out=("vertical", "lateral"), z_h=0.155, y_h=0.012)
    assert np.allclose(a, b, rtol=1e-12)
