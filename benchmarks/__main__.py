"""Benchmarks: `make bench` -> docs/benchmarks.md.

Each benchmark runs the real stage entry points in subprocesses (so cold
start, imports and JIT compilation are counted where the issue asks for
them) and records the machine it ran on.
"""
from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "benchmarks.md"


def machine() -> str:
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = ""
    try:
        kb = int(Path("/proc/meminfo").read_text().split()[1])
        mem = f", {kb / 2**20:.0f} GiB RAM"
    except (OSError, ValueError, IndexError):
        pass
    return f"{cpu}, {os.cpu_count()} cores{mem}, {platform.system()} {platform.release()}, Python {platform.python_version()}"


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


def main() -> int:
    r = bench_wheel_modes()
    # P2 vector elements with 3 components: dofs = 3 x (vertices + edges); edges ~ vertices + triangles
    dofs = 3 * (r["nodes"] + r["nodes"] + r["triangles"] - 1)
    text = f"""# Benchmarks

Machine: {machine()}.
Produced by `make bench` (`benchmarks/__main__.py`) on {time.strftime('%Y-%m-%d')}; each figure is one
wall-clock run of the real stage commands in subprocesses.

## Wheel modes (issue: all C20 modes below 7 kHz, n = 0..10, < 30 s on 2 cores)

| what | wall time |
|---|---|
| mesh + modes, cold (empty FFCx/dolfinx JIT cache, imports included), 2 worker processes | {r['cold']:.1f} s |
| mesh + modes, warm JIT cache, 2 worker processes | {r['warm']:.1f} s |
| mesh + modes, warm JIT cache, 1 process | {r['warm_1worker']:.1f} s |

Mesh: {r['nodes']} vertices, {r['triangles']} triangles (P2, about {dofs} dofs per harmonic);
{r['modes']} modes (flexible and rigid) below 7 kHz.
"""
    OUT.parent.mkdir(exist_ok=True)
    tmp = OUT.with_suffix(".md.tmp")
    tmp.write_text(text)
    os.replace(tmp, OUT)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
