"""The test files a campaign is made of, each read into one small record (SI).

One form per kind of test (thesis chapter 3):

=================  =============================================  =========================
kind               file                                           quantities (columns)
=================  =============================================  =========================
load_deflection    CSV or TYDEX: a table, or the raw loading and  deflection, load [, time]
                   unloading time series of the plate press
drop_test          CSV or TYDEX: rim (axle) height, held then let go time, displacement
contact_patch      CSV: patch size vs deflection or load          deflection or load,
                                                                  length and/or width
footprint_image    PNG bitmap, patch black on white, a 100 mm     (load or deflection in
                   calibration line (:mod:`.footprint_image`)     the manifest)
carcass_profile    CSV: points of the outer contour               y, radius (or drop)
modal              CSV in the form of thesis Table 3-3            mode, freq_Hz_<p>kPa,
                                                                  damping_pct_<p>kPa
static_cleat       CSV or TYDEX: the press on a cleat             deflection, load
dynamic_cleat      TYDEX (or a signal table) of a trailer run     the signal table's channels
=================  =============================================  =========================

CSV files: ``#`` lines are comments, the first other line names the columns.
A column is found by the manifest's ``columns`` (quantity -> header) or by
its name: the quantity or an alias (``load``, ``force``, ``fz`` ...), with the
unit after an underscore or in brackets (``deflection_mm``, ``load [kN]``);
``units`` in the manifest overrides; without any unit the column is SI.
Lengths and widths of a contact patch are the whole patch (2a, 2b). A bad
cell, a missing column or a value that makes no physical sense is one
:class:`~tyrelab.errors.InputError` naming the file, the line and the column.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import InputError
from ..measure.columns import _number, _table
from .lab_columns import check_finite, check_rows, read_test_columns

USES = ("fit", "held_out")


@dataclass
class LabTest:
    """What every test record carries: its file, whether it is fitted or held out, a note."""

    source: str
    use: str = "fit"
    note: str = ""

    @property
    def name(self) -> str:
        return Path(self.source).name


@dataclass
class LoadDeflection(LabTest):
    """Flat-plate press (3.3.1): ``deflection`` [m] from first touch and ``load`` [N] per sample
    or table row."""

    deflection: np.ndarray = field(default_factory=lambda: np.zeros(0))
    load: np.ndarray = field(default_factory=lambda: np.zeros(0))
    time: np.ndarray | None = None
    #: table step [m] a raw loop is averaged onto
    step: float = 0.005
    #: inflation pressure [Pa] of the press (None: the tyre's)
    pressure: float | None = None
    #: the file's deflection [m] at first touch, taken off (:func:`~tyrelab.fit.vertical.first_touch`;
    #: 0: the file counts from it)
    touch: float = 0.0


@dataclass
class DropTrace(LabTest):
    """Trailer drop test (3.4.1): rim height ``displacement`` [m] (up positive) over ``time`` [s],
    from the release or from before it while held (the fit finds the release:
    :func:`tyrelab.fit.damping.drop_release`), and the trailer that was dropped."""

    time: np.ndarray = field(default_factory=lambda: np.zeros(0))
    displacement: np.ndarray = field(default_factory=lambda: np.zeros(0))
    #: load case of thesis Table 3-4 or a wheel load [N]
    load_case: str | float = "LC1"
    #: pendulum inputs (eqs. 3.1-3.7): inertia about the hitch [kg m^2], hitch-to-axle lever [m];
    #: None: those of tyrelab's trailer (ARCHITECTURE.md) at the load case
    inertia: float | None = None
    lever: float | None = None
    wheels: int = 2
    #: low-pass cut-off [Hz] before the decrements are read (0: none)
    lowpass: float = 10.0
    #: overrides of tyrelab's trailer geometry (TrailerGeometry fields, SI)
    trailer: dict = field(default_factory=dict)


@dataclass
class PatchPoints(LabTest):
    """Contact-patch size (3.3.3) at ``deflection`` [m] or ``load`` [N]: whole ``length`` and
    ``width`` [m] (NaN where a row gives only one of them)."""

    deflection: np.ndarray | None = None
    load: np.ndarray | None = None
    length: np.ndarray | None = None
    width: np.ndarray | None = None
    lines: np.ndarray = field(default_factory=lambda: np.zeros(0, int))


@dataclass
class FootprintImage(LabTest):
    """A footprint bitmap (3.3.3) at a ``load`` [N] or ``deflection`` [m], measured on reading."""

    load: float | None = None
    deflection: float | None = None
    calibration: float = 0.1
    travel: str = "vertical"
    footprint: object = None       # footprint_image.Footprint


@dataclass
class CarcassProfile(LabTest):
    """Outer contour (3.3.2): lateral ``y`` [m] from the centre line (both sides allowed) and
    ``radius`` [m] from the spin axis."""

    y: np.ndarray = field(default_factory=lambda: np.zeros(0))
    radius: np.ndarray | None = None
    drop: np.ndarray | None = None


@dataclass
class ModalResults(LabTest):
    """Table 3-3: one row per mode and pressure: ``mode``, ``pressure`` [Pa], ``frequency`` [Hz],
    ``damping`` (ratio, -)."""

    table: pd.DataFrame = field(default_factory=pd.DataFrame)


@dataclass
class StaticCleat(LabTest):
    """Static cleat press (3.3.4): ``deflection`` [m] from first touch, ``load`` [N]."""

    deflection: np.ndarray = field(default_factory=lambda: np.zeros(0))
    load: np.ndarray = field(default_factory=lambda: np.zeros(0))
    cleat: tuple = (0.051, 0.051)
    direction: str = "lateral"
    #: the file's deflection [m] at first touch of the cleat, taken off (as a plate press's)
    touch: float = 0.0


@dataclass
class DynamicCleat(LabTest):
    """Trailer run over a cleat (3.4.2): the signal table (SI, TYDEX names)."""

    signal: pd.DataFrame = field(default_factory=pd.DataFrame)
    cleat: tuple | None = None
    angle: float = 0.0
    speed: float | None = None
    load_case: str | float = "LC1"


# --- readers, one per kind ---------------------------------------------------

def read_load_deflection(path, columns=None, units=None, step=0.005, use="fit",
                         note="", pressure=None) -> LoadDeflection:
    """A plate press: a table or a raw loop (:class:`LoadDeflection`)."""
    data, lines, kind = read_test_columns(path, ("deflection", "load"), ("time",), columns, units)
    check_finite(path, lines, kind, data, ("deflection", "load", "time"))
    d, f = data["deflection"], data["load"]
    if d.size < 3:
        raise InputError(f"{d.size} rows; a load-deflection test needs at least 3", source=str(path))
    floor = -0.05 * float(np.max(np.abs(d)))
    check_rows(path, lines, kind, d, d >= floor, "deflection {value:g} m is negative beyond noise "
           "(deflection is counted from first touch, positive in compression)", "deflection")
    if not np.max(d) > 0:
        raise InputError("the deflection never rises above zero", source=str(path), field="deflection")
    d, f, t, touch = _from_touch(d, f, data.get("time"))
    return LoadDeflection(str(path), use, note, d, f, t, float(step),
                          None if pressure is None else float(pressure), touch)


def read_drop_trace(path, columns=None, units=None, positive="up", **options) -> DropTrace:
    """A drop-test trace (:class:`DropTrace`); ``options`` are its other fields."""
    data, lines, kind = read_test_columns(path, ("time", "displacement"), (), columns, units)
    check_finite(path, lines, kind, data, ("time", "displacement"))
    t, z = data["time"], data["displacement"]
    if t.size < 50:
        raise InputError(f"{t.size} samples; a drop-test trace needs at least 50", source=str(path))
    ok = np.r_[True, np.diff(t) > 0]
    check_rows(path, lines, kind, t, ok, "time {value:g} s does not increase", "time")
    if positive not in ("up", "down"):
        raise InputError(f"positive must be 'up' or 'down', got '{positive}'", field="positive")
    z = z if positive == "up" else -z
    return DropTrace(str(path), time=t - t[0], displacement=z, **options)


def read_patch_points(path, columns=None, units=None, use="fit", note="") -> PatchPoints:
    """Contact-patch sizes (:class:`PatchPoints`)."""
    data, lines, kind = read_test_columns(path, (), ("deflection", "load", "length", "width"), columns, units)
    if "deflection" not in data and "load" not in data:
        raise InputError("a contact-patch file needs a 'deflection' or a 'load' column",
                         source=str(path), field="deflection")
    if "length" not in data and "width" not in data:
        raise InputError("a contact-patch file needs a 'length' or a 'width' column (whole patch)",
                         source=str(path), field="length")
    for q in ("deflection", "load"):
        if q in data:
            v = data[q]
            other = data.get("load" if q == "deflection" else "deflection")
            given = np.isfinite(v) | (other is not None and np.isfinite(other))
            check_rows(path, lines, kind, v, given, "row gives neither deflection nor load", q)
            check_rows(path, lines, kind, v, ~np.isfinite(v) | (v > 0),
                       f"{q} {{value:g}} must be positive", q)
    for q in ("length", "width"):
        if q in data:
            v = data[q]
            check_rows(path, lines, kind, v, ~np.isfinite(v) | (v > 0), f"{q} {{value:g}} m must be positive",
                   q)
    return PatchPoints(str(path), use, note, data.get("deflection"), data.get("load"), data.get("length"),
                       data.get("width"), lines)


def read_carcass_profile(path, columns=None, units=None, use="fit", note="") -> CarcassProfile:
    """Contour points (:class:`CarcassProfile`): ``y`` and ``radius``, or ``y`` and ``drop``."""
    data, lines, kind = read_test_columns(path, ("y",), ("radius", "drop"), columns, units)
    if "radius" not in data and "drop" not in data:
        raise InputError("a carcass profile needs a 'radius' column (from the spin axis) or a 'drop' "
                         "column (below the crown)", source=str(path), field="radius")
    check_finite(path, lines, kind, data, ("y", "radius", "drop"))
    if "radius" in data:
        check_rows(path, lines, kind, data["radius"], data["radius"] > 0, "radius {value:g} m must be "
               "positive", "radius")
    if "drop" in data:
        check_rows(path, lines, kind, data["drop"], data["drop"] >= 0, "drop {value:g} m below the crown "
               "must not be negative", "drop")
    if data["y"].size < 3:
        raise InputError("a carcass profile needs at least 3 points", source=str(path))
    return CarcassProfile(str(path), use, note, data["y"], data.get("radius"), data.get("drop"))


_MODAL = re.compile(r"^(freq|frequency|damping)_(hz|pct|%)?_?(\d+(?:\.\d+)?)kpa$", re.I)


def described_mode(text: str) -> int | None:
    """The Table 3-3 mode a row's description names (1 in-plane rotation about the spin axis,
    2 vertical/longitudinal, 3 lateral, 4 out-of-plane rotation, 5 third in-plane, 6 third
    out-of-plane), or None when it names none of them plainly."""
    t = " ".join(text.lower().replace("-", " ").split())
    out, inp = "out of plane" in t, "in plane" in t
    if "third" in t:
        return 6 if out else 5 if inp else None
    if out:
        return 4
    if "lateral" in t:
        return 3
    if "vertical" in t or "longitudinal" in t:
        return 2
    if inp and ("rotation" in t or "spin" in t):
        return 1
    return None


def read_modal(path, use="fit", note="") -> ModalResults:
    """Modal results in the form of thesis Table 3-3: a ``mode`` column and, per pressure,
    ``freq_Hz_<p>kPa`` and ``damping_pct_<p>kPa`` (empty cells: not measured). Modes are
    numbered as Table 3-3 numbers them; a ``description`` that names another Table 3-3 mode
    (:func:`described_mode`; a test numbered by ascending frequency, say) is refused on its
    line, since the ring would be fitted to the wrong shapes."""
    from ..tyre.ring.modal import MODE_NAMES

    path = Path(path)
    if not path.is_file():
        raise InputError("no such file", source=str(path))
    header, header_line, rows = _table(path, ",")
    lower = [h.lower() for h in header]
    if "mode" not in lower:
        raise InputError("a modal table needs a 'mode' column (Table 3-3)", source=str(path),
                         line=header_line, field="mode")
    mode_col = lower.index("mode")
    described = lower.index("description") if "description" in lower else None
    cols = {}
    for i, h in enumerate(header):
        m = _MODAL.match(h.strip())
        if m:
            cols.setdefault(float(m.group(3)) * 1e3, {})["f" if m.group(1).lower().startswith("f")
                                                          else "c"] = i
    if not cols or any(set(v) != {"f", "c"} for v in cols.values()):
        raise InputError("expected column pairs freq_Hz_<p>kPa and damping_pct_<p>kPa (Table 3-3)",
                         source=str(path), line=header_line)
    out = []
    for ln, row in rows:
        mode = _number(row[mode_col], path, ln, "mode")
        if not (np.isfinite(mode) and mode == int(mode) and mode >= 1):
            raise InputError(f"mode '{row[mode_col]}' is not a mode number", source=str(path), line=ln,
                             field="mode")
        named = described_mode(row[described]) if described is not None and described < len(row) else None
        if named is not None and named != int(mode) and int(mode) in MODE_NAMES:
            raise InputError(f"mode {int(mode)} is Table 3-3's {MODE_NAMES[int(mode)]}, but the row "
                             f"describes '{row[described].strip()}', Table 3-3's mode {named} "
                             f"({MODE_NAMES[named]}): number the modes as Table 3-3 does",
                             source=str(path), line=ln, field="mode")
        for p, ij in cols.items():
            f = _number(row[ij["f"]], path, ln, header[ij["f"]]) if ij["f"] < len(row) else np.nan
            c = _number(row[ij["c"]], path, ln, header[ij["c"]]) if ij["c"] < len(row) else np.nan
            if np.isnan(f):
                continue
            if not f > 0 or not (np.isnan(c) or 0 <= c < 100):
                raise InputError(f"frequency must be positive and damping 0-100 %, got {f:g} Hz, {c:g} %",
                                 source=str(path), line=ln)
            out.append((int(mode), p, f, c / 100.0))
    table = pd.DataFrame(out, columns=["mode", "pressure", "frequency", "damping"])
    return ModalResults(str(path), use, note, table)


def read_static_cleat(path, cleat, direction="lateral", columns=None, units=None, use="held_out",
                      note="") -> StaticCleat:
    """A static cleat press (:class:`StaticCleat`); ``cleat`` (width, height) [m]."""
    data, lines, kind = read_test_columns(path, ("deflection", "load"), (), columns, units)
    check_finite(path, lines, kind, data, ("deflection", "load"))
    d, f = data["deflection"], data["load"]
    check_rows(path, lines, kind, d, d >= 0, "deflection {value:g} m is negative", "deflection")
    d, f, touch = _from_touch(d, f)
    return StaticCleat(str(path), use, note, d, f, tuple(cleat), direction, touch)


def _from_touch(d, f, *others):
    """``d`` counted from first touch (:func:`~tyrelab.fit.vertical.first_touch`): the ram's
    travel before the tyre met the plate or cleat taken off and its unloaded samples dropped,
    from ``f`` and ``others`` (None stays None) alike; last, the travel taken off [m]."""
    from .vertical import first_touch
    touch = first_touch(d, f)
    if not touch:
        return (d, f, *others, 0.0)
    keep = d >= touch
    return (d[keep] - touch, f[keep], *(None if o is None else o[keep] for o in others), touch)


def read_dynamic_cleat(path, use="held_out", note="", **options) -> DynamicCleat:
    """A trailer run over a cleat (:class:`DynamicCleat`): TYDEX, or a signal table tyrelab wrote."""
    from ..measure.io import read_run
    path = Path(path)
    if path.suffix.lower() not in (".tdx", ".csv", ".parquet"):
        raise InputError(f"a dynamic cleat run is a .tdx file (or a tyrelab signal table), got "
                         f"'{path.suffix}'", source=str(path))
    run = read_run(path)
    if "RUNTIME" not in run.columns or not ({"FZW", "FZ", "FZ_HUB"} & set(run.columns)):
        raise InputError("a dynamic cleat run needs RUNTIME and a vertical force (FZW, FZ or FZ_HUB)",
                         source=str(path))
    return DynamicCleat(str(path), use, note, run, **options)
