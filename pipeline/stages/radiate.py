"""Radiate stage: the sound power of a case's wheel (SPEC 5, Thompson-Jones
[4.38]-[4.57]) under the contact forces of its simulation's final stretch.

Inputs: build/wheels/<wheel>/modes.npz (all modes, rigid half-wheelset ones
included, damping [4.11] as in the Green's functions), the wheel parameters
(surfaces, outline) and build/cases/<case>/simulate.npz (F_final).
Artifacts in build/cases/<case>/:

* radiate.npz: 'f' (Hz), 'W' (W per entry), 'W_n' (harmonics, entries),
  'harmonics', 'is_tone'; 'L_W' (dB re 1e-12 W), 'W_total', 'f_sound' (Hz),
  'sound_mode' (index into modes.npz), 'sound_mode_label' ('(n,m,c)'),
  'sound_mode_f', 'sound_harmonic'; per harmonic: 'harmonic_W',
  'harmonic_L_W', 'harmonic_f_peak', 'harmonic_mode', 'harmonic_mode_label',
  'harmonic_mode_f';
  the forces used: 'tone_f', 'tone_F2', 'tone_F3' (complex RMS, N),
  'tone_series', 'force_f', 'F2_spectrum', 'F3_spectrum' (Hann, RMS scaling,
  whole stretch), 'residual_F2', 'residual_F3' (Hann, power scaling, after the
  tones); the squeal measures 'L_F2', 'f_dominant', 'stop_reason',
  'meaningful' (L_F2 >= 10 dB, SPEC 6), 'dt', 'stretch_s'; unit forces at the
  contact point: 'unit_f', 'unit_W_lateral', 'unit_W_radial' (W per N^2 RMS)
  and their 'unit_W_n_*' per harmonic; 'zeta', 'y_wheel', 'contact_rz';
* radiate.png: F2/F3 amplitude spectra, the sound power spectrum, the
  unit-force curves;
* radiate_harmonics.csv: n, W_W, L_W_dB, share, f_peak_hz, mode, mode_f_hz;
* the exports of pipeline/stages/listen_exports.py: radiate_spectrum.csv, radiate_forces.csv,
  radiate_tones.csv, radiate_bands.csv (1/3 octaves) and lw_railway.csv
  (NoiseModelling's LW_RAILWAY layout).

Window and scaling.  The final stretch is the simulation's full-rate
F_final: its last 0.5 s (SPEC 6's squeal measures use the same samples).
F2 and F3 (mean removed) are split into tones and a residual
(solvers/radiation/force_power.py): the tones (the dominant F2 peak, its
harmonic series, up to three series) are fitted by Hann-weighted least
squares and give complex RMS amplitudes evaluated at their own frequencies;
the residual is a periodic-Hann, one-sided spectrum with power scaling (its
squared bins sum to the mean square), evaluated on its bins.  [4.56]'s mean
square with RMS amplitudes is then a time mean square, and L_W sums the
entries.  Band: 0 < f <= 6.5 kHz (the rail model's limit, as the Green's
functions); tones searched above 20 Hz (as the dominant frequency of F2).
Sound power is computed for every case; SPEC 6 calls it meaningful for
L_F2 >= 10 dB, recorded as 'meaningful'.

Helpers for other code (the studies): ``load_radiation_model(case)`` (once per
wheel and contact point) and ``sound_power_of_forces(model, F, dt)``.
"""
from __future__ import annotations

import logging
import time

import numpy as np

from solvers.constants import F_MAX_HZ, SQUEAL_LEVEL_DB

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.case import resolve_case
from geometry.wheel import surface_radii, tread_radius, wheel_segments
from solvers.radiation.surfaces import radiation_surfaces, surface_nodes
from pipeline.config.loader import config_hash
from pipeline.stages.simulate import simulate_config
from solvers.spectra import amplitude_spectrum

log = logging.getLogger("pipeline.radiate")

F_MIN = 20.0  # Hz, lowest tone (as solvers.timeloop.interaction.squeal_measures)
SETTINGS = {"rho": 1.21, "c0": 343.0, "faces": 2, "web_thickness": "tyre", "torsion": False, "rigid": True,
            "window": "hann", "f_min": F_MIN, "f_max": F_MAX_HZ, "prominence_db": 20.0, "unit_f": [100.0, F_MAX_HZ]}


def _case_wheel(case: str):
    rc = resolve_case(case)  # the contact point of the profiles, as the contact and greens stages'
    c, pw, y_w = rc.case, rc.wheel, rc.contact.y_wheel
    modes, mprov = artifacts.load_npz(paths.wheel_dir(c["wheel"]) / "modes.npz", "wheel-modes", pw,
                                      make_target=f"modes WHEEL={c['wheel']}")
    return c, pw, modes, mprov, y_w


def load_radiation_model(case: str, zeta_overrides: dict | None = None):
    """The radiation model of the case's wheel at its contact point (y^W of the rigid
    contact of the case's profiles, ``pipeline.config.case.resolve_case``): modes,
    surfaces, surface nodes, the contact point (interpolated on the running surface
    exactly as the Green's functions stage does, so the wheel is the simulation's), damping [4.11] (``zeta_overrides`` {mode index: zeta} as
    ``solvers.wheel.receptance.modal_damping``).  Load once, reuse for many force sets."""
    from solvers.radiation.force_power import build_model  # lazy: brings in scipy
    from solvers.wheel.receptance import contact_point, contact_shape, modal_damping  # lazy: brings in scipy

    c, pw, modes, mprov, y_w = _case_wheel(case)
    surf = radiation_surfaces(surface_radii(pw), wheel_segments(pw), web_thickness=SETTINGS["web_thickness"],
                                faces=SETTINGS["faces"])
    bnd = {k[len("boundary_"):]: v for k, v in modes.items() if k.startswith("boundary_") and k != "boundary_names"}
    nodes = surface_nodes(modes["points"], bnd, surf)
    running = np.unique(np.concatenate([modes["boundary_tread"], modes["boundary_flange"]]))
    where = contact_point(modes["points"], running, y_w, pw["axle"]["rolling_circle_z"],
                          r_of_y=lambda y: tread_radius(pw, y), cells=modes["cells"])
    zeta = modal_damping(modes["n"], modes["m"], modes["cls"], modes["kind"], modes["zeta_suspension"],
                         zeta_overrides)
    meta = {"case": case, "wheel": c["wheel"], "y_wheel": y_w, "contact": where, "contact_node": where.node,
            "surfaces": surf, "nodes": nodes, "modes": modes, "modes_hash": mprov["config_hash"]}
    return build_model(modes, surf, nodes, contact_shape(modes["shapes"], where), zeta, rho=SETTINGS["rho"],
                       c0=SETTINGS["c0"], f_min=F_MIN, f_max=F_MAX_HZ, meta=meta)


def sound_power_of_forces(model, F, dt: float) -> dict:
    """Sound power of the wheel of ``model`` under the forces ``F`` (n, 3) = (F1, F2,
    F3) on the rail (N) over the final stretch, sampled at ``dt`` (s).  Keys 'L_W'
    (dB re 1e-12 W), 'f_sound' (Hz, frequency of the largest entry), 'f', 'W' (W per
    entry: residual bins and tones), and 'W_n', 'harmonics', 'is_tone', 'W_total',
    'decomposition' (solvers.radiation.force_power.power_of_forces)."""
    from solvers.radiation.force_power import power_of_forces  # lazy: brings in scipy

    F = np.asarray(F, float)
    if F.ndim != 2 or F.shape[1] != 3:
        raise ValueError(f"F must be (n, 3) = (F1, F2, F3), got shape {F.shape}")
    if not np.all(np.isfinite(F)):
        raise ValueError("F contains NaN or inf")
    if not dt > 0:
        raise ValueError(f"dt must be > 0, got {dt}")
    return power_of_forces(model, F[:, 1], F[:, 2], dt)


def radiate_config(case: str, model) -> tuple[dict, dict]:
    """(simulate config, this stage's config)."""
    scfg = simulate_config(case)[-1]
    return scfg, {"case": case, "wheel_modes": model.meta["modes_hash"], "simulate": config_hash(scfg),
                  "settings": SETTINGS}


def compute_radiation(case: str, model=None) -> tuple[dict, object, dict]:
    """(arrays of radiate.npz, model, config) from the current artifacts; writes nothing."""
    from solvers.radiation.force_power import frequency_grid_for, mode_at, unit_force_curve  # lazy: brings in scipy

    model = model or load_radiation_model(case)
    scfg, cfg = radiate_config(case, model)
    sim, _ = artifacts.load_npz(paths.case_dir(case) / "simulate.npz", "simulate", scfg,
                                make_target=f"simulate CASE={case}")
    for key in ("F_final", "t_final", "L_F2", "f_dominant", "stop_reason"):
        if key not in sim:
            raise artifacts.ArtifactError(paths.case_dir(case) / "simulate.npz", f"has no key {key!r}; rebuild it "
                                          f"with `make simulate CASE={case}`")
    t, F = sim["t_final"], sim["F_final"]
    if F.ndim != 2 or F.shape[1] != 3 or len(t) != len(F) or len(t) < 16:
        raise artifacts.ArtifactError(paths.case_dir(case) / "simulate.npz",
                                      f"F_final {F.shape} / t_final {t.shape}: need (n, 3) and n >= 16 samples")
    if "contact_angle_wheel" in sim and float(sim["contact_angle_wheel"]) != 0.0:
        from solvers.contact.frame import to_structure  # forces in the contact plane -> the wheel's directions

        F = F.copy()
        F[:, 1], F[:, 2] = to_structure(F[:, 1], F[:, 2], float(sim["contact_angle_wheel"]))
    dt = float(np.median(np.diff(t)))
    t0 = time.perf_counter()
    res = sound_power_of_forces(model, F, dt)
    wall = time.perf_counter() - t0
    d = res["decomposition"]
    W, W_n, f = res["W"], res["W_n"], res["f"]
    tot = res["W_total"]
    hW = W_n.sum(axis=1)
    with np.errstate(divide="ignore"):
        hL = 10 * np.log10(hW / 1e-12)
    h_fpk = np.array([f[np.argmax(row)] if row.max() > 0 else np.nan for row in W_n])
    h_mode = np.array([int(idx[np.argmin(np.abs(model.f_r[idx] - fp))]) if np.isfinite(fp) else -1
                       for idx, fp in zip(model.groups, h_fpk)])
    if tot > 0:
        k = int(np.argmax(W))
        sm = mode_at(model, f[k], W_n[:, k])
        s_h = int(model.n[sm])
    else:
        sm, s_h = -1, -1
    fs, S2 = amplitude_spectrum(F[:, 1], dt, scaling="rms")
    _, S3 = amplitude_spectrum(F[:, 2], dt, scaling="rms")
    band = (fs > 0) & (fs <= F_MAX_HZ)
    fu = frequency_grid_for(model, *SETTINGS["unit_f"])
    ul, ur = unit_force_curve(model, fu, "lateral"), unit_force_curve(model, fu, "radial")
    L_F2 = float(sim["L_F2"])
    where = model.meta["contact"]
    arrays = {
        "f": f, "W": W, "W_n": W_n, "harmonics": model.harmonics, "is_tone": res["is_tone"],
        "L_W": np.float64(res["L_W"]), "W_total": np.float64(tot), "f_sound": np.float64(res["f_sound"]),
        "sound_mode": np.int64(sm), "sound_mode_label": np.array(model.label(sm) if sm >= 0 else ""),
        "sound_mode_f": np.float64(model.f_r[sm] if sm >= 0 else np.nan), "sound_harmonic": np.int64(s_h),
        "harmonic_W": hW, "harmonic_L_W": hL, "harmonic_f_peak": h_fpk, "harmonic_mode": h_mode,
        "harmonic_mode_label": np.array([model.label(i) if i >= 0 else "" for i in h_mode]),
        "harmonic_mode_f": np.array([model.f_r[i] if i >= 0 else np.nan for i in h_mode]),
        "tone_f": d.tone_f, "tone_F2": d.tone_F2, "tone_F3": d.tone_F3, "tone_series": d.series,
        "force_f": fs[band], "F2_spectrum": S2[band], "F3_spectrum": S3[band], "residual_F2": d.R2,
        "residual_F3": d.R3, "L_F2": np.float64(L_F2), "f_dominant": np.float64(sim["f_dominant"]),
        "stop_reason": np.array(str(sim["stop_reason"])), "meaningful": np.bool_(L_F2 >= SQUEAL_LEVEL_DB),
        "dt": np.float64(dt), "stretch_s": np.float64(len(t) * dt),
        "unit_f": fu, "unit_W_lateral": ul.sum(0), "unit_W_radial": ur.sum(0), "unit_W_n_lateral": ul,
        "unit_W_n_radial": ur, "zeta": model.zeta, "y_wheel": np.float64(model.meta["y_wheel"]),
        "contact_rz": np.array([where.r, where.Z]), "wall_s": np.float64(wall),
    }
    return arrays, model, cfg


def harmonic_rows(a: dict) -> list[list]:
    """Rows of radiate_harmonics.csv (also the report's table)."""
    tot = float(a["W_total"])
    rows = []
    for i, n in enumerate(a["harmonics"]):
        rows.append([int(n), float(a["harmonic_W"][i]), float(a["harmonic_L_W"][i]),
                     float(a["harmonic_W"][i] / tot) if tot > 0 else float("nan"), float(a["harmonic_f_peak"][i]),
                     str(a["harmonic_mode_label"][i]), float(a["harmonic_mode_f"][i])])
    return rows


def run_radiate(case: str) -> dict:
    arrays, model, cfg = compute_radiation(case)
    out = paths.case_dir(case)
    plot_radiation(arrays, out / "radiate.png", case)
    artifacts.save_csv(out / "radiate_harmonics.csv",
                       ["n", "W_W", "L_W_dB", "share", "f_peak_hz", "mode", "mode_f_hz"], harmonic_rows(arrays))
    from pipeline.stages.listen_exports import radiation_tables  # here: Make's DEPS of the module's other entry points stay without it

    radiation_tables(arrays, out, _case_speed(case))  # CSV spectra, bands, LW_RAILWAY (pipeline/stages/listen_exports.py)
    artifacts.save_npz(out / "radiate.npz", "radiate", cfg, **arrays)
    log.info("radiate %s: L_W = %.1f dB re 1e-12 W, peak %.1f Hz (%s), %d tones; L_F2 = %.1f dB (%s) -> %s",
             case, arrays["L_W"], arrays["f_sound"], arrays["sound_mode_label"], len(arrays["tone_f"]),
             arrays["L_F2"], "squeal" if arrays["meaningful"] else f"below {SQUEAL_LEVEL_DB:g} dB: not meaningful",
             out / "radiate.npz")
    return arrays


def _case_speed(case: str) -> float:
    return float(resolve_case(case).case["kinematics"]["speed"])


def plot_radiation(a: dict, path, case: str) -> None:
    """radiate.png (``postprocess.plots.radiate.radiation_figure``), written atomically."""
    from postprocess.plots.radiate import radiation_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(radiation_figure(a, case), path, dpi=90)
