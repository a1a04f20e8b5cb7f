"""Exports of a case's squeal in formats other tools read (written beside the stage's artifacts).

From the radiate stage (``radiation_tables``), in build/cases/<case>/:

* radiate_spectrum.csv: ``f_hz, W_W, L_W_dB, is_tone`` -- the sound power per entry (the tones at
  their fitted frequencies and the residual's bins; radiate.npz 'f', 'W');
* radiate_forces.csv: ``f_hz, F2_rms_N, F3_rms_N`` -- the contact forces' amplitude spectra (Hann,
  RMS scaling) over the final stretch, and radiate_tones.csv: ``f_hz, F2_rms_N, F3_rms_N,
  F2_phase_rad, F3_phase_rad, W_W`` -- the fitted tones;
* radiate_bands.csv: ``band_nominal_hz, band_lower_hz, band_upper_hz, W_W, L_W_dB`` -- the sound
  power per 1/3-octave band (IEC 61260-1), 10 Hz-20 kHz;
* lw_railway.csv: the squeal as one row of NoiseModelling's railway source table LW_RAILWAY
  (``postprocess/exports.py`` states the layout, the CNOSSOS-EU convention and the source height),
  for ONE squealing passage per hour in each period (D, E, N) at the case's speed: for Q passages an
  hour add 10 lg Q dB to every band column.

From the report (``write_vtk``), in build/report/<case>/vtk/ (ParaView: File > Open, then
"Warp By Vector"):

* wheel_modes.vtu: the wheel surface with one displacement array per mode
  (``mode_07_(2,0,a)_434Hz``: unit maximum, the mode's own normalisation);
* ods.pvd + ods/ods_NN.vtu: the squealing wheel's operating deflection shape at its dominant tone,
  16 frames over one period (a time series: press play), array ``displacement`` in m (peak).
"""
from __future__ import annotations

import numpy as np

from pipeline.store import artifacts, paths

CASE_FLOWS = {"D": 1.0, "E": 1.0, "N": 1.0}  # squealing passages per hour in lw_railway.csv


def radiation_tables(a: dict, out, speed_m_s: float) -> dict:
    """Write the radiate stage's CSV exports (module docstring) from radiate.npz's arrays ``a`` into
    the folder ``out``; returns {name: path}."""
    from postprocess.exports import band_power, level, lw_railway_columns, lw_railway_record, nm_band_levels  # here: Make's DEPS of the module's other entry points stay without it

    written = {}
    f, W = np.asarray(a["f"], float), np.asarray(a["W"], float)
    written["spectrum"] = artifacts.save_csv(out / "radiate_spectrum.csv", ["f_hz", "W_W", "L_W_dB", "is_tone"], (
        [float(x), float(w), float(lw), int(t)] for x, w, lw, t in zip(f, W, level(W), a["is_tone"])))
    written["forces"] = artifacts.save_csv(out / "radiate_forces.csv", ["f_hz", "F2_rms_N", "F3_rms_N"], (
        [float(x), float(abs(p)), float(abs(q))] for x, p, q in zip(a["force_f"], a["F2_spectrum"], a["F3_spectrum"])))
    tone = np.asarray(a["is_tone"], bool)
    written["tones"] = artifacts.save_csv(
        out / "radiate_tones.csv", ["f_hz", "F2_rms_N", "F3_rms_N", "F2_phase_rad", "F3_phase_rad", "W_W"],
        ([float(x), float(abs(p)), float(abs(q)), float(np.angle(p)), float(np.angle(q)), float(w)]
         for x, p, q, w in zip(a["tone_f"], a["tone_F2"], a["tone_F3"], W[tone])))
    bands, per, _ = band_power(f, W)
    L = level(per)
    written["bands"] = artifacts.save_csv(
        out / "radiate_bands.csv", ["band_nominal_hz", "band_lower_hz", "band_upper_hz", "W_W", "L_W_dB"],
        ([float(n), float(lo), float(hi), float(w), float(x)] for n, lo, hi, w, x in
         zip(bands.nominal, bands.lower, bands.upper, per, L)))
    row = lw_railway_record(nm_band_levels(bands.nominal, L), 3.6 * speed_m_s, CASE_FLOWS)
    cols = lw_railway_columns()
    written["lw_railway"] = artifacts.save_csv(out / "lw_railway.csv", cols, [[row[c] for c in cols]])
    return written


def _save_pvd(path, files: list[tuple[float, str]]) -> None:
    """A ParaView collection (time series) of the files {time: relative path}."""
    items = "\n".join(f'    <DataSet timestep="{t:.9g}" group="" part="0" file="{name}"/>' for t, name in files)
    text = ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f"  <Collection>\n{items}\n  </Collection>\n</VTKFile>\n")
    with artifacts.atomic_write(path) as tmp:
        tmp.write_text(text)


def _save_vtu(grid, path) -> None:
    # LZ4 (VTK's vtkLZ4DataCompressor, which ParaView reads): ~10x faster to write than zlib here
    with artifacts.atomic_write(path) as tmp:   # the temporary file keeps the .vtu suffix
        grid.save(str(tmp), binary=True, compression="lz4")


def write_vtk(case: str, model, rad: dict, out, n_phi: int = 48, n_frames: int = 16) -> dict:
    """The wheel's mode shapes and the squealing wheel's ODS as VTK files in ``out`` (module
    docstring); ``model``: the case's radiation model (``load_radiation_model``), ``rad``: its
    radiate.npz.  Returns {name: path}."""
    from postprocess.modes.vtk_export import mode_field, modal_amplitudes, ods_frames, wheel_surface  # lazy: brings in pyvista, scipy

    modes = model.meta["modes"]
    surf = wheel_surface(modes["points"], modes["cells"], n_phi)
    grid = surf.mesh.cast_to_unstructured_grid()
    grid.points = grid.points.astype(np.float32)
    out.mkdir(parents=True, exist_ok=True)
    for i in range(len(modes["f_hz"])):
        name = f"mode_{i:02d}_{model.label(i)}_{float(modes['f_hz'][i]):.0f}Hz"
        grid.point_data[name] = mode_field(surf, modes["shapes"][i], int(modes["n"][i])).astype(np.float32)
    written = {"modes": out / "wheel_modes.vtu"}
    _save_vtu(grid, written["modes"])
    if len(rad["tone_f"]):
        k = int(np.argmax(np.abs(rad["tone_F2"])))
        f0 = float(rad["tone_f"][k])
        q = modal_amplitudes(f0, complex(rad["tone_F2"][k]), complex(rad["tone_F3"][k]), model.f_r,
                             model.modal_mass, model.zeta, model.phi)
        th, frames = ods_frames(surf, modes["shapes"], modes["n"], q, n_frames)
        ods = surf.mesh.cast_to_unstructured_grid()
        ods.points = ods.points.astype(np.float32)
        (out / "ods").mkdir(exist_ok=True)
        files = []
        for j, (t, d) in enumerate(zip(th, frames)):
            ods.point_data.clear()
            ods.point_data["displacement"] = d.astype(np.float32)
            _save_vtu(ods, out / "ods" / f"ods_{j:02d}.vtu")
            files.append((float(t / (2 * np.pi * f0)), f"ods/ods_{j:02d}.vtu"))
        written["ods"] = out / "ods.pvd"
        _save_pvd(written["ods"], files)
    return written


def case_vtk(case: str, model, rad: dict) -> dict:
    """``write_vtk`` into build/report/<case>/vtk/."""
    return write_vtk(case, model, rad, paths.build() / "report" / case / "vtk")
