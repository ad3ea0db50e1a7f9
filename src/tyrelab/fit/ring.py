"""Identification of the flexible ring from lab data (thesis 4.5).

The thesis identified FTire with FTire/fit from footprints, static load-
deflection at two pressures, static cleat tests and modal data. Here the
same idea, with the data the thesis publishes:

* fitted: flat-plate load-deflection (Table 3-2) at 300 and 550 kPa, the
  natural frequencies of modes 2 (vertical/longitudinal translation) and 3
  (lateral translation) of Table 3-3 at 300 and 550 kPa, and the half
  contact length from the PA1/PA2 relation (eq. 2.3),
  ``a = PA1 R0 (rho/R0 + PA2 sqrt(rho/R0))``, at 20, 40, 60 mm;
* held out (never in the fit): the whole 100 kPa load-deflection curve and
  modes 4, 5, 6 at both pressures;
* damping: the foundation dampers are set so the model's damping ratios of
  modes 2, 3 and 4 at 300 kPa equal Table 3-3 (:func:`modal_damping`),
  and the contact patch's Maxwell element so the simulated trailer drop
  test gives the thesis's 2.66 N s/mm by the thesis's own procedure
  (:func:`fit_patch_damping`, eqs. 3.1-3.7 in :mod:`tyrelab.fit.damping`); the
  550 kPa damping ratios and those of modes 5 and 6 are predictions.

Free parameters: radial, tangential and lateral foundation stiffness and
their pressure rates, in-plane bending stiffness, effective pressurized
width, tread rubber stiffness, belt mass (bounded by 60 kg and the carcass
mass 154 kg, thesis 3.2). Fixed by prior knowledge (values in the parameter
file): tread depth (25 mm), tread progression and shear stiffness (rubber
of Shore A 60, thesis 4.5), belt extension (nearly inextensible steel
belt), out-of-plane bending, torsion and torsional foundation (no
out-of-plane data is fitted), friction 0.8.
"""

from __future__ import annotations

import dataclasses
import math
from typing import NamedTuple

import numpy as np
import pandas as pd

from ..tyre.library import load_tyre, modal_table
from ..tyre.ring.modal import ring_modal
from ..tyre.ring.parameters import RingParameters
from ..tyre.tir import TirFile, write_tir
from .damping import ring_drop_test_damping
from .ring_press import contact_half_length, contact_half_length_eq23, press_plate

FIT_PRESSURES = (300e3, 550e3)
HELD_OUT_PRESSURE = 100e3
FIT_MODES = (2, 3)
HELD_OUT_MODES = (4, 5, 6)
DAMPING_MODES = (2, 3, 4)
CONTACT_DEFLECTIONS = (0.02, 0.04, 0.06)
#: free parameters and their scales
FREE = {"kr0": 1e5, "krp": 1.0, "kt0": 1e5, "ktp": 1.0, "ky0": 1e5, "kyp": 1.0, "ei": 100.0,
        "pressure_width": 0.1, "tread_stiffness": 1e8, "ring_mass": 100.0}
#: bounds of the free parameters (in their scales): the belt is at most the
#: carcass mass (154 kg, thesis 3.2) and at least 60 kg; the pressure-
#: independent radial foundation is at least 1e5 N/m^2 (half of its start
#: value, see START): a straight line through the measured plate stiffnesses
#: at 300 and 550 kPa (fitted data) leaves about a fifth of the 300 kPa
#: stiffness at zero pressure (sidewall structure), which only the radial
#: foundation, in parallel with the membrane, can carry (the tread is in
#: series and the pre-tension is proportional to the pressure)
BOUNDS = ([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.02, 0.2, 0.6],
          [np.inf] * 9 + [1.54])
#: eq. 2.3 is one pressure-independent curve (a model in the thesis's files,
#: not a measurement at each pressure): with a pressure-independent radial
#: foundation the ring's contact length must change somewhat with pressure,
#: so the contact residuals weigh half of the measured loads
WEIGHTS = {"load": 1.0, "mode": 2.0, "contact": 0.5}
#: share of the 300 kPa radial foundation that is pressure-independent
#: (straight-line intercept of the measured 300/550 kPa stiffnesses, 20-80 mm)
KR0_SHARE = 0.2
#: starting point of the identification of the built-in XZL (the shipped
#: parameter file was fitted from here): the previous identification (which
#: had FOUNDATION_RADIAL = 0), its radial foundation at 300 kPa,
#: 1.03e6 N/m^2, split KR0_SHARE : 1 - KR0_SHARE into kr0 and krp 300 kPa
START = dict(pressure_width=0.2681187, kr0=KR0_SHARE * 1.03e6,
             krp=(1 - KR0_SHARE) * 1.03e6 / 300e3, kt0=19.35, ktp=2.2056,
             ky0=213316.4, kyp=0.71047, ei=10.0, tread_stiffness=35216987.0, ring_mass=153.0)
#: floor of the load residual's reference, as a share of the largest load
LOAD_FLOOR = 0.2


#: with one pressure the pressure rates cannot be told from the constant parts:
#: each foundation is one free factor on its total, split as in the start
PAIRS = {"kr0": "krp", "kt0": "ktp", "ky0": "kyp"}


def free_parameters(n_pressures: int) -> dict:
    """The free parameters and their scales for presses at ``n_pressures`` pressures."""
    return dict(FREE) if n_pressures >= 2 else {k: s for k, s in FREE.items() if k not in PAIRS.values()}


def _with(rp, x, free=None):
    free = FREE if free is None else free
    values = {k: float(v) * s for (k, s), v in zip(free.items(), x)}
    for k0, kp in PAIRS.items():
        if k0 in values and kp not in free:
            # one pressure: the factor on the constant part scales the rate too
            values[kp] = getattr(rp, kp) * (values[k0] / getattr(rp, k0))
    return dataclasses.replace(rp, **values)


class RingData(NamedTuple):
    """What the ring is identified from (SI): one record for a built-in tyre
    (:func:`builtin_data`) and for a user's test campaign
    (:mod:`tyrelab.fit.ring_step`)."""

    #: pressure [Pa] -> the tyre at that pressure (geometry, [SHAPE], PA1/PA2, masses)
    tyres: dict
    #: pressure [Pa] -> flat-plate press ``(n, 2)``: deflection [m], load [N] (fitted)
    loads: dict
    #: pressure [Pa] -> flat-plate press never fitted, only predicted
    held_loads: dict
    #: measured modes: ``mode`` (Table 3-3 numbering), ``pressure`` [Pa], ``frequency`` [Hz],
    #: ``damping`` (ratio, NaN where not measured)
    modes: pd.DataFrame
    #: pressure [Pa] of the damping targets (modal damping, drop test)
    reference: float
    #: bounds of the free parameters, in their scales (:data:`BOUNDS` for the XZL)
    bounds: tuple = BOUNDS

    @property
    def pressures(self) -> list:
        """The fitted pressures, in order."""
        return sorted(self.loads)


def builtin_data(name="xzl-16.00R20") -> RingData:
    """The thesis's data of built-in tyre ``name``: Table 3-2 at 300 and 550 kPa
    (fitted) and 100 kPa (held out), Table 3-3, damping targets at 300 kPa."""
    tyres = {p: load_tyre(name, p) for p in (*FIT_PRESSURES, HELD_OUT_PRESSURE)}
    wide = modal_table(name)
    rows = []
    for p in FIT_PRESSURES:
        col = f"freq_Hz_{p / 1e3:.0f}kPa"
        if col not in wide:
            continue
        for r in wide.itertuples():
            f = getattr(r, col)
            if np.isfinite(f):
                rows.append((int(r.mode), p, float(f),
                             float(getattr(r, f"damping_pct_{p / 1e3:.0f}kPa")) / 100))
    modes = pd.DataFrame(rows, columns=["mode", "pressure", "frequency", "damping"])
    return RingData(tyres, {p: tyres[p].load_deflection[1:] for p in FIT_PRESSURES},
                    {HELD_OUT_PRESSURE: tyres[HELD_OUT_PRESSURE].load_deflection[1:]}, modes, 300e3)


def _data(data) -> RingData:
    return data if isinstance(data, RingData) else builtin_data(data)


def measured_mode(data: RingData, mode: int, pressure: float, column="frequency") -> float:
    """A measured frequency [Hz] or damping ratio of ``mode`` at ``pressure`` (NaN if none)."""
    m = data.modes
    sel = m[(m["mode"] == mode) & np.isclose(m["pressure"], pressure)]
    return float(sel[column].iloc[0]) if len(sel) else float("nan")


def evaluate(data, rp, pressures, modes, contact=True, held_out=False):
    """Model vs data rows for ``pressures`` (load-deflection, ``modes``, contact);
    ``data`` a :class:`RingData` or a built-in tyre's name; ``held_out`` takes
    the presses from ``data.held_loads``."""
    data = _data(data)
    rows = []
    for p in pressures:
        tyre = data.tyres[p]
        press = (data.held_loads if held_out else data.loads)[p]
        d = press[:, 0]
        loads, _ = press_plate(tyre, rp, d)
        for dk, fm, ft in zip(d, loads, press[:, 1]):
            rows.append({"quantity": "load", "pressure_kPa": p / 1e3, "at": f"{dk * 1e3:.0f} mm",
                         "measured": ft, "model": fm})
        if modes:
            mod = ring_modal(tyre, parameters=rp).set_index("mode")
            for m in modes:
                meas = measured_mode(data, m, p)
                if np.isfinite(meas):
                    rows.append({"quantity": "mode", "pressure_kPa": p / 1e3, "at": f"mode {m}",
                                 "measured": meas, "model": float(mod.loc[m, "freq_Hz"])})
        if contact and _has_eq23(tyre):
            for dk in CONTACT_DEFLECTIONS:
                rows.append({"quantity": "contact", "pressure_kPa": p / 1e3,
                             "at": f"{dk * 1e3:.0f} mm",
                             "measured": float(contact_half_length_eq23(tyre, dk)),
                             "model": contact_half_length(tyre, rp, dk)})
    df = pd.DataFrame(rows)
    df["error_pct"] = 100 * (df["model"] - df["measured"]) / df["measured"]
    return df


def _has_eq23(tyre) -> bool:
    return tyre.tir.has("CONTACT_PATCH", "PA1") and tyre.tir.has("CONTACT_PATCH", "PA2")


def _residuals(x, data, rp0, progress=None, free=None):
    rp = _with(rp0, x, free)
    df = evaluate(data, rp, data.pressures, FIT_MODES)
    w = df["quantity"].map(WEIGHTS).to_numpy()
    # loads: relative to the point's load, but not below a fifth of the
    # curve's largest (the first points are small and uncertain)
    ref = df["measured"].to_numpy().copy()
    for p in data.pressures:
        sel = ((df["quantity"] == "load") & (df["pressure_kPa"] == p / 1e3)).to_numpy()
        ref[sel] = np.maximum(ref[sel], LOAD_FLOOR * ref[sel].max())
    r = w * (df["model"].to_numpy() - df["measured"].to_numpy()) / ref
    if progress is not None:
        progress(float(r @ r))
    return r


def modal_damping(tyre, rp, targets: dict, iterations=4):
    """Foundation dampers that give the target damping ratios (fractions) of
    modes 2 (radial = tangential dampers), 3 (lateral) and 4 (torsion).

    The damping ratio of each mode is nearly proportional to its damper;
    fixed-point iteration ``c <- c zeta_target / zeta_model``.
    """
    for _ in range(iterations):
        mod = ring_modal(tyre, parameters=rp).set_index("mode")
        z = {m: mod.loc[m, "damping_pct"] / 100 for m in targets}
        scale = {m: targets[m] / z[m] if z[m] > 0 else 1.0 for m in targets}
        rp = dataclasses.replace(
            rp, cr=rp.cr * scale.get(2, 1.0), ct=rp.ct * scale.get(2, 1.0),
            cy=rp.cy * scale.get(3, 1.0), cb=rp.cb * scale.get(4, 1.0))
    return rp


#: relaxation time of the ring's contact-patch Maxwell element [s]: below its
#: corner, 5 Hz, it is a damper for the trailer's pitch (2.6 Hz) and roll
#: (3.2 Hz) modes (93 % of the damping at 3.2 Hz that it has at 2.6 Hz)
PATCH_DAMPING_TIME = 1.0 / (2.0 * math.pi * 5.0)


def fit_patch_damping(tyre, rp, target, tol=0.01, progress=None):
    """The contact patch's damping that reproduces the drop test (thesis 3.4.1).

    The secant method on ``PATCH_DAMPING`` (relaxation time
    :data:`PATCH_DAMPING_TIME`) until the simulated trailer drop test,
    evaluated with the thesis's own procedure (:func:`drop_test_damping`),
    gives ``target`` [N s/m] per tyre within ``tol``. The element needs
    contact, so the modal damping of the free tyre (Table 3-3) does not move.
    Returns ``(rp, drop)`` with the last :class:`DropTestDamping`.
    """
    rp = dataclasses.replace(rp, tau_p=PATCH_DAMPING_TIME)
    x0 = 0.0
    f0 = ring_drop_test_damping(tyre, dataclasses.replace(rp, cp=x0)).damping - target
    x1 = rp.cp if rp.cp > 0 else max(-f0, 0.1 * target)  # the damping missing without it
    drop = None
    for _ in range(8):
        drop = ring_drop_test_damping(tyre, dataclasses.replace(rp, cp=x1))
        f1 = drop.damping - target
        if progress is not None:
            progress(x1, drop)
        if abs(f1) < tol * target or f1 == f0:
            break
        x0, f0, x1 = x1, f1, max(x1 - f1 * (x1 - x0) / (f1 - f0), 0.0)
    return dataclasses.replace(rp, cp=x1), drop


def start_inside(rp0: RingParameters, free: dict, lower, upper):
    """``(start, x0)``: the start moved inside the bounds, and its free values (scaled).

    The start itself is rebuilt from the clipped values, so that :func:`_with` at ``x0``
    is the start: with one pressure a foundation's pressure rate follows its constant part
    by the ratio to the start's, and a clipped constant part (the XZL's tangential one,
    19.35 N/m^2 against a lower bound of 100) must not scale the rate by that clip.
    """
    x0 = np.array([getattr(rp0, k) / s for k, s in free.items()])
    x0 = np.clip(x0, np.asarray(lower) + 1e-3, np.asarray(upper) - 1e-3)
    return dataclasses.replace(rp0, **{k: float(v) * s for (k, s), v in zip(free.items(), x0)}), x0


def fit_ring(name="xzl-16.00R20", start: RingParameters | None = None, max_nfev=25,
             verbose=0, ftol=2e-3, progress=None):
    """Identify the ring; returns ``(params, fitted, held_out)``.

    ``name`` is a built-in tyre's name (the thesis's data, :func:`builtin_data`)
    or a :class:`RingData` (a user's campaign, :mod:`tyrelab.fit.ring_step`).
    ``fitted`` and ``held_out`` are tables of measured vs model values with
    errors in percent (see the module doc for what is which). ``progress``,
    if given, is called with the cost after every model evaluation.
    """
    from scipy.optimize import least_squares
    data = _data(name)
    free = free_parameters(len(data.pressures))
    keep = [k in free for k in FREE]
    lower = np.array(data.bounds[0], float)[keep]
    upper = np.array(data.bounds[1], float)[keep]
    rp0, x0 = start_inside(start or dataclasses.replace(RingParameters(), **START), free, lower, upper)
    sol = least_squares(_residuals, x0, args=(data, rp0, progress, free), bounds=(lower, upper),
                        diff_step=0.02, max_nfev=max_nfev, verbose=verbose, x_scale=1.0,
                        ftol=ftol, xtol=1e-3)
    rp = _with(rp0, sol.x, free)
    ref = data.tyres[data.reference]
    targets = {m: measured_mode(data, m, data.reference, "damping") for m in DAMPING_MODES}
    rp = modal_damping(ref, rp, {m: z for m, z in targets.items() if np.isfinite(z)})
    # the drop test (thesis 3.4.1) sets the contact patch's damping; modes keep theirs
    rp, drop = fit_patch_damping(ref, rp, ref.vertical_damping)
    fitted = evaluate(data, rp, data.pressures, FIT_MODES)
    fitted = pd.concat([fitted, pd.DataFrame([{
        "quantity": "drop", "pressure_kPa": data.reference / 1e3, "at": "LC1 trailer",
        "measured": ref.vertical_damping / 1e3, "model": drop.damping / 1e3,
        "error_pct": 100 * (drop.damping / ref.vertical_damping - 1)}])], ignore_index=True)
    parts = [modal_comparison(data, rp, HELD_OUT_MODES)]
    if data.held_loads:
        parts.insert(0, evaluate(data, rp, sorted(data.held_loads), (), contact=False, held_out=True))
    held = pd.concat(parts, ignore_index=True)
    return rp, fitted, held


def modal_comparison(data, rp, modes, pressures=None):
    """Model vs measured (Table 3-3) frequencies and damping ratios for ``modes``."""
    data = _data(data)
    rows = []
    for p in data.pressures if pressures is None else pressures:
        mod = ring_modal(data.tyres[p], parameters=rp).set_index("mode")
        for m in modes:
            for q, col, mcol, scale in (("mode", "frequency", "freq_Hz", 1.0),
                                        ("damping", "damping", "damping_pct", 100.0)):
                meas = measured_mode(data, m, p, col) * scale
                if not np.isfinite(meas):
                    continue
                rows.append({"quantity": q, "pressure_kPa": p / 1e3, "at": f"mode {m}",
                             "measured": float(meas), "model": float(mod.loc[m, mcol])})
    df = pd.DataFrame(rows, columns=["quantity", "pressure_kPa", "at", "measured", "model"])
    df["error_pct"] = 100 * (df["model"] - df["measured"]) / df["measured"]
    return df


def write_ring_file(rp, path, header=()):
    """Write a pressure-independent ``.tir`` with [UNITS] and [FLEXIBLE_RING] (SI)."""
    tir = TirFile(header=list(header) or ["$ flexible ring parameters (tyrelab.fit.ring)"])
    rp.to_tir(tir)
    write_tir(tir, path)


def markdown_table(df) -> str:
    """A results table in Markdown (for docs/ring.md and the README)."""
    unit = {"load": "N", "mode": "Hz", "contact": "m", "damping": "%", "drop": "N s/mm"}
    lines = ["| quantity | pressure [kPa] | at | measured | model | error [%] |",
             "|---|---|---|---|---|---|"]
    for r in df.itertuples():
        fmt = "{:.3f}" if r.quantity == "contact" else "{:.2f}" if r.quantity != "load" else "{:.0f}"
        lines.append(f"| {r.quantity} [{unit[r.quantity]}] | {r.pressure_kPa:.0f} | {r.at} | "
                     f"{fmt.format(r.measured)} | {fmt.format(r.model)} | {r.error_pct:+.1f} |")
    return "\n".join(lines)


def rms(df, quantity) -> float:
    """RMS of the percent errors of one quantity."""
    e = df.loc[df["quantity"] == quantity, "error_pct"].to_numpy()
    return float(math.sqrt(np.mean(e ** 2))) if e.size else float("nan")
