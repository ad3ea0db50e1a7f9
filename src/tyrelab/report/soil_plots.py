"""Plots of a wheel on soil: the slip curve (pull, torque, sinkage) and the rut."""

from __future__ import annotations

import numpy as np


def plot_slip_curve(curve, title: str = ""):
    """Drawbar pull, driving torque and sinkage against slip (:func:`tyrelab.rig.single_wheel.slip_curve`);
    one line per value of a ``model`` column, when the table has one."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 1, figsize=(6.5, 7.5), sharex=True)
    groups = list(curve.groupby("model", sort=False)) if "model" in curve else [("", curve)]
    for ax, (col, scale, label) in zip(axes, (("FX", 1e-3, "drawbar pull [kN]"),
                                                ("TORQUE", 1e-3, "driving torque [kN m]"),
                                                ("SINKAGE", 1e3, "sinkage [mm]"))):
        for k, (name, part) in enumerate(groups):
            ax.plot(part["slip"].to_numpy(), part[col].to_numpy() * scale, "o-", color=f"C{k}",
                    label=name or None)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    if len(groups) > 1:
        axes[0].legend(title="model")
    axes[0].axhline(0.0, color="0.5", lw=0.8)
    axes[-1].set_xlabel("slip: driving s = 1 - V / (R_e omega), braking s = R_e omega / V - 1")
    if title:
        axes[0].set_title(title)
    fig.tight_layout()
    return fig


def plot_rut(bed, title: str = ""):
    """The rut a run left: how far the surface lies below the surface as laid [mm] over the bed,
    seen from above (negative: soil a bulldozing soil raised), and its deepest cut along the
    track."""
    import matplotlib.pyplot as plt
    sp = (bed.base - bed.ground.z) * 1e3
    nx, ny = sp.shape
    x = bed.x0 + bed.dx * np.arange(nx)
    y = bed.y0 + bed.dy * np.arange(ny)
    touched = np.flatnonzero(np.abs(sp).max(axis=1) > 0.0)
    if touched.size:  # the part of the bed the wheel went over, and a metre either side
        keep = slice(max(0, touched[0] - int(1.0 / bed.dx)), touched[-1] + int(1.0 / bed.dx) + 1)
        sp, x = sp[keep], x[keep]
    fig, (top, cut) = plt.subplots(2, 1, figsize=(8, 5.5), gridspec_kw={"height_ratios": [2, 1]})
    im = top.pcolormesh(x, y, sp.T, shading="nearest", cmap="viridis_r")
    fig.colorbar(im, ax=top, label="rut depth [mm]")
    top.set_ylabel("y [m]")
    top.set_aspect("auto")
    k = int(np.argmax(sp.max(axis=0)))
    cut.plot(x, -sp[:, k], color="C1")
    cut.set_xlabel("x [m]")
    cut.set_ylabel(f"surface at y = {y[k]:.2f} m [mm]")
    cut.grid(True, alpha=0.3)
    if title:
        top.set_title(title)
    fig.tight_layout()
    return fig
