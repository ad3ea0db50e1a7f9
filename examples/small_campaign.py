"""A small campaign: two contact models over a cleat, evaluated against a measurement.

A study spec (TOML, the form ``tyrelab study --example`` prints) names the
tyres, the model variants, the tests with their speeds and load cases, and
each test's reference -- here the **synthetic** measurement
``data/measured.tdx`` (see ``data/make_data.py``). :func:`tyrelab.study.run`
runs every simulation as a Dask task on two local worker processes, keeps
each run's signal table under a key of its complete specification (a rerun
computes nothing), evaluates the chapter-5 metrics against the reference and
writes the HTML report. Writes ``small_study/`` (the results folder with
``report.html``), the spec ``small_study.toml`` and ``small_campaign.png``
into the folder given as the first argument (default: the current folder).

Run: ``python examples/small_campaign.py [OUTPUT_FOLDER]``
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from tyrelab import study
from tyrelab.report.plots import plot_runs

DATA = Path(__file__).resolve().parent / "data"

SPEC = """
[study]
name = "small-campaign"
output = "small_study"           # results folder, relative to this file's folder

[[tyre]]
name = "xzl"
file = "xzl-16.00R20"
pressure_kpa = 300

[[model]]
name = "OPC lk"                  # one-point contact, linear stiffness
contact = "point"
stiffness = "linear"

[[model]]
name = "3D ENV nlk"              # enveloping contact, load-deflection table
contact = "enveloping"
stiffness = "table"

[[test]]
name = "cleat 50x50 perpendicular"
road = "cleat:50x50"
speeds_kmh = [12]
loads = ["LC1"]
duration = 6.0
reference = { files = ["{measured}"] }   # synthetic, see data/make_data.py
"""


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    # the reference file by its absolute path (relative paths count from the spec's folder)
    spec_file = out / "small_study.toml"
    spec_file.write_text(SPEC.replace("{measured}", (DATA / "measured.tdx").as_posix()), encoding="utf-8")
    result = study.run(spec_file, workers=2, progress=False)
    print(result.index[["model", "test", "speed_kmh", "load", "status"]].to_string(index=False))
    metrics = result.metrics.set_index("model")
    cols = ["mRE_disturbance_pct", "mRE_response_pct", "max_error_pct"]
    print(metrics[cols].round(1).to_string())
    print(f"report: {result.folder / study.REPORT}")

    runs = [result.signal(key) for key in result.index["key"]]
    fig = plot_runs(runs, labels=list(result.index["model"]), channel="FZ_HUB")
    measured = result.signal("measured.tdx")      # the reference, by its file name
    ax = fig.axes[0]
    ax.plot(measured["RUNTIME"], measured["FZ_HUB"] / 1e3, color="k", lw=0.6, label="measured (synthetic)")
    ax.set_xlim(1.0, 4.0)
    ax.legend()
    fig.savefig(out / "small_campaign.png", dpi=100)
    print(f"wrote {out / 'small_campaign.png'}")


if __name__ == "__main__":  # the Dask workers are new processes: they import this file
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
