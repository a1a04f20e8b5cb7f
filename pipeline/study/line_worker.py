"""One row of the line study on a Dask worker: the curve verdict screen first
(``pipeline.curve.screen_first``) of one curve, vehicle and friction condition -> one row of scalars.

The row reports the loudest squealing wheel of the leading bogie (by L_pA; the curve verdict's
``report.loudest``): its id, its squeal frequency and mode, L_pA at the case's listener (7.5 m, 1.2 m),
L_W and L_W per NoiseModelling 1/3-octave band (50 Hz - 10 kHz: ``postprocess.exports``, the radiate
stage's band sums), and which wheels the screen found unstable and the time loop ran for.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
import signal
import threading

import numpy as np

from pipeline.config.nouns import Curve
from postprocess.exports import NM_BANDS_HZ, band_power, level, nm_band_levels
from pipeline.store import paths
from pipeline.curve.verdict_report import loudest
from pipeline.curve.screen_first import run_screen_first
from pipeline.study.line_risk import EMPTY as NO_RISK, risk_columns
from pipeline.config.loader import ConfigError

NAN = float("nan")


@dataclass(frozen=True)
class LineContext:
    """What every row of a line runs with (scattered once to each worker): whether the mitigation
    what-ifs run and the squealing wheels' stages draw figures."""
    what_ifs: bool
    figures: bool = False


@dataclass(frozen=True)
class LineTask:
    """One row of the line: its Curve (built on the client, ``line_input.line_curves``) and the CSV
    row's values ((column, value) pairs)."""
    curve: Curve
    row: tuple


def band_columns() -> list[str]:
    return [f"L_W_{f}Hz" for f in NM_BANDS_HZ]


def band_levels(case: str) -> np.ndarray:
    """L_W (dB re 1 pW) per NoiseModelling band of a squealing wheel's radiate.npz."""
    with np.load(paths.case_dir(case) / "radiate.npz", allow_pickle=False) as a:
        f, W = np.asarray(a["f"], float), np.asarray(a["W"], float)
    bands, per, _ = band_power(f, W)
    return nm_band_levels(bands.nominal, level(per))


def summary_row(curve: str, rows: list[dict]) -> dict:
    """The line's row of one curve verdict (module notes)."""
    loud = loudest(rows)
    out = {"curve": curve, "squeals": loud is not None,
           "unstable_wheels": " ".join(r["wheel"] for r in rows if math.isfinite(r["screen_sigma"])),
           "time_loop_wheels": " ".join(r["wheel"] for r in rows if r.get("time_loop")),
           "squealing_wheels": " ".join(r["wheel"] for r in rows if r["squeals"]),
           "wheel": "", "f_squeal": NAN, "mode": "", "L_F2": NAN, "L_W": NAN, "L_pA": NAN,
           "aoa_mrad": 1e3 * max((abs(r["angle_of_attack"]) for r in rows), default=NAN)}
    bands = band_columns()
    out |= {b: NAN for b in bands}
    if loud is not None:
        out |= {"wheel": loud["wheel"], "f_squeal": float(loud["f_squeal"]), "mode": loud["mode"],
                "L_F2": float(loud["L_F2"]), "L_W": float(loud["L_W"]), "L_pA": float(loud["L_pA"])}
        out |= dict(zip(bands, map(float, band_levels(f"{curve}/{loud['wheel']}"))))
    return out


class _MainThreadSignal:
    """``signal`` as gmsh's module uses it, its handler changes made in the main thread only (elsewhere
    the handler is left as it is: gmsh sets SIGINT to its default while it runs, so that Ctrl-C stops it)."""

    def __getattr__(self, name):
        return getattr(signal, name)

    @staticmethod
    def signal(num, handler):
        if threading.current_thread() is threading.main_thread():
            return signal.signal(num, handler)
        return signal.getsignal(num)


def thread_safe_gmsh() -> None:
    """Let gmsh (Debian's 4.8 module) be imported, initialised and finalised in a worker's task thread:
    its module-level ``signal`` replaced by ``_MainThreadSignal`` (call in the main thread)."""
    import gmsh  # lazy: brings in gmsh

    gmsh.signal = _MainThreadSignal()


def prepare_worker() -> int:
    """Run on every worker in its main thread (``Client.run``) before the rows: ``thread_safe_gmsh``
    (the rows run in the worker's task thread; the greens stage meshes the rail section with gmsh)."""
    thread_safe_gmsh()
    return os.getpid()


def line_case(ctx: LineContext, t: LineTask) -> dict:
    """The worker's function (``pipeline.study.runner``): the curve's screen-first verdict, summarised."""
    try:
        res = run_screen_first(t.curve, what_ifs=ctx.what_ifs, figures=ctx.figures)
    except ConfigError as e:                           # no steady curving, or a wheel outside a case's range
        return dict(t.row) | summary_row(t.curve.name, []) | NO_RISK | {"note": " ".join(str(e).split())}
    risk = risk_columns(t.curve, res["rows"])          # onset, climate, rolling noise (issue 32: line_risk)
    return dict(t.row) | summary_row(t.curve.name, res["rows"]) | risk | {"note": ""}
