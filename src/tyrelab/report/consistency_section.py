"""The report's "Consistency with what the thesis measured" part (HTML).

Shown when the study's reference is the thesis's FTire TP stand-in
(:attr:`tyrelab.study.results.Study.consistency`): for each view (our variants;
our variants with the thesis's enveloping model in its "3D ENV" column) the
cells within the bound the thesis's tables impose, per model and metric; the
agreement with Table 5-15 (a linear-or-nonlinear variant matching, and both
matching); Spearman's ρ of our errors against the thesis's per metric; and,
folded, every cell with its bound. The equations are in
:mod:`tyrelab.validate.consistency`.
"""

from __future__ import annotations

import html

import numpy as np
import pandas as pd

from ..validate.consistency import COUNTED, EXACT

_NAMES = {"ours": "our variants",
          "thesis's ENV": "with the thesis's enveloping model (3D ENV edge) in the 3D ENV column"}


def _e(x) -> str:
    return html.escape(str(x))


def _cell(v) -> str:
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "<b>no</b>"
    if isinstance(v, (float, np.floating)):
        return f"{v:.3g}" if np.isfinite(v) else "&ndash;"
    return _e(v)


def _table(df: pd.DataFrame, cls: str, index_name: str | None = None) -> str:
    cols = ([index_name] if index_name else []) + [str(c) for c in df.columns]
    out = [f"<div class='scroll'><table class='{cls}'><tr>" + "".join(f"<th>{_e(c)}</th>" for c in cols)
           + "</tr>"]
    for idx, row in df.iterrows():
        cells = ([f"<td class='text'>{_e(idx)}</td>"] if index_name else []) + [
            f"<td class='text'>{_cell(v)}</td>" if isinstance(v, str) else f"<td>{_cell(v)}</td>"
            for v in row]
        out.append("<tr>" + "".join(cells) + "</tr>")
    return "\n".join(out) + "</table></div>"


def _view(name: str, view: dict) -> str:
    counts, agree, rho = view["counts"], view["agreement"], view["spearman"]
    within, cells = counts.attrs.get("within", 0), counts.attrs.get("cells", 0)
    share = f"{100.0 * within / cells:.0f} %" if cells else "&ndash;"
    out = [f"<h4>{_e(_NAMES.get(name, name))}</h4>",
           f"<p class='consistency-total' data-view='{_e(name)}'>Within the bound: <b>{within} of "
           f"{cells}</b> cells ({share}; {', '.join(COUNTED)}). Table 5-15: <b>{int(agree['any'].sum())} "
           f"of {len(agree)}</b> cells reproduced by the linear or the nonlinear variant, "
           f"{int(agree['all'].sum())} by both.</p>",
           _table(counts, "consistency-counts", "model"),
           _table(agree.rename(columns={"any": "lk or nlk", "all": "both"}).set_index("group"),
                  "consistency-5-15", "group"),
           _table(rho.set_index("metric"), "consistency-rho", "metric")]
    return "\n".join(out)


def consistency_html(result) -> str:
    """The section's HTML for a :class:`~tyrelab.validate.consistency.Consistency`, or ""."""
    if result is None or not result.views:
        return ""
    out = ["<h3 id='consistency'>Consistency with what the thesis measured</h3>",
           "<p>The thesis compared every model, and FTire TP, with the load cells; this study "
           "compares every model with its FTire TP stand-in. For an RMS error over the same "
           "samples the triangle inequality holds: RMS(model &minus; FTire TP) &le; RMS(model "
           "&minus; measured) + RMS(FTire TP &minus; measured), both terms from the thesis's "
           "Tables 5-2 to 5-10. A cell of ours above that bound says our model, our reference "
           "or our metric differs from the thesis's there. The bound is exact for "
           f"{', '.join(EXACT)} and, for the relative errors (their denominators differ between "
           "the two sides), the same sum taken as an approximate bound. Spearman's &rho;: our "
           "errors against the thesis's over every cell both tables hold.</p>"]
    for name, view in result.views.items():
        out.append(_view(name, view))
    b = result.bounds.sort_values("excess", ascending=False)
    out.append("<details><summary>Every cell and its bound (largest excess first)</summary>"
               + _table(b[["test", "speed_kmh", "load_case", "model", "metric", "ours",
                           "thesis_model_error", "thesis_reference_error", "bound", "within",
                           "exact"]].set_index("test"), "consistency-cells", "test")
               + "</details>")
    return "\n".join(out)
