"""Steady curving against independent solutions (issue 25, "Done when" (1)-(4))."""
from __future__ import annotations

import dataclasses
import math

import pytest

from solvers.curving import solve
from pipeline.validation.references.curving import pure_rolling_shift
from pipeline.validation.references.curving_cases import RESIDUAL, independent_conicity, linear_case, metro

@pytest.mark.parametrize("radius", [600.0, 1000.0, 2000.0])
def test_free_wheelset_takes_the_pure_rolling_shift(radius):
    """(1) y = r0 l0 / (lam R) within 1 %, lam the profile pair's equivalent conicity at that shift."""
    from scipy.optimize import brentq

    veh, trk, prof, law = metro(radius)
    sol = solve(prof, veh, dataclasses.replace(trk, speed=5.0), law, bogie=False)
    assert sol.max_residual < RESIDUAL
    y = sol.wheelsets[0].y

    def g(v):
        lam, l0 = independent_conicity(prof, trk.c, veh.r0, veh.rolling_circle, v)
        return v - pure_rolling_shift(veh.r0, l0, lam, radius)

    y_ref = brentq(g, 0.2e-3, 14e-3, xtol=1e-12)
    assert y == pytest.approx(y_ref, rel=0.01), (y, y_ref)
    assert sol.wheelsets[0].flange == 0


@pytest.mark.parametrize("kx,ky,radius", [(1e6, 1e6, 5000.0), (5e6, 0.5e6, 8000.0), (0.3e6, 3e6, 6000.0)])
def test_bogie_matches_the_linear_closed_form(kx, ky, radius):
    """(2) elastic primary yaw, large radius, linear creep, no flange: Boocock/Wickens within 1 %."""
    sol, (psi1, y1, psi_b, y2) = linear_case(kx, ky, radius)
    assert sol.max_residual < RESIDUAL
    lead, trail = sol.wheelsets
    assert lead.flange == 0 and trail.flange == 0
    assert lead.psi == pytest.approx(psi1, rel=0.01)
    assert lead.y == pytest.approx(y1, rel=0.01)
    assert trail.psi == pytest.approx(-psi1, rel=0.01)
    assert sol.frame_psi == pytest.approx(psi_b, rel=0.01)


def test_stiff_bogie_flanges_at_the_geometric_angle_of_attack():
    """(3) a stiff bogie on R = 150 m: leading outer wheel in flange contact, angle of attack the
    rigid bogie's a/R + (y_1 - y_2) / (2a)."""
    veh, trk, prof, law = metro(150.0, kx=1e8, ky=1e8)  # 10 x the metro's primary
    sol = solve(prof, veh, trk, law)
    assert sol.max_residual < RESIDUAL
    lead, trail = sol.wheelsets
    assert lead.flange == 1 and lead.flange_force > 0
    assert len([c for c in lead.contacts if c.side == 1]) == 2
    a = veh.semi_wheelbase
    geo = a / trk.radius + (sol.flange_shift - trail.y) / (2 * a)
    assert lead.psi == pytest.approx(geo, rel=0.01)
    assert lead.psi > a / trk.radius


@pytest.mark.parametrize("name", ["r150", "r300", "r100_cant", "y25_r300"])
def test_shipped_curves_are_in_equilibrium(name):
    """(4) every shipped curve: residuals below 1e-8 of the wheel load; the four wheels reported."""
    from pipeline.curve.curving import solve_curve

    s = solve_curve(name)
    assert s.max_residual < RESIDUAL
    assert [w.wheel for w in s.wheels] == ["a1o", "a1i", "a2o", "a2i"]
    for w in s.wheels:
        assert w.dy_wr == pytest.approx(w.dy_wr)  # finite
        assert (w.contact_points == 2) == (not math.isnan(w.nadal))
    lead = s.solution.wheelsets[0]
    assert s.wheels[0].dy_wr == pytest.approx(lead.y) and s.wheels[1].dy_wr == pytest.approx(-lead.y)
    # vertical equilibrium of the bogie: the wheel loads carry the two axle loads
    Q = sum(w.wheel_load for w in s.wheels)
    assert Q == pytest.approx(4 * s.vehicle_model.wheel_load, rel=0.02)



def test_traction_is_carried_by_the_creep_forces():
    """A tractive force per axle: each wheelset's longitudinal creep forces add up to it (the axle
    torque F r0 over the contacts' rolling radii: within 2 % on the trailing wheelset's treads,
    5 % on the leading one, whose flange contact rolls on a 3 % larger radius)."""
    veh, trk, prof, law = metro(300.0)
    sol = solve(prof, veh, dataclasses.replace(trk, tractive_force=10e3), law)
    assert sol.max_residual < RESIDUAL
    lead, trail = sol.wheelsets
    assert sum(c.force_on_wheel()[0] for c in trail.contacts) == pytest.approx(10e3, rel=0.02)
    assert sum(c.force_on_wheel()[0] for c in lead.contacts) == pytest.approx(10e3, rel=0.05)


@pytest.mark.validation
@pytest.mark.parametrize("curve", ["r150", "y25_r300"])
def test_both_vehicles_over_the_radius_are_in_equilibrium(curve):
    """(4) over R = 50 ... 1000 m (docs/validation/90_curving.md, its writer's ``sweep``): every residual
    below 1e-8 of the wheel load."""
    from pipeline.validation.writers.curving import sweep

    assert max(sweep(curve)["res"]) < RESIDUAL
