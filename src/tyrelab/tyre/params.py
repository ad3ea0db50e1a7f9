"""Tyre parameters: one object, read from (and written to) a ``.tir`` file.

:class:`Tyre` holds what every model needs in SI (radius, width, vertical
law, carcass shape, wheel mass) and keeps the whole parsed property file in
``tir`` for the models that need more (enveloping cams, ring, handling).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import InputError
from .tir import TirFile, read_tir, write_tir
from .vertical import DEFAULT_DAMPING_RAMP, VerticalLaw

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

    # -- construction ---------------------------------------------------
    @classmethod
    def from_tir(cls, tir: TirFile | str, name: str | None = None) -> "Tyre":
        """Tyre from a parsed or on-disk property file."""
        if not isinstance(tir, TirFile):
            tir = read_tir(tir)
        src = tir.source
        r0 = tir.number("DIMENSION", "UNLOADED_RADIUS", required=True)
        if not r0 > 0:
            raise InputError(f"UNLOADED_RADIUS must be positive, got {r0}", source=src,
                             field="UNLOADED_RADIUS")
        width = tir.number("DIMENSION", "WIDTH", default=0.0)
        table = tir.table("DEFLECTION_LOAD_CURVE")
        k = tir.number("VERTICAL", "VERTICAL_STIFFNESS", default=None)
        if k is None and table is None:
            raise InputError("needs VERTICAL_STIFFNESS in [VERTICAL] or a [DEFLECTION_LOAD_CURVE]",
                             source=src, field="VERTICAL_STIFFNESS")
        if k is None:  # secant stiffness of the table's last point
            k = float(table[-1, 1] / table[-1, 0])
        c = tir.number("VERTICAL", "VERTICAL_DAMPING", default=0.0)
        if c < 0 or k <= 0:
            raise InputError("vertical stiffness must be positive and damping non-negative",
                             source=src, field="VERTICAL")
        if table is not None:
            if table.shape[1] != 2:
                raise InputError("[DEFLECTION_LOAD_CURVE] needs two columns (deflection, load)",
                                 source=src, field="DEFLECTION_LOAD_CURVE")
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
    def vertical_law(self) -> VerticalLaw:
        """The compiled-ready vertical law (rebuilt only when its inputs change)."""
        use_table = self.stiffness == "table" and self.load_deflection is not None
        key = (use_table, self.vertical_stiffness, self.vertical_damping, self.damping_ramp,
               self.load_deflection.tobytes() if use_table else b"")
        cached = self.__dict__.get("_law")
        if cached is not None and cached[0] == key:
            return cached[1]
        if use_table:
            t = self.load_deflection
            law = VerticalLaw.table(t[:, 0], t[:, 1], self.vertical_damping, self.damping_ramp,
                                    stiffness=self.vertical_stiffness, source=self.tir.source)
        else:
            law = VerticalLaw.linear(self.vertical_stiffness, self.vertical_damping, self.damping_ramp)
        self.__dict__["_law"] = (key, law)
        return law

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
