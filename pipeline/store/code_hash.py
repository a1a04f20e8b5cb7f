"""The hash of the code an artifact's numbers depend on: the ``code`` entry of a cache key.

``code_key(entries)`` is the one way a cache names its code: ``entries`` are the functions whose
results it keeps (``"package.module:function"``), and the files hashed are those the functions can
reach through the imports (``pipeline.store.deps.stage_files``, the analysis that writes Make's
dependencies), so no list of files is kept by hand and a module a computation starts to use is in its
key from then on.  Each file counts as its relative path followed by its bytes, so a changed file
makes a new key and a stale cache is never read.  ``ignore_docs=True`` hashes a Python file's syntax
tree without its docstrings instead of its bytes (``code_text``), so that editing documentation keeps
the results (the study rows).  Computed once per process for the same files (path, size,
modification time).
"""
from __future__ import annotations

import ast
import functools
import hashlib

from pipeline.store import deps
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


@functools.lru_cache(maxsize=None)
def reached_files(entries: tuple[str, ...], root=ROOT) -> tuple[str, ...]:
    """The repository files (relative paths, sorted) that the functions ``entries`` can reach."""
    files = set()
    for entry in entries:
        module, _, function = entry.partition(":")
        files.update(deps.stage_files(module, function, root))
    return tuple(sorted(files))


@functools.lru_cache(maxsize=None)
def _code_text(path, mtime_ns: int, size: int) -> bytes:
    """``code_text`` once per process while the file stays the same."""
    return code_text(path)


def code_key(*entries: str, ignore_docs: bool = False, root=ROOT) -> str:
    """16 hex digits of the hash of the code the functions ``entries`` ("module:function") reach."""
    files = [root / f for f in reached_files(tuple(sorted(entries)), root)]
    return _hash(root, tuple((p, p.stat().st_mtime_ns, p.stat().st_size) for p in files), ignore_docs)


@functools.lru_cache(maxsize=64)
def _hash(root, files: tuple, ignore_docs: bool) -> str:
    h = hashlib.sha256()
    for p, *stamp in files:
        h.update(p.relative_to(root).as_posix().encode())
        h.update(_code_text(p, *stamp) if ignore_docs else p.read_bytes())
    return h.hexdigest()[:16]
