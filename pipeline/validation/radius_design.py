"""Speed and cant of the radius studies, per vehicle (issue 32): the metro's and the freight wagon's design
rule is the radius study's (``pipeline.study.radius.design``: line speed 70 km/h or the speed at 1.0 m/s^2
in the track plane, cant for 2/3 of it); the tram's is a street track's, without cant:

    V = min(V_TRAM, sqrt(A_TRAM R)),  cant = 0

A_TRAM = 0.7 m/s^2 of uncompensated lateral acceleration (ASSUMED, a street tram's comfortable value; it
reproduces the shipped tram curves' assumed speeds, 15 km/h at 25 m and 30 km/h at 100 m:
(15/3.6)^2/25 = (30/3.6)^2/100 = 0.69 m/s^2), V_TRAM = 60 km/h (ASSUMED, an urban tram's line speed)."""
from __future__ import annotations

import math

from pipeline.config.curve_inputs import read_curve
from pipeline.study.radius import design

A_TRAM = 0.7             # m/s^2, uncompensated lateral acceleration of a street tram (ASSUMED)
V_TRAM = 60.0            # km/h, tram line speed (ASSUMED)
TRAMS = ("tram",)        # vehicle names designed as trams


def tram_design(radius: float) -> tuple[float, float]:
    """(speed km/h, cant m) of a tram in a street curve of radius ``radius`` m (module notes)."""
    return round(min(V_TRAM, 3.6 * math.sqrt(A_TRAM * radius)), 1), 0.0


def design_of(base: str, radius: float) -> tuple[float, float]:
    """(speed km/h, cant m) for the vehicle of the base curve ``base`` (a shipped curve's name)."""
    return tram_design(radius) if read_curve(base).vehicle.name in TRAMS else design(radius)
