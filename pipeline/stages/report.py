"""Report: one self-contained Markdown file (figures copied beside it) that
gathers what the stages produced for a case.  Sections appear as their
stages exist: wheel, rail, contact, Green's functions, interaction, radiation,
and the studies found in build/studies/ (pipeline/study/report_section.py).

Output: build/report/<case>/report.md and its figures.
"""
from __future__ import annotations

import logging
import shutil

import numpy as np

from solvers.constants import SQUEAL_LEVEL_DB

from pipeline.store import artifacts, paths

from pipeline.stages.report_headline import headline, headline_markdown, stability_of
from pipeline.stages.wheel import load_wheel
from pipeline.stages.rail import load_rail_params
from postprocess.plots.contact import friction_curves_figure, mark_operating_slip, operating_point
from pipeline.store.atomic import save_figure
from pipeline.stages.greens import greens_inputs
from pipeline.stages.simulate import simulate_config
from pipeline.stages.radiate import load_radiation_model, radiate_config
from pipeline.stages.listen import listen_files, listener_inputs, load_listening, receiver_tag, receivers
from pipeline.stages.passby import passby_files
from pipeline.config.case import resolve_case
from pipeline.config.check import outer_wheel_note, over_radial_note
from pipeline.stages.listen_exports import case_vtk
from pipeline.study.report_section import studies_section
from pipeline.stages.report_html import write_html

log = logging.getLogger("pipeline.stages.report")


def flat(case: str) -> str:
    """The case's name in figure file names (a curve wheel's case 'r150/a1i' -> 'r150_a1i')."""
    return case.replace("/", "_")


def wheel_section(wheel: str, figdir) -> str:
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


def contact_section(case: str, cfg: dict, figdir, c: dict | None = None) -> str:
    """The contact; the friction curves redrawn with the case's operating slip marked (``c``: the case)."""
    a, _ = artifacts.load_npz(paths.case_dir(case) / "contact.npz", "contact", cfg, make_target=f"contact CASE={case}")
    op = ""
    if c is not None:
        kin, mu = c["kinematics"], c["friction"].get("mu")
        mu = float("nan") if mu is None else float(mu)       # a friction law without a Coulomb mu: the slip only
        s_op, mu_op = operating_point(a, kin["speed"], kin["gamma_y"], kin.get("gamma_x", 0.0), mu)
        fig = friction_curves_figure(a, f"{case}: dy_WR = {1e3 * c['contact']['dy_wr']:.0f} mm")
        save_figure(mark_operating_slip(fig, a, s_op, mu), figdir / f"{flat(case)}_contact_rf.png", dpi=100)
        op = (f" The case rolls at the slip s = |gamma| v = {s_op:.3f} m/s (gamma_y = {kin['gamma_y']:#.4g}, "
              f"v = {3.6 * kin['speed']:.0f} km/h)" + (f", where mu_RF = {mu_op:.3f} of mu = {mu:g}"
                                                      if np.isfinite(mu_op) else "") + " (marked).")
    else:
        shutil.copy2(paths.case_dir(case) / "contact_rf.png", figdir / f"{flat(case)}_contact_rf.png")
    p = a["p3_static"]
    ncontact = int((p > 0).sum())
    return f"""## Contact

Nominal contact point y^W = {1e3 * float(a['y_wheel']):+.0f} mm on the tread, y^R = {1e3 * float(a['y_rail']):+.0f} mm on
the rail head; grid {len(a['x'])} x {len(a['y'])} elements of {1e3 * float(a['dx']):.2f} x {1e3 * float(a['dy']):.2f} mm
(dx = v dt). Static preload: approach {1e6 * float(a['xi3_static']):.1f} um, {ncontact} elements in contact,
peak pressure {float(p.max()) / 1e9:.2f} GPa. Regularized friction curves (Kalker's TANG, steady state).{op}

![friction curves](figures/{flat(case)}_contact_rf.png)
"""


def greens_section(case: str, figdir) -> str:
    cfg = greens_inputs(case)[-1]
    a, _ = artifacts.load_npz(paths.case_dir(case) / "greens.npz", "greens", cfg, make_target=f"greens CASE={case}")
    shutil.copy2(paths.case_dir(case) / "greens.png", figdir / f"{flat(case)}_greens.png")
    return f"""## Green's functions

Wheel: {len(a['wheel_f'])} modes at the contact point; Kropp's grid of N_t = {int(a['wheel_nt'])} samples of dt =
{1e6 * float(a['dt']):.0f} us (the kernel has decayed to {float(a['wheel_decay_db']):.0f} dB within N_t / 2 samples); the time
loop uses the equivalent recursive modal filters. Rail: moving Green's function of {len(a['rail_kernel'])} lags of dt, its
tail at {float(a['rail_tail_ratio']):.1e} of the peak.

![Green's functions](figures/{flat(case)}_greens.png)
"""


def simulate_section(case: str, figdir) -> str:
    a, _ = artifacts.load_npz(paths.case_dir(case) / "simulate.npz", "simulate", simulate_config(case)[-1],
                              make_target=f"simulate CASE={case}")
    shutil.copy2(paths.case_dir(case) / "simulate.png", figdir / f"{flat(case)}_simulate.png")
    squeal = float(a["L_F2"]) >= SQUEAL_LEVEL_DB
    return f"""## Interaction

{int(a['n_steps'])} time steps, stopped: {a['stop_reason']}. L_F2 = {float(a['L_F2']):.1f} dB re 1 N, dominant frequency of F2
{float(a['f_dominant']):.1f} Hz: {'squeal' if squeal else 'no squeal (L_F2 < 10 dB)'}.

![force histories](figures/{flat(case)}_simulate.png)
"""


def radiate_section(case: str, figdir) -> str:
    a, _ = artifacts.load_npz(paths.case_dir(case) / "radiate.npz", "radiate",
                              radiate_config(case, load_radiation_model(case))[1], make_target=f"radiate CASE={case}")
    shutil.copy2(paths.case_dir(case) / "radiate.png", figdir / f"{flat(case)}_radiate.png")
    rows = ["| n | L_W (dB re 1e-12 W) | share | peak (Hz) | nearest mode of that n | its f (Hz) |", "|---:|---:|---:|---:|---|---:|"]
    for i, n in enumerate(a["harmonics"]):
        rows.append(f"| {n} | {a['harmonic_L_W'][i]:.1f} | {100 * a['harmonic_W'][i] / a['W_total']:.2f} % | "
                    f"{a['harmonic_f_peak'][i]:.1f} | {a['harmonic_mode_label'][i]} | {a['harmonic_mode_f'][i]:.1f} |"
                    if a["W_total"] > 0 else f"| {n} | -inf | - | - | - | - |")
    flag = ("" if a["meaningful"] else
            f" L_F2 = {float(a['L_F2']):.1f} dB < 10 dB: no squeal, the sound power is not meaningful (docs/physics.md section 6).")
    return f"""## Sound radiation

Thompson-Jones model (docs/physics.md section 5) driven by the final {float(a['stretch_s']):.2f} s of F2, F3: {len(a['tone_f'])} tones
fitted at their own frequencies plus the Hann-windowed residual.{flag}
Overall L_W = {float(a['L_W']):.1f} dB re 1e-12 W; loudest at {float(a['f_sound']):.1f} Hz, the
{a['sound_mode_label']} mode ({float(a['sound_mode_f']):.1f} Hz); dominant force frequency {float(a['f_dominant']):.1f} Hz.

![sound power](figures/{flat(case)}_radiate.png)

{chr(10).join(rows)}
"""


def stability_section(case: str, figdir) -> str:
    """The stability screen (pipeline/stages/stability.py): every closed-loop pole, fastest first."""
    head = "## Stability screen\n\n"
    st = stability_of(case)
    if st is None:
        return head + f"Not computed (or stale): `make stability CASE={case}` (then `make report CASE={case}`).\n"
    shutil.copy2(paths.case_dir(case) / "stability.png", figdir / f"{flat(case)}_stability.png")
    order = np.argsort(-st["sigma"])
    rows = ["| pole | f (Hz) | growth rate sigma (1/s) | open-loop f (Hz) |", "|---|---:|---:|---:|"]
    for k in order:
        fo = float(st["f_open"][k])
        rows.append(f"| {st['label'][k]} | {float(st['f_hz'][k]):.1f} | {float(st['sigma'][k]):+.3f} | "
                    f"{fo:.1f} |" if np.isfinite(fo) else
                    f"| {st['label'][k]} (wheelset on the track) | {float(st['f_hz'][k]):.1f} | "
                    f"{float(st['sigma'][k]):+.3f} | - |")
    unstable = [str(st["label"][k]) for k in order if st["sigma"][k] > 0]
    return head + f"""The time loop linearised about steady rolling (mu_RF = {float(st['mu0']):.3f}, slope {float(st['dmu']):.3g} s/m at
the operating slip): {len(order)} closed-loop poles, {len(unstable)} growing ({', '.join(unstable) or 'none'}). A growing pole is a
mode that can squeal; the time loop decides which one wins and how loud.

![closed-loop poles](figures/{flat(case)}_stability.png)

{chr(10).join(rows)}
"""


def listen_section(case: str, figdir) -> str:
    """'What a listener hears' (pipeline/stages/listen.py): every receiver computed, side by side, and the
    case's own one in detail (its spectrum, bands, WAV), when `make listen` has run for the current
    radiate and simulate artifacts; its files copied beside the report."""
    head = "## What a listener hears\n\n"
    tags = receivers(case)
    if not tags:
        return head + f"Not computed yet: `make listen CASE={case}` (then `make report CASE={case}`).\n"
    found, provs, notes = {}, {}, []
    for tag in tags:
        try:
            found[tag], provs[tag] = load_listening(case, tag)
        except artifacts.ArtifactError as e:
            notes.append(f"Receiver {tag} not shown: {e}")
    if not found:
        return head + "\n".join(notes) + "\n"
    lis = listener_inputs(case)[2]
    own = receiver_tag(lis["distance"], lis["height"])
    tag = own if own in found else next(iter(found))
    a = found[tag]
    side = ["| receiver | distance (m) | height (m) | L_p (dB) | L_pA (dB(A)) | L_pA, ground incoherent | loudest (Hz) |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for t_, b in found.items():
        side.append(f"| {t_}{' (the case' + chr(39) + 's)' if t_ == own else ''} | {float(b['distance']):g} | "
                    f"{float(b['height']):g} | {float(b['L_p']):.1f} | {float(b['L_pA']):.1f} | "
                    f"{float(b['L_pA_incoherent']):.1f} | {float(b['f_peak']):.1f} |")
    files = listen_files(case, tag)
    names = {k: f"{flat(case)}_{files[k].name}" for k in ("png", "wav", "json", "bands")}
    for k, name in names.items():
        shutil.copy2(files[k], figdir / name)
    sel = np.isfinite(a["band_L_p"]) & (a["band_L_p"] >= float(a["L_p"]) - 40)
    rows = ["| band (Hz) | " + " | ".join(f"{v:g}" for v in a["band_nominal"][sel]) + " |",
            "|---|" + "---:|" * int(sel.sum())]
    for key, name in (("band_L_p", "L_p (dB)"), ("band_L_pA", "L_pA (dB(A))")):
        rows.append(f"| {name} | " + " | ".join(f"{v:.1f}" for v in a[key][sel]) + " |")
    flag = ("" if a["meaningful"] else f" The case does not squeal (L_F2 = {float(a['L_F2']):.1f} dB < 10 dB): the "
            "levels are those of its non-squealing forces and the WAV is silent.")
    return head + f"""{chr(10).join(side)}

{' '.join(notes)}
Receiver {tag}: {float(a['distance']):g} m from the track centre, {float(a['height']):g} m above the top of the rail
(the squealing wheel's centre {float(a['r_direct']):.2f} m away; {a['ground']} ground {float(a['ground_depth']):g} m below
the rail, image source; {'a dipole along the axle' if str(a['directivity']) == 'dipole' else 'omnidirectional'};
air absorption ISO 9613-1).{flag}
L_p = {float(a['L_p']):.1f} dB, **L_pA = {float(a['L_pA']):.1f} dB(A)** (ground reflection added incoherently:
{float(a['L_p_incoherent']):.1f} dB, {float(a['L_pA_incoherent']):.1f} dB(A)); loudest at {float(a['f_peak']):.1f} Hz
(sound power peak {float(a['f_sound']):.1f} Hz). A pure tone over a rigid ground interferes with its reflection:
the coherent level depends on the exact position, the incoherent one is its average over positions. Bands within
40 dB of the overall level ([all bands, CSV](figures/{names['bands']})):

{chr(10).join(rows)}

![1/3-octave spectrum at the receiver](figures/{names['png']})

The sound: [{files['wav'].name}](figures/{names['wav']}) ({float(a['wav_duration']):.2f} s, 44.1 kHz, 16 bit; the onset from
the simulation's growth phase, the limit cycle from {float(a['t_limit_cycle']):.2f} s). Calibration
([{files['json'].name}](figures/{names['json']})): a 0 dBFS sine is {float(a['full_scale_sine_dB']):.1f} dB SPL; read back,
the limit cycle in the file is {float(a['wav_L_p']):.1f} dB at {float(a['wav_f_peak']):.1f} Hz.
{passby_section(case, tag, figdir, provs[tag]["config_hash"])}"""


def passby_section(case: str, tag: str, figdir, listen_hash: str) -> str:
    """The pass-by at receiver ``tag`` (pipeline/stages/passby.py), when the listen stage wrote it for the
    listening artifact of hash ``listen_hash``."""
    files = passby_files(case, tag)
    if not files["npz"].exists():
        return ""
    b, prov = artifacts.load_npz(files["npz"], "passby")
    if prov["config"].get("listen") != listen_hash:
        return f"\n### Pass-by\n\nNot shown: {files['npz'].name} is stale; run `make listen CASE={case}`.\n"
    for k in ("png", "wav"):
        shutil.copy2(files[k], figdir / f"{flat(case)}_{files[k].name}")
    return f"""
### Pass-by

{int(b['n_bogies'])} squealing wheels (one per bogie, {float(b['bogie_spacing']):g} m apart) passing at
{3.6 * float(b['speed']):.0f} km/h, heard at receiver {tag} (distance, dipole directivity, Doppler, ground
reflection and air absorption as above; each wheel with its own phase): **L_pAeq = {float(b['L_Aeq']):.1f} dB(A)**
over the {float(b['T']):.1f} s passage (the first squealing wheel {float(b['window']):g} m before the receiver to the last
one {float(b['window']):g} m past it), **L_AFmax = {float(b['L_AFmax']):.1f} dB(A)** (IEC 61672-1 time weighting F),
L_AE = {float(b['L_AE']):.1f} dB(A). ({100 * float(b['kept_share']):.2f} % of the sound power synthesized: the tones and
the strongest residual bins.)

![pass-by](figures/{flat(case)}_{files['png'].name})

The passage: [{files['wav'].name}](figures/{flat(case)}_{files['wav'].name}).
"""


def exports_section(case: str, vtk: dict) -> str:
    """Where the exported tables and 3D files are (pipeline/stages/listen_exports.py)."""
    cdir = paths.shown(paths.case_dir(case))
    return f"""## Exports

- Spectra and bands (CSV, in `{cdir}/`): `radiate_spectrum.csv` (sound power per tone and bin),
  `radiate_forces.csv` and `radiate_tones.csv` (contact forces), `radiate_bands.csv` (sound power per
  1/3-octave band), `listen_<receiver>_bands.csv` (levels at each receiver).
- Noise mapping: `lw_railway.csv`, the squeal as a row of NoiseModelling's railway source table LW_RAILWAY
  (bands 50 Hz-10 kHz per period; CNOSSOS-EU line source at 0.5 m, rolling-noise directivity, one squealing
  passage per hour: add 10 lg Q for Q an hour; `postprocess/exports.py`).
- 3D (ParaView; Warp By Vector): `vtk/{vtk['modes'].name}` (every wheel mode){'' if 'ods' not in vtk else
    f", `vtk/{vtk['ods'].name}` (the squealing wheel's operating deflection shape, one period, a time series)"}.
"""


def case_line(cpath, c: dict, friction: str) -> str:
    """The report's line of the case's inputs, in engineering units, 4 significant digits (a curve wheel's
    creepages are the steady curving's, e.g. -0.015402692482766116)."""
    kin = c["kinematics"]
    return (f"Case file `{paths.shown(cpath)}`: wheel `{c['wheel']}`, rail `{c['rail']}`, "
            f"dy_WR = {1e3 * c['contact']['dy_wr']:.1f} mm, {friction}, creepages gamma_y = {kin['gamma_y']:#.4g}, "
            f"gamma_x = {kin.get('gamma_x', 0.0):#.4g} (slip / speed, dimensionless), "
            f"v = {3.6 * kin['speed']:.0f} km/h.\n")


def run_report(case: str) -> str:
    rc = resolve_case(case)
    cpath, c = rc.case_file, rc.case
    out = paths.build() / "report" / case
    figdir = out / "figures"
    (figdir / case).parent.mkdir(parents=True, exist_ok=True)  # figures/<case>_*.png; a curve wheel's in figures/<curve>/
    sections = [f"# Curve squeal report: case `{case}`\n\n{c['description']}\n\n"
                + case_line(cpath, c, rc.friction.text),
                wheel_section(c["wheel"], figdir), rail_section(c["rail"], figdir)]

    note = over_radial_note(c) or outer_wheel_note(c)
    if note:
        sections.insert(1, f"**Note.** {note}.\n")
    from pipeline.stages.contact import contact_inputs  # lazy: brings in numba, rocket_fft, scipy

    sections.append(contact_section(case, contact_inputs(case)[3], figdir, c))
    sections.append(greens_section(case, figdir))
    sections.append(simulate_section(case, figdir))
    sections.append(stability_section(case, figdir))
    sections.append(radiate_section(case, figdir))
    sections.append(listen_section(case, figdir))

    sim, rad, model = case_results(case)
    sections.append(exports_section(case, case_vtk(case, model, rad)))

    sections.append(studies_section(figdir))
    # the headline block (pipeline/stages/report_headline.py) right under the title, before anything else
    sections[0] = sections[0].replace("\n\n", f"\n\n{headline_markdown(headline(case, sim, rad))}\n", 1)
    sections[0] += "The model: `docs/physics.md`; every input key: `docs/inputs.md`.\n"
    text = "\n".join(sections)
    with artifacts.atomic_write(out / "report.md") as tmp:
        tmp.write_text(text)

    write_html(out / "report.md", f"Curve squeal report: {case}")
    log.info("report %s -> %s, report.html", case, out / "report.md")
    return str(out / "report.md")


def case_results(case: str):
    """(simulate.npz, radiate.npz, the radiation model) of the case, checked against its inputs."""
    cdir = paths.case_dir(case)
    sim, _ = artifacts.load_npz(cdir / "simulate.npz", "simulate", simulate_config(case)[-1],
                                make_target=f"simulate CASE={case}")
    model = load_radiation_model(case)
    rad, _ = artifacts.load_npz(cdir / "radiate.npz", "radiate", radiate_config(case, model)[1],
                                make_target=f"radiate CASE={case}")
    return sim, rad, model
