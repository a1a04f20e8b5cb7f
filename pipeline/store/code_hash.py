"""The hash of the code an artifact's numbers depend on: the ``code`` entry of a cache key.

``code_hash(patterns)`` hashes the files that the glob ``patterns`` (relative to the repository,
each expanded in sorted order; a pattern that matches nothing adds nothing) name, each as its
relative path followed by its bytes, so a changed file makes a new key and a stale cache is never
read.  ``ignore_docs=True`` hashes a Python file's syntax tree without its docstrings instead of
its bytes (``code_text``), so that editing documentation keeps the results (the study rows).
Computed once per process for the same files (path, size, modification time).
"""
from __future__ import annotations

import ast
import functools
import hashlib

from pipeline.store.paths import ROOT


def code_text(path) -> bytes:
    """The code of a Python file without its docstrings and comments (its AST dump); other files
    as they are."""
    if path.suffix != ".py":
        return path.read_bytes()
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            node.body = body[1:] or [ast.Pass()]
    return ast.dump(tree).encode()


def code_hash(patterns, *, ignore_docs: bool = False) -> str:
    """16 hex digits of the hash of the files ``patterns`` name (module notes)."""
    files = [p for pattern in patterns for p in sorted(ROOT.glob(pattern))]
    return _hash(tuple((p, p.stat().st_mtime_ns, p.stat().st_size) for p in files), ignore_docs)


@functools.lru_cache(maxsize=32)
def _hash(files: tuple, ignore_docs: bool) -> str:
    h = hashlib.sha256()
    for p, _, _ in files:
        h.update(p.relative_to(ROOT).as_posix().encode())
        h.update(code_text(p) if ignore_docs else p.read_bytes())
    return h.hexdigest()[:16]
