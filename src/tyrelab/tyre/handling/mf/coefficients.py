"""Magic Formula 5.2 / 6.1 / 6.2 coefficients: reading, defaults, packing.

A property file is reduced to one float64 vector (``pack``) that the
compiled kernels index with the integer constants of :mod:`.coefficient_index`
(``coefficient_index.PCX1`` is the position of PCX1 in the vector). That module
is generated from :data:`NAMES` (:func:`index_module_source`, written by
``python tools/make_mf_coefficient_index.py``) and checked in, so editors and
linters see every name; ``tests/test_mf_coefficient_index.py`` fails, and
:func:`pack` refuses to run, when it is not current.

Defaults
--------
A coefficient missing from a file takes the value MFeval 4.3.1's ``readTIR``
gives it (for example PKY4 = 2, QSX4 = 5, Q_FZ2 = 1e-4, LONGVL = 16.7), so
that results agree with MFeval for incomplete files. FNOMIN has no default:
a file without it is rejected.

Version
-------
Taken from ``[MODEL] FITTYP`` (6 or 21: MF 5.2, 61: MF 6.1, 62: MF 6.2),
else from ``PROPERTY_FILE_FORMAT`` ('PAC2002' and 'MF_05': 5.2, 'MF_61',
'MF61': 6.1, 'MF_62', 'MF62': 6.2), else from ``FILE_VERSION`` when it
reads 5.2, 6.1 or 6.2. PAC89/PAC94/motorcycle files are refused.
MF-Tyre 5.0 (``FITTYP = 5``, written with ``PROPERTY_FILE_FORMAT = 'MF_05'``)
is read with the 5.2 equations, which carry its coefficients unchanged (the
Pacejka 2002 set; Project Chrono's ``ChPac02Tire`` reads 'MF_05' files the same
way); MFeval reads no 5.0 file, so that reading has no reference run.

Combined slip
-------------
``[MODEL] FE_METHOD = 'YES'`` (MF-Tyre's switch, "use friction ellipsis method
for combined forces") replaces Pacejka's weighting functions by the friction
ellipse (:func:`.forces.friction_ellipse_weights`); a file without the key, or
with 'NO', uses Pacejka's (MFeval's default). The slot ``FRICTION_ELLIPSE`` is 1
or 0.

Mirroring
---------
A negative ``[MODEL] USE_MODE`` (MF-Tyre's "*-1: mirroring of tyre characteristics") mirrors
the tyre: the slot ``MIRRORED`` is 1 and the kernel evaluates it as the file's tyre seen in a
mirror through its wheel plane (:func:`.kernel.mf_forces`). A rig that mounts the tyre on the
other side of a vehicle than ``TYRESIDE`` states mirrors it too
(:func:`.wheel.mf_mirrored`).

Units
-----
:func:`tyrelab.tyre.tir.read_tir` converts the keys it knows to SI. The few
dimensional keys used here that it does not know (PRESMIN, PRESMAX,
LONGITUDINAL_STIFFNESS, LATERAL_STIFFNESS) are converted here with the
file's [UNITS]. MF coefficients are dimensionless (or SI by the standard).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np

from ...tir import TirFile, read_tir
from ...tir_units import KEY_DIMENSIONS, units_factor
from ...vertical import mf_q_fz1
from ....errors import InputError

#: (name, MFeval readTIR default). Order defines the packed vector (and
#: :mod:`.coefficient_index`: regenerate it after any change here).
PARAMETERS: tuple[tuple[str, float], ...] = (
    # model, dimensions, operating conditions
    ("LONGVL", 16.7), ("VXLOW", 1.0),
    ("UNLOADED_RADIUS", 0.3135), ("WIDTH", 0.205), ("ASPECT_RATIO", 0.6), ("RIM_RADIUS", 0.1905),
    ("INFLPRES", 220000.0), ("NOMPRES", 220000.0),
    # vertical
    ("FNOMIN", math.nan), ("VERTICAL_STIFFNESS", 200000.0),
    ("BREFF", 8.4), ("DREFF", 0.27), ("FREFF", 0.07), ("Q_RE0", 1.0), ("Q_V1", 0.0), ("Q_V2", 0.0),
    ("Q_FZ2", 1.0e-4), ("Q_FCX", 0.0), ("Q_FCY", 0.0), ("PFZ1", 0.0), ("BOTTOM_OFFST", 0.01),
    ("Q_FCY2", 0.0), ("Q_CAM1", 0.0), ("Q_CAM2", 0.0), ("Q_CAM3", 0.0),
    ("Q_FYS1", 0.0), ("Q_FYS2", 0.0), ("Q_FYS3", 0.0),
    # structural
    ("LONGITUDINAL_STIFFNESS", 300000.0), ("LATERAL_STIFFNESS", 100000.0),
    ("PCFX1", 0.0), ("PCFX2", 0.0), ("PCFX3", 0.0), ("PCFY1", 0.0), ("PCFY2", 0.0), ("PCFY3", 0.0),
    # contact patch
    ("Q_RA1", 0.5), ("Q_RA2", 1.0), ("Q_RB1", 1.0), ("Q_RB2", -1.0), ("Q_A1", 0.0), ("Q_A2", 0.0),
    # input ranges
    ("PRESMIN", 10000.0), ("PRESMAX", 1000000.0), ("FZMIN", 100.0), ("FZMAX", 10000.0),
    ("KPUMIN", -1.5), ("KPUMAX", 1.5), ("ALPMIN", -1.5), ("ALPMAX", 1.5),
    ("CAMMIN", -0.175), ("CAMMAX", 0.175),
    # scaling
    ("LFZO", 1.0), ("LCX", 1.0), ("LMUX", 1.0), ("LEX", 1.0), ("LKX", 1.0), ("LHX", 1.0), ("LVX", 1.0),
    ("LCY", 1.0), ("LMUY", 1.0), ("LEY", 1.0), ("LKY", 1.0), ("LHY", 1.0), ("LVY", 1.0),
    ("LTR", 1.0), ("LRES", 1.0), ("LXAL", 1.0), ("LYKA", 1.0), ("LVYKA", 1.0), ("LS", 1.0),
    ("LKYC", 1.0), ("LKZC", 1.0), ("LVMX", 1.0), ("LMX", 1.0), ("LMY", 1.0),
    ("LSGKP", 1.0), ("LSGAL", 1.0),
    # longitudinal
    ("PCX1", 1.65), ("PDX1", 1.3), ("PDX2", -0.15), ("PDX3", 0.0),
    ("PEX1", 0.0), ("PEX2", 0.0), ("PEX3", 0.0), ("PEX4", 0.0),
    ("PKX1", 20.0), ("PKX2", 0.0), ("PKX3", 0.0), ("PHX1", 0.0), ("PHX2", 0.0),
    ("PVX1", 0.0), ("PVX2", 0.0), ("PPX1", 0.0), ("PPX2", 0.0), ("PPX3", 0.0), ("PPX4", 0.0),
    ("RBX1", 20.0), ("RBX2", 15.0), ("RBX3", 0.0), ("RCX1", 1.0), ("REX1", 0.0), ("REX2", 0.0),
    ("RHX1", 0.0), ("PTX1", 0.0), ("PTX2", 0.0), ("PTX3", 0.0),
    # overturning
    ("QSX1", 0.0), ("QSX2", 0.0), ("QSX3", 0.0), ("QSX4", 5.0), ("QSX5", 1.0), ("QSX6", 10.0),
    ("QSX7", 0.0), ("QSX8", 0.0), ("QSX9", 0.4), ("QSX10", 0.0), ("QSX11", 5.0),
    ("QSX12", 0.0), ("QSX13", 0.0), ("QSX14", 0.0), ("PPMX1", 0.0),
    # lateral
    ("PCY1", 1.3), ("PDY1", 1.1), ("PDY2", -0.15), ("PDY3", 0.0),
    ("PEY1", 0.0), ("PEY2", 0.0), ("PEY3", 0.0), ("PEY4", 0.0), ("PEY5", 0.0),
    ("PKY1", -20.0), ("PKY2", 1.0), ("PKY3", 0.0), ("PKY4", 2.0), ("PKY5", 0.0), ("PKY6", -1.0),
    ("PKY7", 0.0), ("PHY1", 0.0), ("PHY2", 0.0), ("PHY3", 0.0),
    ("PVY1", 0.0), ("PVY2", 0.0), ("PVY3", 0.0), ("PVY4", 0.0),
    ("PPY1", 0.0), ("PPY2", 0.0), ("PPY3", 0.0), ("PPY4", 0.0), ("PPY5", 0.0),
    ("RBY1", 10.0), ("RBY2", 10.0), ("RBY3", 0.0), ("RBY4", 0.0), ("RCY1", 1.0),
    ("REY1", 0.0), ("REY2", 0.0), ("RHY1", 0.0), ("RHY2", 0.0),
    ("RVY1", 0.0), ("RVY2", 0.0), ("RVY3", 0.0), ("RVY4", 20.0), ("RVY5", 2.0), ("RVY6", 10.0),
    ("PTY1", 0.0), ("PTY2", 0.0),
    # rolling resistance
    ("QSY1", 0.01), ("QSY2", 0.0), ("QSY3", 4.0e-4), ("QSY4", 4.0e-5), ("QSY5", 0.0),
    ("QSY6", 0.0), ("QSY7", 0.85), ("QSY8", -0.4),
    # aligning
    ("QBZ1", 10.0), ("QBZ2", 0.0), ("QBZ3", 0.0), ("QBZ4", 0.0), ("QBZ5", 0.0),
    ("QBZ9", 10.0), ("QBZ10", 0.0), ("QCZ1", 1.1),
    ("QDZ1", 0.12), ("QDZ2", 0.0), ("QDZ3", 0.0), ("QDZ4", 0.0), ("QDZ6", 0.0), ("QDZ7", 0.0),
    ("QDZ8", -0.05), ("QDZ9", 0.0), ("QDZ10", 0.0), ("QDZ11", 0.0),
    ("QEZ1", 0.0), ("QEZ2", 0.0), ("QEZ3", 0.0), ("QEZ4", 0.0), ("QEZ5", 0.0),
    ("QHZ1", 0.0), ("QHZ2", 0.0), ("QHZ3", 0.0), ("QHZ4", 0.0),
    ("PPZ1", 0.0), ("PPZ2", 0.0), ("SSZ1", 0.0), ("SSZ2", 0.0), ("SSZ3", 0.0), ("SSZ4", 0.0),
)

#: derived slots appended after the file parameters (filled by :func:`pack`)
DERIVED = ("VERSION", "Q_FZ1", "QA1_EFF", "QA2_EFF", "FRICTION_ELLIPSE", "MIRRORED")

NAMES: tuple[str, ...] = tuple(n for n, _ in PARAMETERS) + DERIVED
INDEX: dict[str, int] = {n: i for i, n in enumerate(NAMES)}
N_COEFFICIENTS = len(NAMES)

#: the generated module of positions (:mod:`.coefficient_index`)
INDEX_MODULE = Path(__file__).with_name("coefficient_index.py")


def index_module_source() -> str:
    """The text of :mod:`.coefficient_index`: one ``NAME = position`` line per name of :data:`NAMES`."""
    lines = ['"""Positions of the Magic Formula coefficients in the packed vector (generated: do not edit).',
             "",
             "Written by ``python tools/make_mf_coefficient_index.py`` from",
             ":data:`tyrelab.tyre.handling.mf.coefficients.NAMES` (the property-file parameters,",
             "then the derived slots); ``tests/test_mf_coefficient_index.py`` fails when this file",
             "is not current. The compiled kernels read ``C.PCX1`` after ``from . import",
             "coefficient_index as C``: numba freezes these integers into the machine code, and the",
             "compile cache's digest covers this module (imported by the kernels at top level).",
             '"""',
             ""]
    for i, name in enumerate(NAMES):
        if i == len(PARAMETERS):
            lines += ["", "# derived slots, filled by coefficients.pack"]
        lines.append(f"{name} = {i}")
    lines += ["", "#: length of the packed vector", f"N_COEFFICIENTS = {N_COEFFICIENTS}"]
    return "\n".join(lines) + "\n"


def stale_index_names() -> list[str]:
    """Names whose position in :mod:`.coefficient_index` is not their position in
    :data:`NAMES` (empty when the generated module is current)."""
    from . import coefficient_index  # here: the generator runs before the module exists
    stale = [n for i, n in enumerate(NAMES) if getattr(coefficient_index, n, None) != i]
    if getattr(coefficient_index, "N_COEFFICIENTS", None) != N_COEFFICIENTS:
        stale.append("N_COEFFICIENTS")
    return stale


_index_checked = False


def _check_index_module() -> None:
    """Refuse to pack for kernels that would read the wrong slots (a stale generated module)."""
    global _index_checked
    if not _index_checked:
        stale = stale_index_names()
        if stale:
            raise RuntimeError(f"{INDEX_MODULE.name} is not current with coefficients.NAMES "
                               f"({', '.join(stale[:5])}{' ...' if len(stale) > 5 else ''}): run "
                               "python tools/make_mf_coefficient_index.py")
        _index_checked = True


#: keys with a physical dimension that tir.py may not convert, as
#: (LENGTH, FORCE, ANGLE, MASS, TIME) exponents
_EXTRA_DIMENSIONS = {
    "PRESMIN": (-2, 1, 0, 0, 0), "PRESMAX": (-2, 1, 0, 0, 0),
    "LONGITUDINAL_STIFFNESS": (-1, 1, 0, 0, 0), "LATERAL_STIFFNESS": (-1, 1, 0, 0, 0),
}

_FITTYP_VERSION = {5: "5.2", 6: "5.2", 21: "5.2", 61: "6.1", 62: "6.2"}
_FORMAT_VERSION = {"PAC2002": "5.2", "MF_05": "5.2", "MF05": "5.2", "MF_52": "5.2", "MF52": "5.2",
                   "MF_61": "6.1", "MF61": "6.1", "MF_62": "6.2", "MF62": "6.2"}
_UNSUPPORTED_FORMATS = {"PAC89", "PAC94", "PAC_MC", "MF_MC", "PAC2002_MC", "PAC_TIME"}
VERSION_CODE = {"5.2": 52.0, "6.1": 61.0, "6.2": 62.0}


def _locate(tir: TirFile, key: str):
    """(section name, value) of ``key`` in any section but [UNITS], or (None, None)."""
    for name, sec in tir.sections.items():
        if name != "UNITS" and key in sec.entries:
            return name, sec.entries[key]
    return None, None


def detect_version(tir: TirFile) -> str:
    """MF version "5.2", "6.1" or "6.2" of a property file (see module docstring)."""
    section, fittyp = _locate(tir, "FITTYP")
    if section is not None:
        value = tir.number(section, "FITTYP")
        if value not in _FITTYP_VERSION:
            sec = tir.sections[section]
            raise InputError(f"unsupported FITTYP {fittyp!r}: this model reads Magic Formula 5.x "
                             "(FITTYP = 5, 6 or 21), 6.1 (61) and 6.2 (62)",
                             source=tir.source, line=sec.lines.get("FITTYP"), field="FITTYP")
        return _FITTYP_VERSION[int(value)]
    section, fmt = _locate(tir, "PROPERTY_FILE_FORMAT")
    if isinstance(fmt, str):
        word = fmt.strip().upper()
        if word in _FORMAT_VERSION:
            return _FORMAT_VERSION[word]
        if word in _UNSUPPORTED_FORMATS:
            raise InputError(f"PROPERTY_FILE_FORMAT '{fmt}' is not Magic Formula 5.2/6.1/6.2",
                             source=tir.source, field="PROPERTY_FILE_FORMAT")
    section, fver = _locate(tir, "FILE_VERSION")
    if isinstance(fver, (int, float)):
        for version in ("5.2", "6.1", "6.2"):
            if abs(float(fver) - float(version)) < 1e-9:
                return version
    raise InputError("cannot tell the Magic Formula version: no FITTYP in [MODEL] and no "
                     "PROPERTY_FILE_FORMAT such as 'PAC2002' or 'MF_61'",
                     source=tir.source, field="FITTYP")


def _default_contact_length(r0: float, cz0: float, fz0: float) -> tuple[float, float]:
    """MF 5.2 contact-length coefficients Q_A1, Q_A2 used by MFeval when a file has neither.

    Empirical fit of MFeval (Solver.calculateContactPatch) in y = log10(R0 Cz0 / Fz0).
    """
    y = math.log10(r0 * (cz0 / fz0))
    qa1 = -0.0388 * y ** 3 + 0.2509 * y ** 2 - 0.6283 * y + 0.6279
    return qa1, 1.693 * qa1 ** 2


def pack(tir: TirFile, version: str | None = None) -> tuple[np.ndarray, str]:
    """Coefficient vector (SI) and version string of a parsed property file."""
    _check_index_module()
    version = version or detect_version(tir)
    values = np.empty(N_COEFFICIENTS)
    units = tir.units
    for name, default in PARAMETERS:
        section, raw = _locate(tir, name)
        if section is None:
            if name == "FNOMIN":
                raise InputError("missing key FNOMIN (nominal wheel load) in [VERTICAL]",
                                 source=tir.source, field="FNOMIN")
            values[INDEX[name]] = default
            continue
        value = tir.number(section, name)
        if name in _EXTRA_DIMENSIONS and name not in KEY_DIMENSIONS:
            value *= units_factor(units, _EXTRA_DIMENSIONS[name], tir.source,
                                   tir.sections[section].lines.get(name))
        if not math.isfinite(value):
            raise InputError(f"{name} must be a finite number, found {raw!r}", source=tir.source,
                             line=tir.sections[section].lines.get(name), field=name)
        values[INDEX[name]] = value
    _check_physical(values, tir.source)
    r0 = values[INDEX["UNLOADED_RADIUS"]]
    cz0 = values[INDEX["VERTICAL_STIFFNESS"]]
    fz0 = values[INDEX["FNOMIN"]]
    values[INDEX["VERSION"]] = VERSION_CODE[version]
    q_fz1 = mf_q_fz1(cz0, r0, fz0, values[INDEX["Q_FZ2"]])   # rearranged load-deflection law
    values[INDEX["Q_FZ1"]] = 0.0 if q_fz1 is None else q_fz1
    qa1, qa2 = values[INDEX["Q_A1"]], values[INDEX["Q_A2"]]
    if qa1 == 0.0 and qa2 == 0.0:
        qa1, qa2 = _default_contact_length(r0, cz0, fz0)
    values[INDEX["QA1_EFF"]], values[INDEX["QA2_EFF"]] = qa1, qa2
    values[INDEX["FRICTION_ELLIPSE"]] = _friction_ellipse(tir)
    use_mode = tir.get("MODEL", "USE_MODE")
    values[INDEX["MIRRORED"]] = 1.0 if isinstance(use_mode, (int, float)) and use_mode < 0 else 0.0
    _warn_mixed_mx(values, tir.source)
    return values, version


def _friction_ellipse(tir: TirFile) -> float:
    """1.0 when ``FE_METHOD`` says 'YES' (combined slip by the friction ellipse), 0.0 for 'NO'
    or no key; anything else is refused."""
    section, raw = _locate(tir, "FE_METHOD")
    if section is None:
        return 0.0
    word = str(raw).strip().upper()  # the reader strips the quotes
    if word in ("YES", "NO"):
        return 1.0 if word == "YES" else 0.0
    raise InputError(f"FE_METHOD must be 'YES' or 'NO', found {raw!r}", source=tir.source,
                     line=tir.sections[section].lines.get("FE_METHOD"), field="FE_METHOD")


def _check_physical(values: np.ndarray, source: str) -> None:
    """Reject values the equations cannot use (division by zero, negative radius)."""
    for name in ("FNOMIN", "UNLOADED_RADIUS", "VERTICAL_STIFFNESS", "NOMPRES", "LONGVL", "LFZO"):
        if not values[INDEX[name]] > 0.0:
            raise InputError(f"{name} must be positive, found {values[INDEX[name]]:g}",
                             source=source, field=name)
    if not values[INDEX["VXLOW"]] >= 0.0:
        raise InputError("VXLOW must not be negative", source=source, field="VXLOW")


def _warn_mixed_mx(values: np.ndarray, source: str) -> None:
    """MFeval's warning when both QSX1..QSX11 and QSX12..QSX14 are non-zero."""
    new = any(values[INDEX[f"QSX{i}"]] != 0.0 for i in (12, 13, 14))
    old = any(values[INDEX[f"QSX{i}"]] != 0.0 for i in range(1, 12))
    if new and old:
        warnings.warn(f"{source}: QSX1..QSX11 and QSX12..QSX14 are both non-zero; Mx uses the "
                      "combined (TNO) form", UserWarning, stacklevel=3)


def load(path_or_tir) -> tuple[np.ndarray, str, TirFile]:
    """Read (if needed) and pack a property file: (vector, version, TirFile)."""
    tir = path_or_tir if isinstance(path_or_tir, TirFile) else read_tir(path_or_tir)
    values, version = pack(tir)
    return values, version, tir
