"""The curving solver on the example line's curves where the active-set iteration alone stalled
(pipeline/studies/metro_line.csv: the C20 metro on dry rail mu = 0.4 and wet rail mu = 0.15): the
semismooth fallback (solvers/curving/semismooth.py) must find an equilibrium whose residuals,
recomputed from scratch, are below 1e-8 of the wheel load, with every unilateral condition met."""
from __future__ import annotations

import importlib

import numpy as np
import pytest

from solvers.curving import solve
from solvers.curving.wheelrail import zone_point

solve_mod = importlib.import_module("solvers.curving.solve")

# (row of metro_line.csv, radius m, cant mm, speed km/h, mu)
ROWS = [("C05 dry", 40.0, 102.0, 22.8, 0.4), ("C13 dry", 70.0, 102.0, 30.1, 0.4),
        ("C26 dry", 75.0, 102.0, 31.2, 0.4), ("C17 wet", 60.0, 102.0, 27.9, 0.15),
        ("C11 wet", 85.0, 102.0, 33.2, 0.15), ("C25 wet", 100.0, 102.0, 36.0, 0.15),
        ("C22 wet", 545.0, 71.0, 70.0, 0.15)]


def _problem(radius, cant, speed, mu):
    from pipeline.curve.curving import build_problem

    c, v, veh, trk, prof, law, names = build_problem("r150", radius_m=radius, cant_mm=cant, speed_kmh=speed, mu=mu)
    return veh, trk, prof, law


@pytest.mark.parametrize("row,radius,cant,speed,mu", ROWS, ids=[r[0] for r in ROWS])
def test_previously_failing_rows_reach_equilibrium(row, radius, cant, speed, mu):
    veh, trk, prof, law = _problem(radius, cant, speed, mu)
    sol = solve(prof, veh, trk, law)
    Q0 = veh.wheel_load
    # residuals recomputed from the solved state's contacts (not the solver's own number)
    from solvers.curving.model import wheelset_residual

    for ws in sol.wheelsets:
        r = np.array(wheelset_residual(ws.contacts, veh, trk, ws.F_susp, ws.M_susp)) / Q0
        assert np.max(np.abs(r)) < 1e-8, (row, r)
    Ff = -sum(ws.F_susp for ws in sol.wheelsets) + 2.0 * (2.0 * Q0 / 9.81 - veh.wheelset_mass) * trk.unbalanced()[0]
    Mf = (-sum(ws.M_susp + ws.x * ws.F_susp for ws in sol.wheelsets)
          - veh.secondary_yaw * (sol.frame_psi - 0.5 * veh.bogie_spacing / trk.radius))
    assert max(abs(Ff), abs(Mf)) / Q0 < 1e-8
    assert sol.max_residual < 1e-8
    for ws in sol.wheelsets:
        assert abs(ws.y) <= sol.flange_shift * (1 + 1e-12)       # no wheelset through its flange
        assert ws.flange_force >= 0.0                            # a flange pushes, never pulls
        for c in ws.contacts:
            assert c.N >= 0.0
        for side in (1, -1):
            tread = [c for c in ws.contacts if c.side == side and c.point.zone == "tread"]
            if len(tread) == 2:  # a two-point tread contact: both points equally low (the rigid contact)
                assert abs(tread[0].point.sep - tread[1].point.sep) < 1e-10
                assert abs(tread[0].point.y_wheel - tread[1].point.y_wheel) > 1e-3
                lowest = zone_point(prof.wheel, prof.rail, trk.c + side * ws.y, "tread", prof.edge)
                assert lowest.sep == pytest.approx(tread[0].point.sep, abs=1e-10)


def test_complementarity_form_is_continuous_across_its_switches():
    """The semismooth map's residual has no jump where a tread contact's second point or the
    flange takes over (what lets MINPACK cross them): a step of 1e-6 in w changes it by O(1e-6)."""
    from solvers.curving.semismooth import PLATEAU, Complementarity
    from solvers.curving.wheelrail import flange_shift

    veh, trk, prof, law = _problem(70.0, 102.0, 30.1, 0.15)
    y_f = flange_shift(prof.wheel, prof.rail, trk.c, prof.edge)
    cp = Complementarity(solve_mod.bogie_residual, 2, y_f, prof, veh, trk, law)
    assert len(cp.ev) >= 2  # the worn pair's tread jumps (both wheels)
    base = np.array([0.0, 20.0, -3.0, 0.95, 1.05, 0.0, 2.0, -3.0, 0.95, 1.05, -5.0, 15.0])
    switches = []
    for k, e in enumerate(cp.ev):
        a = 1e3 * e[0] + PLATEAU * (k - cp.n0)
        switches += [a, a + PLATEAU]
    k = len(cp.ev)
    switches.append(1e3 * y_f + PLATEAU * (k - cp.n0))
    for s in switches:
        lo, hi = base.copy(), base.copy()
        lo[5], hi[5] = s - 1e-6, s + 1e-6
        jump = np.max(np.abs(cp.residual(hi) - cp.residual(lo)))
        assert jump < 1e-3, (s, jump)
        # and round trip w -> (z, states) -> w
        assert cp.join(*cp.split(hi))[5] == pytest.approx(hi[5], abs=1e-9)
