"""The early-stop rule of the time loop (SPEC 6: never beyond 8 s; stop at a limit cycle or when
the motion has decayed): the rule's settings, its per-window statistics and its decision, in
numba (called from both drivers at the end of every step)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numba
import numpy as np

STOP_REASONS = {0: "duration", 1: "limit cycle", 2: "decayed"}


@dataclass(frozen=True)
class StopRule:
    """Early stop (checked at the end of every window of ``window`` s):

    * 'decayed': the rms of the F2 and F3 deviations from their window means are both below
      ``decay_tol`` * preload and the rms of F2 has fallen from window to window over the last
      ones: the motion has died out to a constant force (a mode growing from far below that
      level, slower than the others decay, would be missed: the kick sets the start level);
    * 'limit cycle': over the last ceil(final / window) windows (at least ``min_windows``; they
      cover the full-rate final stretch) the rms of F2 (mean removed) and its zero-crossing
      frequency differ from the last window's by less than ``rms_tol`` and ``freq_tol``;
    * never before ``min_time`` (default: the final stretch plus one window)."""
    window: float = 0.25
    rms_tol: float = 0.03
    freq_tol: float = 0.03
    decay_tol: float = 1e-6
    min_windows: int = 3
    min_time: float | None = None


class Windows(NamedTuple):
    """The stop rule as the loop applies it.  Settings (read only): nw steps per window, need
    windows compared, min_steps before any stop, rms_tol, f_tol (relative), decay_abs [N].
    Buffers the loop WRITES in place: wbuf (nw, 2) the current window's (F2, F3); stats
    (n_windows, 5) per closed window: t_end, mean F2, rms F2, zero-crossing frequency of F2, rms F3."""
    nw: int
    need: int
    min_steps: int
    rms_tol: float
    f_tol: float
    decay_abs: float
    wbuf: np.ndarray
    stats: np.ndarray


def windows(stop: StopRule | None, n_steps: int, dt: float, final: float, preload: float) -> Windows:
    """Fresh buffers and the settings of ``stop`` for a run of n_steps steps of dt [s] with a
    full-rate final stretch of ``final`` s; stop None: window statistics only, never a stop."""
    rule = stop if stop is not None else StopRule()
    nw = max(1, int(round(rule.window / dt)))
    need = max(rule.min_windows, int(math.ceil(final / rule.window - 1e-9)) if final else 0)
    min_time = rule.min_time if rule.min_time is not None else final + rule.window
    min_steps = int(round(min_time / dt)) if stop is not None else n_steps + 1
    return Windows(nw, need, min_steps, float(rule.rms_tol), float(rule.freq_tol), float(rule.decay_tol * preload),
                   np.zeros((max(nw, 1), 2)), np.zeros((n_steps // nw if nw else 0, 5)))


@numba.njit(cache=True)
def _end_window(iw, wbuf, nw, dt, t_end, win_stats):
    """Statistics of one window of nw steps: t_end, mean F2, rms F2, zero-crossing frequency of
    F2 - mean, rms F3 (means removed)."""
    m2 = 0.0
    m3 = 0.0
    for j in range(nw):
        m2 += wbuf[j, 0]
        m3 += wbuf[j, 1]
    m2 /= nw
    m3 /= nw
    v2 = 0.0
    v3 = 0.0
    cross = 0
    prev = wbuf[0, 0] - m2
    for j in range(nw):
        a = wbuf[j, 0] - m2
        v2 += a * a
        v3 += (wbuf[j, 1] - m3) ** 2
        if (a > 0.0) != (prev > 0.0):
            cross += 1
        prev = a
    win_stats[iw, 0] = t_end
    win_stats[iw, 1] = m2
    win_stats[iw, 2] = math.sqrt(v2 / nw)
    win_stats[iw, 3] = cross / (2.0 * nw * dt)
    win_stats[iw, 4] = math.sqrt(v3 / nw)


@numba.njit(cache=True)
def _stop_decision(iw, win_stats, need, rms_tol, f_tol, decay_abs):
    """0: go on, 1: limit cycle, 2: decayed (see StopRule)."""
    if iw + 1 < need:
        return 0
    if win_stats[iw, 2] <= decay_abs and win_stats[iw, 4] <= decay_abs:
        for j in range(iw - need + 2, iw + 1):         # and still falling: nothing growing underneath
            if win_stats[j, 2] >= win_stats[j - 1, 2] and win_stats[j, 2] > 1e-6 * decay_abs:
                return 0                                # (1e-6 decay_abs: the rounding floor)
        return 2
    r = win_stats[iw, 2]
    f = win_stats[iw, 3]
    if f <= 0.0:
        return 0
    for j in range(iw - need + 1, iw):
        if abs(win_stats[j, 2] - r) > rms_tol * r or abs(win_stats[j, 3] - f) > f_tol * f:
            return 0
    return 1


@numba.njit(cache=True)
def record_window(F2, F3, done, dt, win, jw, iw):
    """Store (F2, F3) of step ``done`` - 1 in the window buffer (``win``: Windows); at a full
    window, close it and decide whether to stop.  Returns (jw, iw, reason), reason 0 = go on."""
    wbuf = win.wbuf
    wbuf[jw, 0] = F2
    wbuf[jw, 1] = F3
    jw += 1
    reason = 0
    if jw == win.nw:
        jw = 0
        if iw < win.stats.shape[0]:
            _end_window(iw, wbuf, win.nw, dt, done * dt, win.stats)
            if done >= win.min_steps:
                reason = _stop_decision(iw, win.stats, win.need, win.rms_tol, win.f_tol, win.decay_abs)
            iw += 1
    return jw, iw, reason
