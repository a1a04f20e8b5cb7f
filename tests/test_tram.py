"""The tram (issue 32): its wheel, vehicle and curve files read by the pipeline's own readers, their
published numbers (Wikipedia "M28 (tram)": 680 mm wheels, 1.800 m axle distance, 7.000 m bogie
centres, 16.8 t empty, 38 + 78 places, Bo'Bo'), its steady curving in the tightest radius class, and
its wheel modes from the wheel stage's artifact (docs/tram.md)."""
from __future__ import annotations

import pytest

from pipeline.config import curve_inputs as inputs
from pipeline.curve.curving import solve_curve
from pipeline.stages.wheel import load_wheel
from pipeline.validation.references.curving_cases import RESIDUAL

G = 9.81


def test_tram_files_validate_with_their_published_numbers():
    p, _ = load_wheel("tram")
    assert 2 * p["tyre"]["rolling_radius"] == pytest.approx(0.680)          # [M28] wheel diameter
    v = inputs.read_vehicle("tram")
    assert v.name == "tram" and v.wheel == "tram"
    assert v.bogie.wheelbase_m == 1.8 and v.train.bogie_spacing_m == 7.0   # [M28]
    # [M28] 16.8 t empty + (38 + 78) passengers at 80 kg, over 8 wheels
    q_ref = (16.8e3 + (38 + 78) * 80.0) * G / 8
    assert v.wheel_load_N == pytest.approx(q_ref, rel=0.005)
    # the wheel file's flange back and the vehicle's back-to-back agree: 2 (z_rc - back_offset)
    b2b = 2 * (p["axle"]["rolling_circle_z"] - p["tyre"]["back_offset"]) * 1e3
    assert v.bogie.back_to_back_mm == pytest.approx(b2b, abs=0.5)
    for name, radius in (("tram_r25", 25.0), ("tram_r100", 100.0)):
        c = inputs.read_curve(name)
        assert c.vehicle.name == "tram" and c.radius_m == radius and c.rail == "60e1"


def test_tram_in_25_m_is_in_equilibrium_and_flanging():
    """R = 25 m: residuals below 1e-8 of the wheel load, the leading outer wheel on its flange, the wheel
    loads carrying the two axle loads, and the leading wheelset's angle of attack above the radial
    position's a/R but below the rigid bogie's a/R + (clearance shift)/(2a) bound of 2a/R."""
    s = solve_curve("tram_r25")
    assert s.max_residual < RESIDUAL
    lead, trail = s.solution.wheelsets
    assert lead.flange == 1 and lead.flange_force > 0
    Q = sum(w.wheel_load for w in s.wheels)
    assert Q == pytest.approx(4 * s.vehicle_model.wheel_load, rel=0.02)
    a, R = 0.9, 25.0
    assert a / R < lead.psi < 2 * a / R
    # the two wheelsets' yaw difference: at most the rigid bogie's 2a/R (yaw-compliant primary: less)
    assert 0.9 * 2 * a / R < lead.psi - trail.psi <= 2 * a / R + 1e-9
