"""Fitting a tyre: a test campaign in, a property file out, and the drop test by the thesis's procedure.

1. **The campaign** (thesis chapter 4): ``examples/xzl_campaign`` holds the
   XZL 16.00R20's lab tests at 300 kPa -- the plate load-deflection (Table
   3-2), a trailer drop-test trace, contact-patch sizes and a footprint
   image, the carcass profile -- with a manifest, ``campaign.toml`` (files
   the thesis shows only as figures are labelled stand-ins).
   :func:`tyrelab.fit.workflow.fit_campaign` fits the vertical stiffness and
   load-deflection table (eq. 4.1), the damping, PA1/PA2 (eq. 2.3), PB1-PB3
   (eq. 2.4) and the ``[SHAPE]`` table, as ``tyrelab fit all --skip ring``
   does (the ring step, in ``fit all`` by default, takes minutes); the
   fitted file then drives the enveloping model over the 50 mm cleat beside
   the built-in XZL.
2. **The drop test** (thesis 3.4.1, eqs. 3.1-3.7): a simulated drop of the
   trailer goes through the thesis's own pendulum procedure,
   :func:`tyrelab.fit.damping.drop_test_damping`. The simulated tyre's
   damping is known, so this checks the procedure; on a measured trace
   (``tyrelab.measure.read_run``) the same call identifies a real tyre.

Writes ``xzl_fitted.tir``, its fit report ``xzl_fitted_fit.html`` and
``fit_tyre.png`` into the folder given as the first argument (default: the
current folder).

Run: ``python examples/fit_tyre.py [OUTPUT_FOLDER]``
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from scipy.signal import find_peaks

import tyrelab
from tyrelab.fit.campaign import read_campaign
from tyrelab.fit.damping import drop_test_damping
from tyrelab.fit.workflow import STEPS, fit_campaign
from tyrelab.report.fit_report import write_report
from tyrelab.rig.trailer import Trailer
from tyrelab.tyre.tir import write_tir

CAMPAIGN = Path(__file__).resolve().parent / "xzl_campaign"
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
out.mkdir(parents=True, exist_ok=True)

# -- 1. the campaign -> a property file ------------------------------------------------------
steps = [s for s in STEPS if s != "ring"]  # the ring: tyrelab fit ring examples/xzl_campaign
result = fit_campaign(read_campaign(CAMPAIGN), steps, skip_missing=True, skipped=("ring",))
write_tir(result.tir, out / "xzl_fitted.tir", units=result.tir.units or None)
write_report(result, out / "xzl_fitted_fit.html")
fitted = tyrelab.load_tyre(out / "xzl_fitted.tir")
builtin = tyrelab.load_tyre("xzl-16.00R20", 300e3)
print(f"campaign fit: stiffness {fitted.vertical_stiffness / 1e3:.0f} N/mm "
      f"(built-in {builtin.vertical_stiffness / 1e3:.0f}), "
      f"damping {fitted.vertical_damping / 1e3:.2f} N s/mm (built-in {builtin.vertical_damping / 1e3:.2f})")

runs = {name: tyrelab.simulate(tyre=tyre, model="enveloping", road="cleat:50x50", speed=12 / 3.6,
                               load="LC1", progress=False)
        for name, tyre in (("built-in XZL", builtin), ("fitted from the campaign", fitted))}
for name, run in runs.items():
    print(f"{name}: peak FZW over the 50 mm cleat {run['FZW'].max() / 1e3:.1f} kN")

# -- 2. the drop test by the thesis's pendulum procedure (eqs. 3.1-3.7) -----------------------
model = tyrelab.make_tyre_model("xzl-16.00R20", "point", pressure=300e3, stiffness="linear")
trace = tyrelab.simulate(model="point", stiffness="linear", rig="drop", load="LC1", duration=4.0,
                         progress=False)
t, z = trace["RUNTIME"].to_numpy(), trace["Z_WC"].to_numpy()
# the pendulum of eq. 3.1: the trailer's pitch inertia about the hitch and the hitch-to-axle lever
trailer = Trailer(model, "LC1")
inertia, lever = float(trailer.setup.inertia[1, 1]), float(trailer.geometry.hitch_to_axle)
fit = drop_test_damping(t, z, inertia=inertia, lever=lever, wheels=2, cycles=3)

c_file, k_file = model.tyre.vertical_damping, model.tyre.vertical_stiffness
print(f"damping ratio {fit.ratio * 100:.1f} %, natural frequency {fit.frequency:.2f} Hz")
print(f"damping   identified {fit.damping / 1e3:.2f} N s/mm, tyre file {c_file / 1e3:.2f} N s/mm")
print(f"stiffness identified {fit.stiffness / 1e3:.0f} N/mm, tyre file {k_file / 1e3:.0f} N/mm")

fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7), layout="constrained")
for (name, run), style in zip(runs.items(), ("-", "--")):
    ax1.plot(run["RUNTIME"], run["FZW"] / 1e3, style, lw=1.2, label=name)
ax1.set(xlim=(1.0, 4.0), xlabel="time [s]", ylabel="FZW [kN]",
        title="enveloping model over the 50 x 50 mm cleat, 12 km/h, LC1")
ext = np.sort(np.r_[find_peaks(z)[0], find_peaks(-z)[0]])[:8]
ax2.plot(t, z * 1e3, lw=1.0, label="axle height Z_WC (simulated drop test)")
ax2.plot(t[ext], z[ext] * 1e3, "o", label="extremes of the three cycles (eq. 3.6)")
ax2.set(xlabel="time [s]", ylabel="Z_WC [mm]",
        title=f"drop test: xi = {fit.ratio * 100:.1f} %, c = {fit.damping / 1e3:.2f} N s/mm per tyre")
for ax in (ax1, ax2):
    ax.grid(True, alpha=0.3)
    ax.legend()
fig.savefig(out / "fit_tyre.png", dpi=100)
print(f"wrote {out / 'xzl_fitted.tir'}, {out / 'xzl_fitted_fit.html'} and {out / 'fit_tyre.png'}")
