"""Project Chrono's JSON tyre files, read as a tyrelab tyre.

Project Chrono (``data/vehicle/*/tire/*.json``, BSD-3-Clause) keeps a tyre as
a JSON file with ``//`` and ``/* */`` comments, whose ``"Template"`` names the
Chrono tyre model. :func:`read_chrono_tyre` turns one into a :class:`Tyre`;
:func:`read_chrono_json` gives the property file (:class:`TirFile`, SI) the
tyre is built from, so ``write_tir(read_chrono_json(path), "tyre.tir")``
converts a JSON file to a ``.tir``. ``load_tyre("FILE.json")`` and
``tyrelab simulate --tyre FILE.json`` use it.

Chrono's JSON numbers are SI (N, m, s, kg) unless the key says otherwise
(the TMeasy keys carry their unit in brackets, which is SI too), so no value
is converted. A key path is written ``A > B`` below and in error messages.

What each template gives
------------------------

Every template: ``"Mass"`` [kg] -> ``[INERTIA] MASS`` (:attr:`Tyre.wheel_mass`)
and the second component of ``"Inertia"`` ``[Ixx, Iyy, Izz]`` [kg m^2], the
spin axis being y -> ``[INERTIA] IYY`` (:attr:`Tyre.wheel_spin_inertia`).
Chrono's tyre mass is the tyre alone: the rim is the wheel's, in another
Chrono file; add it if a rig needs the whole wheel.

``Pac89Tire`` (Pacejka '89: vertical data and handling)
    ``Design Parameters > Unloaded Radius`` [m] -> ``[DIMENSION] UNLOADED_RADIUS``
    (:attr:`Tyre.unloaded_radius`); ``> Width`` [m] -> ``WIDTH``
    (:attr:`Tyre.width`); ``> Vertical Stiffness`` [N/m] ->
    ``[VERTICAL] VERTICAL_STIFFNESS`` (:attr:`Tyre.vertical_stiffness`,
    optional when the curve is given); ``> Vertical Damping`` [N s/m] ->
    ``VERTICAL_DAMPING`` (:attr:`Tyre.vertical_damping`); ``> Vertical Curve
    Data`` rows of (deflection [m], load [N]) -> ``[DEFLECTION_LOAD_CURVE]``
    (:attr:`Tyre.load_deflection`; as in Chrono the curve takes precedence over
    the linear stiffness). ``Lateral Coefficients > a0 .. a13``,
    ``Longitudinal Coefficients > b0 .. b10`` and ``Aligning Coefficients > c0
    .. c17`` (ADAMS/Bakker convention: Fz in kN, angles in degrees, slip in
    percent) -> ``[LATERAL_COEFFICIENTS] A0 .. A13``,
    ``[LONGITUDINAL_COEFFICIENTS] B0 .. B10``, ``[ALIGNING_COEFFICIENTS] C0 ..
    C17`` unchanged, with ``[MODEL] PROPERTY_FILE_FORMAT = 'PAC89'``; the
    handling model ``pac89`` then runs it. ``Lateral Stiffness`` [N/m] and ``Rolling
    Resistance`` -> ``[STRUCTURAL] LATERAL_STIFFNESS`` and ``[ROLLING_COEFFICIENTS]
    QSY1`` (Chrono's PAC89 additions: :mod:`tyrelab.tyre.handling.pac89`);
    ``Coefficient of Friction`` is kept as a header comment only.
``Pac02Tire`` (Magic Formula 5.2 / PAC2002)
    ``TIR Specification File`` names a ``.tir``; it is read by
    :func:`~tyrelab.tyre.tir.read_tir` (its own ``[UNITS]``) and is the tyre.
    Chrono resolves the name against its vehicle data directory
    (``"citybus/tire/CityBus_Pac02Tire.tir"``); here it is looked for
    relative to the JSON's folder, next to the JSON (its file name alone) and
    relative to each folder above the JSON (Chrono's data-directory layout),
    first found wins; none found is an :class:`InputError` naming the key and
    the paths tried. The JSON's ``Mass``/``Inertia`` and the embedded keys
    below fill only what the ``.tir`` lacks. Without a ``.tir`` the
    coefficients are embedded: ``Dimension > Unloaded Radius, Width, Aspect
    Ratio, Rim Radius, Rim Width`` [m, -] -> ``[DIMENSION] UNLOADED_RADIUS,
    WIDTH, ASPECT_RATIO, RIM_RADIUS, RIM_WIDTH``; ``Vertical > Vertical
    Stiffness`` [N/m], ``Vertical Damping`` [N s/m], ``Nominal Wheel Load`` [N]
    -> ``[VERTICAL] VERTICAL_STIFFNESS, VERTICAL_DAMPING, FNOMIN``, ``BREFF,
    DREFF, FREFF`` unchanged, ``QFZ1, QFZ2, QFZ3, QPFZ1, QV2`` -> ``Q_FZ1,
    Q_FZ2, Q_FZ3, PFZ1, Q_V2``; ``Tire Conditions > Inflation Pressure,
    Nominal Inflation Pressure`` [Pa] -> ``[TIRE_CONDITIONS] IP, IP_NOM``;
    ``FITTYP``, ``LONGVL`` [m/s], ``VXLOW`` [m/s] -> ``[MODEL]``; the sections
    ``Scaling Factors``, ``Longitudinal / Lateral / Aligning / Overturning /
    Rolling Coefficients`` -> ``[SCALING_COEFFICIENTS]``,
    ``[LONGITUDINAL_COEFFICIENTS]`` ... with their keys (the ADAMS names)
    unchanged; ``[MODEL] PROPERTY_FILE_FORMAT = 'PAC2002'``. Chrono's ``Use
    Mode`` and ``Tire Side`` are not carried (tyrelab's Magic Formula takes
    its use mode as an option).
``PacejkaTire`` (Chrono's older Pacejka template)
    ``Pacejka Parameter File`` names a ``.tir``, read as for ``Pac02Tire``.
``MFTire`` (Magic Formula 5.2 / 6.1 / 6.2 with the property file embedded)
    Every top-level object whose name is an ADAMS section name (upper case:
    ``MODEL``, ``DIMENSION``, ``VERTICAL``, ...) is that section with its keys;
    the embedded ``UNITS`` apply as in a ``.tir``.
``FialaTire`` (vertical data and Fiala handling)
    ``Fiala Parameters > Unloaded Radius`` [m], ``Width`` [m], ``Vertical
    Stiffness`` [N/m] (optional with a curve), ``Vertical Damping`` [N s/m],
    ``Vertical Curve Data`` [m, N] -> as for ``Pac89Tire``. ``CSLIP`` [N],
    ``CALPHA`` [N/rad], ``UMIN``, ``UMAX`` -> ``[PARAMETER]`` with ``[MODEL]
    PROPERTY_FILE_FORMAT = 'FIALA'`` (ADAMS's Fiala layout; the ``fiala``
    handling model, :mod:`tyrelab.tyre.handling.fiala`): all four or none. The
    relaxation lengths and the rolling resistance are kept as header comments.
``TMeasyTire``, ``TMsimpleTire`` (vertical data and their handling)
    ``Design > Unloaded Radius [m]``, ``Width [m]``, ``Rim Radius [m]`` ->
    ``[DIMENSION] UNLOADED_RADIUS, WIDTH, RIM_RADIUS``; ``Design > Mass [kg]``,
    ``Inertia [kg.m2]`` -> ``[INERTIA]`` (these replace the top-level ``Mass``
    and ``Inertia`` of other templates). The vertical law, in Chrono's order
    of precedence:

    1. ``Parameters > Vertical > Vertical Tire Stiffness [N/m]`` or ``Tire
       Spring Curve Data`` (deflection [m], load [N]) and ``Tire Vertical
       Damping [Ns/m]``. Chrono fits ``F = d1 z + d2 z^2`` to the curve by least
       squares; here the curve itself is the ``[DEFLECTION_LOAD_CURVE]``.
    2. ``Load Index`` (0-279): Chrono's "engineer's guess" (G. Rill): the
       index's load capacity ``F`` (:data:`LOAD_INDEX_KG` times g = 9.81 m/s^2,
       as Chrono), the section height ``H = R0 - rim radius`` and the
       deflection ``0.16 H`` at that load give the linear stiffness
       ``k = F / (0.16 H)``; the damping is ``2 zeta sqrt(k m)`` with zeta = 0.5
       (Chrono's default) and m the tyre mass.
    3. ``Maximum Bearing Capacity [N]`` as ``F`` in the same guess (Chrono
       passes the rim *radius* as the rim diameter on this path, which shrinks
       its R0; here R0 stays the file's).

    ``Inflation Pressure Use [Pa]`` -> ``[OPERATING_CONDITIONS] INFLPRES``
    (:attr:`Tyre.pressure`). TMeasy's bottoming spring is carried as Chrono
    computes it: ``Parameters > Vertical > Tire Bottoming Radius [m]`` and
    ``Tire Bottoming Stiffness [N/m]``, by default (absent or 0) the rim radius
    + 10 mm and 5 times ``d1`` (the linear stiffness; for a curve, the linear
    coefficient of Chrono's least-squares ``d1 z + d2 z^2``), written as
    ``[VERTICAL] BOTTOM_OFFST`` (bottoming radius less rim radius) and
    ``BOTTOM_STIFF`` (:attr:`Tyre.bottoming`). ``TMeasyTire``'s handling parameters
    (for the ``tmeasy`` handling model, :mod:`tyrelab.tyre.handling.tmeasy`): ``Parameters >
    Vertical > Nominal Vertical Force [N]`` (and ``Maximum Vertical Force [N]``) ->
    ``[TYRE_LOAD] FZ_NOM`` (``FZ_MAX``), and each pair of ``Parameters > Longitudinal``,
    ``Lateral``, ``Aligning`` -> Chrono's TMeasy parameter-file keys ``_1``, ``_2``; a file
    given by its load index or bearing capacity gets Chrono's guess (``GuessTruck80Par``,
    ``GuessPassCar70Par``) for its ``Vehicle Type`` ("Truck" or "Passenger"; absent: no
    handling parameters). Chrono picks the pattern on the bearing-capacity path from the
    file's ``Name`` (and passes the rim radius as the rim diameter); here ``Vehicle Type``
    picks it on both paths. ``TMsimpleTire`` likewise, for the ``tmsimple`` model
    (:mod:`tyrelab.tyre.handling.tmsimple`): its ``Longitudinal`` and ``Lateral`` pairs
    (slopes, maximum and sliding forces; no slips, no trail) or ``ChTMsimpleTire``'s own guess,
    under ``PROPERTY_FILE_FORMAT = 'TMSIMPLE'`` (TMeasy's files: 'TMEASY'). Its damping is
    ``Vertical Tire Damping [Ns/m]``, as Chrono's TMsimple reader spells it.
``RigidTire`` (vertical data only)
    ``Radius`` [m] -> ``UNLOADED_RADIUS``; ``Width`` [m] -> ``WIDTH``; the
    contact material's ``Contact Material > Coefficients > Normal Stiffness``
    [N/m] and ``Normal Damping`` [N s/m] -> ``VERTICAL_STIFFNESS``,
    ``VERTICAL_DAMPING``: a rigid tyre's only compliance is Chrono's penalty
    contact, and these are its linear (Hooke) coefficients for one contact.
    Chrono uses them only when its contact system is not set to use material
    properties (Young modulus, Poisson ratio), which are not read.
``LugreTire`` (obsolete in Chrono; vertical data only)
    ``Radius`` [m] -> ``UNLOADED_RADIUS``; the span of ``Disc Locations`` [m]
    -> ``WIDTH`` (as Chrono's width); ``Normal Stiffness`` [N/m], ``Normal
    Damping`` [N s/m] -> ``VERTICAL_STIFFNESS``, ``VERTICAL_DAMPING`` (Chrono
    shares that force among the discs).

The finite-element and multibody templates (``ANCFTire``,
``ANCFToroidalTire``, ``ReissnerTire``, ``ReissnerToroidalTire``,
``FEATire``, ``MBTire``) have no vertical law to read: their stiffness comes
from their structure and inflation pressure. They raise an
:class:`InputError` saying so, as does any other template (listing the
supported ones).

Assumptions
-----------
Chrono's JSON has no contact-patch data. So that every contact model runs
the tyre, the templates read from JSON values (all but a ``.tir`` or an
embedded ``MFTire`` property file) get the same assumed ``[CONTACT_PATCH]``
and ``[CONTACT_WIDTH_CURVE]`` as the built-in HMMWV tyre
(``tyre/data/hmmwv-pac89.tir``): :data:`ASSUMED_CONTACT_PATCH` (length and
cam shape: the thesis's dimensionless XZL values, section 4.4; cams:
Schmeitz's passenger-car optimum, 5 along and 6 across) and a half contact
width of :data:`ASSUMED_HALF_WIDTH` times the section width at every
deflection (the PB1-PB3 formula needs a fit). There is no ``[SHAPE]``
table: the volume model uses a square section, as ADAMS does. The property
file's header lists these assumptions. No template gives an inflation
pressure the vertical data were measured at except where stated above, so
:attr:`Tyre.pressure` is NaN otherwise.

Errors
------
Everything wrong with a file is an :class:`InputError` naming the file, a
line where it can (the JSON decoder's line for malformed JSON; otherwise the
line of the key, or of the object that lacks it) and the key path: malformed
JSON, a missing key, a value that is not a finite number (JSON's ``NaN``,
``Infinity`` and overflowing literals included) or is out of range, a curve
that is not rows of increasing deflection, an unknown template, a missing
``.tir``.
"""

from __future__ import annotations

import re
from pathlib import Path

from ..errors import InputError
from .params import Tyre
from .chrono_templates import fiala_tir, lugre_tir, pac89_tir, rigid_tir, tmeasy_tir
from .chrono_document import (_SECTION_NAME, ASSUMED_CONTACT_PATCH, ASSUMED_HALF_WIDTH,  # noqa: F401
                              _Builder, _comment, _Document, _kind, _where)
from .tir import TirFile, TirSection, parse_tir, read_tir

#: every template :func:`read_chrono_tyre` reads
SUPPORTED_TEMPLATES = ("Pac89Tire", "Pac02Tire", "PacejkaTire", "MFTire", "FialaTire", "TMeasyTire",
                       "TMsimpleTire", "RigidTire", "LugreTire")
#: Chrono templates with no vertical law in the file (finite-element and multibody tyres)
STRUCTURAL_TEMPLATES = ("ANCFTire", "ANCFToroidalTire", "ReissnerTire", "ReissnerToroidalTire",
                        "FEATire", "MBTire")


#: Pac02Tire embedded keys: (JSON object, JSON key) -> (section, ADAMS key)
_PAC02_NAMED = {
    ("Dimension", "Unloaded Radius"): ("DIMENSION", "UNLOADED_RADIUS"),
    ("Dimension", "Width"): ("DIMENSION", "WIDTH"),
    ("Dimension", "Aspect Ratio"): ("DIMENSION", "ASPECT_RATIO"),
    ("Dimension", "Rim Radius"): ("DIMENSION", "RIM_RADIUS"),
    ("Dimension", "Rim Width"): ("DIMENSION", "RIM_WIDTH"),
    ("Vertical", "Vertical Stiffness"): ("VERTICAL", "VERTICAL_STIFFNESS"),
    ("Vertical", "Vertical Damping"): ("VERTICAL", "VERTICAL_DAMPING"),
    ("Vertical", "Nominal Wheel Load"): ("VERTICAL", "FNOMIN"),
    ("Vertical", "BREFF"): ("VERTICAL", "BREFF"),
    ("Vertical", "DREFF"): ("VERTICAL", "DREFF"),
    ("Vertical", "FREFF"): ("VERTICAL", "FREFF"),
    ("Vertical", "QFZ1"): ("VERTICAL", "Q_FZ1"),
    ("Vertical", "QFZ2"): ("VERTICAL", "Q_FZ2"),
    ("Vertical", "QFZ3"): ("VERTICAL", "Q_FZ3"),
    ("Vertical", "QPFZ1"): ("VERTICAL", "PFZ1"),
    ("Vertical", "QV2"): ("VERTICAL", "Q_V2"),
    ("Tire Conditions", "Inflation Pressure"): ("TIRE_CONDITIONS", "IP"),
    ("Tire Conditions", "Nominal Inflation Pressure"): ("TIRE_CONDITIONS", "IP_NOM"),
}
#: Pac02Tire embedded top-level keys -> [MODEL] keys
_PAC02_MODEL = {"FITTYP": "FITTYP", "LONGVL": "LONGVL", "VXLOW": "VXLOW"}
#: Pac02Tire embedded coefficient objects -> sections (keys are the ADAMS names)
_PAC02_SECTIONS = {"Scaling Factors": "SCALING_COEFFICIENTS",
                   "Longitudinal Coefficients": "LONGITUDINAL_COEFFICIENTS",
                   "Lateral Coefficients": "LATERAL_COEFFICIENTS",
                   "Aligning Coefficients": "ALIGNING_COEFFICIENTS",
                   "Overturning Coefficients": "OVERTURNING_COEFFICIENTS",
                   "Rolling Coefficients": "ROLLING_COEFFICIENTS"}

def _pac02_embedded(doc: _Document, b: _Builder, only_missing: bool) -> None:
    """Copy Pac02Tire's embedded keys into ``b.tir`` (``only_missing``: keep what is there)."""
    tir = b.tir

    def put(section, key, value, keys):
        if not (only_missing and tir.has(section, key)):
            b.put(section, key, value, keys)

    for (obj, name), (section, key) in _PAC02_NAMED.items():
        if doc.has(obj, name):
            put(section, key, doc.number(obj, name), (obj, name))
    for name, key in _PAC02_MODEL.items():
        if doc.has(name):
            put("MODEL", key, doc.number(name), (name,))
    for obj, section in _PAC02_SECTIONS.items():
        if not doc.has(obj):
            continue
        entries = doc.value(obj)
        if not isinstance(entries, dict):
            raise doc.error(f"expected an object of coefficients, found {_kind(entries)}", (obj,))
        for name in entries:
            if not _SECTION_NAME.fullmatch(name):
                raise doc.error("expected an ADAMS coefficient name (upper case, e.g. PCX1)", (obj, name))
            put(section, name, doc.number(obj, name), (obj, name))


def _fill_inertia(doc: _Document, tir: TirFile) -> None:
    """The JSON's Mass and Inertia where the property file has no wheel or tyre mass/inertia."""
    sec = tir.sections.get("INERTIA")
    if sec is None:
        sec = tir.sections["INERTIA"] = TirSection("INERTIA", 0)
    if not (tir.has("INERTIA", "WHEEL_MASS") or tir.has("INERTIA", "MASS")):
        sec.entries["MASS"] = doc.number("Mass", minimum=0.0)
    if not (tir.has("INERTIA", "WHEEL_IYY") or tir.has("INERTIA", "IYY")):
        sec.entries["IYY"] = doc.vector("Inertia", size=3)[1]


def _named_tir(doc: _Document, key: str) -> Path:
    """The .tir a JSON names under ``key``, found as the module docstring says."""
    name = doc.string(key)
    given = Path(name)
    folder = doc.path.parent
    if given.is_absolute():
        tried = [given]
    else:
        tried = [folder / given, folder / given.name] + [up / given for up in folder.resolve().parents]
    seen = []
    for candidate in tried:
        if candidate not in seen:
            seen.append(candidate)
        if candidate.is_file():
            return candidate
    shown = ", ".join(str(p) for p in seen[:3]) + (" and the folders above" if len(seen) > 3 else "")
    raise doc.error(f"the property file '{name}' was not found (looked for {shown})", (key,))


def _property_file(doc: _Document, template: str, key: str) -> TirFile:
    if template == "Pac02Tire" and not doc.has(key):  # coefficients embedded in the JSON
        doc.value("Dimension")
        doc.value("Vertical")
        b = _Builder(doc, template)
        b.put("MODEL", "PROPERTY_FILE_FORMAT", "PAC2002")
        _pac02_embedded(doc, b, only_missing=False)
        for obj, name in (("Dimension", "Unloaded Radius"), ("Dimension", "Width"),
                          ("Vertical", "Vertical Stiffness")):
            doc.number(obj, name, positive=True)
        doc.number("Vertical", "Vertical Damping", minimum=0.0)
        b.mass_and_inertia()
        b.assumed_contact_patch(b.tir.number("DIMENSION", "WIDTH"))
        return b.tir
    doc.number("Mass", minimum=0.0)  # Chrono requires both, whatever the .tir holds
    doc.vector("Inertia", size=3)
    path = _named_tir(doc, key)
    tir = read_tir(path)
    tir.header = [f"$ read through Project Chrono {template} file {doc.source} (key '{key}')", *tir.header]
    if template == "Pac02Tire":
        _pac02_embedded(doc, _Builder(doc, template, tir=tir), only_missing=True)
    _fill_inertia(doc, tir)
    return tir


def _render(value) -> str:
    if isinstance(value, str):
        quote = "'" if "'" not in value else '"'
        return f"{quote}{value}{quote}"
    return repr(value) if isinstance(value, float) else str(int(value))


def _mf_embedded(doc: _Document) -> TirFile:
    """MFTire: the property file's sections as top-level JSON objects."""
    lines = [f"$ Project Chrono MFTire read from {doc.path.name} by tyrelab.tyre.chrono_json"]
    where = {}
    for name, entries in doc.data.items():
        if not _SECTION_NAME.fullmatch(name):
            continue
        if not isinstance(entries, dict):
            raise doc.error(f"expected an object of '{name}' keys, found {_kind(entries)}", (name,))
        lines.append(f"[{name}]")
        for key, value in entries.items():
            if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", key):
                raise doc.error("expected a property-file key (letters, digits, _)", (name, key))
            if not isinstance(value, str):
                doc.number(name, key)  # finite numbers only
            elif "'" in value and '"' in value:
                raise doc.error("a string may not hold both kinds of quote", (name, key))
            lines.append(f"{key} = {_render(value)}")
            where[(name.upper(), key.upper())] = (name, key)
    if len(lines) == 1:
        raise InputError("no property-file sections (upper-case objects such as \"MODEL\", "
                         "\"DIMENSION\", \"VERTICAL\")", source=doc.source, field="MFTire")
    try:
        tir = parse_tir("\n".join(lines) + "\n", source=doc.source)
    except InputError as exc:  # its line is the rendered text's: name the JSON's instead
        keys = next((v for k, v in where.items() if k[1] == exc.field), ())
        raise InputError(exc.reason, source=doc.source, line=doc.line(keys) if keys else None,
                         field=_where(keys) or exc.field) from None
    for sec in tir.sections.values():
        sec.line = doc.line((sec.name,)) or 0
        sec.lines = {key: doc.line(where[(sec.name, key)]) for key in sec.entries
                     if (sec.name, key) in where}
    _fill_inertia(doc, tir)
    return tir


# --- front door -----------------------------------------------------------------

def read_chrono_json(path) -> TirFile:
    """The property file (:class:`TirFile`, SI) of a Project Chrono JSON tyre file.

    See the module docstring for the keys each template gives and what is
    assumed. Raises :class:`InputError` naming the file, line and key.
    """
    doc = _Document(Path(path))
    if doc.has("Type") and doc.value("Type") != "Tire":
        raise doc.error(f"expected a Chrono tyre file (\"Type\": \"Tire\"), found {_kind(doc.value('Type'))}",
                        ("Type",))
    template = doc.string("Template")
    if template == "Pac89Tire":
        return pac89_tir(doc)
    if template == "FialaTire":
        return fiala_tir(doc)
    if template in ("TMeasyTire", "TMsimpleTire"):
        return tmeasy_tir(doc, template)
    if template == "RigidTire":
        return rigid_tir(doc)
    if template == "LugreTire":
        return lugre_tir(doc)
    if template == "Pac02Tire":
        return _property_file(doc, template, "TIR Specification File")
    if template == "PacejkaTire":
        return _property_file(doc, template, "Pacejka Parameter File")
    if template == "MFTire":
        return _mf_embedded(doc)
    supported = ", ".join(SUPPORTED_TEMPLATES)
    if template in STRUCTURAL_TEMPLATES:
        raise doc.error(f"'{template}' is a finite-element or multibody tyre: its vertical stiffness comes "
                        f"from its structure and inflation pressure, not from a number in the file, so "
                        f"tyrelab cannot run it; supported templates: {supported}", ("Template",))
    raise doc.error(f"unknown template '{template}'; supported templates: {supported}", ("Template",))


def read_chrono_tyre(path, name: str | None = None) -> Tyre:
    """A :class:`Tyre` from a Project Chrono JSON tyre file (named after the file by default).

    Parameters
    ----------
    path : str or Path
        The ``.json`` file (``//`` and ``/* */`` comments allowed, as Chrono).
    name : str, optional
        The tyre's name; default the file's stem.

    Raises
    ------
    InputError
        Malformed JSON (with its line), a missing key, a value that is not a
        finite number in range, an unknown template, a missing ``.tir``.

    Examples
    --------
    >>> tyre = read_chrono_tyre("HMMWV_Pac89Tire.json")  # doctest: +SKIP
    >>> tyre.unloaded_radius, tyre.vertical_law.static_load(0.05)  # doctest: +SKIP
    (0.464, 19670.0)
    """
    path = Path(path)
    return Tyre.from_tir(read_chrono_json(path), name=name or path.stem)
