"""Wave types of the rail (which part of the section moves how) and the dispersion curves of a
family joined into labelled branches (notes in ``solvers.rail.waveguide``)."""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from solvers.rail.wfe.assembly import RAIL_TAG
from solvers.rail.wfe.family import Family, eig_real_k


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
    from scipy.optimize import linear_sum_assignment  # lazy: brings in scipy

    ks = np.asarray(ks, float)
    branches: list[dict] = []
    prev = None  # (branch ids, vectors)
    for i, k in enumerate(ks):
        if snapshots is not None and k in snapshots:
            f, phi = snapshots[k]
            sel = f <= fmax
            f, phi = f[sel], phi[:, sel]
        else:
            # as many eigenpairs as the last k had waves, and one more (SLEPc's cost grows with
            # the number asked for; eig_real_k asks again for more if they do not reach fmax)
            f, phi = eig_real_k(fam, k, fmax, nev_min=4 if prev is None else max(4, len(prev[0]) + 1))
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
