"""Friction curves at any value (issue 26), validated: the curve at mu = 0.33 (a value the contact
stage did not build before) between its neighbours 0.30 and 0.35, self-similar with them, and its
slope at zero slip against Kalker's linear theory (pipeline/validation/references/kalker.py, Kalker's Table
E.3), on the Hertzian wheel/rail contact of SPEC 6 and on the default case's worn-profile contact.
Written to docs/validation/32_friction_values.md (+ friction_values.png) by this writer (`make validate`);
the limits it states are asserted by tests/contact/test_friction_values_validation.py on ``measures()``."""
import numpy as np

from pipeline.validation.writers import DOCS, pyplot, save_figure, save_fragment
from pipeline.caches.friction_curves import Friction, compute_curve
from pipeline.validation.references.kalker import creep_coefficient

MUS = (0.30, 0.33, 0.35)


def _curves(p3, dx, dy, v, E, nu):
    return {mu: compute_curve(p3, dx, dy, v, Friction.coulomb(mu), E, nu) for mu in MUS}


def _measures(curves, F3, v, kalker_k):
    """Ordering, self-similarity and zero-slip slope of the curves (dict mu -> curve)."""
    from solvers.contact.friction import mu_rf  # lazy: brings in numba, rocket_fft, scipy

    s = np.linspace(0, curves[0.33]["s"][-1], 4001)
    m = {mu: np.array([mu_rf(x, c["s"], c["mu_rf"], c["slope"]) for x in s]) for mu, c in curves.items()}
    below = float(np.max(m[0.30] - m[0.33]))                # <= 0 (up to interpolation noise) when ordered
    above = float(np.max(m[0.33] - m[0.35]))
    c30 = curves[0.30]
    scaled = np.array([mu_rf(x * 0.30 / 0.33, c30["s"], c30["mu_rf"], c30["slope"]) for x in s]) / 0.30
    similar = float(np.max(np.abs(m[0.33] / 0.33 - scaled)))
    k = float(curves[0.33]["creep_stiffness"])
    slope_num = float(curves[0.33]["slope"][0])             # d mu_RF / ds at s = 0 (one-sided, first node)
    slope_lin = k / (v * F3)                                 # the TANG no-slip stiffness on the grid
    slope_kalker = kalker_k / (v * F3)
    return dict(m=m, s=s, below=below, above=above, similar=similar, k=k, slope_num=slope_num,
                slope_lin=slope_lin, slope_kalker=slope_kalker, plateau=float(curves[0.33]["mu_rf"][-1]))


def measures() -> dict:
    """contact name -> (the curves' measures at mu = 0.30, 0.33, 0.35, (a, b)) on the Hertzian contact of
    SPEC 6 and on the default case's worn-profile contact."""
    from solvers.contact.static import static_contact  # lazy: brings in numba, rocket_fft, scipy

    from pipeline.stages.contact import contact_setup  # lazy: brings in numba, rocket_fft, scipy
    from solvers.contact.surfaces import patch_metrics  # lazy: brings in numba, rocket_fft, scipy
    from pipeline.validation.references.contact import DX, E, NU, V, hertz_case  # lazy: brings in scipy
    from solvers.contact.norm import approach_for_load  # lazy: brings in numba, scipy

    G = E / (2 * (1 + NU))
    res = {}
    # 1. the Hertzian contact of SPEC 6 (R 0.39 m on a 0.3 m crown, 65 kN): Kalker's C22 is exact here
    _, _, h, H = hertz_case(dx=DX, dy=DX)
    _, ns = approach_for_load(65e3, h, DX, DX)
    kal = G * H.a * H.b * creep_coefficient("C22", H.a, H.b, NU)
    res["Hertz (SPEC 6)"] = _measures(_curves(ns.p, DX, DX, V, E, NU), ns.F3, V, kal), (H.a, H.b)
    # 2. the default case's contact (worn profiles, not Hertzian): Kalker with the patch's half length/width
    c, pw, _, geo, _ = contact_setup("default")
    Ew, nuw = pw["material"]["E"], pw["material"]["nu"]
    v, dt, F_L = c["kinematics"]["speed"], c["time"]["dt"], c["loading"]["preload"]
    x, y, gap, A, B, xi, st = static_contact(geo, Ew, nuw, F_L, v * dt)
    pm = patch_metrics(st.p, x, y)
    a, b = 0.5 * pm["length"], 0.5 * pm["width"]
    kal = Ew / (2 * (1 + nuw)) * a * b * creep_coefficient("C22", a, b, nuw)
    res["default case (worn C20/BV50)"] = _measures(_curves(st.p, v * dt, float(y[1] - y[0]), v, Ew, nuw),
                                                    F_L, v, kal), (a, b)
    return res


def write() -> str:
    plt = pyplot()
    res, rows = measures(), []
    fig, axs = plt.subplots(1, 2, figsize=(11, 4))
    for ax, (name, (r, (a, b))) in zip(axs, res.items()):
        for mu, col in zip(MUS, ("C0", "C3", "C2")):
            ax.plot(r["s"], r["m"][mu], color=col, lw=2 if mu == 0.33 else 1, label=f"mu = {mu:g}")
        sl = r["s"][r["s"] < 0.6 * 0.33 / r["slope_kalker"]]
        ax.plot(sl, r["slope_kalker"] * sl, "k--", lw=1, label="Kalker linear theory (C22)")
        ax.set_xlim(0, 4 * 0.33 / r["slope_lin"])
        ax.set_xlabel("slip velocity s (m/s)")
        ax.set_title(f"{name}: a = {1e3 * a:.1f} mm, b = {1e3 * b:.1f} mm", fontsize=9)
        ax.grid(alpha=0.3)
        rows.append(f"| {name} | {r['plateau']:.5f} | {r['below']:.1e} / {r['above']:.1e} | {r['similar']:.1e} | "
                    f"{r['slope_num']:.3f} | {r['slope_lin']:.3f} | {r['slope_kalker']:.3f} "
                    f"({100 * (r['slope_lin'] / r['slope_kalker'] - 1):+.1f} %) |")
    axs[0].set_ylabel("mu_RF = F2 / F3")
    axs[0].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, DOCS / "friction_values.png", dpi=90)

    text = f"""## Friction curves at any value (issue 26)

The contact stage builds the regularized friction curve mu_RF(s) (SPEC 4.4, thesis [4.36-4.37]: steady
TANG over the creepage, F2/F3) for the case's own friction, and a study for its grid, each once per
contact and cached by value (`pipeline.caches.friction_curves`); before, only mu = 0.10 .. 0.60 in steps of 0.05 existed.
A value off that grid, mu = 0.33, against its neighbours 0.30 and 0.35 and against Kalker's linear theory
(`pipeline/validation/writers/friction_values.py`; asserted by `tests/contact/test_friction_values_validation.py`):

| contact | mu_RF at the end (mu = 0.33) | max(mu_RF(0.30) - mu_RF(0.33)) / max(mu_RF(0.33) - mu_RF(0.35)) | self-similarity: max \\|mu_RF(s; 0.33)/0.33 - mu_RF(0.30 s/0.33; 0.30)/0.30\\| | secant d mu_RF/ds over the first node (s/m) | no-slip TANG k/(v F3) | Kalker G a b C22/(v F3) |
|---|---:|---:|---:|---:|---:|---:|
{chr(10).join(rows)}

The curve at 0.33 lies between its neighbours at every slip speed (they coincide in the no-slip start,
where the friction level does not enter: the differences there are interpolation noise, < 1e-5), reaches
0.33 on the plateau, and is the curve at 0.30 stretched by 0.33/0.30 in both axes (without spin the
problem is self-similar), to the Hermite interpolation's error. Its initial slope is the no-slip creep
stiffness on the grid, which matches Kalker's linear theory (C22 from Kalker's Table E.3, interpolated to
nu = 0.3 and the semi-axis ratio) on the Hertzian contact within a few per cent (the 0.5 mm grid); on the
default case's worn-profile patch (not an ellipse) Kalker's value with the patch's half length and half
width is an estimate only.

![friction curves at 0.30, 0.33, 0.35](friction_values.png)
"""
    return save_fragment("32_friction_values.md", text)


if __name__ == "__main__":
    write()
