"""Units of measured channels and their conversion to and from SI.

TYDEX files and laboratory CSV files carry a unit per channel (N, kN, deg,
km/h, mm ...). The signal table (:mod:`tyrelab.signal`) is always SI, so a
reader converts on the way in and a writer converts on the way out. Every
unit is an affine map ``si = scale * value + offset``; only temperatures
need the offset.

The unit spellings accepted are the ones written in TYDEX files (release 1.3
uses plain ASCII such as ``N``, ``Nm``, ``deg``, ``km/h``, ``rad/s``, ``1/s``)
and their common variants. An unknown unit is an :class:`InputError`, never a
silent pass-through.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError

_DEG = math.pi / 180.0

#: unit spelling -> (SI unit, scale, offset); si = scale * value + offset
_UNITS: dict[str, tuple[str, float, float]] = {
    # force
    "n": ("N", 1.0, 0.0), "dan": ("N", 10.0, 0.0), "kn": ("N", 1e3, 0.0),
    # moment
    "nm": ("N m", 1.0, 0.0), "n m": ("N m", 1.0, 0.0), "n*m": ("N m", 1.0, 0.0),
    "n.m": ("N m", 1.0, 0.0), "knm": ("N m", 1e3, 0.0), "kn m": ("N m", 1e3, 0.0),
    "danm": ("N m", 10.0, 0.0), "nmm": ("N m", 1e-3, 0.0),
    # length
    "m": ("m", 1.0, 0.0), "mm": ("m", 1e-3, 0.0), "cm": ("m", 1e-2, 0.0),
    "km": ("m", 1e3, 0.0), "in": ("m", 0.0254, 0.0),
    # time
    "s": ("s", 1.0, 0.0), "sec": ("s", 1.0, 0.0), "ms": ("s", 1e-3, 0.0),
    "min": ("s", 60.0, 0.0), "h": ("s", 3600.0, 0.0),
    # speed
    "m/s": ("m/s", 1.0, 0.0), "km/h": ("m/s", 1.0 / 3.6, 0.0),
    "kph": ("m/s", 1.0 / 3.6, 0.0), "mm/s": ("m/s", 1e-3, 0.0),
    "mph": ("m/s", 0.44704, 0.0),
    # acceleration
    "m/s2": ("m/s2", 1.0, 0.0), "m/s^2": ("m/s2", 1.0, 0.0), "m/s**2": ("m/s2", 1.0, 0.0),
    "g": ("m/s2", 9.80665, 0.0),
    # angle
    "rad": ("rad", 1.0, 0.0), "deg": ("rad", _DEG, 0.0), "grad": ("rad", _DEG, 0.0),
    "degree": ("rad", _DEG, 0.0), "mrad": ("rad", 1e-3, 0.0),
    # angular speed
    "rad/s": ("rad/s", 1.0, 0.0), "1/s": ("rad/s", 1.0, 0.0), "deg/s": ("rad/s", _DEG, 0.0),
    "rpm": ("rad/s", 2 * math.pi / 60.0, 0.0), "1/min": ("rad/s", 2 * math.pi / 60.0, 0.0),
    # pressure
    "pa": ("Pa", 1.0, 0.0), "kpa": ("Pa", 1e3, 0.0), "mpa": ("Pa", 1e6, 0.0),
    "bar": ("Pa", 1e5, 0.0), "mbar": ("Pa", 100.0, 0.0), "psi": ("Pa", 6894.757293168, 0.0),
    # stiffness
    "n/m": ("N/m", 1.0, 0.0), "n/mm": ("N/m", 1e3, 0.0), "kn/m": ("N/m", 1e3, 0.0),
    # mass, temperature
    "kg": ("kg", 1.0, 0.0), "t": ("kg", 1e3, 0.0),
    "k": ("K", 1.0, 0.0), "degc": ("K", 1.0, 273.15), "c": ("K", 1.0, 273.15),
    # dimensionless
    "": ("", 1.0, 0.0), "-": ("", 1.0, 0.0), "1": ("", 1.0, 0.0), "%": ("", 0.01, 0.0),
}


def _key(unit: str) -> str:
    return " ".join(str(unit).strip().replace("[", "").replace("]", "").split()).lower()


def is_known_unit(unit: str) -> bool:
    """True if :func:`to_si` knows ``unit``."""
    return _key(unit) in _UNITS


def si_unit(unit: str, source=None, line=None, field=None) -> str:
    """The SI unit that ``unit`` converts to (``"kN"`` -> ``"N"``)."""
    return _lookup(unit, source, line, field)[0]


def _lookup(unit, source, line, field):
    try:
        return _UNITS[_key(unit)]
    except KeyError:
        raise InputError(f"unknown unit '{unit}'", source=source, line=line,
                         field=field) from None


def to_si(values, unit: str, source=None, line=None, field=None) -> np.ndarray:
    """Convert ``values`` given in ``unit`` to SI.

    Returns a float array; ``source``/``line``/``field`` only name the place
    in the error raised for an unknown unit.
    """
    _, scale, offset = _lookup(unit, source, line, field)
    return np.asarray(values, dtype=float) * scale + offset


def from_si(values, unit: str, source=None, line=None, field=None) -> np.ndarray:
    """Convert SI ``values`` to ``unit`` (the inverse of :func:`to_si`)."""
    _, scale, offset = _lookup(unit, source, line, field)
    return (np.asarray(values, dtype=float) - offset) / scale


def same_dimension(unit_a: str, unit_b: str) -> bool:
    """True if both units convert to the same SI unit (``"kN"``, ``"N"``)."""
    return is_known_unit(unit_a) and is_known_unit(unit_b) and si_unit(unit_a) == si_unit(unit_b)
