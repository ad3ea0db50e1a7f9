"""Tyre parameters: one object, read from (and written to) a ``.tir`` file.

:class:`Tyre` holds what every model needs in SI (radius, width, vertical
law, carcass shape, wheel mass) and keeps the whole parsed property file in
``tir`` for the models that need more (enveloping cams, ring, handling).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .. import limits
from ..errors import InputError
from .tir import TirFile, read_tir, write_tir
from .vertical import DEFAULT_DAMPING_RAMP, NO_BOTTOMING, VerticalLaw, bottoming_table

#: the least spin inertia [kg m^2] a spin step divides by (:attr:`Tyre.spin_inertia`); the rigs
#: turn a wheel whose file gives none with :func:`tyrelab.limits.wheel_spin_inertia`'s estimate
MIN_SPIN_INERTIA = 1e-3
#: vertical stiffness modes a user can ask for
STIFFNESS_MODES = ("table", "linear")


@dataclass
class Tyre:
    """A tyre as the models see it (SI units).

    Attributes
    ----------
    name : str
    unloaded_radius : float
        R0 [m].
    width : float
        W0, nominal section width [m].
    vertical_stiffness : float
        Linear stiffness k_z [N/m].
    vertical_damping : float
        c_z [N s/m].
    load_deflection : ndarray or None
        ``(n, 2)`` table of deflection [m] and load [N].
    stiffness : str
        ``"table"`` (spline through ``load_deflection``; the default when the
        table exists, as in ADAMS) or ``"linear"``.
    shape : ndarray or None
        Carcass half-section ``(n, 2)``: radius ratio, width ratio (Table 4-1).
    wheel_mass : float
        Mass of tyre + rim carried by the hub [kg].
    wheel_spin_inertia : float
        Spin inertia of tyre + rim [kg m^2].
    pressure : float
        Inflation pressure [Pa] the parameters describe.
    bottoming : ndarray or None
        The bottoming table (deflection [m], load added to the vertical law [N]) from
        ``[BOTTOMING_CURVE]`` or ``BOTTOM_STIFF``; None: the tyre does not bottom out.
    tir : TirFile
        The whole property file, for models that need more.
    """

    name: str
    unloaded_radius: float
    width: float
    vertical_stiffness: float
    vertical_damping: float
    load_deflection: np.ndarray | None = None
    stiffness: str = "table"
    shape: np.ndarray | None = None
    wheel_mass: float = 0.0
    wheel_spin_inertia: float = 0.0
    pressure: float = float("nan")
    damping_ramp: float = DEFAULT_DAMPING_RAMP
    tir: TirFile = field(default_factory=TirFile, repr=False)
    bottoming: np.ndarray | None = None

    # -- construction ---------------------------------------------------
    @classmethod
    def from_tir(cls, tir: TirFile | str, name: str | None = None) -> "Tyre":
        """Tyre from a parsed or on-disk property file."""
        if not isinstance(tir, TirFile):
            tir = read_tir(tir)
        src = tir.source
        check_physics(tir)
        r0 = tir.number("DIMENSION", "UNLOADED_RADIUS", required=True)
        width = tir.number("DIMENSION", "WIDTH", default=0.0)
        table = tir.table("DEFLECTION_LOAD_CURVE")
        k = tir.number("VERTICAL", "VERTICAL_STIFFNESS", default=None)
        if k is None and table is None:
            raise InputError("needs VERTICAL_STIFFNESS in [VERTICAL] or a [DEFLECTION_LOAD_CURVE]",
                             source=src, field="VERTICAL_STIFFNESS")
        if k is None:  # secant stiffness of the table's last point
            k = float(table[-1, 1] / table[-1, 0])
            if not k <= limits.MAX_STIFFNESS:
                raise InputError(f"the table's secant stiffness {k:g} N/m is not physical; allowed: "
                                 f"up to {limits.MAX_STIFFNESS:g} N/m", source=src,
                                 line=tir.row_line("DEFLECTION_LOAD_CURVE", len(table) - 1),
                                 field="DEFLECTION_LOAD_CURVE")
        c = tir.number("VERTICAL", "VERTICAL_DAMPING", default=0.0)
        if c < 0 or k <= 0:
            raise InputError("vertical stiffness must be positive and damping non-negative",
                             source=src, field="VERTICAL")
        if table is not None:
            VerticalLaw.table(table[:, 0], table[:, 1], c, source=src)  # validates the table
        shape = tir.table("SHAPE")
        if shape is not None and (shape.shape[1] != 2 or shape.shape[0] > 10):
            raise InputError("[SHAPE] needs up to 10 rows of (radius ratio, width ratio)",
                             source=src, field="SHAPE")
        pressure = tir.number("OPERATING_CONDITIONS", "INFLPRES", default=None)
        if pressure is None:
            pressure = tir.number("TIRE_CONDITIONS", "IP", default=float("nan"))
        return cls(
            name=name or tir.source,
            unloaded_radius=r0,
            width=width,
            vertical_stiffness=k,
            vertical_damping=c,
            load_deflection=table,
            stiffness="table" if table is not None else "linear",
            shape=shape,
            wheel_mass=tir.number("INERTIA", "WHEEL_MASS",
                                  default=tir.number("INERTIA", "MASS", default=0.0)),
            wheel_spin_inertia=tir.number("INERTIA", "WHEEL_IYY",
                                          default=tir.number("INERTIA", "IYY", default=0.0)),
            pressure=pressure,
            damping_ramp=tir.number("VERTICAL", "DAMPING_RAMP", default=DEFAULT_DAMPING_RAMP),
            tir=tir,
            bottoming=_bottoming(tir, r0),
        )

    def with_stiffness(self, mode: str) -> "Tyre":
        """The same tyre with ``"linear"`` or ``"table"`` vertical stiffness."""
        if mode not in STIFFNESS_MODES:
            raise InputError(f"unknown stiffness '{mode}', expected one of {', '.join(STIFFNESS_MODES)}",
                             field="stiffness")
        if mode == "table" and self.load_deflection is None:
            raise InputError("this tyre has no [DEFLECTION_LOAD_CURVE]; use linear stiffness",
                             source=self.tir.source, field="stiffness")
        return replace(self, stiffness=mode)

    # -- what the kernels take -------------------------------------------
    @property
    def spin_inertia(self) -> float:
        """The file's spin inertia [kg m^2], ``wheel_spin_inertia``, at least
        :data:`MIN_SPIN_INERTIA` (a file that gives none; the spin step divides by it). The
        rigs take :func:`tyrelab.limits.wheel_spin_inertia`, which estimates a missing one."""
        return float(max(self.wheel_spin_inertia, MIN_SPIN_INERTIA))

    @property
    def vertical_law(self) -> VerticalLaw:
        """The compiled-ready vertical law (rebuilt only when its inputs change)."""
        use_table = self.stiffness == "table" and self.load_deflection is not None
        bottoming = NO_BOTTOMING if self.bottoming is None else self.bottoming
        key = (use_table, self.vertical_stiffness, self.vertical_damping, self.damping_ramp,
               self.load_deflection.tobytes() if use_table else b"", bottoming.tobytes())
        cached = self.__dict__.get("_law")
        if cached is not None and cached[0] == key:
            return cached[1]
        if use_table:
            t = self.load_deflection
            law = VerticalLaw.table(t[:, 0], t[:, 1], self.vertical_damping, self.damping_ramp,
                                    stiffness=self.vertical_stiffness, source=self.tir.source,
                                    bottoming=bottoming)
        else:
            law = VerticalLaw.linear(self.vertical_stiffness, self.vertical_damping, self.damping_ramp,
                                     bottoming=bottoming)
        self.__dict__["_law"] = (key, law)
        return law

    @property
    def pressure_text(self) -> str:
        """The inflation pressure as a message gives it: "300 kPa", or "pressure not stated"."""
        return f"{self.pressure / 1e3:g} kPa" if math.isfinite(self.pressure) else "pressure not stated"

    def static_deflection(self, load: float) -> float:
        """Deflection [m] at which the vertical law carries ``load`` [N]."""
        return self.vertical_law.deflection_at(load)

    def write(self, path) -> None:
        """Write the property file (SI units) with the current values."""
        tir = self.tir
        tir.set("DIMENSION", "UNLOADED_RADIUS", self.unloaded_radius)
        tir.set("DIMENSION", "WIDTH", self.width)
        tir.set("VERTICAL", "VERTICAL_STIFFNESS", self.vertical_stiffness)
        tir.set("VERTICAL", "VERTICAL_DAMPING", self.vertical_damping)
        if self.load_deflection is not None:
            tir.set_table("DEFLECTION_LOAD_CURVE", self.load_deflection, ["pen", "fz"])
        write_tir(tir, path)


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


def _bottoming(tir: TirFile, r0: float | None) -> np.ndarray | None:
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
    _bottoming(tir, r0)   # checks BOTTOM_STIFF / BOTTOM_OFFST
