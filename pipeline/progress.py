"""Progress bars: one helper for every stage and study.

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
    from tqdm import tqdm

    return tqdm(iterable, disable=None if enabled else True, dynamic_ncols=True, **kwargs)
