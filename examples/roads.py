"""Reading roads: an OpenCRG file and an Adams road data file (.rdf), and a run over each kind.

* ``data/my_road.crg`` -- an OpenCRG road that ``tyrelab road export`` wrote (a
  pothole 60 mm deep, 600 mm long, 1.4 m wide); read at a lateral offset of
  0.5 m from its reference line (``my_road.crg@0.5``), so the wheel runs
  through the pothole's side;
* ``data/handmade_straight.crg`` -- the ASAM OpenCRG sample road (a straight
  reference line with three smooth bumps), read through the ASAM C library;
* ``data/plateau_road.rdf`` -- an Adams 2D ``poly_line`` road (a 4.9 m hill
  over 200 m; MathWorks' Simscape Vehicle Templates).

Every road is a :class:`tyrelab.road.base.Road` with an exact, vectorised
``height(x, y)``; a road name, file name or ``FILE@OFFSET`` goes to
:func:`tyrelab.road.spec.road_from_spec` as on the command line. Writes
``roads_crg.png`` (heightmap and cut of my_road.crg@0.5) and
``roads_profiles.png`` (the other two profiles and a run's normal force)
into the folder given as the first argument (default: the current folder).

Run: ``python examples/roads.py [OUTPUT_FOLDER]``
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import tyrelab
from tyrelab.report.road_plots import plot_road
from tyrelab.road.spec import road_from_spec
from tyrelab.road.spectrum import road_profile

DATA = Path(__file__).resolve().parent / "data"
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(".")
out.mkdir(parents=True, exist_ok=True)

pothole = road_from_spec(f"{DATA / 'my_road.crg'}@0.5")
asam = road_from_spec(str(DATA / "handmade_straight.crg"))
plateau = road_from_spec(str(DATA / "plateau_road.rdf"))
for road in (pothole, asam, plateau):
    xmin, xmax, ymin, ymax = road.extent()
    print(f"{road.name}: x {xmin:g} to {xmax:g} m, y {ymin:g} to {ymax:g} m")

# heights are exact and vectorised: the pothole's floor under the wheel, the hill's top
print(f"pothole floor at x = 5.3 m, y = 0: {pothole.height(5.3, 0.0) * 1e3:.1f} mm")
x = np.linspace(*plateau.extent()[:2], 2001)
print(f"plateau.rdf: highest point {plateau.height(x, 0 * x).max():.2f} m")

# the trailer over the pothole, and over the ASAM sample road (point contact, 12 km/h, LC1)
runs = {road.name: tyrelab.simulate(model="point", road=road, speed=12 / 3.6, load="LC1", progress=False)
        for road in (pothole, asam)}
for name, run in runs.items():
    static = run["FZW"].iloc[:50].mean()
    print(f"{name}: FZW {run['FZW'].min() / 1e3:.1f} to {run['FZW'].max() / 1e3:.1f} kN "
          f"(static {static / 1e3:.1f} kN)")

plot_road(pothole).savefig(out / "roads_crg.png", dpi=90)

fig, axes = plt.subplots(3, 1, figsize=(9, 8), layout="constrained")
for ax, road in zip(axes[:2], (asam, plateau)):
    xs, zs = road_profile(road)
    ax.plot(xs, zs * 1e3, lw=0.8)
    ax.set(title=road.name, xlabel="x [m]", ylabel="height at y = 0 [mm]")
    ax.grid(True, alpha=0.3)
for name, run in runs.items():
    axes[2].plot(run["DISTANCE"], run["FZW"] / 1e3, lw=0.8, label=name)
axes[2].set(title="trailer, point contact, 12 km/h, LC1", xlabel="distance travelled [m]", ylabel="FZW [kN]")
axes[2].legend(fontsize=8)
axes[2].grid(True, alpha=0.3)
fig.savefig(out / "roads_profiles.png", dpi=90)
print(f"wrote {out / 'roads_crg.png'} and {out / 'roads_profiles.png'}")
