"""Falling friction laws on a case's contact (the stability and falling-friction checks): Polach's law with
the registry's parameters, and the case's contact with the global curve of such a law (TANG with the local
law, ``solvers.contact.falling.tang_curve``), as the contact stage builds a law's curve."""
from __future__ import annotations


def falling_law(mu_s: float, mu_k: float, s_ref: float):
    """Polach's law mu(s) = mu_s ((1 - A) exp(-s / s_ref) + A), A = mu_k / mu_s (the registry's)."""
    from solvers.contact.friction_laws import get_friction_law  # lazy: brings in numba, rocket_fft, scipy

    return get_friction_law("polach", mu0=mu_s, A=mu_k / mu_s, B=1.0 / s_ref)


def falling_contact(cm, law_params, v: float, preload: float):
    """The case's contact with the global curve of a falling law (mu_s, mu_k, s_ref): TANG with the
    local law on the pressure at the static approach (``solvers.contact.falling.tang_curve``: the
    peer's rf_curve and the law's tail), as the contact stage builds a law's curve."""
    from solvers.contact.falling import tang_curve  # lazy: brings in numba, rocket_fft, scipy
    from solvers.contact.norm import NormTable, table_pressure  # lazy: brings in numba, scipy
    from solvers.timeloop.interaction import static_approach  # lazy: brings in numba, rocket_fft, scipy

    table = NormTable(cm.xi3_nodes, cm.F3_nodes, cm.q_nodes, cm.pressure_nodes, cm.pressure_nodes > 0)
    p3 = table_pressure(table, static_approach(cm, preload))
    s, m, d = tang_curve(p3, cm.dx, cm.dy, v, falling_law(*law_params), cm.E, cm.nu)
    return cm._replace(s_nodes=s, mu_nodes=m, slopes=d)
