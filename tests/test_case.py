"""Case names and the one resolved case (issue 25): ``pipeline.paths`` for curve wheels
``<curve>/<wheel>``, ``pipeline.case.resolve_case``."""
from __future__ import annotations

import pytest

from pipeline import paths


def test_curve_wheel_paths(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    assert paths.case_file("r150/a1i") == tmp_path / "curves" / "r150" / "cases" / "a1i.toml"
    assert paths.case_dir("r150/a1i") == tmp_path / "cases" / "r150" / "a1i"
    assert paths.case_file("default") == paths.cases() / "default.toml"
    assert paths.case_dir("default") == tmp_path / "cases" / "default"
    assert paths.curve_wheel("r150/a1i") == ("r150", "a1i") and paths.curve_wheel("default") is None


@pytest.mark.parametrize("bad", ["a/b/c", "/a1i", "r150/", "../x", "r150/.."])
def test_malformed_curve_wheel_names(bad):
    with pytest.raises(ValueError, match="<curve>/<wheel>"):
        paths.case_file(bad)


def test_missing_curve_wheel_asks_for_make_curve(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    assert paths.missing_case("r150/a1i") == "no case file for the curve wheel r150/a1i: run make curve CURVE=r150 first"
    assert "available" in paths.missing_case("nosuchcase")
    assert paths.missing_case("default") is None
    f = paths.case_file("r150/a1i")
    f.parent.mkdir(parents=True)
    f.write_text("")
    assert paths.missing_case("r150/a1i") is None
