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


def pytest_sessionstart(session):
    """Make sure the C20 modal artifact (build/wheels/c20/modes.npz) exists and
    matches the current wheel file before collection: the receptance, Green's
    function and radiation tests run on the real C20, also on a fresh clone."""
    from pipeline.artifacts import ArtifactError, load_npz
    from pipeline.paths import wheel_dir
    from pipeline.wheel_stage import load_wheel, run_mesh, run_modes

    p, _ = load_wheel("c20")
    try:
        load_npz(wheel_dir("c20") / "modes.npz", "wheel-modes", p)
    except ArtifactError:
        run_mesh("c20")
        run_modes("c20")
