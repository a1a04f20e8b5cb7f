"""Generated documentation pages.

``python -m pipeline.validation.docs validation`` assembles docs/validation.md from the
fragments the validation writers write (docs/validation/*.md, in name order; ``pipeline.validation.writers``);
``python -m pipeline.validation.docs inputs`` writes docs/inputs.md, the reference of every
input key (unit, range, default, meaning) generated from the schemas
(``pipeline/config/input_schemas.py``, the study schemas, and the schema modules listed in
``INPUT_PAGES`` that exist); tests/test_docs.py checks it is up to date."""
from __future__ import annotations

import importlib
import sys
import time
from collections.abc import Mapping

from pipeline.store.artifacts import atomic_write
from pipeline.store.paths import ROOT
from pipeline.config.schema import REQUIRED, Field, ListOf

HEADER = """# Validation

Every stage is checked against something it did not produce: exact
solutions, published tables, an independent second method. This file is
assembled by `make validate` from the fragments in `docs/validation/`
(each written by the writer named in it, `pipeline/validation/writers/`; the
limits a fragment states are asserted by the tests it names); plots are beside them.
"""

# (title, file pattern, module, attribute): one section of docs/inputs.md each; a dict attribute
# maps kind -> schema (one subsection per kind); modules that do not exist (yet) are left out
INPUT_PAGES = (
    ("Wheel", "geometry/wheels/<name>.toml", "pipeline.config.input_schemas", "WHEEL"),
    ("Rail", "geometry/rails/<name>.toml", "pipeline.config.input_schemas", "RAIL"),
    ("Case", "pipeline/cases/<name>.toml", "pipeline.config.input_schemas", "CASE"),
    ("Study (`kind` picks the schema)", "pipeline/studies/<name>.toml", "pipeline.study.kinds", "NAMES"),
    ("A line study's curves (CSV columns, one row per curve, vehicle and friction condition)",
     "pipeline/studies/<curves>.csv", "pipeline.study.line_input", "ROW_SCHEMA"),
    ("Vehicle", "geometry/vehicles/<name>.toml", "pipeline.config.curve_schemas", "VEHICLE"),
    ("Curve", "pipeline/curves/<name>.toml", "pipeline.config.curve_schemas", "CURVE"),
)

INPUTS_HEADER = """# Input reference

Every key of every input file, with its unit, allowed range, default and meaning.
Generated from the schemas by `python -m pipeline.validation.docs inputs` (do not edit by hand;
`tests/test_docs.py` checks that it is up to date). A key without a default must be
given; "optional" means it may be left out (then the behaviour in its description
applies). A value outside its range is refused before any work, with one line naming
the file, the key, the value and this range (`make check CASE=..`).
"""


def assemble_validation() -> str:
    parts = [HEADER, f"_Assembled {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}._\n"]
    for frag in sorted((ROOT / "docs" / "validation").glob("*.md")):
        parts.append(frag.read_text().strip() + "\n")
    text = "\n".join(parts)
    with atomic_write(ROOT / "docs" / "validation.md") as tmp:
        tmp.write_text(text)
    return text


def _cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _default(spec) -> str:
    d = spec.default
    if d is REQUIRED:
        return "required"
    if d is None:
        return "optional"
    if isinstance(d, tuple):
        d = list(d)
    return f"`{d!r}`" if not isinstance(d, bool) else f"`{str(d).lower()}`"


def schema_rows(schema: Mapping, prefix: str = "") -> list[tuple[str, str, str, str, str]]:
    """(dotted key, unit, allowed, default, description) of every key of ``schema``, tables
    flattened in their order (``[a] b`` is ``a.b``)."""
    rows = []
    for key, spec in schema.items():
        name = f"{prefix}{key}"
        if isinstance(spec, Mapping):
            rows.extend(schema_rows(spec, name + "."))
        elif isinstance(spec, Field):
            rows.append((name, spec.unit or "-", spec.describe(), _default(spec), spec.doc))
        elif isinstance(spec, ListOf):
            rows.append((name, spec.item.unit or "-", spec.describe(), _default(spec), spec.doc or spec.item.doc))
        else:
            raise TypeError(f"{name}: not a schema entry: {spec!r}")
    return rows


def _table(schema: Mapping) -> str:
    lines = ["| key | unit | allowed | default | meaning |", "|---|---|---|---|---|"]
    lines += [f"| `{k}` | {_cell(u)} | {_cell(a)} | {_cell(d)} | {_cell(doc)} |" for k, u, a, d, doc in
              schema_rows(schema)]
    return "\n".join(lines) + "\n"


def inputs_text() -> str:
    """The text of docs/inputs.md (deterministic: no date)."""
    parts = [INPUTS_HEADER]
    for title, pattern, module, attr in INPUT_PAGES:
        try:
            mod = importlib.import_module(module)
        except ModuleNotFoundError as e:
            if e.name != module:
                raise
            continue
        schema = getattr(mod, attr, None)
        if schema is None:
            continue
        parts.append(f"## {title}: `{pattern}`\n")
        if attr == "NAMES":  # the study kinds: each module's SCHEMA
            for kind in schema:
                parts.append(f"### `kind = \"{kind}\"`\n\n" + _table(mod.kind_module(kind).SCHEMA))
        else:
            parts.append(_table(schema))
    return "\n".join(parts)


def write_inputs() -> str:
    text = inputs_text()
    with atomic_write(ROOT / "docs" / "inputs.md") as tmp:
        tmp.write_text(text)
    return text


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv == ["validation"]:
        assemble_validation()
        print("wrote docs/validation.md")
        return 0
    if argv == ["inputs"]:
        write_inputs()
        print("wrote docs/inputs.md")
        return 0
    print("usage: python -m pipeline.validation.docs validation|inputs", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
