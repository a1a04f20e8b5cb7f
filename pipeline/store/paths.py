"""Where inputs live and where artifacts land (one folder per input name).

The folders are overridable through the environment (tests and users build
elsewhere without touching the tree): ``SQUEAL_BUILD_DIR``, ``SQUEAL_WHEEL_DIR``,
``SQUEAL_CASE_DIR``, ``SQUEAL_RAIL_DIR``, ``SQUEAL_STUDY_DIR``.  They are read
when a function is called, not when this module is imported, so a change of
the environment (a test's monkeypatch, a worker's) takes effect.
"""
from __future__ import annotations

import os
from pathlib import Path

#: The repository (code and input files); fixed by where this file is.
ROOT = Path(__file__).resolve().parents[2]


def _folder(variable: str, default: Path) -> Path:
    return Path(os.environ.get(variable, default))


def build() -> Path:
    """The build folder (``SQUEAL_BUILD_DIR``, default ``<repo>/build``)."""
    return _folder("SQUEAL_BUILD_DIR", ROOT / "build")


def wheels() -> Path:
    """Wheel files ``<name>.toml`` (``SQUEAL_WHEEL_DIR``, default geometry/wheels)."""
    return _folder("SQUEAL_WHEEL_DIR", ROOT / "geometry" / "wheels")


def cases() -> Path:
    """Case files (``SQUEAL_CASE_DIR``, default pipeline/cases)."""
    return _folder("SQUEAL_CASE_DIR", ROOT / "pipeline" / "cases")


def rails() -> Path:
    """Rail files (``SQUEAL_RAIL_DIR``, default geometry/rails)."""
    return _folder("SQUEAL_RAIL_DIR", ROOT / "geometry" / "rails")


def studies() -> Path:
    """Study files (``SQUEAL_STUDY_DIR``, default pipeline/studies)."""
    return _folder("SQUEAL_STUDY_DIR", ROOT / "pipeline" / "studies")


def rail_file(name: str) -> Path:
    return rails() / f"{name}.toml"


def rail_dir(name: str) -> Path:
    """build/rails/<name>/: section.msh, rail.npz, receptance.png, dispersion.png."""
    return build() / "rails" / name


def curve_wheel(name: str) -> tuple[str, str] | None:
    """(curve, wheel) of a curve wheel's case name ``<curve>/<wheel>`` (e.g. ``r150/a1i``), None for
    an ordinary case name; a name with more than one ``/`` or an empty part is neither (ValueError)."""
    if "/" not in name:
        return None
    parts = name.split("/")
    if len(parts) != 2 or not all(parts) or any(p in (".", "..") for p in parts):
        raise ValueError(f"case name {name!r}: a curve wheel is named <curve>/<wheel> (e.g. r150/a1i)")
    return parts[0], parts[1]


def curve_dir(curve: str) -> Path:
    """build/curves/<curve>/: the curve stage's outputs (its wheels' case files in cases/)."""
    return build() / "curves" / curve


def case_dir(name: str) -> Path:
    """build/cases/<name>/: contact.npz, contact_rf.png (and later stages); a curve wheel
    ``<curve>/<wheel>`` has build/cases/<curve>/<wheel>/."""
    cw = curve_wheel(name)
    return build() / "cases" / (name if cw is None else Path(*cw))


def case_file(name: str) -> Path:
    """pipeline/cases/<name>.toml, or for a curve wheel ``<curve>/<wheel>`` the file the curve
    stage writes, build/curves/<curve>/cases/<wheel>.toml."""
    cw = curve_wheel(name)
    if cw is not None:
        return curve_dir(cw[0]) / "cases" / f"{cw[1]}.toml"
    return cases() / f"{name}.toml"


def missing_case(name: str) -> str | None:
    """Why the case ``name`` cannot be read (one line, naming what to do; the caller names the
    file ``case_file(name)``), None when its file exists.  A malformed name is a ValueError."""
    path = case_file(name)
    if path.exists():
        return None
    cw = curve_wheel(name)
    if cw is not None:
        return f"no case file for the curve wheel {name}: run make curve CURVE={cw[0]} first"
    return f"no such case; available: {available(cases())}"


def wheel_file(name: str) -> Path:
    return wheels() / f"{name}.toml"


def wheel_dir(name: str) -> Path:
    """build/wheels/<name>/: section.msh, modes.npz, modes.csv, shapes/."""
    return build() / "wheels" / name


def study_file(name: str) -> Path:
    return studies() / f"{name}.toml"


def available(folder: Path) -> list[str]:
    return sorted(p.stem for p in folder.glob("*.toml"))


def shown(path) -> str:
    """A path as reports print it: relative to the repository when inside it
    (``pipeline/cases/default.toml``), else its file name -- never an absolute
    path of the machine that ran."""
    p = Path(path)
    try:
        return p.resolve().relative_to(ROOT).as_posix()
    except ValueError:
        return p.name
