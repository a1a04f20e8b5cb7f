"""Provenance of an artifact: what produced it (kind, resolved configuration
and its hash, time, git revision, library versions).  The heavy libraries whose
versions are recorded (dolfinx, PETSc, SLEPc, gmsh, numba, scipy) are imported
lazily, once per installation (:func:`library_versions`, cached on disk)."""
from __future__ import annotations

import copy
import functools
import importlib
import platform
import subprocess
from datetime import datetime, timezone
from pathlib import Path
from typing import Mapping
import sys
import json

import numpy as np

from pipeline.config.loader import config_hash
from pipeline.store import paths
from pipeline.store.atomic import save_text

#: Root of the git work tree whose revision is recorded (this repository).
_REPO_ROOT = Path(__file__).resolve().parents[2]

NOT_INSTALLED = "not installed"


def _git(*args: str) -> str:
    """Run a read-only git command in the repository; raise on any failure."""
    result = subprocess.run(
        # --no-optional-locks: `git status` must not write the index, so we
        # never interfere with a concurrent git operation of the user.
        ["git", "--no-optional-locks", "-C", str(_REPO_ROOT), *args],
        capture_output=True,
        text=True,
        timeout=10,
        check=True,
        stdin=subprocess.DEVNULL,
    )
    return result.stdout.strip()


def git_revision() -> str:
    """``git rev-parse HEAD`` of the repository, ``+ "-dirty"`` if modified.

    "Dirty" means tracked files are modified or untracked, non-ignored files
    exist (new source files matter for reproducibility; ignored build
    outputs do not).  Returns ``"unknown"`` if git is unavailable or this is
    not a git checkout -- this function never raises.
    """
    try:
        revision = _git("rev-parse", "HEAD")
    except (OSError, subprocess.SubprocessError, ValueError):
        return "unknown"
    if not revision:
        return "unknown"
    try:
        if _git("status", "--porcelain"):
            revision += "-dirty"
    except (OSError, subprocess.SubprocessError, ValueError):
        revision += "-dirty?"  # revision known, cleanliness could not be checked
    return revision


def _module_version(module_name: str, attribute: str = "__version__") -> str:
    """Version of an importable module, or ``'not installed'``."""
    try:
        module = importlib.import_module(module_name)
    except ImportError:
        return NOT_INSTALLED
    except Exception as exc:  # noqa: BLE001 - e.g. a broken MPI/PETSc install
        return f"import failed ({type(exc).__name__}: {exc})"
    return str(getattr(module, attribute, "unknown"))


def _petsc_like_version(module_name: str) -> str:
    """Version of PETSc/SLEPc via ``<module>.Sys.getVersion()`` (a tuple)."""
    try:
        module = importlib.import_module(module_name)
        version = module.Sys.getVersion()
    except ImportError:
        return NOT_INSTALLED
    except Exception as exc:  # noqa: BLE001
        return f"import failed ({type(exc).__name__}: {exc})"
    if isinstance(version, tuple):
        return ".".join(str(part) for part in version)
    return str(version)


def _import_versions() -> dict[str, str]:
    """The versions, read from the imported modules."""
    return {
        "numpy": np.__version__,
        "dolfinx": _module_version("dolfinx"),
        "petsc4py": _module_version("petsc4py"),
        "PETSc": _petsc_like_version("petsc4py.PETSc"),
        "slepc4py": _module_version("slepc4py"),
        "SLEPc": _petsc_like_version("slepc4py.SLEPc"),
        "gmsh": _module_version("gmsh"),
        "numba": _module_version("numba"),
        "scipy": _module_version("scipy"),
    }


_DISTRIBUTIONS = ("numpy", "fenics-dolfinx", "petsc4py", "slepc4py", "numba", "scipy")


def _installation_key() -> str:
    """What the versions depend on, read without importing the libraries: the interpreter, the
    installed distributions' versions and the locations and times of the modules (a changed
    installation changes the key)."""
    import importlib.metadata  # local: the module binds importlib otherwise
    import importlib.util  # local: the module binds importlib otherwise

    parts = [sys.executable, sys.version]
    for dist in _DISTRIBUTIONS:
        try:
            parts.append(f"{dist}={importlib.metadata.version(dist)}")
        except importlib.metadata.PackageNotFoundError:
            parts.append(f"{dist}=-")
    for name in ("numpy", "dolfinx", "petsc4py", "slepc4py", "gmsh", "numba", "scipy"):
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            spec = None
        origin = getattr(spec, "origin", None)
        try:
            parts.append(f"{name}:{origin}:{Path(origin).stat().st_mtime_ns}" if origin else f"{name}:-")
        except OSError:
            parts.append(f"{name}:{origin}:?")
    return config_hash({"installation": parts})


@functools.lru_cache(maxsize=None)
def library_versions() -> dict[str, str]:
    """Versions of the numerical stack, cached per process and on disk: importing dolfinx, PETSc
    and SLEPc only to read their versions costs a second or two per stage, so the versions are
    read once per installation (``_installation_key``) and kept in
    ``$SQUEAL_BUILD_DIR/.library_versions.json``; without a usable cache they are imported."""
    cache = paths.build() / ".library_versions.json"
    key = _installation_key()
    try:
        stored = json.loads(cache.read_text())
        if stored.get("key") == key and isinstance(stored.get("versions"), dict):
            return dict(stored["versions"])
    except (OSError, ValueError):
        pass
    versions = _import_versions()
    try:
        cache.parent.mkdir(parents=True, exist_ok=True)
        save_text(json.dumps({"key": key, "versions": versions}), cache)
    except OSError:
        pass
    return versions


def provenance(kind: str, config: Mapping) -> dict:
    """The provenance record stored with an artifact.

    Keys: ``kind``, ``config`` (the resolved configuration), ``config_hash``
    (:func:`pipeline.config.loader.config_hash`), ``created_utc`` (ISO 8601),
    ``git_revision`` (see :func:`git_revision`), ``python`` and ``versions``
    (numpy, dolfinx, petsc4py, PETSc, slepc4py, SLEPc, gmsh, numba, scipy;
    ``'not installed'`` for missing ones).
    """
    if not isinstance(kind, str) or not kind:
        raise ValueError(f"artifact kind must be a non-empty string; got {kind!r}")
    return {
        "kind": kind,
        # A copy: later changes to the caller's dict must not alter the record.
        "config": copy.deepcopy(config),
        "config_hash": config_hash(config),
        "created_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "git_revision": git_revision(),
        "python": platform.python_version(),
        "versions": dict(library_versions()),
    }
