"""Atomic, provenance-stamped artifacts (``.npz``, ``.json``, ``.csv``).

Every expensive intermediate result of the pipeline (meshes, modal bases,
eigenvalue sweeps, ...) is written through this module, which guarantees:

* **Atomicity** -- a file at the target path is always complete.  Data is
  written to a temporary file in the same directory, flushed to disk and
  then ``os.replace``-d onto the target.  A crash, Ctrl-C or ``kill -9``
  in the middle of a write leaves the previous target (or none) in place,
  never a truncated one.  (A killed process can leave its hidden temporary
  file ``.<name>.tmp-<pid>-<random><suffix>`` behind; it is harmless and
  can be deleted.)
* **Provenance** -- ``.npz`` and ``.json`` artifacts carry a record of what
  produced them: artifact kind, the resolved configuration and its hash,
  time, git revision and library versions.
* **Checked loading** -- :func:`load_npz` / :func:`load_json` refuse files
  that are missing, truncated, of the wrong kind or built from a different
  configuration (stale), with a message that names the file and says what
  to do, instead of a raw ``zipfile``/``KeyError`` traceback.

Only the standard library and numpy are imported at module import time;
the heavy libraries whose versions are recorded (dolfinx, PETSc, SLEPc,
gmsh, numba, scipy) are imported lazily, on the first call to
:func:`provenance`.
"""

from __future__ import annotations

import contextlib
import copy
import csv
import functools
import importlib
import json
import os
import platform
import secrets
import subprocess
import zipfile
from datetime import datetime, timezone
from pathlib import Path
from typing import Any, Iterable, Iterator, Mapping, Sequence

import numpy as np

from .config import config_hash

__all__ = [
    "ArtifactError",
    "PROVENANCE_KEY",
    "atomic_write",
    "provenance",
    "save_npz",
    "load_npz",
    "save_json",
    "load_json",
    "save_csv",
]

#: Name of the provenance entry inside ``.npz`` files and ``.json`` envelopes.
PROVENANCE_KEY = "__provenance__"

#: Root of the git work tree whose revision is recorded (this repository).
_REPO_ROOT = Path(__file__).resolve().parent.parent

NOT_INSTALLED = "not installed"


class ArtifactError(RuntimeError):
    """An artifact is missing, unreadable, of the wrong kind or stale.

    ``path`` is the offending file; ``problem`` the explanation.  The message
    is ``"<path>: <problem>"``.
    """

    def __init__(self, path: str | os.PathLike, problem: str) -> None:
        self.path = os.fspath(path)
        self.problem = problem
        super().__init__(f"{self.path}: {problem}")

    def __reduce__(self):
        # Keep the exception picklable (multiprocessing workers re-raise it).
        return (type(self), (self.path, self.problem))


# --------------------------------------------------------------------------
# Atomic writing
# --------------------------------------------------------------------------


def _fsync_path(path: Path) -> None:
    """Flush a file's data to stable storage."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _fsync_dir(directory: Path) -> None:
    """Persist a rename by fsyncing the directory (best effort; not on all OSes)."""
    try:
        fd = os.open(directory, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike) -> Iterator[Path]:
    """Context manager yielding a temporary path that replaces ``path`` on success.

    ::

        with atomic_write("build/modes/r920.msh") as tmp:
            gmsh.write(str(tmp))

    The temporary file ``.<name>.tmp-<pid>-<random><suffix>`` lives in the
    target's directory (so the final ``os.replace`` is an atomic rename on
    the same file system) and keeps the target's suffix, so libraries that
    choose the format from the extension (numpy ``.npz``, gmsh ``.msh``)
    behave as for the target.  It is created empty before the body runs;
    the body may overwrite or truncate it.

    On normal exit the file is fsync-ed and renamed onto ``path``.  If the
    body raises (anything, including ``KeyboardInterrupt``) the temporary
    file is deleted and the exception propagates; the target is untouched.
    Parent directories are created as needed.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    # O_EXCL guarantees that the name is ours; mode 0o666 lets the umask
    # decide the final permissions, as for a normally created file.
    while True:
        tmp = target.with_name(
            f".{target.name}.tmp-{os.getpid()}-{secrets.token_hex(4)}{target.suffix}"
        )
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:  # astronomically unlikely; just pick another name
            continue
        os.close(fd)
        break
    try:
        yield tmp
        if not tmp.exists():
            raise FileNotFoundError(
                f"atomic_write: temporary file {tmp} disappeared before it could "
                f"replace {target} (did the writer rename or delete it?)"
            )
        _fsync_path(tmp)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise
    _fsync_dir(target.parent)


# --------------------------------------------------------------------------
# Provenance
# --------------------------------------------------------------------------


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


@functools.lru_cache(maxsize=None)
def library_versions() -> dict[str, str]:
    """Versions of the numerical stack (imported lazily, cached per process)."""
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


def provenance(kind: str, config: Mapping) -> dict:
    """The provenance record stored with an artifact.

    Keys: ``kind``, ``config`` (the resolved configuration), ``config_hash``
    (:func:`pipeline.config.config_hash`), ``created_utc`` (ISO 8601),
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


def _flatten(cfg: Any, prefix: str = "") -> dict[str, Any]:
    """{'a': {'b': 1}} -> {'a.b': 1} (for reporting what changed)."""
    if isinstance(cfg, Mapping):
        out: dict[str, Any] = {}
        for key, value in cfg.items():
            out.update(_flatten(value, f"{prefix}{key}."))
        return out
    return {prefix[:-1]: cfg}


def _config_diff(old: Any, new: Mapping, limit: int = 5) -> str:
    """Human summary of differing keys, e.g. "tyre.radius: 0.46 -> 0.47"."""
    if not isinstance(old, Mapping):
        return ""
    a, b = _flatten(old), _flatten(new)

    def show(flat: dict, key: str) -> str:
        return repr(flat[key]) if key in flat else "(absent)"

    changes = [
        f"{key}: {show(a, key)} -> {show(b, key)}"
        for key in sorted(set(a) | set(b))
        if key not in a or key not in b or a[key] != b[key]
    ]
    if not changes:
        return ""
    more = f", ... ({len(changes) - limit} more)" if len(changes) > limit else ""
    return "; changed: " + ", ".join(changes[:limit]) + more


def _check_provenance(
    path: Path,
    prov: Any,
    kind: str,
    config: Mapping | None,
    make_target: str | None,
) -> dict:
    """Verify kind and (optionally) configuration of a loaded artifact."""
    rebuild = f"; rebuild it with `make {make_target}`" if make_target else "; rebuild it"
    if not isinstance(prov, dict) or "kind" not in prov or "config_hash" not in prov:
        raise ArtifactError(path, f"provenance record is malformed{rebuild}")
    if prov["kind"] != kind:
        raise ArtifactError(
            path, f"wrong artifact kind: expected {kind!r}, found {prov['kind']!r}"
        )
    if config is not None:
        expected = config_hash(config)
        if prov["config_hash"] != expected:
            raise ArtifactError(
                path,
                f"stale artifact: built from configuration {prov['config_hash']}, "
                f"but the current configuration is {expected}"
                f"{_config_diff(prov.get('config'), config)}{rebuild}",
            )
    return prov


def _require_file(path: Path, make_target: str | None) -> None:
    if not path.is_file():
        hint = f"; run `make {make_target}` to build it" if make_target else ""
        what = "is not a regular file" if path.exists() else "artifact not found"
        raise ArtifactError(path, f"{what}{hint}")


def _unreadable(path: Path, exc: BaseException, make_target: str | None) -> ArtifactError:
    hint = f"; delete it and run `make {make_target}`" if make_target else "; delete it and rebuild"
    return ArtifactError(
        path, f"artifact is unreadable or truncated ({type(exc).__name__}: {exc}){hint}"
    )


# --------------------------------------------------------------------------
# .npz
# --------------------------------------------------------------------------


def save_npz(path: str | os.PathLike, kind: str, config: Mapping, /, **arrays: Any) -> dict:
    """Atomically write ``arrays`` to a compressed ``.npz`` with provenance.

    The provenance record is stored as the entry ``__provenance__`` (a JSON
    string in a 0-d unicode array).  Object arrays are rejected
    (``ValueError``) because they would need pickle to load.  The first three
    parameters are positional-only, so arrays may be called ``path``,
    ``kind``, ``config`` or ``file``.  Returns the provenance record.
    """
    if PROVENANCE_KEY in arrays:
        raise ValueError(f"array name {PROVENANCE_KEY!r} is reserved")
    converted = {}
    for name, value in arrays.items():
        array = np.asarray(value)
        if array.dtype.hasobject:
            raise ValueError(
                f"array {name!r} has dtype object, which cannot be stored without pickle"
            )
        converted[name] = array
    prov = provenance(kind, config)
    # Serialise before touching the disk, so that a failure here leaves
    # nothing behind.
    converted[PROVENANCE_KEY] = np.array(json.dumps(prov, sort_keys=True, allow_nan=False))

    with atomic_write(path) as tmp:
        # Written with zipfile + np.lib.format directly (what np.savez does
        # internally) so array names cannot collide with savez's arguments.
        with zipfile.ZipFile(tmp, mode="w", compression=zipfile.ZIP_DEFLATED) as archive:
            for name, array in converted.items():
                with archive.open(name + ".npy", mode="w", force_zip64=True) as member:
                    np.lib.format.write_array(member, array, allow_pickle=False)
    return prov


def load_npz(
    path: str | os.PathLike,
    kind: str,
    config: Mapping | None = None,
    *,
    make_target: str | None = None,
) -> tuple[dict[str, np.ndarray], dict]:
    """Load an ``.npz`` written by :func:`save_npz`; return ``(arrays, provenance)``.

    Raises :class:`ArtifactError` if the file is missing, unreadable or
    truncated, has no provenance, holds a different ``kind``, or -- when
    ``config`` is given -- was built from a different configuration.
    ``make_target`` adds a "run `make <target>`" hint to the message.
    Pickled content is never loaded.
    """
    path = Path(path)
    _require_file(path, make_target)
    try:
        npz = np.load(path, allow_pickle=False)
        if not isinstance(npz, np.lib.npyio.NpzFile):
            raise ValueError("not an .npz archive (found a single .npy array)")
        with npz:
            # Read every member now: this decompresses and CRC-checks all
            # of them, so corruption is detected here and not later.
            arrays = {name: npz[name] for name in npz.files}
    except Exception as exc:  # noqa: BLE001 - zipfile, zlib, pickle refusal, OSError, ...
        raise _unreadable(path, exc, make_target) from exc

    if PROVENANCE_KEY not in arrays:
        raise ArtifactError(
            path, "has no provenance record (not written by pipeline.artifacts.save_npz)"
        )
    raw = arrays.pop(PROVENANCE_KEY)
    try:
        if raw.shape != () or raw.dtype.kind != "U":
            raise ValueError(f"expected a 0-d unicode array, got {raw.dtype} {raw.shape}")
        prov = json.loads(str(raw[()]))
    except ValueError as exc:
        raise ArtifactError(path, f"provenance record is corrupt ({exc})") from exc
    return arrays, _check_provenance(path, prov, kind, config, make_target)


# --------------------------------------------------------------------------
# .json
# --------------------------------------------------------------------------


def save_json(path: str | os.PathLike, kind: str, config: Mapping, payload: Any) -> dict:
    """Atomically write ``payload`` as JSON with provenance; return the provenance.

    The file is ``{"__provenance__": {...}, "payload": payload}``.  Strict
    JSON is written: NaN/inf raise ``ValueError`` (use ``None``).
    """
    prov = provenance(kind, config)
    text = json.dumps(
        {PROVENANCE_KEY: prov, "payload": payload}, indent=2, allow_nan=False, ensure_ascii=False
    )
    with atomic_write(path) as tmp:
        tmp.write_text(text + "\n", encoding="utf-8")
    return prov


def load_json(
    path: str | os.PathLike,
    kind: str,
    config: Mapping | None = None,
    *,
    make_target: str | None = None,
) -> tuple[Any, dict]:
    """Load a file written by :func:`save_json`; return ``(payload, provenance)``.

    Same checks and :class:`ArtifactError` messages as :func:`load_npz`.
    """
    path = Path(path)
    _require_file(path, make_target)
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:  # JSONDecodeError/UnicodeDecodeError are ValueErrors
        raise _unreadable(path, exc, make_target) from exc
    if not isinstance(document, dict) or PROVENANCE_KEY not in document or "payload" not in document:
        raise ArtifactError(
            path, "has no provenance record (not written by pipeline.artifacts.save_json)"
        )
    prov = _check_provenance(path, document[PROVENANCE_KEY], kind, config, make_target)
    return document["payload"], prov


# --------------------------------------------------------------------------
# .csv
# --------------------------------------------------------------------------


def save_csv(path: str | os.PathLike, header: Sequence[str], rows: Iterable[Sequence[Any]]) -> Path:
    """Atomically write a plain CSV file (no provenance) and return its path.

    ``rows`` may be any iterable (e.g. a generator); every row must have as
    many fields as ``header``, otherwise ``ValueError`` is raised and nothing
    is written.  Floats are written with ``repr`` precision (round-trip).
    """
    header = list(header)
    target = Path(path)
    with atomic_write(target) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            writer = csv.writer(fh)
            writer.writerow(header)
            for line_no, row in enumerate(rows, start=2):
                row = list(row)
                if len(row) != len(header):
                    raise ValueError(
                        f"{target}: row {line_no - 1} (CSV line {line_no}) has {len(row)} "
                        f"fields, header has {len(header)}"
                    )
                writer.writerow(row)
    return target
