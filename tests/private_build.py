"""A private build folder with the default case's built artifacts linked in (tests that run one stage for real
without touching build/)."""
from __future__ import annotations

import pytest

from pipeline.store import paths

REAL = paths.ROOT / "build"


def default_case_build(tmp_path, monkeypatch, stages, why: str):
    """tmp_path/build with build/cases/default/<stage>.npz for each of ``stages``, the C20 modes and the BV50
    rail linked, and SQUEAL_BUILD_DIR pointing at it; skipped (``why``) when build/ lacks one of them."""
    need = [REAL / "cases" / "default" / f"{s}.npz" for s in stages]
    if not all(p.exists() for p in need):
        pytest.skip(why)
    build = tmp_path / "build"
    (build / "cases" / "default").mkdir(parents=True)
    for p in need:
        (build / "cases" / "default" / p.name).symlink_to(p)
    for sub in ("wheels/c20/modes.npz", "rails/bv50/rail.npz"):
        (build / sub).parent.mkdir(parents=True, exist_ok=True)
        (build / sub).symlink_to(REAL / sub)
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(build))
    return build
