"""The fit report: one self-contained HTML page of a campaign's fit (``tyrelab fit ... --report``).

A summary table (each parameter with its equation, fitted RMS and held-out
errors), the notes of every step, and data-vs-fit figures in the manner of
the thesis -- load-deflection (Figure 4-11), half contact length and width
against deflection (Figures 4-2, 4-3), static cleats predicted (Figures
4-13 to 4-15) -- each with its residuals; the drop-test trace and the
simulated drop fitted to it; footprint images with the extracted outline;
the carcass profile and its ``[SHAPE]`` table; modal results and dynamic
cleat runs as read; the identified ring on the plate at every pressure, its
modes, contact lengths and cleat-run errors. Figures are matplotlib PNGs embedded as base64.
"""

from __future__ import annotations

import base64
import html
import io

import numpy as np

from ..io_atomic import atomic_write_text

DATA = dict(color="k", ms=4, lw=0, marker="o", label="measured (fitted)")
HELD = dict(color="tab:orange", ms=6, lw=0, marker="s", mfc="none", label="held out")


def _png(fig) -> str:
    import matplotlib.pyplot as plt
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def _pair(title):
    """A figure of data vs fit above its residuals."""
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    fig, (ax, rx) = plt.subplots(2, 1, figsize=(7.5, 5.2), sharex=True,
                                 gridspec_kw={"height_ratios": [2.2, 1]})
    ax.set_title(title, fontsize=10)
    for a in (ax, rx):
        a.grid(alpha=0.3)
    rx.axhline(0.0, color="0.5", lw=0.8)
    return fig, ax, rx


def vertical_figure(step) -> str:
    """Load vs deflection: samples, the table's spline and the linear fit; residuals (Fig. 4-11)."""
    from ..tyre.vertical import VerticalLaw
    d = step.data
    table, lin = d["table"], d["linear"]
    law = VerticalLaw.table(table[:, 0], table[:, 1], 0.0)
    fig, ax, rx = _pair("Vertical stiffness on the flat plate (thesis Fig. 4-11)")
    top = max(float(np.max(t.deflection)) for t in d["tests"])
    x = np.linspace(0.0, top, 200)
    for t in d["tests"]:
        style = DATA if t.use == "fit" else HELD
        raw = t.deflection.size > 100
        ax.plot(t.deflection * 1e3, t.load / 1e3, **({**style, "marker": None, "lw": 0.6, "alpha": 0.6}
                                                      if raw else style))
        for fit_pred, colour in ((lin.stiffness * t.deflection, "tab:blue"),
                                 (law.static_load(np.maximum(t.deflection, 0)), "tab:red")):
            rx.plot(t.deflection * 1e3, (t.load - fit_pred) / 1e3, ".", ms=2 if raw else 5, color=colour)
    ax.plot(table[:, 0] * 1e3, table[:, 1] / 1e3, "D", color="tab:red", ms=5, label="table rows")
    ax.plot(x * 1e3, law.static_load(x) / 1e3, color="tab:red", lw=1.4, label="table (spline, eq. 2.2)")
    ax.plot(x * 1e3, lin.stiffness * x / 1e3, color="tab:blue", lw=1.2, ls="--",
            label=f"linear {lin.stiffness / 1e3:.1f} N/mm, RMS {lin.rms:.0f} N")
    ax.set_ylabel("load [kN]")
    rx.set_ylabel("measured - fit [kN]")
    rx.set_xlabel("deflection [mm]")
    ax.legend(fontsize=8)
    return _png(fig)


def damping_figure(step) -> list[str]:
    """Each fitted drop trace beside the simulated drop fitted to it; residuals."""
    out = []
    for fit, pend in zip(step.data["fits"], step.data["pendulum"]):
        fig, ax, rx = _pair(f"Drop test: rig fit c = {fit.damping / 1e3:.3f} N s/mm (scale "
                            f"{fit.stiffness_scale:.3f}); pendulum eqs. 3.1-3.7 c = "
                            f"{float(pend.damping) / 1e3:.3f} N s/mm")
        ax.plot(fit.time, fit.measured * 1e3, color="k", lw=0.8, label="measured")
        ax.plot(fit.time, fit.simulated * 1e3, color="tab:red", lw=1.0, ls="--", label="trailer, fitted")
        rx.plot(fit.time, (fit.measured - fit.simulated) * 1e3, color="tab:red", lw=0.6)
        ax.set_ylabel("rim displacement [mm]")
        rx.set_ylabel("residual [mm]")
        rx.set_xlabel("time from release [s]")
        ax.legend(fontsize=8)
        out.append(_png(fig))
    return out


def patch_figures(step) -> list[str]:
    """Half contact length and half width vs deflection with their fits (Figs. 4-2, 4-3)."""
    from ..fit.patch import contact_half_length, contact_half_width, width_from_table
    d = step.data
    r0, w0 = d["R0"], d["W0"]
    alld = np.r_[d["deflection"], d["held_deflection"]]
    x = np.linspace(max(1e-4, 0.5 * np.nanmin(alld)), 1.1 * np.nanmax(alld), 200)
    out = []
    if "length_fit" in d:
        f = d["length_fit"]
        fig, ax, rx = _pair(f"Half contact length (thesis Fig. 4-2): PA1 = {f.pa1:.4g}, PA2 = {f.pa2:.4g}")
        pred = lambda v: contact_half_length(v, f.pa1, f.pa2, r0)  # noqa: E731
        for dd, a, style in ((d["deflection"], d["half_length"], DATA),
                             (d["held_deflection"], d["held_half_length"], HELD)):
            if np.isfinite(a).any():
                ax.plot(dd * 1e3, a * 1e3, **style)
                rx.plot(dd * 1e3, (a - pred(dd)) * 1e3, **{**style, "label": None})
        ax.plot(x * 1e3, pred(x) * 1e3, color="tab:red", label=f"eq. 2.3, RMS {f.rms * 1e3:.1f} mm")
        ax.set_ylabel("half length a [mm]")
        rx.set_ylabel("residual [mm]")
        rx.set_xlabel("deflection [mm]")
        ax.legend(fontsize=8)
        out.append(_png(fig))
    if "width_table" in d:
        wt = d["width_table"]
        fig, ax, rx = _pair("Half contact width (thesis Fig. 4-3): eq. 2.4 and the table 4.4 recommends")
        for dd, b, style in ((d["deflection"], d["half_width"], DATA),
                             (d["held_deflection"], d["held_half_width"], HELD)):
            if np.isfinite(b).any():
                ax.plot(dd * 1e3, b * 1e3, **style)
                rx.plot(dd * 1e3, (b - width_from_table(wt.table, dd)) * 1e3, **{**style, "label": None})
        ax.plot(x * 1e3, width_from_table(wt.table, x) * 1e3, color="tab:green",
                label=f"table, RMS {wt.rms * 1e3:.1f} mm")
        ax.plot(x * 1e3, (wt.intercept + wt.slope * x) * 1e3, color="tab:green", ls=":",
                label=f"straight line, RMS {wt.rms_line * 1e3:.1f} mm")
        if "width_fit" in d:
            wf = d["width_fit"]
            ax.plot(x * 1e3, contact_half_width(x, wf.pb1, wf.pb2, wf.pb3, r0, w0, clip=False) * 1e3,
                    color="tab:red", ls="--", label=f"eq. 2.4, RMS {wf.rms * 1e3:.1f} mm")
        ax.set_ylabel("half width b [mm]")
        rx.set_ylabel("measured - table [mm]")
        rx.set_xlabel("deflection [mm]")
        ax.legend(fontsize=8)
        out.append(_png(fig))
    return out


def footprint_figure(test) -> str:
    """A footprint image with the outline the extraction found (red)."""
    import matplotlib.pyplot as plt

    from ..fit.footprint_image import outline_in_image, read_bitmap
    img = read_bitmap(test.source)
    fp = test.footprint
    fig, ax = plt.subplots(figsize=(5.5, 5.5))
    ax.imshow(img, interpolation="nearest")
    rows, cols = outline_in_image(fp, test.travel)
    ax.plot(cols, rows, color="red", lw=1.2)
    ax.set_title(f"{test.name} [{test.use}]: {fp.length * 1e3:.0f} x {fp.width * 1e3:.0f} mm, "
                 f"{fp.area * 1e4:.0f} cm^2 inked, {fp.gross_area * 1e4:.0f} cm^2 in the outline",
                 fontsize=9)
    ax.set_axis_off()
    return _png(fig)


def shape_figure(step) -> str:
    """The folded profile, the fitted [SHAPE] and the base file's (as the models resample it)."""
    from ..tyre.contact.shape import resample_shape
    f = step.data["fit"]
    p = f.profile
    fig, ax, rx = _pair(f"Carcass shape (thesis 4.3, Fig. 4-1): {f.table.shape[0]} points, RMS {f.rms:.4f}")
    ax.plot(p.width_ratio, p.radius_ratio, ".", color="k", ms=3, label="profile (both halves folded)")
    ax.plot(f.table[:, 1], f.table[:, 0], "o-", color="tab:red", label="fitted [SHAPE]")
    model = np.interp(p.width_ratio, f.table[:, 1], f.table[:, 0])
    rx.plot(p.width_ratio, p.radius_ratio - model, ".", color="tab:red", ms=3)
    before = step.data.get("before")
    if before is not None:
        rs = resample_shape(before)
        ax.plot(rs[:, 1], rs[:, 0], "s--", color="tab:blue", mfc="none", label="base file, resampled")
    ax.set_ylabel("radius ratio r / R0")
    rx.set_ylabel("residual")
    rx.set_xlabel("width ratio |y| / (W0 / 2)")
    ax.legend(fontsize=8)
    return _png(fig)


def cleat_figure(test, predictions) -> str:
    """A static cleat test and every analytic model's prediction (Figs. 4-13 to 4-15)."""
    fig, ax, rx = _pair(f"Static cleat {test.cleat[0] * 1e3:g} x {test.cleat[1] * 1e3:g} mm, "
                        f"{test.direction} (held out)")
    ax.plot(test.deflection * 1e3, test.load / 1e3, **{**DATA, "label": "measured"})
    for m, loads in predictions.items():
        ax.plot(test.deflection * 1e3, loads / 1e3, lw=1.2, label=m)
        rx.plot(test.deflection * 1e3, (loads - test.load) / 1e3, ".-", lw=0.8)
    ax.set_ylabel("load [kN]")
    rx.set_ylabel("model - measured [kN]")
    rx.set_xlabel("deflection [mm]")
    ax.legend(fontsize=8)
    return _png(fig)


def dynamic_figure(test) -> str:
    """A dynamic cleat run's vertical force as read."""
    import matplotlib.pyplot as plt
    run = test.signal
    col = next(c for c in ("FZW", "FZ", "FZ_HUB") if c in run.columns)
    fig, ax = plt.subplots(figsize=(7.5, 2.8))
    ax.plot(run["RUNTIME"], run[col] / 1e3, color="k", lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"{col} [kN]")
    use = "fits the ring's patch damping" if test.use == "fit" else "held out: predicted by the ring"
    ax.set_title(f"{test.name} ({use} when the ring step runs)", fontsize=9)
    ax.grid(alpha=0.3)
    return _png(fig)


def ring_figure(step) -> str:
    """The identified ring pressed on the plate at every pressure against the presses,
    fitted and held out; residuals in % (thesis 4.5)."""
    fig, ax, rx = _pair("Flexible ring on the flat plate (thesis 4.5)")
    for df, held in ((step.data["fitted"], False), (step.data["held"], True)):
        df = df[df["quantity"] == "load"]
        for k, (p, g) in enumerate(df.groupby("pressure_kPa")):
            d = np.array([float(a.split()[0]) for a in g["at"]])
            color = "tab:orange" if held else ("C0", "C2", "C4", "C5")[k % 4]
            style = dict(HELD, color=color) if held else dict(DATA, color=color)
            style["label"] = f"{p:g} kPa " + ("(held out)" if held else "(fitted)")
            ax.plot(d, g["measured"] / 1e3, **style)
            ax.plot(d, g["model"] / 1e3, color=color, lw=1.2, ls="--" if held else "-")
            rx.plot(d, g["error_pct"], color=color, marker="s" if held else "o", ms=4,
                    ls="--" if held else "-")
    ax.set_ylabel("load [kN]")
    ax.legend(fontsize=8, title="points: measured, lines: ring", title_fontsize=8)
    rx.set_ylabel("ring - measured [%]")
    rx.set_xlabel("deflection [mm]")
    return _png(fig)


def ring_table(step) -> str:
    """The ring's modes and contact lengths, fitted and held out, and the cleat runs."""
    rows = []
    for label, df in (("fitted", step.data["fitted"]), ("held out", step.data["held"])):
        for r in df[df["quantity"] != "load"].itertuples():
            rows.append(f"<tr><td>{label}</td><td>{html.escape(r.quantity)}</td><td>{r.pressure_kPa:g}</td>"
                        f"<td>{html.escape(r.at)}</td><td>{r.measured:.4g}</td><td>{r.model:.4g}</td>"
                        f"<td>{r.error_pct:+.1f}</td></tr>")
    out = ("<table><tr><th>set</th><th>quantity</th><th>kPa</th><th>at</th><th>measured</th>"
           "<th>ring</th><th>error %</th></tr>" + "".join(rows) + "</table>")
    runs = step.data.get("cleat_runs")
    if runs is not None and len(runs):
        out += ("<p>Trailer runs over cleats: RMS error of FZW in % of the measured peak, with the "
                "drop test's patch damping (before) and after the runs' fit, each where it matches "
                "the run best in time; shift: the simulation's start on the run's clock</p><table><tr>"
                "<th>road</th><th>km/h</th><th>set</th><th>shift s</th><th>before</th><th>after</th></tr>")
        out += "".join(f"<tr><td>{html.escape(r.road)}</td><td>{r.speed_kmh:.0f}</td><td>{r.set}</td>"
                       f"<td>{r.shift_s:.3f}</td><td>{r.rms_before_pct:.2f}</td><td>{r.rms_after_pct:.2f}</td></tr>"
                       for r in runs.itertuples()) + "</table>"
    return out


def summary_table(result) -> str:
    """Every fitted parameter: value, equation, fitted RMS, held-out errors, source."""
    from ..fit.workflow import shown
    head = ("<table><tr><th>parameter</th><th>value</th><th>equation / method</th><th>RMS, fitted</th>"
            "<th>error, held out</th><th>data</th></tr>")
    rows = []
    for step in result.steps.values():
        for r in step.rows:
            unit = r["error_unit"]
            held = "<br>".join(f"{html.escape(k)}: {html.escape(shown(v, unit))}"
                               for k, v in (r["held_out"] or {}).items())
            rows.append(f"<tr><td>{html.escape(r['parameter'])}</td>"
                        f"<td>{html.escape(shown(r['value'], r['unit']))}</td>"
                        f"<td>{html.escape(r['equation'])}</td><td>{html.escape(shown(r['rms'], unit))}</td>"
                        f"<td>{held}</td><td>{html.escape(r['source'])}</td></tr>")
    return head + "".join(rows) + "</table>"


def modal_table(test) -> str:
    t = test.table
    rows = "".join(f"<tr><td>{r.mode}</td><td>{r.pressure / 1e3:g}</td><td>{r.frequency:.2f}</td>"
                   f"<td>{100 * r.damping:.2f}</td></tr>" for r in t.itertuples())
    return (f"<p>{html.escape(test.name)} (Table 3-3 form)</p><table><tr><th>mode</th><th>kPa</th>"
            f"<th>Hz</th><th>damping %</th></tr>{rows}</table>")


def report_html(result, title=None, progress=None) -> str:
    """The whole page as text; ``progress()`` is called after each figure."""
    from ..fit import lab_files as lf
    c = result.campaign
    title = title or f"Fit of {c.name}"
    figs = []

    def add(caption, png):
        figs.append((caption, png))
        if progress:
            progress()

    steps = result.steps
    if "vertical" in steps:
        add("Load-deflection", vertical_figure(steps["vertical"]))
    if "damping" in steps:
        for png in damping_figure(steps["damping"]):
            add("Drop test", png)
    if "patch" in steps:
        for png in patch_figures(steps["patch"]):
            add("Contact patch", png)
    for t in c.of(lf.FootprintImage):
        add("Footprint image", footprint_figure(t))
    if "shape" in steps:
        add("Carcass shape", shape_figure(steps["shape"]))
    if "cleats" in steps:
        for t, pred in steps["cleats"].data["predictions"]:
            add("Static cleat", cleat_figure(t, pred))
    for t in c.of(lf.DynamicCleat):
        add("Dynamic cleat run", dynamic_figure(t))
    if "ring" in steps:
        add("Flexible ring", ring_figure(steps["ring"]))
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'>", f"<title>{html.escape(title)}</title>",
             "<style>body{font-family:sans-serif;max-width:62em;margin:auto}table{border-collapse:collapse}"
             "td,th{border:1px solid #999;padding:2px 6px;vertical-align:top}</style></head><body>",
             f"<h1>{html.escape(title)}</h1>", f"<p>Campaign: {html.escape(c.source)}</p>",
             "<h2>Parameters</h2>", summary_table(result), "<h2>Notes</h2><ul>"]
    parts += [f"<li>{html.escape(n)}</li>" for n in result.notes] + ["</ul>", "<h2>Tests</h2><ul>"]
    parts += [f"<li>{html.escape(t.name)}: {type(t).__name__}, {t.use}"
              f"{': ' + html.escape(t.note) if t.note else ''}</li>" for t in c.tests] + ["</ul>"]
    for t in c.of(lf.ModalResults):
        parts.append("<h2>Modal results</h2>" + modal_table(t))
    if "ring" in steps:
        parts.append("<h2>Flexible ring: modes and contact length</h2>" + ring_table(steps["ring"]))
    for caption, png in figs:
        parts.append(f"<h2>{html.escape(caption)}</h2><img alt='{html.escape(caption)}' "
                     f"src='data:image/png;base64,{png}'>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def figure_count(result) -> int:
    """How many figures :func:`report_html` draws (for a progress bar)."""
    from ..fit import lab_files as lf
    s, c = result.steps, result.campaign
    n = ("vertical" in s) + ("shape" in s) + ("ring" in s)
    n += len(c.of(lf.FootprintImage)) + len(c.of(lf.DynamicCleat))
    n += len(s["damping"].data["fits"]) if "damping" in s else 0
    n += (("length_fit" in s["patch"].data) + ("width_table" in s["patch"].data)) if "patch" in s else 0
    n += len(s["cleats"].data["predictions"]) if "cleats" in s else 0
    return n


def write_report(result, path, progress=None) -> None:
    """Write the report page (atomically)."""
    atomic_write_text(path, report_html(result, progress=progress))
