"""Section properties of the rail from its FE mesh (dolfinx): Saint-Venant torsion, shear
centre, warping constant (notes in ``solvers.rail.waveguide``)."""
from __future__ import annotations

import numpy as np

from solvers.rail.wfe.assembly import RAIL_TAG


def torsion_properties(mesh, cell_tags, degree: int = 2) -> dict:
    """Saint-Venant torsion of the steel section from the warping function
    omega (Laplace's equation with d omega/dn = z n_y - y n_z on the free
    boundary; on the half section omega is odd in y, so omega = 0 on y = 0).
    Returns J (torsion constant, full section), the shear-centre height
    z_s (on y = 0 by symmetry) and the warping constant Gamma (full section,
    sectorial coordinate about the shear centre).  Coordinates (y, z) with
    z from the foot underside; centroid from the same mesh."""
    import ufl  # lazy: brings in ufl (and PETSc's signal handlers)
    from dolfinx import fem, mesh as dmesh  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from dolfinx.fem.petsc import LinearProblem  # lazy: brings in dolfinx (and PETSc's signal handlers)

    # sub-mesh of the steel cells
    cells = cell_tags.indices[cell_tags.values == RAIL_TAG]
    sub, _, _, _ = dmesh.create_submesh(mesh, 2, cells)
    x = ufl.SpatialCoordinate(sub)
    y, z = x[0], x[1]
    one = fem.Constant(sub, 1.0)
    A_half = fem.assemble_scalar(fem.form(one * ufl.dx))
    zc = fem.assemble_scalar(fem.form(z * ufl.dx)) / A_half
    W = fem.FunctionSpace(sub, ("Lagrange", degree))
    w, q = ufl.TrialFunction(W), ufl.TestFunction(W)
    n = ufl.FacetNormal(sub)
    fdim = 1
    sub.topology.create_connectivity(fdim, 2)
    axis = dmesh.locate_entities_boundary(sub, fdim, lambda X: np.isclose(X[0], 0.0, atol=1e-9))
    bc = fem.dirichletbc(0.0, fem.locate_dofs_topological(W, fdim, axis), W)
    a = ufl.inner(ufl.grad(w), ufl.grad(q)) * ufl.dx
    L = ((z - zc) * n[0] - y * n[1]) * q * ufl.ds  # flux on the free boundary (zero flux on the axis is overridden by the bc)
    omega = LinearProblem(a, L, bcs=[bc], petsc_options={"ksp_type": "preonly", "pc_type": "lu"}).solve()
    # J about the centroid (invariant): J = int (y^2 + zz^2 + y omega_z - zz omega_y) dA
    zz = z - zc
    J_half = fem.assemble_scalar(fem.form((y * y + zz * zz + y * omega.dx(1) - zz * omega.dx(0)) * ufl.dx))
    # shear centre (on y = 0 by symmetry): the warping function about a pole (0, z_p) is
    # omega_p = omega - (z_p - zc) y; the shear centre makes it orthogonal to y:
    # z_s = zc + int y omega dA / I_lateral
    Izz_half = fem.assemble_scalar(fem.form(y * y * ufl.dx))
    Iyw_half = fem.assemble_scalar(fem.form(y * omega * ufl.dx))
    dz = Iyw_half / Izz_half
    Gamma_half = fem.assemble_scalar(fem.form((omega - dz * y) ** 2 * ufl.dx))
    Iyy_half = fem.assemble_scalar(fem.form(zz * zz * ufl.dx))
    return {"J": 2 * J_half, "z_shear_centre": zc + dz, "Gamma": 2 * Gamma_half, "area": 2 * A_half,
            "z_centroid": zc, "I_vertical": 2 * Iyy_half, "I_lateral": 2 * Izz_half}
