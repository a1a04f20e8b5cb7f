"""The study tests run on the default case's artifacts (contact.npz, greens.npz and the wheel's
modes): built here in subprocesses (the CLI) when missing or stale, as tests/conftest.py does
for the wheel modes."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def ensure_case(case: str = "default") -> None:
    check = f"from pipeline.study_context import load_context; load_context({case!r}, radiation=False)"
    if subprocess.run([sys.executable, "-c", check], cwd=ROOT, capture_output=True).returncode == 0:
        return
    for stage in ("rail", "contact", "greens"):
        arg = ["--rail", "bv50"] if stage == "rail" else ["--case", case]
        ok = subprocess.run([sys.executable, "-c", f"from pipeline.artifacts import load_npz; "
                             f"from pipeline.rail_stage import load_rail_params; from pipeline.paths import rail_dir; "
                             f"load_npz(rail_dir('bv50') / 'rail.npz', 'rail', load_rail_params('bv50')[0])"],
                            cwd=ROOT, capture_output=True).returncode == 0 if stage == "rail" else False
        if not ok:
            subprocess.run([sys.executable, "-m", "pipeline", stage, *arg, "-q"], cwd=ROOT, check=True)


@pytest.fixture(scope="session")
def default_case():
    ensure_case("default")
    return "default"
