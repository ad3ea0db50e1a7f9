"""A test campaign: a folder of test files and a short manifest, ``campaign.toml``.

The manifest names the tyre and lists the tests, each with its kind, its file
(relative to the manifest) and what the file alone cannot say::

    [campaign]
    name = "Michelin XZL 16.00R20, 300 kPa"

    [tyre]                              # numbers SI, or a string "value unit"
    unloaded_radius = "671.5 mm"
    width = "438 mm"
    pressure = "300 kPa"
    wheel_mass = 240                    # also: rim_radius, mass, wheel_iyy, iyy, fnomin;
    # base = "base.tir"                 # a property file whose other sections are kept

    [[test]]
    kind = "load_deflection"            # see tyrelab.fit.lab_files for every kind
    file = "load_deflection.csv"
    columns = { deflection = "deflection_mm", load = "load_N_300kPa" }
    units = { deflection = "mm" }       # per column; else the header's unit, else SI
    step = "10 mm"                      # table step a raw loop is averaged onto
    use = "fit"                         # or "held_out": predicted, never fitted
    note = "thesis Table 3-2"

Keys of each kind: ``columns``, ``units``, ``use``, ``note`` for all files;
``step``, ``pressure`` (load_deflection: the tyre's by default; presses at
other pressures are for the ring only); ``load_case``, ``inertia``, ``lever``, ``wheels``,
``lowpass``, ``positive``, ``trailer`` (drop_test); ``load`` or
``deflection``, ``calibration`` (default "100 mm"), ``travel``
("vertical"/"horizontal": the image axis along the wheel's travel)
(footprint_image); ``cleat`` ("WxH" in mm), ``direction`` (static_cleat);
``cleat``, ``angle``, ``speed``, ``load_case`` (dynamic_cleat).

Every mistake -- TOML syntax, an unknown key or kind, a missing file, a value
of the wrong kind -- is one :class:`~tyrelab.errors.InputError` naming the
manifest, its line and the key; a mistake inside a test file names that
file and line.
"""

from __future__ import annotations

import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import InputError
from ..measure.units import is_known_unit, si_unit, to_si
from . import lab_files as lf
from .lab_columns import QUANTITIES

MANIFEST = "campaign.toml"
#: kind -> reader and the manifest keys it takes beyond file/kind/use/note
KINDS = {
    "load_deflection": ("columns", "units", "step", "pressure"),
    "drop_test": ("columns", "units", "load_case", "inertia", "lever", "wheels", "lowpass", "positive",
                  "trailer"),
    "contact_patch": ("columns", "units"),
    "footprint_image": ("load", "deflection", "calibration", "travel"),
    "carcass_profile": ("columns", "units"),
    "modal": (),
    "static_cleat": ("columns", "units", "cleat", "direction"),
    "dynamic_cleat": ("cleat", "angle", "speed", "load_case"),
}
#: [tyre] keys -> SI unit
TYRE_KEYS = {"name": None, "base": None, "unloaded_radius": "m", "width": "m", "rim_radius": "m",
             "pressure": "Pa", "mass": "kg", "wheel_mass": "kg", "wheel_iyy": "kg m^2", "iyy": "kg m^2",
             "fnomin": "N"}
#: SI unit of each scalar test key
TEST_UNITS = {"step": "m", "pressure": "Pa", "inertia": "kg m^2", "lever": "m", "lowpass": "Hz", "load": "N",
              "deflection": "m", "calibration": "m", "angle": "rad", "speed": "m/s"}
#: units no unit word converts to: the value is a plain number in them
PLAIN = ("kg m^2", "Hz")
#: how a quantity of each unit may be written, for the messages
UNIT_EXAMPLES = {"m": "10 mm", "Pa": "300 kPa", "N": "40 kN", "kg": "154 kg", "rad": "45 deg",
                 "m/s": "12 km/h"}
TRAILER_KEYS = ("hitch_to_axle", "track", "frame_cg_behind_hitch", "frame_cg_height", "ballast_height")


@dataclass
class Campaign:
    """A parsed campaign: the tyre's known values (SI) and the test records."""

    source: str
    name: str
    tyre: dict = field(default_factory=dict)
    base: Path | None = None
    tests: list = field(default_factory=list)

    def of(self, *types) -> list:
        """The tests of these record types (:mod:`tyrelab.fit.lab_files`)."""
        return [t for t in self.tests if isinstance(t, types)]

    @property
    def folder(self) -> Path:
        return Path(self.source).parent


class _Manifest:
    """Checks of one manifest, each failure naming its line and key path."""

    def __init__(self, path: Path, text: str):
        self.path, self.text, self._locator = path, text, None

    def fail(self, keys, message):
        from ..core.toml_lines import TomlLocator
        line = None
        try:
            self._locator = self._locator or TomlLocator(self.text)
            line = self._locator.line(keys)
        except (ValueError, IndexError):
            pass
        name = ".".join(f"[{k + 1}]" if isinstance(k, int) else str(k) for k in keys).replace(".[", "[")
        raise InputError(message, source=str(self.path), line=line, field=name or None)

    def quantity(self, value, keys, unit):
        """A number in SI, or a string ``"value unit"`` converted to ``unit``."""
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            self.fail(keys, f"expected a number (SI) or a string like \"10 mm\", got {json.dumps(value)}")
        if isinstance(value, str) and unit in PLAIN:
            self.fail(keys, f"expected a plain number in {unit}, got {json.dumps(value)}")
        if isinstance(value, str):
            m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(.*?)\s*", value)
            try:
                number = float(m.group(1)) if m else math.nan
            except ValueError:
                number = math.nan
            word = m.group(2) if m else ""
            if not math.isfinite(number) or not is_known_unit(word) or si_unit(word) != unit:
                self.fail(keys, f"expected a number and a unit of {unit}, like "
                                f"\"{UNIT_EXAMPLES.get(unit, '1 ' + unit)}\", got {json.dumps(value)}")
            value = float(to_si(number, word))
        if not math.isfinite(float(value)):
            self.fail(keys, f"expected a finite number, got {value!r}")
        return float(value)

    def positive(self, value, keys, unit):
        v = self.quantity(value, keys, unit)
        if not v > 0:
            self.fail(keys, f"expected a positive value, got {value!r}")
        return v

    def string_map(self, value, keys):
        if not isinstance(value, dict) or not all(isinstance(v, str) for v in value.values()):
            self.fail(keys, "expected an inline table of strings, like { deflection = \"defl_mm\" }")
        for q in value:
            if q not in QUANTITIES:
                self.fail(keys + (q,), f"unknown quantity '{q}'; expected one of "
                                       f"{', '.join(QUANTITIES)}")
        return dict(value)


def _cleat(m: _Manifest, value, keys):
    match = re.fullmatch(r"\s*(\d+(?:\.\d*)?)\s*x\s*(\d+(?:\.\d*)?)\s*", str(value))
    if not isinstance(value, str) or not match or not float(match.group(1)) > 0 or \
            not float(match.group(2)) > 0:
        m.fail(keys, f"expected a cleat \"WIDTHxHEIGHT\" in mm, like \"51x51\", got {json.dumps(value)}")
    return float(match.group(1)) / 1e3, float(match.group(2)) / 1e3


def _load_case(m: _Manifest, value, keys):
    if isinstance(value, str) and re.fullmatch(r"LC[1-3]", value.strip().upper()):
        return value.strip().upper()
    if isinstance(value, str) and value.strip().upper().startswith("LC"):
        m.fail(keys, f"unknown load case {json.dumps(value)}; expected LC1, LC2, LC3 (thesis "
                     "Table 3-4) or a wheel load, like \"40 kN\"")
    return m.positive(value, keys, "N")


def _pressure(m: _Manifest, value, keys) -> float:
    """An inflation pressure within :data:`tyrelab.limits.MIN_PRESSURE` ..
    :data:`~tyrelab.limits.MAX_PRESSURE`."""
    from ..limits import check_pressure
    v = m.positive(value, keys, "Pa")
    try:
        return check_pressure(v)
    except InputError as exc:
        m.fail(keys, exc.reason)


def _tyre_physics(m: _Manifest, tyre: dict) -> None:
    """The ``[tyre]`` values checked as a property file's would be
    (:func:`tyrelab.tyre.tir_physics.check_physics`: sizes, the rim inside the tyre, masses and
    inertias), each failure at its manifest key."""
    from ..tyre.tir_physics import check_physics
    from ..tyre.tir import TirFile
    from .property_file import TYRE_KEYS as TIR_KEYS
    tir, key_of = TirFile(source=str(m.path)), {}
    for key, (section, name) in TIR_KEYS.items():
        if key in tyre:
            tir.set(section, name, float(tyre[key]))
            key_of[name] = key
    try:
        check_physics(tir)
    except InputError as exc:
        m.fail(("tyre", key_of.get(exc.field, exc.field)), exc.reason)


def _test(m: _Manifest, entry, i, folder: Path):
    keys = ("test", i)
    if not isinstance(entry, dict):
        m.fail(keys, "expected a [[test]] table")
    kind = entry.get("kind")
    if kind not in KINDS:
        m.fail(keys + ("kind",), f"unknown test kind {json.dumps(kind)}; expected one of "
                                 f"{', '.join(KINDS)}")
    allowed = ("kind", "file", "use", "note") + KINDS[kind]
    for k in entry:
        if k not in allowed:
            m.fail(keys + (k,), f"unknown key '{k}' for a {kind} test; allowed: {', '.join(allowed)}")
    if not isinstance(entry.get("file"), str) or not entry["file"].strip():
        m.fail(keys + ("file",), "every test needs file = \"NAME\" (relative to the manifest)")
    path = Path(entry["file"]).expanduser()
    path = path if path.is_absolute() else folder / path
    if not path.is_file():
        m.fail(keys + ("file",), f"no such file: {path}")
    use = entry.get("use", "held_out" if kind in ("static_cleat", "dynamic_cleat") else "fit")
    if use not in lf.USES:
        m.fail(keys + ("use",), f"use must be one of {', '.join(lf.USES)}, got {json.dumps(use)}")
    note = entry.get("note", "")
    if not isinstance(note, str):
        m.fail(keys + ("note",), "note must be a string")
    opts = {"use": use, "note": note}
    for k in ("columns", "units"):
        if k in entry:
            opts[k] = m.string_map(entry[k], keys + (k,))
    for k, unit in TEST_UNITS.items():
        if k in entry and k in KINDS[kind]:
            opts[k] = m.quantity(entry[k], keys + (k,), unit) if k == "angle" else \
                _pressure(m, entry[k], keys + (k,)) if k == "pressure" else \
                m.positive(entry[k], keys + (k,), unit)
    if "load_case" in entry:
        opts["load_case"] = _load_case(m, entry["load_case"], keys + ("load_case",))
    if "cleat" in entry:
        opts["cleat"] = _cleat(m, entry["cleat"], keys + ("cleat",))
    for k, choices in (("direction", ("lateral", "longitudinal")), ("travel", ("vertical", "horizontal")),
                       ("positive", ("up", "down"))):
        if k in entry and entry[k] not in choices:
            m.fail(keys + (k,), f"{k} must be one of {', '.join(choices)}, got {json.dumps(entry[k])}")
        if k in entry:
            opts[k] = entry[k]
    if "wheels" in entry:
        if not isinstance(entry["wheels"], int) or isinstance(entry["wheels"], bool) or entry["wheels"] < 1:
            m.fail(keys + ("wheels",), "wheels must be a whole number >= 1")
        opts["wheels"] = entry["wheels"]
    if "trailer" in entry:
        t = entry["trailer"]
        if not isinstance(t, dict):
            m.fail(keys + ("trailer",), "expected an inline table of trailer dimensions")
        for k, v in t.items():
            if k not in TRAILER_KEYS:
                m.fail(keys + ("trailer", k),
                       f"unknown trailer key '{k}'; allowed: {', '.join(TRAILER_KEYS)}")
        opts["trailer"] = {k: m.quantity(v, keys + ("trailer", k), "m") for k, v in t.items()}
    if kind == "footprint_image" and ("load" in opts) == ("deflection" in opts):
        m.fail(keys, "a footprint image needs its load or its deflection (one of them)")
    if kind == "static_cleat" and "cleat" not in opts:
        m.fail(keys, "a static cleat test needs cleat = \"WIDTHxHEIGHT\" (mm)")
    return read_test(kind, path, **opts)


def read_test(kind: str, path, **options):
    """Read one test file of ``kind`` with its manifest ``options`` (SI)."""
    if kind == "load_deflection":
        return lf.read_load_deflection(path, **options)
    if kind == "drop_test":
        return lf.read_drop_trace(path, **options)
    if kind == "contact_patch":
        return lf.read_patch_points(path, **options)
    if kind == "footprint_image":
        from .footprint_image import read_footprint_image
        image = lf.FootprintImage(str(path), options.get("use", "fit"), options.get("note", ""),
                                  options.get("load"), options.get("deflection"),
                                  options.get("calibration", 0.1), options.get("travel", "vertical"))
        image.footprint = read_footprint_image(path, image.calibration, image.travel)
        return image
    if kind == "carcass_profile":
        return lf.read_carcass_profile(path, **options)
    if kind == "modal":
        return lf.read_modal(path, **options)
    if kind == "static_cleat":
        return lf.read_static_cleat(path, **options)
    if kind == "dynamic_cleat":
        return lf.read_dynamic_cleat(path, **options)
    raise InputError(f"unknown test kind '{kind}'; expected one of {', '.join(KINDS)}", field="kind")


def read_campaign(path) -> Campaign:
    """Read a campaign: a folder holding ``campaign.toml``, or the manifest itself."""
    path = Path(path)
    if path.is_dir():
        path = path / MANIFEST
    if not path.is_file():
        raise InputError(f"no campaign manifest ({MANIFEST}) here", source=str(path))
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InputError("the manifest is not UTF-8 text", source=str(path)) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        found = re.search(r"line (\d+)", str(exc))
        raise InputError(f"not valid TOML ({str(exc).split(' (at')[0]})", source=str(path),
                         line=int(found.group(1)) if found else None) from None
    m = _Manifest(path, text)
    for k in doc:
        if k not in ("campaign", "tyre", "test"):
            m.fail((k,), f"unknown table '{k}'; a manifest has [campaign], [tyre] and [[test]]")
    head = doc.get("campaign", {})
    if not isinstance(head, dict) or any(k not in ("name",) for k in head):
        m.fail(("campaign",), "[campaign] takes name = \"...\" only")
    tyre, base = {}, None
    for k, v in doc.get("tyre", {}).items():
        if k not in TYRE_KEYS:
            m.fail(("tyre", k), f"unknown tyre key '{k}'; allowed: {', '.join(TYRE_KEYS)}")
        if k == "base":
            base = Path(str(v)).expanduser()
            base = base if base.is_absolute() else path.parent / base
            if not base.is_file():
                m.fail(("tyre", k), f"no such property file: {base}")
        elif k == "name":
            tyre[k] = str(v)
        elif k == "pressure":
            tyre[k] = _pressure(m, v, ("tyre", k))
        else:
            tyre[k] = m.positive(v, ("tyre", k), TYRE_KEYS[k])
    _tyre_physics(m, tyre)
    tests = doc.get("test", [])
    if not isinstance(tests, list) or not tests:
        m.fail(("test",), "a campaign lists its tests as one or more [[test]] tables")
    records = [_test(m, entry, i, path.parent) for i, entry in enumerate(tests)]
    name = head.get("name") or tyre.get("name") or path.parent.name
    return Campaign(str(path), str(name), tyre, base, records)


def loose_files(paths, kind: str, **options) -> Campaign:
    """A campaign of test files given one by one (their columns named as in
    :mod:`tyrelab.fit.lab_files`), all of ``kind``; a folder or a manifest among
    them contributes its tests of that kind."""
    tests, tyre, base, name = [], {}, None, "test files"
    for p in paths:
        p = Path(p)
        if p.is_dir() or p.name == MANIFEST or p.suffix.lower() == ".toml":
            c = read_campaign(p)
            tests += c.tests
            tyre, base, name = {**tyre, **c.tyre}, base or c.base, c.name
            continue
        if not p.is_file():
            raise InputError("no such file", source=str(p))
        if kind == "footprint_image" or p.suffix.lower() in (".png", ".bmp", ".jpg", ".jpeg", ".tif"):
            raise InputError("a footprint image needs its load or deflection: list it in a "
                             f"{MANIFEST}", source=str(p))
        tests.append(read_test(kind, p, **options))
    return Campaign(str(Path(paths[0]).resolve()) if paths else "", name, tyre, base, tests)
