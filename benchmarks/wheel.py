"""Wheel-stage benchmark: mesh + all modes n = 0..N below f_max."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _stage(args, env):
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "pipeline", *args, "-q"], cwd=ROOT, env=env, check=True)
    return time.perf_counter() - t0


def bench_wheel_modes(wheel="c20") -> dict:
    """Mesh + all modes n = 0..N below f_max: cold (empty JIT cache) and warm."""
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, SQUEAL_BUILD_DIR=str(Path(tmp) / "build"), XDG_CACHE_HOME=str(Path(tmp) / "cache"))
        cold = _stage(["mesh", "--wheel", wheel], env) + _stage(["modes", "--wheel", wheel], env)
        warm_mesh = _stage(["mesh", "--wheel", wheel], env)
        warm_modes = _stage(["modes", "--wheel", wheel], env)
        w1 = _stage(["modes", "--wheel", wheel, "--workers", "1"], env)
        w = Path(tmp) / "build" / "wheels" / wheel
        meta = json.loads((w / "mesh.json").read_text())["payload"]
        rows = (w / "modes.csv").read_text().splitlines()[1:]
    return {"wheel": wheel, "cold": cold, "warm": warm_mesh + warm_modes, "warm_1worker": warm_mesh + w1,
            "nodes": meta["nodes"], "triangles": meta["triangles"], "modes": len(rows)}



def run() -> str:
    r = bench_wheel_modes()
    # P2 vector elements with 3 components: dofs = 3 x (vertices + edges); edges ~ vertices + triangles
    dofs = 3 * (r["nodes"] + r["nodes"] + r["triangles"] - 1)
    return f"""## Wheel modes (all C20 modes below 7 kHz, n = 0..10; target < 30 s on 2 cores)

| what | wall time |
|---|---|
| mesh + modes, cold (empty FFCx/dolfinx JIT cache, imports included), 2 worker processes | {r['cold']:.1f} s |
| mesh + modes, warm JIT cache, 2 worker processes | {r['warm']:.1f} s |
| mesh + modes, warm JIT cache, 1 process | {r['warm_1worker']:.1f} s |

Mesh: {r['nodes']} vertices, {r['triangles']} triangles (P2, about {dofs} dofs per harmonic);
{r['modes']} modes (flexible and rigid) below 7 kHz. Commands: `python -m pipeline mesh|modes --wheel c20`
in subprocesses (a cold run sets XDG_CACHE_HOME to an empty folder).
"""


if __name__ == "__main__":
    print(run())
