"""Set-ups of the curving checks (tests/curving/, the curving writer): a conical wheel on a round rail head
(no flange, constant contact angle), the shipped metro problem, the equivalent conicity from the rigid
contact search (not from the solver), and the linear bogie beside its closed form."""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from geometry.contact_point import TrackRail, rigid_contact
from geometry.profiles import build_profile
from solvers.curving import CreepLaw, Profiles, Track, Vehicle, flange_edge, solve

from pipeline.validation.references.curving import linear_bogie
from pipeline.curve.curving import build_problem

RESIDUAL = 1e-8   # "Done when" (4): force and moment residuals / wheel load


def independent_conicity(prof, c, r0, l_w, y):
    """(lam, l0) of the profile pair at wheelset shift y from the project's rigid contact search
    (geometry.contact_point), not from the solver: lam = (r_o - r_i) / (2 y)."""
    o = rigid_contact(prof.wheel, prof.rail, c + y)
    i = rigid_contact(prof.wheel, prof.rail, c - y)
    return (o.z_wheel - i.z_wheel) / (2 * y), l_w + 0.5 * (o.y_wheel + i.y_wheel)


def cone_pair(lam: float = 0.005, crown: float = 0.3):
    """A flangeless cone of slope lam (z_W = -lam y^W) on a circular head of radius ``crown``:
    the contact angle is atan(lam) at every shift and the rail point does not move."""
    y = np.linspace(-0.06, 0.06, 241)
    wheel = build_profile(y, -lam * y, "wheel", "cone", "test: cone")
    yr = np.linspace(-0.03, 0.03, 121)
    rail = build_profile(yr, np.sqrt(crown ** 2 - yr ** 2) - crown, "rail", "round", "test: round head")
    return wheel, TrackRail(rail, 0.0)


def metro(radius=None, **vehicle):
    """(Vehicle, Track, Profiles, CreepLaw) of the shipped r150 curve, the radius and vehicle
    fields replaced as given."""
    c, v, veh, trk, prof, law, names = build_problem("r150")
    if radius is not None:
        trk = dataclasses.replace(trk, radius=radius)
    return dataclasses.replace(veh, **vehicle), trk, prof, law


def linear_case(kx, ky, radius):
    """(solution, closed form (psi_1, y_1, psi_b, y_2)) of a bogie with elastic primary yaw on conical wheels
    (balanced cant, linear creep): the set-up of ``references.curving.linear_bogie``."""
    lam, r0, a, f11, f22 = 0.005, 0.45, 1.25, 8e6, 7e6
    wheel, rail_t = cone_pair(lam)
    prof = Profiles(wheel, rail_t, flange_edge(wheel))
    veh = Vehicle(semi_wheelbase=a, bogie_spacing=10.0, wheel_load=10e3, wheelset_mass=1200.0, kx=kx, ky=ky,
                  box_half_spacing=1.0, secondary_yaw=0.0, cg_height=1.2, r0=r0, rolling_circle=0.75)
    V = 3.0  # with the balanced cant: no cant deficiency, as the theory assumes
    trk = Track(radius=radius, cant=1.5 * math.sin(math.atan(V * V / (9.81 * radius))), speed=V, rail_centre=0.75,
                c=0.0)
    assert abs(trk.unbalanced()[0]) < 1e-12
    law = CreepLaw(kind="linear", f11=f11, f22=f22)
    sol = solve(prof, veh, trk, law)
    p = rigid_contact(wheel, rail_t, 0.0)
    r_c, l0 = r0 + p.z_wheel, 0.75 + p.y_track
    ref = linear_bogie(a, radius, r_c, l0, lam, f11, f22, 2 * kx * 1.0 ** 2, 2 * ky)
    return sol, ref
