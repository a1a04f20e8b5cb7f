"""Report: one self-contained Markdown file (figures copied beside it) that
gathers what the stages produced for a case.  Sections appear as their
stages exist: wheel, rail, contact, Green's functions, interaction, radiation,
and the studies found in build/studies/ (pipeline/study/report.py).

Output: build/report/<case>/report.md and its figures.
"""
from __future__ import annotations

import logging
import shutil

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB

from . import artifacts, paths

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

Parameters: `{paths.shown(src)}` (hash {prov['config_hash']}); model: {p['mount']['type']} mount, harmonics n = 0..{p['modes']['n_max']},
modes below {p['modes']['f_max']:.0f} Hz: {int(flex.sum())} flexible and {int((~flex).sum())} rigid half-wheelset modes.
The squeal candidates, axial modes with no nodal circle (n, 0, a): {', '.join(f'{f:.0f} Hz (n={n})' for f, n in zip(a['f_hz'][axial0], a['n'][axial0]))}.

![mode shapes of {wheel}](figures/{wheel}_gallery.png)

{chr(10).join(rows)}
"""


def rail_section(rail: str, figdir) -> str:
    from .rail_stage import load_rail_params

    p, src = load_rail_params(rail)
    rdir = paths.rail_dir(rail)
    a, prov = artifacts.load_npz(rdir / "rail.npz", "rail", p, make_target=f"rail RAIL={rail}")
    for fig in ("receptance", "dispersion"):
        shutil.copy2(rdir / f"{fig}.png", figdir / f"{rail}_{fig}.png")
    f, G = a["f_hz"], a["G"][:, 0]
    i300 = int(np.argmin(abs(f - 300.0)))
    pts = ", ".join(f"{1e3 * y:+.0f} mm" for y in a["point_y_m"])
    return f"""## Rail `{rail}`

Parameters: `{paths.shown(src)}` (hash {prov['config_hash']}). Section: {1e4 * float(a['section_area_m2']):.2f} cm^2,
{float(a['section_mass_per_m']):.2f} kg/m, I_vertical {1e8 * float(a['section_I_vertical_m4']):.0f} cm^4, I_lateral
{1e8 * float(a['section_I_lateral_m4']):.0f} cm^4; pad {float(a['pad_k_vertical_n_per_m2']) / 1e6:.0f} MN/m^2 vertical.
Receptances at the rail-head points {pts}; vertical point receptance at {f[i300]:.0f} Hz:
{20 * np.log10(abs(G[0, i300, 1, 1])):.1f} dB re 1 m/N.

![rail receptances](figures/{rail}_receptance.png)
![rail dispersion](figures/{rail}_dispersion.png)
"""


def contact_section(case: str, cfg: dict, figdir) -> str:
    a, _ = artifacts.load_npz(paths.case_dir(case) / "contact.npz", "contact", cfg, make_target=f"contact CASE={case}")
    shutil.copy2(paths.case_dir(case) / "contact_rf.png", figdir / f"{case}_contact_rf.png")
    p = a["p3_static"]
    ncontact = int((p > 0).sum())
    return f"""## Contact

Nominal contact point y^W = {1e3 * float(a['y_wheel']):+.0f} mm on the tread, y^R = {1e3 * float(a['y_rail']):+.0f} mm on
the rail head; grid {len(a['x'])} x {len(a['y'])} elements of {1e3 * float(a['dx']):.2f} x {1e3 * float(a['dy']):.2f} mm
(dx = v dt). Static preload: approach {1e6 * float(a['xi3_static']):.1f} um, {ncontact} elements in contact,
peak pressure {float(p.max()) / 1e9:.2f} GPa. Regularized friction curves (Kalker's TANG, steady state):

![friction curves](figures/{case}_contact_rf.png)
"""


def greens_section(case: str, figdir) -> str:
    from .greens_stage import greens_inputs

    cfg = greens_inputs(case)[-1]
    a, _ = artifacts.load_npz(paths.case_dir(case) / "greens.npz", "greens", cfg, make_target=f"greens CASE={case}")
    shutil.copy2(paths.case_dir(case) / "greens.png", figdir / f"{case}_greens.png")
    return f"""## Green's functions

Wheel: {len(a['wheel_f'])} modes at the contact point, Kropp's grid N_t = {int(a['wheel_nt'])} ({int(a['wheel_nt']) * float(a['dt']):.0f} s,
decayed to {float(a['wheel_decay_db']):.0f} dB); the time loop uses the equivalent recursive modal filters. Rail: moving Green's
function over {len(a['rail_kernel'])} lags ({len(a['rail_kernel']) * float(a['dt']) * 1e3:.0f} ms), its tail at
{float(a['rail_tail_ratio']):.1e} of the peak.

![Green's functions](figures/{case}_greens.png)
"""


def simulate_section(case: str, figdir) -> str:
    from .simulate_stage import simulate_config

    a, _ = artifacts.load_npz(paths.case_dir(case) / "simulate.npz", "simulate", simulate_config(case)[-1],
                              make_target=f"simulate CASE={case}")
    shutil.copy2(paths.case_dir(case) / "simulate.png", figdir / f"{case}_simulate.png")
    squeal = float(a["L_F2"]) >= SQUEAL_LEVEL_DB
    return f"""## Interaction

{int(a['n_steps'])} time steps, stopped: {a['stop_reason']}. L_F2 = {float(a['L_F2']):.1f} dB re 1 N, dominant frequency of F2
{float(a['f_dominant']):.1f} Hz: {'squeal' if squeal else 'no squeal (L_F2 < 10 dB)'}.

![force histories](figures/{case}_simulate.png)
"""


def radiate_section(case: str, figdir) -> str:
    from .radiate_stage import load_radiation_model, radiate_config

    a, _ = artifacts.load_npz(paths.case_dir(case) / "radiate.npz", "radiate",
                              radiate_config(case, load_radiation_model(case))[1], make_target=f"radiate CASE={case}")
    shutil.copy2(paths.case_dir(case) / "radiate.png", figdir / f"{case}_radiate.png")
    rows = ["| n | L_W (dB re 1e-12 W) | share | peak (Hz) | nearest mode of that n | its f (Hz) |", "|---:|---:|---:|---:|---|---:|"]
    for i, n in enumerate(a["harmonics"]):
        rows.append(f"| {n} | {a['harmonic_L_W'][i]:.1f} | {100 * a['harmonic_W'][i] / a['W_total']:.2f} % | "
                    f"{a['harmonic_f_peak'][i]:.1f} | {a['harmonic_mode_label'][i]} | {a['harmonic_mode_f'][i]:.1f} |"
                    if a["W_total"] > 0 else f"| {n} | -inf | - | - | - | - |")
    flag = ("" if a["meaningful"] else
            f" L_F2 = {float(a['L_F2']):.1f} dB < 10 dB: no squeal, the sound power is not meaningful (SPEC 6).")
    return f"""## Sound radiation

Thompson-Jones model (SPEC 5) driven by the final {float(a['stretch_s']):.2f} s of F2, F3: {len(a['tone_f'])} tones
fitted at their own frequencies plus the Hann-windowed residual.{flag}
Overall L_W = {float(a['L_W']):.1f} dB re 1e-12 W; loudest at {float(a['f_sound']):.1f} Hz, the
{a['sound_mode_label']} mode ({float(a['sound_mode_f']):.1f} Hz); dominant force frequency {float(a['f_dominant']):.1f} Hz.

![sound power](figures/{case}_radiate.png)

{chr(10).join(rows)}
"""


def listen_section(case: str, figdir) -> str:
    """'What a listener hears' (pipeline/listen_stage.py), when `make listen` has run for the
    current radiate and simulate artifacts; the spectrum and the WAV copied beside the report."""
    from .listen_stage import load_listening

    head = "## What a listener hears\n\n"
    if not (paths.case_dir(case) / "listen.npz").exists():
        return head + f"Not computed yet: `make listen CASE={case}` (then `make report CASE={case}`).\n"
    try:
        a, _ = load_listening(case)
    except artifacts.ArtifactError as e:
        return head + f"Not shown: {e}\n"
    cdir = paths.case_dir(case)
    for name in ("listen.png", "listen.wav", "listen.json"):
        shutil.copy2(cdir / name, figdir / f"{case}_{name}")
    sel = np.isfinite(a["band_L_p"]) & (a["band_L_p"] >= float(a["L_p"]) - 40)
    rows = ["| band (Hz) | " + " | ".join(f"{v:g}" for v in a["band_nominal"][sel]) + " |",
            "|---|" + "---:|" * int(sel.sum())]
    for key, name in (("band_L_p", "L_p (dB)"), ("band_L_pA", "L_pA (dB(A))")):
        rows.append(f"| {name} | " + " | ".join(f"{v:.1f}" for v in a[key][sel]) + " |")
    flag = ("" if a["meaningful"] else f" The case does not squeal (L_F2 = {float(a['L_F2']):.1f} dB < 10 dB): the "
            "levels are those of its non-squealing forces and the WAV is silent.")
    return head + f"""Receiver {float(a['distance']):g} m from the track centre, {float(a['height']):g} m above the top of the rail
(the squealing wheel's centre {float(a['r_direct']):.2f} m away; {a['ground']} ground {float(a['ground_depth']):g} m below
the rail, image source; {'a dipole along the axle' if str(a['directivity']) == 'dipole' else 'omnidirectional'};
air absorption ISO 9613-1).{flag}
L_p = {float(a['L_p']):.1f} dB, **L_pA = {float(a['L_pA']):.1f} dB(A)** (ground reflection added incoherently:
{float(a['L_p_incoherent']):.1f} dB, {float(a['L_pA_incoherent']):.1f} dB(A)); loudest at {float(a['f_peak']):.1f} Hz
(sound power peak {float(a['f_sound']):.1f} Hz). A pure tone over a rigid ground interferes with its reflection:
the coherent level depends on the exact position, the incoherent one is its average over positions. Bands within
40 dB of the overall level:

{chr(10).join(rows)}

![1/3-octave spectrum at the receiver](figures/{case}_listen.png)

The sound: [listen.wav](figures/{case}_listen.wav) ({float(a['wav_duration']):.2f} s, 44.1 kHz, 16 bit; the onset from
the simulation's growth phase, the limit cycle from {float(a['t_limit_cycle']):.2f} s). Calibration
([listen.json](figures/{case}_listen.json)): a 0 dBFS sine is {float(a['full_scale_sine_dB']):.1f} dB SPL; read back,
the limit cycle in the file is {float(a['wav_L_p']):.1f} dB at {float(a['wav_f_peak']):.1f} Hz.
"""


def run_report(case: str) -> str:
    from .case import resolve_case

    rc = resolve_case(case)
    cpath, c = rc.case_file, rc.case
    out = paths.build() / "report" / case
    figdir = out / "figures"
    (figdir / case).parent.mkdir(parents=True, exist_ok=True)  # figures/<case>_*.png; a curve wheel's in figures/<curve>/
    sections = [f"# Curve squeal report: case `{case}`\n\n{c['description']}\n\n"
                f"Case file `{paths.shown(cpath)}`: wheel `{c['wheel']}`, rail `{c['rail']}`, dy_WR = {1e3 * c['contact']['dy_wr']:.0f} mm, "
                f"{rc.friction.text}, gamma_y = {c['kinematics']['gamma_y']}, v = {3.6 * c['kinematics']['speed']:.0f} km/h.\n",
                wheel_section(c["wheel"], figdir), rail_section(c["rail"], figdir)]
    from .check import over_radial_note

    if over_radial_note(c):
        sections.insert(1, f"**Note.** {over_radial_note(c)}.\n")
    from .contact_stage import contact_inputs

    sections.append(contact_section(case, contact_inputs(case)[3], figdir))
    sections.append(greens_section(case, figdir))
    sections.append(simulate_section(case, figdir))
    sections.append(radiate_section(case, figdir))
    sections.append(listen_section(case, figdir))
    from .study.report import studies_section

    sections.append(studies_section(figdir))
    text = "\n".join(sections)
    with artifacts.atomic_write(out / "report.md") as tmp:
        tmp.write_text(text)
    log.info("report %s -> %s", case, out / "report.md")
    return str(out / "report.md")

