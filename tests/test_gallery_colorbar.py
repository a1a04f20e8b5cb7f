"""The wheel-mode gallery's colour scale can be read (issue 33): every render carries its own small colour
bar, which the gallery shrank to a few pixels per tile (labels ~5 px high).  The gallery now shows each
render without it and one colour bar for all (every render has the same 0-1 scale) with labels at 12 pt.
Asserted on a real render (pyvista, offscreen) of an annular disc's mode, at the stage's window size."""
from __future__ import annotations

import os

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import numpy as np  # noqa: E402

from postprocess.modes import geometry as mg  # noqa: E402
from postprocess.modes import shapes as ms  # noqa: E402
from tests.test_mode_shapes import RI, RO, annulus_section  # noqa: E402


def _chroma(img) -> np.ndarray:
    a = np.asarray(img, float)
    a = a / 255.0 if a.max() > 1.0 else a
    return a[..., :3].max(axis=2) - a[..., :3].min(axis=2)


def test_gallery_has_one_readable_colour_bar_and_tiles_without_theirs():
    pts, tris = annulus_section()
    U = np.zeros((len(pts), 3))
    U[:, 1] = (pts[:, 0] - RI) / (RO - RI)
    image = ms.render_mode(pts, mg.boundary_edges_from_triangles(tris), U, 2, "(2, 0, a)", 1143.2)
    h, w = image.shape[:2]
    bar = _chroma(image[int(0.15 * h):int(0.75 * h), int(0.86 * w):int(0.93 * w)])
    assert (bar > 0.25).mean() > 0.15                         # the render's own colour bar is where it is put
    fig = ms.gallery_figure([image] * 7, [f"mode {i}" for i in range(7)], ncols=5)
    fig.canvas.draw()
    tiles = [ax for ax in fig.axes if ax.images]
    assert len(tiles) == 7
    for ax in tiles:                                           # no colour bar inside a tile: the render left of it
        shown = np.asarray(ax.images[0].get_array())
        assert shown.shape[1] <= 0.86 * w and shown.shape[0] < h
        top = int(round(h - shown.shape[0]))
        assert np.array_equal(shown, image[top:, :shown.shape[1]])
    bars = [ax for ax in fig.axes if not ax.images and "displacement" in (ax.get_xlabel() + ax.get_ylabel())]
    assert len(bars) == 1
    labels = [t for t in bars[0].get_xticklabels() + bars[0].get_yticklabels() if t.get_text()]
    assert len(labels) >= 3 and min(t.get_fontsize() for t in labels) >= 10
    # at the gallery's 80 dpi its labels are at least 12 px high (the render's, shrunk, were ~5 px)
    r = fig.canvas.get_renderer()
    assert min(t.get_window_extent(r).height for t in labels) >= 12
