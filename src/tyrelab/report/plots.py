"""Signal plots: channels against time or distance, several runs overlaid (thesis Figs 5-4 to 5-6)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..signal import CHANNELS  # noqa: E402
from .study_figures import load_text  # noqa: E402

X_AXES = {"time": ("RUNTIME", "time [s]"), "distance": ("DISTANCE", "distance [m]")}


def _label(run, fallback):
    meta = run.attrs.get("metadata", {})
    if meta.get("model"):
        parts = [meta.get("model"), meta.get("stiffness", "")]
        return " ".join(p for p in parts if p) or fallback
    return fallback


def plot_runs(runs, labels=None, channel="FZW", x="time", ax=None, title=None):
    """Overlay ``channel`` of several signal tables against time or distance.

    Forces are drawn in kN. Returns the matplotlib Figure.
    """
    xcol, xlabel = X_AXES[x]
    if ax is None:
        fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    else:
        fig = ax.figure
    unit, desc = CHANNELS.get(channel, ("", channel))
    scale, unit_shown = (1e-3, "kN") if unit == "N" else (1.0, unit)
    for i, run in enumerate(runs):
        label = labels[i] if labels else _label(run, f"run {i + 1}")
        ax.plot(run[xcol], run[channel] * scale, lw=1.2, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"{channel} [{unit_shown}]")
    ax.grid(True, alpha=0.3)
    meta = runs[0].attrs.get("metadata", {}) if runs else {}
    roads = {r.attrs.get("metadata", {}).get("road") for r in runs}
    if len(roads) > 1:
        meta = {**meta, "road": "several roads"}
    if title is None and meta:
        speed = meta.get("speed_m_s")
        title = f"{desc}: {meta.get('road', '')}" + (f", {speed * 3.6:.0f} km/h" if speed else "") + \
                (f", {load_text(meta.get('load_case'))}" if meta.get("load_case") else "")
    if title:
        ax.set_title(title)
    if len(runs) > 1 or labels:
        ax.legend()
    return fig
