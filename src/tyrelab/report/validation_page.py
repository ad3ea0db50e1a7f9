"""A self-contained HTML validation page: metrics table and figures.

Figures (matplotlib, embedded as base64 PNG, no external files):

* overlay of measured and simulated force on the measurement's time base,
  the disturbance and response segments shaded (thesis Figure 5-1);
* the %RE vector over time with the near-zero rule of
  :mod:`tyrelab.validate.metrics` (thesis Figure 5-9);
* force probability densities with their normal fits (thesis Figure 5-14);
* power spectral densities, when computed.
"""

from __future__ import annotations

import base64
import html
import io
from pathlib import Path

import numpy as np

from ..io_atomic import atomic_write_text
from ..validate.align import Aligned
from ..validate.distributions import fit_normal, histogram_density
from ..validate.metrics import relative_error


def _png(fig) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, bbox_inches="tight")
    import matplotlib.pyplot as plt
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def _figure():
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    return plt.subplots(figsize=(8, 3.2))


def _shade(ax, segments):
    if segments is None:
        return
    ax.axvspan(*segments.disturbance, color="tab:blue", alpha=0.12, label="disturbance")
    ax.axvspan(*segments.response, color="tab:green", alpha=0.08, label="response")


def overlay_figure(a: Aligned, segments=None, labels=("measured", "simulated")) -> str:
    """Measured and simulated signal over time (base64 PNG)."""
    fig, ax = _figure()
    _shade(ax, segments)
    ax.plot(a.t, a.m, color="k", lw=1.0, label=labels[0])
    ax.plot(a.t, a.p, color="tab:red", lw=1.0, ls="--", label=labels[1])
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"{a.channel} [N]")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return _png(fig)


def relative_error_figure(a: Aligned, segments=None) -> str:
    """%RE over time, eq. 5.2 with the near-zero floor (base64 PNG)."""
    fig, ax = _figure()
    _shade(ax, segments)
    ax.plot(a.t, relative_error(a.p, a.m), color="tab:purple", lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("%RE [%]")
    ax.grid(alpha=0.3)
    return _png(fig)


def distribution_figure(a: Aligned, labels=("measured", "simulated"), bins=40) -> str:
    """Force densities and their normal fits, eq. 5.3 (base64 PNG)."""
    fig, ax = _figure()
    lo, hi = float(min(a.m.min(), a.p.min())), float(max(a.m.max(), a.p.max()))
    if hi <= lo:
        hi = lo + 1.0
    x = np.linspace(lo, hi, 300)
    for y, label, colour in ((a.m, labels[0], "k"), (a.p, labels[1], "tab:red")):
        c, d = histogram_density(y, bins=bins, range_=(lo, hi))
        ax.step(c, d, where="mid", color=colour, lw=0.8, alpha=0.7, label=f"{label} histogram")
        mu, s = fit_normal(y)
        if s > 0:
            ax.plot(x, np.exp(-0.5 * ((x - mu) / s) ** 2) / (s * np.sqrt(2 * np.pi)),
                    color=colour, lw=1.4, ls="--", label=f"{label} normal fit")
    ax.set_xlabel(f"{a.channel} [N]")
    ax.set_ylabel("probability density [1/N]")
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    return _png(fig)


def psd_figure(spec: dict) -> str:
    """Measured and simulated PSD (base64 PNG)."""
    fig, ax = _figure()
    f = spec["f"]
    ax.semilogy(f[1:], np.maximum(spec["psd_meas"][1:], 1e-30), color="k", lw=0.9,
                label="measured")
    ax.semilogy(f[1:], np.maximum(spec["psd_pred"][1:], 1e-30), color="tab:red", lw=0.9,
                ls="--", label="simulated")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("PSD [N^2/Hz]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return _png(fig)


def page_html(title: str, table_html: str, aligned: Aligned, result: dict,
              notes: list[str] | None = None) -> str:
    """The whole page as text."""
    det = result.get("details", {})
    seg = det.get("segments")
    figs = [("Measured and simulated signal", overlay_figure(aligned, seg)),
            ("Relative error over time (eq. 5.2)", relative_error_figure(aligned, seg)),
            ("Force distributions and normal fits", distribution_figure(aligned))]
    if "psd" in det:
        figs.append(("Power spectral density", psd_figure(det["psd"])))
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'>",
             f"<title>{html.escape(title)}</title>",
             "<style>body{font-family:sans-serif;max-width:60em;margin:auto}"
             "table{border-collapse:collapse}td,th{border:1px solid #999;padding:2px 6px;"
             "text-align:right}</style></head><body>",
             f"<h1>{html.escape(title)}</h1>", table_html]
    for note in notes or []:
        parts.append(f"<p>{html.escape(note)}</p>")
    for caption, png in figs:
        parts.append(f"<h2>{html.escape(caption)}</h2>"
                     f"<img alt='{html.escape(caption)}' src='data:image/png;base64,{png}'>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def write_page(path, text: str) -> None:
    """Write the page; it appears only when complete (temporary name, rename)."""
    atomic_write_text(Path(path), text)
