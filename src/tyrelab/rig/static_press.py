"""Static press: the non-rolling tyre pushed onto a plate or a cleat (thesis 3.3).

One press for every model: the rim is held level (spin axis along y, no
spin) and lowered onto the plate or cleat in ramps at ``PRESS_RATE``; at each
press depth it is held for ``HOLD`` and the loads of the last ``WINDOW`` are
averaged -- as the lab press measured (rim fixed, hydraulic actuator, load
averaged). Analytic models reach their static value at once; models with
dynamics (the ring) relax to static equilibrium during the hold, built with
their registered static options (the ring's relaxation damping).

Deflection is counted from first touch of the obstacle's top. ``test`` is
``"plate"`` (the flat steel plate of 3.3.1) or ``"cleat:WxH"`` (mm) with a
direction: ``"lateral"`` (cleat axis across the wheel plane, as a tyre rolls
over it) or ``"longitudinal"`` (cleat axis in the wheel plane).
"""

from __future__ import annotations

import re

import numpy as np
import pandas as pd

from ..errors import InputError
from ..road.obstacles import Cleat, Flat, Ridge, sizes_quoted_in_mm
from ..tyre.contact.shape import carcass_discs
from ..tyre.model import TyreModel
from ..tyre.static import DT, HOLD, PC, PRESS_COLUMNS, PRESS_RATE, WINDOW, press_path

DIRECTIONS = ("lateral", "longitudinal")
#: the rim starts this far above first touch [m]
CLEARANCE = 0.002


def press_road(test: str = "plate", direction: str = "lateral"):
    """The plate or cleat of a static test, and the height of its top [m]."""
    if test == "plate":
        return Flat(), 0.0
    m = re.fullmatch(r"cleat:(\d+(?:\.\d*)?)x(\d+(?:\.\d*)?)", test)
    if not m:
        raise InputError(f"unknown static test '{test}', expected 'plate' or 'cleat:WxH' (mm)",
                         field="test")
    w, h = float(m.group(1)) / 1e3, float(m.group(2)) / 1e3
    if direction not in DIRECTIONS:
        raise InputError(f"unknown direction '{direction}', expected {' or '.join(DIRECTIONS)}",
                         field="direction")
    try:
        with sizes_quoted_in_mm():  # as the test's name gives them
            if direction == "lateral":
                return Cleat(w, h, angle=0.0, start=-w / 2), h
            return Ridge(w, h), h
    except InputError as exc:
        raise InputError(f"{exc.reason} in static test '{test}'", field="test") from None


def pressed_wheel(model: TyreModel, grid, top: float, deflections):
    """Press ``model`` on ``grid`` through ``deflections`` [m] (from first touch of ``top``).

    Returns ``(wheel, result)``: the wheel record in its final pressed state
    and the ``(k, len(PRESS_COLUMNS))`` array of :data:`PRESS_COLUMNS` (columns
    ``PC.FZ``, ...), rows in the order given.
    """
    d = np.atleast_1d(np.asarray(deflections, float))
    if np.any(~np.isfinite(d)) or np.any(d < 0):
        raise InputError("press deflections must be finite and >= 0", field="deflection")
    wheel = model.wheel(grid, 0.0, static=True)
    r0 = model.tyre.unloaded_radius
    order = np.argsort(d, kind="stable")
    res = np.zeros((d.size, len(PRESS_COLUMNS)))
    press_path(wheel, top + r0 + CLEARANCE, top + r0 - d[order], PRESS_RATE, HOLD, WINDOW, DT,
               res)
    out = np.empty_like(res)
    out[order] = res
    return wheel, out


def static_press(model: TyreModel, deflection, test: str = "plate",
                 direction: str = "lateral") -> pd.DataFrame:
    """Load [N] on the plate or cleat at each press ``deflection`` [m], any model.

    Returns a table with ``deflection``, ``load`` (vertical force on the
    tyre), ``FX``, ``FY`` (road on tyre) and the model's own tyre deflection
    ``DEFLECT``.
    """
    road, top = press_road(test, direction)
    d = np.atleast_1d(np.asarray(deflection, float))
    _, out = pressed_wheel(model, road.grid(), top, d)
    return pd.DataFrame({"deflection": d, "load": out[:, PC.FZ], "FX": out[:, PC.FX], "FY": out[:, PC.FY],
                         "DEFLECT": np.maximum(out[:, PC.DEFLECT], 0.0)})


#: sampling pitch along x of the geometric footprint of analytic models [m]
FOOTPRINT_PITCH = 0.005


def footprint(model: TyreModel, load: float | None = None,
              deflection: float | None = None) -> dict:
    """Footprint of any model standing on the flat plate (thesis 3.3.3).

    The tyre is pressed onto the plate to the deflection of ``load`` [N] on
    its load-deflection law (or to ``deflection`` [m]); a model with a
    load-deflection of its own (one that registers a ``footprint``: the
    ring) is pressed on until it carries ``load`` (within
    :data:`FOOTPRINT_LOAD_TOLERANCE`). A model that
    registers a ``footprint`` (the ring: each tread block's normal force
    after the belt relaxed) gives its pressure map; an analytic model (point,
    volume, enveloping) has no pressure distribution, so its footprint is the
    geometric one its contact laws rest on: the undeformed carcass (the
    ``[SHAPE]`` discs of :func:`~tyrelab.tyre.contact.shape.carcass_discs`)
    cut by the plate, drawn at the mean pressure load / area.

    Returns a dict: ``x, y`` cell centres [m], ``force`` [N], ``pressure``
    [Pa], ``outline`` (closed polygon ``(k, 2)`` of ``(x, y)``), ``length``,
    ``width`` [m], ``cell`` (cell length, width [m]), ``load`` [N] (plate
    force), ``deflection`` [m], ``pressure_inflation`` [Pa].
    """
    tyre = model.tyre
    at_load = deflection is None
    if at_load:
        if load is None or not (np.isfinite(load) and load > 0):
            raise InputError(f"footprint load must be a positive number of newtons, got {load}",
                             field="load")
        deflection = tyre.static_deflection(float(load))
    d = float(deflection)
    if not (np.isfinite(d) and 0 < d < tyre.unloaded_radius):
        raise InputError(f"footprint deflection must be between 0 and the radius, got {d} m",
                         field="deflection")
    wheel, res = pressed_wheel(model, Flat().grid(), 0.0, [d])
    hook = model.contact_model.footprint
    if hook is None:
        return geometric_footprint(tyre, d, float(res[0, PC.FZ]))
    if at_load:  # a model with a load-deflection of its own: pressed until it carries ``load``
        d, wheel, res = _press_to_load(model, float(load), d, wheel, res)
    return hook(wheel, float(res[0, PC.FZ]), d, tyre)


#: a footprint at a load is pressed until the plate force is within this share of it
FOOTPRINT_LOAD_TOLERANCE = 2e-3


def _press_to_load(model, load, d, wheel, res, presses=6):
    """The deflection, wheel and press result at which ``model`` carries ``load`` [N] on the
    plate: a secant on the deflection from ``d`` (the tyre law's), its first step along the
    law's slope. The ring's own curve departs from the law it was fitted to (23.7 kN at the
    law's deflection of 23.3 kN, the XZL at LC1), so its footprint would be another load's."""
    f = float(res[0, PC.FZ])
    law = model.tyre.vertical_law
    h = 1e-4
    slope = float(law.static_load(d + h) - law.static_load(d - h)) / (2 * h)
    d_prev, f_prev = d, f
    for _ in range(presses):
        if abs(f - load) <= FOOTPRINT_LOAD_TOLERANCE * load:
            break
        d_new = d + (load - f) / slope
        d_new = float(np.clip(d_new, 0.5 * d, min(1.5 * d, 0.99 * model.tyre.unloaded_radius)))
        wheel, res = pressed_wheel(model, Flat().grid(), 0.0, [d_new])
        d_prev, f_prev, d, f = d, f, d_new, float(res[0, PC.FZ])
        if d != d_prev and f != f_prev:
            slope = (f - f_prev) / (d - d_prev)
    return d, wheel, res


def geometric_footprint(tyre, deflection: float, load: float) -> dict:
    """The undeformed carcass cut by a plate ``deflection`` [m] below first touch.

    Each disc k of the carcass (radius ``r_k``, width ``w_k``) cuts the plate
    along a chord of half length ``sqrt(r_k^2 - h^2)``, ``h = R0 - deflection``
    the rim centre's height; the cells of that strip carry the mean pressure
    ``load / area``.
    """
    offsets, radii, widths = carcass_discs(tyre)
    h = tyre.unloaded_radius - deflection
    touching = radii > h
    e, w = offsets[touching], widths[touching]
    a = np.sqrt(radii[touching] ** 2 - h ** 2)  # half chord of each disc on the plate
    counts = np.maximum(1, np.ceil(2 * a / FOOTPRINT_PITCH).astype(int))
    # cells of each strip: centres evenly across its chord, equal shares of its area
    x = np.concatenate([np.linspace(-ak, ak, 2 * n + 1)[1::2] for ak, n in zip(a, counts)] or
                       [np.zeros(0)])
    y = np.repeat(e, counts)
    area = np.repeat(w * 2 * a / counts, counts)
    force = load * area / area.sum() if area.size else area
    # outline: the strips' leading ends left to right, their trailing ends back
    left, right = e - w / 2, e + w / 2
    outline = np.column_stack([np.r_[a, a[-1:], -a[::-1], -a[:1], a[:1]],
                               np.r_[left, right[-1:], right[::-1], left[:1], left[:1]]]) \
        if a.size else np.zeros((0, 2))
    return {"x": x, "y": y, "force": force, "pressure": force / area if area.size else area,
            "outline": outline, "length": float(2 * a.max()) if a.size else 0.0,
            "width": float(right.max() - left.min()) if a.size else 0.0, "load": load,
            "cell": (FOOTPRINT_PITCH, float(widths[0])), "deflection": deflection,
            "pressure_inflation": float(tyre.pressure)}
