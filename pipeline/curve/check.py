"""``make check CURVE=<name>`` (``python -m pipeline check --curve <name>``): what the curve stage would
refuse, found before any of its work and without writing anything: the curve and vehicle files (their
schemas; the vehicle's ``name`` its file's), the wheel, rail and profile files they name (a missing one
named with the file and key that asked for it), the steady curving and every wheel's operating point
inside a case's range and the friction climate's
file (``stage.checked_cases``, the stage's own check).  One line per refusal (``pipeline.config.loader.ConfigError``)."""
from __future__ import annotations

from pipeline.curve.stage import checked_cases, solve


def check_curve(curve: str) -> list[str]:
    """The lines to print for a curve that the curve stage would run; ConfigError (one line) otherwise."""
    sol = solve(curve)
    info, points = sol.curve, sol.wheels
    checked_cases(info, points)
    aoa = ", ".join(f"{p.wheel} {1e3 * p.angle_of_attack:+.1f} mrad" for p in points)
    return [f"curve {info.name}: configuration OK (vehicle {info.vehicle.name}, wheel {info.wheel}, rail {info.rail}, "
            f"R = {info.radius:g} m, {info.speed_kmh:g} km/h; steady curving, angle of attack: {aoa})"]
