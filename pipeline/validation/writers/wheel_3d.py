"""docs/validation/22_wheel_3d.md: the Fourier-harmonic solver against a full 3D model of the C20 wheel (bore
clamped), on three 3D meshes (``pipeline.validation.revolved_wheel.study``, shared with the test that asserts its
criteria, tests/validation/test_wheel_3d.py).  A writer, run by `make validate`:

    OMP_NUM_THREADS=1 .venv/bin/python -m pipeline.validation.writers.wheel_3d
"""
from __future__ import annotations

from pipeline.validation.revolved_wheel import GEOM_ORDER, SIMPLIFY_TOL, SIZE_2D, Study, study
from pipeline.validation.writers import save_fragment


def markdown(study: Study) -> str:
    L = []
    L.append("## Harmonic solver vs full 3D model (C20 wheel, bore clamped)\n")
    L.append("Written by `pipeline/validation/writers/wheel_3d.py` (`make validate`; the 3D runs: "
             "`pipeline/validation/revolved_wheel.py`); its criteria are asserted by `tests/validation/test_wheel_3d.py`.\n")
    L.append(f"Geometry: C20 cross-section, mount 'clamped', outline polylines thinned by Douglas-Peucker "
             f"({SIMPLIFY_TOL * 1000:.2f} mm); the same outline is revolved 360 deg (Gmsh OCC) for the 3D model "
             f"and meshed in 2D for the harmonic solver. Steel E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3. "
             f"Bore clamped (all components).\n")
    L.append(f"Harmonic reference: P2 triangles, size {SIZE_2D * 1000:.0f} mm, {study.h2d_dofs} dofs "
             f"(2D convergence column: size {2 * SIZE_2D * 1000:.0f} mm). 3D: P2 tetrahedra, "
             f"{'curved (quadratic geometry)' if GEOM_ORDER > 1 else 'straight-sided'}, "
             f"SLEPc shift-invert + MUMPS LU, one core (OMP_NUM_THREADS=1); peak RSS is the process maximum so far. For n >= 1 both members of the 3D degenerate pair are listed; "
             f"MAC = mass-weighted fraction of the 3D mode in the span of the harmonic mode expanded to 3D "
             f"(cos and sin orientation).\n")
    L.append("### Meshes and cost\n")
    L.append("| 3D size (mm) | tets | dofs | mesh (s) | assemble + eigensolve (s) | modes | peak RSS (GB) |")
    L.append("|---:|---:|---:|---:|---:|---:|---:|")
    for run in study.runs:
        L.append(f"| {run['h'] * 1000:.0f} | {run['ncells']} | {run['ndofs']} | {run['t_mesh']:.1f} | "
                 f"{run['t_solve']:.1f} | {run['nconv']} | {run['peak_gb']:.2f} |")
    L.append("\n### Frequencies (Hz) and deviation of 3D from harmonic\n")
    head = "| n | mode | dominant | harmonic | harmonic (2D coarse) |"
    sep = "|---:|---:|---|---:|---:|"
    for run in study.runs:
        head += f" 3D h={run['h'] * 1000:.0f} mm | err % |"
        sep += "---:|---:|"
    head += " MAC (finest) |"
    sep += "---:|"
    L.append(head)
    L.append(sep)
    nrows = len(study.runs[0]["rows"])
    for i in range(nrows):
        r0 = study.runs[0]["rows"][i]
        n, m = r0["n"], r0["m"]
        line = f"| {n} | {m + 1} | {study.kinds[n][m]} | {r0['f_h']:.2f} | {study.harmonic_coarse[n][m]:.2f} |"
        for run in study.runs:
            r = run["rows"][i]
            line += " " + " / ".join(f"{f:.2f}" for f in r["f_3d"]) + " | " + \
                " / ".join(f"{100 * e:+.3f}" for e in r["err"]) + " |"
        line += " " + " / ".join(f"{x:.3f}" for x in study.runs[-1]["rows"][i]["mac"]) + " |"
        L.append(line)
    L.append("")
    return "\n".join(L)


def write() -> str:
    return save_fragment("22_wheel_3d.md", markdown(study()))


if __name__ == "__main__":
    write()
