"""Slow validation tests (run with ``pytest --validation``)."""
