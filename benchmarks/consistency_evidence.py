"""The runs behind docs/consistency.md: what makes our campaign differ from the thesis's.

    python benchmarks/consistency_evidence.py [RESULTS]

1. Every contact model pressed over the 50 mm cleat on the fixed-axle rolling rig at
   1 km/h (LC1, 300 kPa): the force's rise above the static load (the models'
   enveloping, free of the trailer's dynamics).
2. The ring converged in its discretisation on the trailer (50 mm cleat, 12 km/h):
   the peak and the trough of FZ_HUB over the cleat at 100 x 10, 200 x 10, 100 x 20.
3. With a finished built-in campaign folder RESULTS (``tyrelab study -o RESULTS``): its
   consistency with the thesis (cells within the bound, Table 5-15, Spearman's rho),
   and per model over the 50 mm cleat at 12 km/h the disturbance's RMS error against
   the reference, the peak, the rise of the wheel centre and the airborne time.

Not a test: it prints figures for a person (about 2 minutes without RESULTS).
"""

from __future__ import annotations

import sys

import numpy as np

import tyrelab
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

MODELS = [("ring-tp", None), ("ring", None), ("volume", "table"), ("enveloping", "table"),
          ("enveloping-edge", "table"), ("point", "table")]


def quasi_static_envelopes(speed_kmh: float = 1.0) -> None:
    print("1. fixed axle over cleat:50x50 at 1 km/h, LC1: force rise over the static load")
    for model, stiffness in MODELS:
        s = tyrelab.simulate(model=model, stiffness=stiffness, road="cleat:50x50", rig="rolling",
                             speed=speed_kmh / 3.6, load="LC1", pressure=300e3,
                             duration=7.0 / (speed_kmh / 3.6), progress=False)
        x, f = s["X_WC"].to_numpy(), s["FZ"].to_numpy()
        near = (x > 4.0) & (x < 6.5)
        print(f"   {model:16s} static {f[50] / 1e3:6.1f} kN  rise {(f[near].max() - f[50]) / 1e3:5.1f} kN")


def ring_convergence() -> None:
    print("2. ring on the trailer, cleat:50x50, 12 km/h, LC1: FZ_HUB over the cleat")
    tyre = load_tyre("xzl-16.00R20", 300e3)
    left = TyreModel(tyre, contact="point")
    for options in ({}, {"n_segments": 200}, {"n_blocks": 20}):
        s = Trailer(TyreModel(tyre, contact="ring", options=options), "LC1", left=left).run(
            "cleat:50x50", 12 / 3.6, duration=2.2)
        t, f = s["RUNTIME"].to_numpy(), s["FZ_HUB"].to_numpy()
        k = (t > 1.38) & (t < 1.62)
        print(f"   {str(options or 'default (100 x 10)'):22s} peak {f[k].max() / 1e3:5.2f} kN  "
              f"trough {f[k].min() / 1e3:5.2f} kN")


def campaign(folder: str) -> None:
    from tyrelab.study import open as open_study
    st = open_study(folder)
    c = st.consistency
    if c is None:
        print(f"3. {folder}: no test is referenced to a model named 'FTire TP'")
        return
    for name, view in c.views.items():
        counts, agree = view["counts"], view["agreement"]
        print(f"3. {name}: within the bound {counts.attrs['within']} of {counts.attrs['cells']}; "
              f"Table 5-15 {int(agree['any'].sum())} of {len(agree)} (both {int(agree['all'].sum())})")
        print(view["spearman"].to_string(index=False))
    m = st.metrics
    sel = m[(m["test"] == "cleat 50x50 perpendicular") & (m["speed_kmh"] == 12)]
    ref = st.signal(sel[sel["is_reference"]]["key"].iloc[0])
    t, q = ref["RUNTIME"].to_numpy(), ref["FZ_HUB"].to_numpy()
    row = sel.iloc[0]
    k = (t >= row["disturbance_start_s"]) & (t <= row["disturbance_end_s"])
    print("   cleat 50x50, 12 km/h: model, RMS over the disturbance, peak, wheel-centre rise, airborne")
    for r in sel.itertuples():
        s = st.signal(r.key)
        # the campaign's store keeps FZ (the wheel centre's), not the patch's FZW: for the
        # analytic models on a level wheel they are one; a ring's FZ also carries its belt's
        # inertia, so for the rings "airborne" is FZ <= 0 at the rim
        p, z, fw = s["FZ_HUB"].to_numpy(), s["Z_WC"].to_numpy(), s["FZ"].to_numpy()
        rms = float(np.sqrt(np.mean((p[k] - q[k]) ** 2)))
        rise = z[(t > 1.3) & (t < 1.8)].max() - z[0]
        airborne = np.sum(fw[t > 0.5] <= 0) * 1e-3   # 1 kHz output
        print(f"   {r.model:16s} {rms / 1e3:6.2f} kN  {p[k].max() / 1e3:5.1f} kN  "
              f"{1e3 * rise:5.1f} mm  {airborne:5.3f} s")


if __name__ == "__main__":
    quasi_static_envelopes()
    ring_convergence()
    if len(sys.argv) > 1:
        campaign(sys.argv[1])
