"""Where inputs live and where artifacts land (one folder per input name)."""
from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# overridable so tests (and users) can build elsewhere without touching the tree
BUILD = Path(os.environ.get("SQUEAL_BUILD_DIR", ROOT / "build"))
WHEELS = Path(os.environ.get("SQUEAL_WHEEL_DIR", ROOT / "geometry" / "wheels"))
CASES = Path(os.environ.get("SQUEAL_CASE_DIR", ROOT / "pipeline" / "cases"))
RAILS = Path(os.environ.get("SQUEAL_RAIL_DIR", ROOT / "geometry" / "rails"))


def rail_file(name: str) -> Path:
    return RAILS / f"{name}.toml"


def rail_dir(name: str) -> Path:
    """build/rails/<name>/: section.msh, rail.npz, receptance.png, dispersion.png."""
    return BUILD / "rails" / name


def case_dir(name: str) -> Path:
    """build/cases/<name>/: contact.npz, contact_rf.png (and later stages)."""
    return BUILD / "cases" / name


def case_file(name: str) -> Path:
    return CASES / f"{name}.toml"


def wheel_file(name: str) -> Path:
    return WHEELS / f"{name}.toml"


def wheel_dir(name: str) -> Path:
    """build/wheels/<name>/: section.msh, modes.npz, modes.csv, shapes/."""
    return BUILD / "wheels" / name


def available(folder: Path) -> list[str]:
    return sorted(p.stem for p in folder.glob("*.toml"))
