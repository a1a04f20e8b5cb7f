"""Axis conditions of the harmonic solver (SPEC 3.1): a solid free disc.

The section r in [0, a] touches the axis, where each harmonic needs its own
regularity condition (n = 0: U_r = U_phi = 0; n = 1: U_z = 0 and
U_r + U_phi = 0; n >= 2: U = 0).  With them the flexural modes of a thin
free disc must match exact Kirchhoff theory for n = 0..3 (n = 1 is the case
that needs the U_r + U_phi = 0 coupling); without them (a wrong condition)
n = 1 would be pinned or singular.
"""
import os

import numpy as np
import pytest

from geometry.mesher import mesh_section, read_msh
from pipeline.validation.references.free_disc import free_disc_nondimensional
from pipeline.validation.references.plates import DISC_A as A, DISC_H as H, E, NU, RHO, disc_segments



def test_free_disc_reference_values():
    # Leissa (NASA SP-160, 1969), free circular plate, nu = 0.3 cited in many texts:
    # lambda^2 = 5.358 (n=2), 9.003 (n=0, one nodal circle), 12.439 (n=3), 20.475 (n=1, one circle)
    assert free_disc_nondimensional(2, NU, 1)[0] == pytest.approx(5.358, rel=2e-3)
    assert free_disc_nondimensional(0, NU, 1)[0] == pytest.approx(9.003, rel=2e-3)
    assert free_disc_nondimensional(3, NU, 1)[0] == pytest.approx(12.439, rel=2e-3)
    assert free_disc_nondimensional(1, NU, 1)[0] == pytest.approx(20.475, rel=2e-3)


@pytest.fixture(scope="module")
def disc(tmp_path_factory):
    from solvers.wheel.axisym import HarmonicSolver

    segs = disc_segments()
    path = os.path.join(tmp_path_factory.mktemp("disc"), "disc.msh")
    names = mesh_section(segs, path)
    mesh, _, ft = read_msh(path)
    return HarmonicSolver(mesh, ft, E, NU, RHO, degree=2, axis=names["axis"])


@pytest.mark.parametrize("n", [0, 1, 2, 3])
def test_free_disc_flexural_modes(disc, n):
    D = E * H**3 / (12 * (1 - NU**2))
    lam2 = free_disc_nondimensional(n, NU, 1)[0]
    f_exact = lam2 / (2 * np.pi * A**2) * np.sqrt(D / (RHO * H))
    res = disc.solve(n, 1.3 * f_exact)
    sh = np.abs(res.shapes)
    flex = [i for i in range(len(res.freqs_hz)) if sh[i, :, 1].max() > 3 * max(sh[i, :, 0].max(), sh[i, :, 2].max())]
    assert flex, res.freqs_hz
    f = res.freqs_hz[flex[0]]
    assert f == pytest.approx(f_exact, rel=0.01), (n, f, f_exact)
