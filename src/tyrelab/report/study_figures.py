"""Interactive figures of the study report (:mod:`.study_report`), drawn with plotly.

Each function returns a ``plotly.graph_objects.Figure``; the page holds it as a
compressed data block that its loader draws (:mod:`.figure_embed`: plotly.js
once, offline).

* :func:`overlay_figure` - every model's compared channel on the reference
  over time, the disturbance and response segments shaded and their bounds
  drawn as vertical lines, zoomable (thesis Figures 5-2 to 5-6 and 5-8; for
  a track, the time record of Figure 5-11);
* :func:`distribution_figure` - the force probability density of every model
  and the reference with their normal fits (thesis Figure 5-14, eq. 5.3);
* :func:`cost_figure` - each model's wall time per simulated second against
  its mean error (accuracy against cost; the thesis compares the models'
  parameterization in chapter 4 but draws no such figure; the points come
  from :func:`cost_points`).

:func:`condition_figures` draws the figures of one test condition from the
study's signals into a :class:`.figure_embed.FigureSink`.

Decimation (:func:`decimate_minmax`), to what a screen shows: a trace of
``n`` samples, more than ``max_points`` (default :data:`MAX_POINTS`, 4000),
is cut into ``c = (max_points - 2) // 2`` columns (1999: about the pixel
columns of a wide screen; a figure of the page is at most about 1100 px
wide), column ``k`` the samples ``k n // c`` to ``(k + 1) n // c - 1``; each
column keeps its smallest and its largest sample, in time order, and the
first and last samples are kept too: the min/max envelope per pixel column,
which is what a line plot draws.
Every kept point is an original sample, so every peak and trough (the
largest and smallest value of each column, hence of the whole trace) is kept
at its exact time; only what lies between a column's extremes is dropped. A
6 s cleat run at 1 kHz keeps 4000 of its 6000 samples, a 100 m track at
3 km/h (126 000 samples) 4000. Non-finite samples (gaps in a measurement)
are left out. In the page the kept values are rounded to the figure's
quantum (0.2 N to 2 N on a wheel-load figure, :func:`.figure_embed.value_quantum`)
and the times kept exactly; each overlay's caption says both. With
``max_points=None`` (the full-resolution page) nothing is dropped.
"""

from __future__ import annotations

import html
import textwrap

import numpy as np
import pandas as pd

from ..errors import InputError
from .figure_embed import value_quantum
from ..validate.compare import THESIS_CLEAT, THESIS_TRACK
from ..validate.distributions import fit_normal, histogram_density
from ..validate.tables import DEFAULT_LIMITS

#: most points per trace in an overlay (see the module docstring)
MAX_POINTS = 4000

#: colour of the reference trace; models cycle through :data:`PALETTE`
REFERENCE_COLOUR = "#000000"
PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2",
           "#17becf", "#bcbd22", "#7f7f7f")


def _e(x) -> str:
    return html.escape(str(x))


def load_text(load) -> str:
    """A load case as written: ``"LC1"``, or a wheel load in N (given as a number or as the
    text of one, as a run's metadata keeps it: ``"4000.0"`` -> ``"4000 N"``)."""
    try:
        return f"{float(load):g} N"
    except (TypeError, ValueError):
        return str(load)


def condition_text(test, speed, load) -> str:
    """``"cleat 50x50, 18 km/h, LC1"``."""
    return f"{test}, {float(speed):g} km/h, {load_text(load)}"


def title_text(main: str, note: str, width: int = 110) -> str:
    """A plotly title: ``main``, then ``note`` wrapped into lines of ``width`` characters."""
    lines = [main, *textwrap.wrap(note, width)]
    return "<br>".join(_e(line) for line in lines)


def decimate_minmax(t, y, max_points: int | None = MAX_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """At most ``max_points`` samples of ``(t, y)`` keeping every extreme exactly.

    The rule is the module docstring's: columns of consecutive samples, the
    minimum and maximum of each kept in time order, plus the first and last
    sample. Non-finite samples are left out first. With no more than
    ``max_points`` samples, or ``max_points=None``, the (finite) trace is
    returned whole. Returns copies (float64) of original samples; never
    interpolates.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.shape != y.shape or t.ndim != 1:
        raise InputError("time and values must be 1-D arrays of one length", field="signal")
    if max_points is not None and max_points < 4:
        raise InputError(f"max_points must be at least 4, got {max_points}", field="max_points")
    finite = np.isfinite(t) & np.isfinite(y)
    if not finite.all():
        t, y = t[finite], y[finite]
    n = y.size
    if max_points is None or n <= max_points:
        return t.copy(), y.copy()
    columns = (max_points - 2) // 2
    edges = np.arange(columns + 1) * n // columns         # column k: samples edges[k] to edges[k+1] - 1
    idx = edges[:-1, None] + np.arange(-(-n // columns))[None, :]
    inside = idx < edges[1:, None]
    idx = np.minimum(idx, n - 1)
    i_min = idx[np.arange(columns), np.argmin(np.where(inside, y[idx], np.inf), axis=1)]
    i_max = idx[np.arange(columns), np.argmax(np.where(inside, y[idx], -np.inf), axis=1)]
    keep = np.unique(np.concatenate([[0, n - 1], i_min, i_max]))
    return t[keep], y[keep]


def _layout(fig, title: str, xtitle: str, ytitle: str, height: int = 440) -> None:
    lines = title.count("<br>") + 1
    fig.update_layout(template="plotly_white", height=height + 18 * max(lines - 2, 0),
                      title={"text": title, "x": 0.01, "xanchor": "left", "font": {"size": 14}},
                      margin={"l": 70, "r": 20, "t": 44 + 18 * lines, "b": 50},
                      legend={"orientation": "h", "y": -0.18, "x": 0},
                      hovermode="x unified")
    fig.update_xaxes(title_text=xtitle, showline=True, linecolor="#888")
    fig.update_yaxes(title_text=ytitle, showline=True, linecolor="#888")


def overlay_figure(reference, models, channel: str, title: str, segments=None,
                   max_points: int | None = MAX_POINTS):
    """Every model's ``channel`` on the reference's over time (thesis Figures 5-2..5-6).

    Parameters
    ----------
    reference : (str, array, array)
        Label, time [s] and values [N] of the reference run.
    models : list of (str, array, array, str)
        Label, time, values and colour of each compared model.
    channel : str
        The compared channel (axis label).
    title : str
        Figure title (carries the reference note).
    segments : dict, optional
        ``{"disturbance": (start, end), "response": (start, end)}`` [s];
        shaded spans with vertical lines at their bounds, and buttons that
        zoom onto the disturbance or back to the whole record.
    max_points : int or None
        Decimation limit per trace (:func:`decimate_minmax`; None: every sample).

    Returns
    -------
    (plotly.graph_objects.Figure, dict)
        The figure and ``{"samples": total, "kept": total kept, "range": (smallest,
        largest) kept value}`` (the range the page's rounding step comes from).
    """
    import plotly.graph_objects as go
    fig = go.Figure()
    samples = kept = 0
    y_lo, y_hi = np.inf, -np.inf
    traces = [(label, t, y, colour, False) for label, t, y, colour in models]
    traces.append((reference[0], reference[1], reference[2], REFERENCE_COLOUR, True))
    for label, t, y, colour, is_ref in traces:
        td, yd = decimate_minmax(t, y, max_points)
        samples += len(t)
        kept += len(td)
        if len(yd):
            y_lo, y_hi = min(y_lo, yd.min()), max(y_hi, yd.max())
        fig.add_trace(go.Scatter(x=td, y=yd, name=label,
                                 mode="lines", line={"color": colour, "width": 2.2 if is_ref else 1.3,
                                                     "dash": "solid" if is_ref else "dash"}))
    _layout(fig, title, "time [s]", f"{channel} [N]")
    if segments:
        fills = {"disturbance": "rgba(31,119,180,0.12)", "response": "rgba(44,160,44,0.08)"}
        lines = {"disturbance": "#1f77b4", "response": "#2ca02c"}
        for name, (lo, hi) in segments.items():
            fig.add_vrect(x0=lo, x1=hi, fillcolor=fills[name], line_width=0, layer="below",
                          annotation_text=name, annotation_position="top left" if name == "disturbance"
                          else "top right",
                          annotation_font_size=10)
            for x in (lo, hi):
                fig.add_vline(x=x, line={"color": lines[name], "width": 1, "dash": "dot"})
        if "disturbance" in segments:
            lo, hi = segments["disturbance"]
            pad = 0.5 * (hi - lo)
            fig.update_layout(updatemenus=[{
                "type": "buttons", "direction": "right", "x": 1.0, "xanchor": "right",
                "y": 1.02, "yanchor": "bottom", "showactive": False, "font": {"size": 11},
                "buttons": [
                    {"label": "disturbance", "method": "relayout",
                     "args": [{"xaxis.range": [lo - pad, hi + pad], "yaxis.autorange": True}]},
                    {"label": "whole record", "method": "relayout",
                     "args": [{"xaxis.autorange": True, "yaxis.autorange": True}]}]}])
    return fig, {"samples": samples, "kept": kept, "range": (float(y_lo), float(y_hi))}


def distribution_figure(series, channel: str, title: str, bins: int = 40):
    """Force probability densities and normal fits (thesis Figure 5-14, eq. 5.3).

    ``series``: list of ``(label, values, colour, is_reference)``. All
    histograms share one range and ``bins`` bins (drawn as steps, solid);
    each normal fit (mean and standard deviation of the samples) is dashed.
    """
    import plotly.graph_objects as go
    values = [np.asarray(y, dtype=float) for _, y, _, _ in series]
    lo = float(min(v.min() for v in values))
    hi = float(max(v.max() for v in values))
    if hi <= lo:
        hi = lo + 1.0
    x = np.linspace(lo, hi, 200)
    fig = go.Figure()
    for (label, _, colour, is_ref), y in zip(series, values):
        c, d = histogram_density(y, bins=bins, range_=(lo, hi))
        width = 2.2 if is_ref else 1.3
        fig.add_trace(go.Scatter(x=c, y=d, name=f"{label} density", mode="lines",
                                 line={"color": colour, "width": width, "shape": "hvh"},
                                 legendgroup=label))
        mu, s = fit_normal(y)
        if s > 0:
            pdf = np.exp(-0.5 * ((x - mu) / s) ** 2) / (s * np.sqrt(2 * np.pi))
            fig.add_trace(go.Scatter(x=x, y=pdf, name=f"{label} normal fit", mode="lines",
                                     line={"color": colour, "width": width, "dash": "dash"},
                                     legendgroup=label))
    _layout(fig, title, f"{channel} [N]", "probability density [1/N]")
    fig.update_layout(hovermode="closest")
    return fig


def cost_figure(points, title: str, colours: dict):
    """Mean error against wall time per simulated second, one marker per (model, group).

    ``points``: DataFrame with ``model``, ``group``, ``wall_per_simulated_s``,
    ``mean_error_pct`` and ``runs``; ``colours``: ``{model: colour}``.
    Log-scaled time axis; marker symbol per group.
    """
    import plotly.graph_objects as go
    symbols = ("circle", "square", "diamond", "triangle-up", "cross", "x")
    fig = go.Figure()
    for i, (group, rows) in enumerate(points.groupby("group", sort=False)):
        fig.add_trace(go.Scatter(
            x=rows["wall_per_simulated_s"], y=rows["mean_error_pct"], name=str(group),
            mode="markers+text", text=list(rows["model"]), textposition="top center",
            marker={"size": 11, "symbol": symbols[i % len(symbols)],
                    "color": [colours.get(m, "#7f7f7f") for m in rows["model"]],
                    "line": {"color": "#333", "width": 1}},
            customdata=np.stack([rows["runs"].to_numpy()], axis=-1),
            hovertemplate="%{text}<br>%{x:.3g} s per simulated s<br>mean error %{y:.3g} %"
                          "<br>%{customdata[0]} runs<extra>" + str(group) + "</extra>"))
    _layout(fig, title, "wall time per simulated second [s/s] (log)", "mean |error| [%]")
    fig.update_xaxes(type="log")
    fig.update_layout(hovermode="closest")
    return fig


def primary_metrics(group, rows) -> list[str]:
    """The primary metrics of a group (the rules' :data:`.tables.DEFAULT_LIMITS`;
    for another group the thesis's metrics) that ``rows`` hold."""
    lim = DEFAULT_LIMITS.get(group)
    names = list(lim) if lim else THESIS_CLEAT + THESIS_TRACK
    return [m for m in names if m in rows.columns and rows[m].notna().any()]


def cost_points(metrics, cost) -> pd.DataFrame:
    """One point per (group, model) for :func:`cost_figure`: the model's wall time
    per simulated second and its mean error, the mean over its compared runs of
    the group of the mean |primary metric| (:func:`primary_metrics`).
    ``metrics``: compared rows only (no repeatability, no error)."""
    points = []
    for (group, model), rows in metrics.groupby(["group", "model"], sort=False):
        err = rows[primary_metrics(group, rows)].abs().mean(axis=1).dropna()
        wall = cost.loc[cost["model"] == model, "wall_per_simulated_s"]
        if len(err) and len(wall):
            points.append({"model": model, "group": group, "wall_per_simulated_s": float(wall.iloc[0]),
                           "mean_error_pct": float(err.mean()), "runs": len(err)})
    return pd.DataFrame(points, columns=["model", "group", "wall_per_simulated_s", "mean_error_pct",
                                        "runs"])


def _stored_text(n: dict, max_points: int | None, exact: bool) -> str:
    """What the page holds of an overlay's traces (its caption's sentence)."""
    if n["kept"] == n["samples"]:
        kept = f"every sample shown ({n['samples']})"
    else:
        kept = (f"{n['kept']} of {n['samples']} samples shown: at most {max_points} per trace, the "
                f"minimum and maximum of each of {(max_points - 2) // 2} pixel columns (every peak "
                "kept)")
    lo, hi = n["range"]
    if exact:
        return kept + ", exact values (full resolution)"
    if not lo <= hi:
        return kept
    return f"{kept}, values rounded to {value_quantum(lo, hi):g} N, times exact"


def _signal(study, key, channel):
    s = study.signal(key, ("RUNTIME", channel))  # only what the figure shows is read
    return s["RUNTIME"].to_numpy(dtype=float), s[channel].to_numpy(dtype=float)


def condition_figures(study, cond, rows, refs, note, figs, colours, max_points) -> str:
    """The figures of one test condition as HTML: an overlay per reference
    (:func:`overlay_figure`) and, for a track (no disturbance segment), the
    force distributions (:func:`distribution_figure`).

    ``cond`` is (test, speed_kmh, load); ``rows`` the condition's compared
    rows of ``study.metrics`` (no repeatability, no error); ``refs`` maps run
    keys to reference labels; ``figs`` a :class:`.figure_embed.FigureSink`;
    ``max_points`` as :func:`decimate_minmax`'s. A signal that cannot be read is
    named in the caption instead of failing the page.
    """
    out = []
    for ref_key, sub in rows.groupby("reference", sort=False):
        channel = str(sub["channel"].iloc[0])
        ref_label = refs.get(ref_key, f"reference {ref_key}")
        try:
            ref = (ref_label, *_signal(study, ref_key, channel))
        except Exception as exc:  # the page reports any unreadable signal
            out.append(f"<p>No figure: the reference signal {_e(ref_key)} could not be read "
                       f"({_e(exc)}).</p>")
            continue
        models, missing = [], []
        for r in sub.itertuples():
            try:
                models.append((str(r.model), *_signal(study, r.key, channel),
                               colours.get(str(r.model), "#7f7f7f")))
            except Exception as exc:  # reported in the caption
                missing.append(f"{r.model} ({exc})")
        seg = {}
        for name in ("disturbance", "response"):
            lo = sub[f"{name}_start_s"].astype(float).dropna()
            hi = sub[f"{name}_end_s"].astype(float).dropna()
            if len(lo) and len(hi):
                seg[name] = (float(lo.iloc[0]), float(hi.iloc[0]))
        title = title_text(f"{condition_text(*cond)}: {channel} of every model on {ref_label}", note)
        fig, n = overlay_figure(ref, models, channel, title, seg, max_points)
        kept = _stored_text(n, max_points, figs.exact)
        span = "; ".join(f"{k} {a:.3f}-{b:.3f} s" for k, (a, b) in seg.items())
        caption = (f"{condition_text(*cond)}: {channel} over time, every model (dashed) on {ref_label} "
                   f"(solid black), as thesis Figures 5-2 to 5-6"
                   + (f"; segments from the reference: {span}" if span else " (Figure 5-11 for a track)")
                   + f". Drag to zoom, double-click to reset. {kept}."
                   + (f" Not shown: {'; '.join(missing)}." if missing else "") + f" {note}")
        out.append(figs.add(fig, "overlay", caption, packed=True))
        if "disturbance" not in seg:
            series = [(m[0], m[2], m[3], False) for m in models] + [(ref_label, ref[2],
                                                                     REFERENCE_COLOUR, True)]
            title = title_text(f"{condition_text(*cond)}: {channel} probability density, models "
                               f"and {ref_label}", note)
            caption = (f"{condition_text(*cond)}: probability density of {channel} of every model and the "
                       f"reference (steps) with normal fits (dashed), as thesis Figure 5-14. {note}")
            out.append(figs.add(distribution_figure(series, channel, title), "distribution",
                                caption))
    return "".join(out)
