"""Argument parsing helpers for the command line (units converted here, once).

Every number a command takes is parsed by one of these argparse types, which
refuse a non-number, a non-finite value and a value outside the bounds of
:mod:`tyrelab.limits` with one line naming the option, the value and what is
allowed; output paths are checked with :func:`tyrelab.io_atomic.check_output_path`
right after parsing, before any work.
"""

from __future__ import annotations

import argparse
import math

from ..errors import InputError
from ..limits import check_number


def _fmt(v: float) -> str:
    return f"{v:.6g}"


def bounded_float(name: str, low: float | None = None, high: float | None = None, unit: str = "",
                  scale: float = 1.0, low_open: bool = False):
    """argparse type: a finite number in ``[low, high]`` (command-line units), times ``scale`` into SI.

    ``low_open``: the low bound itself is excluded (``low < value``).
    """

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got '{text}'") from None
        if low is not None and low >= 0 and value <= 0 and (low_open or low > 0):
            raise argparse.ArgumentTypeError(f"{name} must be a positive number, got '{text}'")
        try:
            check_number(value, name, low, high, unit, low_open, given=text)
        except InputError as exc:
            raise argparse.ArgumentTypeError(exc.reason) from None
        return value * scale
    parse.__name__ = name
    return parse


def positive_float(name: str, scale: float = 1.0):
    """argparse type: a positive finite number, multiplied by ``scale`` into SI."""
    return bounded_float(name, 0.0, None, scale=scale, low_open=True)


def count(name: str, low: int, high: int):
    """argparse type: a whole number in ``[low, high]``."""
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a whole number, got '{text}'") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{name} {value} is out of range; allowed: {low} to {high}")
        return value
    parse.__name__ = name
    return parse


def comma_numbers(text: str, field: str, most: int, accept, what: str) -> list[float]:
    """1 to ``most`` finite numbers separated by commas, each one ``accept(value)`` takes; else
    one :class:`InputError` line on ``field``: "expected 1 to N {what} separated by commas"."""
    try:
        values = [float(v) for v in text.split(",") if v.strip()]
    except ValueError:
        values = []
    if not values or len(values) > most or any(not (math.isfinite(v) and accept(v)) for v in values):
        raise InputError(f"expected 1 to {most} {what} separated by commas, found '{text}'",
                         source="command line", field=field)
    return values


def handling_for(tyre, chosen, source, purpose: str, hint: str) -> str:
    """The handling model a command runs ``tyre`` under: ``chosen`` (an option's value), else
    the one its file describes; "none" is an :class:`InputError` on ``--handling`` saying why
    there is nothing ``purpose`` ("to draw") and what to give instead (``hint``)."""
    from ..api import default_handling

    handling = chosen or default_handling(tyre)
    if handling == "none":
        reason = "'none' has no forces" if chosen else "this tyre's file describes no handling model"
        raise InputError(f"{reason} {purpose}; give {hint}", source=str(source), field="--handling")
    return handling


def nominal_load_for(tyre, given, source, option: str) -> float:
    """``given`` [N], else the load the tyre's file calls nominal (FNOMIN, FZ_NOM); a file that
    names none is an :class:`InputError` on ``option``."""
    from ..report.handling_curves import nominal_load

    nominal = given or nominal_load(tyre)
    if nominal is None:
        raise InputError(f"the file names no nominal load (FNOMIN, FZ_NOM): give {option} in N",
                         source=str(source), field=option)
    return nominal


def load_value(text: str):
    """A load case name (LC1..LC3) or a wheel load in N (finite, at least the limits' minimum)."""
    from ..limits import MIN_LOAD
    try:
        value = float(text)
    except ValueError:
        return text
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"load must be a load case (LC1-LC3) or a positive force in N, "
                                         f"got '{text}'")
    if value < MIN_LOAD:
        raise argparse.ArgumentTypeError(f"load {text} N is out of range; allowed: a load case (LC1-LC3) "
                                         f"or at least {MIN_LOAD:g} N")
    return value


def pressure_kpa(default_help: str = "default 300"):
    """argparse type of ``--pressure`` in kPa (bounds of :mod:`tyrelab.limits`), into Pa."""
    from ..limits import MAX_PRESSURE, MIN_PRESSURE
    return bounded_float("pressure", MIN_PRESSURE / 1e3, MAX_PRESSURE / 1e3, "kPa", scale=1e3)


def output_path(text: str, suffixes=(".parquet", ".csv"), field: str = "-o", inputs=()):
    """Check an output file before any work (:func:`tyrelab.io_atomic.check_output_path`)."""
    from ..io_atomic import check_output_path
    return check_output_path(text, suffixes, field, inputs)


def option_value(text: str) -> tuple[str, object]:
    """``KEY=VALUE`` of ``--option``: the value as an integer, a number, true/false or text."""
    key, sep, value = text.partition("=")
    key, value = key.strip(), value.strip()
    if not sep or not key.isidentifier() or not value:
        raise argparse.ArgumentTypeError(f"expected KEY=VALUE (e.g. n_length=5), got '{text}'")
    lowered = value.lower()
    if lowered in ("true", "false"):
        return key, lowered == "true"
    for kind in (int, float):
        try:
            number = kind(value)
        except ValueError:
            continue
        if kind is float and not math.isfinite(number):
            raise argparse.ArgumentTypeError(f"option {key}: expected a finite number, got '{value}'")
        return key, number
    return key, value


def add_options(parser) -> None:
    """``--option KEY=VALUE`` (repeatable): the contact model's options."""
    parser.add_argument("--option", type=option_value, action="append", default=[],
                        metavar="KEY=VALUE",
                        help="an option of the contact model, e.g. n_length=5 (enveloping cams), "
                             "n_segments=200 (ring), cam_layout=outline; repeat for more; an "
                             "unknown key is refused with the model's options listed")


def add_relaxation(parser) -> None:
    """``--relaxation``: the transient slip of the handling forces (TyreModel.relaxation)."""
    parser.add_argument("--relaxation", default="auto", metavar="HOW",
                        help="transient slip of the handling forces: auto (default: as the "
                             "property file's USE_MODE says, +10 = relaxation), off (steady state), "
                             "file (the handling model's own relaxation lengths: the Magic "
                             "Formula's) or SIGMA_KAPPA,SIGMA_ALPHA in metres")


def relaxation_value(args):
    """``--relaxation`` as :class:`~tyrelab.tyre.model.TyreModel` takes it: a word, or two
    lengths (checked there, the message naming the option)."""
    text = args.relaxation
    return tuple(text.split(",")) if "," in text else text


def model_options(pairs) -> dict:
    """The ``--option`` pairs as a dict (a key given twice: the last one)."""
    return dict(pairs or [])


def add_force(parser) -> None:
    """``--force``: run a request estimated above the memory or time limit."""
    from ..resources import MAX_MEMORY, MAX_WALL_TIME
    parser.add_argument("--force", action="store_true",
                        help=f"run even when the request is estimated to need more than "
                             f"{MAX_MEMORY / 1024 ** 3:g} GiB of memory or {MAX_WALL_TIME / 60:g} min")


#: suffixes of the files commands read besides road files (those: tyrelab.road.formats, with an
#: optional ``@OFFSET``)
INPUT_SUFFIXES = (".tir", ".json", ".tdx", ".csv", ".parquet", ".toml")


def input_files(*values) -> list[str]:
    """The file paths among command values (a tyre file, a road file ``FILE[@V]`` ...), to keep
    outputs off them."""
    from ..road.formats import road_file
    out = []
    for v in values:
        if v is None:
            continue
        text = str(v)
        named = road_file(text)
        if named is not None:
            out.append(named[1])
        elif text.lower().endswith(INPUT_SUFFIXES):
            out.append(text)
    return out


def renamed(exc: InputError, names: dict[str, str], options=()) -> InputError:
    """The same error with the Python argument name replaced by the command-line option; a
    model option the user gave (a name in ``options``, from ``--option NAME=VALUE``) becomes
    ``--option NAME``."""
    if exc.field in options:
        return InputError(exc.reason, source=exc.source, line=exc.line, field=f"--option {exc.field}")
    if exc.field in names:
        return InputError(exc.reason, source=exc.source, line=exc.line, field=names[exc.field])
    return exc


def soil_row_text(row, model_width: int) -> str:
    """One line of a slip curve's table (``tyrelab soil curve``, ``tyrelab study``): the
    model, the slip as given, the steady drawbar pull, driving torque and sinkage."""
    return (f"{row.model:<{model_width}}{f's = {row.slip:g}:':<12}pull {row.FX / 1e3:7.2f} kN  "
            f"torque {row.TORQUE / 1e3:7.2f} kN m  sinkage {row.SINKAGE * 1e3:6.1f} mm")

