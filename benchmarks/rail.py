"""Rail benchmark: BV50 waveguide FE from the parameter file to receptances.

Issue target: >= 1000 frequencies x >= 200 distances in < 120 s on 2
cores, dispersion included.  The whole chain runs in a fresh subprocess
(imports and the dolfinx/FFCx JIT cache as the pipeline would see them):
mesh (gmsh) -> assembly -> pad calibration -> torsion -> SLEPc real-k
waves for the reduced basis -> dispersion curves of the supported rail
(both families, 31 wavenumbers 0..30 rad/m, f <= 6.5 kHz) -> receptances
G22, G33, G23 at the three contact points, 1000 frequencies
(25 Hz .. 6.5 kHz) x 200 distances (0 .. 10 m) -> decay rates.

    .venv/bin/python benchmarks/rail.py          # prints the markdown section
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

_SCRIPT = r"""
import json, sys, time
t0 = time.perf_counter()
sys.path.insert(0, {root!r})
import numpy as np
from geometry.rail_mesh import mesh_rail
from pipeline.stages.rail_io import build_rail_model, load_rail
from solvers import waveguide as wg, rail_response as rr
t_import = time.perf_counter() - t0
T = {{"import": t_import}}
p = load_rail({root!r} + "/geometry/rails/{rail}.toml")
t = time.perf_counter(); mesh_rail(p, {msh!r}); T["mesh"] = time.perf_counter() - t
t = time.perf_counter(); model = build_rail_model(p, {msh!r}); T["model (assembly, pad, torsion, basis waves)"] = time.perf_counter() - t
zc = model.props["torsion"]["z_centroid"]
t = time.perf_counter()
ks = np.linspace(0.0, 30.0, 31)
nb = 0
for name in ("sym", "anti"):
    d = wg.dispersion(model.families[name], ks, 6500.0, p, zc)
    nb += d["f"].shape[1]
T["dispersion (2 x 31 k, SLEPc)"] = time.perf_counter() - t
f = np.linspace(25.0, 6500.0, {nf}); x = np.linspace(0.0, 10.0, {nx})
t = time.perf_counter(); R = rr.receptances(model, f, x); T["receptances"] = time.perf_counter() - t
t = time.perf_counter(); D = rr.decay_rates(model, np.geomspace(25.0, 6500.0, 100)); T["decay rates (100 f)"] = time.perf_counter() - t
T["total"] = time.perf_counter() - t0
info = {{"dofs": {{n: int(fam.M.shape[0]) for n, fam in model.families.items()}},
        "reduced": {{"sym": model.sym.size, "anti": model.anti.size}}, "branches": nb,
        "G_shape": list(R["G"].shape), "finite": bool(np.all(np.isfinite(R["G"])))}}
print("RESULT" + json.dumps({{"T": T, "info": info}}))
"""


def bench(rail: str = "bv50", nf: int = 1000, nx: int = 200, cold: bool = False) -> dict:
    """One run in a fresh process; cold=True empties the FFCx/dolfinx JIT
    cache first (XDG_CACHE_HOME in a temporary folder)."""
    with tempfile.TemporaryDirectory() as tmp:
        msh = str(Path(tmp) / "rail.msh")
        code = _SCRIPT.format(root=str(ROOT), rail=rail, msh=msh, nf=nf, nx=nx)
        env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"))
        if cold:
            env["XDG_CACHE_HOME"] = str(Path(tmp) / "cache")
        t = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, check=True,
                             capture_output=True, text=True)
        wall = time.perf_counter() - t
    line = [ln for ln in out.stdout.splitlines() if ln.startswith("RESULT")][-1]
    res = json.loads(line[len("RESULT"):])
    res["wall"] = wall
    return res


def run() -> str:
    c = bench(cold=True)
    r = bench()
    T, info = r["T"], r["info"]
    rows = "\n".join(f"| {k} | {v:.1f} s | {c['T'][k]:.1f} s |" for k, v in T.items())
    return f"""## Rail

BV50 waveguide FE (issue: rail cross-section and waveguide FE with the pad): from
`geometry/rails/bv50.toml` to receptances G22, G33, G23 at the three contact points,
**1000 frequencies (25 Hz - 6.5 kHz) x 200 distances (0 - 10 m)**, dispersion included;
target < 120 s on 2 cores.  One fresh process (`benchmarks/rail.py`), single-threaded
(OMP_NUM_THREADS=1: OpenBLAS, Debian's libopenblas0-pthread, on one thread).

| phase | warm JIT cache | cold (empty JIT cache) |
|---|---|---|
{rows}
| subprocess wall time (start-up included) | {r['wall']:.1f} s | {c['wall']:.1f} s |

Half-section P2 model: {info['dofs']['sym']} dofs (symmetric family), {info['dofs']['anti']} (antisymmetric);
reduced wave bases {info['reduced']['sym']} + {info['reduced']['anti']}; {info['branches']} dispersion branches
below 6.5 kHz; receptance array {info['G_shape']} (points, distances, frequencies, 2, 2), all finite: {info['finite']}.
"""


if __name__ == "__main__":
    print(run())
