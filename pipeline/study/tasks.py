"""Typed task records: what a study kind hands to a worker for one case (picklable, frozen).

Every field comes from the validated study file (its defaults are the schema's,
pipeline/study/schemas.py) or from the case's context; nothing here has a default of its own
that repeats the schema.  The worker (pipeline/study/worker.py) reads these fields by name.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Mapping


@dataclass(frozen=True)
class Simulation:
    """How a case simulates (the study file's ``[simulation]`` table; SPEC 6, 7): at most
    ``duration`` s of rolling, stopping early at a limit cycle or after decay when
    ``early_stop`` (rule window ``window`` s), measures over the final ``final`` s, squeal
    (and sound power) for L_F2 >= ``level`` dB."""
    duration: float
    early_stop: bool
    final: float
    window: float
    level: float

    @classmethod
    def of(cls, table: Mapping) -> "Simulation":
        """From the validated ``[simulation]`` table."""
        return cls(duration=table["duration"], early_stop=table["early_stop"], final=table["final"],
                   window=table["window"], level=table["squeal_level"])

    def but(self, **changes) -> "Simulation":
        """A copy with some fields changed (e.g. the contact study's own duration)."""
        return replace(self, **changes)


@dataclass(frozen=True)
class MapTask:
    """Creepage/friction map: the full wheel model at (gamma_y, mu).  ``screened``: the
    stability screen's largest growth rate (1/s) when it ruled the case out (not simulated)."""
    gamma_y: float
    mu: float
    sim: Simulation
    screened: float | None


@dataclass(frozen=True)
class DampingTask:
    """Wheel modal damping study: the wheel of modes ``modes`` with the damping vector ``zeta``
    (all modes), one run of the procedure's ``step`` (``model`` 'full' or 'single'); ``mode`` the
    squealing mode (-1: none) and ``zeta_mode`` its damping."""
    step: int
    model: str
    mode: int
    modes: tuple
    zeta: tuple
    zeta_mode: float
    mu: float
    gamma_y: float
    sim: Simulation


@dataclass(frozen=True)
class ModeTask:
    """Contact-model validation, dynamic part: one wheel mode kept (damping ``zeta``, all modes)
    with contact model ``model`` ('point' or 'kalker'), lateral impulse ``kick`` (N s)."""
    case: str
    model: str
    mode: int
    label: str
    f_mode: float
    zeta: tuple
    mu: float
    gamma_y: float
    kick: float
    sim: Simulation


@dataclass(frozen=True)
class CreepageTask:
    """Contact-model validation, stand-alone part: rigid, fixed wheel and rail, creepage
    gamma_y(t) = gamma_0 + amplitude sin(2 pi f t) for ``duration`` s; F2 over the last
    ``periods`` periods."""
    case: str
    model: str
    f: float
    mu: float
    gamma_0: float
    amplitude: float
    periods: int
    duration: float
