"""bogie.png reads as the bogie in its curve (issue 33): every wheel's contact point drawn on its rail (the
wheels were drawn ~0.4 m off the rails: the lateral shift magnified 25 times for the wheels, not for
the rails), the outer wheels on the outer rail, and the left panel's title inside the left panel (it ran
into the right one).  Asserted on the figure's data, from an r150-like operating point (the steady
curving's numbers of `make curve CURVE=r150`, rounded)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from tests.verdict.points import operating_point


NAN = math.nan
# wheel, dy_wr (m), angle of attack (rad), gamma_x, gamma_y, contact points
R150 = [("a1o", +0.0153, 0.01142, -0.0087, +0.0114, 2), ("a1i", -0.0153, 0.01142, -0.0053, -0.0114, 1),
        ("a2o", +0.0067, -0.00043, -0.0022, -0.0004, 1), ("a2i", -0.0067, -0.00043, +0.0038, +0.0004, 1)]


def _inputs(radius=150.0, squeal="a1i"):
    from pipeline.config.curve_inputs import read_curve

    info = read_curve("r150", radius_m=radius, speed_kmh=50.0, cant_mm=0.0)
    points = [operating_point(wheel=w, axle=int(w[1]), side="outer" if w.endswith("o") else "inner", dy_wr=dy,
                     angle_of_attack=aoa, gamma_x=gx, gamma_y=gy, wheel_load=65e3, contact_points=n)
              for w, dy, aoa, gx, gy, n in R150]
    rows = [{"wheel": w, "squeals": w == squeal, "L_pA": 78.3 if w == squeal else NAN,
             "screen_sigma": 1.8 if w == squeal else NAN, "f_squeal": 435.0 if w == squeal else NAN,
             "mode": "(2,0,a)" if w == squeal else ""} for w, *_ in R150]
    return info, points, rows


def _rails_and_wheels(ax):
    rails = [ln for ln in ax.get_lines() if len(ln.get_xdata()) >= 50 and ln.get_linestyle() == "-"]
    dots = [ln for ln in ax.get_lines() if ln.get_marker() == "o" and len(ln.get_xdata()) == 1]
    return rails, dots


@pytest.mark.parametrize("radius", [150.0, 75.0, 1000.0])
def test_wheels_drawn_on_their_rails(radius):
    from pipeline.curve.figures import bogie_figure

    fig = bogie_figure(*_inputs(radius))
    ax = fig.axes[0]
    rails, dots = _rails_and_wheels(ax)
    assert len(rails) == 2 and len(dots) == 4
    outer = max(rails, key=lambda ln: np.mean(ln.get_ydata()))
    for dot in dots:
        x, y = float(dot.get_xdata()[0]), float(dot.get_ydata()[0])
        off = [abs(y - np.interp(x, ln.get_xdata(), ln.get_ydata())) for ln in rails]
        assert min(off) < 0.03, (x, y, off)                     # on a rail, within 3 cm (of a 3 m plot)
    # the outer wheels (drawn above the centre line) on the outer rail
    ys = sorted(float(d.get_ydata()[0]) for d in dots)
    assert np.allclose(ys[2:], np.interp(0.0, outer.get_xdata(), outer.get_ydata()), atol=0.05)


def test_title_inside_the_left_panel():
    from pipeline.curve.figures import bogie_figure

    fig = bogie_figure(*_inputs())
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    left, right = fig.axes[0], fig.axes[1]
    title = left.title.get_window_extent(r)
    assert title.x1 <= right.get_tightbbox(r).x0, (title, right.get_tightbbox(r))
    assert title.x0 >= 0 and title.x1 <= fig.bbox.x1
