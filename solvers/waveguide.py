"""Waveguide finite elements (SAFE / WFE) of the rail cross-section, dolfinx + SLEPc.

SPEC 3.2.  The rail (steel) and the rail pad (an elastic layer under the
foot, clamped at its underside on rigid ground) are meshed in the (y, z)
cross-section; along the rail the displacement is a wave

    u(x, y, z, t) = U(y, z) exp(i (w t - k x)).

Strains (engineering shears, Voigt order xx, yy, zz, yz, xy, xz):

    e_xx = -i k U_x     e_yy = U_y,y    e_zz = U_z,z    g_yz = U_y,z + U_z,y
    g_xy = U_x,y - i k U_y              g_xz = U_x,z - i k U_z

The axial component is scaled by the imaginary unit,

    U_x = -i W        (W real for real k; physical u_x = Re{-i W e^{i(wt-kx)}}),

which turns every strain into a real vector times a common phase:
e_xx = -k W and (g_xy, g_xz) = -i (W,y + k U_y, W,z + k U_z); the factor -i
of the two axial shears cancels in the energy because the isotropic D does
not couple them with the in-plane strains.  With the real strain vector
e(k) = e0 + k e1,

    e0 = (0, U_y,y, U_z,z, U_y,z + U_z,y, W,y, W,z),   e1 = (-W, 0, 0, 0, U_y, U_z),

the stiffness is K(k) = K0 + k K1 + k^2 K2 with the REAL SYMMETRIC matrices

    K0 = int e0' D e0,   K1 = int (e0' D e1 + e1' D e0),   K2 = int e1' D e1,
    M  = int rho (W^2 + U_y^2 + U_z^2),

so for real k the dispersion relation is the real symmetric generalized
eigenproblem (K0 + k K1 + k^2 K2) phi = w^2 M phi (SLEPc, shift-invert,
MUMPS).  The physical matrices are T K(k) T^H with T = diag(-i, 1, 1): the
in-plane (y, z) block is untouched, so forces and responses in y and z
need no conversion.  K1 couples W only with (U_y, U_z), while K0, K2 and M
are block diagonal in (W | U_y, U_z); the spectrum is even in k
(K(-k) = S K(k) S with S = diag(-1, 1, 1)).  ``solvers.rail_response``
exploits both facts.

Symmetry.  The rail is symmetric about y = 0, the mesh covers y >= 0 and the
two wave families are solved separately:

    'sym'  (vertical bending, extension, symmetric foot/web modes):  U_y = 0 on y = 0
    'anti' (lateral bending, torsion, web bending, antisymmetric foot): W = U_z = 0 on y = 0

A full-section field is the sum of the two; for a unit load at a point P
(y > 0 or on the axis), the full-section receptance is
G(P, P) = (G_sym + G_anti) / 2, each G from the half model loaded at P.

Materials.  Steel: E, nu, rho, loss factor eta_s.  Pad: an isotropic
elastic layer with Poisson ratio nu_p whose Young's modulus is calibrated
so that the vertical stiffness per unit rail length of the layer under a
rigid foot equals the given k_pad (N/m^2); the matrices are stored split
into their lambda- and mu-parts per region, K = lam K^lam + mu K^mu, so the
pad (or the steel) can be changed without re-assembly.  Loss factors enter
the forced response as complex moduli (``solvers.rail_response``).

Pad density.  The layer smears discrete pads (stiffness s_p every sleeper
spacing) along the rail, so its modulus is ~20x lower than a real pad's;
with a realistic rubber density (~1200 kg/m^3) the layer would have its
own thickness/shear resonances at 1-2 kHz, which real pads do not have
(and ~90 spurious waves below 7 kHz).  The pad mass (~0.1-0.3 kg/m) is
negligible for the rail, so the parameter files use rho_pad = 10 kg/m^3,
which moves the layer resonances above ~15 kHz.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

RAIL_TAG, PAD_TAG = 1, 2
FACETS = {"running_surface": 1, "rail_surface": 2, "foot_pad": 3, "foot_free": 4, "symmetry": 5,
          "pad_side": 6, "pad_bottom": 7}


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
    import ufl
    from dolfinx import fem
    from dolfinx.fem.petsc import assemble_matrix

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
        from scipy.sparse.linalg import spsolve

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


# --------------------------------------------------------------------------- one wave family
@dataclass
class Family:
    """Constrained matrices of one wave family (scipy CSR over the free
    dofs).  ``Ks[j]`` steel and ``Kp[j]`` pad parts of K_j (j = 0, 1, 2),
    real; ``M`` real.  ``dof_node``, ``dof_comp`` map free dofs to nodes and
    components (0: W, 1: U_y, 2: U_z).  ``eta_s``, ``eta_p`` loss factors."""

    name: str
    supported: bool
    Ks: list
    Kp: list
    M: sp.csr_matrix
    dof_node: np.ndarray
    dof_comp: np.ndarray
    nodes: np.ndarray
    node_region: np.ndarray
    eta_s: float
    eta_p: float
    props: dict = field(default_factory=dict)

    def K(self, k: float, complex_moduli: bool = False):
        fs = (1 + 1j * self.eta_s) if complex_moduli else 1.0
        fp = (1 + 1j * self.eta_p) if complex_moduli else 1.0
        out = (self.Ks[0] + k * self.Ks[1] + k * k * self.Ks[2]) * fs
        if self.supported:
            out = out + (self.Kp[0] + k * self.Kp[1] + k * k * self.Kp[2]) * fp
        return out

    def dof(self, node: int, comp: int) -> int:
        idx = np.where((self.dof_node == node) & (self.dof_comp == comp))[0]
        if len(idx) != 1:
            raise KeyError(f"node {node} component {comp} is not a free dof of family {self.name}")
        return int(idx[0])

    def node_at(self, y: float, z: float, tol: float = 1e-6) -> int:
        d = np.hypot(self.nodes[:, 0] - y, self.nodes[:, 1] - z)
        i = int(np.argmin(d))
        if d[i] > tol:
            raise KeyError(f"no mesh node at (y, z) = ({y}, {z}); nearest is {d[i]:.2e} m away")
        return i


def family(asm: Assembled, mat: dict, name: str, supported: bool = True) -> Family:
    """Apply the family's symmetry conditions on y = 0, clamp the pad
    underside, and drop the pad entirely for the free rail
    (``supported=False``)."""
    if name not in ("sym", "anti"):
        raise ValueError("family must be 'sym' or 'anti'")
    n_nodes = len(asm.nodes)
    keep_node = np.ones(n_nodes, bool) if supported else (asm.node_region == RAIL_TAG)
    fixed = np.zeros(3 * n_nodes, bool)
    axis = asm.facet_nodes["symmetry"]
    comps = (1,) if name == "sym" else (0, 2)
    for c in comps:
        fixed[3 * axis + c] = True
    if supported:
        for c in range(3):
            fixed[3 * asm.facet_nodes["pad_bottom"] + c] = True
    dofs = np.arange(3 * n_nodes)
    free = dofs[(~fixed) & np.repeat(keep_node, 3)]

    def restrict(A):
        return A[free][:, free].tocsr()

    r, p = mat["rail"], mat["pad"]
    Ks = [restrict(r["lam"] * asm.K[j][("rail", "lam")] + r["mu"] * asm.K[j][("rail", "mu")]) for j in range(3)]
    Kp = [restrict(p["lam"] * asm.K[j][("pad", "lam")] + p["mu"] * asm.K[j][("pad", "mu")]) for j in range(3)]
    M = restrict(r["rho"] * asm.M["rail"] + (p["rho"] * asm.M["pad"] if supported else 0 * asm.M["pad"]))
    return Family(name, supported, Ks, Kp, M, free // 3, free % 3, asm.nodes, asm.node_region,
                  r["eta"], p["eta"])


# --------------------------------------------------------------------------- dispersion (real k, SLEPc)
def _petsc(A):
    from petsc4py import PETSc

    A = A.tocsr()
    return PETSc.Mat().createAIJ(size=A.shape, csr=(A.indptr.astype(PETSc.IntType),
                                                    A.indices.astype(PETSc.IntType), A.data))


def eig_real_k(fam: Family, k: float, fmax: float, nev_min: int = 12, tol: float = 1e-10,
               vectors: bool = True):
    """All waves of the family at real wavenumber k (rad/m) with frequency
    <= fmax (Hz): (K0 + k K1 + k^2 K2) phi = w^2 M phi by SLEPc shift-invert
    (MUMPS) about a small negative shift.  Returns (f_hz (n,), phi (N, n)
    M-normalised, or None)."""
    from .eigen import eigenvalues, shift_invert

    K = _petsc(fam.K(k))
    M = _petsc(fam.M)
    sigma = -(2 * np.pi * 2.0) ** 2
    nev = nev_min
    while True:
        eps = shift_invert(K, M, nev, sigma, tol, 300)
        lams = eigenvalues(eps)
        nconv = len(lams)
        top = np.sqrt(max(lams.max(), 0.0)) / (2 * np.pi) if nconv else 0.0
        if nconv >= nev and top > fmax:
            break
        if nev > 400:
            raise RuntimeError(f"k = {k}: could not bracket all waves below {fmax} Hz")
        nev = int(nev * 1.6) + 4
        eps.destroy()
    order = np.argsort(lams)
    freqs, vecs = [], []
    vr = K.createVecRight()
    for i in order:
        lam = eps.getEigenpair(int(i), vr).real
        f = np.sqrt(max(lam, 0.0)) / (2 * np.pi)
        if f > fmax:
            break
        freqs.append(f)
        if vectors:
            x = vr.getArray().copy()
            x /= np.sqrt(x @ (fam.M @ x))
            vecs.append(x)
    eps.destroy()
    K.destroy()
    M.destroy()
    return np.array(freqs), (np.array(vecs).T if vectors else None)


# --------------------------------------------------------------------------- section properties from the FE mesh
def torsion_properties(mesh, cell_tags, degree: int = 2) -> dict:
    """Saint-Venant torsion of the steel section from the warping function
    omega (Laplace's equation with d omega/dn = z n_y - y n_z on the free
    boundary; on the half section omega is odd in y, so omega = 0 on y = 0).
    Returns J (torsion constant, full section), the shear-centre height
    z_s (on y = 0 by symmetry) and the warping constant Gamma (full section,
    sectorial coordinate about the shear centre).  Coordinates (y, z) with
    z from the foot underside; centroid from the same mesh."""
    import ufl
    from dolfinx import fem, mesh as dmesh
    from dolfinx.fem.petsc import LinearProblem

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


# --------------------------------------------------------------------------- wave-type identification
LABELS = ("vertical bending", "lateral bending", "torsion", "extensional", "shear-rotation", "foot flapping",
          "web", "head")


def region_masks(fam: Family, rail: dict) -> dict:
    """Node masks of the steel head / web / foot (by height, from the
    rail parameters) for the family's free dofs."""
    H = rail["section"]["height"]
    z_head = H - rail["head"]["depth"]
    z_foot = rail["foot"]["thickness_web"]
    z = fam.nodes[fam.dof_node, 1]
    steel = fam.node_region[fam.dof_node] == RAIL_TAG
    return {"head": steel & (z >= z_head), "foot": steel & (z <= z_foot),
            "web": steel & (z > z_foot) & (z < z_head), "steel": steel}


def classify(fam: Family, phi: np.ndarray, rail: dict, zc: float, k: float = 0.0) -> tuple[list[str], np.ndarray]:
    """Label each wave shape (columns of phi, real-k eigenvectors of this
    family at wavenumber k) with one of LABELS:

    * axial share e_W of the steel's kinetic energy and the correlation of
      W with a uniform axial displacement: e_W > 0.5 and corr > 0.8 ->
      'extensional'; e_W > 0.5 otherwise -> 'shear-rotation' (the
      cross-section rotating in the x-direction: the second, Timoshenko,
      branch of bending);
    * share R of the in-plane (y, z) kinetic energy captured by the
      rigid-section motions of the family (sym: vertical translation; anti:
      lateral translation and rotation about the centroid).  R > 0.6 ->
      beam-like: sym 'vertical bending'; anti 'lateral bending' if the
      translational kinetic energy of the fit exceeds the rotational one,
      else 'torsion';
    * otherwise the wave deforms the section; the deforming part of the
      motion (shape minus its rigid fit) tells which: more than 60 % of its
      kinetic energy in the foot -> 'foot flapping', else 'web' (web
      bending, the head swaying or bouncing on the web relative to the
      foot; near cut-on the lateral web-bending wave also rocks the foot,
      share ~0.5).  ('head'
      deformation proper lies far above 6.5 kHz.)

    Returns (labels, descriptors (n, 5) = e_W, R, rotational share, corr,
    foot share of the deforming part's kinetic energy)."""
    reg = region_masks(fam, rail)
    st = reg["steel"].astype(float)
    Mst = sp.diags(st) @ fam.M @ sp.diags(st)
    cw = (fam.dof_comp == 0) & reg["steel"]
    cy = (fam.dof_comp == 1) & reg["steel"]
    cz = (fam.dof_comp == 2) & reg["steel"]
    y = fam.nodes[fam.dof_node, 0]
    z = fam.nodes[fam.dof_node, 1] - zc
    rigid = []
    if fam.name == "sym":
        rigid.append(cz.astype(float))
    else:
        rigid.append(cy.astype(float))
        rigid.append(np.where(cy, -z, 0.0) + np.where(cz, y, 0.0))
    Rm = np.column_stack(rigid)
    G = Rm.T @ (Mst @ Rm)
    labels, desc = [], []
    ones_w = cw.astype(float)
    for j in range(phi.shape[1]):
        v = phi[:, j] * st
        vw = v * cw
        vyz = v * (cy | cz)
        Ew = vw @ (Mst @ vw)
        Eyz = vyz @ (Mst @ vyz)
        tot = Ew + Eyz
        eW = Ew / tot if tot > 0 else 0.0
        corr = (ones_w @ (Mst @ vw)) ** 2 / max((ones_w @ (Mst @ ones_w)) * Ew, 1e-300)
        c = np.linalg.solve(G, Rm.T @ (Mst @ vyz))
        fit = Rm @ c
        R = (fit @ (Mst @ fit)) / Eyz if Eyz > 0 else 0.0
        rot_share = 0.0
        if fam.name == "anti":
            Et = c[0] ** 2 * G[0, 0]
            Er = c[1] ** 2 * G[1, 1]
            rot_share = Er / (Et + Er) if Et + Er > 0 else 0.0
        share = 1.0
        if eW > 0.5:
            lab = "extensional" if corr > 0.8 else "shear-rotation"
        elif R > 0.6:
            lab = "vertical bending" if fam.name == "sym" else ("torsion" if rot_share > 0.5 else "lateral bending")
        else:
            # the deforming part of the motion (shape minus its rigid fit): where does it move?
            res = vyz - fit
            e = {name: res @ (Mst @ (res * reg[name])) for name in ("head", "web", "foot")}
            share = e["foot"] / max(sum(e.values()), 1e-300)
            lab = "foot flapping" if share > 0.6 else "web"
        labels.append(lab)
        desc.append((eW, R, rot_share, corr, share))
    return labels, np.array(desc)


def dispersion(fam: Family, ks, fmax: float, rail: dict, zc: float, snapshots: dict | None = None) -> dict:
    """Dispersion curves of one family for real wavenumbers ks (rad/m):
    all waves below fmax (Hz) at each k (SLEPc), labelled (classify) and
    joined into branches by mode-shape correlation (MAC with the M inner
    product, Hungarian assignment between neighbouring k).

    Returns {'k': (nk,), 'f': (nk, nb) Hz NaN where a branch does not
    exist, 'label': (nb,) majority label of each branch, 'point_label':
    (nk, nb) per-point labels ('' where absent)}."""
    from scipy.optimize import linear_sum_assignment

    ks = np.asarray(ks, float)
    branches: list[dict] = []
    prev = None  # (branch ids, vectors)
    for i, k in enumerate(ks):
        if snapshots is not None and k in snapshots:
            f, phi = snapshots[k]
            sel = f <= fmax
            f, phi = f[sel], phi[:, sel]
        else:
            f, phi = eig_real_k(fam, k, fmax)
        labels, _ = classify(fam, phi, rail, zc, k) if len(f) else ([], None)
        ids = [-1] * len(f)
        if prev is not None and len(f) and len(prev[0]):
            mac = (prev[1].T @ (fam.M @ phi)) ** 2
            r, c = linear_sum_assignment(-mac)
            for a, b in zip(r, c):
                if mac[a, b] > 0.5:
                    ids[b] = prev[0][a]
        for j in range(len(f)):
            if ids[j] < 0:
                branches.append({"k": [], "f": [], "lab": []})
                ids[j] = len(branches) - 1
            br = branches[ids[j]]
            br["k"].append(i)
            br["f"].append(f[j])
            br["lab"].append(labels[j])
        prev = (ids, phi)
    nb = len(branches)
    F = np.full((len(ks), nb), np.nan)
    PL = np.full((len(ks), nb), "", dtype=object)
    lab = []
    for b, br in enumerate(branches):
        F[br["k"], b] = br["f"]
        PL[br["k"], b] = br["lab"]
        vals, counts = np.unique(br["lab"], return_counts=True)
        lab.append(str(vals[np.argmax(counts)]))
    return {"k": ks, "f": F, "label": np.array(lab), "point_label": PL.astype(str)}
