"""A model comparison with the validation page: three contact models against a measurement.

The one-point, 3D equivalent volume and 3D enveloping contact models (table
stiffness) drive the trailer over the 50 x 50 mm cleat at 12 km/h, LC1, and
each is compared with ``data/measured.tdx`` -- a **synthetic** measurement
(the enveloping model plus 1 % noise, see ``data/make_data.py``; the thesis's
measured signals are not public) -- with the thesis's metrics and more
(:func:`tyrelab.validate.compare_runs`). Writes into the folder given as the
first argument (default: the current folder):

* ``model_comparison.png``: the measured and simulated vertical force;
* ``model_comparison.md``: the metrics table, best three of each metric marked;
* ``model_comparison.html``: the validation page of the point model (overlay,
  relative error over time, force distributions, spectra), as
  ``tyrelab validate`` writes it.

Run: ``python examples/model_comparison.py [OUTPUT_FOLDER]``
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import tyrelab
from tyrelab.measure import read_run
from tyrelab.report.plots import plot_runs
from tyrelab.report.validation_page import page_html, write_page
from tyrelab.validate import align, compare_aligned, metric_row, metrics_table, table_html, table_markdown

DATA = Path(__file__).resolve().parent / "data"
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
out.mkdir(parents=True, exist_ok=True)

measured = read_run(DATA / "measured.tdx")          # TYDEX -> the signal table, SI
models = {"OPC": "point", "3D VC": "volume", "3D ENV": "enveloping"}
runs = {label: tyrelab.simulate(model=contact, stiffness="table", road="cleat:50x50", speed=12 / 3.6,
                                load="LC1", output_rate=500, progress=False)
        for label, contact in models.items()}

rows, pages = {}, {}
for label, run in runs.items():
    aligned = align(run, measured, channel="FZ")    # the simulation on the measured time base
    result = compare_aligned(aligned, segments="auto")   # disturbance / response from the signal
    rows[label] = metric_row(result)
    pages[label] = (aligned, result)
    print(f"{label:7s} peak FZ {run['FZ'].max() / 1e3:5.1f} kN   m%RE disturbance "
          f"{result['mRE_disturbance_pct']:5.1f} %   response {result['mRE_response_pct']:5.1f} %")
print(f"measured peak FZ {measured['FZ'].max() / 1e3:5.1f} kN")

table = metrics_table(rows)
(out / "model_comparison.md").write_text(table_markdown(table, best=1), encoding="utf-8")
print(table_markdown(table, best=1))

fig = plot_runs(list(runs.values()), labels=list(runs), channel="FZ")
ax = fig.axes[0]
ax.plot(measured["RUNTIME"], measured["FZ"] / 1e3, color="k", lw=0.6, label="measured (synthetic)")
ax.set_xlim(1.0, 4.0)
ax.legend()
fig.savefig(out / "model_comparison.png", dpi=100)

aligned, result = pages["OPC"]
write_page(out / "model_comparison.html",
           page_html("Validation: point contact vs measured.tdx", table_html(table, best=0),
                     aligned, result))
print(f"wrote {out / 'model_comparison.png'}, {out / 'model_comparison.md'}, "
      f"{out / 'model_comparison.html'}")
