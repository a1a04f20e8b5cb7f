"""Progress bars (one helper for every stage and study) and durations as the logs print them.

A tqdm bar on an interactive terminal (rate, ETA); nothing at all when stderr
is not a terminal (Make logs, CI, Dask workers), so logs get no
carriage-return updates.  ``enabled=False`` silences it on a terminal too.
"""
from __future__ import annotations

from typing import Iterable


def progress(iterable: Iterable | None = None, *, enabled: bool = True, **kwargs):
    """``tqdm(iterable, **kwargs)`` drawn only when ``enabled`` and stderr is a
    terminal (tqdm's ``disable=None``); usable as an iterator or a context
    manager with ``update()``, as tqdm."""
    from tqdm import tqdm  # lazy: brings in tqdm

    return tqdm(iterable, disable=None if enabled else True, dynamic_ncols=True, **kwargs)


def seconds(t: float) -> str:
    """A duration for the log, 2 significant digits below 10 s ('0.047 s', '1.3 s', '42 s')."""
    return f"{t:.2g} s" if t < 10 else f"{t:.0f} s"


def loop_time(t_stage: float, t_loop: float, n_steps: int) -> str:
    """'in <stage> (time loop <loop>, <us> us/step)': the stage's wall time (loading, the loop, its figure,
    writing) and the time loop's own (``InteractionResult.wall``; numba, microseconds a step)."""
    return (f"in {seconds(t_stage)} (time loop {seconds(t_loop)}, {1e6 * t_loop / max(n_steps, 1):.2g} us/step)")
