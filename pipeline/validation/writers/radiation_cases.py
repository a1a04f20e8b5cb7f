"""The radiation writer's sections on force spectra, the built C20 (surfaces, unit-force sound power) and the
default case's sound power (docs/validation/70_radiation.md, assembled by ``pipeline.validation.writers.radiation``)."""
from __future__ import annotations

import time

import numpy as np

from solvers.constants import F_MAX_HZ

from solvers.radiation import surfaces as SF, thompson_jones as R
from solvers.spectra import amplitude_spectrum, dominant_frequency, force_level
from solvers.wheel.receptance import modal_damping

from pipeline.store.paths import ROOT
from pipeline.validation.references import node_average as NA
from pipeline.validation.references.radiation import ART, load_c20
from pipeline.validation.writers import DOCS, pyplot, save_figure
from geometry.wheel import surface_radii
from pipeline.store.artifacts import ArtifactError
from pipeline.stages.radiate import compute_radiation, plot_radiation, sound_power_of_forces


def spectra_section() -> list[str]:
    dt, N, A = 36e-6, 20000, 2.5e3
    t = np.arange(N) * dt
    ef = ea = 0.0
    for f0 in np.linspace(200, 6000, 301):
        for ph in (0.0, 1.3):
            f, X = amplitude_spectrum(6.5e4 + A * np.cos(2 * np.pi * f0 * t + ph), dt)
            fp, amp = dominant_frequency(f, X)
            ef, ea = max(ef, abs(fp / f0 - 1)), max(ea, abs(amp / A - 1))
    # peak bin alone (no interpolation)
    worst_bin = 0.0
    for f0 in np.linspace(200, 6000, 301):
        f, X = amplitude_spectrum(A * np.cos(2 * np.pi * f0 * t), dt)
        worst_bin = max(worst_bin, abs(np.abs(X).max() / A - 1))
    dt2 = 25e-6
    t2 = np.arange(8000) * dt2
    lf = force_level(-3000 + 1000 * np.sin(2 * np.pi * 2000 * t2 + 0.3))
    return [
        "### Force spectra and L_F2 (solvers/spectra.py)",
        "",
        "Hann window (periodic), mean removed, one-sided, amplitude-corrected (2 / sum w: a sinusoid of amplitude A "
        "on a bin gives A). A tone A = 2.5 kN on a 65 kN mean, dt = 36 us, N = 20000 (bin 1.39 Hz), 301 frequencies "
        f"200 Hz..6 kHz, two phases: dominant frequency by the log-magnitude parabola within {ef:.1e} "
        f"(criterion 1e-3), amplitude with the Hann scalloping correction within {ea:.1e} (criterion 1e-2); the "
        f"largest bin alone would be low by up to {100 * worst_bin:.1f} % at these frequencies (Hann scalloping: "
        "1.42 dB = 15 % at half a bin). "
        f"L_F2 of 1 kN amplitude on a -3 kN mean: {lf:.4f} dB = 20 log10(1000/sqrt 2) = "
        f"{20 * np.log10(1000 / np.sqrt(2)):.4f} dB. Power-correct alternative (`scaling='power'`, sqrt(2 / (N sum "
        "w^2))): the bins' squares sum to the mean square; a Hann tone's RMS-scaled bins summed give 1.5 times it "
        "(+1.76 dB), so an overall L_W summed over bins should use 'power' scaling, a tone's amplitude 'amplitude' "
        "scaling. `sound_power` expects RMS force amplitudes ('rms' scaling) by default.",
        "",
    ]


def c20_section() -> list[str]:
    if not ART.exists():
        return ["### C20: unit-force sound power", "", "(C20 modal artifact not built: `make modes`.)", ""]
    t0 = time.perf_counter()
    d, p, s, nodes, c = load_c20()
    s_mean = SF.radiation_surfaces({**_radii(p)}, web_thickness="mean")
    zeta = modal_damping(d["n"], d["m"], d["cls"], d["kind"], d["zeta_suspension"])
    f = R.frequency_grid(100.0, F_MAX_HZ, d["f_hz"], zeta)
    lat = NA.unit_force_power(f, d, s, nodes, c, "lateral")
    rad = NA.unit_force_power(f, d, s, nodes, c, "radial")
    lat_flex = NA.unit_force_power(f, d, s, nodes, c, "lateral", rigid=False)
    rad_flex = NA.unit_force_power(f, d, s, nodes, c, "radial", rigid=False)
    lat_t = NA.unit_force_power(f, d, s, nodes, c, "lateral", torsion_points=d["points"])
    lat_mean = NA.unit_force_power(f, d, s_mean, nodes, c, "lateral")
    rad_mean = NA.unit_force_power(f, d, s_mean, nodes, c, "radial")
    t_run = time.perf_counter() - t0
    z_rc = p["axle"]["rolling_circle_z"]
    pc = d["points"][c]
    seg = [k[len("boundary_"):] for k in d if k.startswith("boundary_") and k != "boundary_names" and c in d[k]]
    unit_force_plot(lat, rad, d)

    def lvl(res, fc):
        i = int(np.argmin(np.abs(f - fc)))
        return R.level_db(res.result.W[i])

    def table(u):
        rows = ["| n | peak level (dB re 1e-12 W, 1 N) | at (Hz) | band power, white 1 N^2/Hz (dB) | share |",
                "|---:|---:|---:|---:|---:|"]
        for r_ in u.table:
            rows.append(f"| {r_['n']} | {r_['L_peak_dB']:.1f} | {r_['f_peak_hz']:.1f} | {r_['L_band_dB']:.1f} | "
                        f"{100 * r_['share']:.1f} % |")
        return rows

    ann = " | ".join(f"{s.radii[q]:.4f}-{s.radii[q + 1]:.4f}" for q in range(5))
    k = int(np.argmin(np.abs(d["f_hz"] - lat.f_peak)))
    kr = int(np.argmin(np.abs(d["f_hz"] - rad.f_peak)))
    return [
        "### C20: surfaces, node sets and the unit-force sound power",
        "",
        f"From `build/wheels/c20/modes.npz` ({d['f_hz'].size} modes: {int(np.sum(d['kind'] != 'flexible'))} rigid "
        "half-wheelset modes and the flexible modes to 7 kHz) and the outline of its resolved configuration "
        "(`geometry.wheel.surface_radii` + `wheel_segments`).",
        "",
        "| annulus (m) | " + ann + " |",
        "|---|---:|---:|---:|---:|---:|",
        "| S_aq, both faces (m^2) | " + " | ".join(f"{x:.4f}" for x in s.S_a) + " |",
        "| boundary nodes | " + " | ".join(str(a.size) for a in nodes.axial) + " |",
        "",
        f"r_1 = hub radius {s.radii[0]:.4f} m, r_5 = inner tyre radius at mid-tyre {s.r_in:.4f} m, r_6 = r = "
        f"{s.r:.3f} m; r_2..r_4 divide the web evenly. Radial surface: {nodes.radial.size} nodes (tread, flange, "
        f"tyre inner), S_r = {s.S_r:.4f} m^2; S_t = {s.S_t:.3e} m^4. Web thickness at the tyre, measured on the "
        f"outline: {s.w_web * 1e3:.1f} mm axial (the fitted web is {p['web']['thickness_tyre'] * 1e3:.1f} mm normal "
        f"thickness at the tyre, inclined; {p['web']['thickness_hub'] * 1e3:.1f} mm at the hub), S_out = "
        f"{s.S_out:.4f}, S_in = {s.S_in:.4f} m^2, Gamma = {s.gamma:.3f} (with the mean web thickness "
        f"{s_mean.w_web * 1e3:.1f} mm of `surface_radii`: Gamma = {s_mean.gamma:.3f}, S_r = {s_mean.S_r:.4f} m^2).",
        "",
        f"Contact: y^W = -32 mm (SPEC 2, dy_WR = -15 mm) lies on the flange-root fillet, which the outline names "
        f"`flange` (the `tread` segment starts at y^W = {1e3 * (d['points'][d['boundary_tread'], 1].min() - z_rc):.1f} mm); "
        f"nearest running-surface node {c} at r = {pc[0]:.4f} m, y^W = {1e3 * (pc[1] - z_rc):.1f} mm "
        f"(segment {', '.join(seg)}). Frequencies: `frequency_grid` 100 Hz - 6.5 kHz, 400 per decade plus 41 "
        f"points over f_r (1 +- 50 zeta_r) around each mode ({f.size} frequencies; every peak resolved, -3 dB band "
        f"2 zeta f_r = 0.09 Hz at 434 Hz). Computing the seven unit-force cases below took {t_run:.2f} s.",
        "",
        "Unit lateral force (F2 = 1 N RMS) at the contact node:",
        "",
        f"- loudest frequency {lat.f_peak:.1f} Hz, the ({d['n'][k]},{d['m'][k]},{d['cls'][k]}) mode, "
        f"{lat.L_peak:.1f} dB re 1e-12 W for 1 N; band power for a white unit force (1 N^2/Hz, 100 Hz - 6.5 kHz) "
        f"{lat.L_band:.1f} dB;",
        f"- at 1 kHz (between peaks) {lvl(lat, 1000):.1f} dB, at 3 kHz {lvl(lat, 3000):.1f} dB;",
        f"- rigid half-wheelset modes excluded: band {lat_flex.L_band:.2f} dB (included {lat.L_band:.2f} dB); at "
        f"100 Hz {lvl(lat_flex, 100):.1f} vs {lvl(lat, 100):.1f} dB, above 1 kHz within 0.5 dB;",
        f"- with the torsion term (tyre rotation from a rigid fit of the tyre nodes, sigma_t, S_t): band "
        f"{lat_t.L_band:.2f} dB (+{lat_t.L_band - lat.L_band:.2f} dB), peak torsion part "
        f"{R.level_db(lat_t.result.W_torsion.sum(0).max()):.1f} dB;",
        f"- with the mean web thickness: band {lat_mean.L_band:.2f} dB.",
        "",
        *table(lat),
        "",
        "Unit radial force (F3 = 1 N RMS) at the same node: loudest "
        f"{rad.f_peak:.1f} Hz (({d['n'][kr]},{d['m'][kr]},{d['cls'][kr]})), {rad.L_peak:.1f} dB, band {rad.L_band:.1f} "
        f"dB; rigid modes excluded: band {rad_flex.L_band:.2f} dB, at 100 Hz {lvl(rad_flex, 100):.1f} vs "
        f"{lvl(rad, 100):.1f} dB (the rigid bounce mode is the wheel's whole low-frequency radial motion); mean web "
        f"thickness: band {rad_mean.L_band:.2f} dB.",
        "",
        *table(rad),
        "",
        "![Unit-force sound power of the C20](validation/radiation_unit_force.png)",
        "",
    ]


def _radii(p):
    return surface_radii(p)


def unit_force_plot(lat, rad, d):
    plt = pyplot()
    fig, axs = plt.subplots(2, 1, figsize=(10, 8), sharex=True)
    cm = plt.get_cmap("tab10")
    for ax, u, title in ((axs[0], lat, "unit lateral force F2 = 1 N"), (axs[1], rad, "unit radial force F3 = 1 N")):
        res = u.result
        ax.semilogx(res.f, R.level_db(res.W), "k", lw=1.6, label="total")
        for h, n in enumerate(res.harmonics):
            ax.semilogx(res.f, R.level_db(res.W_n[h]), color=cm(int(n) % 10), lw=0.8, label=f"n = {n}")
        top = R.level_db(res.W).max()
        ax.set_ylim(top - 90, top + 5)
        ax.set_ylabel("L_W (dB re 1e-12 W per N^2)")
        ax.set_title(f"C20, {title} at y^W = -32 mm: peak {u.L_peak:.1f} dB at {u.f_peak:.0f} Hz")
        ax.grid(True, which="both", alpha=0.3)
    axs[0].legend(fontsize=7, ncol=4, loc="lower right")
    axs[1].set_xlabel("frequency (Hz)")
    axs[1].set_xlim(100, F_MAX_HZ)
    fig.tight_layout()
    save_figure(fig, DOCS / "radiation_unit_force.png", dpi=110)


def default_case_section() -> list[str]:
    """The default case's sound power from the current artifacts (simulate.npz, modes.npz)."""
    head = ["### The default case (dy_WR = -15 mm, mu = 0.35, gamma_y = -0.014)", ""]
    try:
        a, model, _ = compute_radiation("default")
    except (ArtifactError, FileNotFoundError) as e:
        return head + [f"Not available from the current artifacts ({e}); `make simulate` and rerun.", ""]
    plot_radiation(a, DOCS / "radiation_default.png", "default")
    flex = model.meta["modes"]["kind"] == "flexible"
    fd = float(a["f_dominant"])
    near = int(np.flatnonzero(flex)[np.argmin(np.abs(model.f_r[flex] - fd))])
    sm = int(a["sound_mode"])
    tone = a["is_tone"]
    k = int(np.argmax(a["W"]))
    sim = ROOT / "build" / "cases" / "default" / "simulate.npz"
    with np.load(sim) as d:
        F, dt = d["F_final"], float(np.median(np.diff(d["t_final"])))
    calls = []
    for _ in range(10):
        t0 = time.perf_counter()
        sound_power_of_forces(model, F, dt)
        calls.append(time.perf_counter() - t0)
    rows = ["| n | L_W (dB re 1e-12 W) | share | loudest at (Hz) | nearest mode of that n |", "|---:|---:|---:|---:|---|"]
    for i, n in enumerate(a["harmonics"]):
        rows.append(f"| {n} | {a['harmonic_L_W'][i]:.1f} | {100 * a['harmonic_W'][i] / a['W_total']:.2f} % | "
                    f"{a['harmonic_f_peak'][i]:.1f} | {a['harmonic_mode_label'][i]} {a['harmonic_mode_f'][i]:.1f} Hz |")
    squeal = bool(a["meaningful"])
    verdict = (f"at the squealing mode: {float(a['f_sound']):.2f} Hz "
               f"{'(a fitted tone)' if tone[k] else '(a residual bin)'}, {float(a['f_sound']) - fd:+.2f} Hz from F2's "
               f"dominant frequency, on the {a['sound_mode_label']} mode ({model.f_r[sm]:.2f} Hz, the wheel mode nearest "
               f"to F2's dominant frequency: {model.label(near)}); harmonic n = {int(a['sound_harmonic'])} carries "
               f"{100 * a['harmonic_W'][list(a['harmonics']).index(int(a['sound_harmonic']))] / a['W_total']:.2f} % of the power."
               if squeal and sm == near else
               f"{float(a['f_sound']):.2f} Hz ({a['sound_mode_label']}); F2's dominant frequency "
               f"{fd:.2f} Hz is nearest to the {model.label(near)} mode.")
    return head + [
        f"From `build/cases/default/simulate.npz` (stop: {a['stop_reason']}, L_F2 = {float(a['L_F2']):.1f} dB, "
        f"dominant frequency of F2 {fd:.2f} Hz) and the C20 modes, regenerated from the artifacts by this report "
        "(`make radiate`, then `.venv/bin/python -m pipeline.validation.writers.radiation`). "
        + ("It squeals (L_F2 >= 10 dB, SPEC 6)." if squeal else
           "**It does not squeal** (L_F2 < 10 dB): the sound power of its decaying residue is computed but not "
           "meaningful (SPEC 6)."),
        "",
        f"- overall **L_W = {float(a['L_W']):.1f} dB re 1e-12 W** (0 < f <= 6.5 kHz; {int(tone.sum())} tones, "
        f"{100 * a['W'][tone].sum() / a['W_total']:.2f} % of the power in them);",
        f"- **peak at {float(a['f_sound']):.1f} Hz**: {verdict}",
        f"- `sound_power_of_forces` on this stretch ({len(F)} samples): median {1e3 * np.median(calls):.0f} ms per call.",
        "",
        *rows,
        "",
        "![Sound power of the default case](validation/radiation_default.png)",
        "",
    ]
