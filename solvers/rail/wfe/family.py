"""One wave family of the rail section (symmetric or antisymmetric about y = 0; supported or
free) and its waves at a real wavenumber by SLEPc (notes in ``solvers.rail.waveguide``)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from solvers.rail.wfe.assembly import RAIL_TAG, Assembled
from solvers.wheel.eigen import eigenvalues, shift_invert


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
    from petsc4py import PETSc  # lazy: brings in petsc4py (and PETSc's signal handlers)

    A = A.tocsr()
    return PETSc.Mat().createAIJ(size=A.shape, csr=(A.indptr.astype(PETSc.IntType),
                                                    A.indices.astype(PETSc.IntType), A.data))


def eig_real_k(fam: Family, k: float, fmax: float, nev_min: int = 12, tol: float = 1e-10,
               vectors: bool = True):
    """All waves of the family at real wavenumber k (rad/m) with frequency
    <= fmax (Hz): (K0 + k K1 + k^2 K2) phi = w^2 M phi by SLEPc shift-invert
    (MUMPS) about a small negative shift.  Returns (f_hz (n,), phi (N, n)
    M-normalised, or None)."""
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
