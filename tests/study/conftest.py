"""The study tests run on the default case's artifacts (contact.npz, greens.npz and the wheel's
modes): built through Make when missing or stale (``pipeline.validation.make.ensure_case``)."""
from pathlib import Path

import pytest

from pipeline.validation.make import ensure_case

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def default_case():
    ensure_case("default")
    return "default"
