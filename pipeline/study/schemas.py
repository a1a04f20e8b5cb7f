"""Schemas of the study definitions pipeline/studies/<name>.toml (validated by pipeline.config.loader;
an error names the file, the key, the value and what is allowed).  One schema per kind;
``kind`` picks it."""
from __future__ import annotations

from solvers.constants import F_MAX_HZ, SQUEAL_LEVEL_DB

from pipeline.config.loader import Field, ListOf

KINDS = ("map", "damping", "contact", "line")

COMMON = {
    "name": Field(str, doc="short name; outputs in build/studies/<name>/"),
    "kind": Field(str, choices=list(KINDS), doc="which study (SPEC 7)"),
    "description": Field(str, default=""),
    "cases": ListOf(Field(str), min_len=1, max_len=10,
                    doc="case files pipeline/cases/<case>.toml: one per contact position; the wheel, rail, speed, "
                        "time step and preload are the case's; keep the list on one line (the Makefile reads it)"),
}

SIMULATION = {
    "duration": Field(float, unit="s", min=0.01, max=8.0, default=8.0, doc="at most this much rolling (SPEC 6)"),
    "early_stop": Field(bool, default=True, doc="stop at a limit cycle or after decay (solvers.timeloop.interaction.StopRule)"),
    "final": Field(float, unit="s", min=0.01, max=2.0, default=0.5, doc="stretch the measures are taken over"),
    "window": Field(float, unit="s", min=0.01, max=2.0, default=0.25,
                    doc="window of the early-stop rule (solvers.timeloop.interaction.StopRule; 0.25 s as the simulate stage)"),
    "squeal_level": Field(float, unit="dB", min=-100.0, max=200.0, default=SQUEAL_LEVEL_DB,
                          doc="squeal when L_F2 >= this; sound power only then (SPEC 6)"),
    "screen_margin": Field(float, unit="1/s", min=0.0, max=1000.0, default=None,
                           doc="map: run the stability screen first and do not simulate the cases whose fastest "
                               "pole grows slower than -screen_margin (recorded as 'screened'); unset: simulate all"),
}

GAMMA = dict(kind=float, min=-0.2, max=0.2)
MU = dict(kind=float, min=0.05, max=1.0)
STEP = dict(kind=float, min=0.0, min_inclusive=False)

MAP = COMMON | {
    "grid": {
        "gamma_y_first": Field(**GAMMA, doc="first lateral creepage"),
        "gamma_y_last": Field(**GAMMA),
        "gamma_y_step": Field(**STEP, max=0.1),
        "mu_first": Field(**MU, doc="friction coefficients (any: their curves are built on each case's contact and cached by value)"),
        "mu_last": Field(**MU),
        "mu_step": Field(**STEP, max=1.0),
    },
    "quick": {
        "gamma_y_step": Field(**STEP, max=0.1, doc="coarser grid of --quick (same first values)"),
        "mu_step": Field(**STEP, max=1.0),
    },
    "simulation": SIMULATION,
}

OPERATING = {
    "mu": Field(float, min=0.05, max=1.0, default=None, doc="default: the case's"),
    "gamma_y": Field(float, min=-0.2, max=0.2, default=None, doc="default: the case's"),
}

DAMPING = COMMON | {
    "operating": OPERATING,
    "bisection": {
        "zeta_max": Field(float, min=1e-4, max=1.0, default=0.1,
                          doc="upper end of the bracket: a mode still squealing there ends the study"),
        "rel_tol": Field(float, min=1e-3, max=1.0, default=0.05,
                         doc="stop when zeta_hi / zeta_lo - 1 <= rel_tol (geometric bisection)"),
    },
    "procedure": {
        "max_steps": Field(int, min=1, max=30, default=8, doc="modes damped at most"),
        "mode_match": Field(float, min=0.001, max=0.5, default=0.05,
                            doc="the squeal frequency must be within this (relative) of the mode's"),
    },
    "simulation": SIMULATION,
}

CONTACT = COMMON | {
    "operating": OPERATING,
    "modes": {
        "classes": ListOf(Field(str, choices=["a", "r", "c"]), min_len=1, default=["a"],
                          doc="mode classes simulated one at a time"),
        "nodal_circles_max": Field(int, min=0, max=5, default=0),
        "f_min": Field(float, unit="Hz", min=0.0, max=20000.0, default=100.0),
        "f_max": Field(float, unit="Hz", min=0.0, max=20000.0, default=F_MAX_HZ),
        "zeta_kept": Field(float, min=0.0, max=1.0, default=1e-6, doc="damping of the mode kept (SPEC 7)"),
        "zeta_others": Field(float, min=0.0, max=10.0, default=1.0, doc="damping of the other flexible modes"),
        "kick": Field(float, unit="N s", min=0.0, max=100.0, default=0.01,
                      doc="lateral impulse at t = 0 (a larger one shortens the growth; the limit cycle does not depend on it)"),
    },
    "simulation": SIMULATION,
    "creepage": {
        "gamma_0": Field(float, min=-0.2, max=0.2, default=-0.003, doc="mean lateral creepage"),
        "amplitude": Field(float, min=0.0, max=0.2, default=0.001, doc="amplitude of the sinusoidal creepage"),
        "frequencies": ListOf(Field(float, unit="Hz", min=1.0, max=10000.0), min_len=1,
                              default=[100.0, 300.0, 1000.0, 3000.0]),
        "periods": Field(int, min=1, max=1000, default=3, doc="whole periods the response is measured over"),
        "settle": Field(float, unit="s", min=0.0, max=1.0, default=0.01,
                        doc="run-in before the measured periods (at least one period)"),
    },
    "quick": {
        "max_modes": Field(int, min=1, max=100, default=3, doc="--quick: the lowest modes only"),
        "duration": Field(float, unit="s", min=0.01, max=8.0, default=0.05),
        "frequencies": ListOf(Field(float, unit="Hz", min=1.0, max=10000.0), min_len=1, default=[1000.0]),
    },
}

LINE = {
    "name": COMMON["name"],
    "kind": COMMON["kind"],
    "description": COMMON["description"],
    "curves": Field(str, doc="the line's curves: a CSV file, its path relative to the study file's folder "
                             "(pipeline/studies/<curves>) or absolute (anywhere), one row per curve, vehicle and "
                             "friction condition, columns id, chainage_m, radius_m, cant_mm, length_m, speed_kmh, "
                             "vehicle (a vehicle file beside the CSV, else geometry/vehicles/), friction "
                             "(pipeline/study/line_input.py)"),
    "base_curve": Field(str, default="r150", doc="pipeline/curves/<base_curve>.toml, or a curve file's path (relative "
                                                 "to the study file's folder): the rail, gauge, gauge widening and "
                                                 "traction of every curve of the line"),
    "friction": {
        "dry_mu": Field(float, min=0.05, max=1.0, default=0.4,
                        doc="Coulomb coefficient of the CSV's friction condition 'dry'"),
        "wet_mu": Field(float, min=0.05, max=1.0, default=0.15,
                        doc="Coulomb coefficient of the CSV's friction condition 'wet'"),
    },
    "what_ifs": Field(bool, default=False, doc="the curve verdict's mitigation what-ifs for every squealing wheel "
                                               "(friction threshold, modal damping; slower)"),
    "wheel_figures": Field(bool, default=False, doc="the stages' figures and the pass-by of each squealing wheel "
                                                    "(contact_rf.png, greens.png, simulate.png, radiate.png, the "
                                                    "listen PNG, passby_*; its npz, CSV, exports and listen WAV are "
                                                    "written either way)"),
    "quick": {
        "rows": Field(int, min=1, max=100000, default=3, doc="--quick: the CSV's first rows only"),
    },
    "export": {
        "passages_day": Field(float, unit="1/h", min=0.0, max=1000.0, default=1.0,
                              doc="squealing passages per hour in the LW_RAILWAY export's day period (D)"),
        "passages_evening": Field(float, unit="1/h", min=0.0, max=1000.0, default=1.0, doc="evening period (E)"),
        "passages_night": Field(float, unit="1/h", min=0.0, max=1000.0, default=1.0, doc="night period (N)"),
    },
}

SCHEMAS = {"map": MAP, "damping": DAMPING, "contact": CONTACT, "line": LINE}
