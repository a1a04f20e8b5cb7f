"""docs/validation/15_profiles.md and profiles_contact.png: the shipped standard
profiles (geometry/profiles/s1002.csv, 60e1_new.csv) against the files CONTACT
ships (``pipeline.validation.contact_reference``).

    python -m pipeline.validation.profiles_doc

Compared: the heights (the shipped table's interpolating spline against
CONTACT's points and its R300/R80/R13 + 1:20 head), the gauge face (lateral
position 12-20 mm below the crown top), and the centred contact: the rigid
contact (``geometry.contact_point``) of the S1002 wheel on the 60E1 rail
inclined 1:40, gauge 1435 mm measured 14 mm below the crown
(``pipeline.curve.curving.gauge_face``), flange backs 1360 mm apart, the tape
circle 70 mm from the flange back (EN 13715), no lateral shift.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.validation import contact_reference as ref
from pipeline.config.case_profiles import read_profile
from geometry.profiles import build_profile
from geometry.contact_point import TrackRail, rigid_contact
from pipeline.curve.curving import gauge_face
from pipeline.store.atomic import save_figure, save_text

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "validation"
GAUGE_MM, BACK_TO_BACK_MM, TAPE_FROM_BACK_MM, INCLINATION = 1435.0, 1360.0, 70.0, 1 / 40
RAIL_BAND_MM = 35.0  # |y| of the rail heights compared: crown, shoulder and gauge corner (slope up to ~60 deg)
WHEEL_BAND_MM = (-62.0, 60.0)  # the shipped S1002 table: flange (tip at -55) to the field side
FACE_DEPTHS_MM = (12.0, 14.0, 16.0, 18.0, 20.0)
REF_DEPTH_MM = 25.0  # CONTACT's head tabulated to this depth for the contact


def shipped_profiles():
    """(wheel, rail) Profiles of the shipped tables s1002.csv and 60e1_new.csv."""
    return read_profile("s1002")[0], read_profile("60e1_new")[0]


def contact_profiles():
    """(wheel, rail) Profiles from CONTACT: an interpolating spline through its
    S1002 points, and its UIC60 head (arcs and side) every 0.02 mm of arc."""
    src = f"CONTACT {ref.CONTACT_COMMIT[:10]} " + ", ".join(Path(f).name for f in ref.CONTACT_FILES)
    wheel = build_profile(*ref.s1002_contact(), "wheel", "s1002 (CONTACT)", src, 0.0)
    rail = build_profile(*ref.uic60_contact_curve(REF_DEPTH_MM), "rail", "uic60 (CONTACT)", src, 0.0)
    return wheel, rail


def face_y(rail, depth_mm: float) -> float:
    """Gauge-side y (mm) of the rail Profile ``depth_mm`` below its crown top, NaN off the table."""
    top = int(np.argmax(rail.z))
    zg, yg = rail.z[: top + 1], rail.y[: top + 1]
    z = float(rail.z[top]) - 1e-3 * depth_mm
    return float(1e3 * np.interp(z, zg, yg)) if zg[0] <= z and np.all(np.diff(zg) > 0) else float("nan")


def heights(shipped, contact) -> dict:
    """Deviations (mm) of the shipped tables from CONTACT's profiles."""
    wy, wz = ref.s1002_contact()
    sel = (wy >= 1e-3 * WHEEL_BAND_MM[0]) & (wy <= 1e-3 * WHEEL_BAND_MM[1])
    dw = 1e3 * (shipped[0](wy[sel]) - wz[sel])
    ry, rz = ref.uic60_contact_points()
    on = np.abs(ry) <= 1e-3 * RAIL_BAND_MM
    grid = 1e-3 * np.arange(-RAIL_BAND_MM, RAIL_BAND_MM + 1e-9, 0.1)
    dr = 1e3 * (shipped[1](grid) - contact[1](grid))
    face = {d: (face_y(shipped[1], d), face_y(contact[1], d)) for d in FACE_DEPTHS_MM}
    return {"wheel_points": int(sel.sum()), "wheel_max": float(np.max(np.abs(dw))),
            "rail_grid_max": float(np.max(np.abs(dr))), "rail_grid": (1e3 * grid, dr),
            "rail_points": int(on.sum()), "rail_points_max": float(np.max(np.abs(1e3 * (shipped[1](ry[on]) - rz[on])))),
            "wheel_dev": (1e3 * wy[sel], dw), "face": face,
            "table_depth": float(1e3 * (shipped[1].z.max() - shipped[1].z[0]))}


def centred_contact(wheel, rail) -> dict:
    """The rigid contact at zero lateral shift (mm, deg): the rail centre lies
    gauge/2 - Y_gauge from the track centre, the tape circle b2b/2 + 70 mm."""
    track = TrackRail(rail, INCLINATION)
    g = gauge_face(track)
    c = 1e-3 * (0.5 * BACK_TO_BACK_MM + TAPE_FROM_BACK_MM - 0.5 * GAUGE_MM) + g
    rc = rigid_contact(wheel, track, c)
    return {"gauge_Y": 1e3 * g, "c": 1e3 * c, "y_wheel": 1e3 * rc.y_wheel, "y_rail": 1e3 * rc.y_rail,
            "angle": float(np.degrees(rc.angle)), "z_wheel": 1e3 * rc.z_wheel}


def plot(shipped, contact, h: dict, path: Path) -> None:
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib


    fig, ax = plt.subplots(2, 2, figsize=(11, 7.5))
    wy, wz = ref.s1002_contact()
    ax[0, 0].plot(1e3 * shipped[0].y, 1e3 * shipped[0].z, "k-", lw=1, label="shipped s1002.csv")
    ax[0, 0].plot(1e3 * wy, 1e3 * wz, "o", mfc="none", color="C1", ms=4, label="CONTACT MBench_S1002_v3 (every 8th)")
    ax[0, 0].set(title="S1002 wheel", xlabel="y (mm, + field side)", ylabel="r - r0 (mm)")
    ry, rz = ref.uic60_contact_points()
    cy, cz = ref.uic60_contact_curve(REF_DEPTH_MM)
    ax[0, 1].plot(1e3 * cy, 1e3 * cz, "-", color="C1", lw=3, alpha=0.4, label="CONTACT MBench_UIC60_v3 (arcs)")
    ax[0, 1].plot(1e3 * ry, 1e3 * rz, "o", mfc="none", color="C1", ms=4, label="CONTACT points (cant turned back)")
    ax[0, 1].plot(1e3 * shipped[1].y, 1e3 * shipped[1].z, "k-", lw=1, label="shipped 60e1_new.csv")
    ax[0, 1].plot([h["face"][14.0][0]], [-14.0], "rx", ms=9, label="gauge point (14 mm)")
    ax[0, 1].set(title="60E1 rail head", xlabel="y (mm, + field side)", ylabel="z (mm)", ylim=(-26, 2))
    ax[1, 0].plot(h["wheel_dev"][0], 1e3 * h["wheel_dev"][1], "o-", color="C0", ms=3)
    ax[1, 0].set(title="S1002: shipped - CONTACT at CONTACT's points", xlabel="y (mm)", ylabel="dz (um)")
    ax[1, 1].plot(h["rail_grid"][0], 1e3 * h["rail_grid"][1], "-", color="C0",
                  label=f"dz, |y| <= {RAIL_BAND_MM:.0f} mm, every 0.1 mm")
    d = np.array(FACE_DEPTHS_MM)
    ax[1, 1].plot([], [], "s", color="C3", label="gauge face: dy = y_shipped - y_CONTACT (top axis: depth)")
    tw = ax[1, 1].twiny()
    tw.plot(d, [1e3 * (h["face"][k][0] - h["face"][k][1]) for k in FACE_DEPTHS_MM], "s", color="C3")
    tw.set_xlabel("depth below the crown top (mm)")
    ax[1, 1].set(title="60E1: shipped - CONTACT", xlabel="y (mm)", ylabel="dz or dy (um)")
    for a in ax.flat:
        a.grid(alpha=0.3)
    ax[0, 0].legend(fontsize=8)
    ax[0, 1].legend(fontsize=8, loc="lower center")
    ax[1, 1].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)


def report() -> str:
    shipped, contact = shipped_profiles(), contact_profiles()
    h = heights(shipped, contact)
    cs, cc = centred_contact(*shipped), centred_contact(*contact)
    plot(shipped, contact, h, DOC / "profiles_contact.png")
    face = " / ".join(f"{k:.0f} mm: {s:.3f} / {c:.3f}" for k, (s, c) in h["face"].items())
    rows = [("gauge point Y (track frame, mm)", "gauge_Y"), ("rolling circle over the rail centre c (mm)", "c"),
            ("contact y^W on the wheel (mm)", "y_wheel"), ("contact y^R on the rail (mm)", "y_rail"),
            ("contact angle (deg)", "angle"), ("r - r0 at the contact (mm)", "z_wheel")]
    f = lambda x: f"{round(x, 3) + 0.0:+.3f}"  # noqa: E731  (no '-0.000')
    w0, w1, b = WHEEL_BAND_MM[0], WHEEL_BAND_MM[1], RAIL_BAND_MM
    heights_rows = "\n".join([
        f"| S1002 heights, {h['wheel_points']} CONTACT points over y = {w0:.0f} ... {w1:+.0f} mm | | | "
        f"max {h['wheel_max']:.1e} mm |",
        f"| 60E1 heights, y = -{b:.0f} ... +{b:.0f} mm every 0.1 mm (crown, shoulder, gauge corner) | | | "
        f"max {h['rail_grid_max']:.1e} mm |",
        f"| 60E1 heights at the {h['rail_points']} CONTACT points within y = +-{b:.0f} mm | | | "
        f"max {h['rail_points_max']:.1e} mm |",
        f"| 60E1 table depth below the crown top | {h['table_depth']:.1f} mm | | |"])
    table = "\n".join(f"| {lab} | {f(cs[k])} | {f(cc[k])} | {f(cs[k] - cc[k])} |" for lab, k in rows)
    return f"""## Standard profiles against CONTACT's files

_Written by `python -m pipeline.validation.profiles_doc`; asserted by
`tests/profiles/test_standard_profiles_contact.py`._

The shipped tables `geometry/profiles/s1002.csv` (EN 13715 piecewise definition) and `60e1_new.csv`
(EN 13674-1 head arcs of `geometry/rails/60e1.toml`), both written by `make calibrate-profiles`
(`pipeline.validation.calibrate_profiles`), against the S1002 wheel and UIC60 (60E1) rail files that CONTACT ships
(E.A.H. Vollebregt, github.com/eve70a/CONTACT, commit `{ref.CONTACT_COMMIT}`, Apache-2.0;
`MBench_S1002_v3.prw`, `MBench_UIC60_v3.prr`, the Manchester Contact Benchmark profiles, Shackleton & Iwnicki,
Vehicle System Dynamics 46, 2008). The files are not in the repository: `pipeline/validation/contact_reference.py`
quotes every 8th wheel point, 59 rail points and the rail's arcs (least-squares circles and line through all 495
points of the file; the quoted points lie within 1 um of them). CONTACT's rail file is canted 1:40; turned back
it is symmetric to 1e-6 mm: R300 crown to 10.5 mm (R80 centre at 7.700 mm), R80, R13, and a 1:20 head side
that widens downward, 72.000 mm wide at its tangent with R13, 14.26 mm below the crown.

| quantity | shipped | CONTACT | shipped - CONTACT |
|---|---|---|---|
{heights_rows}
{table}

Gauge face, y (mm) of the gauge side at depths below the crown top, shipped / CONTACT: {face}.

**Centred contact** (S1002 on 60E1 inclined 1:40, gauge {GAUGE_MM:.0f} mm 14 mm below the crown, flange backs
{BACK_TO_BACK_MM:.0f} mm apart, tape circle {TAPE_FROM_BACK_MM:.0f} mm from the flange back, no lateral shift):
the shipped pair and CONTACT's touch {abs(cs['y_wheel'] - cc['y_wheel']):.3f} mm apart on the wheel (criterion
0.5 mm). The pair is close to a contact jump: shifted 0.25 mm more toward the field side (the flange toward the
rail), the contact leaves the tread near y^W = +3 mm for the flange root near y^W = -8 mm.

**Before this check** (commit 84230a2): the shipped 60E1 table ended 11.6 mm below the crown (its head cut where
the slope reached 75 deg), so the gauge point 14 mm below it was off the table and `gauge_face` fell back to the
table's end, 0.34 mm inboard (track frame -35.204 mm instead of -35.540 mm); with it the centred contact lay beyond
the jump, at y^W = -7.642 mm on the flange root instead of CONTACT's +3.248 mm. The generator also had the 1:20
head side narrowing downward (the corner arc turned past the vertical), 72 mm at the corner arc's vertical
tangent, and the R300 crown to 10.0 mm: heights up to 0.11 mm off CONTACT's (at the gauge corner, |y| = 35 mm;
0.075 mm on the shoulder from the crown width alone). Fixed in
`geometry.rail.crown_arcs` (the side widens downward, the width at its tangent; a vertical side, BV50's, is
unchanged to the bit), `geometry/rails/60e1.toml` (crown_half_width 10.5 mm), and `rail_head_points` /
`calibrate_profiles` (a tapered head is tabulated down to 22 mm, its faces every 0.25 mm of arc). No shipped case,
curve or study uses 60E1 or S1002: their inputs are unchanged to the bit. The 60E1 FE section (docs/validation
40_rail.md) moved with the head: area +1.87 % against the published value (was +1.10 %).

CONTACT's `testbank/profiles/uic60_true.prr` ("UIC60, vertical sides") is not this rail: R300 / R60 / R12.8 arcs
and 80.9 mm wide; it is not used.

![shipped vs CONTACT profiles](profiles_contact.png)
"""


def main() -> int:
    save_text(report(), DOC / "15_profiles.md")
    print(f"wrote {DOC / '15_profiles.md'} and profiles_contact.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
