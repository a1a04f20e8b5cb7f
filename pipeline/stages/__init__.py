"""The one table of the pipeline's stages: the command line (``pipeline/__main__.py``) and Make's
source dependencies (``pipeline/store/deps.py``) both read it.

Standard library only: ``pipeline/store/deps.py`` imports it under /usr/bin/python3 before the venv
exists.  A stage's entry is ``pipeline.<module>.<function>(<input name>)``; ``takes`` is the input
it is run on (``wheel``, ``rail``, ``case``, ``study``, ``curve``, or None); ``numba`` marks the stages that run
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
                  "stages.wheel", "run_mesh", "wheel"),
    "modes": Stage("wheel modes per Fourier harmonic (dolfinx + SLEPc), classified -> modes.npz, modes.csv",
                   "stages.wheel", "run_modes", "wheel"),
    "shapes": Stage("offscreen 3D renders of every wheel mode and a gallery -> shapes/*.png",
                    "stages.wheel", "run_shapes", "wheel"),
    "rail": Stage("rail cross-section, waveguide FE, dispersion and receptances -> build/rails/<rail>/rail.npz",
                  "stages.rail", "run_rail", "rail"),
    "contact": Stage("contact of the case: gap, NORM table, compliance, friction curves -> "
                     "build/cases/<case>/contact.npz", "stages.contact", "run_contact", "case", numba=True),
    "greens": Stage("wheel Green's function (Kropp, modal filters) and moving rail Green's function -> greens.npz",
                    "stages.greens", "run_greens", "case", numba=True),
    "simulate": Stage("time-domain wheel/rail interaction of the case (numba) -> build/cases/<case>/simulate.npz",
                      "stages.simulate", "run_simulate", "case", numba=True),
    "radiate": Stage("sound power of the wheel under the simulated contact forces (Thompson-Jones) -> radiate.npz",
                     "stages.radiate", "run_radiate", "case"),
    "stability": Stage("frequency-domain stability screen of the case (linearised time loop) -> stability.npz, "
                       ".csv, .png", "stages.stability", "run_stability", "case", numba=True),
    "stability_map": Stage("the stability screen over a map study's grid (--study, --quick) -> "
                           "build/studies/<study>/stability.csv", "study.screen", "run_stability_map", "study",
                           numba=True, make=False),
    "listen": Stage("what a listener hears: sound pressure at a receiver, dB(A), 1/3 octaves, a calibrated WAV -> "
                    "listen.*", "stages.listen", "run_listen", "case", numba=True),
    "report": Stage("gather the case's results (wheel, rail, contact, Green's functions, interaction) -> "
                    "build/report/<case>/report.md", "stages.report", "run_report", "case"),
    "curve": Stage("the verdict of a curve (--curve): every wheel of the leading bogie screened, the unstable ones "
                   "simulated, radiated, heard; what would stop it -> build/curves/<curve>/verdict.csv, .md, bogie.png",
                   "curve.stage", "run_curve", "curve", numba=True),
    "check": Stage("everything a later stage would refuse, before any work (files, friction, profiles, contact point, "
                   "time step)", make=False),
    "study": Stage("a parameter study on Dask (SPEC 7): --study map|damping|contact -> build/studies/<study>/",
                   "study.stage", "run_study", "study", numba=True, make=False),
}
