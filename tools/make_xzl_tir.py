"""Write the built-in XZL 16.00R20 property files from the thesis's published data.

Developer tool, run once when the reference data change:

    python tools/make_xzl_tir.py ../shared/reference/xzl_16.00R20 src/tyrelab/tyre/data

It is never run by the package or its tests; the .tir files it writes are
package data. Numbers are written in the units the thesis publishes them in
(mm, N) to show off, and to exercise, the [UNITS] conversion.
"""

import csv
import sys
import tomllib
from pathlib import Path

src, dst = Path(sys.argv[1]), Path(sys.argv[2])
spec = tomllib.loads((src / "tyre.toml").read_text())
rows = list(csv.DictReader(open(src / "load_deflection.csv")))
shape = list(csv.DictReader(open(src / "carcass_shape.csv")))
t, v, cp = spec["tyre"], spec["vertical"], spec["contact_patch"]

def linear_stiffness(kpa):
    """N/mm: the thesis's fit at 300 kPa; elsewhere a least-squares line through the origin."""
    if kpa == 300:
        return v["linear_stiffness_N_per_mm"], "linear fit at 300 kPa (thesis 4.2)"
    d = [float(r["deflection_mm"]) for r in rows]
    f = [float(r[f"load_N_{kpa}kPa"]) for r in rows]
    k = sum(a * b for a, b in zip(d, f)) / sum(a * a for a in d)
    return round(k, 1), "least-squares line through the origin of Table 3-2 (tyrelab)"


for kpa in (100, 300, 550):
    k_lin, k_note = linear_stiffness(kpa)
    lines = f"""$--------------------------------------------------------------------------
$ Michelin XZL 16.00R20, {kpa} kPa: built-in reference tyre of tyrelab.
$ Source: Tyre model verification over off-road terrain (the seed thesis),
$ Tables 3-1 (dimensions), 3-2 (load-deflection, mean of hysteresis loop),
$ 4-1 (carcass shape), section 3.4.1 (damping, drop test at 300 kPa, used at
$ every pressure), section 4.4 (3D enveloping contact parameters).
$ Wheel mass 240 kg (carcass + run-flat insert + rim, section 3.2); the spin
$ inertia is an assumption (see ARCHITECTURE.md).
$--------------------------------------------------------------------------
[MDI_HEADER]
FILE_TYPE     = 'tir'
FILE_VERSION  = 3.0
FILE_FORMAT   = 'ASCII'
$--------------------------------------------------------------------------units
[UNITS]
LENGTH = 'mm'
FORCE  = 'newton'
ANGLE  = 'radians'
MASS   = 'kg'
TIME   = 'second'
$--------------------------------------------------------------------------model
[MODEL]
PROPERTY_FILE_FORMAT = 'TYRELAB'
TYRESIDE             = 'RIGHT'
$--------------------------------------------------------------------------dimension
[DIMENSION]
UNLOADED_RADIUS = {t['overall_diameter_m'] * 1e3 / 2:.1f}   $ Table 3-1: overall diameter 1343 mm
WIDTH           = {t['overall_width_m'] * 1e3:.1f}   $ Table 3-1
RIM_RADIUS      = 254.0   $ 20 in rim
$--------------------------------------------------------------------------operating conditions
[OPERATING_CONDITIONS]
INFLPRES = {kpa / 1e3:.3f}   $ N/mm^2 ({kpa} kPa)
NOMPRES  = 0.300   $ recommended cross-country pressure
$--------------------------------------------------------------------------inertia
[INERTIA]
MASS       = {t['carcass_mass_kg']:.1f}   $ carcass
WHEEL_MASS = {t['wheel_mass_kg']:.1f}   $ carcass + run-flat insert + rim
WHEEL_IYY  = 5.0e7   $ kg mm^2 = 50 kg m^2, assumed (tyre as a ring at 0.55 m, rim at 0.25 m)
$--------------------------------------------------------------------------vertical
[VERTICAL]
VERTICAL_STIFFNESS = {k_lin}   $ N/mm, {k_note}
VERTICAL_DAMPING   = {v['damping_Ns_per_mm']}   $ N s/mm, drop test (thesis 3.4.1)
FNOMIN             = {t['static_load_rating_N']:.1f}   $ static load rating
DAMPING_RAMP       = 2.0   $ mm over which damping ramps in from zero
$--------------------------------------------------------------------------load-deflection, Table 3-2
[DEFLECTION_LOAD_CURVE]
{{pen fz}}
""" + "\n".join(f"{float(r['deflection_mm']):.1f} {float(r[f'load_N_{kpa}kPa']):.1f}" for r in rows) + """
$--------------------------------------------------------------------------carcass shape, Table 4-1
[SHAPE]
{radial width}
""" + "\n".join(f"{float(r['radial_ratio']):.4f} {float(r['width_ratio']):.4f}" for r in shape) + f"""
$--------------------------------------------------------------------------3D enveloping contact, thesis 4.4
[CONTACT_PATCH]
PA1      = {cp['PA1']}
PA2      = {cp['PA2']}
PB1      = {cp['PB1']}
PB2      = {cp['PB2']}
PB3      = {cp['PB3']}
PAE      = {cp['PAE']}
PBE      = {cp['PBE']}
PCE      = {cp['PCE']}
PLS      = {cp['PLS']}
N_WIDTH  = {cp['N_WIDTH']}
N_LENGTH = {cp['N_LENGTH']}
"""
    (dst / f"xzl-16.00R20_{kpa}kPa.tir").write_text(lines)

# the trailer load cases and the modal table travel with the tyre
(dst / "xzl-16.00R20_load_cases.csv").write_text((src / "load_cases.csv").read_text())
(dst / "xzl-16.00R20_modal.csv").write_text((src / "modal.csv").read_text())
print("written to", dst)
