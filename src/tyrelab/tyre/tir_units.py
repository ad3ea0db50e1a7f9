"""Units of a tyre property file (``.tir``): the words its ``[UNITS]`` section may use, the
physical dimension of each key and table column tyrelab knows, and the factor that takes a
value to SI (:func:`units_factor`). :mod:`tyrelab.tyre.tir` applies them as it reads and
writes a file; keys of unknown dimension (Magic Formula coefficients) pass unchanged.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError

#: factor to SI for each unit word the [UNITS] section may use
_LENGTH = {"meter": 1.0, "metre": 1.0, "m": 1.0, "mm": 1e-3, "millimeter": 1e-3,
           "cm": 1e-2, "centimeter": 1e-2, "km": 1e3, "inch": 0.0254, "in": 0.0254,
           "foot": 0.3048, "ft": 0.3048, "mile": 1609.344}
_FORCE = {"newton": 1.0, "n": 1.0, "kn": 1e3, "kilonewton": 1e3,
          "pound_force": 4.4482216152605, "lbf": 4.4482216152605,
          "kg_force": 9.80665, "kgf": 9.80665, "ounce_force": 0.27801385095378,
          "dyne": 1e-5, "kilo_newton": 1e3, "kpound_force": 4448.2216152605}
_ANGLE = {"radians": 1.0, "radian": 1.0, "rad": 1.0, "degrees": np.pi / 180, "degree": np.pi / 180,
          "deg": np.pi / 180}
_MASS = {"kg": 1.0, "kilogram": 1.0, "gram": 1e-3, "g": 1e-3, "tonne": 1e3,
         "pound_mass": 0.45359237, "lbm": 0.45359237, "slug": 14.593902937,
         "kpound_mass": 453.59237, "ounce_mass": 0.028349523125}
_TIME = {"second": 1.0, "sec": 1.0, "s": 1.0, "millisecond": 1e-3, "ms": 1e-3,
         "minute": 60.0, "min": 60.0, "hour": 3600.0, "h": 3600.0}
_UNIT_TABLES = {"LENGTH": _LENGTH, "FORCE": _FORCE, "ANGLE": _ANGLE, "MASS": _MASS, "TIME": _TIME}


def _dim(L=0, F=0, A=0, M=0, T=0):
    return (L, F, A, M, T)


#: physical dimension of known keys, as exponents of (LENGTH, FORCE, ANGLE, MASS, TIME)
KEY_DIMENSIONS: dict[str, tuple[int, int, int, int, int]] = {
    # [DIMENSION]
    "UNLOADED_RADIUS": _dim(L=1), "WIDTH": _dim(L=1), "RIM_RADIUS": _dim(L=1), "RIM_WIDTH": _dim(L=1),
    # [VERTICAL]
    "VERTICAL_STIFFNESS": _dim(F=1, L=-1), "VERTICAL_DAMPING": _dim(F=1, T=1, L=-1),
    "FNOMIN": _dim(F=1), "BOTTOM_OFFST": _dim(L=1), "BOTTOM_STIFF": _dim(F=1, L=-1),
    "DAMPING_RAMP": _dim(L=1),
    # [CONTACT_MODEL] (MF-Swift enveloping)
    "ELLIPS_MAX_STEP": _dim(L=1),
    # [OPERATING_CONDITIONS] / [TIRE_CONDITIONS]
    "INFLPRES": _dim(F=1, L=-2), "NOMPRES": _dim(F=1, L=-2), "IP": _dim(F=1, L=-2), "IP_NOM": _dim(F=1, L=-2),
    # [INERTIA]
    "MASS": _dim(M=1), "IXX": _dim(M=1, L=2), "IYY": _dim(M=1, L=2),
    "WHEEL_MASS": _dim(M=1), "WHEEL_IYY": _dim(M=1, L=2),
    "BELT_MASS": _dim(M=1), "BELT_IXX": _dim(M=1, L=2), "BELT_IYY": _dim(M=1, L=2),
    # [MODEL]
    "LONGVL": _dim(L=1, T=-1), "VXLOW": _dim(L=1, T=-1),
    # ranges
    "ALPMIN": _dim(A=1), "ALPMAX": _dim(A=1), "CAMMIN": _dim(A=1), "CAMMAX": _dim(A=1),
    "FZMIN": _dim(F=1), "FZMAX": _dim(F=1),
    "PRESMIN": _dim(F=1, L=-2), "PRESMAX": _dim(F=1, L=-2),
    # [STRUCTURAL]
    "LONGITUDINAL_STIFFNESS": _dim(F=1, L=-1), "LATERAL_STIFFNESS": _dim(F=1, L=-1),
    "YAW_STIFFNESS": _dim(F=1, L=1, A=-1),
    # Fiala (ADAMS's [PARAMETER]): slip stiffness per unit slip, cornering stiffness per angle
    "CSLIP": _dim(F=1), "CALPHA": _dim(F=1, A=-1),
    "RELAX_LENGTH_X": _dim(L=1), "RELAX_LENGTH_Y": _dim(L=1), "ROLLING_RESISTANCE": _dim(L=1),
    # TMeasy (Chrono's parameter file): loads, and each curve's forces and initial slope
    "FZ_NOM": _dim(F=1), "FZ_MAX": _dim(F=1),
    **{f"{key}_{level}": _dim(F=1) for key in ("DFX0", "FXMAX", "FXSLD", "DFY0", "FYMAX", "FYSLD")
       for level in (1, 2)},
}

#: dimension of each column of known table sections
TABLE_DIMENSIONS: dict[str, tuple] = {
    "DEFLECTION_LOAD_CURVE": (_dim(L=1), _dim(F=1)),
    "BOTTOMING_CURVE": (_dim(L=1), _dim(F=1)),
    "SHAPE": (_dim(), _dim()),
    "CONTACT_WIDTH_CURVE": (_dim(L=1), _dim(L=1)),
}



def units_factor(units: dict[str, str], dim, source, line) -> float:
    """The factor [SI per file unit] of a value of dimension ``dim`` (exponents of LENGTH,
    FORCE, ANGLE, MASS, TIME) in a file whose [UNITS] are ``units`` (a missing word: SI);
    an unknown unit word is an InputError naming ``source`` and ``line``."""
    factor = 1.0
    for name, exponent in zip(("LENGTH", "FORCE", "ANGLE", "MASS", "TIME"), dim):
        if exponent == 0:
            continue
        word = units.get(name, {"LENGTH": "meter", "FORCE": "newton", "ANGLE": "radians",
                                "MASS": "kg", "TIME": "second"}[name])
        table = _UNIT_TABLES[name]
        key = str(word).strip().lower()
        if key not in table:
            raise InputError(f"unknown {name.lower()} unit '{word}', expected one of "
                             f"{', '.join(sorted(table))}", source=source, line=line, field=name)
        factor *= table[key] ** exponent
    return factor
