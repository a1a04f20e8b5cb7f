"""Rail (BV50 / 60E1 waveguide FE) tests.  Shared, cached model builders
(pytest fixtures would need a conftest.py; a cached function is enough)."""
from __future__ import annotations

import atexit
import copy
import functools
import shutil
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RAILS = ROOT / "geometry" / "rails"
_TMP = Path(tempfile.mkdtemp(prefix="rail_tests_"))
atexit.register(shutil.rmtree, _TMP, ignore_errors=True)


def rail_params(name: str = "bv50", mesh_scale: float = 1.0) -> dict:
    from pipeline.stages.rail_io import load_rail

    p = load_rail(RAILS / f"{name}.toml")
    if mesh_scale != 1.0:
        p = copy.deepcopy(p)
        for k in ("size_head", "size_web", "size_foot"):
            p["mesh"][k] *= mesh_scale
    return p


@functools.lru_cache(maxsize=None)
def mesh_path(name: str = "bv50", mesh_scale: float = 1.0) -> str:
    from geometry.rail_mesh import mesh_rail

    path = _TMP / f"{name}_{mesh_scale:g}.msh"
    mesh_rail(rail_params(name, mesh_scale), str(path))
    return str(path)


@functools.lru_cache(maxsize=None)
def assembled(name: str = "bv50", mesh_scale: float = 1.0):
    """(params, mesh, cell_tags, facet_tags, Assembled, materials, torsion props)."""
    from geometry.mesher import read_msh
    from solvers.rail import waveguide as wg

    p = rail_params(name, mesh_scale)
    mesh, ct, ft = read_msh(mesh_path(name, mesh_scale))
    asm = wg.assemble(mesh, ct, ft)
    mat = wg.material_moduli(p, asm)
    tors = wg.torsion_properties(mesh, ct)
    return p, mesh, ct, ft, asm, mat, tors


@functools.lru_cache(maxsize=None)
def rail_model(name: str = "bv50", mesh_scale: float = 1.0):
    from pipeline.stages.rail_io import build_rail_model

    return build_rail_model(rail_params(name, mesh_scale), mesh_path(name, mesh_scale))


def beam_params(model) -> dict:
    """Section and support properties of the FE model for the analytic
    beams (pipeline/validation/references/beam.py): vertical TBOEF and lateral-torsional."""
    p = model.rail
    t = model.props["torsion"]
    pad = model.props["pad"]
    E, nu, rho = p["material"]["E"], p["material"]["nu"], p["material"]["rho"]
    G = E / (2 * (1 + nu))
    return {
        "vertical": dict(EI=E * t["I_vertical"], kGA=0.4 * G * t["area"], m=rho * t["area"],
                         rhoI=rho * t["I_vertical"], k_s=p["pad"]["stiffness"],
                         eta_beam=p["material"]["loss_factor"], eta_support=p["pad"]["loss_factor"]),
        "lateral": dict(EI_l=E * t["I_lateral"], GJ=G * t["J"], EGamma=E * t["Gamma"], m=rho * t["area"],
                        rhoI_l=rho * t["I_lateral"], rhoI_pc=rho * (t["I_lateral"] + t["I_vertical"]),
                        z_c=t["z_centroid"], z_s=t["z_shear_centre"], k_y=pad["k_lateral"], k_r=pad["k_rocking"],
                        eta_beam=p["material"]["loss_factor"], eta_support=p["pad"]["loss_factor"]),
    }
