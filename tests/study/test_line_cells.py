"""line.csv holds no -inf or nan (issue 33): a value that does not exist (a 1/3-octave band the squeal
puts no sound in: L_W = -inf dB; a quiet curve's frequency and levels: nan) is an empty cell, as
line.md states.  The outputs written from two rows as the line's workers return them: one squealing
(its L_W in the 24 NoiseModelling bands, the lowest ones empty of sound), one quiet."""
from __future__ import annotations

import csv
import math

import numpy as np

NAN = float("nan")


def _rows():
    from pipeline.study.line_worker import band_columns

    bands = band_columns()
    base = {"chainage_m": 0.0, "cant_mm": 100.0, "length_m": 50.0, "vehicle": "c20_metro", "mu": 0.35,
            "curve": "t", "note": "", "wall_s": 1.0, "aoa_mrad": 20.0, "time_loop_wheels": "a1i"}
    level = np.linspace(60.0, 105.0, len(bands))
    level[:3] = -np.inf                                        # no sound below the squeal's first harmonic
    loud = base | {"id": "A", "radius_m": 75.0, "speed_kmh": 31.0, "friction": "dry", "squeals": True,
                   "wheel": "a1i", "f_squeal": 435.297, "mode": "(2,0,a)", "L_pA": 78.3374, "L_W": 104.29,
                   "L_F2": 49.977, "squealing_wheels": "a1i", "unstable_wheels": "a1i"} | dict(zip(bands, level)) | {
                   "climate": "default", "mu_onset": "0.3374", "wheel_onset": "a1i", "f_onset": 435.08,
                   "mode_onset": "(2,0,a)", "p_squeal": 0.0232, "axles_p_squeal": 0.0116, "L_pAmax_7m5": 80.08,
                   "L_pAmax_rolling": 69.43, "L_pAeq_rolling": 68.80, "dL_squeal": 0.2554}
    quiet = base | {"id": "B", "chainage_m": 600.0, "radius_m": 600.0, "speed_kmh": 70.0, "friction": "wet",
                    "squeals": False, "wheel": "", "f_squeal": NAN, "mode": "", "L_pA": NAN, "L_W": NAN,
                    "L_F2": -40.0, "squealing_wheels": "", "unstable_wheels": ""} | {b: NAN for b in bands} | {
                    "climate": "default", "mu_onset": ">0.4", "wheel_onset": "a1o", "f_onset": NAN, "mode_onset": "",
                    "p_squeal": 0.0, "axles_p_squeal": 0.0, "L_pAmax_7m5": NAN, "L_pAmax_rolling": 78.6,
                    "L_pAeq_rolling": 77.9, "dL_squeal": 0.0}
    return bands, [loud, quiet]


def test_line_csv_has_no_inf_or_nan(tmp_path):
    from pipeline.study.line_outputs import write_outputs

    bands, rows = _rows()
    spec = {"name": "t", "curves": "t.csv", "export": {"passages_day": 1.0, "passages_evening": 1.0,
                                                      "passages_night": 1.0}}
    write_outputs(spec, str(tmp_path / "t.toml"), tmp_path, False, rows, rows)
    table = list(csv.DictReader(open(tmp_path / "line.csv", newline="")))
    for r in table + list(csv.DictReader(open(tmp_path / "line_classes.csv", newline=""))):
        for k, v in r.items():
            assert v.strip().lower() not in ("inf", "-inf", "+inf", "nan"), (r.get("id"), k, v)
    a, b = table
    assert [a[c] for c in bands[:3]] == ["", "", ""]           # -inf dB: no sound in the band
    assert float(a[bands[-1]]) == 105.0 and float(a["L_pA"]) == 78.3374
    assert b["f_squeal"] == "" and b["L_pA"] == "" and all(b[c] == "" for c in bands)
    assert b["L_pAmax_7m5"] == "" and b["mu_onset"] == ">0.4" and a["p_squeal"] == "0.0232"   # issue 32's columns
    # the bands that hold sound keep their levels: their power sum is the input's
    level = np.array([rows[0][c] for c in bands])
    total = 10 * math.log10(sum(10 ** (float(a[c]) / 10) for c in bands if a[c]))
    assert abs(total - 10 * math.log10(np.sum(10 ** (level[np.isfinite(level)] / 10)))) < 1e-3
    assert "empty cell" in (tmp_path / "line.md").read_text()
