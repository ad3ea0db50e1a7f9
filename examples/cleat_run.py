"""A cleat run and its plot: the thesis's test wheel over a 50 x 50 mm cleat.

The towed trailer carries the XZL 16.00R20 (300 kPa) at load case LC1 over a
50 mm high, 50 mm long cleat at 12 km/h; the one-point contact model. Writes
``cleat_run.parquet`` (the signal table) and ``cleat_run.png`` (the normal
force against time, as thesis Figure 5-4) into the folder given as the first
argument (default: the current folder).

Run: ``python examples/cleat_run.py [OUTPUT_FOLDER]``
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no window: write files only

import tyrelab
from tyrelab.report.plots import plot_runs

out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
out.mkdir(parents=True, exist_ok=True)

# SI in Python: speed in m/s, loads in N; "LC1" is thesis Table 3-4's first load case
run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, load="LC1", progress=False)
tyrelab.write_signal(run, out / "cleat_run.parquet")

static = run["FZW"].iloc[:100].mean()     # the first 0.1 s, before the cleat at x = 5 m
peak = run["FZW"].max()
at = run["RUNTIME"][run["FZW"].idxmax()]
print(f"static load {static / 1e3:.1f} kN, peak {peak / 1e3:.1f} kN at {at:.2f} s "
      f"({peak / static:.2f} x static)")

fig = plot_runs([run], labels=["point contact"])
fig.savefig(out / "cleat_run.png", dpi=100)
print(f"wrote {out / 'cleat_run.parquet'} and {out / 'cleat_run.png'}")
