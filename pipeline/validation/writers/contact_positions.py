"""The contact of the three SPEC 2 positions from the calibrated worn C20 and
BV50 profiles: contact points (thesis [4.1] as a check), static NORM
patches, regularized friction curves; profiles, patches and pressure maps
plotted; written to docs/validation/31_contact_positions.md (a writer, run by `make validate`).
What it states as checked is asserted by tests/contact/test_positions_validation.py on ``positions()``."""
import numpy as np

from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from geometry.contact_point import rigid_contact, FlangeContact, TrackRail, wheel_shift
from pipeline.study.kinds.map import map_mus
from geometry.calibration import THESIS_POSITIONS, jump_offsets, BOUNDS, NAMES
from pipeline.config.case_profiles import read_profile
from pipeline.stages.rail import load_rail_params
from pipeline.stages.wheel import load_wheel
import re

CASES = ("dy05", "dy10", "default")


def conicity(geo, c, u=3e-3):
    """Equivalent conicity Delta r / (2 u) of a symmetric wheelset of the
    case's profiles displaced by u (the left wheel's rolling circle at c + u,
    the right wheel's at c - u over their rails)."""
    yl = rigid_contact(geo.wheel, geo.rail_track, c + u).y_wheel
    yr = rigid_contact(geo.wheel, geo.rail_track, c - u).y_wheel
    return float((geo.wheel(yl) - geo.wheel(yr)) / (2 * u))


def positions() -> dict:
    """case -> the case dict, its contact geometry, the contact stage's arrays at the map's friction
    values (``build_contact``) and the static patch's metrics."""
    from pipeline.stages.contact import build_contact, contact_setup  # lazy: brings in numba, rocket_fft, scipy
    from solvers.contact.surfaces import patch_metrics  # lazy: brings in numba, rocket_fft, scipy

    res = {}
    for case in CASES:
        c, pw, pr, geo, _ = contact_setup(case)
        a = build_contact(c, pw, geo, frictions=map_mus())
        res[case] = dict(c=c, geo=geo, a=a, m=patch_metrics(a["p3_static"], a["x"], a["y"]))
    return res


def write() -> str:
    plt = pyplot()

    res = positions()
    area = np.array([r["m"]["area"] for r in res.values()])
    ratio = np.array([r["m"]["ratio"] for r in res.values()])

    geo = res["default"]["geo"]
    cc = geo.config["rolling_circle_y"]

    def y_of(dy):
        try:
            return rigid_contact(geo.wheel, geo.rail_track, wheel_shift(cc, dy)).y_wheel
        except FlangeContact:
            return None

    jumps = jump_offsets(y_of, -0.016, -0.004, step=5e-5)
    first_flange = next(d for d in np.arange(0.0, 0.03, 5e-5) if y_of(d) is None)  # toward the field side
    new = {k: read_profile(k)[0] for k in ("c20_new", "bv50_new")}
    lam = {"worn pair": conicity(geo, cc),
           "new pair": conicity(type(geo)(new["c20_new"], new["bv50_new"], TrackRail(new["bv50_new"], 1 / 30),
                                          geo.r0, None, {}), cc)}

    # ---- figure 1: profiles (wheel placed over the rail at each offset, track frame) with the contact points
    fig, axs = plt.subplots(1, 3, figsize=(14, 4.2), sharey=True)
    Yr = geo.rail_track.y
    for ax, (case, r) in zip(axs, res.items()):
        g, a = r["geo"], r["a"]
        s = wheel_shift(cc, r["c"]["contact"]["dy_wr"])
        zc = float(g.z_rail(a["y_track"]))  # lower the wheel onto the rail at the contact
        yw = g.wheel.y
        ax.plot(1e3 * Yr, 1e3 * g.z_rail(Yr), "k", label="BV50 worn (1:30)")
        ax.plot(1e3 * Yr, 1e3 * TrackRail(new["bv50_new"], 1 / 30)(Yr), "k:", lw=0.8, label="BV50 new")
        zw0 = float(g.wheel(a["y_wheel"]))
        ax.plot(1e3 * (yw + s), 1e3 * (zc + zw0 - g.wheel(yw)), "C0", label="C20 worn")
        ax.plot(1e3 * (yw + s), 1e3 * (zc + zw0 - new["c20_new"](yw)), "C0:", lw=0.8, label="C20 new")
        ax.plot(1e3 * a["y_track"], 1e3 * zc, "ro", ms=6)
        ax.axvspan(1e3 * (a["y_track"] + a["y"][0]), 1e3 * (a["y_track"] + a["y"][-1]), color="r", alpha=0.08)
        ax.set_xlim(-40, 40)
        ax.set_ylim(-12, 6)
        ax.set_title(f"dy_WR = {1e3 * r['c']['contact']['dy_wr']:.0f} mm: y^W = {1e3 * a['y_wheel']:+.1f}, "
                     f"y^R = {1e3 * a['y_rail']:+.1f} mm", fontsize=9)
        ax.set_xlabel("Y track frame (mm, + field side)")
        ax.grid(alpha=0.3)
    axs[0].set_ylabel("height (mm)")
    axs[0].legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    save_figure(fig, DOCS / "contact_positions_profiles.png", dpi=90)

    # ---- figure 2: static pressure maps and outlines (same scale) + friction curves
    fig, axs = plt.subplots(2, 3, figsize=(14, 7.5))
    pmax = max(r["m"]["p_max"] for r in res.values()) / 1e9
    for col, (case, r) in enumerate(res.items()):
        a = r["a"]
        p = a["p3_static"] / 1e9
        ext = [1e3 * (a["x"][0] - a["dx"] / 2), 1e3 * (a["x"][-1] + a["dx"] / 2),
               1e3 * (a["y"][0] - a["dy"] / 2), 1e3 * (a["y"][-1] + a["dy"] / 2)]
        im = axs[0, col].imshow(p.T, origin="lower", extent=ext, vmin=0, vmax=pmax, cmap="magma", aspect="equal")
        axs[0, col].contour(1e3 * a["x"], 1e3 * a["y"], (p > 0).T.astype(float), levels=[0.5], colors="c",
                            linewidths=1)
        axs[0, col].set_xlim(-12, 12)
        axs[0, col].set_ylim(-12, 16)
        axs[0, col].set_title(f"dy_WR = {1e3 * r['c']['contact']['dy_wr']:.0f} mm: {1e6 * r['m']['area']:.0f} mm^2, "
                              f"{1e3 * r['m']['length']:.1f} x {1e3 * r['m']['width']:.1f} mm", fontsize=9)
        axs[0, col].set_xlabel("x rolling (mm)")
        axs[0, col].set_ylabel("eta lateral from the contact point (mm)")
        for i, mu in enumerate(a["mu_values"]):
            n = a["rf_n"][i]
            axs[1, col].plot(a["rf_s"][i, :n], a["rf_mu"][i, :n], color=plt.cm.viridis(i / 11), label=f"{mu:.2f}")
        axs[1, col].set_xlim(0, 0.25)
        axs[1, col].set_xlabel("slip velocity (m/s)")
        axs[1, col].grid(alpha=0.3)
    fig.colorbar(im, ax=axs[0, :].tolist(), label="p3 (GPa)", shrink=0.8)
    axs[1, 0].set_ylabel("mu_RF = F2 / F3")
    axs[1, 2].legend(title="mu", fontsize=7, ncol=2)
    save_figure(fig, DOCS / "contact_positions.png", dpi=90)

    rows = ["| dy_WR | y^W found / thesis (printed) (mm) | y^R found / thesis (mm) | contact angle | wheel / rail lateral "
            "radius (mm) | grid | elements | area (mm^2) | length x width (mm) | L/W | p_max (GPa) | approach (um) | "
            "full slip at mu = 0.3 (gamma_y) |", "|" + "---|" * 13]
    for case, r in res.items():
        a, m = r["a"], r["m"]
        yw, yr = THESIS_POSITIONS[r["c"]["contact"]["dy_wr"]]
        i03 = int(np.argmin(abs(a["mu_values"] - 0.3)))
        rad = lambda k: f"{-1e3 / k:+.0f}" if abs(k) > 1e-3 else "inf"  # noqa: E731 (+ convex)
        rows.append(f"| {1e3 * r['c']['contact']['dy_wr']:.0f} mm | {1e3 * a['y_wheel']:+.2f} / {1e3 * yw:+.0f} ({-1e3 * yw:+.0f}) | "
                    f"{1e3 * a['y_rail']:+.2f} / {1e3 * yr:+.0f} | {np.degrees(a['contact_angle']):+.1f} deg | "
                    f"{rad(a['curvature_wheel'])} / {rad(a['curvature_rail'])} | {len(a['x'])} x {len(a['y'])} | "
                    f"{m['elements']} | {1e6 * m['area']:.0f} | {1e3 * m['length']:.1f} x {1e3 * m['width']:.1f} | "
                    f"{m['ratio']:.2f} | {m['p_max'] / 1e9:.2f} | {1e6 * a['xi3_static']:.1f} | "
                    f"{a['rf_gamma_sat'][i03]:.4f} |")
    w = read_profile("c20_worn")[0]
    GAUGE = 1.435  # m, standard gauge (measured 14 mm below the crown, on the head's vertical side here)

    half_head = 0.5 * load_rail_params("bv50")[0]["head"]["width"]
    z_rc = load_wheel("c20")[0]["axle"]["rolling_circle_z"]
    rail_centre = GAUGE / 2 + half_head
    c_geo = z_rc - rail_centre
    dyr = max(abs(r["a"]["y_rail"] - THESIS_POSITIONS[r["c"]["contact"]["dy_wr"]][1]) for r in res.values())
    dyw = max(abs(r["a"]["y_wheel"] - THESIS_POSITIONS[r["c"]["contact"]["dy_wr"]][0]) for r in res.values())


    par = {k: 1e-3 * float(v) for k, v in re.findall(r"(\w+) = ([-\d.]+) mm", w.meta["wear_parameters"])}
    at_bound = [f"{k} = {1e3 * par[k]:g} mm (range {1e3 * lo:g} .. {1e3 * hi:g})" for k, (lo, hi) in zip(NAMES, BOUNDS)
                if min(abs(par[k] - lo), abs(par[k] - hi)) < 2e-6]
    sec = res["dy10"]["geo"].contact.second
    sec10 = ("at y^W = {:+.2f} mm, {:.3f} mm further from the rail".format(1e3 * sec[0], 1e3 * sec[1]) if sec
             else "more than 0.25 mm further away")
    jtxt = "; ".join(f"between {1e3 * d0:.2f} and {1e3 * d1:.2f} mm from y^W = {1e3 * y0:+.1f} to {1e3 * y1:+.1f} mm"
                     for d0, y0, d1, y1 in jumps if y1 is not None)
    text = f"""## Contact at the three positions from the profiles (C20 on BV50, worn)

Written by `pipeline/validation/writers/contact_positions.py` (`make validate`); the checks below are asserted by
`tests/contact/test_positions_validation.py`. The contact point of each SPEC 2
position is the rigid contact of the case's profiles (`pipeline.config.case_profiles.case_contact`, the one function the
contact, greens and radiate stages use; simulate, stability and listen take it from their artifacts): the
calibrated worn C20 tread `geometry/profiles/c20_worn.csv` on the calibrated worn BV50 head
`geometry/profiles/bv50_worn.csv`, the rail inclined 1:30, the wheel's rolling circle at c + dy_WR over the rail
centre (y^W and y^R both + toward the field side, the flange at negative y^W). Around it the contact stage's
own function (`pipeline.stages.contact.build_contact`) builds the gap from the profiles on the 0.5 mm grid
(dx = v dt; the potential area from the gap itself), solves NORM for the 65 kN preload and computes the
regularized friction curves with Kalker's TANG. Checked: the thesis' points in the project's convention
(below), pressures >= 0, force = preload, every curve rises monotonically from 0 to mu, and that the patches
differ (area or length/width by more than 25 % between two positions).

{chr(10).join(rows)}

Patch area from {1e6 * area.min():.0f} to {1e6 * area.max():.0f} mm^2 ({area.max() / area.min():.2f} x), length/width
from {ratio.min():.2f} to {ratio.max():.2f} ({ratio.max() / ratio.min():.2f} x). With the former nominal surfaces
(1:40 cone on the R300/R80/R13 head at the tabulated points) the three patches were the same (47 x 17 grid,
207-216 elements, p_max 1.87-1.89 GPa): the R80 shoulder under a cone at all three points. Lateral radii of the
profiles at the contact: + convex, - concave (each body seen from the other).

![profiles and contact points](validation/contact_positions_profiles.png)

![static pressure (same scale, cyan: patch outline) and friction curves](validation/contact_positions.png)

### Convention: the thesis prints y^W positive toward the flange

The thesis' table [4.1] prints (y^W, y^R) = (+5, -16), (-4, -12), (-32, +12) mm at dy_WR = -5, -10, -15 mm.
A rigid wheelset moved by dy_WR moves every wheel point by dy_WR over the rail, so the contact pair must satisfy
y^R = dy_WR + y^W + c with ONE constant c (the wheel's rolling circle over the rail centre for the centred
wheelset). With the printed numbers y^R - dy_WR - y^W = -16, -6, +59 mm: no common c. With the printed y^W
negated (y^W = -5, +4, +32 mm) and the rail points as printed, y^R - dy_WR - y^W = -6, -6, -5 mm: c = -17/3 mm
= -5.67 mm, residuals 1/3, 1/3, 2/3 mm, i.e. the table's integer-mm rounding. So the printed y^W is positive
toward the flange while its y^R is positive toward the field side. This project keeps SPEC 2's axes (y^W and
y^R both + toward the field side, the flange at negative y^W); the table in that convention is
`solvers.constants.THESIS_CONTACT_POINTS_FIELD` (y^W = -printed, next to the printed
`THESIS_CONTACT_POSITIONS`), and c is `contact.rolling_circle_y` (default -17/3 mm,
`solvers.constants.thesis_rolling_circle_offset`). Reading: dy_WR < 0 moves the wheel toward the track centre
(its gauge side) -- the inner wheel of a curve, pushed inward as the wheelset runs toward the outer rail --
so its contact runs toward the field side of the tread and the flange stays clear of the rail (flange contact
only when the wheelset moves the other way, from dy_WR = {1e3 * first_flange:+.2f} mm). The default case
(dy_WR = -15 mm) runs on the field side of the tread (y^W = +32 mm) and of the head (y^R = +12 mm). (The
previous profiles branch flipped the rail instead, Y = -y^R with c = +5.67 mm, which put the default case on
the gauge side of the head, y^R = -11 mm, with its wheel point near the flange root: wrong.) A plausibility
check of c from the geometry: on 1435 mm track (gauge face {1e3 * GAUGE / 2:.1f} mm from the track centre, BV50
head half-width {1e3 * half_head:.1f} mm: rail centre at {1e3 * rail_centre:.1f} mm) the C20's rolling circle
({1e3 * z_rc:.1f} mm from the wheelset centre) lies at c = {1e3 * c_geo:+.1f} mm for the centred wheelset: the
same sign as the table's -5.67 mm.

### Calibrated vs predicted

Calibrated (fitted, `make calibrate`, `pipeline/validation/calibrate_profiles.py` + `geometry/calibration.py`; targets: the
three wheel points y^W = -5, +4, +32 mm, nothing else): the 8 wear parameters -- `{w.meta['wear_parameters']}`;
fitted points `{w.meta['fit_contact_points']}`; objective {w.meta['fit_objective']}. Derived from the table
itself, not fitted: c = -17/3 mm. Inputs: the new C20 tread and BV50 head, the 1:30 rail inclination (Swedish
track practice, as recalled). Wear model (`geometry/wear.py`): the new profile moved inward along its normal by
C2 depth functions -- a hollow band on the tread; on the head a top band and gauge-face wear that ramps up over
12 mm of arc length from `gauge_start`. Parameters at a bound of their range: {', '.join(at_bound) or 'none'}.
The objective adds 0.05 x the squared depths (mm^2): the least wear that puts the contact at the three points,
so the worn shapes are one possible pair, not a reconstruction of the measured profiles. Constraints of the fit
besides the targets: each fitted point moves < 3 mm for +-0.5 mm of offset (not at the brink of a jump), any
other contact zone lies >= 0.15 mm further from the rail (one patch under the static load; on the fit's
uniform grid -- with the written, resampled profiles the next zone at -10 mm is {sec10}), the worn head stays
convex on |y^R| < 22 mm (a positive curvature is penalised; the fit keeps it below +0.003 1/m, i.e. flat,
where the top wear is deepest). Pipeline contact points (the case files, spline profiles): y^W within
{1e3 * dyw:.2f} mm of the targets. Predictions (not fitted): the rail points y^R (within {1e3 * dyr:.2f} mm of the
table), the contact angles, radii, gaps, patch sizes and shapes, pressures and friction curves above.

Checks the calibration was not fitted to (chosen: intermediate offsets and the jump; also the equivalent conicity):
- the contact point moves monotonically toward the field side of the tread from -5 to -15 mm; -7.5 and -12.5 mm
  lie between their neighbours (`tests/profiles/test_calibration.py`); near -10.6 mm it jumps from the
  flange-side flank of the hollow band to its field side (jumps > 2 mm in 0.05 mm steps: {jtxt}); flange
  contact only from
  dy_WR = {1e3 * first_flange:+.2f} mm (the wheelset moved toward the field side);
- equivalent conicity Delta r / 2u at u = 3 mm (symmetric wheelset, same c): worn pair {lam['worn pair']:+.3f},
  new pair {lam['new pair']:+.3f} (measured worn profiles usually show a higher conicity than new ones, Polach &
  Nicklisch, Wear 2016). The pair reproduces the squeal positions (-5 .. -15 mm); it is one possible worn pair,
  not a reconstruction of the measured one.
"""
    return save_fragment("31_contact_positions.md", text)


if __name__ == "__main__":
    write()
