"""``tyrelab fit ring`` end to end in the default suite: a round trip on a reduced campaign.

The campaign is the XZL's (its built-in property file as the manifest's ``base``, so the
vertical law, [SHAPE], masses and the 659.6 N/mm the start is scaled by are the thesis's)
with the ring's own data made by a known ring, the *truth*:

* plate presses at 300 and 550 kPa (fitted) and 100 kPa (held out), 20-80 mm every 20 mm;
* modes 2-6 at 300 and 550 kPa in Table 3-3's form, frequencies and damping ratios;
* the drop test's ``VERTICAL_DAMPING``: what the truth gives in the simulated trailer drop
  test (thesis 3.4.1).

No PA1/PA2 (the truth's contact length is not eq. 2.3's, which would be a target it misses).

The truth's structure is the start the campaign route derives for this tyre (the XZL's
identified start, :data:`tyrelab.fit.ring.START`, scaled by 659.6/659.6 N/mm: unchanged, with
the tangential foundation's constant part and the bending stiffness moved onto the
optimiser's inner bounds, 1e-3 of their scales, as the optimiser moves its start).
Its dampers are the shipped XZL ring's, and the fit starts from other ones (the parameter
file's defaults, no patch damping), so they must be *found*: the foundation dampers from the
modes' damping ratios, the patch damping from the drop test. The optimiser is given one
evaluation (``--max-evaluations 1``): the residuals and their Jacobian at the start (eleven
ring evaluations of two presses and two modal analyses, about 1 s each), no step; a step
would double that (the optimiser takes the Jacobian at the new point before it stops). The
optimiser's steps from a start away from the truth are
``test_round_trip_a_known_ring_is_reproduced`` in ``test_fit_ring_campaign.py`` (slow).

What the round trip asserts: the file the CLI writes holds the truth's structure and
recovered dampers; the fitted presses and modes 2-3 are reproduced and the held-out 100 kPa
press and modes 4-6 predicted to within 0.01 % (the data are the truth's; a unit, pressure or
mode mixed up on the way from the files to the residuals is percents); the drop test gives
its target within the 1 % the patch-damping search stops at (``fit_patch_damping``'s tol).
"""

from __future__ import annotations

import copy
import dataclasses
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from tyrelab.fit import ring
from tyrelab.fit.damping import ring_drop_test_damping
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.params import Tyre
from tyrelab.tyre.ring.modal import ring_modal
from tyrelab.tyre.ring.parameters import RingParameters, ring_parameters
from tyrelab.tyre.tir import read_tir, write_tir

#: fitted and held-out presses
PRESSURES = {300e3: "fit", 550e3: "fit", 100e3: "held_out"}
DEFLECTIONS = np.array([0.02, 0.04, 0.06, 0.08])
DAMPERS = ("cr", "ct", "cy", "cb", "cp", "tau_p")


def _truth() -> RingParameters:
    shipped = ring_parameters(load_tyre("xzl-16.00R20"))
    # the optimiser starts inside its bounds by 1e-3 of each scale: the XZL's kt0, 19.35 N/m^2,
    # at 100 N/m^2 (nothing beside ktp * p = 6.6e5 N/m^2), its EI, on its bound 10 N m^2, at 10.1
    lower, upper = (np.array(b, float) for b in ring.BOUNDS)
    structure = {k: float(np.clip(ring.START[k] / s, lo + 1e-3, hi - 1e-3)) * s
                 for (k, s), lo, hi in zip(ring.FREE.items(), lower, upper)}
    return dataclasses.replace(RingParameters(), **structure,
                               **{k: getattr(shipped, k) for k in DAMPERS})


def _at(tyre, pressure):
    """The tyre at another inflation pressure (its geometry and masses kept)."""
    tyre = copy.deepcopy(tyre)
    tyre.pressure = pressure
    tyre.tir.set("OPERATING_CONDITIONS", "INFLPRES", pressure)
    return tyre


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ring-campaign")
    truth = _truth()
    tir = copy.deepcopy(load_tyre("xzl-16.00R20").tir)
    for key in ("PA1", "PA2"):
        del tir.sections["CONTACT_PATCH"].entries[key]
    base = Tyre.from_tir(tir, name="base")
    target = ring_drop_test_damping(base, truth).damping
    tir.set("VERTICAL", "VERTICAL_DAMPING", float(target))
    write_tir(tir, folder / "base.tir", units=tir.units or None)
    manifest = '[tyre]\nbase = "base.tir"\n'
    data = {}
    for p, use in PRESSURES.items():
        load, _ = ring.press_plate(_at(base, p), truth, DEFLECTIONS)
        data[p] = load
        name = f"press_{p / 1e3:.0f}kPa.csv"
        (folder / name).write_text("deflection_mm,load_kN\n0,0\n" + "".join(
            f"{d * 1e3:g},{f / 1e3!r}\n" for d, f in zip(DEFLECTIONS, load.tolist())))
        manifest += (f'[[test]]\nkind = "load_deflection"\nfile = "{name}"\n'
                     f'pressure = "{p / 1e3:g} kPa"\nuse = "{use}"\n')
    modes = {p: ring_modal(_at(base, p), parameters=truth).set_index("mode")
             for p, use in PRESSURES.items() if use == "fit"}
    header = ",".join(f"freq_Hz_{p / 1e3:.0f}kPa,damping_pct_{p / 1e3:.0f}kPa" for p in modes)
    rows = [f"{m},mode {m}," + ",".join(f"{float(t.loc[m, 'freq_Hz'])!r},{float(t.loc[m, 'damping_pct'])!r}"
                                        for t in modes.values())
            for m in range(2, 7)]
    (folder / "modal.csv").write_text("mode,description," + header + "\n" + "\n".join(rows) + "\n")
    manifest += '[[test]]\nkind = "modal"\nfile = "modal.csv"\n'
    (folder / "campaign.toml").write_text(manifest)
    return folder, truth, target, data, modes


@pytest.fixture(scope="module")
def fitted(campaign):
    """``tyrelab fit ring`` on the campaign (one BLAS thread: the ring's modal analysis is an
    800 x 800 eigenproblem, and BLAS threads contending for two shared cores cost 5x)."""
    folder = campaign[0]
    out = folder / "fitted.tir"
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
    r = subprocess.run([sys.executable, "-m", "tyrelab.cli.main", "fit", "ring", str(folder), "-o", str(out),
                        "--no-report", "--max-evaluations", "1"],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr
    return read_tir(out), r.stdout


def test_the_written_ring_is_the_truth_with_its_dampers_found(campaign, fitted):
    """The structure as the truth's: the start the campaign route derives for this tyre (the
    documented scaling of the XZL's start), which one evaluation leaves. The foundation
    dampers of modes 2 (radial = tangential) and 3 (lateral) found from the parameter file's
    defaults to 0.1 %: four fixed-point steps on damping ratios (2-3 %) that are proportional
    to their dampers but for terms of the ratio's square. The patch damping found from none to
    2 %: the search stops within 1 % of the drop test's target, and the patch carries four
    fifths of that damping (0.58 of 2.69 N s/mm is the foundation's), so 1 % of it is 1.25 %
    of the patch damping. (Mode 4's torsion damper is not identifiable: docs/ring.md.)"""
    truth = campaign[1]
    rp = RingParameters.from_tir(fitted[0])
    start = RingParameters()
    for name in ring.FREE:
        assert getattr(rp, name) == pytest.approx(getattr(truth, name), rel=1e-6), name
    for name in ("cr", "ct", "cy"):
        assert abs(getattr(start, name) / getattr(truth, name) - 1) > 0.3      # a real search
        assert getattr(rp, name) == pytest.approx(getattr(truth, name), rel=1e-3), name
    assert start.cp == 0.0
    assert rp.cp == pytest.approx(truth.cp, rel=0.02)
    assert rp.tau_p == pytest.approx(truth.tau_p)


def test_fitted_and_held_out_errors_of_the_round_trip(campaign, fitted):
    """The CLI's report of its fit: presses and modes 2-3 reproduced, the 100 kPa press and
    modes 4-6 predicted within 0.01 % (see the module doc); the drop test within 1 %."""
    tir, text = fitted
    assert tir.number("TYRELAB_FIT", "RING_LOAD_RMS_PCT") < 0.01
    assert tir.number("TYRELAB_FIT", "RING_MODE_RMS_PCT") < 0.01
    row = {line.split("|")[1].strip(): line.split("|")[2:-1] for line in text.splitlines()
           if line.startswith("| ")}
    held_press = re.fullmatch(r"100 kPa press: ([-+.\de]+) %", row["plate load-deflection"][2].strip())
    held_modes = re.fullmatch(r"modes 4-6: ([-+.\de]+) %",
                              row["modes 2, 3 (fitted), 4-6 (held out)"][2].strip())
    assert held_press and float(held_press.group(1)) < 0.01, row["plate load-deflection"]
    assert held_modes and float(held_modes.group(1)) < 0.01
    drop = float(re.match(r"\s*([-+.\de]+) %", row["PATCH_DAMPING"][1]).group(1))
    assert drop < 1.0


def test_the_written_file_predicts_the_held_out_press(campaign, fitted):
    """The ring read back from the written file, pressed at 100 kPa on the tyre the file
    describes, gives the truth's press (which the fit never saw)."""
    data, target = campaign[3], campaign[2]
    tyre = Tyre.from_tir(fitted[0], name="fitted")
    load, _ = ring.press_plate(_at(tyre, 100e3), RingParameters.from_tir(fitted[0]), DEFLECTIONS)
    assert load == pytest.approx(data[100e3], rel=1e-4)
    assert fitted[0].number("VERTICAL", "VERTICAL_DAMPING") == pytest.approx(target)
