"""The study tests run on the default case's artifacts (contact.npz, greens.npz and the wheel's
modes): built here in subprocesses (the CLI) when missing or stale, as tests/conftest.py does
for the wheel modes."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _ok(code: str) -> bool:
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True).returncode == 0


def _stage(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pipeline", *args, "-q"], cwd=ROOT, check=True)


def ensure_case(case: str = "default") -> None:
    if _ok(f"from pipeline.study.context import load_context; load_context({case!r}, radiation=False)"):
        return
    if not _ok("from pipeline.store.artifacts import load_npz; from pipeline.stages.rail import load_rail_params; "
               "from pipeline.store.paths import rail_dir; "
               "load_npz(rail_dir('bv50') / 'rail.npz', 'rail', load_rail_params('bv50')[0])"):
        _stage("rail", "--rail", "bv50")
    _stage("contact", "--case", case)
    _stage("greens", "--case", case)


@pytest.fixture(scope="session")
def default_case():
    ensure_case("default")
    return "default"
