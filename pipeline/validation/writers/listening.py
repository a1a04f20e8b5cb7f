"""Validation of the listening stage (postprocess/listening/listener.py, postprocess/listening/audio.py,
pipeline/stages/listen.py): measured numbers and a plot for docs/validation/75_listening.md and
docs/validation/listening_default.png.

    .venv/bin/python -m pipeline.validation.writers.listening      # ~15 s

A writer, run by `make validate`.  The limits it states are asserted by tests/listen/ (test_listener.py:
the standards and the image solutions; test_stage.py: a synthetic squeal; test_default_listening.py,
--validation: the default case through ``default_section`` here).
"""
from __future__ import annotations

import tempfile
from pathlib import Path
import json

import numpy as np

from postprocess.listening import listener as L, audio as A

from pipeline.validation.make import make_targets
from pipeline.validation.references import listening as TL, wavcheck as WC
from pipeline.validation.writers import DOCS, save_figure, save_fragment
from pipeline.store.artifacts import ArtifactError
from pipeline.config.loader import ConfigError
from pipeline.stages.listen import compute_listening, listener_inputs


def standards_section() -> list[str]:
    x = np.arange(-20, 14)
    exact = 1000.0 * 10 ** (0.1 * x)
    table = np.array(list(TL.IEC_61672_A.values()))
    nominal = np.array(list(TL.IEC_61672_A), float)
    dev = np.abs(L.a_weighting(exact) - table)
    dev_nom = np.abs(L.a_weighting(nominal) - table)
    b = L.third_octave_bands()
    G = 10 ** 0.3
    edge = max(np.abs(b.centre / (1000 * G ** (x / 3)) - 1).max(), np.abs(b.lower / (b.centre * G ** (-1 / 6)) - 1).max())
    f = np.geomspace(50, 10000, 40)
    iso = np.abs(L.air_attenuation(f) / TL.iso_9613_alpha(f) - 1).max()
    return [
        "### Standards: A-weighting, 1/3-octave bands, air absorption",
        "",
        f"- **A-weighting** (IEC 61672-1 formula E.6, through pyfar) against the standard's Table 3, typed into "
        f"`pipeline/validation/references/listening.py` from the published table (34 bands, 10 Hz - 20 kHz): largest deviation "
        f"**{dev.max():.3f} dB** at the exact base-10 mid-band frequencies 1000 * 10^(0.1 x) Hz, where the table is "
        f"defined (it is rounded to 0.1 dB; the test allows 0.06 dB). At the nominal labels themselves (12.5, 16, "
        f"31.5 Hz...) the curve differs from the table by up to {dev_nom.max():.2f} dB "
        f"({nominal[np.argmax(dev_nom)]:g} Hz), because a nominal label is not the frequency the table is computed "
        "at; the stage weights every component at its own frequency.",
        f"- **1/3-octave bands** (IEC 61260-1, base 10, G = 10^(3/10); pyfar): mid-band and edge frequencies equal "
        f"1000 G^(x/3) and f_m G^(+-1/6) to {edge:.1e}; the nominal labels are the standard's list.",
        f"- **Air absorption** (ISO 9613-1 through pyfar; 20 degC, 70 % RH, 101.325 kPa) against the standard's "
        f"formulas typed in the test, 50 Hz - 10 kHz: largest relative deviation {iso:.1e}; 1 kHz: "
        f"{1e3 * L.air_attenuation(1000.0)[0]:.2f} dB/km (the standard's Table 1: 4.98).",
        "",
    ]


def propagation_section() -> list[str]:
    errs = []
    for h_s, h_r, d in [(0.59, 1.4, 6.75), (0.59, 4.0, 24.25), (0.3, 0.3, 2.0)]:
        f = np.array([200.0, 1151.5, 3457.0, 6000.0])
        g = L.Geometry(distance=d, h_source=h_s, h_receiver=h_r, directivity="omni", air=False)
        ref = []
        for fi in f:
            k = 2 * np.pi * fi / TL.C0
            Q = np.sqrt(4 * np.pi / (TL.RHO * TL.C0 * k**2))
            ref.append(abs(TL.monopole_field(np.array([[0.0, d, h_r]]), [np.array([0, 0, h_s]), np.array([0, 0, -h_s])],
                                             [Q, Q], fi)[0]) ** 2)
        errs.append(np.abs(L.mean_square_pressure(f, 1.0, g) / np.array(ref) - 1).max())
    dip = [abs(m / r - 1) for m, r in (TL.dipole_from_two_monopoles(f) for f in (500.0, 1151.5, 3000.0))]
    gz = [L.Geometry(distance=50.0, h_source=1e-3, h_receiver=1e-3, ground=g, directivity="omni", air=False)
          for g in ("none", "rigid")]
    p0 = L.mean_square_pressure([500.0], 1.0, gz[0])[0]
    coh = L.level(L.mean_square_pressure([500.0], 1.0, gz[1])[0]) - L.level(p0)
    inc = L.level(L.mean_square_pressure([500.0], 1.0, gz[1], coherent=False)[0]) - L.level(p0)
    fb = np.linspace(1000, 30000, 20001)
    gh = L.Geometry(distance=6.75, h_source=0.59, h_receiver=1.4, directivity="omni", air=False)
    avg = L.mean_square_pressure(fb, 1.0, gh).mean() / L.mean_square_pressure(fb, 1.0, gh, coherent=False).mean()
    return [
        "### Propagation: image source, dipole, ground",
        "",
        "The wheel is a point source at its centre, abreast of the receiver, radiating the radiate stage's sound "
        "power W: p^2 = rho c0 W Q / (4 pi r^2) per path, Q = 3 cos^2 theta (a dipole along the axle: the "
        "squealing (n,0,a) modes move the wheel axially) or 1 (omnidirectional); a rigid ground plane adds the "
        "exact image source, added coherently with the path difference for every component (tones are pure tones); "
        "ISO 9613-1 air absorption on each path; no shielding, no Doppler shift, no ground impedance. "
        "The wheel is not compact at squeal frequencies (ka = 2 pi f a / c0 is given below for the default case), "
        "where a real wheel beams more along its axis than a dipole: the dipole is the stated, energy-conserving "
        "middle choice; `directivity = \"omni\"` gives the lower bound (-4.8 dB on the axis).",
        "",
        f"- Monopole over rigid ground against the exact field of the source and its image, summed in the test "
        f"with the volume velocity from the monopole's power formula (3 geometries x 4 frequencies): largest "
        f"relative deviation of p^2 **{max(errs):.1e}**.",
        "- Dipole: two opposite monopoles 1 mm apart along the axle and their images; the dipole's power "
        "integrated over a 60 m sphere; the model's p^2 for that power at the default receiver (wheel centre "
        f"0.59 m, receiver 1.4 m above the ground, 6.75 m apart) at 0.5, 1.15 and 3 kHz: largest relative "
        f"deviation **{max(dip):.1e}** (`test_dipole_along_the_axle_from_two_monopoles`).",
        f"- Grazing incidence (source and receiver 1 mm above the ground): {coh:+.4f} dB coherent, {inc:+.4f} dB "
        f"incoherent over free field (6.0206, 3.0103 exactly); averaged over 1-30 kHz (~20 interference fringes at "
        f"the default receiver) the coherent sum is {avg:.3f} x the incoherent one.",
        "",
    ]


def default_section() -> tuple[list[str], dict | None]:
    head = ["### The default case at the ISO 3095 position (7.5 m, 1.2 m)", ""]
    make_targets("radiate", CASE="default")
    try:
        a, wav, cal, _ = compute_listening("default")
    except (ArtifactError, ConfigError, FileNotFoundError) as e:
        return head + [f"Not available from the current artifacts ({e}); `make radiate` and rerun.", ""], None
    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "listen.wav").write_bytes(wav)
        (Path(tmp) / "listen.json").write_text(json.dumps(cal))
        fs, p, lc, cal = WC.read_calibrated(Path(tmp) / "listen.wav", Path(tmp) / "listen.json")
    f_wav = WC.dominant(lc, fs)
    nom, Lb = WC.filter_bank_levels(p, fs, cal["limit_cycle_start_s"], cal["duration_s"] - WC.FADE_S)
    n = len(nom)
    loud = a["band_L_p"][:n] > float(a["L_p"]) - 70
    with np.errstate(divide="ignore"):
        bsum = 10 * np.log10(np.sum(10 ** (a["band_L_p"] / 10)))

    pw = listener_inputs("default")[1]
    m = {"z_rc": pw["axle"]["rolling_circle_z"], "radius": pw["tyre"]["rolling_radius"], "a": a, "p": p, "fs": fs, "nom": nom, "Lb": Lb, "f_wav": f_wav, "L_wav": WC.level(lc), "bsum": bsum,
         "fb_ideal": float(np.abs(Lb[loud] - a["band_L_p"][:n][loud]).max()),
         "fb_dev": float(np.abs(Lb[loud] - WC.filter_bank_from_lines(a["f"], a["p2"], fs)[loud]).max()),
         "fb_sum": abs(10 * np.log10(np.sum(10 ** (Lb / 10))) - WC.level(lc))}
    d = np.geomspace(2.0, 100.0, 300)
    gA = 10 ** (a["A_weight"] / 10)
    m["sweep"] = {"d": d}
    for kind, ground, coh in (("coherent", "rigid", True), ("incoherent", "rigid", False), ("free field", "none", True)):
        m["sweep"][kind] = np.array([L.level((L.mean_square_pressure(a["f"], a["W"], L.Geometry(
            distance=di - m["z_rc"], h_source=float(a["h_source"]), h_receiver=float(a["h_receiver"]), ground=ground,
            directivity=str(a["directivity"])), coherent=coh) * gA).sum()) for di in d])
    dips = m["sweep"]["incoherent"] - m["sweep"]["coherent"]
    ka = 2 * np.pi * float(a["f_sound"]) * m["radius"] / 343.0
    squeal = bool(a["meaningful"])
    rows = ["| band (Hz) | line spectrum L_p (dB) | filter bank on the WAV (dB) | L_pA (dB(A)) |", "|---:|---:|---:|---:|"]
    for j in np.flatnonzero(loud):
        rows.append(f"| {nom[j]:g} | {a['band_L_p'][j]:.2f} | {Lb[j]:.2f} | {a['band_L_pA'][j]:.2f} |")
    return head + [
        f"From the current `build/cases/default/` radiate and simulate artifacts (L_F2 = {float(a['L_F2']):.1f} dB, "
        f"{'squeal' if squeal else 'no squeal: silent file'}; L_W = {float(a['L_W']):.1f} dB re 1e-12 W), receiver "
        f"{float(a['distance']):g} m from the track centre and {float(a['height']):g} m above the rail, the wheel "
        f"centre {float(a['r_direct']):.2f} m away, rigid ground {float(a['ground_depth']):g} m below the rail, "
        f"{a['directivity']} source. Generated by `compute_listening` (what `make listen` writes) and read back from "
        "the WAV bytes with scipy.io.wavfile and the JSON calibration:",
        "",
        f"- **L_p = {float(a['L_p']):.2f} dB, L_pA = {float(a['L_pA']):.2f} dB(A)** (ground added incoherently: "
        f"{float(a['L_p_incoherent']):.2f} dB, {float(a['L_pA_incoherent']):.2f} dB(A));",
        f"- the WAV's dominant frequency {f_wav:.3f} Hz vs the radiate stage's squeal frequency "
        f"{float(a['f_sound']):.3f} Hz: **{100 * abs(f_wav / float(a['f_sound']) - 1):.1e} %** (required < 0.5 %);",
        f"- the WAV's calibrated level over its limit cycle {m['L_wav']:.3f} dB vs L_p: **{m['L_wav'] - float(a['L_p']):+.3f} "
        f"dB** (required within 0.5 dB; 0 dBFS sine = {cal['full_scale_sine_dB_SPL']:.2f} dB SPL);",
        f"- the 1/3-octave bands' energy sum vs L_p: **{bsum - float(a['L_p']):+.1e} dB** (required within 0.1 dB; "
        f"{float(a['outside_p2']):.1e} Pa^2 outside 10 Hz-20 kHz);",
        f"- second method: pyfar's order-14 Butterworth IEC 61260-1 filter bank on the WAV: bands within 70 dB of "
        f"L_p within **{m['fb_dev']:.3f} dB** (required < 0.5 dB) of the stage's line spectrum passed through the same "
        f"filters' responses, their energy sum within {m['fb_sum']:.3f} dB of the WAV's level. Against the stage's "
        f"ideal bands the filter bank differs by up to {m['fb_ideal']:.2f} dB: its skirts show the squeal tone "
        "~25 dB down in the neighbouring band, which ideal band edges do not.",
        f"- the sound's onset: {float(a['t_limit_cycle']):.2f} s of growth (from {float(a['t_history_start']):.2f} s "
        "of simulation) then the limit cycle; read back, its 20 ms running level follows the predicted envelope "
        "(bottom panel).",
        "",
        f"The squeal at {float(a['f_sound']):.0f} Hz on a wheel of radius {m['radius']:.2f} m: ka = {ka:.1f} (not "
        "compact; see the directivity above). A pure tone over a rigid ground interferes with its reflection: the "
        "coherent level moves with the receiver position (middle panel: between 2 and 100 m from the track centre "
        f"it lies from {dips.max():.1f} dB below to {-dips.min():.1f} dB above the incoherent level, the dips where "
        "the path difference is an odd number of half wavelengths), "
        "the incoherent level (+3 dB over free field at most) is its average over positions; both are stored "
        "(`L_p`, `L_p_incoherent`). Real ground impedance, turbulence and the moving source smooth the dips.",
        "",
        *rows,
        "",
        "![Listening, default case](validation/listening_default.png)",
        "",
    ], m


def plot(m: dict) -> None:
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib


    a = m["a"]
    fig, axs = plt.subplots(3, 1, figsize=(9, 11))
    n = len(m["nom"])
    x = np.arange(n)
    floor = float(a["L_p"]) - 80
    axs[0].bar(x, np.maximum(a["band_L_p"][:n], floor) - floor, 0.6, bottom=floor, label="line spectrum (stage)")
    axs[0].plot(x, np.maximum(m["Lb"], floor), "kx", label="pyfar filter bank on the WAV")
    axs[0].plot(x, np.maximum(a["band_L_pA"][:n], floor), "C3_", ms=12, mew=2, label="A-weighted (stage)")
    axs[0].set_xticks(x[::3], [f"{v:g}" for v in m["nom"][::3]])
    axs[0].set_ylim(floor, float(a["L_p"]) + 8)
    axs[0].set_ylabel("L_p (dB re 20 uPa)")
    axs[0].set_title(f"1/3-octave bands at {float(a['distance']):g} m / {float(a['height']):g} m: L_p = "
                     f"{float(a['L_p']):.1f} dB, L_pA = {float(a['L_pA']):.1f} dB(A)", fontsize=9)
    for kind, style in (("coherent", "-"), ("incoherent", "--"), ("free field", ":")):
        axs[1].semilogx(m["sweep"]["d"], m["sweep"][kind], style, label=kind)
    axs[1].axvline(float(a["distance"]), color="k", lw=0.5)
    axs[1].set_xlabel(f"receiver distance from the track centre (m), {float(a['height']):g} m above the rail")
    axs[1].set_ylabel("L_pA (dB(A))")
    fs, p = m["fs"], m["p"]
    w = int(0.02 * fs)
    run = 10 * np.log10(np.convolve(p**2, np.ones(w) / w, mode="same") / WC.P0**2 + 1e-30)
    t = np.arange(p.size) / fs
    axs[2].plot(t, run, lw=0.6, label="the WAV, read back: 20 ms running level")
    with np.errstate(divide="ignore"):
        axs[2].plot(a["onset_t"], 20 * np.log10(a["onset_gain"]) + float(a["L_p"]), "k--", lw=0.8,
                    label="predicted envelope (growth phase of F2, then L_p)")
    axs[2].set_ylim(float(a["L_p"]) - 60, float(a["L_p"]) + 8)
    axs[2].set_xlabel("time in the WAV (s)")
    axs[2].set_ylabel("L_p (dB)")
    axs[2].set_title(f"the sound: {float(a['wav_duration']):.2f} s at {A.FS} Hz, 16 bit", fontsize=9)
    for ax in axs:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, DOCS / "listening_default.png", dpi=90)


def write() -> tuple[str, dict | None]:
    text = [
        "## Listening: sound pressure at a receiver, dB(A), 1/3 octaves, the sound",
        "",
        "Written by `pipeline/validation/writers/listening.py` (`make validate`); `tests/listen/` asserts its limits "
        "(the default case's with --validation, the same checks on a synthetic squeal in the fast tests). Code: `postprocess/listening/listener.py` (propagation, levels, "
        "bands), `postprocess/listening/audio.py` (the sound), `pipeline/stages/listen.py` (`make listen`). Standards through "
        "pyfar 0.8.1 (it installs with numpy 1.24.2), each checked here against the standard's own table or formulas.",
        "",
    ]
    text += standards_section()
    text += propagation_section()
    sec, m = default_section()
    text += sec
    if m is not None:
        plot(m)
    out = "\n".join(text)
    save_fragment("75_listening.md", out)
    return out, m


if __name__ == "__main__":
    write()
