"""Road figures: a heightmap with a longitudinal cut, and the displacement spectral density.

The spectrum figure follows thesis Figures 3-27/3-28 (Becker 2008): DSD against
spatial frequency on log-log axes, with the fitted power law ``S = A phi^-n``
(eq. 3.8) over the ISO 8608 band.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..io_atomic import save_figure as _save_atomic  # noqa: E402
from ..road.iso8608 import BAND, ISO_CLASSES, N0, W_ISO, iso_class  # noqa: E402
from ..road.spectrum import log_binned, road_profile  # noqa: E402

#: at most this many grid nodes along each axis of the heightmap image
MAX_PIXELS = (2000, 400)


def save_figure(fig, path, dpi: int = 120) -> Path:
    """Save ``fig`` so that ``path`` appears only when complete (:func:`tyrelab.io_atomic.save_figure`)."""
    return _save_atomic(fig, path, dpi=dpi)


def _heightmap(ax, road):
    """Image of the road's grid heights [mm], thinned to :data:`MAX_PIXELS`."""
    g = road.grid()
    step_x = max(1, int(np.ceil(g.z.shape[0] / MAX_PIXELS[0])))
    step_y = max(1, int(np.ceil(g.z.shape[1] / MAX_PIXELS[1])))
    z = g.z[::step_x, ::step_y] * 1e3
    x1 = g.x0 + g.dx * (g.z.shape[0] - 1)
    y1 = g.y0 + g.dy * (g.z.shape[1] - 1)
    im = ax.imshow(z.T, origin="lower", aspect="auto", cmap="terrain",
                   extent=(g.x0, x1, g.y0, y1), interpolation="nearest")
    ax.set_ylabel("y [m]")
    ax.set_title(road.name)
    return im


def plot_road(road, y: float = 0.0, spacing: float | None = None):
    """Heightmap (top) and the longitudinal cut at lateral position ``y`` (bottom)."""
    fig, (ax_map, ax_cut) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, layout="constrained")
    im = _heightmap(ax_map, road)
    ax_map.axhline(y, color="k", lw=0.6, ls="--")
    fig.colorbar(im, ax=[ax_map, ax_cut], label="height [mm]", pad=0.01, shrink=0.5, anchor=(0, 1))
    x, z = road_profile(road, y, spacing)
    ax_cut.plot(x, z * 1e3, lw=0.7)
    ax_cut.set_xlabel("x [m]")
    ax_cut.set_ylabel(f"height at y = {y:g} m [mm]")
    ax_cut.grid(True, alpha=0.3)
    return fig


def plot_spectrum(phi, s, fit=None, band=BAND, title: str | None = None, iso_classes: bool = True):
    """DSD ``S(phi)`` on log-log axes with the fitted power law (thesis Figures 3-27/3-28).

    The raw Welch estimate is drawn light, its average in logarithmic
    frequency bins dark, the fit red, and ISO 8608 classes A, C, E, G dotted.
    """
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.loglog(phi, s, lw=0.5, color="0.75", label="DSD, Welch estimate")
    pc, sc = log_binned(phi, s, band=(phi[0], phi[-1]))
    ax.loglog(pc, sc, lw=1.2, color="0.1", marker=".", ms=3, label="DSD, log-binned mean")
    f = np.geomspace(band[0], band[1], 50)
    if iso_classes:
        for c in "ACEG":
            g = ISO_CLASSES[c] * (f / N0) ** -W_ISO
            ax.loglog(f, g, lw=0.6, ls=":", color="tab:blue")
            ax.text(f[-1], g[-1], f" {c}", fontsize=7, color="tab:blue", va="center", clip_on=True)
    if fit is not None:
        a, n = fit
        ax.loglog(f, a * f ** -n, lw=1.8, color="tab:red",
                  label=f"S = A φ^-n: A = {a:.3g} m²/(cycles/m), n = {n:.2f} "
                        f"(ISO 8608 class {iso_class(a, n)})")
    for edge in band:
        ax.axvline(edge, color="0.6", lw=0.5)
    ax.set_xlabel("spatial frequency φ [cycles/m]")
    ax.set_ylabel("DSD [m²/(cycles/m)]")
    ax.set_xlim(min(phi[0], band[0]), max(phi[-1], band[1]) * 1.3)
    inband = sc[(pc >= band[0]) & (pc <= band[1]) & (sc > 0)]
    if inband.size:
        ax.set_ylim(inband.min() * 0.02, inband.max() * 20)
    ax.grid(True, which="both", alpha=0.2)
    ax.legend(fontsize=8, loc="lower left")
    if title:
        ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return fig
