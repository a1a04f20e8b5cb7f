"""Assembly of the rail section's waveguide matrices (dolfinx), the materials and the pad's
calibration to its vertical stiffness (notes in ``solvers.rail.waveguide``)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from geometry.rail import CURVE_TAGS as FACETS  # the mesh's physical curve tags (geometry.rail_mesh)
from geometry.rail import PAD_TAG, RAIL_TAG


def lame(E, nu):
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


# --------------------------------------------------------------------------- assembly
@dataclass
class Assembled:
    """Unconstrained half-section matrices (scipy CSR, dof = 3 node + c,
    c = 0: W (axial, scaled), 1: U_y, 2: U_z) split by region and Lame part:
    K[j][(region, part)] with j = 0, 1, 2, region in ('rail', 'pad'),
    part in ('lam', 'mu'); M[region] with unit density."""

    K: list
    M: dict
    nodes: np.ndarray  # (n_nodes, 2) coordinates (y, z)
    node_region: np.ndarray  # (n_nodes,) 1 if the node belongs to a steel cell, else 2
    facet_nodes: dict  # {name: node indices on that physical curve}
    cells: np.ndarray  # (n_cells, 3) vertex-node triangles (P1 part of the P2 nodes) for plots
    cell_region: np.ndarray


def assemble(mesh, cell_tags, facet_tags, degree: int = 2) -> Assembled:
    """Assemble the waveguide matrices of the half section once (JIT: four
    forms).  Region coefficients are DG0 indicator functions so that one
    compiled form serves all (region, part) combinations."""
    import ufl  # lazy: brings in ufl (and PETSc's signal handlers)
    from dolfinx import fem  # lazy: brings in dolfinx (and PETSc's signal handlers)
    from dolfinx.fem.petsc import assemble_matrix  # lazy: brings in dolfinx (and PETSc's signal handlers)

    V = fem.FunctionSpace(mesh, ufl.VectorElement("Lagrange", mesh.ufl_cell(), degree, dim=3))
    Q = fem.FunctionSpace(mesh, ("DG", 0))
    cl, cm = fem.Function(Q), fem.Function(Q)  # lambda- and mu-coefficients (indicators)
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)

    def tr0(w):
        return w[1].dx(0) + w[2].dx(1)

    def k0(u, v):
        lam = tr0(u) * tr0(v)
        mu = 2 * (u[1].dx(0) * v[1].dx(0) + u[2].dx(1) * v[2].dx(1)) \
            + (u[1].dx(1) + u[2].dx(0)) * (v[1].dx(1) + v[2].dx(0)) \
            + u[0].dx(0) * v[0].dx(0) + u[0].dx(1) * v[0].dx(1)
        return cl * lam + cm * mu

    def k1(u, v):
        # a(e1(u), e0(v)) + a(e0(u), e1(v)), e1 = (-W, 0, 0, 0, U_y, U_z)
        lam = u[0] * tr0(v) + v[0] * tr0(u)  # enters with a minus sign (e1_xx = -W)
        mu = u[1] * v[0].dx(0) + u[2] * v[0].dx(1) + v[1] * u[0].dx(0) + v[2] * u[0].dx(1)
        return cm * mu - cl * lam

    def k2(u, v):
        return cl * u[0] * v[0] + cm * (2 * u[0] * v[0] + u[1] * v[1] + u[2] * v[2])

    forms = [fem.form(f(u, v) * ufl.dx) for f in (k0, k1, k2)]
    m_form = fem.form(cl * ufl.inner(u, v) * ufl.dx)

    def to_csr(A):
        A.assemble()
        ip, ix, val = A.getValuesCSR()
        n = A.getSize()
        out = sp.csr_matrix((val.real.copy(), ix.copy(), ip.copy()), shape=n)
        A.destroy()
        return out

    regions = {"rail": RAIL_TAG, "pad": PAD_TAG}
    K = [dict(), dict(), dict()]
    M = {}
    for rname, tag in regions.items():
        ind = (cell_tags.values == tag).astype(float)
        cells = cell_tags.indices
        for part in ("lam", "mu"):
            cl.x.array[:] = 0.0
            cm.x.array[:] = 0.0
            (cl if part == "lam" else cm).x.array[cells] = ind
            for j in range(3):
                K[j][(rname, part)] = to_csr(assemble_matrix(forms[j]))
        cl.x.array[:] = 0.0
        cl.x.array[cells] = ind
        M[rname] = to_csr(assemble_matrix(m_form))

    nodes = V.tabulate_dof_coordinates()[:, :2].copy()
    n_cells = mesh.topology.index_map(2).size_local
    cell_nodes = np.array([V.dofmap.cell_dofs(c) for c in range(n_cells)])
    creg = np.zeros(n_cells, int)
    creg[cell_tags.indices] = cell_tags.values
    node_region = np.full(len(nodes), PAD_TAG)
    node_region[np.unique(cell_nodes[creg == RAIL_TAG])] = RAIL_TAG
    fdim = mesh.topology.dim - 1
    facet_nodes = {}
    for name, tag in FACETS.items():
        f = facet_tags.find(tag)
        if len(f):
            facet_nodes[name] = np.asarray(fem.locate_dofs_topological(V, fdim, f), dtype=int)
    return Assembled(K, M, nodes, node_region, facet_nodes, cell_nodes[:, :3].copy(), creg)


# --------------------------------------------------------------------------- materials and the pad
def pad_calibration(asm: Assembled, nu_pad: float) -> dict:
    """Static stiffnesses per unit rail length (full section, both halves)
    of the pad layer with E = 1 under a rigid foot at k = 0: vertical
    (uniform u_z), lateral (uniform u_y) and rocking about the foot-bottom
    centre (u_z = y).  The layer's underside is clamped; its other faces
    are free.  Returns {'vertical', 'lateral', 'rocking'} for E = 1."""
    lam, mu = lame(1.0, nu_pad)
    K0 = lam * asm.K[0][("pad", "lam")] + mu * asm.K[0][("pad", "mu")]
    pad_nodes = np.where(asm.node_region == PAD_TAG)[0]
    top = asm.facet_nodes["foot_pad"]
    bottom = asm.facet_nodes["pad_bottom"]
    axis = asm.facet_nodes["symmetry"]
    all_pad = np.union1d(pad_nodes, top)
    out = {}
    for case in ("vertical", "lateral", "rocking"):
        u = np.zeros(K0.shape[0])
        fixed = set()
        for nd in bottom:
            fixed.update((3 * nd + 1, 3 * nd + 2))
        for nd in top:
            fixed.update((3 * nd + 1, 3 * nd + 2))
            y = asm.nodes[nd, 0]
            if case == "vertical":
                u[3 * nd + 2] = 1.0
            elif case == "lateral":
                u[3 * nd + 1] = 1.0
            else:
                u[3 * nd + 2] = y
        # in-plane problem only (W decouples at k = 0); symmetry conditions on y = 0
        axis_pad = np.intersect1d(axis, all_pad)
        for nd in axis_pad:
            fixed.add(3 * nd + (1 if case == "vertical" else 2))
        dofs = np.array(sorted({3 * n + c for n in all_pad for c in (1, 2)}))
        fixed = np.array(sorted(fixed))
        free = np.setdiff1d(dofs, fixed)
        Kff = K0[free][:, free].tocsc()
        Kfb = K0[free][:, fixed]
        u[free] = -spsolve(Kff, Kfb @ u[fixed])
        energy2 = u @ (K0 @ u)  # = stiffness for a unit generalized displacement (half section)
        out[case] = 2.0 * energy2
    return out


def material_moduli(rail: dict, asm: Assembled | None = None, calib: dict | None = None) -> dict:
    """Lame constants, densities and loss factors of steel and pad from a
    rail parameter dict.  The pad modulus is calibrated to the vertical
    stiffness rail['pad']['stiffness'] (needs ``asm`` or a precomputed
    ``calib = pad_calibration(asm, nu_pad)``)."""
    m, pad = rail["material"], rail["pad"]
    ls, ms = lame(m["E"], m["nu"])
    if calib is None:
        calib = pad_calibration(asm, pad["poisson"])
    E_pad = pad["stiffness"] / calib["vertical"]
    lp, mp = lame(E_pad, pad["poisson"])
    return {"rail": {"lam": ls, "mu": ms, "rho": m["rho"], "eta": m.get("loss_factor", 0.0)},
            "pad": {"lam": lp, "mu": mp, "rho": pad["rho"], "eta": pad.get("loss_factor", 0.0),
                    "E": E_pad, "k_vertical": pad["stiffness"], "k_lateral": E_pad * calib["lateral"],
                    "k_rocking": E_pad * calib["rocking"]}}
