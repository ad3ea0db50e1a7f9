"""The contact patch of the enveloping models: its keys in a property file (ADAMS
``[CONTACT_PATCH]`` or their MF-Swift twins, with defaults) and its half-length and
half-width against the deflection (thesis eqs. 2.3 and 2.4; MF-Swift's laws, written in the
load over the vertical stiffness, Fz / (Cz R0)).
"""

from __future__ import annotations

import math
import warnings

import numba as nb
import numpy as np

from ...errors import InputError

#: values used when the property file has neither the ADAMS nor the MF-Swift key
DEFAULTS = {"PA1": 0.15, "PA2": 7.06, "PAE": 0.72, "PBE": 1.0, "PCE": 2.0, "PLS": 0.9,
            "N_WIDTH": 10, "N_LENGTH": 15}
#: ADAMS key -> MF-Swift key for the same cam quantity
SWIFT = {"PAE": "ELLIPS_LENGTH", "PBE": "ELLIPS_HEIGHT", "PCE": "ELLIPS_ORDER",
         "PLS": "ELLIPS_SHIFT", "N_WIDTH": "ELLIPS_NWIDTH", "N_LENGTH": "ELLIPS_NLENGTH"}


def assumed_patch(tir, given=()) -> list[str]:
    """The contact-patch quantities ``tir`` gives neither as an ADAMS nor as an MF-Swift key
    (nor ``given`` as a model option), each with the default :func:`patch_key`,
    :func:`length_law` and :func:`width_law` take instead: the thesis XZL 16.00R20's."""
    def has(*keys):
        return any(tir.has("CONTACT_PATCH", k) for k in keys)

    missing = []
    mf52 = mf52_length(tir) is not None      # MF 5.2 has its own length, and the whole width
    if not has("PA1", "PA2", "Q_RA1", "Q_RA2") and not mf52:
        missing.append(f"the length law (PA1 {DEFAULTS['PA1']:g}, PA2 {DEFAULTS['PA2']:g})")
    if tir.table("CONTACT_WIDTH_CURVE") is None and not has("PB1", "Q_RB1", "Q_RB2") and not mf52:
        missing.append("the width law (the whole section width)")
    missing += [f"{name} {DEFAULTS[name]:g}" for name in ("PAE", "PBE", "PCE", "PLS", "N_WIDTH", "N_LENGTH")
                if not has(name, SWIFT[name]) and name.lower() not in given]
    return missing


#: property files whose assumed patch has been warned about in this process
_WARNED: set[str] = set()


def warn_assumed_patch(tir, given=()) -> None:
    """Warn, once per property file and process, when the enveloping models take the XZL's
    contact patch for quantities the file does not give (:func:`assumed_patch`)."""
    missing = assumed_patch(tir, given)
    if not missing or tir.source in _WARNED:
        return
    _WARNED.add(tir.source)
    warnings.warn(f"{tir.source}: no [CONTACT_PATCH] value for {', '.join(missing)}: the enveloping "
                  "models take the thesis XZL 16.00R20's, not this tyre's; fit them from its "
                  "footprints and cleat presses (tyrelab fit CAMPAIGN --into FILE)", UserWarning,
                  stacklevel=3)


def patch_key(tir, name):
    """The ADAMS key, else its MF-Swift twin, else the default."""
    for k in (name, SWIFT.get(name)):
        if k is not None and tir.has("CONTACT_PATCH", k):
            return tir.number("CONTACT_PATCH", k)
    return DEFAULTS[name]


def mf52_length(tir):
    """MF-Tyre 5.2's contact half length as an MF-Swift law, ``(Q_RA1, Q_RA2)`` equivalents, or
    None for a file that is not MF 5.2 (or whose Magic Formula does not read).

    MF 5.2 writes ``a = R0 (Q_A2 z + Q_A1 sqrt(z))`` in ``z = Fz / FNOMIN`` (MFeval's contact
    patch; ``Q_A1``, ``Q_A2`` from the file, else MFeval's estimate from ``R0 Cz / FNOMIN``).
    With ``z = s x``, ``x = Fz / (Cz R0)`` the MF-Swift laws' argument and ``s = Cz R0 / FNOMIN``,
    that is the MF-Swift law with ``Q_RA1 = Q_A1 sqrt(s)`` and ``Q_RA2 = Q_A2 s``.
    """
    from ...errors import InputError as _Unreadable
    from ..handling.mf import MagicFormula
    try:
        mf = MagicFormula.from_tir(tir)
    except _Unreadable:
        return None
    if mf.version != "5.2":
        return None
    s = mf.coefficient("VERTICAL_STIFFNESS") * mf.coefficient("UNLOADED_RADIUS") / mf.coefficient("FNOMIN")
    return mf.coefficient("QA1_EFF") * math.sqrt(s), mf.coefficient("QA2_EFF") * s


def length_law(tir):
    """(mode, (c1, c2)) of the half-length law: 0 eq. 2.3 (PA1, PA2), 1 MF-Swift (Q_RA1, Q_RA2;
    or MF 5.2's contact length, :func:`mf52_length`); else the defaults (the thesis XZL's)."""
    if tir.has("CONTACT_PATCH", "PA1") or tir.has("CONTACT_PATCH", "PA2"):
        return 0, (tir.number("CONTACT_PATCH", "PA1", DEFAULTS["PA1"]),
                   tir.number("CONTACT_PATCH", "PA2", DEFAULTS["PA2"]))
    if tir.has("CONTACT_PATCH", "Q_RA1") or tir.has("CONTACT_PATCH", "Q_RA2"):
        return 1, (tir.number("CONTACT_PATCH", "Q_RA1", 0.0), tir.number("CONTACT_PATCH", "Q_RA2", 0.0))
    mf52 = mf52_length(tir)
    if mf52 is not None:
        return 1, mf52
    return 0, (DEFAULTS["PA1"], DEFAULTS["PA2"])


def width_law(tir, width_table, b_max):
    """(mode, (c1, c2, c3), table rows) of the half-width law."""
    table = tir.table("CONTACT_WIDTH_CURVE")
    if width_table and table is None:
        raise InputError("width_table=True needs a [CONTACT_WIDTH_CURVE] table (deflection, "
                         "half width)", source=tir.source, field="CONTACT_WIDTH_CURVE")
    if table is not None and width_table is not False:
        if table.shape[1] != 2 or np.any(np.diff(table[:, 0]) <= 0) or np.any(table[:, 1] < 0):
            raise InputError("[CONTACT_WIDTH_CURVE] needs rows of increasing deflection and "
                             "non-negative half width", source=tir.source, field="CONTACT_WIDTH_CURVE")
        return 2, (0.0, 0.0, 0.0), table
    if tir.has("CONTACT_PATCH", "PB1"):
        return 0, tuple(tir.number("CONTACT_PATCH", k, 0.0) for k in ("PB1", "PB2", "PB3")), None
    if tir.has("CONTACT_PATCH", "Q_RB1") or tir.has("CONTACT_PATCH", "Q_RB2"):
        return 1, (tir.number("CONTACT_PATCH", "Q_RB1", 0.0),
                   tir.number("CONTACT_PATCH", "Q_RB2", 0.0), 0.0), None
    return 2, (0.0, 0.0, 0.0), np.array([[0.0, b_max]])  # no law: the whole tread


@nb.njit(cache=True)
def swift_argument(params, rho):
    """The MF-Swift laws' argument ``Fz / (Cz R0)`` at deflection ``rho`` > 0: the load of
    the tyre's static law over its stiffness Cz, per R0 (Besselink et al. 2010, eqs. 9 and 10),
    from ``params.swift_c1`` and ``swift_c2`` (:class:`.enveloping_params.EnvelopingParams`)."""
    return (params.swift_c1 + params.swift_c2 * rho) * rho / params.unloaded_radius


@nb.njit(cache=True)
def half_length(params, rho):
    """Half contact length a [m] at deflection ``rho``: eq. 2.3 (``length_law`` 0) or
    MF-Swift (1)."""
    if rho <= 0.0:
        return 0.0
    r0 = params.unloaded_radius
    c1 = params.length_c1
    c2 = params.length_c2
    if params.length_law == 0:
        x = rho / r0
        return c1 * r0 * (x + c2 * math.sqrt(x))  # eq. 2.3: PA1, PA2
    x = swift_argument(params, rho)
    return r0 * (c2 * x + c1 * math.sqrt(x))  # MF-Swift: Q_RA1, Q_RA2


@nb.njit(cache=True)
def half_width(params, rho):
    """Half contact width b [m] at deflection ``rho``, at most ``params.max_half_width``.

    ``width_law`` 0: eq. 2.4 (PB1-PB3); 1: MF-Swift (Q_RB1, Q_RB2); 2: the
    table ``params.width_table`` of (deflection, half width) rows, linear,
    clamped at its ends.
    """
    mode = params.width_law
    if mode == 2:
        table = params.width_table
        rows = table.shape[0]
        if rho <= table[0, 0]:
            b = table[0, 1]
        elif rho >= table[rows - 1, 0]:
            b = table[rows - 1, 1]
        else:
            i = 0
            while table[i + 1, 0] < rho:
                i += 1
            d0 = table[i, 0]
            d1 = table[i + 1, 0]
            f = (rho - d0) / (d1 - d0)
            b = table[i, 1] * (1.0 - f) + table[i + 1, 1] * f
    elif rho <= 0.0:
        b = 0.0
    else:
        w0 = params.width
        c1, c2, c3 = params.width_c1, params.width_c2, params.width_c3
        if mode == 0:
            x = rho / params.unloaded_radius
            b = c1 * w0 * (x + c2 * math.sqrt(x) + c3 * x * math.sqrt(x))  # eq. 2.4
        else:
            x = swift_argument(params, rho)
            b = w0 * (c2 * x + c1 * x ** (1.0 / 3.0))  # MF-Swift
    return min(max(b, 0.0), params.max_half_width)
