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
from geometry.outline import Segment
from pipeline.validation.references.free_disc import free_disc_nondimensional

A, H = 0.2, 0.002
E, NU, RHO = 210e9, 0.3, 7850.0


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

    nl, nt = 30, 2
    r = np.linspace(0, A, nl + 1)
    z = np.linspace(0, H, nt + 1)
    segs = [
        Segment("bottom", np.column_stack([r, np.zeros_like(r)]), A / nl),
        Segment("edge", np.column_stack([np.full_like(z, A), z]), H / nt),
        Segment("top", np.column_stack([r[::-1], np.full_like(r, H)]), A / nl),
        Segment("axis", np.column_stack([np.zeros_like(z), z[::-1]]), H / nt),
    ]
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
