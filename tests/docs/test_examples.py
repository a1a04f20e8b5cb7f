"""The README's and the tutorial's examples run (issue 33), as scikit-fem runs its documented examples.

A fenced ```bash or ```python block is preceded by a marker: ``<!-- test: run -->`` (executed: a bash
block with ``bash -e`` in the repository root, a python block by this interpreter, cwd the root; exit 0
asserted) or ``<!-- test: skip <reason> -->`` (not executed: the reason is required).  A fenced block
after ``<!-- test: output -->`` shows the output of the run block before it: each of its lines must
appear in what the block printed (the repository's path printed as ``.``; a line ``...`` stands for
lines left out).  Every bash/python block carries a marker, so an example cannot drift unrun."""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = ["README.md", "docs/tutorial.md"]
BLOCK = re.compile(r"(?:<!--\s*test:\s*(?P<marker>.*?)\s*-->\s*\n)?```(?P<lang>\w*)\n(?P<body>.*?)\n```", re.S)


def blocks(doc: str) -> list[dict]:
    """The fenced blocks of a document: lang, body, marker (None when unmarked), line number."""
    text = (ROOT / doc).read_text(encoding="utf-8")
    return [{"lang": m["lang"], "body": m["body"], "marker": m["marker"], "line": text.count("\n", 0, m.start()) + 1}
            for m in BLOCK.finditer(text)]


def examples(doc: str) -> list[tuple[dict, dict | None]]:
    """(run block, its output block or None) of a document."""
    out, bs = [], blocks(doc)
    for i, b in enumerate(bs):
        if b["marker"] == "run":
            nxt = bs[i + 1] if i + 1 < len(bs) and bs[i + 1]["marker"] == "output" else None
            out.append((b, nxt))
    return out




def test_every_code_block_is_marked():
    for doc in PAGES:
        bs = blocks(doc)
        assert bs, f"{doc}: no fenced block"
        for b in bs:
            if b["lang"] in ("bash", "sh", "python"):
                m = b["marker"] or ""
                assert m == "run" or (m.startswith("skip") and len(m) > len("skip") + 5), \
                    f"{doc}:{b['line']}: a {b['lang']} block needs <!-- test: run --> or <!-- test: skip <reason> -->"
            if b["marker"] == "output":
                assert b["lang"] == "text", f"{doc}:{b['line']}: an output block is ```text"
        assert any(b["marker"] == "run" for b in bs), f"{doc}: no example is run"


def run(block: dict) -> subprocess.CompletedProcess:
    env = os.environ | {"OMP_NUM_THREADS": "1"}
    cmd = ["bash", "-e", "-c", block["body"]] if block["lang"] in ("bash", "sh") else [sys.executable, "-c", block["body"]]
    return subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True, timeout=900, stdin=subprocess.DEVNULL)


@pytest.mark.parametrize("doc", PAGES)
def test_examples_run(doc):
    """A page's examples in the page's order (a tutorial's step builds on the one before: its files, its
    results, which Make then finds up to date), whatever order the tests run in."""
    for block, output in examples(doc):
        r = run(block)
        printed = (r.stdout + r.stderr).replace(str(ROOT), ".")
        assert r.returncode == 0, f"{doc}:{block['line']} exit {r.returncode}:\n{printed[-3000:]}"
        if output is not None:
            for line in output["body"].splitlines():
                if line.strip() and line.strip() != "...":
                    assert line.rstrip() in printed, f"{doc}:{output['line']}: not printed: {line!r}\n{printed[-3000:]}"


def test_the_required_examples_are_run_and_show_output():
    """The README's curve command and its Python API example are among the executed blocks, each with
    the output it shows (the headline: wheel, frequency, mode, L_pA)."""
    ex = examples("README.md")
    curve = [(b, o) for b, o in ex if b["lang"] == "bash" and "make curve CURVE=r75" in b["body"]]
    api = [(b, o) for b, o in ex if b["lang"] == "python" and "curve_verdict(" in b["body"]]
    assert curve and api
    for b, o in curve + api:
        assert o is not None and re.search(r"a1i\W+at\W+\d+ Hz", o["body"]), b["body"]
