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

import numpy as np
from pipeline.store.atomic import atomic_write
from solvers.constants import F_MAX_HZ

WHEEL_KEYS = ("mode", "f_hz", "force", "vertices", "solver", "L_W_simple", "L_W_bem_free", "L_W_bem_ground",
              "dL_free", "dL_ground", "wall_free_s", "wall_ground_s", "load")
CONV_KEYS = ("mode", "ds_max", "n_phi", "vertices", "solver", "dL_free", "wall_s", "load")
TEXT_KEYS = ("mode", "force", "solver", "load")
GROUND_BELOW_CONTACT = 0.16      # m: a rigid ground at about the BV50's foot (153 mm rail height + pad)
SOLVER_3D = "3-D"                 # solvers.radiation.bem.radiated_power: the whole mesh (image wheel for the ground)
SOLVER_REV = "revolution"         # solvers.radiation.bem_revolution: first block row per harmonic; ground by mirror symmetry

# fragment column headers -> CSV keys (a two-valued cell "a / b" fills two keys)
_WHEEL_COLS = {"mode": ("mode",), "f (Hz)": ("f_hz",), "force": ("force",), "vertices (wheel)": ("vertices",),
               "solver": ("solver",), "L_W simple (dB)": ("L_W_simple",), "BEM free": ("L_W_bem_free",),
               "BEM + ground": ("L_W_bem_ground",), "Delta free (dB)": ("dL_free",),
               "Delta ground (dB)": ("dL_ground",), "wall free / ground (s)": ("wall_free_s", "wall_ground_s"),
               "load": ("load",)}
_CONV_COLS = {"mode": ("mode",), "element size along the outline (mm)": ("ds_max",),
              "ds_max along the outline (mm; lambda/6 caps it)": ("ds_max",),
              "vertices around": ("n_phi",), "vertices": ("vertices",), "solver": ("solver",),
              "Delta free (dB)": ("dL_free",), "wall (s)": ("wall_s",), "load": ("load",)}


def _value(key: str, text: str):
    text = text.strip()
    if key in TEXT_KEYS:
        return text
    if text in ("", "-", "nan"):
        return math.nan
    if key == "ds_max" and text == "FE outline":
        return 0.0
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
    """(wheel rows, convergence rows): the CSV cache in ``out``; a table whose CSV is missing is seeded
    from the fragment's rows (as printed)."""
    seed_w, seed_c = rows_from_fragment(fragment.read_text()) if fragment.exists() else ([], [])
    w = read_csv(out / "wheel.csv", WHEEL_KEYS, {"solver": SOLVER_3D, "load": ""}) if (out / "wheel.csv").exists() else []
    c = (read_csv(out / "convergence.csv", CONV_KEYS, {"solver": SOLVER_3D, "mode": "(2,0,a)", "load": ""})
         if (out / "convergence.csv").exists() else [])
    return merge_wheel([] if w else seed_w, w), merge_conv([] if c else seed_c, c)


def _f(x, fmt: str) -> str:
    return format(x, fmt) if _finite(x) else "-"


WHEEL_HEAD = ("| mode | f (Hz) | force | vertices (wheel) | solver | L_W simple (dB) | BEM free | BEM + ground | "
              "Delta free (dB) | Delta ground (dB) | wall free / ground (s) | load |")
CONV_HEAD = ("| mode | ds_max along the outline (mm; lambda/6 caps it) | vertices around | vertices | solver | Delta free (dB) | "
             "wall (s) | load |")


def wheel_table(rows: list[dict]) -> str:
    lines = [WHEEL_HEAD, "|" + "---|" * 12]
    for r in rows:
        lines.append(f"| {r['mode']} | {r['f_hz']:.1f} | {r['force']} | {int(r['vertices'])} | {r['solver']} | "
                     f"{r['L_W_simple']:.1f} | {_f(r['L_W_bem_free'], '.1f')} | {_f(r['L_W_bem_ground'], '.1f')} | "
                     f"{_f(r['dL_free'], '+.1f')} | {_f(r['dL_ground'], '+.1f')} | "
                     f"{_f(r['wall_free_s'], '.0f')} / {_f(r['wall_ground_s'], '.0f')} | {r['load']} |")
    return "\n".join(lines)


def _rank(label: str) -> int:
    """Preference among solves of one mode: revolution at bempp's quadrature, then its variants, then 3-D
    (stored as printed)."""
    return 0 if label == SOLVER_REV else 1 if label.startswith(SOLVER_REV) else 2


def mode_table(rows: list[dict], conv: list[dict] = ()) -> str:
    """Per (n,0,a) mode: Delta free and over the ground for the lateral and radial force, each from the
    preferred solve that has it (``_rank``), and the convergence check's finest mesh (unit lateral force,
    free field) with the spread of Delta over its meshes."""
    lines = ["| mode | f (Hz) | vertices | Delta free, lateral / radial (dB) | Delta ground, lateral / radial (dB) | "
             "solver (free; ground) | Delta free, finest mesh (vertices) | spread over the meshes (dB) |",
             "|" + "---|" * 8]
    modes = sorted({r["mode"] for r in rows if not r["mode"].startswith("default")})
    for m in modes:
        rs = [r for r in rows if r["mode"] == m]
        pick = {}
        for col in ("dL_free", "dL_ground"):
            have = [r for r in rs if _finite(r[col])]
            if have:
                best = min(have, key=lambda r: _rank(r["solver"]))
                pick[col] = [r for r in have if r["solver"] == best["solver"]]
        cell = {c: " / ".join(_f(next((r[c] for r in pick[c] if r["force"] == fo), math.nan), "+.1f")
                              for fo in ("lateral", "radial")) if c in pick else "-" for c in ("dL_free", "dL_ground")}
        src = "; ".join(pick[c][0]["solver"] if c in pick else "not done" for c in ("dL_free", "dL_ground"))
        cs = [r for r in conv if r["mode"] == m]
        fine = max(cs, key=lambda r: float(r["vertices"])) if cs else None
        d = [float(r["dL_free"]) for r in cs]
        conv_cells = (f"{float(fine['dL_free']):+.1f} ({int(float(fine['vertices']))}) | {max(d) - min(d):.1f} ({len(cs)})"
                      if fine else "- | -")
        lines.append(f"| {m} | {rs[0]['f_hz']:.0f} | {int(rs[0]['vertices'])} | {cell['dL_free']} | {cell['dL_ground']} | "
                     f"{src} | {conv_cells} |")
    return "\n".join(lines)


def conv_table(rows: list[dict]) -> str:
    lines = [CONV_HEAD, "|" + "---|" * 8]
    for r in rows:
        ds = f"{1e3 * float(r['ds_max']):.1f}" if float(r["ds_max"]) > 0 else "FE outline"
        lines.append(f"| {r['mode']} | {ds} | {int(float(r['n_phi']))} | {int(float(r['vertices']))} "
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
    fine = {m: float(max((r for r in rows if r["mode"] == m), key=lambda r: float(r["vertices"]))["dL_free"])
            for m in sorted({r["mode"] for r in rows})}
    if fine:
        grp = lambda ok: ", ".join(m for m, d in fine.items() if ok(d)) or "no mode"           # noqa: E731
        out.append(f"On each mode's finest mesh Delta is {min(fine.values()):+.1f} to {max(fine.values()):+.1f} dB: the "
                   f"simple model is 0.5 dB or more above the BEM (the reference's finding) for {grp(lambda d: d <= -0.5)}, "
                   f"within 0.5 dB for {grp(lambda d: abs(d) < 0.5)} and 0.5 dB or more below it for "
                   f"{grp(lambda d: d >= 0.5)}.")
    return " ".join(out)


def _summary(rows: list[dict]) -> str:
    """What the table says, from its numbers: the range of Delta per field, its sign against the
    reference's finding, and whether lateral and radial forces agree."""
    modes_ = [r for r in rows if not r["mode"].startswith("default") and np.isfinite(r["dL_free"])]
    if not modes_:
        return ""
    dfree = [r["dL_free"] for r in modes_]
    dgr = [r["dL_ground"] for r in modes_ if np.isfinite(r["dL_ground"])]
    pairs = {}
    for r in modes_:
        pairs.setdefault((r["mode"], r["solver"]), []).append(r["dL_free"])
    split = max(max(v) - min(v) for v in pairs.values())
    below = sorted({r["mode"] for r in modes_ if r["dL_free"] <= -0.5})
    above = sorted({r["mode"] for r in modes_ if r["dL_free"] >= 0.5})
    within = sorted({r["mode"] for r in modes_} - set(below) - set(above))
    grd = sorted({r["mode"] for r in modes_ if np.isfinite(r["dL_ground"])})
    sh = {m: max(abs(r["dL_ground"] - r["dL_free"]) for r in modes_ if r["mode"] == m and np.isfinite(r["dL_ground"]))
          for m in grd}
    low, rest = (grd[0], grd[1:]) if grd else (None, [])
    ground_text = (f"The ground's reflection (the radiation stage has none) changes Delta by {sh[low]:.1f} dB at {low}"
                   + (f" and by at most {max(sh[m] for m in rest):.2f} dB at the higher modes computed over it "
                      f"({', '.join(rest)}), as expected of a source several wavelengths from its image" if rest else "")
                   + ". " if grd else "")
    return (f"Delta L_W per (n,0,a) mode and unit force: free field {min(dfree):+.1f} to {max(dfree):+.1f} dB"
            + (f", over the ground {min(dgr):+.1f} to {max(dgr):+.1f} dB" if dgr else "")
            + f" (|Delta| <= {max(abs(d) for d in dfree):.1f} dB in free field). The reference found the simple "
            "model 0.5 to 4 dB above its BEM (Delta -4 to -0.5 dB; its BEM had a reflecting ground). Here the simple "
            "model is 0.5 dB or more above the free-field BEM for "
            + (", ".join(below) if below else "no mode")
            + ", within 0.5 dB for " + (", ".join(within) if within else "no mode")
            + ", and 0.5 dB or more BELOW it for " + (", ".join(above) if above else "no mode")
            + ": the reference's finding is reproduced in direction and size only where the simple model is above. "
            + ground_text
            + f"Lateral and radial forces give the same Delta to {split:.2f} dB at the eigenfrequency, where the "
            "(n,0,a) mode dominates the velocity field whichever force drives it.")


def fragment_text(wheel: list[dict], conv: list[dict], ds_max: float, plan=()) -> str:
    """docs/validation/72_bem_wheel.md from the cached rows."""
    spread = {}
    for r in wheel:
        for c in ("L_W_bem_free", "L_W_bem_ground"):
            if np.isfinite(r[c]):
                spread.setdefault((r["mode"], r["force"], c), []).append(r[c])
    sf = [max(v) - min(v) for (_, _, c), v in spread.items() if c == "L_W_bem_free" and len(v) > 1]
    sg = [max(v) - min(v) for (_, _, c), v in spread.items() if c == "L_W_bem_ground" and len(v) > 1]
    agree_text = (" Where a mode was computed more than once (solvers, backends, cross-block quadrature orders) "
                  f"the free-field levels differ by at most {max(sf):.2f} dB"
                  + (f" and the ground levels by at most {max(sg):.4f} dB" if sg else "")
                  + " (the earlier 3-D rows are stored as printed, to 0.1 dB)." if sf else "")
    both = {}
    for r in wheel:
        both.setdefault((r["mode"], r["force"]), {})[r["solver"]] = r
    quad = {}
    for (m, _), v in both.items():
        for s_, r in v.items():
            base = s_.split(", ground q")[0].replace(", opencl", "")
            if ", ground q" in s_ and np.isfinite(r["dL_ground"]) and base in v and np.isfinite(v[base]["dL_ground"]):
                d = abs(r["dL_ground"] - v[base]["dL_ground"])
                quad[(m, s_)] = max(quad.get((m, s_), 0.0), d)
    if quad:
        agree_text += (" A lower quadrature order of the image's cross block (its integrals are regular: the image "
                       f"is at least {2 * GROUND_BELOW_CONTACT * 1e3:.0f} mm away) changes Delta ground by at most "
                       + ", ".join(f"{d:.4f} dB ({m}, {s_.split(', ')[1]})" for (m, s_), d in quad.items()) + ".")
    status = ""
    if plan:
        done = {}
        for r in wheel:
            d = done.setdefault(r["mode"], [False, False])
            d[0] |= bool(np.isfinite(r["dL_free"]))
            d[1] |= bool(np.isfinite(r["dL_ground"]))
        status = ("\n\nThe radiation stage's (n,0,a) modes with n >= 2 (up to its f_max, "
                  f"{F_MAX_HZ:.0f} Hz), their lambda/6 meshes and what is in the table above (the 3-D solve's "
                  "dense matrices need 16 N^2 bytes each, four times that with the image wheel; the revolution "
                  "solver's free field needs 1/(vertices around) of that, its ground two N x N matrices: the "
                  "left-hand side, factored in place, and one operator at a time of the right-hand side):\n\n"
                  "| mode | f (Hz) | vertices (along x around) | one dense 3-D matrix (GB) | free field | ground |\n"
                  "|---|---|---|---|---|---|\n"
                  + "\n".join(f"| {p['mode']} | {p['f_hz']:.0f} | {p['vertices']} ({p['along']} x {p['around']}) | "
                              f"{p['dense_gb']:.1f} | {'done' if done.get(p['mode'], [0, 0])[0] else 'not done'} | "
                              f"{'done' if done.get(p['mode'], [0, 0])[1] else 'not done'} |" for p in plan)
                  + _cost_note(wheel, plan, done))
    text = f"""## The radiation stage against a boundary-element solution: the wheel (issue 28)

Script: `python -m pipeline.validation.bem_check` (bempp-cl, Burton-Miller, P1; checked on the spheres above).
The default case's wheel: the FE section's outline revolved (element size <= lambda/6 around, <= min(lambda/6,
{ds_max * 1e3:.0f} mm) along the outline, corners kept), the outward normal velocity of harmonic n for a unit RMS
lateral or radial force at the contact point at the (n,0,a) eigenfrequency, from the radiation stage's modal
velocities; bore clamped (zero velocity). Ground: rigid, {GROUND_BELOW_CONTACT * 1e3:.0f} mm below the contact
point (an image wheel; the wheel's axis horizontal, the contact at the bottom). Delta = L_W(BEM) - L_W(radiation
stage) for harmonic n. The reference (thesis sec. 5.1) found 0.5 to 4 dB with the simple model higher, i.e. Delta
between -4 and -0.5 dB.

Two solvers of the same discrete problem. `3-D` (`solvers.radiation.bem.radiated_power`): the whole mesh, dense
(assembly and memory grow with the square of the vertices N; the ground by the wheel and its image, 2N
unknowns). `revolution` (`solvers.radiation.bem_revolution`): the mesh is rotated copies of one ring of vertices, so
its Galerkin matrices are block-circulant; bempp-cl assembles only the first block row (ring 0's test
functions against the whole mesh: 1/(vertices around) of the 3-D assembly) and the problem splits into one
ring-sized problem per harmonic +-n; over the ground, by the mirror symmetry of wheel and image, the
unknowns are the wheel's: its own matrix (rebuilt from the first block row) plus the image's cross block
(N x N, bempp-cl, no singular integrals). `tests/radiation/test_bem_revolution.py` asserts that both give
the same power to 1e-8 in free field (harmonics 0-3) and to 1e-4 over a ground (the 3-D pair is mirror-symmetric only to bempp's quadrature).{agree_text} Wall times: one
thread (`OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1`, `nice -n 5`) on a shared 2-core machine, including
bempp's numba compilation (about 1-2 min per process); load = the 1-min load average at the end of the
solve ("4-10": the first rows' runs, as stated then). Backends: bempp-cl's numba (default) or its OpenCL
kernels on the CPU through pocl (`, opencl` in the solver column, `--device opencl`; the sphere check and the
solvers' check run on both; `python -m benchmarks bem` compares their speed); `, ground qN`: the image's
cross block at quadrature order N instead of bempp's 4.

Delta L_W per mode (the table of every solve follows):

{mode_table(wheel, conv)}

{_summary(wheel)}

Every solve:

{wheel_table(wheel)}{status}
"""
    if conv:
        text += ("\nMesh convergence, unit lateral force, free field (`--convergence N`):\n\n" + conv_table(conv)
                 + "\n\n" + conv_summary(conv) + " The per-mode table above (the lambda/6 rule) is "
                 "uncertain by about these spans.\n")
    return text


POCL_MAX_BUFFER_GB = 4.29   # pocl's largest buffer on the 2-core EPYC of these runs (pyopencl max_mem_alloc_size)


def _cost_note(wheel: list[dict], plan, done: dict) -> str:
    """Why the grounds not done are not: their cost extrapolated from the fastest measured one (the
    revolution solver's ground: the image's cross block, (2N)^2 triangle pairs; two dense N x N
    matrices; bempp's OpenCL backend holds one whole matrix in one buffer)."""
    meas = [(r["wall_ground_s"] / (2 * r["vertices"]) ** 2, r) for r in wheel
            if r["solver"].startswith(SOLVER_REV) and np.isfinite(r["wall_ground_s"]) and r["vertices"] > 3000]
    todo = [p for p in plan if not done.get(p["mode"], [0, 0])[1]]
    if not meas or not todo:
        return ""
    rate, ref = min(meas, key=lambda m: m[0])
    numba = [m for m in meas if "opencl" not in m[1]["solver"]]
    rate_nb, ref_nb = min(numba, key=lambda m: m[0]) if numba else (rate, ref)

    def cost(p):
        big = p["dense_gb"] > POCL_MAX_BUFFER_GB
        r = rate_nb if big else rate
        return (f"{p['mode']} would take {r * (2 * p['vertices']) ** 2 / 60:.0f} min and {2 * p['dense_gb']:.0f} GB"
                + (f" (one matrix, {p['dense_gb']:.1f} GB, exceeds pocl's largest buffer here, {POCL_MAX_BUFFER_GB} GB: "
                   f"numba, {rate_nb * 1e6:.2f} us per pair measured on {ref_nb['mode']})" if big else ""))

    return ("\n\nThe grounds not done: the fastest measured ground took "
            f"{ref['wall_ground_s']:.0f} s for {ref['mode']} ({int(ref['vertices'])} vertices, {ref['solver']}, load "
            f"{ref['load']}), {rate * 1e6:.2f} us per pair of triangles of the image's cross block; at that rate "
            + ", ".join(cost(p) for p in todo)
            + " on a machine of 23 GB shared by three sessions.")
