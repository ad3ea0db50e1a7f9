"""What a fit step returns and the small helpers every step shares (:mod:`tyrelab.fit.workflow`)."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import InputError
from ..tyre.tir import TirFile


@dataclass
class StepResult:
    """What one step fitted: rows of the summary, notes, and the arrays its figures draw."""

    name: str
    rows: list = field(default_factory=list)      # dicts: parameter, value, unit, rms, held_out, source
    notes: list = field(default_factory=list)
    data: dict = field(default_factory=dict)


#: unit of each step's errors (fitted RMS and held-out errors)
ERROR_UNITS = {"vertical": "N", "damping": "m", "patch": "m", "shape": "-", "cleats": "N", "ring": "%"}


def summary_row(step, parameter, value, unit, rms=None, held_out=None, source="", equation=""):
    """A summary row: ``held_out`` maps a held-out file to its error (RMS, in the step's unit)."""
    return {"parameter": parameter, "value": value, "unit": unit, "rms": rms, "held_out": held_out,
            "source": source, "equation": equation, "error_unit": ERROR_UNITS[step]}


def shown(value, unit="") -> str:
    """A value as a person reads it: N/mm, N s/mm and mm for the SI N/m, N s/m and m."""
    if value is None:
        return ""
    if isinstance(value, str):
        return value
    scale, word = {"N/m": (1e-3, "N/mm"), "N s/m": (1e-3, "N s/mm"), "m": (1e3, "mm"),
                   "-": (1.0, "")}.get(unit, (1.0, unit))
    return f"{value * scale:.4g} {word}".strip()


def file_names(tests) -> str:
    """The tests' file names, each once (one file may hold several tests, as a table per pressure)."""
    return ", ".join(dict.fromkeys(t.name for t in tests))


def tyre_dimension(tir: TirFile, key: str, step: str) -> float:
    value = tir.number("DIMENSION", key, None)
    if value is None or not value > 0:
        raise InputError(f"the {step} fit needs the tyre's {key}: give it in the manifest's [tyre] "
                         "table, or a base property file (--into)", source=tir.source, field=key)
    return value


def fitted_tyre(tir: TirFile, step: str):
    from ..tyre.params import Tyre
    tyre_dimension(tir, "UNLOADED_RADIUS", step)
    if not (tir.has("VERTICAL", "VERTICAL_STIFFNESS") or tir.table("DEFLECTION_LOAD_CURVE") is not None):
        raise InputError(f"the {step} fit needs the tyre's vertical law: fit the vertical step first "
                         "(a load_deflection test) or start from a property file (--into)",
                         source=tir.source, field="VERTICAL")
    return Tyre.from_tir(tir, name="fitted")
