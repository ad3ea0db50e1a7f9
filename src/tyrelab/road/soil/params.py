"""Soil parameters: the record, soil files (TOML) and the built-in soil library.

A soil file holds one ``[soil]`` table in SI, in the order and units of Project
Chrono's ``SCMTerrain::SetSoilParameters``::

    [soil]
    name = "LETE sand"          # optional label
    n = 0.79                    # Bekker's sinkage exponent, 0 < n <= 2
    kc = 102e3                  # cohesive modulus k_c [N/m^(n+1)]
    kphi = 5301e3               # frictional modulus k_phi [N/m^(n+2)]
    cohesion = 1.3e3            # Mohr-Coulomb cohesion c [Pa], at most 1e6
    friction_angle = 31.1       # Mohr-Coulomb internal friction angle phi [deg], 0 <= phi < 60
    janosi_k = 0.0115           # Janosi-Hanamoto shear deformation modulus K [m]
    elastic_stiffness = 4e7     # optional: unloading/reloading stiffness [Pa/m]
    damping = 0.0               # optional: viscous damping of the normal stress [Pa s/m]

    [bulldozing]                # optional: the soil a wheel presses down flows beside and ahead
    erosion_angle = 55.0        # angle of repose of the displaced soil [deg], 0 < angle < 90
    flow_factor = 1.0           # optional: volume raised / volume pressed down (default 1)
    iterations = 5              # optional: erosion sweeps per step (default 5)
    propagations = 6            # optional: nodes the erosion reaches beyond the rut's edge (6)

(the ``[bulldozing]`` keys are those of Chrono's ``SCMTerrain::SetBulldozingParameters``;
the defaults its rigid-tyre demo's; without the table the soil does not bulldoze).

The equations these parameters enter (:mod:`tyrelab.road.soil.scm`):

* pressure-sinkage, Bekker (1969): ``p = (k_c / b + k_phi) z^n``, ``b`` the
  smaller dimension of the contact patch [m], ``z`` the sinkage [m];
* shear strength, Mohr-Coulomb: ``tau_max = c + p tan(phi)``;
* shear stress-displacement, Janosi & Hanamoto (1961):
  ``tau = tau_max (1 - exp(-j / K))``, ``j`` the shear displacement [m] slid one way
  (sliding back, the shear reverses by Dahl's law: :func:`tyrelab.road.soil.scm.mobilized_shear`);
* elastic unloading and reloading (Krenn & Hirzinger 2009; Chrono SCM): below the
  largest sinkage reached, ``p`` falls and rises along the line of slope
  ``elastic_stiffness`` [Pa/m].

The built-in soils (:func:`soil_names`) carry their published values and the source
of each in their file's comments; their Janosi moduli and elastic stiffnesses,
which Wong's Table 2.3 does not give, are stated there as assumptions.
"""

from __future__ import annotations

import math
import tomllib
from importlib import resources
from pathlib import Path
from typing import NamedTuple

from ...errors import InputError

#: unloading/reloading stiffness when a soil file gives none [Pa/m] (Chrono's SCM demo)
DEFAULT_ELASTIC_STIFFNESS = 4e7
#: largest friction angle accepted [deg]: above it tan(phi) > 1.7, no natural soil
MAX_FRICTION_ANGLE = 60.0
#: largest cohesion accepted [Pa]: 1 MPa. The firmest soil of Wong's Table 2.3 (heavy clay)
#: has 69 kPa; a ground of megapascals is rock, for the rigid road. (A cohesion of 10 MPa
#: gave a single wheel on 23 kN a drawbar pull of 528 kN; 1e15 Pa threw it off the ground.)
MAX_COHESION = 1e6
#: the keys of a [soil] table: required, then optional with their defaults
REQUIRED = ("n", "kc", "kphi", "cohesion", "friction_angle", "janosi_k")
OPTIONAL = {"name": None, "elastic_stiffness": DEFAULT_ELASTIC_STIFFNESS, "damping": 0.0}
_UNITS = {"n": "", "kc": "N/m^(n+1)", "kphi": "N/m^(n+2)", "cohesion": "Pa", "friction_angle": "deg",
          "janosi_k": "m", "elastic_stiffness": "Pa/m", "damping": "Pa s/m"}


class Soil(NamedTuple):
    """A soil's parameters, SI (the friction angle in radians).

    ``n``, ``kc`` [N/m^(n+1)], ``kphi`` [N/m^(n+2)]: Bekker's pressure-sinkage law;
    ``cohesion`` [Pa] and ``friction_angle`` [rad]: Mohr-Coulomb; ``janosi_k`` [m]:
    Janosi-Hanamoto; ``elastic_stiffness`` [Pa/m] and ``damping`` [Pa s/m]: the
    normal stress below the largest sinkage reached. ``bulldozing``: the soil pressed down
    is raised beside and ahead of the rut (:mod:`tyrelab.road.soil.bulldozing`), eroded to
    the slope ``erosion_slope`` (tan of the angle of repose) by ``erosion_iterations``
    sweeps over ``erosion_propagations`` nodes beyond the contact, ``flow_factor`` times
    the volume pressed down.
    """

    n: float
    kc: float
    kphi: float
    cohesion: float
    friction_angle: float
    janosi_k: float
    elastic_stiffness: float
    damping: float
    bulldozing: bool = False
    erosion_slope: float = 0.0
    flow_factor: float = 1.0
    erosion_iterations: int = 5
    erosion_propagations: int = 6

    def bekker_pressure(self, sinkage, width):
        """Bekker's pressure [Pa] at ``sinkage`` [m] under a contact ``width`` [m] wide."""
        import numpy as np
        z = np.maximum(np.asarray(sinkage, float), 0.0)
        return (self.kc / width + self.kphi) * z ** self.n


def soil_from_table(table: dict, source: str | None = None, lines=None) -> tuple[Soil, str]:
    """``(Soil, name)`` from a ``[soil]`` table's values (file units: the angle in degrees).

    ``lines(key)`` gives a key's line for messages. Every value is checked: numbers,
    finite, not negative, ``0 < n <= 2``, ``cohesion <= 1 MPa``, ``0 <= friction_angle < 60``
    deg, ``janosi_k`` and ``elastic_stiffness`` above 0 and ``kc + kphi`` above 0 (a soil
    that carries something). Unknown keys are refused with the allowed ones listed.
    """
    def fail(key, why):
        raise InputError(why, source=source, line=lines(key) if lines else None,
                         field=f"soil.{key}" if key else "soil")

    if not isinstance(table, dict):
        fail(None, "expected a [soil] table")
    unknown = sorted(set(table) - set(REQUIRED) - set(OPTIONAL))
    if unknown:
        fail(unknown[0], f"unknown key '{unknown[0]}'; a [soil] table takes: "
                         f"{', '.join(REQUIRED + tuple(OPTIONAL))}")
    values = {}
    for key in REQUIRED + tuple(k for k in OPTIONAL if k != "name"):
        if key not in table:
            if key in REQUIRED:
                fail(None, f"missing key '{key}' [{_UNITS[key]}] in [soil]")
            values[key] = OPTIONAL[key]
            continue
        v = table[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            fail(key, f"expected a finite number [{_UNITS[key]}], got {v!r}")
        if v < 0:
            fail(key, f"expected a value >= 0 [{_UNITS[key]}], got {v!r}")
        values[key] = float(v)
    if not 0.0 < values["n"] <= 2.0:
        fail("n", f"expected the sinkage exponent n in (0, 2], got {values['n']!r}")
    if values["cohesion"] > MAX_COHESION:
        fail("cohesion", f"expected a cohesion up to {MAX_COHESION:g} Pa (1 MPa; a firmer ground is "
                         f"rock: use the rigid road), got {values['cohesion']!r}")
    if not values["friction_angle"] < MAX_FRICTION_ANGLE:
        fail("friction_angle", f"expected a friction angle in [0, {MAX_FRICTION_ANGLE:g}) deg, "
                               f"got {values['friction_angle']!r}")
    for key in ("janosi_k", "elastic_stiffness"):
        if values[key] == 0:
            fail(key, f"expected a value > 0 [{_UNITS[key]}], got 0")
    if values["kc"] + values["kphi"] == 0:
        fail("kphi", "kc and kphi are both 0: the soil would carry nothing")
    name = table.get("name")
    if name is not None and not isinstance(name, str):
        fail("name", f"expected a text, got {name!r}")
    values["friction_angle"] = math.radians(values["friction_angle"])
    return Soil(**values), name or ""


#: the keys of a [bulldozing] table and their defaults (None: required)
BULLDOZING = {"erosion_angle": None, "flow_factor": 1.0, "iterations": 5, "propagations": 6}


def bulldozing_from_table(soil: Soil, table, source: str | None = None, lines=None) -> Soil:
    """``soil`` that bulldozes as a ``[bulldozing]`` table says (see the module docstring):
    ``0 < erosion_angle < 90`` deg, ``flow_factor >= 0``, ``iterations`` a whole number from 1
    to 1000 and ``propagations`` from 1 to 100."""
    def fail(key, why):
        raise InputError(why, source=source, line=lines(key) if lines else None,
                         field=f"bulldozing.{key}" if key else "bulldozing")

    if not isinstance(table, dict):
        fail(None, "expected a [bulldozing] table")
    unknown = sorted(set(table) - set(BULLDOZING))
    if unknown:
        fail(unknown[0], f"unknown key '{unknown[0]}'; a [bulldozing] table takes: "
                         f"{', '.join(BULLDOZING)}")
    if "erosion_angle" not in table:
        fail(None, "missing key 'erosion_angle' [deg] in [bulldozing]")
    values = {}
    for key, default in BULLDOZING.items():
        v = table.get(key, default)
        whole = key in ("iterations", "propagations")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or (whole and v != int(v)):
            fail(key, f"expected a {'whole' if whole else 'finite'} number, got {v!r}")
        values[key] = v
    if not 0.0 < values["erosion_angle"] < 90.0:
        fail("erosion_angle", f"expected an angle of repose in (0, 90) deg, got "
                              f"{values['erosion_angle']!r}")
    if values["flow_factor"] < 0:
        fail("flow_factor", f"expected a value >= 0, got {values['flow_factor']!r}")
    for key, most in (("iterations", 1000), ("propagations", 100)):
        if not 1 <= values[key] <= most:
            fail(key, f"expected a whole number from 1 to {most}, got {values[key]!r}")
    return soil._replace(bulldozing=True,
                         erosion_slope=math.tan(math.radians(values["erosion_angle"])),
                         flow_factor=float(values["flow_factor"]),
                         erosion_iterations=int(values["iterations"]),
                         erosion_propagations=int(values["propagations"]))


def read_soil(path) -> tuple[Soil, str]:
    """``(Soil, name)`` from a soil file (see the module docstring); errors name file and line."""
    from ...core.toml_lines import TomlLocator
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError("no such soil file", source=str(path)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read the soil file as UTF-8 text ({type(exc).__name__})",
                         source=str(path)) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", source=str(path)) from None
    unknown = sorted(set(doc) - {"soil", "bulldozing"})
    if unknown or "soil" not in doc:
        raise InputError("expected one [soil] table (and an optional [bulldozing] table)"
                         + (f", found '{unknown[0]}'" if unknown else ""), source=str(path))
    where = TomlLocator(text)
    soil, name = soil_from_table(doc["soil"], str(path), lambda key: where.line(("soil", key) if key
                                                                                else ("soil",)))
    if "bulldozing" in doc:
        soil = bulldozing_from_table(soil, doc["bulldozing"], str(path), lambda key: where.line(
            ("bulldozing", key) if key else ("bulldozing",)))
    return soil, name or path.stem


def soil_names() -> list[str]:
    """Names of the built-in soils (their files in ``road/soil/data``)."""
    folder = resources.files("tyrelab.road.soil").joinpath("data")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def load_soil(spec) -> tuple[Soil, str]:
    """``(Soil, name)`` of a built-in soil's name or a soil file's path (``*.toml``)."""
    if isinstance(spec, Soil):
        return spec, "soil"
    text = str(spec).strip()
    if text.lower().endswith(".toml"):
        return read_soil(text)
    if text.lower() in soil_names():
        data = resources.files("tyrelab.road.soil").joinpath("data", f"{text.lower()}.toml")
        with resources.as_file(data) as path:
            return read_soil(path)
    raise InputError(f"unknown soil '{text}', expected one of {', '.join(soil_names())} or a soil "
                     "file FILE.toml", field="terrain")
