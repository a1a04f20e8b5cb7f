"""The radiate stage (pipeline/stages/radiate.py) on the real C20 modes and a
synthetic simulation artifact in a private build folder: artifacts and keys,
the sound peak at the driven mode, the flag of SPEC 6, staleness and
atomicity.  Needs build/wheels/c20/modes.npz (tests/conftest.py builds it) and
build/rails/bv50/rail.npz (the simulate artifact's configuration names its hash)."""
import csv
import shutil

import numpy as np
import pytest

from pipeline.store import artifacts, paths
from pipeline.stages import radiate as RS
from solvers.constants import F_MAX_HZ
from pipeline.validation.references import node_average as NA

ROOT = paths.ROOT
REAL = ROOT / "build"
pytestmark = pytest.mark.skipif(not (REAL / "rails" / "bv50" / "rail.npz").exists(),
                                reason="needs build/rails/bv50/rail.npz (make rail)")
DT = 36e-6
N = 13889
WRITE_ARRAY = np.lib.format.write_array


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    b = tmp_path_factory.mktemp("build")
    for sub in ("wheels/c20/modes.npz", "rails/bv50/rail.npz"):
        (b / sub).parent.mkdir(parents=True)
        (b / sub).symlink_to(REAL / sub)
    return b


_RAIL_CACHE: dict = {}
_load_npz = artifacts.load_npz


def _cached_load_npz(path, kind, config=None, **kw):
    """artifacts.load_npz, reading the 58 MB rail artifact once (only its hash is needed here)."""
    if kind != "rail":
        return _load_npz(path, kind, config, **kw)
    from pipeline.config.loader import config_hash

    key = (str(path), config_hash(config) if config is not None else None)
    if key not in _RAIL_CACHE:
        _RAIL_CACHE[key] = _load_npz(path, kind, config, **kw)
    return _RAIL_CACHE[key]


@pytest.fixture
def tmp_build(build, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(build))
    monkeypatch.setattr(artifacts, "load_npz", _cached_load_npz)
    return build


def no_plot(a, path, case):
    with artifacts.atomic_write(path) as tmp:
        tmp.write_bytes(b"png")


@pytest.fixture(scope="module")
def model(build):
    mp = pytest.MonkeyPatch()
    mp.setenv("SQUEAL_BUILD_DIR", str(build))
    try:
        yield RS.load_radiation_model("default")
    finally:
        mp.undo()


def squeal_forces(f0, a2=1500.0, a3=600.0):
    """A limit-cycle-like history: a tone 2 Hz below a wheel mode (the coupled frequency) and its harmonics."""
    t = np.arange(N) * DT
    F2 = -3e3 + a2 * np.cos(2 * np.pi * f0 * t) + 0.1 * a2 * np.cos(4 * np.pi * f0 * t + 0.4)
    F3 = 65e3 + a3 * np.cos(2 * np.pi * f0 * t + 1.2)
    return t, np.column_stack([np.zeros(N), F2, F3])


def write_simulate(t, F, case="default"):
    from pipeline.stages.simulate import simulate_config
    from solvers.timeloop.interaction import squeal_measures

    m = squeal_measures(F[:, 1], DT)
    artifacts.save_npz(paths.case_dir(case) / "simulate.npz", "simulate", simulate_config(case)[-1], t_final=t,
                       F_final=F, L_F2=np.float64(m["L_F2"]), f_dominant=np.float64(m["f_dominant"]),
                       stop_reason=np.array("limit cycle"))
    return m


def mode(model, n, m, cls="a"):
    return int(np.flatnonzero((model.n == n) & (model.m == m) & (model.cls == cls))[0])


def test_model_is_the_simulations_wheel(model):
    # the Gram-matrix form equals the node averages of radiation.sound_power on the real C20, with the
    # contact point as an extra node carrying the interpolated shapes
    modes = model.meta["modes"]
    extra = np.stack([model.phi[:, 1], model.phi[:, 0], np.zeros(model.f_r.size)], axis=1)[:, None, :]
    md = dict(modes, shapes=np.concatenate([modes["shapes"], extra], axis=1))
    f = np.array([150.0, 437.0, 1000.0, 1153.0, 3100.0, 6200.0])
    from solvers.radiation.force_power import harmonic_power

    rng = np.random.default_rng(0)
    F2, F3 = rng.standard_normal(6) + 1j * rng.standard_normal(6), rng.standard_normal(6)
    ref = NA.sound_power(f, F2, F3, md, model.meta["surfaces"], model.meta["nodes"], md["shapes"].shape[1] - 1,
                        zeta=model.zeta)
    np.testing.assert_allclose(harmonic_power(model, f, F2, F3), ref.W_n, rtol=1e-9, atol=1e-12 * ref.W.max())
    # contact point and damping as in the Green's functions stage (when that artifact is of this wheel)
    g = REAL / "cases" / "default" / "greens.npz"
    if g.exists():
        gr, gp = artifacts.load_npz(g, "greens")
        if gp["config"]["wheel_modes"] == model.meta["modes_hash"]:
            np.testing.assert_allclose(model.phi, gr["wheel_phi"], rtol=1e-12)
            np.testing.assert_allclose(model.zeta, gr["wheel_zeta"], rtol=1e-12)
    assert abs(model.meta["contact"].Z - modes["points"][model.meta["contact_node"], 1]) < 2e-3


def test_run_radiate_artifacts(tmp_build, model):
    i3 = mode(model, 3, 0)
    f0 = model.f_r[i3] - 2.0
    t, F = squeal_forces(f0)
    meas = write_simulate(t, F)
    a = RS.run_radiate("default")
    out = paths.case_dir("default")
    npz, prov = artifacts.load_npz(out / "radiate.npz", "radiate", RS.radiate_config("default", model)[1])
    for k in ("f", "W", "W_n", "L_W", "f_sound", "harmonic_L_W", "tone_f", "tone_F2", "tone_F3", "force_f",
              "F2_spectrum", "F3_spectrum", "unit_f", "unit_W_lateral", "unit_W_radial", "meaningful"):
        assert k in npz, k
    # the peak is the tone at the (3,0,a) mode, and the flag follows L_F2 >= 10 dB
    assert float(npz["f_sound"]) == pytest.approx(f0, rel=1e-7)
    assert str(npz["sound_mode_label"]) == "(3,0,a)" and int(npz["sound_mode"]) == i3
    assert bool(npz["meaningful"]) and float(npz["L_F2"]) == pytest.approx(meas["L_F2"])
    np.testing.assert_allclose(np.sort(npz["tone_f"]), [f0, 2 * f0], rtol=1e-7)
    assert float(npz["L_W"]) == pytest.approx(10 * np.log10(npz["W"].sum() / 1e-12), abs=1e-9)
    # the harmonic n = 3 carries almost everything
    h3 = int(np.flatnonzero(npz["harmonics"] == 3)[0])
    assert npz["harmonic_W"][h3] / npz["W_total"] > 0.9
    with open(out / "radiate_harmonics.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [int(r["n"]) for r in rows] == npz["harmonics"].tolist()
    assert sum(float(r["share"]) for r in rows) == pytest.approx(1.0)
    assert 10 * np.log10(sum(float(r["W_W"]) for r in rows) / 1e-12) == pytest.approx(float(npz["L_W"]), abs=1e-9)
    assert rows[h3]["mode"] == "(3,0,a)"
    assert (out / "radiate.png").stat().st_size > 10_000
    # unit-force curves: W per N^2 at the contact point, loudest at an axial mode with no nodal circle
    k = int(np.argmax(npz["unit_W_lateral"]))
    j = int(np.argmin(np.abs(model.f_r - npz["unit_f"][k])))
    assert abs(model.f_r[j] - npz["unit_f"][k]) < 1e-6 * model.f_r[j] and model.cls[j] == "a" and model.m[j] == 0
    assert np.all(npz["unit_W_radial"] > 0) and npz["unit_f"][0] == 100.0 and npz["unit_f"][-1] == F_MAX_HZ
    assert a["L_W"] == npz["L_W"]


def test_quiet_case_is_computed_and_flagged(tmp_build, model):
    t, F = squeal_forces(model.f_r[mode(model, 2, 0)] - 1.0, a2=1.0, a3=0.5)  # 1 N: L_F2 = -3 dB
    write_simulate(t, F)
    a, _, _ = RS.compute_radiation("default", model)
    assert not bool(a["meaningful"]) and np.isfinite(a["L_W"]) and str(a["sound_mode_label"]) == "(2,0,a)"


def test_stale_simulation_and_stale_radiate(tmp_build, model, tmp_path, monkeypatch):
    monkeypatch.setattr(RS, "plot_radiation", no_plot)
    t, F = squeal_forces(1000.0)
    write_simulate(t, F)
    RS.run_radiate("default")
    cases = tmp_path / "cases"
    cases.mkdir()
    text = (ROOT / "pipeline" / "cases" / "default.toml").read_text()
    (cases / "default.toml").write_text(text.replace("mu = 0.35", "mu = 0.30"))
    monkeypatch.setenv("SQUEAL_CASE_DIR", str(cases))
    with pytest.raises(artifacts.ArtifactError, match=r"simulate\.npz: stale artifact.*friction\.mu.*make simulate"):
        RS.compute_radiation("default", model)
    with pytest.raises(artifacts.ArtifactError, match=r"radiate\.npz: stale"):
        artifacts.load_npz(paths.case_dir("default") / "radiate.npz", "radiate", RS.radiate_config("default", model)[1])


def test_failed_run_leaves_the_previous_artifact(tmp_build, model, monkeypatch):
    monkeypatch.setattr(RS, "plot_radiation", no_plot)
    t, F = squeal_forces(1500.0)
    write_simulate(t, F)
    RS.run_radiate("default")
    out = paths.case_dir("default")
    before = (out / "radiate.npz").read_bytes()
    write_simulate(t, 2 * F)

    def boom(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(np.lib.format, "write_array", boom)  # dies inside save_npz's zip writing
    with pytest.raises(KeyboardInterrupt):
        RS.run_radiate("default")
    monkeypatch.setattr(np.lib.format, "write_array", WRITE_ARRAY)
    assert (out / "radiate.npz").read_bytes() == before
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporary files left
    shutil.rmtree(out)
