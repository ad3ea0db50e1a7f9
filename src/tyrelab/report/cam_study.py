"""Plot of the cam-count study (:mod:`tyrelab.fit.cams`): error against cost, each pair labelled."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_cam_study(study, path) -> Path:
    """Write error [%] against wall time per simulated second of every cam pair (atomically).

    One series per road and speed (points labelled ``N_LENGTH x N_WIDTH``),
    the mean over the conditions in black, the tolerance band of the
    recommendation shaded and the recommended pair ringed in red.
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..io_atomic import save_figure

    table, summary = study.table, study.summary
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    conditions = list(table.groupby(["road", "speed"], sort=False))
    for (road, speed), rows in conditions:
        ax.plot(rows["wall_s_per_sim_s"] * 1e3, rows["error_pct"], "o", alpha=0.6, ms=5,
                label=f"{road}, {speed * 3.6:.4g} km/h")
    ax.plot(summary["wall_s_per_sim_s"] * 1e3, summary["error_pct"], "ks", ms=6,
            label="mean over conditions" if len(conditions) > 1 else "pair")
    for _, r in summary.iterrows():
        ax.annotate(f"{int(r['n_length'])}x{int(r['n_width'])}",
                    (r["wall_s_per_sim_s"] * 1e3, r["error_pct"]), textcoords="offset points",
                    xytext=(4, 4), fontsize=8)
    ok = summary[summary["qualifies"]]
    if len(ok):
        ax.axhspan(float(summary["error_pct"].min()), float(ok["error_pct"].max()), color="tab:green",
                   alpha=0.12, label="within tolerance")
    nl, nw = study.recommended
    rec = summary[(summary["n_length"] == nl) & (summary["n_width"] == nw)]
    ax.plot(rec["wall_s_per_sim_s"] * 1e3, rec["error_pct"], "o", ms=16, mfc="none", mec="red", mew=2,
            label=f"recommended {nl}x{nw}")
    ax.set_xlabel("wall time per simulated second [ms/s]")
    ax.set_ylabel("error [%]")
    if np.all(summary["error_pct"] > 0) and summary["error_pct"].max() > 20 * summary["error_pct"].min():
        ax.set_yscale("log")
    ax.set_title(f"Enveloping model cam count, {study.tyre} vs {study.reference}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.text(0.01, 0.01, study.metric, fontsize=7, alpha=0.8)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    return save_figure(fig, path)
