"""The rail's waveguide model (SPEC 3.2): both supported wave families of the half section,
reduced with unit point loads and responses at the contact nodes of the head (``RailModel``),
built from an assembled mesh (reading the mesh file is the pipeline's: ``pipeline.stages.rail_io``)."""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from geometry.rail import head_profile

from solvers.rail import waveguide as wg
from solvers.rail.reduced import ReducedFamily, reduce_family


@dataclass
class RailModel:
    """Everything the forced response needs, built once per rail: the two
    reduced families with unit point loads/responses in y and z at the
    contact nodes (|y^R| of each contact point) and at the head centre,
    plus section-mean responses (beam kinematics) for validation."""

    rail: dict
    point_y: np.ndarray  # |y| of the loaded head nodes (m)
    point_z: np.ndarray
    sym: ReducedFamily
    anti: ReducedFamily
    families: dict  # the unreduced wg.Family objects ('sym', 'anti')
    props: dict  # section, torsion and pad properties
    snapshots: dict  # {family: {k: (f_hz, phi)}} real-k waves used for the basis
    asm: wg.Assembled = None  # unconstrained matrices (for other families, e.g. the free rail)
    materials: dict = None  # wg.material_moduli output


def _head_nodes(fam: wg.Family, rail: dict, ys) -> tuple[np.ndarray, np.ndarray, list[int]]:
    ys = np.unique(np.round(np.abs(np.asarray(ys, float)), 10))
    zs = head_profile(rail, ys)
    nodes = [fam.node_at(y, z, tol=2e-6) for y, z in zip(ys, zs)]
    return ys, zs, nodes


def section_functionals(fam: wg.Family, zc: float) -> dict:
    """Mass-weighted section means over the steel (beam kinematics):
    'mean_z' (vertical), 'mean_y' (lateral), 'rot_x' (rotation about the
    longitudinal axis through the centroid, positive from +y toward +z)."""
    rail = fam.node_region[fam.dof_node] == wg.RAIL_TAG
    y, z = fam.nodes[fam.dof_node, 0], fam.nodes[fam.dof_node, 1] - zc
    mask = sp.diags(rail.astype(float))
    Ms = mask @ fam.M @ mask
    ones_y = ((fam.dof_comp == 1) & rail).astype(float)
    ones_z = ((fam.dof_comp == 2) & rail).astype(float)
    out = {}
    if fam.name == "sym":
        m = ones_z @ (Ms @ ones_z)
        out["mean_z"] = (Ms @ ones_z) / m
    else:
        m = ones_y @ (Ms @ ones_y)
        out["mean_y"] = (Ms @ ones_y) / m
        rot = np.where(fam.dof_comp == 1, -z, 0.0) + np.where(fam.dof_comp == 2, y, 0.0)
        rot = rot * rail
        Ip = rot @ (Ms @ rot)
        out["rot_x"] = (Ms @ rot) / Ip
    return out


def contact_points(rail: dict) -> list:
    """The rail's nominal contact points y^R (m): its parameter file's [contact] y (SPEC 2), or none."""
    return list(rail.get("contact", {}).get("y", []))


def assemble_rail_model(rail: dict, mesh, cell_tags, facet_tags, contact_y=None, basis: dict | None = None,
                        with_centre: bool = True, verbose: bool = False) -> RailModel:
    """The rail model of the half-section mesh (dolfinx mesh and its cell and facet tags, as
    written by geometry.rail_mesh.mesh_rail): assemble, calibrate the pad, build both supported
    families and their reduced models with unit loads in y and z at the contact nodes (|y^R| of
    ``contact_y``, default the rail's [contact] y) and at the head centre (y = 0, for decay
    rates; ``with_centre``).  ``basis`` overrides the keyword arguments of reduce_family."""
    t0 = time.perf_counter()
    ct, ft = cell_tags, facet_tags
    asm = wg.assemble(mesh, ct, ft)
    calib = wg.pad_calibration(asm, rail["pad"]["poisson"])
    mat = wg.material_moduli(rail, calib=calib)
    tors = wg.torsion_properties(mesh, ct)
    if contact_y is None:
        contact_y = contact_points(rail)
    ys = list(np.abs(contact_y)) + ([0.0] if with_centre else [])
    fams = {n: wg.family(asm, mat, n, supported=True) for n in ("sym", "anti")}
    py, pz, _ = _head_nodes(fams["sym"], rail, ys)
    basis = dict(basis or {})
    red = {}
    snaps = {}
    for name, fam in fams.items():
        loads = {}
        for y, z in zip(py, pz):
            nd = fam.node_at(y, z, tol=2e-6)
            for c, lab in ((1, "y"), (2, "z")):
                try:
                    d = fam.dof(nd, c)
                except KeyError:  # constrained on the symmetry line for this family
                    continue
                e = np.zeros(fam.M.shape[0])
                e[d] = 1.0
                loads[(float(y), lab)] = e
        resp = dict(loads)
        for key, vec in section_functionals(fam, tors["z_centroid"]).items():
            resp[key] = vec
        kw = dict(basis)
        k_modes = kw.pop("k_modes", (0.0, 1.5, 4.0, 8.0, 13.0, 20.0, 30.0, 45.0))
        f_basis = kw.pop("f_basis", 10000.0)
        snaps[name] = {k: wg.eig_real_k(fam, k, f_basis) for k in k_modes}
        red[name] = reduce_family(fam, loads, resp, k_modes=k_modes, f_basis=f_basis,
                                  snapshots=snaps[name], **kw)
        if verbose:
            print(f"family {name}: {fam.M.shape[0]} dofs -> {red[name].size} "
                  f"({red[name].BW.shape[1]} W + {red[name].BY.shape[1]} yz), {time.perf_counter() - t0:.1f} s")
    props = {"torsion": tors, "pad": mat["pad"], "steel": mat["rail"], "calibration": calib}
    return RailModel(rail, py, pz, red["sym"], red["anti"], fams, props, snaps, asm, mat)
