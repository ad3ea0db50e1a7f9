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
from . import tir_physics
from .vertical import DEFAULT_DAMPING_RAMP, NO_BOTTOMING, VerticalLaw

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
    tyre_spin_inertia : float
        Spin inertia of the tyre alone [kg m^2] (``[INERTIA] IYY`` in a file that also gives
        ``WHEEL_IYY``; 0: not given): a model whose belt carries the tyre's turns the rim
        with the rest (:func:`tyrelab.limits.rim_spin_inertia`).
    pressure : float
        Inflation pressure [Pa] the parameters describe.
    bottoming : ndarray or None
        The bottoming table (deflection [m], load added to the vertical law [N]) from
        ``[BOTTOMING_CURVE]`` or ``BOTTOM_STIFF``; None: the tyre does not bottom out.
    quadratic_law : tuple or None
        MF-Tyre 6.x's load-deflection law from ``[VERTICAL] Q_FZ2``: (k1 [N/m], k2 [N/m^2]) of
        ``k1 rho + k2 rho^2`` at the file's pressure (:func:`~tyrelab.tyre.vertical.mf_load_deflection`);
        the ``"table"`` stiffness of a file without ``[DEFLECTION_LOAD_CURVE]``.
    pressure_factor : float
        ``1 + PFZ1 dpi``, dpi = (INFLPRES - NOMPRES) / NOMPRES: how MF-Tyre's vertical stiffness
        follows the pressure (Besselink et al. 2010, eq. 5); it scales ``vertical_stiffness``
        in the linear law (the quadratic law has it already). 1 for other files.
    speed_stiffening : float
        ``Q_V2 R0 / LONGVL`` [s] (MF-Tyre, LONGVL 16.7 m/s if the file has none): the vertical
        law stiffens by ``1 + speed_stiffening |omega|`` with the spin (Pacejka 2012, eq. A3.3),
        in each stiffness mode; 0 without ``Q_V2``.
    force_softening : tuple
        ``((Q_FCX / FNOMIN)^2, (Q_FCY / FNOMIN)^2)`` [1/N^2]: MF-Tyre's law softens by
        ``- force_softening[0] Fx^2 - force_softening[1] Fy^2`` in the same factor (Pacejka
        2012, eq. A3.3), in each stiffness mode; zeros without ``Q_FCX``, ``Q_FCY``.
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
    tyre_spin_inertia: float = 0.0
    pressure: float = float("nan")
    damping_ramp: float = DEFAULT_DAMPING_RAMP
    tir: TirFile = field(default_factory=TirFile, repr=False)
    bottoming: np.ndarray | None = None
    quadratic_law: tuple[float, float] | None = None
    pressure_factor: float = 1.0
    speed_stiffening: float = 0.0
    force_softening: tuple[float, float] = (0.0, 0.0)

    # -- construction ---------------------------------------------------
    @classmethod
    def from_tir(cls, tir: TirFile | str, name: str | None = None) -> "Tyre":
        """Tyre from a parsed or on-disk property file."""
        if not isinstance(tir, TirFile):
            tir = read_tir(tir)
        tir = tir_physics.adams_fiala_layout(tir)
        src = tir.source
        tir_physics.check_physics(tir)
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
        pressure_factor = tir_physics.pressure_factor(tir)
        quadratic = tir_physics.quadratic_law(tir, r0, k, pressure_factor)
        return cls(
            name=name or tir.source,
            unloaded_radius=r0,
            width=width,
            vertical_stiffness=k,
            vertical_damping=c,
            load_deflection=table,
            stiffness="table" if table is not None or quadratic is not None else "linear",
            shape=shape,
            wheel_mass=tir.number("INERTIA", "WHEEL_MASS",
                                  default=tir.number("INERTIA", "MASS", default=0.0)),
            wheel_spin_inertia=tir.number("INERTIA", "WHEEL_IYY",
                                          default=tir.number("INERTIA", "IYY", default=0.0)),
            tyre_spin_inertia=(tir.number("INERTIA", "IYY", default=0.0)
                               if tir.has("INERTIA", "WHEEL_IYY") else 0.0),
            pressure=pressure,
            damping_ramp=tir.number("VERTICAL", "DAMPING_RAMP", default=DEFAULT_DAMPING_RAMP),
            tir=tir,
            bottoming=tir_physics.bottoming(tir, r0),
            quadratic_law=quadratic,
            pressure_factor=pressure_factor,
            speed_stiffening=tir_physics.speed_stiffening(tir, r0),
            force_softening=tir_physics.force_softening(tir),
        )

    def with_stiffness(self, mode: str) -> "Tyre":
        """The same tyre with ``"linear"`` or ``"table"`` vertical stiffness."""
        if mode not in STIFFNESS_MODES:
            raise InputError(f"unknown stiffness '{mode}', expected one of {', '.join(STIFFNESS_MODES)}",
                             field="stiffness")
        if mode == "table" and not self.has_nonlinear_law:
            raise InputError("this tyre has no [DEFLECTION_LOAD_CURVE] (nor MF-Tyre's Q_FZ2); use "
                             "linear stiffness", source=self.tir.source, field="stiffness")
        return replace(self, stiffness=mode)

    def require_width(self, what: str) -> "Tyre":
        """This tyre, if it has a width (``[DIMENSION] WIDTH``); else an :class:`InputError`
        saying that ``what`` (a model spreading its contact across the tyre) needs it."""
        if not self.width > 0:
            raise InputError(f"{what} needs the tyre's width ([DIMENSION] WIDTH), which the file "
                             "does not give; state it, or use the point model", source=self.tir.source,
                             field="WIDTH")
        return self

    @property
    def has_nonlinear_law(self) -> bool:
        """True when the file gives a nonlinear load-deflection law (the ``"table"`` stiffness):
        a ``[DEFLECTION_LOAD_CURVE]`` or MF-Tyre 6.x's ``Q_FZ2``."""
        return self.load_deflection is not None or self.quadratic_law is not None

    @property
    def quadratic_in_use(self) -> tuple[float, float] | None:
        """:attr:`quadratic_law` when it is the law :attr:`vertical_law` runs (the table
        stiffness of a file without ``[DEFLECTION_LOAD_CURVE]``), else None."""
        if self.stiffness == "table" and self.load_deflection is None:
            return self.quadratic_law
        return None

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
        quadratic = self.quadratic_in_use
        bottoming = NO_BOTTOMING if self.bottoming is None else self.bottoming
        key = (use_table, quadratic, self.vertical_stiffness, self.pressure_factor,
               self.speed_stiffening, self.force_softening, self.vertical_damping, self.damping_ramp,
               self.load_deflection.tobytes() if use_table else b"", bottoming.tobytes())
        cached = self.__dict__.get("_law")
        if cached is not None and cached[0] == key:
            return cached[1]
        if use_table:
            t = self.load_deflection
            law = VerticalLaw.table(t[:, 0], t[:, 1], self.vertical_damping, self.damping_ramp,
                                    stiffness=self.vertical_stiffness, source=self.tir.source,
                                    bottoming=bottoming, speed_stiffening=self.speed_stiffening,
                                    force_softening=self.force_softening)
        elif quadratic is not None:
            law = VerticalLaw.quadratic(*quadratic, self.vertical_damping, self.damping_ramp,
                                        stiffness=self.vertical_stiffness, up_to=self.unloaded_radius,
                                        bottoming=bottoming, speed_stiffening=self.speed_stiffening,
                                        force_softening=self.force_softening)
        else:
            law = VerticalLaw.linear(self.vertical_stiffness * self.pressure_factor,
                                     self.vertical_damping, self.damping_ramp, bottoming=bottoming,
                                     speed_stiffening=self.speed_stiffening,
                                     force_softening=self.force_softening)
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
