"""Structural parameters of the flexible ring: the ``[FLEXIBLE_RING]`` section.

One parameter set serves every inflation pressure (thesis 4.5: FTire is
identified from two pressures). Stiffnesses that rise with pressure are
linear in it, ``k(p) = k0 + kp p``; the belt pre-tension is the membrane
hoop force ``T0 = p b Rb`` of the effective pressurized width ``b``.
Foundation values are per unit belt length (the kernel multiplies by the
segment length ``L0 = 2 pi Rb / N``).

Keys (SI; a file may state other units in [UNITS], converted on reading):

=============================  ========  ==========================================
TREAD_DEPTH                    m         tread thickness at the crown (Rb = R0 - depth)
RING_MASS                      kg        belt (ring) mass
FOUNDATION_RADIAL(_P)          N/m^2     radial sidewall stiffness per length (_P: per Pa, -)
FOUNDATION_TANGENTIAL(_P)      N/m^2     tangential foundation stiffness (per Pa)
FOUNDATION_LATERAL(_P)         N/m^2     lateral foundation stiffness (per Pa)
FOUNDATION_TORSION(_P)         N        torsional foundation stiffness per length (per Pa)
DAMPING_RADIAL ... _TORSION    N s/m^2   foundation dampers per length (torsion N s)
PATCH_DAMPING                  N s/m     damping of the contact patch's normal force
                                         below 1/(2 pi PATCH_DAMPING_TIME): a Maxwell
                                         element acting where the tyre meets the road,
                                         so rolling does not wash it out (docs/ring.md,
                                         "Damping")
PATCH_DAMPING_TIME             s         relaxation time of that element
PRESSURE_WIDTH                 m         b in T0 = p b Rb
EXTENSION_STIFFNESS            N         EA of the belt
EXTENSION_DAMPING              N s       damping of belt extension
BENDING_IN_PLANE               N m^2     EI about the spin axis
BENDING_OUT_OF_PLANE           N m^2     EI about the radial axis
TORSION_STIFFNESS              N m^2     GJ of the belt
TREAD_STIFFNESS                N/m^3     radial block stiffness per footprint area
TREAD_PROGRESSION              -         q in k d (1 + q d / h)
TREAD_DAMPING                  N s/m^3   radial block damping per area
TREAD_SHEAR_STIFFNESS          N/m^3     tangential block stiffness per area
TREAD_SHEAR_DAMPING            N s/m^3   tangential block damping per area
FRICTION                       -         mu of the tread on the road
CONTOUR_FACTOR                 -         share of the carcass contour drop ([SHAPE])
                                         the blocks keep: the rest is flattened by
                                         the belt's lateral bending, which a rigid
                                         segment does not have (assumed 0.5)
=============================  ========  ==========================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from importlib import resources
from pathlib import Path

import numpy as np

from ...errors import InputError
from ..tir import TirFile, read_tir
from ..tir_units import units_factor

SECTION = "FLEXIBLE_RING"
#: built-in tyres with an identified ring parameter file
BUILT_IN_RING = {"xzl-16.00R20": "xzl-16.00R20_ring.tir"}



def _d(L=0, F=0, M=0, T=0):
    return (L, F, 0, M, T)


#: field -> (key, dimension as exponents of LENGTH, FORCE, ANGLE, MASS, TIME)
KEYS = {
    "tread_depth": ("TREAD_DEPTH", _d(L=1)),
    "ring_mass": ("RING_MASS", _d(M=1)),
    "kr0": ("FOUNDATION_RADIAL", _d(F=1, L=-2)),
    "krp": ("FOUNDATION_RADIAL_P", _d()),  # (N/m^2) per Pa: dimensionless
    "kt0": ("FOUNDATION_TANGENTIAL", _d(F=1, L=-2)),
    "ktp": ("FOUNDATION_TANGENTIAL_P", _d()),
    "ky0": ("FOUNDATION_LATERAL", _d(F=1, L=-2)),
    "kyp": ("FOUNDATION_LATERAL_P", _d()),
    "kb0": ("FOUNDATION_TORSION", _d(F=1)),
    "kbp": ("FOUNDATION_TORSION_P", _d(L=2)),
    "cr": ("DAMPING_RADIAL", _d(F=1, T=1, L=-2)),
    "ct": ("DAMPING_TANGENTIAL", _d(F=1, T=1, L=-2)),
    "cy": ("DAMPING_LATERAL", _d(F=1, T=1, L=-2)),
    "cb": ("DAMPING_TORSION", _d(F=1, T=1)),
    "cp": ("PATCH_DAMPING", _d(F=1, T=1, L=-1)),
    "tau_p": ("PATCH_DAMPING_TIME", _d(T=1)),
    "pressure_width": ("PRESSURE_WIDTH", _d(L=1)),
    "ea": ("EXTENSION_STIFFNESS", _d(F=1)),
    "cea": ("EXTENSION_DAMPING", _d(F=1, T=1)),
    "ei": ("BENDING_IN_PLANE", _d(F=1, L=2)),
    "eio": ("BENDING_OUT_OF_PLANE", _d(F=1, L=2)),
    "gj": ("TORSION_STIFFNESS", _d(F=1, L=2)),
    "tread_stiffness": ("TREAD_STIFFNESS", _d(F=1, L=-3)),
    "tread_progression": ("TREAD_PROGRESSION", _d()),
    "tread_damping": ("TREAD_DAMPING", _d(F=1, T=1, L=-3)),
    "tread_shear_stiffness": ("TREAD_SHEAR_STIFFNESS", _d(F=1, L=-3)),
    "tread_shear_damping": ("TREAD_SHEAR_DAMPING", _d(F=1, T=1, L=-3)),
    "friction": ("FRICTION", _d()),
    "contour_factor": ("CONTOUR_FACTOR", _d()),
}


@dataclass
class RingParameters:
    """Pressure-independent structural parameters of the ring (SI, see module doc)."""

    tread_depth: float = 0.025
    ring_mass: float = 100.0
    kr0: float = 2.0e5
    krp: float = 2.0
    kt0: float = 2.0e5
    ktp: float = 1.0
    ky0: float = 1.4e5
    kyp: float = 0.46
    kb0: float = 2.0e4
    kbp: float = 0.0
    cr: float = 200.0
    ct: float = 200.0
    cy: float = 120.0
    cb: float = 5.0
    cp: float = 0.0
    tau_p: float = 0.04
    pressure_width: float = 0.25
    ea: float = 5.0e6
    cea: float = 40.0
    ei: float = 300.0
    eio: float = 5000.0
    gj: float = 500.0
    tread_stiffness: float = 1.6e8
    tread_progression: float = 1.0
    tread_damping: float = 5.0e4
    tread_shear_stiffness: float = 5.0e7
    tread_shear_damping: float = 1.0e4
    friction: float = 0.8
    contour_factor: float = 0.5

    @classmethod
    def from_tir(cls, tir: TirFile) -> "RingParameters":
        """Read ``[FLEXIBLE_RING]`` (missing keys keep their defaults)."""
        units = tir.units
        values = {}
        for name, (key, dim) in KEYS.items():
            raw = tir.get(SECTION, key, None)
            if raw is None:
                continue
            if not isinstance(raw, (int, float)) or not math.isfinite(raw):
                raise InputError(f"expected a finite number, found '{raw}'", source=tir.source,
                                 field=key)
            values[name] = float(raw) * units_factor(units, dim, tir.source, None)
        p = cls(**values)
        p.validate(tir.source)
        return p

    def validate(self, source="<memory>"):
        """Raise :class:`InputError` for values no ring can have."""
        positive = ("tread_depth", "ring_mass", "ea", "tread_stiffness", "tread_shear_stiffness")
        for name in positive:
            if not getattr(self, name) > 0:
                raise InputError(f"{KEYS[name][0]} must be positive", source=source,
                                 field=KEYS[name][0])
        for f in fields(self):
            v = getattr(self, f.name)
            if not math.isfinite(v):
                raise InputError(f"{KEYS[f.name][0]} must be finite", source=source,
                                 field=KEYS[f.name][0])
        if self.cp < 0 or not self.tau_p > 0:
            raise InputError("PATCH_DAMPING must be >= 0 and PATCH_DAMPING_TIME > 0",
                             source=source, field="PATCH_DAMPING")
        if self.friction < 0:
            raise InputError("FRICTION must be >= 0", source=source, field="FRICTION")

    def to_tir(self, tir: TirFile) -> TirFile:
        """Write the parameters into ``tir``'s [FLEXIBLE_RING] section, in the file's
        [UNITS] (SI without them), so :meth:`from_tir` reads back the same values."""
        for name, (key, dim) in KEYS.items():
            factor = units_factor(tir.units, dim, tir.source, None)
            tir.set(SECTION, key, float(getattr(self, name)) / factor)
        return tir

    def at_pressure(self, p: float) -> dict:
        """Per-length foundation stiffnesses and pre-tension at pressure ``p`` [Pa]."""
        return {"kr": self.kr0 + self.krp * p, "kt": self.kt0 + self.ktp * p,
                "ky": self.ky0 + self.kyp * p, "kb": self.kb0 + self.kbp * p,
                "pb": p * self.pressure_width}


def _ring_file(name: str):
    return resources.files("tyrelab.tyre").joinpath("data", BUILT_IN_RING[name])


def ring_parameters(tyre) -> RingParameters:
    """The ring parameters of a tyre.

    From the tyre's own ``[FLEXIBLE_RING]`` section if it has one, else from
    the identified file of a built-in tyre; otherwise :class:`InputError`.
    """
    if tyre.tir.has(SECTION):
        return RingParameters.from_tir(tyre.tir)
    key = {k.lower(): k for k in BUILT_IN_RING}.get(str(tyre.name).lower())
    if key is None:
        raise InputError(f"the ring model needs a [{SECTION}] section in the tyre's property "
                         f"file (fit one from your tests: tyrelab fit ring CAMPAIGN --into "
                         f"{Path(str(tyre.tir.source)).name})", source=tyre.tir.source,
                         field=SECTION)
    with resources.as_file(_ring_file(key)) as path:
        if not path.is_file():
            raise InputError(f"missing [{SECTION}] parameter file", source=str(path),
                             field=SECTION)
        tir = read_tir(path)
    if not tir.has(SECTION):
        raise InputError(f"no [{SECTION}] section", source=str(path), field=SECTION)
    return RingParameters.from_tir(tir)


def stable_step(rp: RingParameters, tyre, n: int, nb: int, safety: float = 0.5) -> float:
    """Largest internal step [s] for the explicit part of the update, ``safety * 2 / omega_max``.

    ``omega_max^2`` is bounded (Gershgorin) by the sum of the stiffnesses that
    act on one segment over its mass and are integrated explicitly: the radial
    and tangential foundation, the transverse
    stiffness of the chords' tension ``4 |T0| / L0``, in-plane bending
    ``16 EI / L0^3`` and every block of the segment pressed to the tread
    depth, ``sum k A (1 + 2 q) + k_s A`` (in plane, across and, with the
    lever of the half width, in twist). The chords' extension (``EA``,
    ``c_EA``), the belt's lateral bending and its torsion are implicit
    (:mod:`.implicit`) and set no limit; across, the lateral foundation, the
    tension's string stiffness ``4 |T0| / L0`` and the blocks do. The explicit
    dampers do: ``h <= safety * 2 / c_max``.
    """
    r0 = tyre.unloaded_radius
    rb = r0 - rp.tread_depth
    p = max(float(tyre.pressure), 0.0) if math.isfinite(tyre.pressure) else 0.0
    l0 = 2.0 * math.pi * rb / n
    m = rp.ring_mass / n
    k = rp.at_pressure(p)
    t0 = k["pb"] * rb
    half = tread_half_width(tyre, rp)
    area = l0 * 2.0 * half
    normal = area * rp.tread_stiffness * (1.0 + 2.0 * rp.tread_progression)
    tread = normal + area * rp.tread_shear_stiffness
    k_in = (k["kr"] + k["kt"]) * l0 + 4.0 * abs(t0) / l0 + 16.0 * rp.ei / l0 ** 3 + tread
    jt = m * (2.0 * half) ** 2 / 12.0
    k_lat = k["ky"] * l0 + 4.0 * abs(t0) / l0 + tread
    k_tw = k["kb"] * l0 + normal * half ** 2
    w2 = max(k_in / m, k_lat / m, k_tw / jt)
    c_in = (area * rp.tread_damping + (rp.cr + rp.ct) * l0) / m
    c_lat = (area * rp.tread_shear_damping + rp.cy * l0) / m
    h = safety * 2.0 / math.sqrt(w2)
    c_max = max(c_in, c_lat, rp.cb * l0 / jt)
    if c_max > 0:
        h = min(h, safety * 2.0 / c_max)
    return h


def tread_half_width(tyre, rp: RingParameters) -> float:
    """Half width of the tread [m]: where the carcass contour ([SHAPE]) is still
    within the tread depth less 5 mm of the crown (the shoulder drops below it)."""
    r0 = tyre.unloaded_radius
    shape = tyre.shape
    half_w = 0.5 * tyre.width if tyre.width > 0 else 0.3 * r0
    if shape is None or len(shape) < 2:
        return 0.75 * half_w
    limit = 1.0 - max(rp.tread_depth - 0.005, 0.002) / r0
    ratio, width = shape[:, 0], shape[:, 1]
    for k in range(1, len(ratio)):
        if ratio[k] < limit:
            f = (ratio[k - 1] - limit) / (ratio[k - 1] - ratio[k])
            return float(half_w * (width[k - 1] + f * (width[k] - width[k - 1])))
    return float(half_w * width[-1])


def contour_height(tyre, rp: RingParameters, y: np.ndarray) -> np.ndarray:
    """Block height above the belt [m] at lateral offsets ``y``:
    ``depth - CONTOUR_FACTOR R0 (1 - r(|y|))``, r the [SHAPE] radius ratio."""
    r0 = tyre.unloaded_radius
    shape = tyre.shape
    half_w = 0.5 * tyre.width if tyre.width > 0 else 0.3 * r0
    y = np.abs(np.asarray(y, float))
    if shape is None or len(shape) < 2:
        return np.full(y.shape, rp.tread_depth)
    order = np.argsort(shape[:, 1])
    r = np.interp(y / half_w, shape[order, 1], shape[order, 0])
    drop = r0 * (1.0 - r) * rp.contour_factor
    return np.maximum(rp.tread_depth - drop, 0.005)
