"""Results a validation writer and the test asserting its limits both need, computed once per code and inputs:
``cached(name, compute, functions, inputs)`` returns ``compute()`` (JSON-able: numbers, strings, lists, dicts),
kept in build/validation/<name>.json under a key of the code the ``functions`` ("module:function") reach
(``pipeline.store.code_hash.code_key``) and the ``inputs`` files (size and time: a rebuilt artifact is a new
input); run again when the key changes.  One computation at a time per name (a lock file)."""
from __future__ import annotations

import fcntl
import json
from pathlib import Path

import numpy as np

from pipeline.store import paths
from pipeline.store.atomic import save_text
from pipeline.store.code_hash import code_key


def plain(x):
    """``x`` with numpy arrays and scalars turned into JSON's lists and numbers (keys into strings)."""
    if isinstance(x, dict):
        return {str(k): plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [plain(v) for v in x]
    if isinstance(x, np.ndarray):
        return plain(x.tolist())
    if isinstance(x, np.generic):
        return x.item()
    return x


def cached(name: str, compute, functions: tuple[str, ...], inputs=()):
    files = sorted(Path(f) for f in inputs)
    key = {"code": code_key(*functions),
           "inputs": {str(f): [f.stat().st_size, f.stat().st_mtime_ns] for f in files}}
    path = paths.build() / "validation" / f"{name}.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if path.exists():
            d = json.loads(path.read_text())
            if d.get("key") == key:
                return d["value"]
        value = plain(compute())
        save_text(json.dumps({"key": key, "value": value}), path)
        return value
