"""A study file (``pipeline/studies/<name>.toml``) read and validated, and the map's grid it defines."""
from __future__ import annotations

import tomllib

import numpy as np

from solvers.study import grid

from pipeline.config.loader import ConfigError, load
from pipeline.store import paths
from pipeline.study.schemas import COMMON, KINDS, SCHEMAS


def load_study(name: str) -> tuple[dict, str]:
    """The validated study definition and its path."""
    path = paths.study_file(name)
    if not path.exists():
        raise ConfigError(str(path), detail=f"no such study; available: {paths.available(paths.studies())}")
    try:
        kind = tomllib.loads(path.read_text()).get("kind")
    except (tomllib.TOMLDecodeError, UnicodeDecodeError):
        kind = None                                  # load() reports the syntax error
    schema = SCHEMAS.get(kind, COMMON) if isinstance(kind, str) else COMMON
    spec = load(path, schema)                        # an unknown kind fails here, naming the key
    if spec["kind"] not in KINDS:                    # pragma: no cover - the schema's choices catch it
        raise ConfigError(str(path), [("kind", spec["kind"], f"one of {list(KINDS)}")])
    for case in spec.get("cases", []):              # a line study names curves instead (pipeline/study/line.py)
        if not paths.case_file(case).exists():
            raise ConfigError(str(path), [("cases", case, f"a case in {paths.cases()}: "
                                                          f"{paths.available(paths.cases())}")])
    return spec, str(path)


def grid_of(spec: dict, quick: bool) -> tuple[np.ndarray, np.ndarray]:
    g = spec["grid"]
    step = spec["quick"] if quick else g
    return (grid(g["gamma_y_first"], g["gamma_y_last"], step["gamma_y_step"]),
            grid(g["mu_first"], g["mu_last"], step["mu_step"]))
