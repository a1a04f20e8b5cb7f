"""The one table of the pipeline's stages: the command line (``pipeline/__main__.py``) and Make's
source dependencies (``pipeline/deps.py``) both read it.

Standard library only: ``pipeline/deps.py`` imports it under /usr/bin/python3 before the venv
exists.  A stage's entry is ``pipeline.<module>.<function>(<input name>)``; ``takes`` is the input
it is run on (``wheel``, ``rail``, ``case``, ``study``, or None); ``numba`` marks the stages that run
numba code (``pipeline/numba_setup.py``); ``make`` those whose artifacts Make tracks (deps.py
writes their ``DEPS_<stage>``).
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Stage:
    help: str
    module: str | None = None
    function: str | None = None
    takes: str | None = None
    numba: bool = False
    make: bool = True


STAGES: dict[str, Stage] = {
    "mesh": Stage("mesh the wheel cross-section (Gmsh) -> build/wheels/<wheel>/section.msh",
                  "wheel_stage", "run_mesh", "wheel"),
    "modes": Stage("wheel modes per Fourier harmonic (dolfinx + SLEPc), classified -> modes.npz, modes.csv",
                   "wheel_stage", "run_modes", "wheel"),
    "shapes": Stage("offscreen 3D renders of every wheel mode and a gallery -> shapes/*.png",
                    "wheel_stage", "run_shapes", "wheel"),
    "rail": Stage("rail cross-section, waveguide FE, dispersion and receptances -> build/rails/<rail>/rail.npz",
                  "rail_stage", "run_rail", "rail"),
    "contact": Stage("contact of the case: gap, NORM table, compliance, friction curves -> "
                     "build/cases/<case>/contact.npz", "contact_stage", "run_contact", "case", numba=True),
    "greens": Stage("wheel Green's function (Kropp, modal filters) and moving rail Green's function -> greens.npz",
                    "greens_stage", "run_greens", "case", numba=True),
    "simulate": Stage("time-domain wheel/rail interaction of the case (numba) -> build/cases/<case>/simulate.npz",
                      "simulate_stage", "run_simulate", "case", numba=True),
    "radiate": Stage("sound power of the wheel under the simulated contact forces (Thompson-Jones) -> radiate.npz",
                     "radiate_stage", "run_radiate", "case"),
    "stability": Stage("frequency-domain stability screen of the case (linearised time loop) -> stability.npz, "
                       ".csv, .png", "stability_stage", "run_stability", "case", numba=True),
    "stability_map": Stage("the stability screen over a map study's grid (--study, --quick) -> "
                           "build/studies/<study>/stability.csv", "study.screen", "run_stability_map", "study",
                           numba=True, make=False),
    "listen": Stage("what a listener hears: sound pressure at a receiver, dB(A), 1/3 octaves, a calibrated WAV -> "
                    "listen.*", "listen_stage", "run_listen", "case", numba=True),
    "report": Stage("gather the case's results (wheel, rail, contact, Green's functions, interaction) -> "
                    "build/report/<case>/report.md", "report", "run_report", "case"),
    "check": Stage("everything a later stage would refuse, before any work (files, friction, profiles, contact point, "
                   "time step)", make=False),
    "study": Stage("a parameter study on Dask (SPEC 7): --study map|damping|contact -> build/studies/<study>/",
                   "study.stage", "run_study", "study", numba=True, make=False),
}
