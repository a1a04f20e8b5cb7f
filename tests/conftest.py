"""Pytest configuration: the 'validation' marker.

Tests marked ``@pytest.mark.validation`` are slow cross-checks (full 3D
models, minutes of run time); they are skipped unless pytest is run with
``--validation``:

    .venv/bin/python -m pytest tests/validation --validation -s
"""
import pytest


def pytest_addoption(parser):
    parser.addoption("--validation", action="store_true", default=False,
                     help="run the slow validation tests (marked 'validation')")


def pytest_configure(config):
    config.addinivalue_line("markers", "validation: slow validation test, run only with --validation")


def pytest_collection_modifyitems(config, items):
    if config.getoption("--validation"):
        return
    skip = pytest.mark.skip(reason="validation test: needs --validation")
    for item in items:
        if "validation" in item.keywords:
            item.add_marker(skip)
