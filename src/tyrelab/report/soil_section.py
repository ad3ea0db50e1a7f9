"""The study report's "On soil" section: each soil test's slip curves, as a figure and a table.

A study's soil tests (the single-wheel tester at prescribed slips, or under driving
torques, each run then at the slip the soil gave it) are read
through ``study.soil_curves`` (:func:`tyrelab.study.soil.soil_curves`: one row
per run, the steady drawbar pull ``FX`` [N], driving torque ``TORQUE`` [N m],
sinkage ``SINKAGE`` [m] and load ``FZ`` [N], and with a reference model each
model's difference from it). Per soil test condition (tyre, test, speed, load):

* a zoomable figure of three stacked panels sharing the slip axis -- drawbar
  pull [kN], driving torque [kN m], sinkage [mm] -- one trace per model
  (markers at the run slips, joined by lines), drawn into the page's
  :class:`.figure_embed.FigureSink` as the other study figures are;
* the table of those values, with the differences from the reference when the
  test has one (pull and torque in % of the reference's largest driving force
  ``max |TORQUE_ref| / R0``, sinkage relative).

Nothing is drawn when the study has no soil test.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .study_figures import _layout, load_text, title_text
from .study_sections import esc, frame_html

#: the condition of a soil test: one figure and one table each
CONDITION = ["tyre", "test", "speed_kmh", "load"]
#: the panels, top to bottom: (column, axis title, factor from SI)
PANELS = (("FX", "drawbar pull [kN]", 1e-3), ("TORQUE", "driving torque [kN m]", 1e-3),
          ("SINKAGE", "sinkage [mm]", 1e3))


def condition_title(rows: pd.DataFrame) -> str:
    """``"LETE sand slip curve: LETE sand, 3.6 km/h, 23300 N"`` (with the tyre when several)."""
    r = rows.iloc[0]
    return f"{r['test']}: {r['soil']}, {float(r['speed_kmh']):g} km/h, {load_text(r['load'])}"


def reference_text(rows: pd.DataFrame) -> str:
    """What the condition's models are compared with."""
    refs = [str(v) for v in rows.get("reference", pd.Series(dtype=object)) if isinstance(v, str) and v]
    if not refs:
        return "no reference model: the models side by side"
    return f"reference: {refs[0]} (a model, not a measurement)"


def soil_figure(rows: pd.DataFrame, title: str, colours: dict):
    """The three stacked panels of one soil condition (module notes); ``rows`` its table rows."""
    import plotly.graph_objects as go
    from plotly.subplots import make_subplots
    fig = make_subplots(rows=len(PANELS), cols=1, shared_xaxes=True, vertical_spacing=0.05)
    for k, (model, curve) in enumerate(rows.groupby("model", sort=False)):
        curve = curve.sort_values("slip")
        colour = colours.get(model, "#7f7f7f")
        for i, (column, axis, factor) in enumerate(PANELS, start=1):
            fig.add_trace(go.Scatter(x=curve["slip"].to_numpy(dtype=float),
                                     y=curve[column].to_numpy(dtype=float) * factor,
                                     name=str(model), legendgroup=str(model), showlegend=i == 1,
                                     mode="lines+markers", line={"color": colour, "width": 1.6},
                                     marker={"size": 7, "symbol": k % 12}), row=i, col=1)
    _layout(fig, title, "", "", height=760)
    for i, (_, axis, _) in enumerate(PANELS, start=1):
        fig.update_yaxes(title_text=axis, row=i, col=1)
    fig.update_xaxes(title_text="slip [-]: driving 1 - V / (R_e omega), braking R_e omega / V - 1",
                     row=len(PANELS), col=1)
    fig.update_layout(hovermode="x unified", legend={"y": -0.08})
    return fig


def soil_table(rows: pd.DataFrame) -> pd.DataFrame:
    """The values of one condition as the page prints them (kN, kN m, mm; differences in %)."""
    out = pd.DataFrame({"model": rows["model"].astype(str).to_numpy(),
                        "slip": rows["slip"].to_numpy(dtype=float),
                        "drawbar pull FX [kN]": rows["FX"].to_numpy(dtype=float) * 1e-3,
                        "driving torque [kN m]": rows["TORQUE"].to_numpy(dtype=float) * 1e-3,
                        "sinkage [mm]": rows["SINKAGE"].to_numpy(dtype=float) * 1e3,
                        "FZ [kN]": rows["FZ"].to_numpy(dtype=float) * 1e-3})
    diffs = rows.get("FX_diff_pct")
    if diffs is not None and np.isfinite(diffs.to_numpy(dtype=float)).any():
        out["pull - reference [% of F_ref]"] = diffs.to_numpy(dtype=float)
        out["torque - reference [% of R0 F_ref]"] = rows["TORQUE_diff_pct"].to_numpy(dtype=float)
        out["sinkage - reference [%]"] = rows["SINKAGE_diff_pct"].to_numpy(dtype=float)
    return out


def soil_section(study, figs, colours: dict) -> str:
    """The "On soil" section (module notes) as HTML; "" when the study has no soil test."""
    table = getattr(study, "soil_curves", None)
    if table is None or len(table) == 0:
        return ""
    out = ["<section id='soil'><h2>On soil</h2><p>Each soil test drives the single-wheel tester "
           "through the soil at each slip, or under each driving torque (its slip then the soil's "
           "answer); the values are the means over the steady last part of "
           "each run (drawbar pull positive forward; sinkage of the wheel's lowest point below the "
           "undisturbed surface). These tests stay out of the summary and the comparison with the "
           "thesis, which are about its rigid-road tests.</p>"]
    several = table["tyre"].nunique() > 1
    for n, (_, rows) in enumerate(table.groupby(CONDITION, sort=False), start=1):
        title = condition_title(rows) + (f" ({rows['tyre'].iloc[0]})" if several else "")
        note = reference_text(rows)
        out.append(f"<section class='soil-test' id='soil-{n}'><h3>{esc(title)}</h3>")
        caption = (f"{title}: steady drawbar pull, driving torque and sinkage against slip, one "
                   f"trace per model; {note}.")
        out.append(figs.add(soil_figure(rows, title_text(
            f"{title}: pull, torque and sinkage against slip", note), colours), "soil", caption))
        what = (f"{title}: steady means per model and slip; {note}" + (
            ". Pull and torque differences in % of the reference's largest driving force "
            f"F_ref = max |torque| / R0 = {rows['force_scale_N'].iloc[0] / 1e3:.3g} kN, sinkage "
            "relative to the reference's" if np.isfinite(rows["force_scale_N"].to_numpy(
                dtype=float)).any() else ""))
        out.append(frame_html(soil_table(rows), what))
        out.append("</section>")
    return "\n".join(out) + "</section>\n"
