"""Study kinds are found, not listed (issue 34: adding a kind touches one place, pipeline/study/kinds/)."""
from __future__ import annotations

import shutil

import pytest

from pipeline.config.loader import ConfigError
from pipeline.store import deps
from pipeline.study import kinds
from pipeline.study.check import check_study


def test_every_kind_module_has_a_schema_and_a_run():
    assert set(kinds.NAMES) == {"contact", "damping", "line", "map"}
    for name in kinds.NAMES:
        mod = kinds.kind_module(name)
        assert callable(mod.run) and "kind" in mod.SCHEMA


def test_a_new_kind_is_one_module(tmp_path):
    """A module dropped into a copy of pipeline/study/kinds/ is a kind that Make's dependency scan follows."""
    root = tmp_path / "repo"
    for pkg in ("pipeline", "solvers", "geometry", "postprocess"):
        shutil.copytree(deps.ROOT / pkg, root / pkg, ignore=shutil.ignore_patterns("__pycache__"))
    (root / "pipeline/study/kinds/sweep.py").write_text(
        "from solvers.constants import F_MAX_HZ\n\nSCHEMA = {}\n\n\ndef run(spec, src, out, **kw):\n"
        "    return F_MAX_HZ\n")
    reached = deps.stage_files("pipeline.study.check", "check_study", root)
    assert "pipeline/study/kinds/sweep.py" in reached and "solvers/constants.py" in reached


def test_an_unknown_kind_names_the_key_and_the_kinds(tmp_path, monkeypatch):
    (tmp_path / "odd.toml").write_text('name = "odd"\nkind = "sweep"\n')
    monkeypatch.setattr("pipeline.store.paths.study_file", lambda name: tmp_path / f"{name}.toml")
    with pytest.raises(ConfigError, match=r"kind = 'sweep'.*one of \['contact', 'damping', 'line', 'map'\]"):
        check_study("odd")
