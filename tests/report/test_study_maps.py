"""The map study's figure and L_W table (issue 27's newcomer list): the squealing mode as a
categorical colour with its label, the sound's frequency (not a harmonic of F2), oscillations
below 200 Hz marked as the wheelset's, a signed creepage axis, legends."""
from __future__ import annotations

import numpy as np

from pipeline.study.kinds.map import lw_table
from postprocess.plots.study import LOW_LABEL, map_figure, mode_categories

GAMMA = np.array([-0.06, -0.04, -0.02, -0.01])
MU = np.array([0.3, 0.4, 0.5])
MODE_F = np.array([6.8, 241.0, 336.9, 434.1, 1147.9])
MODE_L = ["(1,0,s)", "(1,0,a)", "(0,0,a)", "(2,0,a)", "(3,0,a)"]


def fields():
    L = np.array([[5.0, 53.0, 50.0, 20.0], [45.0, 52.0, 49.0, 8.0], [44.0, 51.0, np.nan, 30.0]])
    fd = np.array([[434.0, 869.4, 434.5, 70.0], [1148.0, 869.0, 435.0, 434.0], [1148.1, 868.8, np.nan, 71.0]])
    fs = np.array([[np.nan, 434.7, 434.5, 70.0], [1148.2, 434.6, 435.0, np.nan], [1148.1, 434.4, np.nan, 71.0]])
    LW = np.where(np.isfinite(fs), 100.0, np.nan)
    return {"L_F2": L, "f_dominant": fd, "f_sound": fs, "L_W": LW}


def test_mode_categories_use_the_sound_not_the_force_harmonic():
    cat, names = mode_categories(fields(), MODE_F, MODE_L)
    assert names[0] == LOW_LABEL
    lab = {k: names[k].split()[0] for k in range(1, len(names))}
    # 869 Hz in F2 is the second harmonic of a 434.6 Hz sound: the (2,0,a) mode
    assert lab[cat[0, 1]] == "(2,0,a)" and lab[cat[1, 1]] == "(2,0,a)" and lab[cat[2, 1]] == "(2,0,a)"
    assert lab[cat[1, 0]] == "(3,0,a)"
    assert cat[0, 3] == 0 and cat[2, 3] == 0               # 70 Hz: the wheelset, not squeal
    assert cat[0, 0] == -1 and cat[1, 3] == -1 and cat[2, 2] == -1   # below 10 dB, no data
    assert sorted(set(names[1:])) == ["(2,0,a) 434 Hz", "(3,0,a) 1148 Hz"]


def test_map_figure_has_legends_a_signed_axis_and_marks_low_oscillations():
    from matplotlib.patches import Rectangle

    fig = map_figure(GAMMA, MU, fields(), "t", modes=(MODE_F, MODE_L))
    axs = fig.axes[:4] if len(fig.axes) == 4 else [ax for ax in fig.axes if ax.get_label() != "<colorbar>"][:4]
    mode_ax = axs[1]
    texts = [t.get_text() for t in mode_ax.get_legend().get_texts()]
    assert texts == [LOW_LABEL, "(2,0,a) 434 Hz", "(3,0,a) 1148 Hz"]
    lo, hi = axs[0].get_xlim()
    assert lo < -0.06 and hi < 0                          # signed creepage, not |gamma_y|
    assert axs[2].get_xlabel() == "gamma_y (lateral creepage, signed)"
    hatched = [p for p in mode_ax.patches if isinstance(p, Rectangle) and p.get_hatch() == "xx"]
    assert len(hatched) == 2
    assert axs[3].get_legend() is not None and "sound's frequency" in axs[3].get_title()


def test_lw_table_lists_level_and_mode_per_cell():
    text = lw_table(fields(), GAMMA, MU, 10.0, (MODE_F, MODE_L))
    rows = [r for r in text.splitlines() if r.startswith("| -")]
    assert rows[0] == "| -0.06 |  | 100 (3,0,a) | 100 (3,0,a) |"
    assert rows[1] == "| -0.04 | 100 (2,0,a) | 100 (2,0,a) | 100 (2,0,a) |"
    assert rows[3] == "| -0.01 | LF |  | LF |"
