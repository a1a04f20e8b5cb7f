"""The line study's figures read as what they show (issue 33): no quiet curve drawn at a level (the
level-against-radius plot put quiet curves at an arbitrary 79.6 dB(A), the chainage plot at 0 dB(A)):
they sit on the axis floor, whose tick reads "quiet", below every level tick; the chainage plot's radius
axis is labelled (it had one tick label on a log axis).  Asserted on the figures' data, from a
synthetic line like pipeline/studies/metro_line.csv (radii 40-600 m, dry and wet)."""
from __future__ import annotations

import numpy as np

RADII = np.array([180, 415, 50, 455, 95, 260, 40, 600, 130, 330, 70, 220], float)


def _line():
    n = RADII.size
    chain = 350.0 + 420.0 * np.arange(n)
    length = 30.0 + np.round(RADII / 40) * 10
    radius, level, squeals, cond, ch, ln = [], [], [], [], [], []
    for i, R in enumerate(RADII):
        for c, limit in (("dry", 300.0), ("wet", 90.0)):       # dry squeals up to 300 m, wet below 90 m
            s = R <= limit
            radius.append(R), cond.append(c), squeals.append(s), ch.append(chain[i]), ln.append(length[i])
            level.append(95.0 - 10 * np.log10(R / 40.0) if s else np.nan)
    return tuple(np.array(x) for x in (ch, ln, radius, level, squeals, cond))


def _quiet_and_level_ticks(ax):
    """(y of the quiet markers (open), y of the squealing ones, {tick y: label} inside the axis)."""
    ax.figure.canvas.draw()
    lo, hi = sorted(ax.get_ylim())
    quiet = [y for ln in ax.get_lines() if ln.get_marker() not in ("None", None, "") and ln.get_mfc() == "none"
             for y in ln.get_ydata()]
    loud = [y for ln in ax.get_lines() if ln.get_marker() not in ("None", None, "") and ln.get_mfc() != "none"
            and ln.get_linestyle() in ("None", "") for y in ln.get_ydata()]
    ticks = {float(t): lab.get_text() for t, lab in zip(ax.get_yticks(), ax.get_yticklabels()) if lo <= t <= hi}
    return np.array(quiet, float), np.array(loud, float), ticks


def _assert_quiet_on_the_floor(ax):
    quiet, loud, ticks = _quiet_and_level_ticks(ax)
    assert quiet.size and loud.size
    floor = [t for t, s in ticks.items() if s == "quiet"]
    assert len(floor) == 1, ticks                              # the floor is labelled "quiet" ...
    assert np.allclose(quiet, floor[0])                        # ... and every quiet curve is on it
    levels = {t: s for t, s in ticks.items() if s != "quiet"}
    assert len(levels) >= 3 and all(t > floor[0] for t in levels), ticks   # levels above it, none at it
    for t, s in levels.items():                                # the level ticks read their own values
        assert float(s.replace("\u2212", "-")) == t
    assert loud.min() > floor[0] and loud.min() >= min(levels) - 10


def test_level_radius_shows_quiet_curves_as_quiet():
    from postprocess.plots.line import level_radius_figure

    ch, ln, R, L, S, C = _line()
    fig = level_radius_figure(R, L, S, C, [(1.0, 300.0, "R <= 300 m"), (300.0, 500.0, "300-500 m")])
    ax = next(a for a in fig.axes if a.get_ylabel().startswith("L_pA"))
    _assert_quiet_on_the_floor(ax)


def test_chainage_radius_axis_is_labelled_and_quiet_curves_are_quiet():
    from postprocess.plots.line import chainage_figure

    ch, ln, R, L, S, C = _line()
    pen = {"CNOSSOS-EU": np.where(R <= 300, 8.0, np.where(R <= 500, 5.0, 0.0))}
    fig = chainage_figure(ch, ln, R, L, S, C, pen, ids=[f"C{i}" for i in range(R.size)])
    a = fig.axes[0]
    fig.canvas.draw()
    lo, hi = a.get_ylim()
    labels = [(float(t), lab.get_text()) for t, lab in zip(a.get_yticks(), a.get_yticklabels())
              if lo <= t <= hi and lab.get_text()]
    assert len(labels) >= 3, labels
    for t, s in labels:                                        # plain numbers in metres, each its own value
        assert float(s) == t, labels
    assert min(t for t, _ in labels) <= RADII.min() * 1.6 and max(t for t, _ in labels) >= RADII.max() / 1.6
    b = next(x for x in fig.axes if x.get_ylabel().startswith("L_pA"))
    _assert_quiet_on_the_floor(b)


def test_no_squeal_at_all_is_all_quiet():
    from postprocess.plots.line import level_radius_figure

    ch, ln, R, L, S, C = _line()
    fig = level_radius_figure(R, np.full(R.size, np.nan), np.zeros(R.size, bool), C, [])
    ax = fig.axes[0]
    quiet, loud, ticks = _quiet_and_level_ticks(ax)
    assert quiet.size == R.size and loud.size == 0 and list(ticks.values()) == ["quiet"]
