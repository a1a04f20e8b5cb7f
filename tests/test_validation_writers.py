"""The validation writers and the tests kept apart (issue 34): every fragment of docs/validation/ has exactly
one writer in ``pipeline.validation.writers.registry`` (run by `make validate`, or named as a study run by
hand), every writer module exists and has its entry point; no test writes into docs/validation/ (no string
naming that folder outside docstrings, no ``DOCS``, no writer's ``write``/``save_fragment`` called from
tests/); nothing outside tests/ imports tests/ (the writers, benchmarks and the pipeline take their
references from pipeline/validation/references/).  Read from the source text (AST), nothing run."""
from __future__ import annotations

import ast
from pathlib import Path

from pipeline.validation.writers.registry import WRITERS

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs" / "validation"


def _module_file(module: str) -> Path:
    p = ROOT / Path(*module.split("."))
    return p / "__init__.py" if p.is_dir() else p.with_suffix(".py")


def test_every_fragment_has_exactly_one_writer():
    claimed = [f for w in WRITERS for f in w.fragments]
    assert len(claimed) == len(set(claimed)), sorted(f for f in claimed if claimed.count(f) > 1)
    on_disk = {p.name for p in DOCS.glob("*.md")}
    assert on_disk == set(claimed), (sorted(on_disk - set(claimed)), sorted(set(claimed) - on_disk))
    assert len({w.name for w in WRITERS}) == len(WRITERS)


def test_every_writer_module_exists_and_runs_as_a_script():
    for w in WRITERS:
        path = _module_file(w.module)
        assert path.exists(), (w.name, path)
        tree = ast.parse(path.read_text())
        main = [n for n in tree.body if isinstance(n, ast.If) and "__main__" in ast.unparse(n.test)]
        assert main, f"{path}: no `if __name__ == '__main__'` entry"


def _docstrings(tree) -> set[int]:
    out = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(body, list) and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            out.add(id(body[0].value))
    return out


def test_no_test_writes_into_docs_validation():
    offenders = []
    for p in sorted((ROOT / "tests").rglob("*.py")):
        if p == Path(__file__):
            continue
        tree = ast.parse(p.read_text())
        docs = _docstrings(tree)
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs \
                    and "docs/validation" in node.value:
                offenders.append(f"{p.relative_to(ROOT)}:{node.lineno}: {node.value[:40]!r}")
            elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div) \
                    and "'docs' / 'validation'" in ast.unparse(node):
                offenders.append(f"{p.relative_to(ROOT)}:{node.lineno}: {ast.unparse(node)}")
            elif isinstance(node, ast.Name) and node.id in ("DOCS", "save_fragment"):
                offenders.append(f"{p.relative_to(ROOT)}:{node.lineno}: {node.id}")
            elif isinstance(node, ast.Attribute) and node.attr in ("save_fragment", "write", "write_report") \
                    and isinstance(node.value, ast.Name) and node.value.id not in ("tmp", "fh", "f", "path", "p"):
                offenders.append(f"{p.relative_to(ROOT)}:{node.lineno}: {ast.unparse(node)}")
    assert not offenders, "tests writing docs/validation (move the writing into pipeline/validation/writers/):\n" \
        + "\n".join(offenders)


def test_nothing_outside_tests_imports_tests():
    offenders = []
    for top in ("pipeline", "solvers", "postprocess", "geometry", "benchmarks"):
        for p in sorted((ROOT / top).rglob("*.py")):
            for node in ast.walk(ast.parse(p.read_text())):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                    [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else []
                offenders += [f"{p.relative_to(ROOT)}:{node.lineno}: {n}" for n in names
                              if n == "tests" or n.startswith("tests.")]
    assert not offenders, "\n".join(offenders)
