"""Validation of issue 27's pass-by and exports: writes docs/validation/76_passby_exports.md (a writer, run
by `make validate`: `.venv/bin/python -m pipeline.validation.writers.passby_exports`).  The limits it
states are asserted by tests/report/test_passby.py (the closed forms, IEC 61672-1 Table 4) and
tests/report/test_exports.py (the LW_RAILWAY read-back)."""
from __future__ import annotations

import csv

import numpy as np

from pipeline.store import paths
from postprocess.listening.listener import Geometry
from postprocess.listening.passby import Train, exposure_dipole, exposure_monopole, f_weighted, passby_signal

from pipeline.validation.make import make_targets
from pipeline.validation.writers import save_fragment

TABLE4_F = ((1000, 0.0), (500, -0.1), (200, -1.0), (100, -2.6), (50, -4.8), (20, -8.3), (10, -11.1), (5, -14.1),
            (2, -18.0), (1, -21.0), (0.5, -24.0), (0.25, -27.0))  # IEC 61672-1:2013 Table 4, F, ms -> dB


def passby_rows():
    rows = []
    for kmh in (50.0, 80.0, 120.0):
        v = kmh / 3.6
        for kind in ("omni", "dipole"):
            geo = Geometry(distance=6.75, h_source=0.59, h_receiver=1.4, ground="none", directivity=kind, air=False)
            _, p = passby_signal([434.7], [0.05], Train(1, 0.0, v, 40.0), geo, 44100.0, weighted=False)
            d = np.hypot(6.75, 0.81)
            ref = exposure_monopole(0.05, d, v, 40.0) if kind == "omni" else exposure_dipole(0.05, d, 6.75, v, 40.0)
            rows.append((kmh, kind, 10 * np.log10(np.sum(p**2) / 44100.0 / ref)))
    return rows


def burst_rows():
    fs, out = 192000.0, []
    for ms, table in TABLE4_F:
        n = int(round(ms * 1e-3 * fs))
        t = np.arange(int(0.5 * fs) + n) / fs
        x = np.where(t < n / fs, np.sin(2 * np.pi * 4000 * t), 0.0)
        out.append((ms, table, 10 * np.log10(f_weighted(x**2, fs).max() / 0.5)))
    return out


def export_deviation():
    make_targets("radiate", CASE="default")          # the exports are the radiate stage's
    d = paths.case_dir("default")
    with open(d / "lw_railway.csv", newline="") as fh:
        r = list(csv.reader(fh))
    row = dict(zip(r[0], r[1]))
    with open(d / "radiate_bands.csv", newline="") as fh:
        bands = {round(float(x[0])): float(x[4]) for x in list(csv.reader(fh))[1:]}
    dev = [abs(float(row[f"HZD{f}"]) - 10 * np.log10(3) - 10 * np.log10(1 / 5e4) - bands[f])
           for f in (50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000, 1250, 1600, 2000, 2500, 3150,
                     4000, 5000, 6300, 8000, 10000) if float(row[f"HZD{f}"]) > -99]
    return max(dev), len(dev)


def write() -> str:
    pb, bu, ex = passby_rows(), burst_rows(), export_deviation()
    text = ["## Pass-by and exports (issue 27)", "",
            "Written by `pipeline/validation/writers/passby_exports.py` (`make validate`); `tests/report/test_passby.py` "
            "and `tests/report/test_exports.py` assert its limits. Code: `postprocess/listening/passby.py`, `pipeline/stages/passby.py`, "
            "`postprocess/exports.py`, `pipeline/stages/listen_exports.py`.", "",
            "### A steady tone passing at constant speed",
            "",
            "One source of 0.05 W at 434.7 Hz on a straight track, the receiver 6.75 m from it horizontally and 0.81 m "
            "higher (the default receiver: d = 6.80 m), free field, no air absorption, synthesized at the exact emission "
            "times (Doppler included), summed over |x| <= 40 m, against the closed forms "
            "int p^2 dt = rho c0 W / (4 pi) 2 arctan(u) / (v d) (monopole) and rho c0 W / (4 pi) 3 y^2 (u / (1 + u^2) + "
            "arctan u) / (v d^3) (dipole along the axle), u = 40 m / d:", "",
            "| speed (km/h) | source | synthesized - closed form (dB) |", "|---:|---|---:|"]
    text += [f"| {k:.0f} | {s} | {x:+.4f} |" for k, s, x in pb]
    text += ["", f"Largest deviation **{max(abs(x) for *_, x in pb):.4f} dB** (the issue asks 0.5 dB); what remains is "
             "the O(M) Jacobian dt/dt_e = 1 - M cos alpha at the window's unequal ends.", "",
             "### Time weighting F (IEC 61672-1)", "",
             "4 kHz tone bursts of duration T_b (sampled at 192 kHz) through the F weighting's recursion, the maximum "
             "relative to the steady tone, against the standard's Table 4 (reference responses, rounded to 0.1 dB):", "",
             "| T_b (ms) | Table 4 (dB) | computed (dB) |", "|---:|---:|---:|"]
    text += [f"| {ms:g} | {t:+.1f} | {c:+.3f} |" for ms, t, c in bu]
    text += ["", f"Largest deviation **{max(abs(t - c) for _, t, c in bu):.3f} dB**.", ""]
    text += ["### NoiseModelling's LW_RAILWAY row of the default case", ""]
    text += [f"Read back into the sound power bands it came from (minus the dipole's 10 lg 3 and CNOSSOS-EU's "
             f"10 lg(Q / 1000 v) for one passage an hour at 50 km/h): {ex[1]} bands above the -99 dB floor, largest "
             f"deviation **{ex[0]:.2e} dB** (the issue asks 0.01 dB).", ""]
    return save_fragment("76_passby_exports.md", "\n".join(text))


if __name__ == "__main__":
    write()
