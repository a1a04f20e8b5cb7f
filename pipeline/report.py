"""Report: one self-contained Markdown file (figures copied beside it) that
gathers what the stages produced for a case.  Sections appear as their
stages exist; today: the wheel (mode table and mode-shape gallery).

Output: build/report/<case>/report.md and its figures.
"""
from __future__ import annotations

import logging
import shutil

from . import artifacts, paths
from .config import load
from .schemas import CASE

log = logging.getLogger("pipeline.report")


def wheel_section(wheel: str, figdir) -> str:
    from .wheel_stage import load_wheel

    p, src = load_wheel(wheel)
    wdir = paths.wheel_dir(wheel)
    a, prov = artifacts.load_npz(wdir / "modes.npz", "wheel-modes", p, make_target=f"modes WHEEL={wheel}")
    gallery = wdir / "shapes" / "gallery.png"
    if not gallery.exists():
        raise artifacts.ArtifactError(gallery, f"not found; run `make modes WHEEL={wheel}`")
    shutil.copy2(gallery, figdir / f"{wheel}_gallery.png")
    rows = ["| f (Hz) | n | m | class | modal mass (kg) | kind |", "|---:|---:|---:|---|---:|---|"]
    for f, n, m, c, mm, k in zip(a["f_hz"], a["n"], a["m"], a["cls"], a["modal_mass"], a["kind"]):
        rows.append(f"| {f:.1f} | {n} | {m} | {c} | {mm:.3g} | {k} |")
    flex = a["kind"] == "flexible"
    axial0 = flex & (a["cls"] == "a") & (a["m"] == 0)
    return f"""## Wheel `{wheel}`

Parameters: `{src}` (hash {prov['config_hash']}); model: {p['mount']['type']} mount, harmonics n = 0..{p['modes']['n_max']},
modes below {p['modes']['f_max']:.0f} Hz: {int(flex.sum())} flexible and {int((~flex).sum())} rigid half-wheelset modes.
The squeal candidates, axial modes with no nodal circle (n, 0, a): {', '.join(f'{f:.0f} Hz (n={n})' for f, n in zip(a['f_hz'][axial0], a['n'][axial0]))}.

![mode shapes of {wheel}](figures/{wheel}_gallery.png)

{chr(10).join(rows)}
"""


def run_report(case: str) -> str:
    cpath = paths.case_file(case)
    c = load(cpath, CASE)
    out = paths.BUILD / "report" / case
    figdir = out / "figures"
    figdir.mkdir(parents=True, exist_ok=True)
    sections = [f"# Curve squeal report: case `{case}`\n\n{c['description']}\n\n"
                f"Case file `{cpath}`: wheel `{c['wheel']}`, rail `{c['rail']}`, dy_WR = {1e3 * c['contact']['dy_wr']:.0f} mm, "
                f"mu = {c['friction']['mu']}, gamma_y = {c['kinematics']['gamma_y']}, v = {3.6 * c['kinematics']['speed']:.0f} km/h.\n",
                wheel_section(c["wheel"], figdir)]
    text = "\n".join(sections)
    with artifacts.atomic_write(out / "report.md") as tmp:
        tmp.write_text(text)
    log.info("report %s -> %s", case, out / "report.md")
    return str(out / "report.md")

