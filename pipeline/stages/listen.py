"""Listen stage: what a listener beside the track hears of a case's squeal.

Inputs: build/cases/<case>/radiate.npz (sound power per tone and residual bin,
the tones' forces), simulate.npz (the force history with its growth phase),
the case's ``[listener]`` table (schemas.LISTENER; ``--distance``/``--height``
override it) and the wheel file (rolling radius, flange height, the rolling
circle's distance from the wheelset centre).  Propagation and levels:
postprocess/listening/listener.py; the sound: postprocess/listening/audio.py (assumptions stated
there).  The squealing wheel is taken on the rail nearer the receiver, its
centre at the rolling radius above the top of the rail.

Artifacts in build/cases/<case>/, one set per receiver, side by side: ``<tag>`` names the receiver
(``receiver_tag``: ``7.5m`` at 7.5 m and the ISO 3095 height 1.2 m, ``25m_3.5m`` otherwise), so that a
run with ``--distance 25`` keeps the 7.5 m result; the case's own receiver is also written as
listen.npz (Make's target; the same arrays as its listen_<tag>.npz):

* listen_<tag>.npz: receiver 'distance', 'height', 'ground_depth', 'ground',
  'directivity', 'h_source', 'h_receiver' (above the ground plane),
  'horizontal' (wheel centre to receiver), 'r_direct', 'r_image' (m);
  per component (the radiate stage's tones and residual bins) 'f' (Hz),
  'is_tone', 'W' (W), 'p2' (Pa^2, coherent), 'p2_incoherent', 'A_weight' (dB);
  'L_p', 'L_pA' (dB re 20 uPa, coherent), 'L_p_incoherent', 'L_pA_incoherent',
  'f_peak' (Hz, the loudest component at the receiver), 'f_sound', 'L_W',
  'L_F2', 'meaningful' (L_F2 >= 10 dB, SPEC 6), 'silent'; 1/3-octave bands
  'band_nominal', 'band_centre', 'band_lower', 'band_upper' (Hz), 'band_L_p',
  'band_L_pA' (dB), 'outside_p2' (Pa^2 outside 10 Hz-20 kHz); the tones
  'tone_f', 'tone_p' (complex RMS Pa); the sound 'fs', 'pa_per_count',
  'full_scale_sine_dB', 'wav_duration', 't_limit_cycle' (s into the sound),
  't_history_start' (s of simulation), 'onset_t', 'onset_gain', and its
  read-back 'wav_L_p' (limit-cycle part), 'wav_f_peak';
* listen_<tag>.wav: mono, 44.1 kHz, 16-bit PCM; its calibration in a LIST/INFO
  comment and in
* listen_<tag>.json: the calibration sidecar (Pa per count, the level of a
  full-scale sine, L_p, L_pA, receiver, assumptions);
* listen_<tag>.png: the 1/3-octave spectrum (unweighted, A-weighted) and the
  sound's envelope;
* listen_<tag>_bands.csv: the 1/3-octave bands (nominal, centre, lower, upper
  frequency in Hz, L_p, L_pA in dB re 20 uPa).
"""
from __future__ import annotations

import logging

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.loader import ConfigError, config_hash, validate
from postprocess.listening import audio as A, listener as L
from postprocess.listening.listener import Geometry, level
from pipeline.config.case import resolve_case
from pipeline.config.input_schemas import LISTENER
from pipeline.stages.radiate import load_radiation_model, radiate_config
from postprocess.listening.audio import growth_envelope, onset_from_history
from solvers.spectra import amplitude_spectrum, dominant_frequency

log = logging.getLogger("pipeline.listen")

BANDS_HZ = (10.0, 20000.0)  # 1/3-octave bands reported (IEC 61672-1's range)
SEED = 0  # the residual noise's phases


def _settings() -> dict:
    return {"fs": A.FS, "headroom_db": A.HEADROOM_DB, "onset_s": A.ONSET_S, "hold_s": A.HOLD_S,
            "envelope_window_s": A.ENVELOPE_WINDOW_S, "reference_s": A.REFERENCE_S, "fade_s": A.FADE_S,
            "air": L.AIR, "bands_hz": list(BANDS_HZ), "seed": SEED, "p_ref": L.P_REF}


def listener_inputs(case: str, distance: float | None = None, height: float | None = None):
    """(case, wheel parameters, resolved listener table, postprocess.listening.listener.Geometry);
    ``distance``/``height`` override the case file's [listener] values.  Raises
    ConfigError naming the file (or the command line), key, value and allowed range."""
    rc = resolve_case(case)
    cpath, c, pw = rc.case_file, rc.case, rc.wheel
    lis = dict(c["listener"])
    over = {f"--{k}": v for k, v in (("distance", distance), ("height", height)) if v is not None}
    if over:
        got = validate(over, {k: LISTENER[k[2:]] for k in over}, "command line")
        lis.update({k[2:]: v for k, v in got.items()})
    source = {k: ("command line", f"--{k}") if f"--{k}" in over else (str(cpath), f"listener.{k}")
              for k in ("distance", "height")}
    z_rc, radius = pw["axle"]["rolling_circle_z"], pw["tyre"]["rolling_radius"]
    outer = radius + pw["flange"]["height"]
    horizontal = lis["distance"] - z_rc
    h_s, h_r = lis["ground_depth"] + radius, lis["ground_depth"] + lis["height"]
    r = float(np.hypot(horizontal, h_r - h_s))
    if horizontal <= 0 or r <= outer:
        src, key = source["distance"]
        raise ConfigError(src, [(key, lis["distance"],
                                 f"a receiver beside the track and outside the wheel: distance > {z_rc} m (the "
                                 f"wheel's plane, wheel file axle.rolling_circle_z) and more than the wheel's outer "
                                 f"radius {outer:.3f} m from its centre (here {max(r, 0):.3f} m at distance "
                                 f"{lis['distance']} m, height {lis['height']} m)")])
    geo = Geometry(distance=horizontal, h_source=h_s, h_receiver=h_r, ground=lis["ground"],
                   directivity=lis["directivity"])
    return c, pw, lis, geo


def listen_config(case: str, lis: dict, pw: dict) -> tuple[dict, dict, dict]:
    """(simulate config, radiate config, this stage's config)."""
    scfg, rcfg = radiate_config(case, load_radiation_model(case))
    wheel = {"rolling_radius": pw["tyre"]["rolling_radius"], "flange_height": pw["flange"]["height"],
             "rolling_circle_z": pw["axle"]["rolling_circle_z"]}
    return scfg, rcfg, {"case": case, "radiate": config_hash(rcfg), "simulate": config_hash(scfg),
                        "listener": lis, "wheel": wheel, "settings": _settings()}


def _onset(sim: dict, case: str):
    path = paths.case_dir(case) / "simulate.npz"
    for key in ("t", "F"):
        if key not in sim:
            raise artifacts.ArtifactError(path, f"has no key {key!r} (the force history); rebuild it with "
                                          f"`make simulate CASE={case}`")
    try:
        t, env = growth_envelope(sim["t"], sim["F"][:, 1], f_tone=float(sim["f_dominant"]))
    except ValueError as e:
        raise artifacts.ArtifactError(path, f"no onset envelope from its force history: {e}") from None
    return onset_from_history(t, env)


def compute_listening(case: str, distance=None, height=None, allow_silent: bool = False):
    """(arrays of listen.npz, WAV bytes, calibration payload, config); writes nothing."""
    c, pw, lis, geo = listener_inputs(case, distance, height)
    scfg, rcfg, cfg = listen_config(case, lis, pw)
    cdir = paths.case_dir(case)
    a, _ = artifacts.load_npz(cdir / "radiate.npz", "radiate", rcfg, make_target=f"radiate CASE={case}")
    sim, _ = artifacts.load_npz(cdir / "simulate.npz", "simulate", scfg, make_target=f"simulate CASE={case}")
    squeal = bool(a["meaningful"])
    if not squeal and not allow_silent:
        raise ConfigError(str(paths.case_file(case)), detail=(
            f"case {case!r} does not squeal: L_F2 = {float(a['L_F2']):.1f} dB < 10 dB (docs/physics.md section 6; the simulation "
            f"stopped: {a['stop_reason']}), so there is no squeal to listen to. `--allow-silent` "
            f"(make listen ALLOW_SILENT=1) writes the levels and a silent WAV."))
    f, W, tone = a["f"], a["W"], a["is_tone"].astype(bool)
    H, Hd, Hi = L.transfer(f, geo)
    p2, p2i = np.abs(H) ** 2 * W, (Hd**2 + Hi**2) * W
    Aw = L.a_weighting(f)
    gA = 10 ** (Aw / 10)
    bands = L.third_octave_bands(*BANDS_HZ)
    b, out = L.band_sums(f, p2, bands)
    bA, _ = L.band_sums(f, p2 * gA, bands)
    if not np.allclose(f[tone], a["tone_f"], rtol=1e-12):
        raise artifacts.ArtifactError(cdir / "radiate.npz", "its tone entries differ from tone_f; rebuild it")
    tone_p = H[tone] * np.sqrt(W[tone]) * np.exp(1j * np.angle(a["tone_F2"]))
    if squeal:
        onset = _onset(sim, case)
        n = int(round(onset.duration * A.FS))
        p = A.tones(f[tone], tone_p, n) + A.shaped_noise(f[~tone], p2[~tone], n, seed=SEED)
        p = A.apply_onset(p, onset)
    else:
        onset = A.Onset(t=np.array([0.0, A.HOLD_S]), gain=np.zeros(2), t_limit_cycle=0.0, t_history=float("nan"),
                        duration=A.HOLD_S)
        p = np.zeros(int(round(A.HOLD_S * A.FS)))
    pcm, ppc = A.to_pcm16(p)
    wav_L, wav_f = _read_back(pcm, ppc, onset)
    arrays = {
        "distance": np.float64(lis["distance"]), "height": np.float64(lis["height"]),
        "ground_depth": np.float64(lis["ground_depth"]), "ground": np.array(lis["ground"]),
        "directivity": np.array(lis["directivity"]), "h_source": np.float64(geo.h_source),
        "h_receiver": np.float64(geo.h_receiver), "horizontal": np.float64(geo.distance),
        "r_direct": np.float64(geo.paths()[0][0]), "r_image": np.float64(geo.paths()[1][0]),
        "f": f, "is_tone": tone, "W": W, "p2": p2, "p2_incoherent": p2i, "A_weight": Aw,
        "L_p": np.float64(L.level(p2.sum())), "L_pA": np.float64(L.level((p2 * gA).sum())),
        "L_p_incoherent": np.float64(L.level(p2i.sum())), "L_pA_incoherent": np.float64(L.level((p2i * gA).sum())),
        "f_peak": np.float64(f[np.argmax(p2)] if p2.max() > 0 else np.nan), "f_sound": np.float64(a["f_sound"]),
        "L_W": np.float64(a["L_W"]), "L_F2": np.float64(a["L_F2"]), "meaningful": np.bool_(squeal),
        "silent": np.bool_(not squeal), "band_nominal": bands.nominal, "band_centre": bands.centre,
        "band_lower": bands.lower, "band_upper": bands.upper, "band_L_p": L.level(b), "band_L_pA": L.level(bA),
        "outside_p2": np.float64(out), "tone_f": f[tone], "tone_p": tone_p, "fs": np.int64(A.FS),
        "pa_per_count": np.float64(ppc), "full_scale_sine_dB": np.float64(A.full_scale_sine_level(ppc, L.P_REF)),
        "wav_duration": np.float64(pcm.size / A.FS), "t_limit_cycle": np.float64(onset.t_limit_cycle),
        "t_history_start": np.float64(onset.t_history), "onset_t": onset.t, "onset_gain": onset.gain,
        "wav_L_p": np.float64(wav_L), "wav_f_peak": np.float64(wav_f),
    }
    cal = calibration(arrays, case)
    return arrays, A.wav_bytes(pcm, A.FS, cal["comment"]), cal, cfg


def _read_back(pcm, pa_per_count: float, onset) -> tuple[float, float]:
    """Level (dB re 20 uPa) and dominant frequency of the sound's limit-cycle part
    (after the onset, without the end fade), from the int16 samples."""
    i0, i1 = int(np.ceil(onset.t_limit_cycle * A.FS)), pcm.size - int(round(A.FADE_S * A.FS))
    x = pcm[i0:i1].astype(float) * pa_per_count
    if x.size < 16 or not np.any(x):
        return -np.inf, float("nan")
    fr, X = amplitude_spectrum(x, 1 / A.FS)
    return float(level(np.mean(x**2))), dominant_frequency(fr, X, f_min=20.0)[0]


def calibration(a: dict, case: str) -> dict:
    """The sidecar's fields (and the WAV comment)."""
    lc = (f"{float(a['t_limit_cycle']):.3f} s" if not a["silent"] else "none (silent)")
    comment = (f"squeal of case {case} at {float(a['distance'])} m from the track centre, {float(a['height'])} m above "
               f"the rail; sample value v -> v * {float(a['pa_per_count']):.6e} Pa; 0 dBFS sine = "
               f"{float(a['full_scale_sine_dB']):.2f} dB SPL re 20 uPa; limit cycle from {lc}: L_p = "
               f"{float(a['L_p']):.2f} dB, L_pA = {float(a['L_pA']):.2f} dB(A)")
    return {
        "wav": f"listen_{receiver_tag(a['distance'], a['height'])}.wav", "sample_rate_hz": int(a["fs"]), "bits": 16, "channels": 1,
        "pa_per_count": float(a["pa_per_count"]),
        "full_scale_sine_dB_SPL": float(a["full_scale_sine_dB"]),
        "calibration": "sample value v (int16) is v * pa_per_count Pa; a full-scale sine (peak 32767) has "
                       "full_scale_sine_dB_SPL dB re 20 uPa",
        "limit_cycle_start_s": float(a["t_limit_cycle"]), "duration_s": float(a["wav_duration"]),
        "L_p_dB": _num(a["L_p"]), "L_pA_dB": _num(a["L_pA"]), "L_p_incoherent_dB": _num(a["L_p_incoherent"]),
        "wav_L_p_dB": _num(a["wav_L_p"]), "f_peak_hz": _num(a["f_peak"]), "f_sound_hz": _num(a["f_sound"]),
        "silent": bool(a["silent"]),
        "receiver": {k: (str(a[k]) if a[k].dtype.kind == "U" else float(a[k]))
                     for k in ("distance", "height", "ground_depth", "ground", "directivity", "h_source",
                               "h_receiver", "horizontal", "r_direct", "r_image")},
        "assumptions": ["wheel centre as a point source abreast of the receiver, on the rail nearer to it",
                        "directivity: " + ("dipole along the axle, Q = 3 cos^2 theta" if str(a["directivity"]) ==
                                           "dipole" else "omnidirectional"),
                        "ground: " + ("rigid plane, image source, tones added coherently" if str(a["ground"]) ==
                                      "rigid" else "none (free field)"),
                        "air absorption ISO 9613-1 at 20 degC, 70 % RH", "no shielding, no Doppler shift",
                        "onset: F2 envelope of the simulation's growth phase; then the limit cycle"],
        "comment": comment,
    }


def _num(x):
    x = float(x)
    return x if np.isfinite(x) else None


ISO_HEIGHT = 1.2  # m, ISO 3095's receiver height: a receiver at it is named by its distance alone


def receiver_tag(distance: float, height: float) -> str:
    """The receiver's name in file names: '7.5m' (at the ISO 3095 height 1.2 m), else '25m_3.5m'."""
    return f"{float(distance):g}m" + ("" if float(height) == ISO_HEIGHT else f"_{float(height):g}m")


def listen_files(case: str, tag: str) -> dict:
    """{kind: path} of one receiver's artifacts ('npz', 'wav', 'json', 'png', 'bands')."""
    out = paths.case_dir(case)
    return {k: out / f"listen_{tag}{s}" for k, s in (("npz", ".npz"), ("wav", ".wav"), ("json", ".json"),
                                                       ("png", ".png"), ("bands", "_bands.csv"))}


BAND_COLUMNS = ["band_nominal_hz", "band_centre_hz", "band_lower_hz", "band_upper_hz", "L_p_dB", "L_pA_dB"]


def band_rows(a: dict) -> list[list[float]]:
    """Rows of listen_<tag>_bands.csv (every band, -inf where a band holds nothing)."""
    return [[float(x) for x in row] for row in zip(a["band_nominal"], a["band_centre"], a["band_lower"],
                                                    a["band_upper"], a["band_L_p"], a["band_L_pA"])]


def run_listen(case: str, distance=None, height=None, allow_silent: bool = False, passby: bool = True) -> dict:
    """Listen to ``case`` at its receiver (or ``distance``, ``height``), and its pass-by when it is heard
    and ``passby``."""
    arrays, wav, cal, cfg = compute_listening(case, distance, height, allow_silent)
    tag = receiver_tag(arrays["distance"], arrays["height"])
    files = listen_files(case, tag)
    plot_listening(arrays, files["png"], case)
    with artifacts.atomic_write(files["wav"]) as tmp:
        tmp.write_bytes(wav)
    artifacts.save_sidecar(files["json"], "listen-wav", cfg, cal)   # flat: keys at the top (docs/reference.md)
    artifacts.save_csv(files["bands"], BAND_COLUMNS, band_rows(arrays))
    artifacts.save_npz(files["npz"], "listen", cfg, **arrays)
    if arrays["meaningful"] and passby:
        from pipeline.stages.passby import run_passby  # here: Make's DEPS of the module's other entry points stay without it

        c, _, _, geo = listener_inputs(case, distance, height)
        rad, _ = artifacts.load_npz(paths.case_dir(case) / "radiate.npz", "radiate")
        run_passby(case, c, geo, rad, cfg, tag)
    own = listener_inputs(case)[2]
    if (own["distance"], own["height"]) == (float(arrays["distance"]), float(arrays["height"])):
        artifacts.save_npz(paths.case_dir(case) / "listen.npz", "listen", cfg, **arrays)  # Make's target
    log.info("listen %s: receiver %.2f m from the track, %.2f m above the rail: L_p = %.1f dB, L_pA = %.1f dB(A) "
             "(incoherent ground %.1f dB), loudest %.1f Hz%s; %.2f s WAV (0 dBFS sine = %.1f dB SPL) -> %s",
             case, arrays["distance"], arrays["height"], arrays["L_p"], arrays["L_pA"], arrays["L_p_incoherent"],
             arrays["f_peak"], " (no squeal: silent file)" if arrays["silent"] else "", arrays["wav_duration"],
             arrays["full_scale_sine_dB"], files["wav"])
    return arrays


def receivers(case: str) -> list[str]:
    """Tags of the receivers computed for a case (listen_<tag>.npz), nearest first."""
    tags = [p.name[len("listen_"):-len(".npz")] for p in paths.case_dir(case).glob("listen_*.npz")]
    return sorted(tags, key=lambda s: tuple(float(x[:-1]) for x in s.split("_")))


def load_listening(case: str, tag: str | None = None) -> tuple[dict, dict]:
    """listen_<tag>.npz (``tag`` None: listen.npz, the case's own receiver), checked against the
    current radiate and simulate artifacts (its receiver may come from the command line, so the
    listener is the artifact's own)."""
    path = paths.case_dir(case) / ("listen.npz" if tag is None else f"listen_{tag}.npz")
    a, prov = artifacts.load_npz(path, "listen", make_target=f"listen CASE={case}")
    c, pw, _, _ = listener_inputs(case)
    _, _, cfg = listen_config(case, prov["config"]["listener"], pw)
    if config_hash(cfg) != prov["config_hash"]:
        raise artifacts.ArtifactError(path, f"stale artifact (its radiate, simulate, wheel or settings changed); "
                                      f"run `make listen CASE={case}`")
    return a, prov


def plot_listening(a: dict, path, case: str) -> None:
    """listen.png (``postprocess.plots.listen.listening_figure``), saved atomically to ``path``."""
    from postprocess.plots.listen import listening_figure  # here: Make's DEPS of the module's other entry points stay without it

    save_figure(listening_figure(a, case), path, dpi=90)
