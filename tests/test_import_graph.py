"""The house's import graph (issue 34), read from the source text (AST, nothing imported).

- no import circle among the project's modules, counting the imports inside functions too (an import
  deferred into a function hides a circle from Python, not from a reader);
- at most 12 modules at pipeline/'s top level (the rest lives in its sub-packages);
- no hand-kept list of code files: a cache names the functions whose results it keeps and its code key is
  derived from the import graph (``pipeline.store.code_hash.code_key``), so no module assigns a list of
  ``.py`` paths.

The circle finder is checked on a graph with a known circle, so that a broken finder cannot pass.
"""
from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("pipeline", "solvers", "postprocess", "geometry")
MAX_TOP = 12


def _modules(root: Path = ROOT) -> dict[str, Path]:
    out = {}
    for pkg in PACKAGES:
        for p in sorted((root / pkg).rglob("*.py")):
            if "__pycache__" in p.parts:
                continue
            name = ".".join(p.relative_to(root).with_suffix("").parts)
            out[name.removesuffix(".__init__")] = p
    return out


def import_graph(root: Path = ROOT) -> dict[str, set[str]]:
    """module -> the project modules it imports (anywhere in the file)."""
    mods = _modules(root)
    graph = {m: set() for m in mods}
    for m, p in mods.items():
        package = m if p.name == "__init__.py" else m.rpartition(".")[0]
        for node in ast.walk(ast.parse(p.read_text(), filename=str(p))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    parts = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join(parts + ([base] if base else []))
                names = [base] + [f"{base}.{a.name}" for a in node.names]
            else:
                continue
            for n in names:
                if n in mods and n != m and not m.startswith(n + "."):  # a package's own __init__ runs anyway
                    graph[m].add(n)
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan), a package's __init__
    re-exporting its own sub-modules excepted."""
    index, low, on, stack, out, counter = {}, {}, set(), [], [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    own = [c for c in out if all(any(o.startswith(x + ".") or x.startswith(o + ".") for o in c if o != x) for x in c)]
    return [c for c in out if c not in own]


def test_the_circle_finder_finds_a_circle():
    g = {"a.x": {"a.y"}, "a.y": {"a.z"}, "a.z": {"a.x"}, "a.w": {"a.x"}, "p": {"p.m"}, "p.m": {"p"}}
    assert circles(g) == [["a.x", "a.y", "a.z"]]


def test_no_import_circle():
    found = circles(import_graph())
    assert not found, "import circles (function-level imports counted):\n" + "\n".join(" -> ".join(c) for c in found)


def test_pipeline_top_level_is_small():
    top = sorted(p.name for p in (ROOT / "pipeline").glob("*.py") if p.name != "__init__.py")
    assert len(top) <= MAX_TOP, f"pipeline/ has {len(top)} modules at its top level (at most {MAX_TOP}): {top}"


def test_no_hand_kept_list_of_code_files():
    """No module assigns a list or tuple of .py paths (a cache's code comes from ``code_key``)."""
    bad = []
    for name, p in _modules().items():
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, (ast.Assign, ast.AnnAssign)) and isinstance(node.value, (ast.List, ast.Tuple, ast.Set)):
                strings = [e.value for e in node.value.elts if isinstance(e, ast.Constant) and isinstance(e.value, str)]
                if any(s.endswith(".py") for s in strings):
                    bad.append(f"{p.relative_to(ROOT)}:{node.lineno}")
    assert not bad, "hand-kept lists of code files (derive them with pipeline.store.code_hash.code_key):\n" + "\n".join(bad)


def unexplained_local_imports(root: Path = ROOT) -> list[str]:
    """Imports inside functions or classes without a comment on their line saying why (issue 34: a module's top
    says what it depends on; a local import is the exception and carries its reason, e.g. '# lazy: brings in
    dolfinx')."""
    out = []
    for mod, path in _modules(root).items():
        src = path.read_text()
        lines = src.splitlines()
        for node in ast.walk(ast.parse(src)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                for sub in ast.walk(node):
                    if isinstance(sub, (ast.Import, ast.ImportFrom)):
                        text = "\n".join(lines[sub.lineno - 1:sub.end_lineno])
                        if "#" not in text:
                            out.append(f"{path.relative_to(root)}:{sub.lineno}: {lines[sub.lineno - 1].strip()}")
    return sorted(set(out))


def test_the_local_import_check_finds_an_unexplained_import(tmp_path):
    pkg = tmp_path / "pipeline"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "m.py").write_text("def f():\n    import json\n    import math  # lazy: reason\n    return json, math\n")
    assert unexplained_local_imports(tmp_path) == ["pipeline/m.py:2: import json"]


def test_local_imports_say_why():
    bad = unexplained_local_imports()
    assert not bad, "imports inside functions without a reason:\n" + "\n".join(bad[:40])
