"""Writes docs/validation/30_contact.md and contact_*.png (make validate)."""
import pytest


@pytest.mark.validation
def test_contact_validation_report():
    from tests.contact import report

    text = report.write()
    assert "## Contact mechanics" in text
