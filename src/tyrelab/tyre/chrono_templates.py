"""Project Chrono tyre templates whose vertical law is written out as keys in the JSON.

``Pac89Tire`` (with its handling coefficients), ``FialaTire``, ``TMeasyTire`` and
``TMsimpleTire`` (TMeasy's load-index estimate as Chrono's), ``RigidTire`` and
``LugreTire``: each function turns a parsed JSON document
(:class:`~.chrono_document._Document`) into the property file tyrelab builds the
tyre from. The keys each reads and what it assumes are listed in
:mod:`tyrelab.tyre.chrono_json`'s module docstring, which also reads the templates
that name or embed an ADAMS property file (Pac02Tire, PacejkaTire, MFTire).
"""

from __future__ import annotations

import math
from importlib import resources

from ..errors import InputError
from .chrono_document import _Builder, _comment, _Document, _kind
from .handling.tmeasy import DEFAULT_MAX_LOAD_RATIO, KEY_SECTIONS, LOAD_SECTION, ROLLING_SECTION
from .tir import TirFile
from .tir_units import KEY_DIMENSIONS


#: Chrono's TMeasy "engineer's guess": deflection at the load capacity per section height,
#: damping ratio, and the g that turns a load index's mass into a force [m/s^2]
GUESS_DEFLECTION_RATIO = 0.16
GUESS_DAMPING_RATIO = 0.5
GUESS_GRAVITY = 9.81
#: Chrono's TMeasy/TMsimple bottoming when the file sets none (``Initialize``): it starts at the
#: rim radius plus this carcass thickness [m], with this many times the linear stiffness d1
BOTTOM_CARCASS = 0.01
BOTTOM_STIFFNESS_FACTOR = 5.0


def _load_index_table() -> tuple[float, ...]:
    """Load capacity [kg] per load index, from ``data/load_index_kg.csv`` (Chrono's table)."""
    text = resources.files("tyrelab.tyre").joinpath("data", "load_index_kg.csv").read_text()
    rows = [line.split(",") for line in text.splitlines() if line and not line.startswith(("#", "load"))]
    assert [int(r[0]) for r in rows] == list(range(len(rows)))
    return tuple(float(r[1]) for r in rows)


#: load capacity [kg] of each load index (index = position)
LOAD_INDEX_KG = _load_index_table()

_PAC89_SETS = (("Lateral Coefficients", "a", 14, "LATERAL_COEFFICIENTS", "A"),
               ("Longitudinal Coefficients", "b", 11, "LONGITUDINAL_COEFFICIENTS", "B"),
               ("Aligning Coefficients", "c", 18, "ALIGNING_COEFFICIENTS", "C"))

def pac89_tir(doc: _Document) -> TirFile:
    dp = ("Design Parameters",)
    header = [*_comment(doc, "source's coefficient of friction", "Coefficient of Friction"),
              "$ Coefficients in the ADAMS/Bakker convention (Fz in kN, slip angle and camber in",
              "$ degrees, longitudinal slip in percent)."]
    b = _Builder(doc, "Pac89Tire", header)
    b.put("MODEL", "PROPERTY_FILE_FORMAT", "PAC89")
    b.put("MODEL", "TYRESIDE", "LEFT")
    _, width = b.dimensions(dp + ("Unloaded Radius",), width_keys=dp + ("Width",))
    b.mass_and_inertia()
    b.vertical(dp + ("Vertical Stiffness",), dp + ("Vertical Damping",), dp + ("Vertical Curve Data",))
    b.assumed_contact_patch(width)
    for obj, letter, count, section, adams in _PAC89_SETS:
        b.section(section, (obj,))
        for i in range(count):
            keys = (obj, f"{letter}{i}")
            b.put(section, f"{adams}{i}", doc.number(*keys), keys)
    # Chrono's PAC89 additions (tyre/handling/pac89.py): rolling resistance, carcass stiffness
    if doc.has(*dp, "Rolling Resistance"):
        keys = dp + ("Rolling Resistance",)
        b.put(ROLLING_SECTION, "QSY1", doc.number(*keys, minimum=0.0), keys)
    if doc.has(*dp, "Lateral Stiffness"):
        keys = dp + ("Lateral Stiffness",)
        b.put("STRUCTURAL", "LATERAL_STIFFNESS", doc.number(*keys, positive=True), keys)
    return b.tir


#: the Fiala handling parameters of Chrono's JSON, written to the ADAMS Fiala layout's [PARAMETER]
FIALA_HANDLING = ("CSLIP", "CALPHA", "UMIN", "UMAX")
#: its relaxation lengths and rolling resistance (the load centre's shift [m]), the ADAMS Fiala
#: layout's keys
FIALA_LENGTHS = {"X Relaxation Length": "RELAX_LENGTH_X", "Y Relaxation Length": "RELAX_LENGTH_Y",
                 "Rolling Resistance": "ROLLING_RESISTANCE"}


def fiala_tir(doc: _Document) -> TirFile:
    fp = ("Fiala Parameters",)
    b = _Builder(doc, "FialaTire")
    _, width = b.dimensions(fp + ("Unloaded Radius",), width_keys=fp + ("Width",))
    b.mass_and_inertia()
    b.vertical(fp + ("Vertical Stiffness",), fp + ("Vertical Damping",), fp + ("Vertical Curve Data",))
    if any(doc.has(*fp, key) for key in FIALA_HANDLING):  # the fiala handling model's
        b.put("MODEL", "PROPERTY_FILE_FORMAT", "FIALA")
        for key in FIALA_HANDLING:
            b.put("PARAMETER", key, doc.number(*fp, key, positive=True), fp + (key,))
        for key, adams in FIALA_LENGTHS.items():  # the transient slip's (if asked for), My's
            if doc.has(*fp, key):
                b.put("PARAMETER", adams, doc.number(*fp, key, minimum=0.0), fp + (key,))
    b.assumed_contact_patch(width)
    return b.tir


#: the vertical damping's key in each template's ``Parameters > Vertical`` (Chrono's readers
#: spell them differently)
DAMPING_KEY = {"TMeasyTire": "Tire Vertical Damping [Ns/m]", "TMsimpleTire": "Vertical Tire Damping [Ns/m]"}
#: the keys each template's handling model has (TMsimple: no slips and no trail), and the
#: property-file format its parameters are written under
HANDLING_KEYS = {"TMeasyTire": ("DFX0", "FXMAX", "SXMAX", "FXSLD", "SXSLD", "DFY0", "FYMAX", "SYMAX",
                                "FYSLD", "SYSLD", "PT_NORM", "SY_CHSI", "SY_ZERO"),
                 "TMsimpleTire": ("DFX0", "FXMAX", "FXSLD", "DFY0", "FYMAX", "FYSLD")}
HANDLING_FORMAT = {"TMeasyTire": "TMEASY", "TMsimpleTire": "TMSIMPLE"}


def tmeasy_tir(doc: _Document, template: str) -> TirFile:
    design = ("Design",)
    b = _Builder(doc, template)
    r0, width = b.dimensions(design + ("Unloaded Radius [m]",), width_keys=design + ("Width [m]",),
                             rim_keys=design + ("Rim Radius [m]",))
    rim = b.tir.sections["DIMENSION"].entries["RIM_RADIUS"]
    b.mass_and_inertia(design + ("Mass [kg]",), design + ("Inertia [kg.m2]",))
    mass = b.tir.sections["INERTIA"].entries["MASS"]
    vert = ("Parameters", "Vertical")
    if doc.has("Parameters"):
        stiffness, curve = vert + ("Vertical Tire Stiffness [N/m]",), vert + ("Tire Spring Curve Data",)
        if not doc.has(*stiffness) and not doc.has(*curve):
            doc.value(*vert)  # names a missing 'Vertical'
            raise doc.error("missing key 'Vertical Tire Stiffness [N/m]' (or 'Tire Spring Curve Data')",
                            vert)
        if doc.has(*stiffness):
            d1 = doc.number(*stiffness, positive=True)
            b.put("VERTICAL", "VERTICAL_STIFFNESS", d1, stiffness)
            b.put("VERTICAL", "VERTICAL_DAMPING",
                  doc.number(*vert, DAMPING_KEY[template], minimum=0.0), vert + (DAMPING_KEY[template],))
        else:
            b.vertical(stiffness, vert + (DAMPING_KEY[template],), curve)
            d1 = _linear_coefficient(b.tir.table("DEFLECTION_LOAD_CURVE"))
    else:
        if doc.has("Load Index"):
            keys = ("Load Index",)
            li = doc.number(*keys, minimum=0.0)
            if li != int(li) or li >= len(LOAD_INDEX_KG):
                raise doc.error(f"expected a whole load index 0-{len(LOAD_INDEX_KG) - 1}, found {li:g}", keys)
            load = LOAD_INDEX_KG[int(li)] * GUESS_GRAVITY
            what = f"load index {int(li)} ({LOAD_INDEX_KG[int(li)]:g} kg)"
        elif doc.has("Maximum Bearing Capacity [N]"):
            keys = ("Maximum Bearing Capacity [N]",)
            load = doc.number(*keys, positive=True)
            what = f"bearing capacity {load:g} N"
        else:
            raise InputError("no vertical data: expected 'Parameters' > 'Vertical', a 'Load Index' or a "
                             "'Maximum Bearing Capacity [N]'", source=doc.source, field="Parameters")
        k = load / (GUESS_DEFLECTION_RATIO * (r0 - rim))
        c = 2.0 * GUESS_DAMPING_RATIO * math.sqrt(k * mass)
        b.put("VERTICAL", "VERTICAL_STIFFNESS", k, keys)
        b.put("VERTICAL", "VERTICAL_DAMPING", c, keys)
        d1 = k
        b.tir.header += [
            f"$ Vertical law GUESSED as Chrono does from the {what}: stiffness = load /",
            f"$ ({GUESS_DEFLECTION_RATIO:g} x (unloaded radius - rim radius)), damping = 2 x "
            f"{GUESS_DAMPING_RATIO:g} x sqrt(stiffness x tyre mass)."]
    _tmeasy_bottoming(doc, b, r0, rim, d1)
    if doc.has("Parameters"):
        _tmeasy_handling_given(doc, b, template)
    else:
        _tmeasy_handling_guess(doc, b, load, keys, template)
    if doc.has("Rolling Resistance Coefficient"):  # My = -c Fz R0 tanh(omega), as Chrono
        keys = ("Rolling Resistance Coefficient",)
        b.put(ROLLING_SECTION, "QSY1", doc.number(*keys, minimum=0.0), keys)
    if doc.has("Inflation Pressure Use [Pa]"):
        keys = ("Inflation Pressure Use [Pa]",)
        b.put("OPERATING_CONDITIONS", "INFLPRES", doc.number(*keys, positive=True), keys)
    b.assumed_contact_patch(width)
    return b.tir


#: TMeasy's keys (stems: the section is :data:`~.handling.tmeasy.KEY_SECTIONS`'s) with the JSON
#: object and key that state each as a pair (at the nominal load and at twice it)
_TMEASY_KEYS = (
    ("DFX0", "Longitudinal", "Initial Slopes dFx/dsx [N]"),
    ("FXMAX", "Longitudinal", "Maximum Fx Load [N]"),
    ("SXMAX", "Longitudinal", "Slip sx at Maximum Fx"),
    ("FXSLD", "Longitudinal", "Sliding Fx Load [N]"),
    ("SXSLD", "Longitudinal", "Slip sx where sliding begins"),
    ("DFY0", "Lateral", "Initial Slopes dFy/dsy [N]"),
    ("FYMAX", "Lateral", "Maximum Fy Load [N]"),
    ("SYMAX", "Lateral", "Slip sy at Maximum Fy"),
    ("FYSLD", "Lateral", "Sliding Fy Load [N]"),
    ("SYSLD", "Lateral", "Slip sy where sliding begins"),
    ("PT_NORM", "Aligning", "Normalized Trail at Zero Slip sy"),
    ("SY_CHSI", "Aligning", "Slip sy where Trail Changes Sign"),
    ("SY_ZERO", "Aligning", "Slip sy where Trail Tends to Zero"),
)
#: Chrono's ``Vehicle Type`` words and the guess pattern each picks
TMEASY_PATTERNS = {"Truck": "truck", "Passenger": "passenger"}


def _tmeasy_guess_table() -> dict[str, dict[str, tuple[float, float]]]:
    """``{pattern: {key: (at FZ_NOM, at 2 FZ_NOM)}}`` from ``data/tmeasy_guess.csv``."""
    text = resources.files("tyrelab.tyre").joinpath("data", "tmeasy_guess.csv").read_text()
    table: dict[str, dict[str, tuple[float, float]]] = {}
    for line in text.splitlines():
        if line and not line.startswith(("#", "pattern")):
            pattern, key, one, two = line.split(",")
            table.setdefault(pattern, {})[key] = (float(one), float(two))
    return table


def _tmeasy_handling_given(doc: _Document, b: _Builder, template: str) -> None:
    """The template's handling parameters as the JSON's ``Parameters`` state them (each a
    pair: at the nominal load and at twice it); none when it gives only ``Vertical``."""
    par = ("Parameters",)
    if not any(doc.has(*par, name) for name in ("Longitudinal", "Lateral", "Aligning")):
        b.tir.header.append("$ No handling parameters (only 'Parameters' > 'Vertical').")
        return
    vert = par + ("Vertical",)
    nominal = vert + ("Nominal Vertical Force [N]",)
    b.put("MODEL", "PROPERTY_FILE_FORMAT", HANDLING_FORMAT[template])
    b.put(LOAD_SECTION, "FZ_NOM", doc.number(*nominal, positive=True), nominal)
    if doc.has(*vert, "Maximum Vertical Force [N]"):
        keys = vert + ("Maximum Vertical Force [N]",)
        b.put(LOAD_SECTION, "FZ_MAX", doc.number(*keys, positive=True), keys)
    for key, obj, name in _TMEASY_KEYS:
        if key in HANDLING_KEYS[template]:
            keys = par + (obj, name)
            pair = doc.vector(*keys, size=2)
            b.put(KEY_SECTIONS[key], f"{key}_1", pair[0], keys)
            b.put(KEY_SECTIONS[key], f"{key}_2", pair[1], keys)


def _tmeasy_handling_guess(doc: _Document, b: _Builder, capacity: float, capacity_keys,
                           template: str) -> None:
    """The template's handling parameters guessed from the load capacity as Chrono does
    (``GuessTruck80Par``, ``GuessPassCar70Par`` of ``ChTMeasyTire`` or ``ChTMsimpleTire``;
    ``data/tmeasy_guess.csv``): the nominal load half the capacity, times ``(Inflation Pressure
    Use / Inflation Pressure Design)^0.8`` when the file gives both, the pattern from ``Vehicle
    Type``. Without a ``Vehicle Type`` no handling parameters (Chrono would stop)."""
    keys = ("Vehicle Type",)
    if not doc.has(*keys):
        b.tir.header.append("$ No handling parameters: the file gives no 'Vehicle Type' "
                            "('Truck' or 'Passenger') to guess them by.")
        return
    kind = doc.string(*keys)
    if kind not in TMEASY_PATTERNS:
        raise doc.error(f"expected 'Truck' or 'Passenger', found '{kind}'", keys)
    ratio = 1.0
    design, use = ("Inflation Pressure Design [Pa]",), ("Inflation Pressure Use [Pa]",)
    if doc.has(*design) and doc.has(*use):
        ratio = doc.number(*use, positive=True) / doc.number(*design, positive=True)
    nominal = 0.5 * capacity * ratio ** 0.8
    b.put("MODEL", "PROPERTY_FILE_FORMAT", HANDLING_FORMAT[template])
    b.put(LOAD_SECTION, "FZ_NOM", nominal, capacity_keys)
    b.put(LOAD_SECTION, "FZ_MAX", DEFAULT_MAX_LOAD_RATIO * nominal, capacity_keys)
    pattern = TMEASY_PATTERNS[kind] if template == "TMeasyTire" else f"tmsimple-{TMEASY_PATTERNS[kind]}"
    table = _tmeasy_guess_table()[pattern]
    for key in HANDLING_KEYS[template]:
        one, two = table[key]
        if f"{key}_1" in KEY_DIMENSIONS:  # forces and slopes [N] scale with the load; slips not
            one, two = one * nominal, two * 2.0 * nominal
        b.put(KEY_SECTIONS[key], f"{key}_1", one, keys)
        b.put(KEY_SECTIONS[key], f"{key}_2", two, keys)
    b.tir.header.append(
        f"$ {template[:-4]} handling GUESSED as Chrono does ({kind.lower()} pattern): FZ_NOM = half the "
        f"load capacity{' x pressure ratio^0.8' if ratio != 1.0 else ''} = {nominal:.6g} N.")


def _linear_coefficient(curve) -> float:
    """``d1`` of Chrono's least-squares ``F = d1 z + d2 z^2`` through a spring curve's rows."""
    import numpy as np

    z, f = curve[:, 0], curve[:, 1]
    (d1, _), *_ = np.linalg.lstsq(np.column_stack([z, z * z]), f, rcond=None)
    return float(d1)


def _tmeasy_bottoming(doc: _Document, b: _Builder, r0: float, rim: float, d1: float) -> None:
    """TMeasy's bottoming spring, as Chrono's ``GetNormalStiffnessForce``: ``Tire Bottoming
    Stiffness [N/m]`` times the deflection past ``R0 - Tire Bottoming Radius [m]`` (either
    absent or 0: the rim radius + 10 mm and 5 d1, Chrono's ``Initialize``), written as MF 6.x's
    ``BOTTOM_OFFST`` (bottoming radius less rim radius) and ``BOTTOM_STIFF``."""
    vert = ("Parameters", "Vertical")
    radius_keys = vert + ("Tire Bottoming Radius [m]",)
    stiff_keys = vert + ("Tire Bottoming Stiffness [N/m]",)
    radius = doc.number(*radius_keys, minimum=0.0) if doc.has(*radius_keys) else 0.0
    stiff = doc.number(*stiff_keys, minimum=0.0) if doc.has(*stiff_keys) else 0.0
    if radius and not rim <= radius < r0:
        raise doc.error(f"the bottoming radius {radius:g} m must lie between the rim radius {rim:g} m "
                        f"and the unloaded radius {r0:g} m", radius_keys)
    radius = radius or rim + BOTTOM_CARCASS
    stiff = stiff or BOTTOM_STIFFNESS_FACTOR * d1
    b.put("VERTICAL", "BOTTOM_OFFST", radius - rim, radius_keys if doc.has(*radius_keys) else ())
    b.put("VERTICAL", "BOTTOM_STIFF", stiff, stiff_keys if doc.has(*stiff_keys) else ())
    b.tir.header.append(f"$ Bottoming as Chrono's TMeasy: {stiff:.6g} N/m from the radius {radius:.6g} m "
                        "(BOTTOM_OFFST, BOTTOM_STIFF).")


def rigid_tir(doc: _Document) -> TirFile:
    coeffs = ("Contact Material", "Coefficients")
    b = _Builder(doc, "RigidTire", [
        "$ Vertical law: the Hooke coefficients of Chrono's penalty contact (Contact Material >",
        "$ Coefficients > Normal Stiffness, Normal Damping) for one contact."])
    _, width = b.dimensions(("Radius",), width_keys=("Width",))
    b.mass_and_inertia()
    b.vertical(coeffs + ("Normal Stiffness",), coeffs + ("Normal Damping",))
    b.assumed_contact_patch(width)
    return b.tir


def lugre_tir(doc: _Document) -> TirFile:
    keys = ("Disc Locations",)
    discs = doc.value(*keys)
    if not isinstance(discs, list) or len(discs) < 2:
        raise doc.error(f"expected a list of at least two disc positions, found {_kind(discs)}", keys)
    ys = [doc.check_number(v, keys) for v in discs]
    width = abs(ys[0] - ys[-1])
    if not width > 0:
        raise doc.error("the first and last discs are at the same place: the tyre has no width", keys)
    b = _Builder(doc, "LugreTire", ["$ Width: the span of the Lugre discs (as Chrono)."])
    b.dimensions(("Radius",), width=width)
    b.tir.sections["DIMENSION"].lines["WIDTH"] = doc.line(keys)
    b.mass_and_inertia()
    b.vertical(("Normal Stiffness",), ("Normal Damping",))
    b.assumed_contact_patch(width)
    return b.tir
