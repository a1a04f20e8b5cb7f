"""The WAVs' calibration sidecars are flat, as the README documents them (issue 33: their keys sat under
`payload`): `listen_<receiver>.json` has `pa_per_count`, `full_scale_sine_dB_SPL`, `limit_cycle_start_s`,
`L_p_dB`, `L_pA_dB`, the receiver and the assumptions at its top level, beside its provenance; the
pass-by's `passby_<receiver>.json` likewise.  The listen stage runs for real on the default case in a
private build (its simulate and radiate artifacts linked); the calibration is checked on the WAV read
back with scipy (an independent reader): its limit cycle's level is the sidecar's `wav_L_p_dB`."""
from __future__ import annotations

import json

import numpy as np
import pytest

from tests.private_build import default_case_build
from pipeline.validation.references import wavcheck as WC



def test_listen_and_passby_sidecars_are_flat(tmp_path, monkeypatch):
    build = default_case_build(tmp_path, monkeypatch, ("contact", "greens", "simulate", "radiate"), "needs the default case built up to radiate (make)")
    from pipeline.stages.listen import run_listen

    a = run_listen("default")
    d = build / "cases" / "default"
    doc = json.loads((d / "listen_7.5m.json").read_text())
    assert "payload" not in doc
    assert doc["__provenance__"]["kind"] == "listen-wav"
    for key in ("pa_per_count", "full_scale_sine_dB_SPL", "limit_cycle_start_s", "L_p_dB", "L_pA_dB", "receiver",
                "assumptions", "wav"):
        assert key in doc, key
    assert doc["wav"] == "listen_7.5m.wav" and doc["receiver"]["distance"] == 7.5
    assert doc["L_pA_dB"] == pytest.approx(float(a["L_pA"]), abs=1e-9)
    fs, p, lc, cal = WC.read_calibrated(d / "listen_7.5m.wav", d / "listen_7.5m.json")
    assert WC.level(lc) == pytest.approx(doc["wav_L_p_dB"], abs=0.05)
    # a 0 dBFS sine is full_scale_sine_dB_SPL: 32767 counts peak, RMS 32767 / sqrt 2
    assert 20 * np.log10(32767 / np.sqrt(2) * doc["pa_per_count"] / 20e-6) == pytest.approx(
        doc["full_scale_sine_dB_SPL"], abs=1e-6)
    pb = json.loads((d / "passby_7.5m.json").read_text())
    assert "payload" not in pb and pb["__provenance__"]["kind"] == "passby-wav"
    for key in ("pa_per_count", "full_scale_sine_dB_SPL", "L_Aeq_dB", "L_AFmax_dB", "T_s", "wav"):
        assert key in pb, key
