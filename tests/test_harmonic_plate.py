"""Harmonic (Fourier-n) FE solver against the exact Kirchhoff annular plate.

A thin annular plate, inner edge r = b clamped, outer edge r = a free, is
meshed as its (r, z) cross-section -- a 300 mm x 4 mm strip -- and solved
with solvers.wheel.axisym.HarmonicSolver (3D elasticity in each harmonic n,
P2 triangles).  Its out-of-plane (axial, U_z) modes are compared with
pipeline/validation/references/annular_plate.py (exact Kirchhoff theory).

Plate: a = 0.4 m, b = 0.1 m, h = 4 mm (h/a = 0.01), steel.  Model error of
Kirchhoff theory (no shear deformation, no rotary inertia, plane stress
through the thickness): the 3D solution lies below Kirchhoff by roughly
(k h)^2 / 5 with k^2 = lambda^2 / a^2, i.e. < 0.01 % for the fundamentals
and ~0.1-0.25 % for the one-nodal-circle modes; a 4-layer reference mesh
confirms this (n = 3, s = 1: -0.23 %).  Mesh: 2 elements through the
thickness, ~3.5 h (14 mm) along the radius -- ~180 triangles, ~1400 dofs.

The flexural modes are picked by their dominant U_z (not by order); the
in-plane (U_r, U_phi) modes of a thin plate are far above and the test
checks that none falls below the second flexural mode.
"""
import os

import numpy as np
import pytest

from geometry.mesher import mesh_section, read_msh
from pipeline.validation.references.annular_plate import annular_plate_frequencies
from pipeline.validation.references.plates import A, B, E, H, NU, RHO, plate_segments

TOL = 0.01  # relative, against Kirchhoff


@pytest.fixture(scope="module")
def plate_solver(tmp_path_factory):
    from solvers.wheel.axisym import HarmonicSolver

    path = os.path.join(tmp_path_factory.mktemp("plate"), "plate.msh")
    names = mesh_section(plate_segments(), path)
    mesh, _, facet_tags = read_msh(path, gdim=2)
    return HarmonicSolver(mesh, facet_tags, E, NU, RHO, degree=2, clamped=(names["inner"],))


def test_plate_mesh_is_small(plate_solver):
    ncell = plate_solver.mesh.topology.index_map(2).size_local
    assert 50 < ncell < 1000


def test_flexural_modes_against_kirchhoff(plate_solver):
    rows = []
    failures = []
    for n in range(4):
        exact = annular_plate_frequencies(A, B, H, E, NU, RHO, n, count=3)
        # up to above the second flexural mode: everything below it is listed
        res = plate_solver.solve(n, 1.25 * exact[1])
        sh = np.abs(res.shapes)  # (M, nodes, 3): U_r, U_z, U_phi
        uz = sh[:, :, 1].max(axis=1)
        inplane = np.maximum(sh[:, :, 0].max(axis=1), sh[:, :, 2].max(axis=1))
        flex = np.nonzero(uz > 3.0 * inplane)[0]
        other = np.nonzero(uz <= 3.0 * inplane)[0]
        assert len(flex) >= 2, (n, res.freqs_hz, uz, inplane)
        # thin plate: no in-plane mode below the second flexural one
        assert len(other) == 0 or res.freqs_hz[other].min() > res.freqs_hz[flex[1]], (n, res.freqs_hz)
        for s in (0, 1):
            f = res.freqs_hz[flex[s]]
            err = f / exact[s] - 1.0
            rows.append((n, s, exact[s], f, 100 * err))
            if abs(err) > TOL:
                failures.append((n, s, exact[s], f, err))
    print("\nannular plate a=%.2f b=%.2f h=%.4f m, P2, %d dofs" % (A, B, H, 3 * plate_solver.V.dofmap.index_map.size_local))
    print(" n  s   Kirchhoff Hz      FE Hz   err %")
    for n, s, fe, f, e in rows:
        print(f"{n:2d} {s:2d} {fe:13.3f} {f:10.3f} {e:+7.3f}")
    assert not failures, failures
