"""Fourier-harmonic (axisymmetric) elasticity eigenproblem, dolfinx + SLEPc.

SPEC 3.1: on the cross-section (r, z) the displacement of harmonic n is

    u_r = U_r(r, z) cos(n phi),  u_z = U_z(r, z) cos(n phi),  u_phi = U_phi(r, z) sin(n phi)

and K_n x = w^2 M_n x is real symmetric.  The strain amplitudes (engineering
shears) are

    e_rr = U_r,r          e_zz = U_z,z         e_pp = (U_r + n U_phi) / r
    g_rz = U_r,z + U_z,r  g_rp = (-n U_r + r U_phi,r - U_phi) / r
    g_zp = U_phi,z - n U_z / r

and all forms carry the weight r dr dz; the circumferential integral (pi for
n >= 1, 2 pi for n = 0) is a common factor of K and M and enters only the
physical modal mass.  For n = 0 the phi component is the torsional family
(u_phi = U_phi), decoupled from (U_r, U_z).

On the axis r = 0 (a solid axle in the section) each harmonic has its own
regularity condition: n = 0: U_r = U_phi = 0; n = 1: U_z = 0 and
U_r + U_phi = 0; n >= 2: U = 0.  To impose U_r + U_phi = 0 as a plain
Dirichlet condition the unknowns are (a, U_z, b) with U_r = a + b,
U_phi = b - a, so U_r + U_phi = 2 b.

Ring springs on a boundary (the primary suspension at the journal) add
int k (U . V) r ds with k per unit area; see ``SpringSupport``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from solvers.wheel.eigen import eigenvalues, shift_invert


@dataclass
class SpringSupport:
    """Distributed spring on the facets with physical tag ``tag``: stiffness
    per unit area (N/m^3) normal to the axis (radial and circumferential,
    acting for n >= 1) and along it (axial)."""

    tag: int
    k_transverse: float
    k_axial: float


@dataclass
class ModalResult:
    freqs_hz: np.ndarray  # (M,)
    shapes: np.ndarray  # (M, ndof_nodes, 3) physical amplitudes (U_r, U_z, U_phi) at the output nodes, max |U| = 1
    modal_mass: np.ndarray  # (M,) kg, physical (includes the pi / 2 pi circumferential factor)
    n: int


class HarmonicSolver:
    """Assemble once per mesh; solve per harmonic order n.

    Parameters: a dolfinx mesh of the section (x[0] = r, x[1] = z), its facet
    tags, material constants, polynomial degree, the facet tags that are
    clamped, the tag of the axis (or None), the tag of a symmetry plane
    z = const and its type ('symmetric': U_z = 0; 'antisymmetric':
    U_r = U_phi = 0), and optional spring supports.
    """

    def __init__(self, mesh, facet_tags, E, nu, rho, degree=2, clamped=(), axis=None,
                 plane=None, plane_type="symmetric", springs=()):
        import ufl  # lazy: brings in ufl (and PETSc's signal handlers)
        from dolfinx import fem  # lazy: brings in dolfinx (and PETSc's signal handlers)
        from petsc4py import PETSc  # lazy: brings in petsc4py (and PETSc's signal handlers)

        self.mesh, self.facet_tags = mesh, facet_tags
        self.rho = rho
        self.clamped, self.axis, self.plane, self.plane_type = tuple(clamped), axis, plane, plane_type
        el = ufl.VectorElement("Lagrange", mesh.ufl_cell(), degree, dim=3)
        self.V = V = fem.FunctionSpace(mesh, el)
        self.n_const = fem.Constant(mesh, PETSc.ScalarType(0.0))
        self.tors = fem.Constant(mesh, PETSc.ScalarType(1.0))  # 0 for n = 0: no torsional spring restraint
        n = self.n_const
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        mu = E / (2 * (1 + nu))
        x = ufl.SpatialCoordinate(mesh)
        r = x[0]

        # (a, U_z, b) -> (U_r, U_z, U_phi); a Constant matrix rather than
        # literal +-1 sums, which trip FFCx 0.5's block factorisation
        T = fem.Constant(mesh, np.array([[1.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 1.0]]))

        def phys(w):
            q = ufl.dot(T, w)
            return q[0], q[1], q[2]

        def strain(w):
            ur, uz, up = phys(w)
            return (ur.dx(0), uz.dx(1), (ur + n * up) / r,
                    ur.dx(1) + uz.dx(0), (-n * ur + r * up.dx(0) - up) / r, up.dx(1) - n * uz / r)

        u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
        eu, ev = strain(u), strain(v)
        tr_u, tr_v = eu[0] + eu[1] + eu[2], ev[0] + ev[1] + ev[2]
        energy = lam * tr_u * tr_v + 2 * mu * sum(eu[i] * ev[i] for i in range(3)) \
            + mu * sum(eu[i] * ev[i] for i in range(3, 6))
        k_form = energy * r * ufl.dx
        ur, uz, up = phys(u)
        vr, vz, vp = phys(v)
        if springs:
            ds = ufl.Measure("ds", domain=mesh, subdomain_data=facet_tags)
            for s in springs:
                kt = fem.Constant(mesh, PETSc.ScalarType(s.k_transverse))
                ka = fem.Constant(mesh, PETSc.ScalarType(s.k_axial))
                k_form += (kt * ur * vr + kt * self.tors * up * vp + ka * uz * vz) * r * ds(s.tag)
        m_form = rho * (ur * vr + uz * vz + up * vp) * r * ufl.dx
        self.k_form = fem.form(k_form)
        self.m_form = fem.form(m_form)
        self.mass_density_form = m_form
        # output nodes: the mesh vertices (P1 geometry), for shapes and plots
        self._setup_output()

    def _setup_output(self):
        from dolfinx import fem  # lazy: brings in dolfinx (and PETSc's signal handlers)
        import ufl  # lazy: brings in ufl (and PETSc's signal handlers)

        mesh = self.mesh
        P1 = fem.FunctionSpace(mesh, ufl.VectorElement("Lagrange", mesh.ufl_cell(), 1, dim=3))
        self.P1 = P1
        self.points = P1.tabulate_dof_coordinates()[:, :2].copy()
        self._u = fem.Function(self.V)
        self._u1 = fem.Function(P1)

    def _bcs(self, n):
        from dolfinx import fem  # lazy: brings in dolfinx (and PETSc's signal handlers)
        from petsc4py import PETSc  # lazy: brings in petsc4py (and PETSc's signal handlers)

        V, ft = self.V, self.facet_tags
        fdim = self.mesh.topology.dim - 1
        fixed: list[tuple[int, np.ndarray]] = []  # (component, facets)

        def facets(tag):
            return ft.find(tag)

        for tag in self.clamped:
            for c in range(3):
                fixed.append((c, facets(tag)))
        if self.axis is not None:
            comps = {0: (0, 2), 1: (1, 2)}.get(n, (0, 1, 2))  # n=0: a=b=0; n=1: Uz=0, b=0; n>=2: all
            for c in comps:
                fixed.append((c, facets(self.axis)))
        if self.plane is not None:
            comps = (1,) if self.plane_type == "symmetric" else (0, 2)
            for c in comps:
                fixed.append((c, facets(self.plane)))
        bcs = []
        zero = PETSc.ScalarType(0.0)
        for c, f in fixed:
            dofs = fem.locate_dofs_topological(V.sub(c), fdim, f)
            bcs.append(fem.dirichletbc(zero, dofs, V.sub(c)))
        return bcs

    def solve(self, n: int, fmax: float, nev_min: int = 8, tol: float = 1e-10) -> ModalResult:
        """All modes of harmonic n below fmax (Hz), by shift-invert about a
        small negative shift (so rigid-body modes do not make K - sigma M
        singular).  Requested count grows until the highest converged
        eigenvalue exceeds fmax."""
        from dolfinx.fem.petsc import assemble_matrix  # lazy: brings in dolfinx (and PETSc's signal handlers)


        self.n_const.value = float(n)
        self.tors.value = 0.0 if n == 0 else 1.0
        bcs = self._bcs(n)
        K = assemble_matrix(self.k_form, bcs=bcs, diagonal=1.0)
        K.assemble()
        M = assemble_matrix(self.m_form, bcs=bcs, diagonal=0.0)
        M.assemble()
        sigma = -(2 * np.pi * 5.0) ** 2
        nev = nev_min
        while True:
            eps = shift_invert(K, M, nev, sigma, tol, 200, self.mesh.comm)
            lams = eigenvalues(eps)
            nconv = len(lams)
            order = np.argsort(lams)
            lams = lams[order]
            top = np.sqrt(max(lams[-1], 0.0)) / (2 * np.pi) if nconv else 0.0
            if nconv >= nev and top > fmax:
                break
            if nev > 200:
                raise RuntimeError(f"harmonic n={n}: could not bracket all modes below {fmax} Hz")
            nev *= 2
            eps.destroy()
        keep = [i for i in order if 0 < eps.getEigenvalue(i).real and
                np.sqrt(eps.getEigenvalue(i).real) / (2 * np.pi) <= fmax]
        freqs, shapes, masses = [], [], []
        vr, _ = K.createVecs()
        circ = 2 * np.pi if n == 0 else np.pi
        for i in keep:
            lam = eps.getEigenpair(i, vr).real
            f = np.sqrt(lam) / (2 * np.pi)
            if f < 0.5:  # rigid-body motion (e.g. free rolling rotation for n = 0)
                continue
            self._u.vector.array[:] = vr.array
            self._u.x.scatter_forward()
            U = self._physical_at_nodes()
            scale = np.max(np.abs(U))
            # physical modal mass of the shape normalised to max |U| = 1
            mvec = M.createVecLeft()
            M.mult(vr, mvec)
            mr = circ * vr.dot(mvec) / scale**2
            freqs.append(f)
            shapes.append(U / scale)
            masses.append(mr)
        eps.destroy()
        K.destroy()
        M.destroy()
        idx = np.argsort(freqs)
        shapes = np.array(shapes).reshape(len(freqs), len(self.points), 3)
        return ModalResult(np.array(freqs)[idx], shapes[idx], np.array(masses)[idx], n)

    def _physical_at_nodes(self) -> np.ndarray:
        """(U_r, U_z, U_phi) of the current solution at the P1 output nodes."""
        self._u1.interpolate(self._u)
        w = self._u1.x.array.reshape(-1, 3)
        return np.column_stack([w[:, 0] + w[:, 2], w[:, 1], w[:, 2] - w[:, 0]])

    def cells(self) -> np.ndarray:
        """Triangles (vertex indices into ``points``)."""
        dm = self.P1.dofmap
        return np.array([dm.cell_dofs(c) for c in range(self.mesh.topology.index_map(2).size_local)])
