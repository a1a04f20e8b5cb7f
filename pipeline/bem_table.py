"""The BEM check's record (issue 28): every solve's row in a CSV cache (build/studies/bem/wheel.csv and
convergence.csv), merged with each new run's rows so that a run adds modes instead of recomputing them,
and the fragment docs/validation/72_bem_wheel.md rendered from it.  When the cache is missing (a fresh
clone or build directory) it is seeded from the fragment's own tables, the record of earlier solves
(their values as printed: 0.1 dB, 0.01 dB in the convergence table).
"""
from __future__ import annotations

import csv
import math
from pathlib import Path

WHEEL_KEYS = ("mode", "f_hz", "force", "vertices", "solver", "L_W_simple", "L_W_bem_free", "L_W_bem_ground",
              "dL_free", "dL_ground", "wall_free_s", "wall_ground_s", "load")
CONV_KEYS = ("mode", "ds_max", "n_phi", "vertices", "solver", "dL_free", "wall_s", "load")
TEXT_KEYS = ("mode", "force", "solver", "load")
SOLVER_3D = "3-D"                 # solvers.bem.radiated_power: the whole mesh (image wheel for the ground)
SOLVER_REV = "revolution"         # solvers.bem_revolution: first block row per harmonic; ground by mirror symmetry

# fragment column headers -> CSV keys (a two-valued cell "a / b" fills two keys)
_WHEEL_COLS = {"mode": ("mode",), "f (Hz)": ("f_hz",), "force": ("force",), "vertices (wheel)": ("vertices",),
               "solver": ("solver",), "L_W simple (dB)": ("L_W_simple",), "BEM free": ("L_W_bem_free",),
               "BEM + ground": ("L_W_bem_ground",), "Delta free (dB)": ("dL_free",),
               "Delta ground (dB)": ("dL_ground",), "wall free / ground (s)": ("wall_free_s", "wall_ground_s"),
               "load": ("load",)}
_CONV_COLS = {"mode": ("mode",), "element size along the outline (mm)": ("ds_max",),
              "vertices around": ("n_phi",), "vertices": ("vertices",), "solver": ("solver",),
              "Delta free (dB)": ("dL_free",), "wall (s)": ("wall_s",), "load": ("load",)}


def _value(key: str, text: str):
    text = text.strip()
    if key in TEXT_KEYS:
        return text
    if text in ("", "-", "nan"):
        return math.nan
    return float(text)


def _complete(row: dict, keys, defaults: dict) -> dict:
    out = {k: row.get(k, defaults.get(k, math.nan)) for k in keys}
    for k in keys:
        v = out[k]
        if k in TEXT_KEYS:
            empty = v is None or v == "" or (isinstance(v, float) and math.isnan(v))
            out[k] = defaults.get(k, "") if empty else str(v)
        elif isinstance(v, str):
            out[k] = _value(k, v)
    return out


def _tables(text: str) -> list[list[list[str]]]:
    """The Markdown tables of ``text`` as lists of rows of cells (header first, separator dropped)."""
    tables, cur = [], []
    for line in text.splitlines() + [""]:
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not all(set(c) <= {"-", ":"} for c in cells):
                cur.append(cells)
        elif cur:
            tables.append(cur)
            cur = []
    return tables


def rows_from_fragment(text: str) -> tuple[list[dict], list[dict]]:
    """(wheel rows, convergence rows) printed in a fragment written by ``render`` (or its earlier form
    without the solver, load and mode columns: the 3-D solver, convergence of (2,0,a))."""
    wheel, conv = [], []
    for table in _tables(text):
        head = table[0]
        cols = _WHEEL_COLS if "BEM free" in head else _CONV_COLS if "vertices around" in head else None
        if cols is None:
            continue
        rows = []
        for cells in table[1:]:
            r = {}
            for h, c in zip(head, cells):
                keys = cols.get(h, ())
                parts = c.split(" / ") if len(keys) == 2 else [c]
                for k, v in zip(keys, parts):
                    r[k] = _value(k, v)
            if "ds_max" in r:
                r["ds_max"] = r["ds_max"] / 1e3
            rows.append(r)
        if cols is _WHEEL_COLS:
            wheel += [_complete(r, WHEEL_KEYS, {"solver": SOLVER_3D, "load": "4-10"}) for r in rows]
        else:
            conv += [_complete(r, CONV_KEYS, {"solver": SOLVER_3D, "mode": "(2,0,a)", "load": "4-10"}) for r in rows]
    return wheel, conv


def read_csv(path: Path, keys, defaults: dict) -> list[dict]:
    with open(path, newline="") as fh:
        return [_complete(r, keys, defaults) for r in csv.DictReader(fh)]


def write_csv(path: Path, rows: list[dict], keys) -> None:
    from .atomic import atomic_write

    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_write(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(keys))
        w.writeheader()
        w.writerows(rows)


def _finite(x) -> bool:
    return isinstance(x, float) and math.isfinite(x)


def merge_wheel(old: list[dict], new: list[dict]) -> list[dict]:
    """Rows of ``new`` replace those of ``old`` with the same mode, force and solver; a new row without a
    ground solve keeps the old row's ground columns when both used the same mesh (vertices)."""
    by = {(r["mode"], r["force"], r["solver"]): dict(r) for r in old}
    for r in new:
        key = (r["mode"], r["force"], r["solver"])
        o = by.get(key)
        r = dict(r)
        if o is not None and not _finite(r["dL_ground"]) and _finite(o["dL_ground"]) and o["vertices"] == r["vertices"]:
            for k in ("L_W_bem_ground", "dL_ground", "wall_ground_s"):
                r[k] = o[k]
        by[key] = r
    return sorted(by.values(), key=lambda r: (r["mode"].startswith("default"), r["mode"], r["force"],
                                              r["solver"] != SOLVER_3D))


def merge_conv(old: list[dict], new: list[dict]) -> list[dict]:
    """Convergence rows keyed by mode, element size, vertices around and solver (new replaces old)."""
    key = lambda r: (r["mode"], round(float(r["ds_max"]), 4), int(float(r["n_phi"])), r["solver"])  # noqa: E731
    by = {key(r): r for r in old}
    by.update({key(r): r for r in new})
    return sorted(by.values(), key=lambda r: (r["mode"], r["solver"] != SOLVER_3D, float(r["vertices"])))


def cached(out: Path, fragment: Path) -> tuple[list[dict], list[dict]]:
    """(wheel rows, convergence rows): the CSV cache in ``out``, merged over the fragment's rows."""
    seed_w, seed_c = rows_from_fragment(fragment.read_text()) if fragment.exists() else ([], [])
    w = read_csv(out / "wheel.csv", WHEEL_KEYS, {"solver": SOLVER_3D, "load": ""}) if (out / "wheel.csv").exists() else []
    c = (read_csv(out / "convergence.csv", CONV_KEYS, {"solver": SOLVER_3D, "mode": "(2,0,a)", "load": ""})
         if (out / "convergence.csv").exists() else [])
    return merge_wheel(seed_w, w), merge_conv(seed_c, c)


def _f(x, fmt: str) -> str:
    return format(x, fmt) if _finite(x) else "-"


WHEEL_HEAD = ("| mode | f (Hz) | force | vertices (wheel) | solver | L_W simple (dB) | BEM free | BEM + ground | "
              "Delta free (dB) | Delta ground (dB) | wall free / ground (s) | load |")
CONV_HEAD = ("| mode | element size along the outline (mm) | vertices around | vertices | solver | Delta free (dB) | "
             "wall (s) | load |")


def wheel_table(rows: list[dict]) -> str:
    lines = [WHEEL_HEAD, "|" + "---|" * 12]
    for r in rows:
        lines.append(f"| {r['mode']} | {r['f_hz']:.1f} | {r['force']} | {int(r['vertices'])} | {r['solver']} | "
                     f"{r['L_W_simple']:.1f} | {_f(r['L_W_bem_free'], '.1f')} | {_f(r['L_W_bem_ground'], '.1f')} | "
                     f"{_f(r['dL_free'], '+.1f')} | {_f(r['dL_ground'], '+.1f')} | "
                     f"{_f(r['wall_free_s'], '.0f')} / {_f(r['wall_ground_s'], '.0f')} | {r['load']} |")
    return "\n".join(lines)


def conv_table(rows: list[dict]) -> str:
    lines = [CONV_HEAD, "|" + "---|" * 8]
    for r in rows:
        lines.append(f"| {r['mode']} | {1e3 * float(r['ds_max']):.0f} | {int(float(r['n_phi']))} | {int(float(r['vertices']))} "
                     f"| {r['solver']} | {float(r['dL_free']):+.2f} | {_f(float(r['wall_s']), '.0f')} | {r['load']} |")
    return "\n".join(lines)


def conv_summary(rows: list[dict]) -> str:
    """Per mode: the spread of Delta over the meshes and the finest mesh's value."""
    out = []
    for mode in sorted({r["mode"] for r in rows}):
        rs = [r for r in rows if r["mode"] == mode]
        d = [float(r["dL_free"]) for r in rs]
        fine = max(rs, key=lambda r: float(r["vertices"]))
        coarse = min(rs, key=lambda r: float(r["vertices"]))
        move = float(fine["dL_free"]) - float(coarse["dL_free"])
        out.append(f"{mode}: Delta spans {max(d) - min(d):.2f} dB over {len(rs)} meshes, {float(coarse['dL_free']):+.2f} dB "
                   f"on the coarsest ({int(float(coarse['vertices']))} vertices) and {float(fine['dL_free']):+.2f} dB "
                   f"on the finest ({int(float(fine['vertices']))}): refinement moves the BEM "
                   f"{'up' if move > 0 else 'down'} by {abs(move):.2f} dB.")
    return " ".join(out)
