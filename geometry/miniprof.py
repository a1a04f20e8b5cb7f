"""Readers for measured profiles in the formats railway engineers exchange,
converted to the profile convention of ``geometry.profiles``.

Supported (text only; pure: text in, arrays out):

* MiniProf ".ban" (rail) / ".whl" (wheel) ASCII exports, the regular
  variant: a header block of ``Keyword=Value`` lines (e.g. ``ColumnDef=X,Y``,
  ``Date=...``), then, after the first empty line, one point per line with
  the columns that ColumnDef names (default X,Y), separated by blanks or
  commas; text after ``"``, ``!`` or ``%`` is a comment.  X is lateral, Y
  vertical, both in mm.  This follows the description of the format in the
  CONTACT package (Vtech CMCC, ``matlab/read_miniprof.m``).  Not supported:
  the old "MINIPROF" header variant and multi-part ``.mpt`` files with
  ``[FileInfo]`` sections (a clear error says so).
* Plain CSV: two columns y, z per line (comma, semicolon, tab or blanks), an
  optional non-numeric column-name line, ``#`` comments.

The measuring device's orientation varies (left/right side, z up or down);
``to_convention`` mirrors and shifts explicitly and checks the result.
"""
from __future__ import annotations

import numpy as np

from geometry.profiles import ProfileError


def parse_miniprof(text: str, source: str) -> tuple[dict, np.ndarray, np.ndarray, np.ndarray]:
    """(header {key: value}, X, Y, line numbers) of a MiniProf .ban/.whl text."""
    lines = text.splitlines()
    head = "\n".join(lines[:3])
    if "[FileInfo]" in head:
        raise ProfileError(source, 1, "multi-part MiniProf file (.mpt, [FileInfo] sections) is not supported; "
                           "export the profile as a regular .ban/.whl file")
    if "MINIPROF" in head:
        raise ProfileError(source, 1, "old-style MiniProf file ('MINIPROF' header) is not supported; "
                           "export it as a regular .ban/.whl file")
    header: dict[str, str] = {}
    rows, where = [], []
    in_data = False
    for k, raw in enumerate(lines, start=1):
        s = raw
        for mark in ('"', "!", "%"):
            s = s.split(mark, 1)[0]
        s = s.strip()
        if not s:
            in_data = in_data or bool(header)
            continue
        if "=" in s and not in_data:
            key, _, val = s.partition("=")
            header[key.strip()] = val.strip()
            continue
        parts = s.replace(",", " ").split()
        try:
            rows.append([float(v) for v in parts])
        except ValueError:
            raise ProfileError(source, k, f"expected numbers (columns {header.get('ColumnDef', 'X,Y')}), "
                               f"got {s[:60]!r}") from None
        where.append(k)
    cols = [c.strip().upper() for c in header.get("ColumnDef", "X,Y").split(",")]
    if "X" not in cols or "Y" not in cols:
        raise ProfileError(source, None, f"ColumnDef={header.get('ColumnDef')!r} names no X and Y columns")
    ix, iy = cols.index("X"), cols.index("Y")
    for row, k in zip(rows, where):
        if len(row) <= max(ix, iy):
            raise ProfileError(source, k, f"{len(row)} columns, ColumnDef {','.join(cols)} needs {max(ix, iy) + 1}")
    X = np.array([r[ix] for r in rows])
    Y = np.array([r[iy] for r in rows])
    return header, X, Y, np.array(where, dtype=int)


def parse_plain(text: str, source: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(y, z, line numbers) of a two-column text file."""
    ys, zs, where = [], [], []
    for k, raw in enumerate(text.splitlines(), start=1):
        s = raw.split("#", 1)[0].strip()
        if not s:
            continue
        parts = [p for p in s.replace(";", " ").replace(",", " ").replace("\t", " ").split() if p]
        try:
            vals = [float(v) for v in parts]
        except ValueError:
            if not ys:
                continue  # a column-name line
            raise ProfileError(source, k, f"expected two numbers 'y, z', got {s[:60]!r}") from None
        if len(vals) != 2:
            raise ProfileError(source, k, f"expected two numbers 'y, z', got {len(vals)} values")
        ys.append(vals[0])
        zs.append(vals[1])
        where.append(k)
    return np.array(ys), np.array(zs), np.array(where, dtype=int)


def to_convention(y, z, lines, kind: str, source: str, mirror_y: bool = False, flip_z: bool = False,
                  y0: float = 0.0, z0: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Measured (y, z) in mm -> the profile convention (y + toward the field
    side from the rolling circle / rail centre, wheel z = r - r0, rail z up
    from the crown top), sorted by y.

    mirror_y: y -> -y (a profile measured on the other side); flip_z: z -> -z
    (z measured downward); y0: the file's y of the rolling circle (wheel) or
    rail centre line, after mirroring; z0: the file's z of the datum (default:
    the wheel's z at y0, the rail's highest point).  For a wheel the flange
    (highest point) must come out at the gauge (low-y) end."""
    y, z, lines = np.asarray(y, float), np.asarray(z, float), np.asarray(lines)
    if mirror_y:
        y = -y
    if flip_z:
        z = -z
    order = np.argsort(y, kind="stable")
    if not (np.all(order == np.arange(len(y))) or np.all(order == np.arange(len(y))[::-1])):
        k = int(np.flatnonzero(np.diff(y) * np.sign(y[-1] - y[0]) <= 0)[0]) + 1
        raise ProfileError(source, int(lines[k]), f"y = {y[k]:g} does not continue the monotonic run of the previous "
                           f"points (line {lines[k - 1]}: y = {y[k - 1]:g}); the profile must be single-valued in y")
    y, z, lines = y[order] - y0, z[order], lines[order]
    if z0 is None:
        z0 = float(np.interp(0.0, y, z)) if kind == "wheel" else float(z.max())
    z = z - z0
    if kind == "wheel" and len(z) > 2 and np.argmax(z) > len(z) // 2:
        raise ProfileError(source, int(lines[np.argmax(z)]), "the flange (highest z) is at the field-side end: "
                           "mirror the profile (mirror_y) or flip z (flip_z) if z was measured downward")
    return y, z, lines
