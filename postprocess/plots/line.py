"""Figures of the line study (issue 27), from plain arrays; each function returns a matplotlib figure.

``level_radius_figure``: the squeal level of every curve against its radius, squealing and quiet curves
and the friction conditions marked, the two rules' radius classes shaded.  ``chainage_figure``: the
line along its chainage: the radius of each curve, the level per friction condition, and the penalty
each rule applies beside it.
"""
from __future__ import annotations

import numpy as np

MARKERS = ("o", "s", "^", "D", "v", "P")
COLOURS = ("tab:red", "tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:brown")


def _plt():
    import matplotlib  # lazy: brings in matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: brings in matplotlib

    return plt


NICE_RADII = (10, 15, 20, 30, 40, 50, 75, 100, 150, 200, 300, 400, 500, 750, 1000, 1500, 2000, 3000, 5000, 10000,
              20000)


def _radius_ticks(lo: float, hi: float) -> list[float]:
    """Radii (m) to label a log axis from lo to hi: the round values inside, at least three (every one of
    NICE_RADII when fewer than six fit, else every other)."""
    inside = [t for t in NICE_RADII if lo <= t <= hi]
    if len(inside) < 3:
        inside = sorted({float(f"{x:.2g}") for x in np.geomspace(lo, hi, 5)[1:-1]} | set(inside))
    return inside if len(inside) < 8 else inside[::2]


def _quiet_floor(ax, floor: float, levels: np.ndarray, pad_top: float) -> None:
    """The level axis with a floor for quiet curves: the level ticks over the squealing levels (none of
    them at or below the floor), the floor's tick labelled "quiet" and a dotted line between the two, so
    that a quiet curve is not read as a level.  ``levels``: the squealing curves' levels (may be empty)."""
    from matplotlib.ticker import MaxNLocator  # lazy: brings in matplotlib

    if levels.size:
        lo, hi = float(np.min(levels)), float(np.max(levels))
        ticks = [t for t in MaxNLocator(5, steps=[1, 2, 2.5, 5, 10]).tick_values(lo - 2, hi + pad_top)
                 if lo - 4 <= t <= hi + pad_top]
        gap = floor + 0.5 * (lo - 3 - floor)
        ax.axhline(gap, color="0.5", lw=0.8, ls=":")
        ax.set_ylim(floor - 3, hi + pad_top)
    else:
        ticks = []
        ax.set_ylim(floor - 1, floor + 1)
    ax.set_yticks([floor, *ticks], ["quiet", *(f"{t:g}" for t in ticks)])


def _conditions(cond) -> list[str]:
    order = {"dry": 0, "wet": 1}
    return sorted(set(cond), key=lambda c: (order.get(c, 2), c))


def level_radius_figure(radius, level, squeals, cond, bands, level_name: str = "L_pA at 7.5 m (dB(A))"):
    """Level against radius: filled markers squeal (the loudest wheel's level), open markers on the
    axis floor labelled "quiet" (not a level: ``_quiet_floor``) are quiet curves; one marker and colour
    per friction condition; ``bands`` [(R_lo, R_hi, text)]: the rules' radius classes shaded (darker
    first), their penalties in the legend."""
    plt = _plt()
    R, L, S, C = (np.asarray(radius, float), np.asarray(level, float), np.asarray(squeals, bool),
                  np.asarray(cond, str))
    fig, ax = plt.subplots(figsize=(11.5, 4.4))
    floor = np.nanmin(L[S]) - 10 if S.any() else 0.0      # quiet curves' row: below every level (_quiet_floor)
    for (lo, hi, text), shade in zip(bands, ("0.82", "0.92", "0.96")):
        ax.axvspan(lo, hi, color=shade, zorder=0, lw=0, label=text)
    for i, c in enumerate(_conditions(C)):
        m, col = MARKERS[i % len(MARKERS)], COLOURS[i % len(COLOURS)]
        k = (C == c) & S
        ax.plot(R[k], L[k], m, color=col, ms=7, label=f"{c}: squeals ({int(k.sum())})")
        q = (C == c) & ~S
        ax.plot(R[q], np.full(q.sum(), floor), m, mfc="none", color=col, ms=7, label=f"{c}: quiet ({int(q.sum())})")
    ax.set_xscale("log")
    ax.set_xlim(0.85 * R.min() if R.size else 10, 1.15 * R.max() if R.size else 1000)
    ticks = _radius_ticks(*ax.get_xlim())
    ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
    ax.minorticks_off()
    _quiet_floor(ax, floor, L[S & np.isfinite(L)], 4.0)
    ax.set_xlabel("curve radius R (m)")
    ax.set_ylabel(level_name)
    ax.set_title("the physics' verdict per curve (open markers on the row 'quiet': no squeal)", fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    return fig


def chainage_figure(chainage, length, radius, level, squeals, cond, penalties: dict, ids=None):
    """The line along its chainage (km): radius of each curve (top, bars over its length, a log axis with
    plain radii), the level of the loudest squealing wheel per friction condition (middle; quiet curves on
    the floor labelled "quiet") and each rule's penalty (bottom,
    ``penalties`` {title: array dB per row})."""
    plt = _plt()
    x0, Lc = np.asarray(chainage, float) / 1e3, np.asarray(length, float) / 1e3
    R, L, S, C = (np.asarray(radius, float), np.asarray(level, float), np.asarray(squeals, bool),
                  np.asarray(cond, str))
    fig, (a, b, c) = plt.subplots(3, 1, figsize=(10, 6.4), sharex=True,
                                  gridspec_kw={"height_ratios": [1.1, 1.4, 1.0]})
    seen = {}
    for x, w, r in zip(x0, Lc, R):
        if (x, r) in seen:
            continue
        seen[(x, r)] = True
        a.bar(x, r, width=max(w, 1e-3), align="edge", color="0.55")
    a.set_yscale("log")
    a.set_ylim(0.5 * R.min() if R.size else 10.0, 1.6 * R.max() if R.size else 1000.0)
    ticks = _radius_ticks(*a.get_ylim())                   # plain radii in m (a log axis labels decades only)
    a.set_yticks(ticks, [f"{t:g}" for t in ticks])
    a.minorticks_off()
    a.set_ylabel("radius (m)")
    if ids is not None:
        for x, w, r, i in zip(x0, Lc, R, ids):
            if (x, r) in seen and seen[(x, r)]:
                a.text(x + 0.5 * w, r * 1.08, str(i), ha="center", va="bottom", fontsize=6)
                seen[(x, r)] = False
    conds = _conditions(C)
    floor = np.nanmin(L[S]) - 10 if S.any() else 0.0      # quiet curves' row (_quiet_floor)
    width = max(float(np.median(Lc)) if Lc.size else 0.1, 1e-3) / max(len(conds), 1)
    for i, cn in enumerate(conds):
        k = C == cn
        col, m = COLOURS[i % len(COLOURS)], MARKERS[i % len(MARKERS)]
        xs = x0[k] + (i + 0.5) * width
        sq = S[k]
        b.plot(xs[sq], L[k][sq], m, color=col, ms=6, label=f"{cn}: squeals")
        b.plot(xs[~sq], np.full((~sq).sum(), floor), m, mfc="none", color=col, ms=5, label=f"{cn}: quiet")
    b.set_ylabel("L_pA at 7.5 m (dB(A))")
    _quiet_floor(b, floor, L[S & np.isfinite(L)], 8.0)
    b.legend(fontsize=7, ncol=len(conds) * 2, loc="upper right")
    for j, (title, p) in enumerate(penalties.items()):
        xs, ys = _stairs(x0, Lc, np.asarray(p, float))
        c.step(xs, ys + 0.15 * j, where="post", color=COLOURS[2 + j], label=title)
    c.set_ylabel("rule penalty (dB)")
    c.set_xlabel("chainage (km)")
    c.set_ylim(-0.5, 9)
    c.legend(fontsize=7, loc="upper right")
    for ax in (a, b, c):
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return fig


def _stairs(x0, w, p) -> tuple[np.ndarray, np.ndarray]:
    """(x, value) of a post-step line: the penalty p from each curve's start, 0 from its end."""
    pts = sorted([(x + d, 0, 0.0) for x, d in zip(x0, w)] + [(x, 1, v) for x, v in zip(x0, p)],
                 key=lambda t: (t[0], t[1]))
    return np.array([t[0] for t in pts]), np.array([t[2] for t in pts])
