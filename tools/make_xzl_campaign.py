"""Write the example test campaign examples/xzl_campaign/ from the thesis's published XZL data.

Developer tool, run once when the reference data change:

    python tools/make_xzl_campaign.py ../shared/reference/xzl_16.00R20 examples/xzl_campaign

It is never run by the package or its tests; the files it writes are the
example. What the thesis tabulates is copied (Table 3-2, Table 3-3); what it
shows only in figures is stood in for, and each such file says so in its
header and in the manifest's note:

* carcass_profile.csv: points on Table 4-1's polyline, both halves (the
  measured contour, Figure 3-4, is not tabulated);
* contact_patch.csv: the half length of eq. 2.3 with the thesis's PA1, PA2
  (Figure 4-2's measurements are not tabulated) and the width of the
  Table 4-1 contour cut by the plate (a geometric estimate; Figure 4-3's
  widths are not tabulated);
* footprint_LC1.png: a rounded patch of that length and width at the LC1
  load, with the 100 mm calibration line (Figure 3-6 is not public);
* drop_test.csv: tyrelab's trailer drop test (point model, 2.66 N s/mm of
  section 3.4.1) with 0.1 mm of noise (Figure 3-13's trace is not tabulated).
"""

import csv
import sys
import tomllib
from pathlib import Path

import numpy as np

from tyrelab.fit.damping import simulated_drop
from tyrelab.fit.footprint_image import render_footprint, write_bitmap
from tyrelab.tyre.library import load_tyre

src, dst = Path(sys.argv[1]), Path(sys.argv[2])
dst.mkdir(parents=True, exist_ok=True)
spec = tomllib.loads((src / "tyre.toml").read_text())
t, cp = spec["tyre"], spec["contact_patch"]
R0 = t["overall_diameter_m"] / 2
W0 = t["overall_width_m"]
shape = np.array([[float(r["radial_ratio"]), float(r["width_ratio"])]
                  for r in csv.DictReader(open(src / "carcass_shape.csv"))])

(dst / "load_deflection.csv").write_text(
    "# thesis Table 3-2: flat-plate load-deflection, mean of the hysteresis loop, 100/300/550 kPa\n"
    + (src / "load_deflection.csv").read_text())
(dst / "modal.csv").write_text("# thesis Table 3-3: modal frequencies and damping, 40 kN impulse\n"
                               + (src / "modal.csv").read_text())

y = np.linspace(-W0 / 2, W0 / 2, 147)
r = np.interp(np.abs(y) / (W0 / 2), shape[:, 1], shape[:, 0]) * R0
with open(dst / "carcass_profile.csv", "w") as fh:
    fh.write("# STAND-IN: points on thesis Table 4-1's polyline, both halves (Figure 3-4 is not tabulated)\n")
    fh.write("y_mm,radius_mm\n")
    fh.writelines(f"{a * 1e3:.2f},{b * 1e3:.2f}\n" for a, b in zip(y, r))


def half_length(d):  # eq. 2.3, thesis PA1, PA2
    x = d / R0
    return cp["PA1"] * R0 * (x + cp["PA2"] * np.sqrt(x))


def half_width(d):  # the Table 4-1 contour cut by the plate at deflection d
    w = np.linspace(0, 1, 20001)
    inside = np.interp(w, shape[:, 1], shape[:, 0]) * R0 > R0 - d
    return w[inside].max() * W0 / 2


deflections = np.arange(20, 86, 5) / 1e3
with open(dst / "contact_patch.csv", "w") as fh:
    fh.write("# STAND-IN: length = 2 a of eq. 2.3 with the thesis's PA1 = 0.15, PA2 = 7.06 (Figure 4-2's\n"
             "# points are not tabulated); width = the Table 4-1 contour cut by the plate (geometric\n"
             "# estimate; Figure 4-3's points are not tabulated). Whole patch, mm.\n")
    fh.write("deflection_mm,length_mm,width_mm\n")
    fh.writelines(f"{d * 1e3:.1f},{2e3 * half_length(d):.1f},{2e3 * half_width(d):.1f}\n"
                  for d in deflections)

tyre = load_tyre("xzl-16.00R20", 300e3)
lc1 = 2375 * 9.80665
d1 = tyre.static_deflection(lc1)
a1, b1 = half_length(d1), half_width(d1)
img = render_footprint(lambda x, yy: (np.abs(x) / a1) ** 4 + (np.abs(yy) / b1) ** 4 <= 1.0, 2 * a1, 2 * b1,
                       scale=0.001, line_length=0.1)
write_bitmap(dst / "footprint_LC1.png", img)

time = np.arange(0.0, 3.0, 1e-3)
z = simulated_drop(tyre, time, "LC1") + R0
z += np.random.default_rng(2011).normal(0.0, 1e-4, z.size)
with open(dst / "drop_test.csv", "w") as fh:
    fh.write("# STAND-IN: tyrelab's trailer drop test (LC1, point model, XZL 300 kPa Table 3-2 law,\n"
             "# 2.66 N s/mm of thesis 3.4.1) plus 0.1 mm of noise; Figure 3-13's trace is not tabulated.\n")
    fh.write("time_s,z_mm\n")
    fh.writelines(f"{a:.3f},{b * 1e3:.3f}\n" for a, b in zip(time, z))
print(f"written to {dst}; LC1 static deflection {d1 * 1e3:.1f} mm, "
      f"footprint {2e3 * a1:.0f} x {2e3 * b1:.0f} mm")
