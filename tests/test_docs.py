"""The generated input reference is up to date, covers every schema key with its range, and the
physics document the code cites lives in the repository (nothing cites a file outside it)."""
from __future__ import annotations

import re
import subprocess

from pipeline.validation import docs
from pipeline.config.schema import Field
from pipeline.store.paths import ROOT
from pipeline.config.input_schemas import CASE, LISTENER


def test_inputs_page_is_up_to_date():
    page = (ROOT / "docs" / "inputs.md").read_text()
    assert page == docs.inputs_text(), "docs/inputs.md is stale: run `.venv/bin/python -m pipeline.validation.docs inputs`"


def test_inputs_page_lists_every_case_key_with_its_range():
    text = docs.inputs_text()
    rows = docs.schema_rows(CASE)
    assert len(rows) >= 20
    for key, unit, allowed, default, _ in rows:
        assert f"| `{key}` |" in text
    # one key checked by hand against its schema: the listener's distance
    f: Field = LISTENER["distance"]
    line = next(s for s in text.splitlines() if s.startswith("| `listener.distance` |"))
    assert "| m |" in line and "0 < value <= 1000" in line and "`7.5`" in line
    assert f.describe() in line
    # the dy_wr bound as the pydantic model enforces it
    line = next(s for s in text.splitlines() if s.startswith("| `contact.dy_wr` |"))
    assert "-0.03 <= value <= 0.03" in line and "required" in line


def test_physics_document_cites_the_thesis_sections_the_code_uses():
    text = (ROOT / "docs" / "physics.md").read_text()
    for n in range(1, 8):
        assert re.search(rf"^## {n}\. ", text, re.M), f"section {n} missing (the code cites 'SPEC {n}')"
    for eq in ("[4.10]", "[4.11]", "[4.3]", "[4.16]", "[4.25]", "[4.32]", "[4.36]", "[4.38]"):
        assert eq in text


def test_nothing_cites_a_file_outside_the_repository():
    out = subprocess.run(["git", "grep", "-n", "shared" + "/SPEC"], cwd=ROOT, capture_output=True, text=True)
    assert out.stdout == "", out.stdout
