"""Closed-form references for steady curving (independent of solvers/curving).

Linear steady curving of a two-axle bogie (Boocock, "Steady-state motion of railway vehicles
on curved track", J. Mech. Eng. Sci. 11 (1969) 556-566; Wickens, *Fundamentals of Rail
Vehicle Dynamics*, 2003, the steady curving of the bogie with shear and bending stiffness).  Assumptions of
the theory: linear creep (F_x = f11 * creepage, F_y = f22 * creepage, no spin), conical
wheels of conicity lam (no gravitational stiffness), equal wheel loads, no cant deficiency
and no secondary yaw restraint.  Wheelsets at x = +a (leading) and -a on a rigid frame with,
per wheelset, lateral stiffness k_y (two boxes: 2 k_y,box) and yaw stiffness k_psi
(2 k_x,box b^2).  The six equilibrium equations (per wheelset: lateral 2 f22 psi_i = k_y d_i
with d_i the lateral spring deflection y_i - y_b - x_i psi_b - x_i^2 / (2R); yaw
2 f11 l0 (l0 / R - lam y_i / r0) = k_psi (psi_i - psi_b - x_i / R); frame lateral and yaw)
give, by the symmetry psi_2 = -psi_1 and psi_b = 2 a f22 psi_1 / k_psi, the closed form

    psi_1 = (a / R) / [1 + 4 f11 f22 l0 lam / (r0 k_psi) * (a^2 / k_psi + 1 / k_y)]
    y_1   = r0 l0 / (lam R) + r0 a f22 psi_1 / (lam f11 l0) + 2 f22 psi_1 (a^2 / k_psi + 1 / k_y)

(the derivation is written out in docs/validation/90_curving.md).  For a rigid bogie
(k -> inf) psi_1 -> a / R and y_1 -> the pure-rolling shift plus the steering term; for a
soft one psi_1 -> 0 (radial).
"""
from __future__ import annotations


def linear_bogie(a, R, r0, l0, lam, f11, f22, k_psi, k_y):
    """(psi_1, y_1, psi_b, y_2) of the leading wheelset (rad, m), the frame yaw and the trailing
    wheelset's shift, from the closed form above."""
    comp = a * a / k_psi + 1.0 / k_y
    psi1 = (a / R) / (1.0 + 4.0 * f11 * f22 * l0 * lam / (r0 * k_psi) * comp)
    y1 = r0 * l0 / (lam * R) + r0 * a * f22 * psi1 / (lam * f11 * l0) + 2.0 * f22 * psi1 * comp
    psi_b = 2.0 * a * f22 * psi1 / k_psi
    y2 = y1 - 4.0 * f22 * psi1 * comp
    return psi1, y1, psi_b, y2


def pure_rolling_shift(r0, l0, lam, R):
    """The free wheelset's pure-rolling shift y = r0 l0 / (lam R) (m)."""
    return r0 * l0 / (lam * R)
