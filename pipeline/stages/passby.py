"""The pass-by, run by the listen stage for each receiver: the case's train (``[listener.passby]``:
squealing wheels, their spacing; the case's speed) passing the receiver of ``[listener]`` (or
``--distance``/``--height``), the sound and its levels from ``postprocess/listening/passby.py``.

Artifacts in build/cases/<case>/, per receiver ``<tag>`` (as listen_<tag>.*):

* passby_<tag>.npz: 'L_Aeq' (dB(A), over the passage window 'T' s), 'L_AE' (re 1 s), 'L_AFmax',
  't_AFmax' (s from the start), 'L_eq' (unweighted), 'n_bogies', 'bogie_spacing', 'window',
  'speed' (m/s), 'kept_share' (of the sound power in the components synthesized), 'f', 'W' (those
  components), and the F-weighted level 't_F', 'L_AF' (dB(A), every 10 ms);
* passby_<tag>.wav: the passage, 44.1 kHz, 16-bit, calibrated as listen's (passby_<tag>.json);
* passby_<tag>.png: L_AF(t) and the instantaneous A-weighted level.
"""
from __future__ import annotations

import logging

import numpy as np

from pipeline.store import artifacts, paths
from pipeline.store.atomic import save_figure
from pipeline.config.loader import config_hash
from postprocess.listening.audio import FS
from postprocess.listening import audio as A

log = logging.getLogger("pipeline.listen")
SEED = 0  # the bogies' phases


def passby_files(case: str, tag: str) -> dict:
    out = paths.case_dir(case)
    return {k: out / f"passby_{tag}{s}" for k, s in (("npz", ".npz"), ("wav", ".wav"), ("json", ".json"),
                                                       ("png", ".png"))}


def compute_passby(c: dict, geo, rad: dict) -> tuple[dict, np.ndarray]:
    """(arrays of passby_<tag>.npz, the unweighted pressure signal in Pa) of the case ``c`` (validated
    dict) at the receiver ``geo`` (postprocess.listening.listener.Geometry) from radiate.npz's arrays."""
    from postprocess.listening import passby as P  # lazy: brings in scipy

    pb = c["listener"]["passby"]
    train = P.Train(pb["n_bogies"], pb["bogie_spacing"], c["kinematics"]["speed"], pb["window"])
    f, W, share = P.components(rad["f"], rad["W"], rad["is_tone"])
    _, (pA, p) = P.passby_signals(f, W, train, geo, FS, (True, False), seed=SEED)
    L = P.levels(pA, FS)
    LF = P.f_weighted(pA**2, FS)
    step = int(FS // 100)
    arrays = {"L_Aeq": np.float64(L["L_Aeq"]), "L_AE": np.float64(L["L_AE"]), "L_AFmax": np.float64(L["L_AFmax"]),
              "t_AFmax": np.float64(L["t_AFmax"]), "T": np.float64(L["T"]),
              "L_eq": np.float64(10 * np.log10(np.mean(p**2) / P.P_REF**2)),
              "n_bogies": np.int64(train.n_bogies), "bogie_spacing": np.float64(train.bogie_spacing),
              "window": np.float64(train.window), "speed": np.float64(train.speed), "kept_share": np.float64(share),
              "f": f, "W": W, "t_F": np.arange(0, LF.size, step) / FS,
              "L_AF": 10 * np.log10(np.maximum(LF[::step], 1e-30) / P.P_REF**2)}
    return arrays, p


def run_passby(case: str, c: dict, geo, rad: dict, listen_cfg: dict, tag: str) -> dict:
    """Compute and write the pass-by of one receiver (module docstring)."""
    from postprocess.plots.passby import passby_figure  # here: Make's DEPS of the module's other entry points stay without it

    arrays, p = compute_passby(c, geo, rad)
    cfg = {"listen": config_hash(listen_cfg), "passby": c["listener"]["passby"], "speed": c["kinematics"]["speed"],
           "seed": SEED}
    files = passby_files(case, tag)
    pcm, ppc = A.to_pcm16(p)
    cal = {"wav": files["wav"].name, "sample_rate_hz": A.FS, "bits": 16, "channels": 1, "pa_per_count": float(ppc),
           "full_scale_sine_dB_SPL": float(A.full_scale_sine_level(ppc, 20e-6)),
           "L_Aeq_dB": float(arrays["L_Aeq"]), "L_AFmax_dB": float(arrays["L_AFmax"]), "T_s": float(arrays["T"])}
    save_figure(passby_figure(arrays, f"{case}: pass-by at receiver {tag}"), files["png"], dpi=90)
    with artifacts.atomic_write(files["wav"]) as tmp:
        tmp.write_bytes(A.wav_bytes(pcm, A.FS, f"pass-by of case {case} at receiver {tag}; sample value v -> "
                                                 f"v * {ppc:.6e} Pa"))
    artifacts.save_sidecar(files["json"], "passby-wav", cfg, cal)   # flat: keys at the top (docs/reference.md)
    artifacts.save_npz(files["npz"], "passby", cfg, **arrays)
    log.info("pass-by %s at %s: %d squealing wheels %.1f m apart at %.0f km/h: L_pAeq = %.1f dB(A) over %.1f s, "
             "L_AFmax = %.1f dB(A), L_AE = %.1f dB(A) -> %s", case, tag, arrays["n_bogies"], arrays["bogie_spacing"],
             3.6 * arrays["speed"], arrays["L_Aeq"], arrays["T"], arrays["L_AFmax"], arrays["L_AE"], files["npz"])
    return arrays
