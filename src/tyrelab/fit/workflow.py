"""Thesis chapter 4 as a workflow: a campaign's tests in, a complete property file out.

Steps, in order (each reads what the earlier ones wrote into the file):

========  ======================================================  ==============================
step      tests fitted                                            writes
========  ======================================================  ==============================
vertical  load_deflection (:mod:`.vertical`: eq. 4.1, Table 3-2)  [VERTICAL] VERTICAL_STIFFNESS,
                                                                  [DEFLECTION_LOAD_CURVE]
damping   drop_test (:mod:`.damping`: the rig's drop test fitted  [VERTICAL] VERTICAL_DAMPING
          to the trace; eqs. 3.1-3.7 beside it)
patch     contact_patch, footprint_image (:mod:`.patch`:          [CONTACT_PATCH] PA1, PA2,
          eqs. 2.3, 2.4 and the half-width table)                 PB1-PB3; [CONTACT_WIDTH_CURVE]
shape     carcass_profile (:mod:`.shape`)                         [SHAPE]
ring      load_deflection at one or more pressures, modal, the    [FLEXIBLE_RING]
          file's VERTICAL_DAMPING, PA1/PA2, [SHAPE], MASS;
          dynamic_cleat runs (:mod:`.ring_step`, thesis 4.5)
========  ======================================================  ==============================

Tests marked ``use = "held_out"`` are predicted, never fitted; static cleat
tests are always held out (the analytic models' cleat loads follow from
the plate and the carcass: predicted with every analytic model, and with
the ring once the file has one). The fit's
record -- sources, RMS errors, the pendulum's damping -- goes into
``[TYRELAB_FIT]``, tyrelab's own section (SI, the unit in each key's name),
which ADAMS/Tire does not read. Presses at a pressure other than the
tyre's feed the ring only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..errors import InputError, naming
from ..tyre.tir import TirFile
from . import lab_files as lf
from .campaign import Campaign
from .property_file import FIT_SECTION, start_tir, tidy
from .step_result import ERROR_UNITS, StepResult, shown  # noqa: F401  (the report imports shown here)
from .step_result import fitted_tyre as _tyre
from .step_result import summary_row as _row
from .step_result import file_names as _names
from .step_result import tyre_dimension as _dimension

STEPS = ("vertical", "damping", "patch", "shape", "ring")


def predicted_models(tir: TirFile) -> tuple[str, ...]:
    """The models whose held-out cleat loads the fit predicts: every registered model the fit
    parameterizes (:attr:`~tyrelab.tyre.registry.ContactModel.fit_steps`), those that need the
    ring's own step only once the property file has the ring (thesis 4.5 fitted FTire to the
    cleats; tyrelab predicts them)."""
    from ..tyre.registry import contact_models
    return tuple(name for name, m in contact_models().items()
                 if m.fit_steps and ("ring" not in m.fit_steps or tir.has("FLEXIBLE_RING")))


@dataclass
class FitResult:
    """The fitted property file and each step's result."""

    campaign: Campaign
    tir: TirFile
    steps: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)


# --- the steps -----------------------------------------------------------------------------

def fit_vertical_step(campaign: Campaign, tir: TirFile) -> StepResult:
    """Linear stiffness and load-deflection table (:mod:`tyrelab.fit.vertical`) into ``tir``."""
    from .ring_step import at_tyre_pressure
    from .vertical import hysteresis, linear_stiffness, press_table, table_rms
    every = campaign.of(lf.LoadDeflection)
    tests = at_tyre_pressure(every, tir.number("OPERATING_CONDITIONS", "INFLPRES", None))
    fit = [t for t in tests if t.use == "fit"]
    if not fit:
        raise InputError("no load_deflection test at the tyre's pressure to fit", source=campaign.source,
                         field="vertical")
    d = np.concatenate([t.deflection for t in fit])
    f = np.concatenate([t.load for t in fit])
    lin = linear_stiffness(d, f)
    tables = [press_table(t) for t in fit]
    rows_d = tables[0].deflection
    inside = [np.where(rows_d <= tb.deflection[-1] + 1e-9, np.interp(rows_d, tb.deflection, tb.load),
                       np.nan) for tb in tables]
    rows_f = np.maximum.accumulate(np.nan_to_num(np.nanmean(inside, axis=0)))
    law_rms = table_rms(rows_d, rows_f, d, f)
    src = _names(fit)
    tir.set("VERTICAL", "VERTICAL_STIFFNESS", lin.stiffness)
    tir.set_table("DEFLECTION_LOAD_CURVE", np.column_stack([rows_d, rows_f]), ["pen", "fz"])
    tir.set(FIT_SECTION, "VERTICAL_SOURCE", src)
    tir.set(FIT_SECTION, "LINEAR_STIFFNESS_RMS_N", lin.rms)
    tir.set(FIT_SECTION, "TABLE_RMS_N", law_rms)
    res = StepResult("vertical", data={"tests": tests, "linear": lin, "tables": tables,
                                       "table": np.column_stack([rows_d, rows_f])})
    held_linear, held_table = {}, {}   # held-out test -> RMS error of the line, of the table
    for t in (t for t in tests if t.use == "held_out"):
        held_linear[t.name] = float(np.sqrt(np.mean((lin.stiffness * t.deflection - t.load) ** 2)))
        held_table[t.name] = table_rms(rows_d, rows_f, t.deflection, t.load)
    res.rows.append(_row("vertical", "VERTICAL_STIFFNESS", lin.stiffness, "N/m", lin.rms,
                         held_linear or None, src, "eq. 4.1, F = k rho (4.2)"))
    res.rows.append(_row("vertical", "DEFLECTION_LOAD_CURVE",
                         f"{rows_d.size} rows to {rows_d[-1] * 1e3:.0f} mm", "", law_rms,
                         held_table or None, src,
                         "mean of loading and unloading (Table 3-2), spline eq. 2.2"))
    if len(tests) < len(every):
        res.notes.append(f"vertical: {len(every) - len(tests)} press(es) at other pressures are for the "
                         "ring only")
    res.notes.extend(_touch_note("vertical", t, " (the ram's travel before the tyre met the plate)")
                     for t in tests if t.touch)
    loop = [tb for tb in tables if tb.branches]
    if loop:
        res.notes.append(f"vertical: {sum(tb.branches for tb in loop)} loading/unloading branches "
                         f"averaged; largest half hysteresis {max(hysteresis(tb) for tb in loop):.0f} N")
    if any(tb.raised for tb in tables):
        res.notes.append("vertical: some table rows fell below the row before and were raised to it")
    return res


def _touch_note(step: str, test, why: str = "") -> str:
    """The note that a press's file was counted from its first touch (``test.touch``)."""
    return (f"{step}: {test.name}: the load starts to rise at {1e3 * test.touch:.1f} mm of the file's "
            f"deflection{why}; deflection is counted from there")


def _trailer_pendulum(trace: lf.DropTrace, tyre):
    from ..rig.trailer import Trailer, TrailerGeometry
    from ..tyre.model import TyreModel
    geometry = TrailerGeometry(**trace.trailer)
    trailer = Trailer(TyreModel(tyre, "point"), trace.load_case, geometry)
    inertia = trace.inertia or float(trailer.setup.inertia[1, 1])
    lever = trace.lever or float(geometry.hitch_to_axle)
    return geometry, inertia, lever


def _fit_trace(trace: lf.DropTrace, tyre, geometry, **options):
    """:func:`~tyrelab.fit.damping.fit_drop_trace` of a campaign's trace; a trace it refuses is
    named by its file."""
    from .damping import fit_drop_trace
    with naming(trace.source):
        return fit_drop_trace(trace.time, trace.displacement, tyre, trace.load_case, geometry, **options)


def fit_damping_step(campaign: Campaign, tir: TirFile) -> StepResult:
    """Tyre damping from drop tests by the rig fit (written) and the pendulum (compared)."""
    from .damping import drop_test_damping, lowpass
    tests = campaign.of(lf.DropTrace)
    fit = [t for t in tests if t.use == "fit"]
    if not fit:
        raise InputError("no drop_test to fit", source=campaign.source, field="damping")
    tyre = _tyre(tir, "damping")
    res = StepResult("damping", data={"fits": [], "pendulum": [], "tests": tests})
    rig, pend = [], []
    for t in fit:
        geometry, inertia, lever = _trailer_pendulum(t, tyre)
        r = _fit_trace(t, tyre, geometry)
        after = t.time >= r.release  # the pendulum's cycles start after the release (3.4.1)
        p = drop_test_damping(t.time[after], lowpass(t.time, t.displacement, t.lowpass)[after], inertia,
                              lever, t.wheels)
        rig.append(r.damping)
        pend.append(float(p.damping))
        res.data["fits"].append(r)
        res.data["pendulum"].append(p)
    c = float(np.mean(rig))
    c_pend = float(np.mean(pend))
    tir.set("VERTICAL", "VERTICAL_DAMPING", c)
    tir.set(FIT_SECTION, "DAMPING_SOURCE", _names(fit))
    tir.set(FIT_SECTION, "DAMPING_RIG_FIT_NS_PER_M", c)
    tir.set(FIT_SECTION, "DAMPING_PENDULUM_NS_PER_M", c_pend)
    scale = float(np.mean([r.stiffness_scale for r in res.data["fits"]]))
    tir.set(FIT_SECTION, "DROP_STIFFNESS_SCALE", scale)
    rms = float(np.sqrt(np.mean([r.rms ** 2 for r in res.data["fits"]])))
    tir.set(FIT_SECTION, "DROP_RMS_M", rms)
    held = {}
    refitted = _tyre(tir, "damping")
    for t in (t for t in tests if t.use == "held_out"):
        geometry, _, _ = _trailer_pendulum(t, refitted)
        # the trace's zero and its release are its own, fitted as in the fit; the tyre is not
        held[t.name] = _fit_trace(t, refitted, geometry, fit_stiffness=False, fit_damping=False).rms
    res.rows.append(_row("damping", "VERTICAL_DAMPING", c, "N s/m", rms, held or None, _names(fit),
                         "trailer drop test simulated and fitted to the trace (3.4.1)"))
    res.rows.append(_row("damping", "pendulum damping (not written)", c_pend, "N s/m", None, None,
                         _names(fit), "eqs. 3.1-3.7, log decrement"))
    res.notes.append(f"damping: the pendulum route gives {c_pend:.0f} N s/m, {100 * (c_pend / c - 1):+.1f} % "
                     f"from the rig fit's {c:.0f} N s/m (the pendulum assumption's error on this trailer); "
                     f"the trace fits best with the load-deflection law times {scale:.3f}")
    return res


class _PatchFile(NamedTuple):
    """The patch measurements of one file: deflection, full length and width [m] per point."""

    deflection: np.ndarray
    length: np.ndarray
    width: np.ndarray
    source: str


def _patch_points(campaign: Campaign, tir: TirFile, use: str) -> list[_PatchFile]:
    """A :class:`_PatchFile` for every patch measurement file of ``use``."""
    tyre = None
    out = []
    for t in campaign.of(lf.PatchPoints, lf.FootprintImage):
        if t.use != use:
            continue
        if isinstance(t, lf.FootprintImage):
            d, ll, w = np.array([t.deflection or np.nan]), np.array([t.footprint.length]), \
                np.array([t.footprint.width])
            loads = np.array([t.load or np.nan])
        else:
            n = len(t.lines)
            d = t.deflection if t.deflection is not None else np.full(n, np.nan)
            loads = t.load if t.load is not None else np.full(n, np.nan)
            ll = t.length if t.length is not None else np.full(n, np.nan)
            w = t.width if t.width is not None else np.full(n, np.nan)
        d = np.array(d, float)
        need = ~np.isfinite(d)
        if need.any():
            tyre = tyre or _tyre(tir, "contact patch (a load given without its deflection)")
            d[need] = [tyre.static_deflection(float(x)) for x in loads[need]]
        out.append(_PatchFile(d, ll, w, t.name))
    return out


def fit_patch_step(campaign: Campaign, tir: TirFile) -> StepResult:
    """PA1, PA2 (eq. 2.3), PB1-PB3 (eq. 2.4) and the half-width table into ``tir``."""
    from ..tyre.contact.patch_laws import DEFAULTS
    from .patch import (contact_half_length, contact_half_width, contact_width_table, fit_contact_length,
                        fit_contact_width, width_from_table)
    r0 = _dimension(tir, "UNLOADED_RADIUS", "contact patch")
    w0 = _dimension(tir, "WIDTH", "contact patch")
    pts = _patch_points(campaign, tir, "fit")
    if not pts:
        raise InputError("no contact_patch or footprint_image test to fit", source=campaign.source,
                         field="patch")
    d = np.concatenate([p.deflection for p in pts])
    a = 0.5 * np.concatenate([p.length for p in pts])
    b = 0.5 * np.concatenate([p.width for p in pts])
    src = ", ".join(dict.fromkeys(p.source for p in pts))
    res = StepResult("patch", data={"deflection": d, "half_length": a, "half_width": b, "R0": r0, "W0": w0})
    for t in campaign.of(lf.FootprintImage):
        turn = float(np.degrees(t.footprint.angle))
        if abs(turn) >= 0.5:
            res.notes.append(f"patch: {t.name}: the print is turned {turn:+.1f} deg from the image's "
                             f"{t.travel} axis; its length and width are measured along its own axes")
    held = _patch_points(campaign, tir, "held_out")
    if held:
        hd = np.concatenate([p.deflection for p in held])
        ha = 0.5 * np.concatenate([p.length for p in held])
        hb = 0.5 * np.concatenate([p.width for p in held])
    else:
        hd = ha = hb = np.zeros(0)
    res.data.update(held_deflection=hd, held_half_length=ha, held_half_width=hb)

    def errors(predict, size):
        """RMS error of ``predict(deflection)`` on each held-out file's half ``size``
        (``"length"`` or ``"width"``)."""
        out = {}
        for p in held:
            meas = 0.5 * getattr(p, size)
            ok = np.isfinite(meas)
            if ok.any():
                out[p.source] = float(np.sqrt(np.mean((predict(p.deflection[ok]) - meas[ok]) ** 2)))
        return out or None

    ok = np.isfinite(a)
    if ok.any():
        with naming(src):
            fl = fit_contact_length(d[ok], a[ok], r0)
        tir.set("CONTACT_PATCH", "PA1", fl.pa1)
        tir.set("CONTACT_PATCH", "PA2", fl.pa2)
        tir.set(FIT_SECTION, "CONTACT_LENGTH_RMS_M", fl.rms)
        res.data["length_fit"] = fl
        res.rows.append(_row("patch", "PA1, PA2", f"{fl.pa1:.4g}, {fl.pa2:.4g}", "-", fl.rms,
                             errors(lambda x: contact_half_length(x, fl.pa1, fl.pa2, r0), "length"), src,
                             "eq. 2.3 on the half length a"))
    ok = np.isfinite(b)
    if ok.any():
        wt = contact_width_table(d[ok], b[ok])
        tir.set_table("CONTACT_WIDTH_CURVE", wt.table, ["pen", "half_width"])
        tir.set(FIT_SECTION, "WIDTH_TABLE_RMS_M", wt.rms)
        tir.set(FIT_SECTION, "WIDTH_LINE_INTERCEPT_M", wt.intercept)
        tir.set(FIT_SECTION, "WIDTH_LINE_SLOPE", wt.slope)
        res.data["width_table"] = wt
        res.rows.append(_row("patch", "CONTACT_WIDTH_CURVE", f"{wt.table.shape[0]} rows", "", wt.rms,
                             errors(lambda x: np.minimum(width_from_table(wt.table, x), 0.5 * w0), "width"),
                             src,
                             "half width vs deflection (4.4's recommendation)"))
        if np.unique(np.round(d[ok], 6)).size >= 2:
            with naming(src):
                wf = fit_contact_width(d[ok], b[ok], r0, w0)
            for k, v in zip(("PB1", "PB2", "PB3"), wf[:3]):
                tir.set("CONTACT_PATCH", k, v)
            tir.set(FIT_SECTION, "CONTACT_WIDTH_RMS_M", wf.rms)
            res.data["width_fit"] = wf
            res.rows.append(_row("patch", "PB1, PB2, PB3", f"{wf.pb1:.4g}, {wf.pb2:.4g}, {wf.pb3:.4g}", "-",
                                 wf.rms, errors(lambda x: contact_half_width(x, *wf[:3], r0, w0), "width"),
                                 src,
                                 "eq. 2.4 on the half width b (clipped to W0/2 as the model)"))
        else:
            res.notes.append("patch: widths at one deflection only: PB1-PB3 not fitted")
    for key, value in DEFAULTS.items():
        if key not in ("PA1", "PA2") and not tir.has("CONTACT_PATCH", key):
            tir.set("CONTACT_PATCH", key, value)
    tir.set(FIT_SECTION, "PATCH_SOURCE", src)
    res.notes.append("patch: cam shape and count (PAE, PBE, PCE, PLS, N_WIDTH, N_LENGTH) are not fitted "
                     "(kept from the base file, else thesis 4.4's values)")
    return res


def fit_shape_step(campaign: Campaign, tir: TirFile) -> StepResult:
    """The ``[SHAPE]`` table of the carcass profile(s) into ``tir``."""
    from .shape import fit_carcass_shape, fold_profile, profile_centre, shape_rms
    tests = [t for t in campaign.of(lf.CarcassProfile) if t.use == "fit"]
    if not tests:
        raise InputError("no carcass_profile test to fit", source=campaign.source, field="shape")
    r0 = tir.number("DIMENSION", "UNLOADED_RADIUS", None)
    w0 = tir.number("DIMENSION", "WIDTH", None)
    y, r, moved = [], [], []
    for t in tests:
        if t.radius is None and not r0:
            raise InputError("a profile given as drop below the crown needs the unloaded radius",
                             source=t.source, field="drop")
        radius = t.radius if t.radius is not None else r0 - t.drop
        centre = profile_centre(t.y, radius)
        if centre:
            moved.append(f"shape: {t.name}: y runs {1e3 * t.y.min():.1f} to {1e3 * t.y.max():.1f} mm with "
                         f"the crown between: measured from a side, centred on its shoulders' midpoint, "
                         f"y = {1e3 * centre:.1f} mm")
        y.append(t.y - centre)
        r.append(radius)
    y, r = np.concatenate(y), np.concatenate(r)
    before = tir.table("SHAPE")
    shape = fit_carcass_shape(y, r, r0, 0.5 * w0 if w0 else None)
    tir.set_table("SHAPE", shape.table, ["radial", "width"])
    tir.set(FIT_SECTION, "SHAPE_SOURCE", _names(tests))
    tir.set(FIT_SECTION, "SHAPE_RMS", shape.rms)
    res = StepResult("shape", data={"fit": shape, "before": before})
    res.notes.extend(moved)
    res.rows.append(_row("shape", "SHAPE", f"{shape.table.shape[0]} points", "-", shape.rms, None,
                         _names(tests), "least-squares polyline, equal steps (4.3)"))
    if before is not None:
        prof = fold_profile(y, r, r0, 0.5 * w0 if w0 else None)
        old = shape_rms(before, prof.width_ratio, prof.radius_ratio)
        res.notes.append(f"shape: the base file's [SHAPE] as the models resample it is {old:.4f} RMS "
                         f"from the profile, the fitted table {shape.rms:.4f}")
    if np.isfinite(shape.profile.asymmetry):
        res.notes.append(f"shape: the two halves differ by {shape.profile.asymmetry:.4f} RMS (radius ratio)")
    return res


def predict_cleats(campaign: Campaign, tir: TirFile) -> StepResult:
    """Held-out static cleat tests predicted by every analytic model of the fitted tyre (and the ring)."""
    from ..rig.static_press import static_press
    from ..tyre.model import TyreModel
    res = StepResult("cleats", data={"predictions": []})
    tests = campaign.of(lf.StaticCleat)
    if not tests:
        return res
    tyre = _tyre(tir, "cleat prediction")
    models = predicted_models(tir)
    for t in tests:
        width, height = t.cleat
        spec = f"cleat:{width * 1e3:g}x{height * 1e3:g}"
        if t.touch:
            res.notes.append(_touch_note("cleats", t))
        pred = {}
        for m in models:
            loads = static_press(TyreModel(tyre, m), t.deflection, spec, t.direction)["load"].to_numpy()
            pred[m] = loads
            rms = float(np.sqrt(np.mean((loads - t.load) ** 2)))
            res.rows.append(_row("cleats", f"{m}: {spec} {t.direction}", "-", "", None, {t.name: rms},
                                 t.name, "static press (3.3.4), predicted"))
        res.data["predictions"].append((t, pred))
    return res


FITS = {"vertical": fit_vertical_step, "damping": fit_damping_step, "patch": fit_patch_step,
        "shape": fit_shape_step}
#: tests a step needs (a step of ``fit all`` without them is skipped)
NEEDS = {"vertical": (lf.LoadDeflection,), "damping": (lf.DropTrace,),
         "patch": (lf.PatchPoints, lf.FootprintImage), "shape": (lf.CarcassProfile,),
         "ring": (lf.ModalResults,)}


def fit_campaign(campaign: Campaign, steps=STEPS, base=None, progress=None, skip_missing=None,
                 ring_evaluations=None, ring_progress=None, skipped=()) -> FitResult:
    """Run ``steps`` of the workflow on ``campaign``; returns the property file and the results.

    ``base`` is the property file to update (a TirFile or a path; default: the
    manifest's base, else a new file); ``progress(name)`` is called after each step.
    A step asked for whose tests are missing is an error, unless
    ``skip_missing`` (default: when every step is asked for, ``fit all``):
    then it is skipped with a note. ``ring_evaluations`` is the ring's
    optimiser budget, ``ring_progress(cost)`` is called after each of its
    model evaluations; ``skipped`` names steps left out on purpose (noted).
    """
    from .ring_step import MAX_EVALUATIONS, fit_ring_step
    tir = start_tir(campaign, base)
    result = FitResult(campaign, tir, notes=[f"{name}: skipped on request (the base file's values "
                                             f"stay)" for name in skipped])
    if skip_missing is None:
        skip_missing = tuple(steps) == STEPS
    for name in steps:
        if skip_missing and not [t for t in campaign.of(*NEEDS[name]) if t.use == "fit"]:
            result.notes.append(f"{name}: no test in the campaign, skipped (the base file's values stay)")
        else:
            if name == "ring":
                step = fit_ring_step(campaign, tir, ring_evaluations or MAX_EVALUATIONS, ring_progress)
            else:
                step = FITS[name](campaign, tir)
            result.steps[name] = step
            result.notes += step.notes
        if progress:
            progress(name)
    if campaign.of(lf.StaticCleat):
        result.steps["cleats"] = predict_cleats(campaign, tir)
    if progress:
        progress("predictions")
    tidy(tir, new=base is None and campaign.base is None)
    if tir.has("DIMENSION", "UNLOADED_RADIUS"):
        from ..tyre.tir_physics import check_physics
        try:
            check_physics(tir)  # what is written must read back
        except InputError as exc:  # the fitted values' fault, not the output file's: name the tests
            field = f"{exc.field}: " if exc.field else ""
            raise InputError(f"the fit gives {field}{exc.reason}", source=str(campaign.source)) from None
    return result
