"""Record or compare golden traces: behaviour that a refactor must not change.

    python tools/golden.py record     # writes tests/data/golden/*.npz
    python tools/golden.py compare    # prints the largest relative difference per case
    python tools/golden.py record ring        # only the cases whose name contains "ring"
    python tools/golden.py compare '!ring'    # every case except those

Each case is a public-API run (`tyrelab.simulate`, the static press, the
ring's fixed-height roll); its channels are stored at full output rate.
`tests/test_golden.py` compares against the same files.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

GOLDEN = Path(__file__).resolve().parents[1] / "tests" / "data" / "golden"
CHANNELS = ("FZW", "FX", "FY", "MX")
MODELS = ("point", "volume", "enveloping", "ring", "ring-tp")
ROADS = {"cleat": ("cleat:50x50", 2.5), "oblique": ("cleat:50x50@45", 2.5),
         "paving": ("belgian-paving", 20.0 / (12 / 3.6)), "step": ("step:50", 2.5)}
LOADS = ("LC1", "LC3")


def trailer_cases():
    for model in MODELS:
        for rname, (road, duration) in ROADS.items():
            for load in LOADS:
                yield f"trailer-{model}-{rname}-{load}", dict(model=model, road=road,
                                                               load=load, duration=duration)


def extra_cases():
    """Handling models and the other rigs."""
    yield "trailer-point-pac89-cleat-hmmwv", dict(tyre="hmmwv-pac89", model="point",
                                                  handling="pac89", road="cleat:50x50",
                                                  load=15000.0, duration=2.5)
    yield "trailer-volume-pac89-oblique-hmmwv", dict(tyre="hmmwv-pac89", model="volume",
                                                     handling="pac89", road="cleat:50x50@45",
                                                     load=15000.0, duration=2.5)
    yield "quarter-point-cleat-LC1", dict(model="point", road="cleat:50x50", load="LC1",
                                          rig="quarter-vehicle", duration=2.5)
    yield "quarter-enveloping-step-LC1", dict(model="enveloping", road="step:50", load="LC1",
                                              rig="quarter-vehicle", duration=2.5)


def run_case(kw):
    import tyrelab
    run = tyrelab.simulate(speed=12 / 3.6, progress=False, **kw)
    return {c: run[c].to_numpy() for c in CHANNELS + ("FZ",)}


def static_cases():
    d = np.linspace(0.0, 0.06, 7)
    for model in ("point", "volume", "enveloping", "ring"):
        for test, direction in (("plate", "lateral"), ("cleat:51x51", "lateral"),
                                ("cleat:51x51", "longitudinal")):
            if model == "ring" and test != "plate":
                continue
            name = f"press-{model}-{test.replace(':', '')}-{direction}"
            yield name, (model, d, test, direction)


def run_static(args):
    import tyrelab
    from tyrelab.rig.static_press import static_press
    model, d, test, direction = args
    tm = tyrelab.make_tyre_model(model=model)
    table = static_press(tm, d, test, direction)
    return {c: table[c].to_numpy() for c in ("load", "FX", "FY", "DEFLECT")}


def all_cases():
    for name, kw in list(trailer_cases()) + list(extra_cases()):
        yield name, run_case, kw
    for name, args in static_cases():
        yield name, run_static, args


def _selected(name, pattern):
    if pattern is None:
        return True
    if pattern.startswith("!"):
        return pattern[1:] not in name
    return pattern in name


def main(mode, pattern=None):
    GOLDEN.mkdir(parents=True, exist_ok=True)
    worst = 0.0
    for name, fn, args in all_cases():
        if not _selected(name, pattern):
            continue
        got = fn(args)
        path = GOLDEN / f"{name}.npz"
        if mode == "record":
            np.savez_compressed(path, **got)
            print("recorded", name, flush=True)
            continue
        ref = np.load(path)
        rel = max(relative_difference(got[k], ref[k]) for k in ref.files)
        worst = max(worst, rel)
        print(f"{name:45s} {rel:.2e}", flush=True)
    if mode == "compare":
        print("worst", worst)


def relative_difference(a, b):
    """max |a - b| over max |b| (the channel's scale), the scale at least 1 (N, N m, m, rad);
    inf if the lengths differ.

    The floor: a channel that is zero by physics (FY of the point model, which has no
    lateral force) holds only rounding noise of ~1e-13 N, whose "relative" change says
    nothing; against the floor, 1e-9 still means a nanonewton on a tyre carrying tens
    of kilonewtons.
    """
    if a.shape != b.shape:
        return np.inf
    scale = max(np.max(np.abs(b)), 1.0)
    return float(np.max(np.abs(a - b)) / scale)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "compare", sys.argv[2] if len(sys.argv) > 2 else None)
