"""Tests for pipeline.store.artifacts: atomic writes, provenance, checked loading."""

from __future__ import annotations

import csv
import json
import os
import pickle
import re
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from pipeline.store import provenance as provenance_module
from pipeline.store.artifacts import (
    PROVENANCE_KEY,
    ArtifactError,
    atomic_write,
    load_json,
    load_npz,
    provenance,
    save_csv,
    save_json,
    save_npz,
)
from pipeline.store.provenance import git_revision, library_versions
from pipeline.config.loader import config_hash

REPO_ROOT = Path(__file__).resolve().parent.parent

CFG = {"name": "r920", "tyre": {"rolling_radius": 0.46, "width": 0.135}, "n_modes": 60}


def temp_files(directory: Path) -> list[Path]:
    """Leftover temporary files of atomic_write in ``directory``."""
    return sorted(p for p in directory.iterdir() if ".tmp-" in p.name)


def changed(cfg: dict, radius: float) -> dict:
    return {**cfg, "tyre": {**cfg["tyre"], "rolling_radius": radius}}


# --------------------------------------------------------------------------
# atomic_write
# --------------------------------------------------------------------------


def test_atomic_write_success_replaces_target_and_creates_parents(tmp_path):
    target = tmp_path / "a" / "b" / "mesh.msh"
    with atomic_write(target) as tmp:
        # Hidden temp file in the same directory, same suffix as the target.
        assert tmp.parent == target.parent
        assert re.fullmatch(rf"\.mesh\.msh\.tmp-{os.getpid()}-[0-9a-f]+\.msh", tmp.name), tmp.name
        assert not target.exists()
        tmp.write_text("$MeshFormat\n")
    assert target.read_text() == "$MeshFormat\n"
    assert os.listdir(target.parent) == ["mesh.msh"]


def test_atomic_write_exception_leaves_nothing(tmp_path):
    target = tmp_path / "out.npz"
    with pytest.raises(RuntimeError, match="boom"):
        with atomic_write(target) as tmp:
            tmp.write_bytes(b"partial data")
            raise RuntimeError("boom")
    assert not target.exists()
    assert list(tmp_path.iterdir()) == []


def test_atomic_write_exception_keeps_previous_target(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old")
    for exc in (ValueError, KeyboardInterrupt):  # BaseException too
        with pytest.raises(exc):
            with atomic_write(target) as tmp:
                tmp.write_text("new but incomplete")
                raise exc()
        assert target.read_text() == "old"
        assert temp_files(tmp_path) == []


def test_atomic_write_works_with_numpy_suffix_check(tmp_path):
    # np.savez_compressed appends ".npz" unless the name already ends with it.
    target = tmp_path / "plain.npz"
    with atomic_write(target) as tmp:
        np.savez_compressed(tmp, a=np.arange(3))
    assert os.listdir(tmp_path) == ["plain.npz"]
    with np.load(target) as npz:
        assert npz["a"].tolist() == [0, 1, 2]


def test_atomic_write_respects_umask(tmp_path):
    old = os.umask(0o022)
    try:
        with atomic_write(tmp_path / "f.txt") as tmp:
            tmp.write_text("x")
    finally:
        os.umask(old)
    assert (tmp_path / "f.txt").stat().st_mode & 0o777 == 0o644  # not mkstemp's 0o600


def test_atomic_write_body_removing_temp_is_an_error(tmp_path):
    with pytest.raises(FileNotFoundError, match="disappeared"):
        with atomic_write(tmp_path / "f.txt") as tmp:
            tmp.unlink()
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------
# Real crash: SIGKILL a writer in the middle of save_npz
# --------------------------------------------------------------------------

# The child writes ~64 MB of incompressible data (takes ~2 s to deflate);
# it is killed as soon as its temporary file holds 1 MB.  Library-version
# lookup is stubbed only to keep the child's start-up fast.
_WRITER = textwrap.dedent(
    """
    import sys
    import numpy as np
    import pipeline.store.artifacts as artifacts
    import pipeline.store.provenance as provenance
    provenance.library_versions = lambda: {}
    data = np.random.default_rng(0).random(8_000_000)
    artifacts.save_npz(sys.argv[1], "big", {"n": 1}, data=data)
    print("finished")
    """
)


def _kill_writer_mid_write(target: Path) -> None:
    env = {**os.environ, "PYTHONPATH": str(REPO_ROOT)}
    proc = subprocess.Popen(
        [sys.executable, "-c", _WRITER, str(target)],
        cwd=REPO_ROOT,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        deadline = time.monotonic() + 30
        while True:
            tmps = temp_files(target.parent)
            if tmps and tmps[0].stat().st_size > 1_000_000:
                break  # well inside the write
            if proc.poll() is not None:
                out, err = proc.communicate()
                pytest.fail(f"writer exited before it could be killed: {out!r} {err!r}")
            if time.monotonic() > deadline:
                pytest.fail("temporary file never appeared")
            time.sleep(0.005)
        os.kill(proc.pid, signal.SIGKILL)
        assert proc.wait(timeout=10) == -signal.SIGKILL
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
        proc.stdout.close()
        proc.stderr.close()
    # The half-written temporary file is what a crash leaves behind ...
    assert temp_files(target.parent), "expected the killed writer's temp file"


def test_sigkill_mid_write_leaves_no_target(tmp_path):
    target = tmp_path / "big.npz"
    _kill_writer_mid_write(target)
    # ... but the target itself never exists in a partial state.
    assert not target.exists()
    with pytest.raises(ArtifactError, match=r"artifact not found; run `make modes`"):
        load_npz(target, "big", make_target="modes")


def test_sigkill_mid_write_keeps_previous_target(tmp_path):
    target = tmp_path / "big.npz"
    save_npz(target, "big", {"n": 1}, data=np.arange(5.0))
    _kill_writer_mid_write(target)
    arrays, _ = load_npz(target, "big", {"n": 1})
    np.testing.assert_array_equal(arrays["data"], np.arange(5.0))


# --------------------------------------------------------------------------
# save_npz / load_npz
# --------------------------------------------------------------------------


def test_npz_round_trip_is_exact(tmp_path):
    rng = np.random.default_rng(42)
    arrays = {
        "freqs": rng.random(1000) * 5e3,
        "modes": rng.standard_normal((50, 7)).astype(np.float32),
        "eig": rng.standard_normal(30) + 1j * rng.standard_normal(30),
        "cells": rng.integers(0, 10**6, size=(20, 4), dtype=np.int64),
        "mask": rng.random(9) > 0.5,
        "labels": np.array(["clamped", "axle"]),
        "scalar": np.float64(np.pi),
        "empty": np.zeros((0, 3)),
        "fortran": np.asfortranarray(rng.random((4, 5))),
        # Names that would collide with the function's own parameters.
        "file": np.arange(3),
        "path": np.arange(4),
        "kind": np.arange(5),
        "config": np.arange(6),
    }
    target = tmp_path / "modes" / "r920.npz"
    written = save_npz(target, "modes", CFG, **arrays)
    loaded, prov = load_npz(target, "modes", CFG)

    assert set(loaded) == set(arrays)
    for name, expected in arrays.items():
        expected = np.asarray(expected)
        assert loaded[name].dtype == expected.dtype, name
        assert loaded[name].shape == expected.shape, name
        np.testing.assert_array_equal(loaded[name], expected, err_msg=name)
    assert os.listdir(target.parent) == ["r920.npz"]  # no temp files left

    assert prov == written
    assert prov["kind"] == "modes"
    assert prov["config"] == CFG
    assert prov["config_hash"] == config_hash(CFG)
    assert re.fullmatch(r"[0-9a-f]{40}(-dirty)?|unknown", prov["git_revision"])
    assert prov["python"] == ".".join(map(str, sys.version_info[:3]))
    assert prov["versions"]["numpy"] == np.__version__
    assert set(prov["versions"]) == {
        "numpy", "dolfinx", "petsc4py", "PETSc", "slepc4py", "SLEPc", "gmsh", "numba", "scipy",
    }
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", prov["created_utc"])


def test_npz_provenance_entry_is_json_in_0d_unicode_array(tmp_path):
    target = tmp_path / "x.npz"
    save_npz(target, "modes", CFG, a=np.ones(2))
    with np.load(target, allow_pickle=False) as npz:
        raw = npz[PROVENANCE_KEY]
    assert raw.shape == () and raw.dtype.kind == "U"
    assert json.loads(str(raw[()]))["config_hash"] == config_hash(CFG)


def test_load_npz_without_config_skips_staleness_check(tmp_path):
    target = tmp_path / "x.npz"
    save_npz(target, "modes", CFG, a=np.ones(2))
    arrays, prov = load_npz(target, "modes")
    assert prov["config_hash"] == config_hash(CFG)


def test_save_npz_rejects_object_arrays_and_reserved_name(tmp_path):
    with pytest.raises(ValueError, match="object"):
        save_npz(tmp_path / "x.npz", "k", CFG, a=np.array([{"a": 1}], dtype=object))
    with pytest.raises(ValueError, match="reserved"):
        save_npz(tmp_path / "x.npz", "k", CFG, **{PROVENANCE_KEY: np.ones(1)})
    assert list(tmp_path.iterdir()) == []


def test_wrong_kind(tmp_path):
    target = tmp_path / "x.npz"
    save_npz(target, "mesh", CFG, a=np.ones(2))
    with pytest.raises(ArtifactError) as info:
        load_npz(target, "modes", CFG)
    msg = str(info.value)
    assert str(target) in msg
    assert "expected 'modes', found 'mesh'" in msg


def test_stale_config(tmp_path):
    target = tmp_path / "x.npz"
    save_npz(target, "modes", CFG, a=np.ones(2))
    new = changed(CFG, 0.47)
    with pytest.raises(ArtifactError) as info:
        load_npz(target, "modes", new, make_target="modes")
    msg = str(info.value)
    assert str(target) in msg
    assert "stale" in msg
    assert config_hash(CFG) in msg and config_hash(new) in msg
    assert "tyre.rolling_radius: 0.46 -> 0.47" in msg
    assert "make modes" in msg


def _corrupt(kind: str, target: Path) -> None:
    data = target.read_bytes()
    if kind == "truncated-half":
        target.write_bytes(data[: len(data) // 2])
    elif kind == "truncated-tail":
        target.write_bytes(data[:-10])
    elif kind == "empty":
        target.write_bytes(b"")
    elif kind == "flipped-byte":
        i = len(data) // 2  # inside the big incompressible array member
        target.write_bytes(data[:i] + bytes([data[i] ^ 0xFF]) + data[i + 1 :])
    elif kind == "garbage":
        target.write_text("this is not a zip file\n")
    elif kind == "pickle":
        target.write_bytes(pickle.dumps({"a": 1}))
    elif kind == "npy":
        with open(target, "wb") as fh:
            np.save(fh, np.arange(3))
    elif kind == "object-array":  # needs pickle to load -> refused
        with open(target, "wb") as fh:
            np.savez(fh, a=np.array([{"x": 1}], dtype=object))
    else:  # pragma: no cover
        raise AssertionError(kind)


@pytest.mark.parametrize(
    "kind",
    ["truncated-half", "truncated-tail", "empty", "flipped-byte", "garbage", "pickle", "npy",
     "object-array"],
)
def test_damaged_npz_raises_artifact_error(tmp_path, kind):
    target = tmp_path / "x.npz"
    save_npz(target, "modes", CFG, a=np.random.default_rng(0).random(100_000))
    _corrupt(kind, target)
    with pytest.raises(ArtifactError, match="unreadable or truncated") as info:
        load_npz(target, "modes", CFG, make_target="modes")
    assert str(target) in str(info.value)
    assert "make modes" in str(info.value)


def test_npz_without_provenance(tmp_path):
    target = tmp_path / "x.npz"
    np.savez(target, a=np.ones(3))
    with pytest.raises(ArtifactError, match="has no provenance") as info:
        load_npz(target, "modes")
    assert str(target) in str(info.value)


def test_missing_npz_without_hint(tmp_path):
    with pytest.raises(ArtifactError) as info:
        load_npz(tmp_path / "nope.npz", "modes")
    assert str(info.value) == f"{tmp_path / 'nope.npz'}: artifact not found"


def test_artifact_error_is_runtime_error_and_picklable(tmp_path):
    err = ArtifactError(tmp_path / "x.npz", "artifact not found")
    assert isinstance(err, RuntimeError)
    clone = pickle.loads(pickle.dumps(err))
    assert str(clone) == str(err) and clone.path == err.path


# --------------------------------------------------------------------------
# JSON
# --------------------------------------------------------------------------


def test_json_round_trip_and_checks(tmp_path):
    target = tmp_path / "sweep.json"
    payload = {"unstable": [{"f_hz": 3412.5, "sigma": 1.25}], "count": 1, "note": "µ sweep"}
    save_json(target, "sweep", CFG, payload)
    loaded, prov = load_json(target, "sweep", CFG)
    assert loaded == payload
    assert prov["config_hash"] == config_hash(CFG)
    assert "git_revision" in prov

    with pytest.raises(ArtifactError, match="expected 'modes', found 'sweep'"):
        load_json(target, "modes")
    new = changed(CFG, 0.5)
    with pytest.raises(ArtifactError) as info:
        load_json(target, "sweep", new)
    assert config_hash(CFG) in str(info.value) and config_hash(new) in str(info.value)


def test_json_damaged_or_foreign(tmp_path):
    target = tmp_path / "sweep.json"
    save_json(target, "sweep", CFG, {"x": list(range(100))})
    target.write_text(target.read_text()[:50])
    with pytest.raises(ArtifactError, match="unreadable or truncated"):
        load_json(target, "sweep")
    target.write_text('{"x": 1}')
    with pytest.raises(ArtifactError, match="has no provenance"):
        load_json(target, "sweep")
    with pytest.raises(ArtifactError, match="run `make sweep`"):
        load_json(tmp_path / "nope.json", "sweep", make_target="sweep")


def test_json_rejects_nan_without_leaving_files(tmp_path):
    with pytest.raises(ValueError):
        save_json(tmp_path / "x.json", "sweep", CFG, {"x": float("nan")})
    assert list(tmp_path.iterdir()) == []


# --------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------


def test_csv_round_trip(tmp_path):
    target = tmp_path / "out" / "table.csv"
    rows = [(0.1, 1, "a,b"), (1 / 3, 2, 'q"uote')]
    save_csv(target, ["f", "n", "label"], (r for r in rows))
    with open(target, newline="") as fh:
        read = list(csv.reader(fh))
    assert read[0] == ["f", "n", "label"]
    assert [(float(a), int(b), c) for a, b, c in read[1:]] == rows  # floats exact
    assert temp_files(target.parent) == []


def test_csv_bad_row_keeps_previous_file(tmp_path):
    target = tmp_path / "table.csv"
    save_csv(target, ["a", "b"], [(1, 2)])
    before = target.read_bytes()
    with pytest.raises(ValueError, match="row 2 .* has 1 fields, header has 2"):
        save_csv(target, ["a", "b"], [(3, 4), (5,)])
    assert target.read_bytes() == before
    assert temp_files(tmp_path) == []


# --------------------------------------------------------------------------
# Provenance robustness
# --------------------------------------------------------------------------


@pytest.fixture
def fresh_versions():
    library_versions.cache_clear()
    yield
    library_versions.cache_clear()


def test_git_revision_in_this_repo():
    rev = git_revision()
    assert re.fullmatch(r"[0-9a-f]{40}(-dirty)?", rev), rev


def test_git_unavailable_gives_unknown(tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))  # no git executable here
    assert git_revision() == "unknown"
    assert provenance("k", CFG)["git_revision"] == "unknown"


def test_not_a_git_checkout_gives_unknown(tmp_path, monkeypatch):
    monkeypatch.setattr(provenance_module, "_REPO_ROOT", tmp_path)
    monkeypatch.setenv("GIT_CEILING_DIRECTORIES", str(tmp_path.parent))
    assert git_revision() == "unknown"


def test_missing_library_recorded_as_not_installed(monkeypatch, fresh_versions):
    # A None entry in sys.modules makes the import raise ImportError.
    monkeypatch.setitem(sys.modules, "scipy", None)
    monkeypatch.setitem(sys.modules, "slepc4py", None)
    monkeypatch.setitem(sys.modules, "slepc4py.SLEPc", None)
    versions = provenance("k", CFG)["versions"]
    assert versions["scipy"] == "not installed"
    assert versions["slepc4py"] == "not installed"
    assert versions["SLEPc"] == "not installed"
    assert versions["numpy"] == np.__version__


def test_heavy_libraries_not_imported_at_module_import():
    code = (
        "import sys, pipeline.store.artifacts, pipeline.config.loader\n"
        "heavy = {'dolfinx', 'petsc4py', 'slepc4py', 'gmsh', 'numba', 'scipy'}\n"
        "print(sorted(heavy & set(sys.modules)))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=REPO_ROOT, capture_output=True, text=True, check=True,
        env={**os.environ, "PYTHONPATH": str(REPO_ROOT)},
    ).stdout
    assert out.strip() == "[]"
