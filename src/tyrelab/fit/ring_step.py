"""The ring step of ``tyrelab fit``: a user's test campaign in, ``[FLEXIBLE_RING]`` out (thesis 4.5).

The thesis identified FTire from plate presses at two pressures, modal
tests, footprints and static cleats, and found its damping "by brute force"
from dynamic cleat runs. The same route here, for any tyre whose campaign
has:

* ``load_deflection`` tests (each at its ``pressure``, the tyre's by
  default): the fitted ones, one curve per pressure, are the presses the
  ring is fitted to (:func:`tyrelab.fit.ring.fit_ring`); held-out ones are
  predicted. With presses at one pressure only, each foundation's pressure
  rate cannot be told from its constant part: one factor scales both, their
  split kept from the start (stated in the notes);
* a ``modal`` test (thesis Table 3-3's form and mode numbers): modes 2 and 3
  fitted, 4-6 predicted; the damping ratios of modes 2-4 at the tyre's
  pressure set the foundation dampers;
* what the earlier steps wrote into the property file: the drop test's
  ``VERTICAL_DAMPING`` (the contact patch's damping is set to reproduce it),
  ``PA1``/``PA2`` (the eq. 2.3 contact length is fitted at 20, 40, 60 mm;
  skipped without them), ``[SHAPE]`` (the tread's contour) and the carcass
  ``MASS`` (bounds of the belt mass, 39-100 % of it as for the XZL's
  60-154 kg);
* optionally ``dynamic_cleat`` runs: those marked ``use = "fit"`` fit the
  patch damping's factor (:func:`tyrelab.fit.ring_dynamic.fit_ring_damping`);
  every other run is predicted before and after and reported.

The start is the XZL's identified ring scaled to the tyre: stiffnesses by the
ratio of vertical stiffnesses (659.6 N/mm for the XZL, thesis 4.2), the
pressure rates also by 300 kPa over the tyre's pressure, the effective
pressurized width by the widths, the belt mass 153/154 of the carcass mass.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np
import pandas as pd

from ..errors import InputError
from . import lab_files as lf
from .ring import BOUNDS, FREE, START, RingData, fit_ring
from .property_file import FIT_SECTION
from .ring_dynamic import CleatRun, fit_ring_damping, run_table
from .step_result import StepResult
from .step_result import fitted_tyre as _tyre
from .step_result import summary_row as _row
from .step_result import file_names as _names

#: the XZL's vertical stiffness at 300 kPa [N/m] (thesis 4.2), its width [m],
#: carcass mass [kg] and the pressure [Pa] the start values belong to
XZL_STIFFNESS = 659.6e3
XZL_WIDTH = 0.438
XZL_CARCASS_MASS = 154.0
XZL_PRESSURE = 300e3
#: optimiser budget of the campaign's ring (as ``tyrelab fit ring``)
MAX_EVALUATIONS = 25


def _pressure(t: lf.LoadDeflection, reference: float) -> float:
    return reference if t.pressure is None else float(t.pressure)


def at_tyre_pressure(tests, reference: float | None) -> list:
    """The load-deflection tests at the tyre's pressure (all if it is unknown)."""
    if reference is None:
        return list(tests)
    return [t for t in tests if np.isclose(_pressure(t, reference), reference, rtol=1e-6)]


def _press(tests) -> np.ndarray:
    """One press curve ``(n, 2)`` from tests at one pressure: each test's table
    (mean of loading and unloading, :func:`~tyrelab.fit.vertical.load_deflection_table`),
    rows above zero deflection, in order of deflection."""
    from .vertical import press_table
    rows = []
    for t in tests:
        tb = press_table(t)
        rows.append(np.column_stack([tb.deflection, tb.load]))
    press = np.concatenate(rows)
    press = press[press[:, 0] > 0]
    return press[np.argsort(press[:, 0], kind="stable")]


def campaign_ring_data(campaign, tir) -> RingData:
    """:class:`~tyrelab.fit.ring.RingData` of a campaign and the property file written so far."""
    from .vertical import linear_stiffness
    reference = tir.number("OPERATING_CONDITIONS", "INFLPRES", None)
    if not reference or not reference > 0:
        raise InputError("the ring fit needs the tyre's inflation pressure: give 'pressure' in the "
                         "manifest's [tyre] table", source=campaign.source, field="pressure")
    mass = tir.number("INERTIA", "MASS", None)
    if not mass or not mass > 0:
        raise InputError("the ring fit needs the carcass mass (it bounds the belt's mass): give "
                         "'mass' in the manifest's [tyre] table", source=campaign.source, field="mass")
    base = _tyre(tir, "ring")
    if not base.vertical_damping > 0:
        raise InputError("the ring fit needs the drop test's VERTICAL_DAMPING (it sets the contact "
                         "patch's damping): fit the damping step first (a drop_test)",
                         source=campaign.source, field="VERTICAL_DAMPING")
    groups: dict[str, dict[float, list]] = {"fit": {}, "held_out": {}}
    for t in campaign.of(lf.LoadDeflection):
        groups[t.use].setdefault(_pressure(t, reference), []).append(t)
    if not any(np.isclose(p, reference) for p in groups["fit"]):
        raise InputError(f"the ring fit needs a fitted load_deflection test at the tyre's pressure, "
                         f"{reference / 1e3:g} kPa", source=campaign.source, field="load_deflection")
    modal = [t for t in campaign.of(lf.ModalResults) if t.use == "fit"]
    if not modal:
        raise InputError("the ring fit needs modal results (a 'modal' test in thesis Table 3-3's "
                         "form): they fix the belt's mass", source=campaign.source, field="modal")
    modes = pd.concat([t.table for t in modal], ignore_index=True)
    fitted = {p: _press(ts) for p, ts in groups["fit"].items()}
    held = {p: _press(ts) for p, ts in groups["held_out"].items()}
    for group in (fitted, held):
        for p in list(group):
            if np.isclose(p, reference):  # the tyre's own pressure, exactly
                group[reference] = group.pop(p)
    tyres = {}
    for p in {*fitted, *held}:
        tyre = copy.deepcopy(base)
        tyre.pressure = p
        tyre.tir.set("OPERATING_CONDITIONS", "INFLPRES", p)
        if not np.isclose(p, reference):
            press = fitted.get(p, held.get(p))
            tyre.vertical_stiffness = linear_stiffness(press[:, 0], press[:, 1]).stiffness
        tyres[p] = tyre
    lower, upper = list(BOUNDS[0]), list(BOUNDS[1])
    i = list(FREE).index("ring_mass")
    lower[i] = BOUNDS[0][i] * mass / XZL_CARCASS_MASS
    upper[i] = BOUNDS[1][i] * mass / XZL_CARCASS_MASS
    return RingData(tyres, fitted, held, modes, reference, (lower, upper))


def ring_start(data: RingData):
    """The XZL's identified ring scaled to the campaign's tyre (module doc)."""
    from ..tyre.ring.parameters import RingParameters
    tyre = data.tyres[data.reference]
    s = tyre.vertical_stiffness / XZL_STIFFNESS
    per_pa = s * XZL_PRESSURE / data.reference
    i = list(FREE).index("ring_mass")
    mass = data.bounds[1][i] * FREE["ring_mass"]
    values = dict(START)
    for k in ("kr0", "kt0", "ky0", "ei", "tread_stiffness"):
        values[k] = START[k] * s
    for k in ("krp", "ktp", "kyp"):
        values[k] = START[k] * per_pa
    if tyre.width > 0:
        values["pressure_width"] = START["pressure_width"] * tyre.width / XZL_WIDTH
    values["ring_mass"] = START["ring_mass"] / XZL_CARCASS_MASS * mass
    return dataclasses.replace(RingParameters(), **values)


def _road(t: lf.DynamicCleat) -> str:
    w, h = (1e3 * v for v in t.cleat)
    angle = np.degrees(t.angle)
    return f"cleat:{w:g}x{h:g}" + (f"@{angle:g}" if angle else "")


def cleat_run(t: lf.DynamicCleat) -> CleatRun:
    """A campaign's dynamic cleat test as a :class:`~tyrelab.fit.ring_dynamic.CleatRun`."""
    for key, value in (("cleat", t.cleat), ("speed", t.speed)):
        if value is None:
            raise InputError(f"a dynamic_cleat run the ring is fitted to or judged by needs its "
                             f"'{key}' in the manifest", source=t.source, field=key)
    signal = t.signal
    if "FZW" not in signal:
        name = "FZ" if "FZ" in signal else "FZ_HUB"
        signal = signal.rename(columns={name: "FZW"})
    return CleatRun(_road(t), float(t.speed), t.load_case, signal[["RUNTIME", "FZW"]])


def fit_ring_step(campaign, tir, max_evaluations=MAX_EVALUATIONS, progress=None):
    """Identify the ring of ``campaign`` into ``tir`` (module doc); returns a
    :class:`~tyrelab.fit.workflow.StepResult`. ``progress(cost)`` after every model
    evaluation."""
    data = campaign_ring_data(campaign, tir)
    start = ring_start(data)
    rp, fitted, held = fit_ring(data, start=start, max_nfev=max_evaluations, progress=progress)
    res = StepResult("ring", data={"fitted": fitted, "held": held, "data": data})
    loads = campaign.of(lf.LoadDeflection)
    modal = [t for t in campaign.of(lf.ModalResults) if t.use == "fit"]
    src = _names([t for t in loads if t.use == "fit"] + modal)

    def rms(df, quantity, pressure=None):
        sel = df["quantity"] == quantity
        if pressure is not None:
            sel &= np.isclose(df["pressure_kPa"], pressure / 1e3)
        e = df.loc[sel, "error_pct"].to_numpy()
        return float(np.sqrt(np.mean(e ** 2))) if e.size else None

    held_loads = {f"{p / 1e3:g} kPa press": rms(held, "load", p) for p in sorted(data.held_loads)}
    pressures = ", ".join(f"{p / 1e3:g}" for p in data.pressures) + " kPa"
    res.rows.append(_row("ring", "plate load-deflection", pressures, "-", rms(fitted, "load"),
                         held_loads or None, src, "static press on a plate (3.3.1), % of the load"))
    res.rows.append(_row("ring", "modes 2, 3 (fitted), 4-6 (held out)", "frequency", "-",
                         rms(fitted, "mode"), {"modes 4-6": rms(held, "mode")}, _names(modal),
                         "ring modal analysis vs Table 3-3, % of the frequency"))
    if rms(fitted, "contact") is not None:
        res.rows.append(_row("ring", "contact half length", "eq. 2.3", "-", rms(fitted, "contact"), None,
                             "PA1, PA2", "ring pressed on a plate vs eq. 2.3, %"))
    else:
        res.notes.append("ring: no PA1/PA2 in the file, the contact length was not fitted (fit the "
                         "patch step first)")
    drop = fitted[fitted["quantity"] == "drop"].iloc[0]
    res.rows.append(_row("ring", "PATCH_DAMPING", rp.cp, "N s/m", abs(drop["error_pct"]), None,
                         "VERTICAL_DAMPING", "simulated drop test (3.4.1) gives the fitted damping, %"))
    if len(data.pressures) < 2:
        res.notes.append(f"ring: presses at {data.pressures[0] / 1e3:g} kPa only: each foundation's "
                         "pressure rate is scaled with its constant part (their split is the XZL's); "
                         "a press at a second pressure identifies it")
    runs = campaign.of(lf.DynamicCleat)
    if runs:
        fit_runs = [cleat_run(t) for t in runs if t.use == "fit"]
        other = [cleat_run(t) for t in runs if t.use != "fit"]
        tyre = data.tyres[data.reference]
        if fit_runs:
            dyn = fit_ring_damping(tyre, fit_runs, other, parameters=rp, progress=progress)
            rp = dyn.parameters
            tir.set(FIT_SECTION, "RING_PATCH_DAMPING_FACTOR", dyn.patch)
            res.notes.append(f"ring: the dynamic cleat runs scale the drop test's patch damping by "
                             f"{dyn.patch:.3f}")
            table = dyn.table
        else:
            table = run_table(tyre, rp, rp, held_out=other)
        res.data["cleat_runs"] = table
        for t, r in zip([t for t in runs if t.use == "fit"] + [t for t in runs if t.use != "fit"],
                        table.itertuples()):
            res.rows.append(_row("ring", f"FZW over {r.road} at {r.speed_kmh:.0f} km/h", r.set, "",
                                 r.rms_after_pct if r.set == "fit" else None,
                                 None if r.set == "fit" else {t.name: r.rms_after_pct}, t.name,
                                 "trailer run (3.4.2), RMS % of the measured peak"))
    rp.to_tir(tir)
    tir.set(FIT_SECTION, "RING_SOURCE", src)
    tir.set(FIT_SECTION, "RING_LOAD_RMS_PCT", rms(fitted, "load"))
    tir.set(FIT_SECTION, "RING_MODE_RMS_PCT", rms(fitted, "mode"))
    res.data["parameters"] = rp
    return res

