"""Exports (issue 27): the CSV spectra and bands, NoiseModelling's LW_RAILWAY row (its column layout
as NoiseModelling writes it, and read back into the band levels it came from within 0.01 dB), and
the VTK files of the mode shapes and the operating deflection shape (read back with VTK's own XML
reader through pyvista, as ParaView reads them)."""
from __future__ import annotations

import csv
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from pipeline.store import paths
from pipeline.stages.listen_exports import CASE_FLOWS, radiation_tables

# NoiseModelling (Universite-Gustave-Eiffel/NoiseModelling, EmissionTableGenerator.makeTrainLWTable with
# the prefix "HZ" of Railway_Emission_from_Traffic.groovy; the bands of ProfileBuilder
# .DEFAULT_FREQUENCIES_THIRD_OCTAVE), typed here from the source, not from postprocess/exports.py
NM_HEAD = ["PK_SECTION", "THE_GEOM", "DIR_ID", "GS"]
NM_FREQ = [50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000, 1250, 1600, 2000, 2500, 3150, 4000,
           5000, 6300, 8000, 10000]
V = 50 / 3.6


def synthetic_radiation():
    """Tones and residual bins of known power; the forces arbitrary."""
    rng = np.random.default_rng(1)
    f_bins = np.arange(1, 6501) * 2.0
    W_bins = 1e-9 * rng.random(f_bins.size)
    tone_f = np.array([434.7, 869.4, 1304.1])
    tone_W = np.array([0.05, 2e-4, 3e-5])
    f = np.concatenate([f_bins, tone_f])
    W = np.concatenate([W_bins, tone_W])
    o = np.argsort(f)
    F = np.linspace(0, 6500, 200)
    return {"f": f[o], "W": W[o], "is_tone": np.concatenate([np.zeros(f_bins.size, bool), np.ones(3, bool)])[o],
            "force_f": F, "F2_spectrum": np.exp(-F / 1e3 + 1j * F / 100), "F3_spectrum": 0.4 * np.exp(-F / 1e3 - 1j * F / 70),
            "tone_f": tone_f, "tone_F2": np.array([1500 + 20j, 150j, 10.0]),
            "tone_F3": np.array([600 - 5j, 60.0, 4j])}


def exact_band_levels(f, W, nominal):
    """L_W per base-10 1/3-octave band, edges f_m 10^(+-1/20), f_m = 1000 10^(k/10) (IEC 61260-1)."""
    out = []
    for fn in nominal:
        k = round(10 * np.log10(fn / 1000.0))
        fm = 1000.0 * 10 ** (k / 10)
        sel = (f >= fm * 10 ** (-1 / 20)) & (f < fm * 10 ** (1 / 20))
        out.append(10 * np.log10(W[sel].sum() / 1e-12) if W[sel].sum() > 0 else -np.inf)
    return np.array(out)


def read_csv(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def test_lw_railway_layout_and_read_back(tmp_path):
    a = synthetic_radiation()
    radiation_tables(a, tmp_path, V)
    head, rows = read_csv(tmp_path / "lw_railway.csv")
    assert head == NM_HEAD + [f"HZ{p}{f}" for p in "DEN" for f in NM_FREQ]
    assert len(rows) == 1
    row = dict(zip(head, rows[0]))
    assert row["DIR_ID"] == "1" and float(row["GS"]) == 1.0 and row["THE_GEOM"] == ""
    # the bands CSV against exact band sums
    bh, brows = read_csv(tmp_path / "radiate_bands.csv")
    nominal = np.array([float(r[0]) for r in brows])
    L_bands = np.array([float(r[4]) for r in brows])
    ok = np.isfinite(L_bands)
    np.testing.assert_allclose(L_bands[ok], exact_band_levels(a["f"], a["W"], nominal)[ok], atol=1e-9)
    # read back: minus the dipole's index 10 lg 3 and CNOSSOS-EU's 10 lg(Q / (1000 v)), v in km/h
    for p in "DEN":
        back = np.array([float(row[f"HZ{p}{f}"]) for f in NM_FREQ]) - 10 * np.log10(3) - 10 * np.log10(
            CASE_FLOWS[p] / (1000 * 50.0))
        src = np.array([L_bands[np.flatnonzero(np.isclose(nominal, f))[0]] for f in NM_FREQ])
        live = np.array([float(row[f"HZ{p}{f}"]) for f in NM_FREQ]) > -99
        assert live.sum() >= 20
        assert np.max(np.abs(back[live] - src[live])) < 0.01
        assert np.all(src[~live] - 10 * np.log10(3) - 10 * np.log10(1 / 5e4) < -99 + 1e-9) or not (~live).any()
    # the 400 Hz band holds the 434.7 Hz tone (0.05 W) and its share of the residual
    i400 = NM_FREQ.index(400)
    assert float(row["HZD400"]) == pytest.approx(10 * np.log10(0.05 / 1e-12) + 10 * np.log10(3) - 10 * np.log10(5e4),
                                                 abs=0.01)
    assert i400 == 9


def test_bands_are_the_listen_stages():
    """The radiate stage's own 1/3-octave bands (no pyfar: it runs before the listening packages are
    installed) equal the listen stage's (pyfar's IEC 61260-1 bands)."""
    pytest.importorskip("pyfar")
    from postprocess.exports import third_octaves
    from postprocess.listening.listener import third_octave_bands

    for lo, hi in ((10.0, 20000.0), (50.0, 10000.0), (44.0, 11000.0)):
        a, b = third_octaves(lo, hi), third_octave_bands(lo, hi)
        np.testing.assert_array_equal(a.nominal, b.nominal)
        for k in ("centre", "lower", "upper"):
            np.testing.assert_allclose(getattr(a, k), getattr(b, k), rtol=1e-12)


def test_radiate_exports_do_not_import_the_listening_packages():
    import subprocess
    import sys

    code = ("import sys; import pipeline.stages.listen_exports as E, postprocess.exports as P, numpy as np; "
            "P.band_power(np.array([434.7]), np.array([0.05])); assert 'pyfar' not in sys.modules")
    r = subprocess.run([sys.executable, "-c", code], cwd=paths.ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_spectra_csv_read_back(tmp_path):
    a = synthetic_radiation()
    radiation_tables(a, tmp_path, V)
    h, rows = read_csv(tmp_path / "radiate_spectrum.csv")
    assert h == ["f_hz", "W_W", "L_W_dB", "is_tone"]
    W = np.array([float(r[1]) for r in rows])
    np.testing.assert_array_equal(W, a["W"])
    assert sum(int(r[3]) for r in rows) == 3
    h, rows = read_csv(tmp_path / "radiate_tones.csv")
    np.testing.assert_allclose([float(r[1]) for r in rows], np.abs(a["tone_F2"]))
    np.testing.assert_allclose([float(r[5]) for r in rows], [0.05, 2e-4, 3e-5])
    h, rows = read_csv(tmp_path / "radiate_forces.csv")
    assert h == ["f_hz", "F2_rms_N", "F3_rms_N"] and len(rows) == 200
    # the complex spectra's magnitudes (their real parts once were written)
    np.testing.assert_allclose([float(r[1]) for r in rows], np.abs(a["F2_spectrum"]), rtol=1e-15)
    np.testing.assert_allclose([float(r[2]) for r in rows], np.abs(a["F3_spectrum"]), rtol=1e-15)


def test_default_case_export_matches_its_bands():
    d = paths.case_dir("default")
    if not (d / "lw_railway.csv").exists():
        pytest.skip("needs build/cases/default/lw_railway.csv (make radiate)")
    head, rows = read_csv(d / "lw_railway.csv")
    row = dict(zip(head, rows[0]))
    _, brows = read_csv(d / "radiate_bands.csv")
    L = {round(float(r[0])): float(r[4]) for r in brows}
    for f in NM_FREQ:
        v = float(row[f"HZD{f}"])
        if v > -99:
            assert abs(v - 10 * np.log10(3) - 10 * np.log10(1 / 5e4) - L[f]) < 0.01


@pytest.mark.skipif(not (paths.ROOT / "build" / "wheels" / "c20" / "modes.npz").exists(), reason="needs make modes")
def test_vtk_modes_and_ods_read_back(tmp_path):
    import pyvista as pv

    from pipeline.stages.listen_exports import write_vtk
    from pipeline.stages.radiate import load_radiation_model

    model = load_radiation_model("default")
    a = synthetic_radiation()
    k = 4  # a flexible mode's frequency plus a little: the ODS is dominated by it
    f0 = float(model.f_r[k]) + 0.3
    rad = {"tone_f": np.array([f0]), "tone_F2": np.array([100.0 + 0j]), "tone_F3": np.array([40.0 + 10j])}
    w = write_vtk("default", model, rad, tmp_path, n_phi=36, n_frames=8)
    g = pv.read(w["modes"])
    modes = model.meta["modes"]
    names = [n for n in g.point_data if n.startswith("mode_")]
    assert len(names) == len(modes["f_hz"])
    assert names[k] == f"mode_{k:02d}_{model.label(k)}_{modes['f_hz'][k]:.0f}Hz"
    # a mode's field on the surface: its section amplitudes swept with cos n phi, sin n phi: never more
    # than the section's largest |U| on the boundary, and at phi = 0 exactly (U_r, 0, U_z) of the node
    amp = np.linalg.norm(g.point_data[names[k]], axis=1)
    idx = g.point_data["rz_index"].astype(int)
    sec = np.linalg.norm(modes["shapes"][k][idx], axis=1)
    assert 0.2 < amp.max() <= sec.max() * (1 + 1e-6)
    at0 = np.abs(g.point_data["phi"]) < 1e-12
    np.testing.assert_allclose(g.point_data[names[k]][at0][:, [0, 2]], modes["shapes"][k][idx[at0]][:, [0, 1]],
                               atol=1e-6)
    tree = ET.parse(w["ods"])
    files = [d.get("file") for d in tree.getroot().iter("DataSet")]
    times = [float(d.get("timestep")) for d in tree.getroot().iter("DataSet")]
    assert len(files) == 8 and np.allclose(np.diff(times), 1 / (8 * f0))
    # the displacement at the contact node (phi = 0) over one period: peak sqrt(2) |sum_r q_r U_z,r|
    node = int(model.meta["contact"].node)
    phi = g.point_data["phi"]
    v0 = np.flatnonzero((g.point_data["rz_index"] == node) & (np.abs(phi) < 1e-12))
    assert v0.size == 1
    uz = np.array([pv.read(tmp_path / f).point_data["displacement"][v0[0], 2] for f in files])
    series = pv.get_reader(str(w["ods"]))          # the .pvd collection as ParaView opens it
    assert len(series.time_values) == 8 and series.time_values[1] == pytest.approx(times[1])
    W = 2 * np.pi * f0
    w_r = 2 * np.pi * model.f_r
    q = (model.phi[:, 0] * 100.0 + model.phi[:, 1] * (40.0 + 10j)) / (
        model.modal_mass * (w_r**2 - W**2 + 2j * model.zeta * w_r * W))
    expect = np.sqrt(2) * (q * modes["shapes"][:, node, 1]).sum()
    th = 2 * np.pi * np.arange(8) / 8
    np.testing.assert_allclose(uz, (expect * np.exp(1j * th)).real, rtol=2e-4, atol=1e-6 * abs(expect))
