"""The limit-cycle measures of issue 28 (``postprocess.limit_cycle_measures``) on inputs with known answers:
the knee of a curve given in closed form, a mode's response off resonance, the sound power's
face velocity, and which bound synthetic slip/force records sit on."""
from __future__ import annotations

import numpy as np

from postprocess.limit_cycle_measures import (RHO_C, bound_of, curve, cycle_measures, face_velocity_for_level, knee_slip,
                                     sdof_detuning)
from solvers.contact.friction import monotone_slopes

MU, A = 0.35, 0.03          # mu_RF(s) = MU tanh(s / A): knee (0.99 MU) at A artanh(0.99)


def _curve():
    s = np.concatenate([np.linspace(0.0, 0.2, 400), [0.5, 1.0]])
    m = MU * np.tanh(s / A)
    return s, m, monotone_slopes(s, m)


def test_knee_of_a_closed_form_curve():
    sn, mn, sl = _curve()
    assert abs(knee_slip(sn, mn, sl) - A * np.arctanh(0.99 * MU / mn[-1])) < 2e-4
    assert np.allclose(curve(np.array([0.01, 0.05]), sn, mn, sl), MU * np.tanh(np.array([0.01, 0.05]) / A), atol=1e-5)


def test_detuning_of_a_mode():
    assert sdof_detuning(434.0, 434.0, 1e-4) == (0.0, 0.0)
    bw, db = sdof_detuning(434.0 * (1 + 1e-4), 434.0, 1e-4)       # one half-power bandwidth off: -3 dB
    assert abs(bw - 1.0) < 1e-9 and abs(db + 10 * np.log10(2)) < 0.01
    assert abs(sdof_detuning(434.0 * 1.1, 434.0, 1e-4)[1] - 20 * np.log10(2e-4 / (1.21 - 1))) < 0.01


def test_face_velocity_gives_the_level_back():
    v = face_velocity_for_level(120.0, 0.15, 0.9)
    assert abs(10 * np.log10(RHO_C * 0.15 * 0.9 * v**2 / 1e-12) - 120.0) < 1e-9
    assert abs(v - 0.134) < 0.002                                   # the scale check


def _records(amp, s0=0.2, loss=False, n=4000):
    t = np.arange(n) * 1e-5
    s2 = -s0 + amp * np.sin(2 * np.pi * 434 * t)
    F3 = 65e3 + 2e3 * np.sin(2 * np.pi * 434 * t)
    if loss:
        F3[::50] = 0.0
    F = np.column_stack([np.zeros(n), MU * F3, F3])
    sn, mn, sl = _curve()
    state = np.where(F3 <= 0, 0, np.where(np.abs(s2) < knee_slip(sn, mn, sl), 1, 2))
    return cycle_measures(F, np.column_stack([np.zeros(n), s2]), state, 1e-5, v=10.0, gamma_y=-s0 / 10.0,
                          s_nodes=sn, mu_nodes=mn, slopes=sl, xi=np.zeros((n, 2)))


def test_bounds_of_synthetic_cycles():
    sn, mn, sl = _curve()
    margin = 0.2 - knee_slip(sn, mn, sl)
    m = _records(1.05 * margin)
    assert abs(m["margin"] - margin) < 1e-12 and abs(m["s2_swing_down"] - 1.05 * margin) < 1e-4
    assert m["reversal_share"] == 0 and m["share_partial"] > 0 and bound_of(m) == "saturation"
    assert bound_of(_records(0.3)) == "slip reversal"
    assert bound_of(_records(0.05, loss=True)) == "contact loss"
    assert bound_of(_records(0.0)) == "none"
    assert bound_of(_records(0.5 * margin)) == "other"
