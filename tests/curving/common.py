"""Shared set-ups of the curving tests: a conical wheel on a round rail head (no flange, constant
contact angle) and the shipped metro problem."""
from __future__ import annotations

import dataclasses

import numpy as np

from geometry.contact_point import TrackRail
from geometry.profiles import build_profile


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
    from pipeline.curve.curving import build_problem

    c, v, veh, trk, prof, law, names = build_problem("r150")
    if radius is not None:
        trk = dataclasses.replace(trk, radius=radius)
    return dataclasses.replace(veh, **vehicle), trk, prof, law
