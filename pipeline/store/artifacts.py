"""Atomic, provenance-stamped artifacts (``.npz``, ``.json``, ``.csv``).

Every expensive intermediate result of the pipeline (meshes, modal bases,
eigenvalue sweeps, ...) is written through this module, which guarantees:

* **Atomicity** -- a file at the target path is always complete
  (``pipeline.store.atomic.atomic_write``).
* **Provenance** -- ``.npz`` and ``.json`` artifacts carry a record of what
  produced them (``pipeline.store.provenance``): artifact kind, the resolved
  configuration and its hash, time, git revision and library versions.
* **Checked loading** -- :func:`load_npz` / :func:`load_json` refuse files
  that are missing, truncated, of the wrong kind or built from a different
  configuration (stale), with a message that names the file and says what
  to do, instead of a raw ``zipfile``/``KeyError`` traceback.
"""

from __future__ import annotations

import csv
import json
import os
import zipfile
from pathlib import Path
from typing import Any, Iterable, Mapping, Sequence

import numpy as np

from pipeline.store.atomic import atomic_write
from pipeline.config.loader import config_hash
from pipeline.store.provenance import provenance

__all__ = [
    "ArtifactError",
    "PROVENANCE_KEY",
    "atomic_write",
    "provenance",
    "save_npz",
    "load_npz",
    "save_json",
    "load_json",
    "save_sidecar",
    "save_csv",
]

#: Name of the provenance entry inside ``.npz`` files and ``.json`` envelopes.
PROVENANCE_KEY = "__provenance__"


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
    """Atomically write ``arrays`` to an ``.npz`` (uncompressed, as ``np.savez``) with provenance.

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
        # Stored, not deflated: the arrays are floating-point numbers, which
        # deflate shrinks by ~12 % (rail.npz: 66 -> 58 MB) for ~2 s of CPU.
        with zipfile.ZipFile(tmp, mode="w", compression=zipfile.ZIP_STORED) as archive:
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
            path, "has no provenance record (not written by pipeline.store.artifacts.save_npz)"
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


def save_sidecar(path: str | os.PathLike, kind: str, config: Mapping, fields: Mapping[str, Any]) -> dict:
    """Atomically write a sidecar JSON for readers outside the pipeline (a WAV's calibration, as the
    docs/reference.md documents it): ``fields`` at the top level beside ``__provenance__`` (no ``payload`` level).
    Strict JSON, as :func:`save_json`; returns the provenance."""
    if PROVENANCE_KEY in fields:
        raise ValueError(f"a sidecar field may not be named {PROVENANCE_KEY!r}")
    prov = provenance(kind, config)
    text = json.dumps({PROVENANCE_KEY: prov, **fields}, indent=2, allow_nan=False, ensure_ascii=False)
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
            path, "has no provenance record (not written by pipeline.store.artifacts.save_json)"
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
