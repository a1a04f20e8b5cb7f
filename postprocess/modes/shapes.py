"""3D renders of axisymmetric wheel mode shapes (pyvista, offscreen) and a
gallery of them (matplotlib).  Functions return images / figures and write
nothing: the pipeline's ``shapes`` stage saves them (``pipeline.store.atomic``).
The geometry (swept surface, harmonic displacement) is
``postprocess.modes.geometry``.

Offscreen rendering: the module selects VTK's EGL render window (no X
display needed) unless ``VTK_DEFAULT_OPENGL_WINDOW`` is already set.
"""

from __future__ import annotations

import copy
import os
from typing import Sequence

# Must be set before pyvista / vtk are imported anywhere in the process.
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import numpy as np  # noqa: E402
import pyvista as pv  # noqa: E402

from postprocess.modes.geometry import displacement_vectors, sweep_surface  # noqa: E402

pv.OFF_SCREEN = True
#: pyvista's theme without multisampling: llvmpipe's 8x MSAA (the default) is ~40 % of a render's
#: time on one thread, for edges hardly seen at this size
THEME = copy.deepcopy(pv.global_theme)
THEME.multi_samples = 1

__all__ = ["render_mode", "gallery_figure", "tile"]

#: Default deformation amplitude as a fraction of the maximum radius.
DEFAULT_SCALE_FRACTION = 0.06
#: A render's colour bar starts at this fraction of its width (its labels to the right), its title text
#: ends above this fraction of its height: the gallery crops both off and draws one colour bar for all
BAR_X = 0.86
TEXT_Y = 0.08
CMAP = "turbo"
BAR_LABEL = "relative displacement |u| / max |u| (each mode scaled to its own maximum)"


# ---------------------------------------------------------------------------
# Rendering
# ---------------------------------------------------------------------------


def _title(label: str, freq_hz) -> str:
    label = str(label)
    text = f"(n, m, class) = {label}" if label.startswith("(") else label
    if freq_hz is not None:
        text += f"   {float(freq_hz):.1f} Hz"
    return text


def render_mode(
    points_rz,
    boundary_edges,
    U,
    n: int,
    label: str,
    freq_hz=None,
    scale: float | None = None,
    window_size=(800, 600),
    n_phi: int = 120,
):
    """Render one mode shape of the body of revolution; returns the RGB image
    (H, W, 3) uint8 (``window_size`` = (W, H)).

    The deformed surface is coloured by displacement magnitude (normalised to
    the maximum), the undeformed body is drawn as a translucent grey surface
    with its feature edges, the title reads
    ``"(n, m, class) = <label>   <freq> Hz"``. Camera: oblique 3/4 view with
    the wheel axis vertical on screen so axial motion is clearly visible.
    ``scale`` (m) is the largest displayed displacement; default is 6 % of the
    maximum radius.
    """
    pts = np.asarray(points_rz, dtype=float)
    surf = sweep_surface(pts, boundary_edges, n_phi=n_phi)
    rmax = float(np.max(np.abs(pts[:, 0])))
    if scale is None:
        scale = DEFAULT_SCALE_FRACTION * rmax
    u = displacement_vectors(surf, U, n, scale)
    mag = np.linalg.norm(u, axis=1)

    base = surf.mesh
    deformed = base.copy()
    deformed.points = np.asarray(base.points) + u
    deformed.point_data["rel. displ."] = mag / scale if scale > 0 else mag

    pl = pv.Plotter(off_screen=True, window_size=tuple(int(v) for v in window_size), theme=THEME)
    try:
        pl.set_background("white")
        # Undeformed reference: translucent grey body + its sharp edges.
        pl.add_mesh(base, color="lightgrey", opacity=0.15, show_scalar_bar=False)
        edges = base.extract_feature_edges(
            feature_angle=30.0,
            boundary_edges=True,
            non_manifold_edges=False,
            manifold_edges=False,
        )
        if edges.n_points:
            pl.add_mesh(edges, color="grey", line_width=1, opacity=0.6, show_scalar_bar=False)
        pl.add_mesh(
            deformed,
            scalars="rel. displ.",
            cmap=CMAP,
            clim=(0.0, 1.0),
            smooth_shading=True,
            split_sharp_edges=True,
            show_scalar_bar=True,
            scalar_bar_args=dict(
                title="rel. displ.",
                color="black",
                vertical=True,
                position_x=BAR_X,
                position_y=0.15,
                width=0.07,
                height=0.6,
                n_labels=3,
                fmt="%.1f",
                title_font_size=14,
                label_font_size=12,
            ),
        )
        pl.add_text(_title(label, freq_hz), position="upper_left", font_size=12, color="black")

        # Oblique 3/4 view: axis (Z) vertical on screen, looking down ~30 deg
        # onto the wheel face, so axial motion appears as vertical waviness.
        zc = float(np.mean(pts[:, 1]))
        elev = np.radians(30.0)
        azim = np.radians(-60.0)
        direction = np.array(
            [np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)]
        )
        focal = np.array([0.0, 0.0, zc])
        pl.camera_position = [tuple(focal + direction), tuple(focal), (0.0, 0.0, 1.0)]
        pl.reset_camera()
        pl.camera.zoom(1.25)
        image = pl.screenshot(None, return_img=True)
    finally:
        pl.close()
    return np.asarray(image)


def tile(image):
    """A render as a gallery tile: without its own colour bar (right of ``BAR_X``) and its title text
    (above ``TEXT_Y``), which at a tile's size cannot be read; the gallery has one of each."""
    a = np.asarray(image)
    h, w = a.shape[:2]
    return a[int(TEXT_Y * h):, : max(1, int((BAR_X - 0.015) * w))]


def gallery_figure(images: Sequence, labels: Sequence[str], ncols: int = 4):
    """A gallery of images (arrays as ``render_mode`` returns) in one figure, one
    titled tile per image (``tile``: without the render's own colour bar and title)
    and one colour bar for all at the top, readable at the gallery's size (every
    render has the same scale, 0-1); matplotlib's Agg canvas, no pyplot state.  Save
    it with ``facecolor="white"``."""
    from matplotlib import colormaps  # lazy: brings in matplotlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # lazy: brings in matplotlib
    from matplotlib.cm import ScalarMappable  # lazy: brings in matplotlib
    from matplotlib.colors import Normalize  # lazy: brings in matplotlib
    from matplotlib.figure import Figure  # lazy: brings in matplotlib

    labels = [str(s) for s in labels]
    if len(images) == 0:
        raise ValueError("gallery_figure needs at least one image")
    if len(images) != len(labels):
        raise ValueError("images and labels must have the same length")
    ncols = max(1, min(int(ncols), len(images)))
    nrows = -(-len(images) // ncols)

    arrays = [tile(a) for a in images]
    h, w = arrays[0].shape[:2]
    tile_w = 4.0
    tile_h = tile_w * h / w + 0.4  # room for the title
    bar_h = 1.3                    # inches at the top: the colour bar and its label
    height = nrows * tile_h + bar_h
    # 80 dpi: tiles of ~320 px, enough to recognise a mode, and a gallery of
    # some 40 modes stays around a megabyte
    fig = Figure(figsize=(ncols * tile_w, height), dpi=80)
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False)
    for i, ax in enumerate(axes.ravel()):
        ax.set_axis_off()
        if i < len(arrays):
            ax.imshow(arrays[i])
            ax.set_title(labels[i], fontsize=11)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=1 - bar_h / height, wspace=0.02, hspace=0.12)
    width = min(0.6, 8.0 / (ncols * tile_w))       # at most 8 in wide
    cax = fig.add_axes([0.5 - width / 2, 1 - 0.45 / height, width, 0.22 / height])
    bar = fig.colorbar(ScalarMappable(Normalize(0.0, 1.0), colormaps[CMAP]), cax=cax, orientation="horizontal",
                       ticks=[0.0, 0.25, 0.5, 0.75, 1.0])
    bar.ax.tick_params(labelsize=12)
    bar.set_label(BAR_LABEL, fontsize=12)
    bar.ax.xaxis.set_label_position("bottom")
    return fig
