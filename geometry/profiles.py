"""Tabulated running-surface profiles (wheel tread, rail head): the text
format, its validation, and the smoothed profile the contact uses.

File format (``geometry/profiles/<name>.csv``; docs/reference.md, "Running-surface profiles")::

    # kind: wheel                      (wheel | rail; required)
    # source: EN 13715 S1002 ...       (required)
    # units: mm                        (mm | m; required)
    # noise_mm: 0                      (optional: measurement noise; see smoothing)
    # <any other key>: <value>         (kept as metadata: calibration, date, ...)
    y,z
    -62.000,27.123
    ...

Convention: y lateral, + toward the field side -- for a wheel from the
nominal rolling (tape) circle (y^W of SPEC 2), for a rail from the rail
centre line (y^R); z for a wheel is r - r0, the radius above the nominal
rolling radius (the flange is positive), for a rail the height above the
crown top of the new head (up).  Both bodies are solid below their curve in
their own z.  One point per line, y strictly increasing (flange/gauge side
first), at least MIN_POINTS points, no gap wider than MAX_GAP.

Smoothing (``build_profile``): a cubic smoothing spline
(``scipy.interpolate.make_smoothing_spline``, penalty lam * int z''^2) in mm,
with lam chosen so that the RMS residual equals ``noise_mm`` (discrepancy
principle; ``noise_mm: 0`` interpolates, for generated profiles), or by
generalized cross-validation when the file states no noise.  It is
evaluated on a uniform GRID_STEP grid for searches and plots; values,
slopes and curvatures come from the spline itself (C2).

Everything here is pure: text in, arrays and Profile out (``pipeline.config.case_profiles``
reads and writes the files).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

MIN_POINTS = 20
MAX_GAP_MM = 10.0
SPAN_MM = (10.0, 300.0)  # plausible lateral extent of a wheel or rail profile
Z_MAX_MM = 60.0
GRID_STEP = 5e-5  # m: the uniform evaluation grid
REQUIRED = ("kind", "source", "units")
KINDS = ("wheel", "rail")


class ProfileError(ValueError):
    """A profile file that cannot be used: ``source`` (file), ``line`` (1-based
    or None) and the reason, formatted as 'file line N: reason'."""

    def __init__(self, source: str, line: int | None, reason: str):
        self.source, self.line, self.reason = str(source), line, reason
        where = f"{source} line {line}" if line else str(source)
        super().__init__(f"{where}: {reason}")


@dataclass(frozen=True)
class Profile:
    """A smoothed running-surface profile (SI units).

    ``z(y)`` is NaN outside [y[0], y[-1]]; ``slope`` is dz/dy, ``curvature``
    d2z/dy2 (1/m; negative where the body is convex, e.g. a rail crown).
    """

    name: str
    kind: str
    source: str
    y: np.ndarray  # uniform grid (m)
    z: np.ndarray  # smoothed z on the grid (m)
    spline: object = field(repr=False)  # scipy BSpline in mm
    smoothing: str = ""
    meta: dict = field(default_factory=dict)

    def _eval(self, y, nu: int) -> np.ndarray:
        y = np.asarray(y, float)
        ymm = 1e3 * y
        out = self.spline(ymm, nu)
        return np.where((y >= self.y[0] - 1e-12) & (y <= self.y[-1] + 1e-12), out, np.nan)

    def __call__(self, y) -> np.ndarray:
        return 1e-3 * self._eval(y, 0)

    def slope(self, y) -> np.ndarray:
        return self._eval(y, 1)

    def curvature(self, y) -> np.ndarray:
        return 1e3 * self._eval(y, 2)


# --------------------------------------------------------------------------- parsing
def parse_profile(text: str, source: str) -> tuple[dict, np.ndarray, np.ndarray, np.ndarray]:
    """(meta, y, z, line numbers) of a profile file's text, y and z in the
    file's units.  Raises ProfileError naming the file and line."""
    meta: dict[str, str] = {}
    meta_line: dict[str, int] = {}
    ys, zs, lines = [], [], []
    header_seen = False
    for k, raw in enumerate(text.splitlines(), start=1):
        s = raw.strip()
        if not s:
            continue
        if s.startswith("#"):
            body = s[1:].strip()
            if ":" in body and not ys:
                key, _, val = body.partition(":")
                meta[key.strip().lower()] = val.strip()
                meta_line[key.strip().lower()] = k
            continue
        parts = [p for p in s.replace(";", ",").replace("\t", ",").replace(" ", ",").split(",") if p]
        if not header_seen and not ys and parts and not _is_number(parts[0]):
            header_seen = True  # the column line, e.g. 'y,z'
            continue
        if len(parts) != 2:
            raise ProfileError(source, k, f"expected two numbers 'y, z', got {s[:60]!r}")
        try:
            y, z = float(parts[0]), float(parts[1])
        except ValueError:
            raise ProfileError(source, k, f"expected two numbers 'y, z', got {s[:60]!r}") from None
        ys.append(y)
        zs.append(z)
        lines.append(k)
    for key in REQUIRED:
        if key not in meta:
            raise ProfileError(source, None, f"header key '# {key}: ...' is missing (required: {', '.join(REQUIRED)})")
    if meta["kind"] not in KINDS:
        raise ProfileError(source, meta_line["kind"], f"kind {meta['kind']!r} is not one of {', '.join(KINDS)}")
    if meta["units"] not in ("mm", "m"):
        raise ProfileError(source, meta_line["units"], f"units {meta['units']!r} is not one of mm, m")
    return meta, np.array(ys), np.array(zs), np.array(lines, dtype=int)


def _is_number(s: str) -> bool:
    try:
        float(s)
        return True
    except ValueError:
        return False


def check_points(y, z, source: str, lines=None, units: str = "mm") -> None:
    """Validate tabulated points (in ``units``): finite, y strictly
    increasing, enough points, no large gaps, plausible extent (catches mm
    vs m).  Raises ProfileError naming the file and the line."""
    y, z = np.asarray(y, float), np.asarray(z, float)
    lines = np.arange(1, len(y) + 1) if lines is None else np.asarray(lines)
    scale = 1.0 if units == "mm" else 1e3
    for name, v in (("y", y), ("z", z)):
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ProfileError(source, int(lines[bad[0]]), f"{name} = {v[bad[0]]} is not a finite number")
    if len(y) < MIN_POINTS:
        where = int(lines[-1]) if len(lines) else None
        raise ProfileError(source, where, f"only {len(y)} points; a profile needs at least {MIN_POINTS}")
    step = np.diff(y)
    bad = np.flatnonzero(step <= 0)
    if bad.size:
        i = bad[0] + 1
        raise ProfileError(source, int(lines[i]), f"y = {y[i]:g} {units} does not increase (line {lines[i - 1]}: "
                           f"y = {y[i - 1]:g} {units}); y must increase strictly, flange/gauge side first")
    span = (y[-1] - y[0]) * scale
    if not SPAN_MM[0] <= span <= SPAN_MM[1]:
        other = "m" if units == "mm" else "mm"
        hint = ""
        if SPAN_MM[0] <= span * (1e3 if units == "mm" else 1e-3) <= SPAN_MM[1]:
            hint = f"; the values look like {other} (units off by 1000): set '# units: {other}'"
        raise ProfileError(source, int(lines[-1]), f"the profile spans {span:g} mm in y (units: {units}), outside "
                           f"the plausible {SPAN_MM[0]:g}-{SPAN_MM[1]:g} mm{hint}")
    zmax = np.abs(z).max() * scale
    if zmax > Z_MAX_MM:
        i = int(np.argmax(np.abs(z)))
        raise ProfileError(source, int(lines[i]), f"|z| = {zmax:g} mm exceeds {Z_MAX_MM:g} mm (units: {units}); "
                           "z is measured from the rolling circle (wheel) or the crown top (rail)")
    gap = np.flatnonzero(step * scale > MAX_GAP_MM)
    if gap.size:
        i = gap[0] + 1
        raise ProfileError(source, int(lines[i]), f"a gap of {step[gap[0]] * scale:g} mm after line {lines[i - 1]} "
                           f"(at most {MAX_GAP_MM:g} mm between points)")


# --------------------------------------------------------------------------- smoothing
def _smoothing_spline(x, y, noise):
    """Cubic smoothing spline of (x, y) (mm) and its description: RMS residual
    = noise (bisection on log lam), noise 0 -> interpolating, None -> GCV."""
    from scipy.interpolate import make_interp_spline, make_smoothing_spline  # lazy: brings in scipy

    if noise is not None and noise <= 0.0:
        return make_interp_spline(x, y, k=3), "interpolating cubic spline (noise_mm = 0)"
    if noise is None:
        spl = make_smoothing_spline(x, y)
        rms = float(np.sqrt(np.mean((spl(x) - y) ** 2)))
        return spl, f"cubic smoothing spline, penalty by generalized cross-validation (RMS residual {rms:.4f} mm)"
    lo, hi = -12.0, 6.0  # log10 lam (mm^3)
    rms = lambda lg: float(np.sqrt(np.mean((make_smoothing_spline(x, y, lam=10**lg)(x) - y) ** 2)))  # noqa: E731
    if rms(hi) < noise:
        lo = hi
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if rms(mid) < noise else (lo, mid)
    spl = make_smoothing_spline(x, y, lam=10**lo)
    return spl, (f"cubic smoothing spline, lam = {10**lo:.3g} mm^3 for an RMS residual of {rms(lo):.4f} mm "
                 f"(noise_mm = {noise:g})")


def build_profile(y, z, kind: str, name: str, source: str, noise_mm: float | None = 0.0,
                  meta: dict | None = None, lines=None, units: str = "m") -> Profile:
    """Validate points (in ``units``) and return the smoothed Profile.

    Parameters
    ----------
    y, z : array_like
        Lateral position and height (see the module convention).
    kind : {'wheel', 'rail'}
    noise_mm : float or None
        Measurement noise (mm): 0 interpolates, None selects the penalty by
        generalized cross-validation.
    """
    if kind not in KINDS:
        raise ProfileError(name, None, f"kind {kind!r} is not one of {', '.join(KINDS)}")
    check_points(y, z, source=name if lines is None else name, lines=lines, units=units)
    f = 1e3 if units == "m" else 1.0
    ymm, zmm = np.asarray(y, float) * f, np.asarray(z, float) * f
    spl, how = _smoothing_spline(ymm, zmm, noise_mm)
    grid = np.arange(math.ceil(ymm[0] / (1e3 * GRID_STEP)), math.floor(ymm[-1] / (1e3 * GRID_STEP)) + 1) * GRID_STEP
    return Profile(name=name, kind=kind, source=source, y=grid, z=1e-3 * spl(1e3 * grid), spline=spl,
                   smoothing=how, meta=dict(meta or {}))


def profile_from_text(text: str, source: str, name: str) -> Profile:
    """Parse, validate and smooth a profile file's text (see module doc)."""
    meta, y, z, lines = parse_profile(text, source)
    noise = meta.get("noise_mm")
    try:
        noise = None if noise in (None, "", "gcv") else float(noise)
    except ValueError:
        raise ProfileError(source, None, f"noise_mm {noise!r} is not a number (mm) or 'gcv'") from None
    check_points(y, z, source, lines, meta["units"])
    f = 1e-3 if meta["units"] == "mm" else 1.0
    return build_profile(y * f, z * f, meta["kind"], name, meta["source"], noise, meta=meta)


def format_profile(meta: dict, y, z) -> str:
    """The text of a profile file (y, z in m, written in mm to 1 nm, so that
    the curvature of an interpolated generated profile is exact
    to ~0.1 1/m at 0.25 mm spacing);
    ``meta`` must hold kind and source, units is set to mm."""
    head = {"kind": meta["kind"], "source": meta["source"], "units": "mm"}
    head.update({k: v for k, v in meta.items() if k not in head})
    out = [f"# {k}: {' '.join(str(v).split())}" for k, v in head.items()]
    out.append("y,z")
    out += [f"{1e3 * a:.6f},{1e3 * b:.6f}" for a, b in zip(np.asarray(y, float), np.asarray(z, float))]
    return "\n".join(out) + "\n"
