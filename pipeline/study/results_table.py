"""Append-only results table of a study (CSV, one row per finished case).

A study is interrupted at any moment (Ctrl-C, kill -9, a lost machine) and
resumed later, so the table is written row by row:

* every row is one complete line, appended with a single ``write`` on a file
  opened with ``O_APPEND``, then flushed and ``fsync``-ed, before the case
  counts as done;
* a kill in the middle of a write can leave a torn last line (no newline,
  or fewer fields): :meth:`ResultsTable.open` drops it (the file is rewritten
  atomically without it) and the case runs again;
* rows carry a ``key`` (stable name of the case) and an ``inputs`` hash (the
  case artifacts and settings it was computed from): a row whose hash is no
  longer the study's is stale and dropped on open too, and a key is never
  stored twice.

Values are written with ``repr`` precision (floats round-trip exactly), read
back by the column types given to the table.
"""
from __future__ import annotations

import csv
import io
import logging
import math
import os
from pathlib import Path
from typing import Any, Collection, Iterable, Mapping

from pipeline.store.artifacts import ArtifactError, atomic_write

log = logging.getLogger("pipeline.study")

KEY, INPUTS = "key", "inputs"
_PARSE = {float: float, int: int, str: str}


def _fmt(value: Any) -> str:
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)                         # round-trips exactly; 'nan', 'inf', '-inf' too
    if value is None:
        return ""
    if hasattr(value, "item"):                     # numpy scalar
        return _fmt(value.item())
    return str(value)


def _parse(kind: type, text: str) -> Any:
    if kind is str:
        return text
    if text == "":
        return math.nan if kind is float else None
    return _PARSE[kind](text)


class ResultsTable:
    """The table at ``path`` with ``columns`` {name: float | int | str}; ``key`` and ``inputs``
    come first and are added when missing.  Use :meth:`open` before appending."""

    def __init__(self, path: str | os.PathLike, columns: Mapping[str, type]):
        self.path = Path(path)
        cols = {KEY: str, INPUTS: str}
        cols.update({k: v for k, v in columns.items() if k not in cols})
        self.columns = cols
        self.header = list(cols)
        self.rows: dict[str, dict] = {}

    # -- reading ---------------------------------------------------------------------------------
    def open(self, valid_inputs: Collection[str] | None = None) -> dict[str, dict]:
        """Load the finished rows, dropping a torn last line, malformed lines, rows whose inputs
        hash is not in ``valid_inputs`` (stale; None keeps all) and repeated keys (the first
        one stays).  Rewrites the file atomically when it dropped anything; a missing file is
        created with the header.  Returns {key: row}."""
        self.rows = {}
        if not self.path.exists():
            self._rewrite()
            return self.rows
        raw = self.path.read_bytes()
        lines = raw.split(b"\n")
        torn = lines.pop()                         # b"" after a final newline, else a torn line
        dropped = {"torn": int(bool(torn)), "malformed": 0, "stale": 0, "repeated": 0}
        if not lines:
            raise ArtifactError(self.path, "results table without a header line; delete it to start over")
        header = next(csv.reader([lines[0].decode("utf-8")]))
        if header != self.header:
            raise ArtifactError(self.path, f"results table with other columns ({header[:4]}...) than this study "
                                           f"({self.header[:4]}...); move it away to start over")
        for line in lines[1:]:
            try:
                fields = next(csv.reader([line.decode("utf-8")]))
                if len(fields) != len(self.header):
                    raise ValueError
                row = {k: _parse(t, v) for (k, t), v in zip(self.columns.items(), fields)}
            except (ValueError, UnicodeDecodeError, StopIteration):
                dropped["malformed"] += 1
                continue
            key = row[KEY]
            if valid_inputs is not None and row[INPUTS] not in valid_inputs:
                dropped["stale"] += 1
                continue
            if key in self.rows:
                dropped["repeated"] += 1
                continue
            self.rows[key] = row
        if any(dropped.values()):
            log.warning("%s: dropped %s; %d rows kept", self.path,
                        ", ".join(f"{n} {k}" for k, n in dropped.items() if n), len(self.rows))
            self._rewrite()
        return self.rows

    def _rewrite(self) -> None:
        with atomic_write(self.path) as tmp:
            tmp.write_text(self._lines([self.header] + [[_fmt(r[k]) for k in self.header] for r in self.rows.values()]))

    @staticmethod
    def _lines(rows: Iterable[Iterable[str]]) -> str:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        for r in rows:
            w.writerow(r)
        return buf.getvalue()

    # -- writing ---------------------------------------------------------------------------------
    def append(self, row: Mapping[str, Any]) -> None:
        """Append one complete row (all columns; unknown keys are an error) durably."""
        extra = set(row) - set(self.columns)
        if extra:
            raise KeyError(f"{self.path}: row has columns the table does not: {sorted(extra)}")
        key = str(row[KEY])
        if key in self.rows:
            raise KeyError(f"{self.path}: case {key!r} is already in the table")
        text = self._lines([[_fmt(row.get(k)) for k in self.header]]).encode("utf-8")
        fd = os.open(self.path, os.O_WRONLY | os.O_APPEND)
        try:
            done = os.write(fd, text)             # one write of the whole line (a regular file
            while done < len(text):               # takes it at once; loop for a short write)
                done += os.write(fd, text[done:])
            os.fsync(fd)
        finally:
            os.close(fd)
        self.rows[key] = {k: _parse(t, _fmt(row.get(k))) for k, t in self.columns.items()}

    def sorted_rows(self, keys: Iterable[str] | None = None) -> list[dict]:
        """The rows of ``keys`` (all, sorted by key, when None), in that order; missing keys are skipped."""
        keys = sorted(self.rows) if keys is None else keys
        return [self.rows[k] for k in keys if k in self.rows]
