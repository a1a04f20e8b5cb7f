"""Steady-state curving of a wheelset and of the leading bogie (issue 25): the quasi-static
equilibrium with the creep forces of the actual profiles, flange contact as a constraint.
Pure numerics (no pipeline import): ``pipeline.curve.curving`` loads the vehicle and curve files.

Modules: ``hertz`` (the contact ellipse), ``creep`` (Kalker's linear coefficients from TANG,
Shen-Hedrick-Elkins saturation), ``wheelrail`` (tread and flange contact points of one wheel),
``model`` (the equations), ``solve`` (the equilibrium and the flange's active set).
"""
from solvers.curving.creep import CreepLaw  # noqa: F401
from solvers.curving.model import Profiles, Track, Vehicle  # noqa: F401
from solvers.curving.solve import CurvingError, CurvingSolution, WheelsetState, solve  # noqa: F401
from solvers.curving.wheelrail import flange_edge, flange_shift  # noqa: F401
