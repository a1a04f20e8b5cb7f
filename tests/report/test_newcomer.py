"""What the newcomer found (issue 27), mended: the headline block and its verdict, the stability
figure with every pole, the friction curves with the operating slip, kernel lengths as samples."""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.stages.report_headline import headline_markdown, verdict
from postprocess.plots.contact import friction_curves_figure, mark_operating_slip, operating_point
from postprocess.plots.stability import screen_figure

CASE = {"contact": {"dy_wr": -0.015}, "friction": {"mu": 0.35}, "kinematics": {"gamma_y": -0.014}}


def _h(**kw):
    h = {"case": "x", "L_F2": 53.2, "f_dominant": 434.8, "stop_reason": "limit cycle", "verdict": "squeals",
         "L_W": 106.8, "f_sound": 434.7, "mode": "(2,0,a)", "mode_f": 434.1, "L_pA": 80.9, "receiver": (7.5, 1.2),
         "sigma_max": 9.69, "sigma_label": "(2,0,a)", "sigma_f": 434.6, "unstable": ["(2,0,a)"]}
    h.update(kw)
    return h


def test_verdict_separates_squeal_from_low_frequency_oscillation_and_silence():
    assert verdict(53.2, 434.8) == "squeals"
    assert verdict(40.0, 70.0) == "low-frequency oscillation"      # the wheelset on its suspension
    assert verdict(9.99, 434.8) == "does not squeal"
    assert verdict(float("nan"), 434.8) == "does not squeal"


def test_headline_block_names_frequency_mode_and_levels():
    text = headline_markdown(_h())
    first = text.splitlines()[0]
    assert "SQUEALS" in first and "434.7 Hz" in first and "(2,0,a)" in first
    assert "| 53.2 | 434.7 | (2,0,a) | 106.8 | 80.9 at 7.5 m, 1.2 m |" in text
    low = headline_markdown(_h(verdict="low-frequency oscillation", f_dominant=71.0, L_pA=None, sigma_max=None))
    assert "LOW-FREQUENCY OSCILLATION" in low and "71.0 Hz" in low and "`make listen`" in low
    assert "(not meaningful)" in low and "`make stability`" in low


def test_stability_figure_shows_every_pole():
    a = {"f_hz": np.array([15.0, 434.6, 3881.0, 4116.0]), "sigma": np.array([-7.7, 9.7, -243.9, -2586.0]),
         "label": np.array(["track", "(2,0,a)", "(1,0,c)", "(1,2,a)"])}
    fig = screen_figure(a, "x", CASE)
    lo, hi = fig.axes[0].get_ylim()
    assert lo < -2586.0 and hi > 9.7                         # nothing cut off (it was -30 1/s)
    shown = np.concatenate([ln.get_ydata() for ln in fig.axes[0].lines if len(ln.get_ydata()) and
                            ln.get_linestyle() == "None"])
    assert set(a["sigma"]) <= set(shown)


def test_friction_curves_mark_the_operating_slip():
    s = np.linspace(0, 0.5, 51)
    a = {"mu_values": np.array([0.3, 0.35]), "rf_n": np.array([51, 51]),
         "rf_s": np.vstack([s, s]), "rf_mu": np.vstack([0.3 * np.tanh(s / 0.05), 0.35 * np.tanh(s / 0.05)])}
    v, gy = 50 / 3.6, -0.014
    s_op, mu_op = operating_point(a, v, gy, 0.0, 0.35)
    assert s_op == pytest.approx(0.014 * v)
    assert mu_op == pytest.approx(0.35 * np.tanh(s_op / 0.05), rel=2e-3)       # on the curve, linear interpolation
    assert np.isnan(operating_point(a, v, gy, 0.0, 0.5)[1])                    # no curve for that mu
    fig = mark_operating_slip(friction_curves_figure(a, "x"), a, s_op, 0.35)
    marks = [ln for ln in fig.axes[0].lines if ln.get_marker() == "o"]
    assert len(marks) == 1 and marks[0].get_xdata()[0] == pytest.approx(s_op)


def test_greens_section_writes_kernel_lengths_as_samples(monkeypatch, tmp_path):
    import pipeline.stages.report as R

    a = {"wheel_f": np.ones(37), "wheel_nt": np.int64(2834352), "dt": np.float64(36e-6),
         "wheel_decay_db": np.float64(-126.0), "rail_kernel": np.zeros((4096, 2, 2)),
         "rail_tail_ratio": np.float64(1.3e-4)}
    monkeypatch.setattr(R.artifacts, "load_npz", lambda *x, **k: (a, {}))
    monkeypatch.setattr(R.shutil, "copy2", lambda *x: None)
    monkeypatch.setattr(R, "greens_inputs", lambda case: ({},))
    text = R.greens_section("default", tmp_path)
    assert "N_t = 2834352 samples" in text and "4096 lags" in text
    assert " s," not in text and " ms)" not in text and "(102 s" not in text
