"""Assemble docs/validation.md from the fragments the validation tests write
(docs/validation/*.md, in name order).  Usage: python -m pipeline.docs validation"""
from __future__ import annotations

import sys
import time

from .artifacts import atomic_write
from .paths import ROOT

HEADER = """# Validation

Every stage is checked against something it did not produce: exact
solutions, published tables, an independent second method. This file is
assembled by `make validate` from the fragments in `docs/validation/`
(each written by the validation test named in it); plots are beside them.
"""


def assemble_validation() -> str:
    parts = [HEADER, f"_Assembled {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}._\n"]
    for frag in sorted((ROOT / "docs" / "validation").glob("*.md")):
        parts.append(frag.read_text().strip() + "\n")
    text = "\n".join(parts)
    with atomic_write(ROOT / "docs" / "validation.md") as tmp:
        tmp.write_text(text)
    return text


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv != ["validation"]:
        print("usage: python -m pipeline.docs validation", file=sys.stderr)
        return 2
    assemble_validation()
    print("wrote docs/validation.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
