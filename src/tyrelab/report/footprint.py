"""Footprint plot: contact-pressure map and outline of a tyre model (thesis 3.3.3, Fig. 4-9)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_footprint(result: dict, path) -> Path:
    """Write the footprint of :func:`tyrelab.rig.static_press.footprint` as an image (atomically).

    Each contacting tread block is drawn as a rectangle of its cell, coloured
    by its contact pressure [kPa]; the outline is drawn in red (as FTire/fit
    draws the model's outline over the footprint bitmap).
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle

    path = Path(path)
    x = np.asarray(result["x"]) * 1e3
    y = np.asarray(result["y"]) * 1e3
    p = np.asarray(result["pressure"]) / 1e3
    on = p > 0
    fig, ax = plt.subplots(figsize=(6.0, 6.5))
    if on.any():
        cell = result.get("cell")
        if cell is not None:
            dx, dy = cell[0] * 1e3, cell[1] * 1e3
        else:  # from the block spacing
            ys = np.unique(np.round(y[on], 1))
            dy = np.min(np.diff(ys)) if ys.size > 1 else 20.0
            xs = np.sort(x[on])
            steps = np.diff(xs)
            dx = np.min(steps[steps > 1.0]) if np.any(steps > 1.0) else 40.0
        rects = [Rectangle((yy - dy / 2, xx - dx / 2), dy, dx) for xx, yy in zip(x[on], y[on])]
        coll = PatchCollection(rects, cmap="viridis", edgecolor="none")
        coll.set_array(p[on])
        ax.add_collection(coll)
        fig.colorbar(coll, ax=ax, label="contact pressure [kPa]")
    outline = np.asarray(result.get("outline", np.zeros((0, 2))))
    if outline.size:
        ax.plot(outline[:, 1] * 1e3, outline[:, 0] * 1e3, color="red", lw=1.5, label="outline")
        ax.legend(loc="upper right")
    ax.set_xlabel("lateral y [mm]")
    ax.set_ylabel("longitudinal x [mm]")
    ax.set_aspect("equal")
    span = max(np.abs(x[on]).max() if on.any() else 100, np.abs(y[on]).max() if on.any() else 100)
    lim = 1.15 * span + 30
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_title(f"footprint: {result.get('load', float('nan')) / 1e3:.1f} kN, "
                 f"{result.get('pressure_inflation', float('nan')) / 1e3:.0f} kPa, "
                 f"{result.get('length', 0) * 1e3:.0f} x {result.get('width', 0) * 1e3:.0f} mm")
    fig.tight_layout()
    from ..io_atomic import save_figure
    return save_figure(fig, path, dpi=120)
