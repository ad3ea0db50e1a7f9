"""The property file a fit writes: started from a base or new, tidied before it is written.

A new file has the sections of the shipped XZL files, in their order
(:data:`ORDER`); an updated one keeps its own sections, order and units and
gains the fitted ones. Either way tyrelab's record of the fit,
``[TYRELAB_FIT]`` (sources, RMS errors, the pendulum's damping; SI with the
unit in each key's name, which ADAMS/Tire does not read), comes last.
"""

from __future__ import annotations

import copy

import numpy as np

from .._version import __version__
from ..tyre.tir import TirFile, read_tir

#: tyrelab's own section of the property file: the fit's record
FIT_SECTION = "TYRELAB_FIT"
#: the manifest's [tyre] keys and where they go
TYRE_KEYS = {"unloaded_radius": ("DIMENSION", "UNLOADED_RADIUS"), "width": ("DIMENSION", "WIDTH"),
             "rim_radius": ("DIMENSION", "RIM_RADIUS"), "pressure": ("OPERATING_CONDITIONS", "INFLPRES"),
             "mass": ("INERTIA", "MASS"), "wheel_mass": ("INERTIA", "WHEEL_MASS"),
             "wheel_iyy": ("INERTIA", "WHEEL_IYY"), "iyy": ("INERTIA", "IYY"),
             "fnomin": ("VERTICAL", "FNOMIN")}


def start_tir(campaign, base=None) -> TirFile:
    """The property file the steps write into: ``base`` (a TirFile or a path), else the
    manifest's ``base``, else a new file; the manifest's ``[tyre]`` values are set over it."""
    if base is None and campaign.base is not None:
        base = campaign.base
    if base is None:
        tir = TirFile(source="<new>", header=[
            "$" + "-" * 74, f"$ {campaign.name}: written by tyrelab {__version__} (tyrelab fit)",
            f"$ from the test campaign {campaign.source}.",
            f"$ [{FIT_SECTION}] is tyrelab's own record of the fit (SI, the unit in each key's name);",
            "$ ADAMS/Tire does not read it.", "$" + "-" * 74])
        tir.set("MDI_HEADER", "FILE_TYPE", "tir")
        tir.set("MDI_HEADER", "FILE_VERSION", 3.0)
        tir.set("MDI_HEADER", "FILE_FORMAT", "ASCII")
        tir.set("MODEL", "PROPERTY_FILE_FORMAT", "TYRELAB")
        tir.set("MODEL", "TYRESIDE", "RIGHT")
    else:
        tir = copy.deepcopy(base) if isinstance(base, TirFile) else read_tir(base)
        tir.header = list(tir.header) + [f"$ updated by tyrelab {__version__} (tyrelab fit) from "
                                         f"{campaign.source}"]
    t = campaign.tyre
    for key, (section, name) in TYRE_KEYS.items():
        if key in t:
            tir.set(section, name, float(t[key]))
    if "pressure" in t and not tir.has("OPERATING_CONDITIONS", "NOMPRES"):
        tir.set("OPERATING_CONDITIONS", "NOMPRES", float(t["pressure"]))
    if campaign.name:
        tir.set(FIT_SECTION, "CAMPAIGN", campaign.name)
    return tir


#: section order of a new file (as the shipped XZL files); others follow in their own order
ORDER = ("MDI_HEADER", "UNITS", "MODEL", "DIMENSION", "OPERATING_CONDITIONS", "INERTIA", "VERTICAL",
         "DEFLECTION_LOAD_CURVE", "SHAPE", "CONTACT_PATCH", "CONTACT_WIDTH_CURVE")


def tidy(tir: TirFile, new: bool) -> None:
    """Round the numbers written to 10 significant digits (no 0.17300000000000001), put the
    sections of a new file in :data:`ORDER` and tyrelab's own section last."""
    for sec in tir.sections.values():
        for k, v in sec.entries.items():
            if isinstance(v, float):
                sec.entries[k] = float(f"{v:.10g}")
        if sec.table is not None:
            sec.table = np.array([[float(f"{v:.10g}") for v in row] for row in sec.table])
    names = list(tir.sections)
    if new:
        names.sort(key=lambda n: ORDER.index(n) if n in ORDER else len(ORDER))
    if FIT_SECTION in names:
        names.remove(FIT_SECTION)
        names.append(FIT_SECTION)
    tir.sections = {n: tir.sections[n] for n in names}
