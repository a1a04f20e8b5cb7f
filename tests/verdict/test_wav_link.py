"""A squealing wheel's verdict row links the WAV the listen stage wrote (issue 33: verdict.csv's `wav`
and verdict.md's "Listen:" named `listen.wav`, a file that is never written; the stage writes
`listen_<receiver>.wav`, e.g. `listen_7.5m.wav`).

The wheel's case is the default case under a curve wheel's name (``t/a1i``) in a private build: its
contact and greens artifacts are the default case's (the same configuration); the simulate, radiate and
listen stages run for real, as ``stage.wheel_verdict`` calls them, and it builds the row."""
from __future__ import annotations

import math
from pathlib import Path

import pytest

from pipeline.store import paths
from tests.verdict.points import operating_point

ROOT = paths.ROOT
REAL = ROOT / "build"
NEED = [REAL / "cases" / "default" / f"{s}.npz" for s in ("contact", "greens")]


@pytest.fixture
def curve_wheel(tmp_path, monkeypatch):
    if not all(p.exists() for p in NEED + [REAL / "rails" / "bv50" / "rail.npz"]):
        pytest.skip("needs the default case built (make)")
    build = tmp_path / "build"
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(build))
    for sub in ("wheels/c20/modes.npz", "rails/bv50/rail.npz"):
        (build / sub).parent.mkdir(parents=True, exist_ok=True)
        (build / sub).symlink_to(REAL / sub)
    case = build / "curves" / "t" / "cases" / "a1i.toml"
    case.parent.mkdir(parents=True)
    case.write_text((ROOT / "pipeline" / "cases" / "default.toml").read_text().replace(
        'name = "default"', 'name = "t/a1i"'))
    d = paths.case_dir("t/a1i")
    d.mkdir(parents=True)
    for p in NEED:
        (d / p.name).symlink_to(p)
    return d


def test_squealing_row_links_the_wav_that_exists(curve_wheel, monkeypatch):
    from pipeline.config.case import clear
    from pipeline.config.loader import load
    from pipeline.config.input_schemas import CASE
    import dataclasses

    from pipeline.config.curve_inputs import read_curve
    from pipeline.curve import stage

    clear()
    real_run = stage.run_stages
    # contact and greens are the default case's (linked above); the others run
    monkeypatch.setattr(stage, "run_stages", lambda name, stages: real_run(name, [s for s in stages
                                                                            if s not in ("contact", "greens")]))
    c = load(paths.case_file("t/a1i"), CASE)
    info = dataclasses.replace(read_curve("r150"), name="t")     # its wheel a1i is the case file t/a1i above
    p = operating_point(wheel="a1i", dy_wr=c["contact"]["dy_wr"], angle_of_attack=0.02, gamma_y=c["kinematics"]["gamma_y"],
               wheel_load=c["loading"]["preload"], normal_load=c["loading"]["preload"])
    row = stage.wheel_verdict(info, p, what_ifs=False)
    assert row["squeals"] and math.isfinite(row["L_pA"])
    wav = Path(row["wav"])
    assert wav.exists(), f"verdict row links {wav.name}; the case folder holds " \
                         f"{sorted(x.name for x in curve_wheel.glob('*.wav'))}"
    assert wav.name == "listen_7.5m.wav" and wav.parent == curve_wheel     # the case's receiver, 7.5 m, 1.2 m
    # verdict.md's "Listen:" names the same file
    from pipeline.curve.verdict_report import verdict_markdown

    md = verdict_markdown(info, [p], [row], wall=1.0)
    assert f"Listen: `{wav}`" in md


