"""The rail stage's reading and artifact layout (SPEC 3.2): the rail parameter file (TOML), the
waveguide model built from the section mesh on disk (``solvers.rail.model``), and every array
the rail stage saves in rail.npz (``stage_arrays``: the artifact's keys)."""
from __future__ import annotations

import numpy as np

from geometry.rail import head_profile
from solvers.rail import waveguide as wg
from solvers.constants import F_MAX_HZ
from solvers.rail.model import RailModel, assemble_rail_model, contact_points
from solvers.rail.response import evaluate_table, wave_sum_decay_rate, wave_table
import tomllib
from geometry.mesher import read_msh


def load_rail(path) -> dict:
    """Read a rail parameter file (TOML) into a plain dict (no schema here; the pipeline's
    configuration schema validates types (``stages.rail.load_rail_params``), geometry.rail's
    check_rail the geometry).  The pad's width defaults to the foot's."""
    with open(path, "rb") as fh:
        p = tomllib.load(fh)
    p.setdefault("pad", {})
    if "width" not in p["pad"]:
        p["pad"]["width"] = p["foot"]["width"]
    return p


def build_rail_model(rail: dict, msh_path, contact_y=None, basis: dict | None = None,
                     with_centre: bool = True, verbose: bool = False) -> RailModel:
    """Read the half-section mesh written by geometry.rail_mesh.mesh_rail and build the rail
    model (``solvers.rail.model.assemble_rail_model``, same arguments)."""
    mesh, ct, ft = read_msh(msh_path)
    return assemble_rail_model(rail, mesh, ct, ft, contact_y=contact_y, basis=basis, with_centre=with_centre,
                               verbose=verbose)


def stage_arrays(model: RailModel, freqs, distances, ks=None, fmax: float = F_MAX_HZ, head_y=None) -> dict:
    """All artifact arrays of a rail stage as a flat {name: ndarray} (SI):

    receptances    f_hz (nf,), x_m (nx,), point_y_m, point_z_m (np,),
                   G (np, nx, nf, 2, 2) complex m/N, SPEC directions
                   [2 lateral to field, 3 vertical down], structural;
    wave table     wave_k (nf, M) complex rad/m, wave_a (nf, M, np, 2, 2)
                   complex m/N: G(x) = sum_n wave_a exp(-i wave_k |x|) at any x;
    decay          decay_f_hz (nf,) = f_hz, decay_vertical_db_per_m, decay_lateral_db_per_m
                   (at the head centre, from the same waves);
    dispersion     disp_k (nk,) rad/m and, for s in (free, supported),
                   fam in (sym, anti): disp_{s}_{fam}_f_hz (nk, nb) Hz (NaN
                   where a branch is absent), disp_{s}_{fam}_label (nb,),
                   disp_{s}_{fam}_point_label (nk, nb) (wave types);
    section        section_area_m2, section_mass_per_m, section_I_vertical_m4,
                   section_I_lateral_m4, section_J_m4, section_Gamma_m6,
                   section_z_centroid_m, section_z_shear_centre_m,
                   pad_E_pa, pad_k_vertical_n_per_m2, pad_k_lateral_n_per_m2,
                   pad_k_rocking_nm_per_rad_m;
    head profile   head_y_m (nh,), head_z_m (nh,) (z^R above the foot underside).
    """
    out = {}
    # the contact points' wave table and, from the same waves, the head centre's (the decay rates)
    T = wave_table(model, freqs, points=[*contact_points(model.rail), 0.0])
    a_centre = T["a"][:, :, -1]
    T.update(a=T["a"][:, :, :-1], y=T["y"][:-1], z=T["z"][:-1])
    x = np.asarray(distances, float)
    out.update(f_hz=T["f"], x_m=x, point_y_m=T["y"], point_z_m=T["z"], G=evaluate_table(T, x),
               wave_k=T["k"], wave_a=T["a"])
    out.update(decay_f_hz=T["f"], decay_vertical_db_per_m=wave_sum_decay_rate(T["k"], a_centre[..., 1, 1]),
               decay_lateral_db_per_m=wave_sum_decay_rate(T["k"], a_centre[..., 0, 0]))
    ks = np.linspace(0.0, 30.0, 31) if ks is None else np.asarray(ks, float)
    out["disp_k"] = ks
    zc = model.props["torsion"]["z_centroid"]
    for sup in (False, True):
        for fam_name in ("sym", "anti"):
            fam = model.families[fam_name] if sup else wg.family(model.asm, model.materials, fam_name, False)
            # the supported families' real-k waves at the basis wavenumbers are already there
            dd = wg.dispersion(fam, ks, fmax, model.rail, zc, snapshots=model.snapshots[fam_name] if sup else None)
            key = f"disp_{'supported' if sup else 'free'}_{fam_name}"
            out[key + "_f_hz"] = dd["f"]
            out[key + "_label"] = dd["label"].astype(str)
            out[key + "_point_label"] = dd["point_label"].astype(str)
    t, pad = model.props["torsion"], model.props["pad"]
    out.update(section_area_m2=t["area"], section_mass_per_m=model.rail["material"]["rho"] * t["area"],
               section_I_vertical_m4=t["I_vertical"], section_I_lateral_m4=t["I_lateral"], section_J_m4=t["J"],
               section_Gamma_m6=t["Gamma"], section_z_centroid_m=t["z_centroid"],
               section_z_shear_centre_m=t["z_shear_centre"], pad_E_pa=pad["E"],
               pad_k_vertical_n_per_m2=pad["k_vertical"], pad_k_lateral_n_per_m2=pad["k_lateral"],
               pad_k_rocking_nm_per_rad_m=pad["k_rocking"])
    hy = np.linspace(-model.rail["head"]["width"] / 2, model.rail["head"]["width"] / 2, 281) if head_y is None \
        else np.asarray(head_y, float)
    out.update(head_y_m=hy, head_z_m=head_profile(model.rail, hy))
    return {k: np.asarray(v) for k, v in out.items()}
