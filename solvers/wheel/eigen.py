"""SLEPc shift-invert for the real symmetric eigenproblems K x = w^2 M x of
this project (wheel harmonics, rail waveguide, 3D check).

Constrained dofs must carry 1 on K's and 0 on M's diagonal (they then map to
infinite eigenvalues, far from the shift).  The shift is a small negative
number so that rigid-body (zero-frequency) modes do not make K - sigma M
singular.
"""
from __future__ import annotations

import numpy as np


def shift_invert(K, M, nev: int, sigma: float, tol: float = 1e-10, max_it: int = 200, comm=None):
    """A solved SLEPc EPS (generalised Hermitian, shift-invert about sigma with
    a MUMPS LU) asking for the nev eigenvalues nearest sigma.  The caller
    reads the pairs and destroys it."""
    from petsc4py import PETSc  # lazy: brings in petsc4py (and PETSc's signal handlers)
    from slepc4py import SLEPc  # lazy: brings in slepc4py (and PETSc's signal handlers)

    eps = SLEPc.EPS().create(comm or PETSc.COMM_SELF)
    eps.setOperators(K, M)
    eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
    st = eps.getST()
    st.setType(SLEPc.ST.Type.SINVERT)
    st.setShift(sigma)
    ksp = st.getKSP()
    ksp.setType("preonly")
    pc = ksp.getPC()
    pc.setType("lu")
    pc.setFactorSolverType("mumps")
    eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
    eps.setTarget(sigma)
    eps.setDimensions(nev, PETSc.DECIDE)
    eps.setTolerances(tol, max_it)
    eps.solve()
    return eps


def eigenvalues(eps) -> np.ndarray:
    """Real parts of the converged eigenvalues, in SLEPc's order."""
    return np.array([eps.getEigenvalue(i).real for i in range(eps.getConverged())])
