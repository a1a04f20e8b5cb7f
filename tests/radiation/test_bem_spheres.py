"""The boundary-element solver (``solvers.radiation.bem``) against the analytic pulsating and oscillating
spheres at ka = 0.1 ... 5, with every backend present: within 0.5 dB (issue 28; docs/validation/71_bem_spheres.md,
whose writer's ``sphere_rows`` computes both, once per code).  Slow: bempp compiles its numba kernels once per process."""
import pytest


@pytest.mark.validation
def test_bem_against_analytic_spheres():
    pytest.importorskip("bempp_cl")
    from pipeline.validation.writers.bem_spheres import sphere_rows

    rows = sphere_rows()["rows"]
    assert len(rows) >= 5 and {r[0] for r in rows} >= {"numba"}
    for dev, ka, lp, ep, lo, eo, _ in rows:
        assert abs(lp - ep) < 0.5 and abs(lo - eo) < 0.5, (dev, ka, lp - ep, lo - eo)
