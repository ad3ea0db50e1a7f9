"""Rebuild the generated example inputs of this folder (run from anywhere).

* ``my_road.crg``: an OpenCRG road written by ``tyrelab road export``: a
  pothole 60 mm deep, 600 mm long and 1.4 m wide at x = 5 m, on a grid of
  20 mm along and 100 mm across (single precision, about 170 kB). With
  ``my_road.crg@0.5`` the wheel runs 0.5 m left of the reference line,
  through the pothole's side.
* ``my.tir``: a copy of the built-in XZL 16.00R20 at 300 kPa, standing for
  your own property file.
* ``measured.tdx``: a **synthetic** "measurement" in TYDEX format: the
  enveloping contact model (table stiffness) on the trailer over the 50 x 50
  mm cleat at 12 km/h and LC1, sampled at 500 Hz, with seeded white noise of
  1 % of the static load added to the force channels. It is not a
  measurement of a real tyre; the thesis's measured signals are not public.

The other files are copies of test data (see README.md beside this file).
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
#: the road name written to my_road.crg and its grid spacing [m]
ROAD = "pothole:60x600x1400"
ROAD_SPACING = ("0.02", "0.1")
#: the test measured.tdx stands for, and the model that "measures" it
MEASURED = dict(model="enveloping", stiffness="table", road="cleat:50x50", speed=12 / 3.6, load="LC1",
                output_rate=500.0)
#: channels kept in measured.tdx
CHANNELS = ["RUNTIME", "X_WC", "FX", "FZ", "FZW", "FZ_HUB"]
#: decimals kept in SI (time to 1 us, position to 0.1 mm, forces to 1 N): a file of 150 kB
DECIMALS = {"RUNTIME": 6, "X_WC": 4}
#: noise on the force channels, as a fraction of the static load, and its seed
NOISE, SEED = 0.01, 17

SYNTHETIC_NOTE = [
    "SYNTHETIC DATA, NOT A MEASUREMENT: written by examples/data/make_data.py from a",
    "tyrelab simulation (enveloping contact, table stiffness, XZL 16.00R20 at 300 kPa,",
    "towed trailer, cleat 50 x 50 mm, 12 km/h, load case LC1, 500 Hz) with seeded white",
    "noise of 1 % of the static load added to the force channels.",
]


def measured_table():
    """The synthetic measurement as a signal table (SI)."""
    import tyrelab

    run = tyrelab.simulate(**MEASURED, progress=False)
    out = run[CHANNELS].copy()
    out.attrs = dict(run.attrs)
    out.attrs["units"] = {c: u for c, u in run.attrs.get("units", {}).items() if c in CHANNELS}
    rng = np.random.default_rng(SEED)
    static = float(run["FZ"].iloc[:50].mean())
    for col in CHANNELS:
        if col.startswith("F"):
            out[col] = out[col].to_numpy() + rng.normal(0.0, NOISE * static, len(out))
    out["FZW"] = out["FZW"].clip(lower=0.0)  # a normal force never pulls
    for col in CHANNELS:
        out[col] = out[col].round(DECIMALS.get(col, 0))
    meta = dict(out.attrs.get("metadata", {}))
    meta["name"] = "synthetic-cleat50-12kmh-LC1"
    meta["synthetic"] = " ".join(SYNTHETIC_NOTE)
    out.attrs["metadata"] = meta
    return out


def write_measured(path: Path) -> Path:
    """Write ``measured.tdx`` (forces in kN) with the synthetic note in ``**COMMENTS``."""
    from tyrelab.io_atomic import atomic_write_text
    from tyrelab.measure.tydex import tydex_text

    table = measured_table()
    units = {c: "kN" for c in CHANNELS if c.startswith("F")}
    text = tydex_text(table, units=units, header={"MEASID": "synthetic-cleat50-12kmh-LC1",
                                                  "SUPPLIER": "tyrelab (synthetic)"})
    head, tail = text.split("**COMMENTS\n", 1)
    text = head + "**COMMENTS\n" + "\n".join(SYNTHETIC_NOTE) + "\n" + tail
    atomic_write_text(path, text, newline="\n")
    return path


def main(folder: Path = HERE) -> int:
    from importlib import resources

    from tyrelab.cli.main import main as tyrelab

    folder.mkdir(parents=True, exist_ok=True)
    code = tyrelab(["road", "export", ROAD, "--spacing", *ROAD_SPACING, "--format", "KRBI",
                    "-o", str(folder / "my_road.crg")])
    if code:
        return code
    with resources.as_file(resources.files("tyrelab.tyre") / "data" / "xzl-16.00R20_300kPa.tir") as tir:
        shutil.copyfile(tir, folder / "my.tir")
    write_measured(folder / "measured.tdx")
    print(f"{folder}: my_road.crg, my.tir, measured.tdx")
    return 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]) if len(sys.argv) > 1 else HERE))
