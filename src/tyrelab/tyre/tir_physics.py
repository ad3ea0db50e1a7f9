"""A property file's values checked for physical sense, and the vertical law read from them.

Every check names the file, the line and the key (:class:`~tyrelab.errors.InputError`).
:func:`check_physics` runs them all; :class:`~tyrelab.tyre.params.Tyre` takes the
vertical law's parts from here: the bottoming table, MF-Tyre 6.x's quadratic law with its
pressure factor, and its stiffening with speed.
"""

from __future__ import annotations

import numpy as np

from .. import limits
from ..errors import InputError
from .tir import TirFile
from .vertical import bottoming_table, mf_load_deflection

#: MF-Tyre's reference speed LONGVL [m/s] when a file has none (MFeval's ``readTIR`` default)
MF_REFERENCE_SPEED = 16.7


def _fail(tir: TirFile, message: str, section: str, key: str | None = None, row: int | None = None):
    line = tir.row_line(section, row) if row is not None else tir.line_of(section, key)
    raise InputError(message, source=tir.source, line=line, field=key or section)


def _bounded(tir: TirFile, section: str, key: str, low: float, high: float, unit: str,
             low_open: bool = True, why: str = "") -> float | None:
    """The value of ``key`` if present, checked to lie in (low, high] ([low, high] unless low_open)."""
    value = tir.get(section, key)
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        _fail(tir, f"expected a number, found '{value}'", section, key)
    v = float(value)
    if (v <= low if low_open else v < low) or v > high:
        lo = f"{low:g} <" if low_open else f"{low:g} <="
        _fail(tir, f"{v:g} {unit} is not physical{why}; allowed: {lo} {key} <= {high:g} {unit}",
              section, key)
    return v


def _check_curve(tir: TirFile, name: str, r0: float | None, what: str, instead: str) -> None:
    """Check a table of (deflection, ``what``) rows, ``[name]``, if the file has one: at least
    two rows of two columns, non-negative deflections that increase strictly (up to ``r0``),
    non-negative loads that never fall and do not all stay zero."""
    if not tir.has(name):
        return
    table = tir.table(name)
    if table is None or table.size == 0:
        _fail(tir, f"section [{name}] has no rows of (deflection, {what}); give at least two rows "
              f"or {instead}", name)
    if table.ndim != 2 or table.shape[1] != 2:
        _fail(tir, f"[{name}] needs two columns (deflection, {what}), found {table.shape[-1]}", name,
              row=0)
    d, f = table[:, 0], table[:, 1]
    if len(d) < 2:
        _fail(tir, f"[{name}] has {len(d)} row; a {what}-deflection curve needs at least two", name,
              row=0)
    for i in range(len(d)):
        if d[i] < 0:
            _fail(tir, f"deflection {d[i]:g} m is negative", name, row=i)
        if f[i] < 0:
            _fail(tir, f"{what} {f[i]:g} N is negative (a tyre does not pull the road)", name, row=i)
        if i and not d[i] > d[i - 1]:
            _fail(tir, f"deflection {d[i]:g} m does not increase (previous row {d[i - 1]:g} m); "
                  "deflections must increase strictly down the table", name, row=i)
        if i and f[i] < f[i - 1]:
            _fail(tir, f"{what} {f[i]:g} N is below the previous row's {f[i - 1]:g} N; the {what} "
                  "must not fall as the deflection grows", name, row=i)
        if r0 is not None and d[i] > r0:
            _fail(tir, f"deflection {d[i]:g} m is beyond the unloaded radius {r0:g} m", name, row=i)
    if not f[-1] > 0:
        _fail(tir, "the last load is zero: the table carries no load", name, row=len(d) - 1)


def bottoming(tir: TirFile, r0: float | None) -> np.ndarray | None:
    """The file's bottoming table (:func:`~tyrelab.tyre.vertical.bottoming_table`), or None.

    From ``[BOTTOMING_CURVE]`` (PAC2002) or ``[VERTICAL] BOTTOM_STIFF`` with ``BOTTOM_OFFST``
    (MF-Tyre 6.1/6.2, default offset 0; ``BOTTOM_STIFF`` 0: none); a file with both is
    refused, as is MF bottoming without ``RIM_RADIUS`` or one that starts before the tyre is
    pressed.
    """
    curve = tir.table("BOTTOMING_CURVE") if tir.has("BOTTOMING_CURVE") else None
    stiff = _bounded(tir, "VERTICAL", "BOTTOM_STIFF", 0.0, limits.MAX_STIFFNESS, "N/m", low_open=False)
    offset = _bounded(tir, "VERTICAL", "BOTTOM_OFFST", -limits.MAX_RADIUS, limits.MAX_RADIUS, "m")
    if stiff and curve is not None:
        _fail(tir, "the file gives bottoming twice, as [BOTTOMING_CURVE] and as BOTTOM_STIFF; keep "
              "one (set BOTTOM_STIFF = 0 to use the curve)", "VERTICAL", "BOTTOM_STIFF")
    if curve is not None:
        return bottoming_table(curve[:, 0], curve[:, 1])
    if not stiff or r0 is None:
        return None
    rim = tir.get("DIMENSION", "RIM_RADIUS")
    if rim is None:
        _fail(tir, "BOTTOM_STIFF needs [DIMENSION] RIM_RADIUS: bottoming starts where the loaded "
              "radius falls to RIM_RADIUS + BOTTOM_OFFST", "VERTICAL", "BOTTOM_STIFF")
    start = r0 - rim - float(offset or 0.0)
    if not start > 0:
        _fail(tir, f"BOTTOM_OFFST {float(offset):g} m puts bottoming at the unloaded tyre: RIM_RADIUS "
              f"{rim:g} m + BOTTOM_OFFST must stay below UNLOADED_RADIUS {r0:g} m", "VERTICAL",
              "BOTTOM_OFFST")
    return bottoming_table(stiffness=stiff, start=start)


def pressure_factor(tir: TirFile) -> float:
    """``1 + PFZ1 dpi`` (Besselink et al. 2010, eq. 5) with dpi = (INFLPRES - NOMPRES) / NOMPRES;
    1 when the file lacks PFZ1 or either pressure. Refused when it is not positive."""
    pfz1 = tir.number("VERTICAL", "PFZ1", default=0.0)
    pressure = tir.number("OPERATING_CONDITIONS", "INFLPRES", default=None)
    nominal = tir.number("OPERATING_CONDITIONS", "NOMPRES", default=None)
    if not pfz1 or pressure is None or not nominal:
        return 1.0
    factor = 1.0 + pfz1 * (pressure - nominal) / nominal
    if not factor > 0.0:
        _fail(tir, f"PFZ1 {pfz1:g} takes the vertical stiffness to {factor:g} times its nominal "
              f"value at INFLPRES {pressure:g} Pa (NOMPRES {nominal:g} Pa); it must stay positive",
              "VERTICAL", "PFZ1")
    return factor


def speed_stiffening(tir: TirFile, r0: float) -> float:
    """``Q_V2 R0 / LONGVL`` [s] (MF-Tyre's vertical stiffening with spin), 0 without Q_V2."""
    q_v2 = _bounded(tir, "VERTICAL", "Q_V2", -limits.MAX_TIR_MAGNITUDE, limits.MAX_TIR_MAGNITUDE, "")
    if not q_v2:
        return 0.0
    if q_v2 < 0.0:
        _fail(tir, f"Q_V2 {q_v2:g} makes the tyre softer the faster it spins, to nothing and below; "
              "it must not be negative", "VERTICAL", "Q_V2")
    longvl = _bounded(tir, "MODEL", "LONGVL", 0.0, limits.MAX_TIR_MAGNITUDE, "m/s")
    return q_v2 * r0 / (longvl or MF_REFERENCE_SPEED)


def force_softening(tir: TirFile) -> tuple[float, float]:
    """``((Q_FCX / FNOMIN)^2, (Q_FCY / FNOMIN)^2)`` [1/N^2]: how MF-Tyre's vertical law softens
    with the horizontal forces (Pacejka 2012, eq. A3.3); zeros without them. MF 6.2's load
    and camber dependence of the lateral term (``Q_FCY2``, ``Q_FYS1-3``) is left out."""
    q_fcx = _bounded(tir, "VERTICAL", "Q_FCX", -limits.MAX_TIR_MAGNITUDE, limits.MAX_TIR_MAGNITUDE, "") or 0.0
    q_fcy = _bounded(tir, "VERTICAL", "Q_FCY", -limits.MAX_TIR_MAGNITUDE, limits.MAX_TIR_MAGNITUDE, "") or 0.0
    if not (q_fcx or q_fcy):
        return 0.0, 0.0
    nominal = tir.get("VERTICAL", "FNOMIN")
    if nominal is None:
        _fail(tir, "Q_FCX and Q_FCY need FNOMIN: the forces' softening is written in FNOMIN",
              "VERTICAL", "Q_FCX" if q_fcx else "Q_FCY")
    nominal = _bounded(tir, "VERTICAL", "FNOMIN", 0.0, limits.MAX_TIR_MAGNITUDE, "N")
    return (q_fcx / nominal) ** 2, (q_fcy / nominal) ** 2


def quadratic_law(tir: TirFile, r0: float, stiffness: float, pressure_factor: float):
    """MF-Tyre 6.x's load-deflection law (k1, k2) if ``[VERTICAL]`` gives ``Q_FZ2``, else None.

    Needs FNOMIN; refused when no such law has the slope VERTICAL_STIFFNESS at FNOMIN
    (``4 Q_FZ2 > (Cz R0 / FNOMIN)^2``) or when its load stops rising before the rim
    (``RIM_RADIUS``; the wheel centre without one).
    """
    if not tir.has("VERTICAL", "Q_FZ2"):
        return None
    q_fz2 = _bounded(tir, "VERTICAL", "Q_FZ2", -limits.MAX_TIR_MAGNITUDE, limits.MAX_TIR_MAGNITUDE, "")
    nominal = tir.get("VERTICAL", "FNOMIN")
    if nominal is None:
        _fail(tir, "Q_FZ2 needs FNOMIN: the load-deflection law is written in FNOMIN", "VERTICAL",
              "Q_FZ2")
    law = mf_load_deflection(stiffness, r0, float(nominal), q_fz2, pressure_factor)
    if law is None:
        most = (stiffness * r0 / float(nominal)) ** 2 / 4.0
        _fail(tir, f"Q_FZ2 {q_fz2:g} is too large for VERTICAL_STIFFNESS {stiffness:g} N/m at FNOMIN "
              f"{float(nominal):g} N: the law's slope at FNOMIN could not be VERTICAL_STIFFNESS; "
              f"allowed: Q_FZ2 <= {most:.6g}", "VERTICAL", "Q_FZ2")
    reach = r0 - float(tir.get("DIMENSION", "RIM_RADIUS") or 0.0)
    if not law[0] + 2.0 * law[1] * reach > 0.0:
        _fail(tir, f"Q_FZ2 {q_fz2:g} makes the load fall before the tyre is pressed to the rim "
              f"({reach:g} m): a tyre does not get softer to nothing", "VERTICAL", "Q_FZ2")
    return law


#: the vertical law's keys an ADAMS Fiala file keeps in [PARAMETER] (its layout), not [VERTICAL]
FIALA_VERTICAL_KEYS = ("VERTICAL_STIFFNESS", "VERTICAL_DAMPING")


def adams_fiala_layout(tir: TirFile) -> TirFile:
    """``tir`` with an ADAMS Fiala file's vertical law where every other file has it: a file
    of ``PROPERTY_FILE_FORMAT = 'FIALA'`` keeps ``VERTICAL_STIFFNESS`` and ``VERTICAL_DAMPING``
    in ``[PARAMETER]`` (with CSLIP, CALPHA, ...); without a ``[VERTICAL]`` section they are
    copied there, each with its line. Other files are returned as they are."""
    fmt = str(tir.get("MODEL", "PROPERTY_FILE_FORMAT", "")).upper()
    if fmt != "FIALA" or tir.has("VERTICAL") or not tir.has("PARAMETER", "VERTICAL_STIFFNESS"):
        return tir
    import copy

    out = copy.deepcopy(tir)
    source = out.sections["PARAMETER"]
    for key in FIALA_VERTICAL_KEYS:
        if key in source.entries:
            out.set("VERTICAL", key, source.entries[key])
            out.sections["VERTICAL"].lines[key] = source.lines.get(key, 0)
    return out


def check_physics(tir: TirFile) -> None:
    """Check a property file's values for physical sense, naming file and line.

    Positive finite radius (at most :data:`tyrelab.limits.MAX_RADIUS`), width,
    stiffness, damping (non-negative), masses and inertias where the file gives
    them; the rim inside the tyre; a ``[DEFLECTION_LOAD_CURVE]`` that has rows,
    two columns, non-negative deflections that increase strictly and
    non-negative loads that never decrease. Sections a file does not have are
    not checked (every model checks what it needs).
    """
    r0 = tir.get("DIMENSION", "UNLOADED_RADIUS")
    if r0 is not None:
        r0 = _bounded(tir, "DIMENSION", "UNLOADED_RADIUS", 0.0, limits.MAX_RADIUS, "m")
    _bounded(tir, "DIMENSION", "WIDTH", 0.0, limits.MAX_WIDTH, "m", why=" (a tyre has a width)")
    rim = _bounded(tir, "DIMENSION", "RIM_RADIUS", 0.0, limits.MAX_RADIUS, "m")
    if rim is not None and r0 is not None and not rim < r0:
        _fail(tir, f"RIM_RADIUS {rim:g} m is not inside the tyre: it must be below UNLOADED_RADIUS "
              f"{r0:g} m", "DIMENSION", "RIM_RADIUS")
    _bounded(tir, "VERTICAL", "VERTICAL_STIFFNESS", 0.0, limits.MAX_STIFFNESS, "N/m")
    _bounded(tir, "VERTICAL", "VERTICAL_DAMPING", 0.0, limits.MAX_DAMPING, "N s/m", low_open=False)
    if r0 is not None:
        _bounded(tir, "VERTICAL", "DAMPING_RAMP", 0.0, r0, "m")
    for key in ("FNOMIN",):
        _bounded(tir, "VERTICAL", key, 0.0, limits.MAX_TIR_MAGNITUDE, "N")
    _bounded(tir, "VERTICAL_FORCE_RANGE", "FZMAX", 0.0, limits.MAX_TIR_MAGNITUDE, "N")
    for key in ("WHEEL_MASS", "MASS"):
        _bounded(tir, "INERTIA", key, 0.0, limits.MAX_WHEEL_MASS, "kg", why=" (a wheel has mass)")
    for key in ("WHEEL_IYY", "IYY"):
        _bounded(tir, "INERTIA", key, 0.0, limits.MAX_WHEEL_INERTIA, "kg m^2",
                 why=" (a wheel has a spin inertia)")
    for sec, key in (("OPERATING_CONDITIONS", "INFLPRES"), ("TIRE_CONDITIONS", "IP")):
        _bounded(tir, sec, key, 0.0, limits.MAX_TIR_MAGNITUDE, "Pa")
    _check_curve(tir, "DEFLECTION_LOAD_CURVE", r0, "load", "remove the section to use VERTICAL_STIFFNESS")
    _check_curve(tir, "BOTTOMING_CURVE", r0, "bottoming load", "remove the section")
    bottoming(tir, r0)   # checks BOTTOM_STIFF / BOTTOM_OFFST
