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
    matches the current wheel file before collection, and that the BV50 rail and the
    default contact are built: the receptance, Green's function, interaction and
    radiation tests run on the real artifacts, also on a fresh clone.
    Built in subprocesses (the CLI), so this process keeps no PETSc/MPI or
    Gmsh state (VTK's offscreen rendering aborts after an in-process PETSc
    initialisation in some orders)."""
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    check = ("from pipeline.store.artifacts import load_npz; from pipeline.store.paths import wheel_dir; "
             "from pipeline.stages.wheel import load_wheel; "
             "load_npz(wheel_dir('c20') / 'modes.npz', 'wheel-modes', load_wheel('c20')[0])")
    if subprocess.run([sys.executable, "-c", check], cwd=root, capture_output=True).returncode != 0:
        for stage in ("mesh", "modes"):
            subprocess.run([sys.executable, "-m", "pipeline", stage, "--wheel", "c20", "-q"], cwd=root, check=True)
    # the BV50 rail and the default case's contact (the interaction tests' per-step NORM and Kalker
    # checks, the radiate stage's tests), through Make: built when missing or older than their inputs,
    # so a fresh clone runs these tests instead of skipping them
    subprocess.run(["make", "-s", "--no-print-directory", "build/rails/bv50/rail.npz",
                    "build/cases/default/contact.npz"], cwd=root, check=True)


@pytest.fixture(scope="session")
def r75_verdict():
    """build/curves/r75 (the default curve `make` runs), made or found up to date through Make, so the tests
    that read it run on a fresh clone and in any order."""
    import subprocess

    from pipeline.store import paths

    subprocess.run(["make", "-s", "--no-print-directory", "curve", "CURVE=r75"], cwd=paths.ROOT, check=True,
                   capture_output=True)
    return paths.build() / "curves" / "r75"
