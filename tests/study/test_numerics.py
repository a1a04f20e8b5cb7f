"""solvers/study.py: grids, the squeal criterion, the mode of a squeal, the single-mode
damping, the harmonic fit of a periodic response and the damping procedure (driven by a
synthetic stability oracle with known critical dampings)."""
import math

import numpy as np
import pytest

from solvers.study import (Outcome, damping_procedure, grid, harmonic_response, nearest_mode,
                           periodic_creepage, relative_difference, single_mode_damping, squeals)


def test_the_spec_map_grid_has_330_points_per_position():
    g = grid(-0.002, -0.06, 0.002)
    m = grid(0.10, 0.60, 0.05)
    assert len(g) == 30 and len(m) == 11 and len(g) * len(m) == 330
    assert g[0] == -0.002 and g[-1] == -0.06 and np.all(np.diff(g) < 0)
    assert m[-1] == 0.6 and 0.35 in m and -0.014 in g                # exact: keys and lookups are stable
    assert list(grid(0.1, 0.6, 0.1)) == [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
    with pytest.raises(ValueError):
        grid(0.0, 1.0, 0.0)


def test_squeal_criterion_and_mode_of_a_squeal():
    assert squeals(10.0) and not squeals(9.99) and not squeals(float("nan")) and not squeals(-math.inf)
    f = np.array([6.8, 9.7, 248.3, 334.5, 438.2, 1161.4])
    flex = np.array([0, 0, 1, 1, 1, 1], bool)
    assert nearest_mode(440.0, f, flex) == 4
    assert nearest_mode(8.0, f, flex) is None                         # only flexible candidates
    assert nearest_mode(9.5, f) == 1 and nearest_mode(8.0, f) is None  # 6.8 Hz nearest, but 18 % off
    assert nearest_mode(800.0, f, flex, rel_tol=0.05) is None         # nothing within 5 %
    assert nearest_mode(float("nan"), f, flex) is None
    assert nearest_mode(876.0, f, flex) is None and nearest_mode(876.0, f, flex, harmonics=(1, 2, 3)) == 4
    assert nearest_mode(1160.0, f, flex, harmonics=(1, 2, 3)) == 5          # the fundamental wins


def test_single_mode_damping_keeps_the_suspension():
    z0 = np.array([0.18, 0.25, 0.08, 1e-2, 1e-3, 1e-4, 1e-4])
    flex = np.array([0, 0, 0, 1, 1, 1, 1], bool)
    z = single_mode_damping(z0, 5, flex, 1e-6, 1.0)
    assert list(z) == [0.18, 0.25, 0.08, 1.0, 1.0, 1e-6, 1.0]
    assert list(z0) == [0.18, 0.25, 0.08, 1e-2, 1e-3, 1e-4, 1e-4]    # input untouched


@pytest.mark.parametrize("f", [100.0, 1000.0, 5000.0])
def test_harmonic_response_of_a_sampled_sinusoid(f):
    dt = 36e-6
    n = int(round(0.05 / dt))
    t = np.arange(n) * dt
    x = 123.0 + 7.5 * np.sin(2 * np.pi * f * t + 0.7) + 0.3 * np.sin(2 * np.pi * 2 * f * t)
    h = harmonic_response(x, dt, f, 5)
    assert abs(h["mean"] - 123.0) < 0.02 and abs(h["amplitude"] - 7.5) < 0.02
    assert abs(np.angle(np.exp(1j * (h["phase"] - 0.7)))) < 0.005
    pure = harmonic_response(123.0 + 7.5 * np.sin(2 * np.pi * f * t + 0.7), dt, f, 5)
    assert abs(pure["amplitude"] - 7.5) < 1e-9 and abs(pure["mean"] - 123.0) < 1e-9
    g = periodic_creepage(-0.003, 0.001, f, dt, n)
    assert abs(harmonic_response(g, dt, f, 3)["amplitude"] - 0.001) < 1e-12
    with pytest.raises(ValueError):
        harmonic_response(x[:10], dt, f, 50)


def test_relative_difference():
    assert relative_difference(1.1, 1.0) == pytest.approx(0.1)
    assert relative_difference(-0.9, -1.0) == pytest.approx(0.1)
    assert math.isnan(relative_difference(1.0, 0.0)) and math.isnan(relative_difference(float("nan"), 1.0))


# ---------------------------------------------------------------------------- damping procedure

F = np.array([6.8, 9.7, 15.3, 248.0, 438.0, 1161.0, 2086.0, 3100.0])
FLEX = np.array([0, 0, 0, 1, 1, 1, 1, 1], bool)
Z0 = np.array([0.18, 0.25, 0.08, 1e-2, 1e-4, 1e-4, 1e-4, 1e-4])


class Oracle:
    """A wheel whose mode i squeals while its damping is below a critical value: zc_full[i] with
    the other modes present, zc_alone[i] with only the suspension.  The full model squeals at the
    unstable mode with the largest zc / zeta; f_dominant 0.3 % above the mode."""

    def __init__(self, zc_full, zc_alone):
        self.zc_full, self.zc_alone = np.asarray(zc_full, float), np.asarray(zc_alone, float)
        self.calls = []

    def __call__(self, req):
        self.calls.append(req)
        z = np.asarray(req.zeta)
        zc = self.zc_alone if req.model == "reduced" else self.zc_full
        cand = [i for i in req.modes if FLEX[i] and z[i] < zc[i]]
        if not cand:
            return Outcome(-30.0, 1000.0)
        i = max(cand, key=lambda j: zc[j] / z[j])
        return Outcome(60.0, 1.003 * F[i])


def drive(oracle, **kw):
    gen = damping_procedure(Z0, F, FLEX, **kw)
    batch = next(gen)
    labels = []
    try:
        while True:
            labels += [r.label for r in batch]
            batch = gen.send([oracle(r) for r in batch])
    except StopIteration as stop:
        return stop.value, labels


def test_damping_procedure_finds_the_succession_and_the_critical_dampings():
    #            rigid x3   (1,0,a) (2,0,a) (3,0,a)  (4,0,a)  (5,0,a)
    zc_full = [0, 0, 0, 1e-3, 2.0e-3, 5.0e-4, 3.0e-4, 5e-5]
    zc_alone = [0, 0, 0, 1e-3, 2.0e-3, 4.0e-4, 5.0e-5, 5e-5]
    # (2,0,a) (zc/zeta = 20) squeals first, then (3,0,a) (5), damped alone to ~4e-4 where it is still
    # unstable with the other modes; (4,0,a) (3) takes over, does not squeal alone (5e-5 < 1e-4), so it is
    # bisected in the full model, where (3,0,a) competes: taken out of that bisection; then (3,0,a)
    # squeals again and is bisected in the full model; then quiet.
    o = Oracle(zc_full, zc_alone)
    res, labels = drive(o, rel_tol=0.05, zeta_max=0.1)
    assert len(labels) == len(set(labels))                               # every simulation has its own key
    assert res.end.startswith("quiet")
    assert [s.mode for s in res.steps] == [4, 5, 6, 5, None]
    assert [s.bisection_model for s in res.steps[:-1]] == ["reduced", "reduced", "full", "full"]
    assert res.steps[2].excluded == [5] and res.steps[3].excluded == []
    for s in res.steps[:-1]:
        true = (zc_alone if s.bisection_model == "reduced" else zc_full)[s.mode]
        assert s.zeta_lo < true <= s.zeta_hi and s.zeta_hi / s.zeta_lo - 1 <= 0.05
    # bisection count: log2 of the bracket's log-width over log(1 + tol), plus the bracket checks
    n_bis = math.ceil(math.log2(math.log(0.1 / 1e-4) / math.log(1.05)))
    assert res.steps[0].runs == 2 + n_bis
    assert [res.zeta[i] for i in (4, 5, 6)] == [res.steps[0].zeta_hi, res.steps[3].zeta_hi, res.steps[2].zeta_hi]
    assert all(res.zeta[i] == Z0[i] for i in (0, 1, 2, 3, 7))
    for c in o.calls:
        if c.model == "reduced":
            assert set(c.modes) == {0, 1, 2, c.mode}                         # the mode plus the suspension
        elif c.step == 2 and c.mode == 6:
            assert set(c.modes) in ({*range(8)}, {*range(8)} - {5})


def test_damping_procedure_ends():
    quiet, _ = drive(Oracle([0] * 8, [0] * 8))
    assert quiet.end.startswith("quiet") and len(quiet.steps) == 1 and quiet.steps[0].mode is None
    o = Oracle([0, 0, 0, 0, 0.5, 0, 0, 0], [0, 0, 0, 0, 0.5, 0, 0, 0])
    loud, _ = drive(o, zeta_max=0.1)
    assert loud.end == "a mode squeals at the largest damping tried" and loud.steps[0].zeta_lo == 0.1
    many, _ = drive(Oracle([0, 0, 0, 1e-3, 2e-3, 5e-4, 3e-4, 5e-5], [0, 0, 0, 1e-3, 2e-3, 5e-4, 3e-4, 5e-5]),
                    max_steps=1)
    assert many.end.startswith("stopped after 1 steps") and [s.mode for s in many.steps] == [4, 5]

    class Low(Oracle):
        def __call__(self, req):
            return Outcome(60.0, 77.0)                                       # e.g. the wheelset on the track
    off, _ = drive(Low([0] * 8, [0] * 8))
    assert off.end == "squeal not at a wheel mode" and "77.0 Hz" in off.steps[0].note
