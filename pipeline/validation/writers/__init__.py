"""The writers of docs/validation/: each module measures one topic against its independent reference
(``pipeline.validation.references``), and writes its Markdown fragment and plots; ``make validate``
runs them all (``python -m pipeline.validation.writers``) and assembles docs/validation.md.  They are
not tests: the limits each fragment states are asserted by the tests under tests/ (the fragment names
them).  ``python -m pipeline.validation.writers.<module>`` runs one.

Shared here: ``DOCS`` (the folder), ``pyplot()`` (matplotlib without a display), ``save_fragment``."""
from __future__ import annotations

from pipeline.store.atomic import save_figure, save_text
from pipeline.store.paths import ROOT

DOCS = ROOT / "docs" / "validation"

__all__ = ["DOCS", "pyplot", "save_figure", "save_fragment"]


def pyplot():
    """matplotlib.pyplot on the Agg backend (imported when a writer draws)."""
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    return plt


def save_fragment(name: str, text: str) -> str:
    """Write docs/validation/<name> atomically; returns the text."""
    DOCS.mkdir(parents=True, exist_ok=True)
    save_text(text, DOCS / name)
    return text
