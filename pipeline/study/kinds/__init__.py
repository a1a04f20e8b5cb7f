"""The study kinds: one module per kind, named as the kind a study file gives (``kind = "<module>"``).

Each module defines ``SCHEMA`` (its study file's keys, built from pipeline/study/schemas.py's shared parts) and
``run(spec, src, out, *, quick, client, progress)``; it may define ``check(spec) -> str`` (what ``make check
STUDY=`` adds to the file's validation, e.g. a line study's CSV of curves).  Adding a kind is adding a module
here: the kinds are found, not listed (pipeline/store/deps.py follows every module of this package).
"""
from __future__ import annotations

import importlib
import tomllib
from types import ModuleType

from pipeline.config.loader import ConfigError, load
from pipeline.store import paths
from pipeline.study.schemas import COMMON, KINDS as NAMES

DISCOVERS_SUBMODULES = True      # read by pipeline/store/deps.py: importing this package reaches every kind


def kind_module(name: str) -> ModuleType:
    """The module of the study kind ``name`` (one of ``NAMES``)."""
    return importlib.import_module(f"{__name__}.{name}")


def load_study(name: str) -> tuple[dict, str]:
    """The validated study definition (its kind's ``SCHEMA``) and its path."""
    path = paths.study_file(name)
    if not path.exists():
        raise ConfigError(str(path), detail=f"no such study; available: {paths.available(paths.studies())}")
    try:
        kind = tomllib.loads(path.read_text()).get("kind")
    except (tomllib.TOMLDecodeError, UnicodeDecodeError):
        kind = None
    if kind not in NAMES:
        load(path, COMMON)                           # the syntax error, or the key and the kinds, named
    spec = load(path, kind_module(kind).SCHEMA)
    if spec["name"] != path.stem:                   # as a vehicle (curve_inputs.vehicle_of): named by its file
        raise ConfigError(str(path), [("name", spec["name"], f"the file's name {path.stem!r} (a study is named by "
                                       "its file, its results land in build/studies/<name>/: rename one to match "
                                       "the other)")])
    for case in spec.get("cases", []):              # a line study names curves instead (kinds/line.py)
        if not paths.case_file(case).exists():
            raise ConfigError(str(path), [("cases", case, f"a case in {paths.cases()}: "
                                                          f"{paths.available(paths.cases())}")])
    return spec, str(path)
