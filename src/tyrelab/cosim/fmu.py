"""Export a tyrelab wheel as an FMI 2.0 co-simulation FMU, built with pythonfmu.

>>> from tyrelab.cosim.fmu import export_fmu
>>> export_fmu("tyre.fmu", tyre="xzl-16.00R20", model="ring", road="cleat:50x50")  # doctest: +SKIP

The FMU (FMI 2.0, co-simulation) is packed by pythonfmu (PyPI), which
supplies the FMI binary and calls the slave class
:class:`~.slave.TyrelabWheel`; inside are the tyre's data and the road file
(:mod:`.manifest`). Its variables are :mod:`.variables`: inputs ``X_WC``,
``Y_WC``, ``Z_WC``, ``VX_WC``, ``VY_WC``, ``VZ_WC``, ``ROTSPEED``,
``INCLANGL``, ``YAW_WC``; outputs ``FX`` ... ``MZ`` at the wheel centre,
``FZW``, ``DEFLECT`` and more; parameters ``PRESSURE``, ``INITIAL_LOAD``,
``INTERNAL_STEP``, ``OUTPUT_FRAME``. The host needs a Python 3 with tyrelab
installed (:func:`.slave.host_requirements`; docs/cosimulation.md).
"""

from __future__ import annotations

import shutil
import sys
import tempfile
from pathlib import Path

from ..api import make_tyre_model
from ..errors import InputError
from ..tyre.library import DEFAULT_TYRE
from .manifest import DATA, terrain_file, write_data
from .stepper import rigid_ground
from .variables import OUTPUT_FRAMES

#: the slave script inside the FMU (its module name is the file's stem): it only names the class
SCRIPT_NAME = "tyrelab_wheel.py"
SCRIPT = '''"""tyrelab's wheel as an FMI 2.0 co-simulation slave (pythonfmu {version}).

The class is tyrelab.cosim.slave.TyrelabWheel: the Python that runs this FMU needs
tyrelab installed (see the model description's text).
"""
from tyrelab.cosim.slave import TyrelabWheel, hold_namespace  # noqa: F401

hold_namespace(globals(), "{version}")  # see tyrelab.cosim.slave.FINDCLASS_DECREF
'''


def _inputs(tyre, road, terrain=None) -> list[Path]:
    """The files the export reads (the output must not be one of them)."""
    from ..road.formats import road_file
    soil = terrain_file(terrain)
    out = [] if soil is None else [soil]
    if isinstance(tyre, (str, Path)) and Path(str(tyre)).suffix.lower() in (".tir", ".json"):
        out.append(Path(str(tyre)))
    named = road_file(road) if isinstance(road, str) else None
    if named is not None:
        out.append(Path(named[1]))
    return out


def export_fmu(path, tyre=DEFAULT_TYRE, model: str = "point", road: str = "flat", *,
               pressure: float | None = None, stiffness: str | None = None,
               handling: str | None = None, options: dict | None = None, load=0.0,
               frame: str = "C-axis", internal_step: float = 0.0, terrain=None,
               relaxation="auto") -> Path:
    """Write an FMI 2.0 co-simulation FMU of a tyre model on a road; returns its path.

    Parameters
    ----------
    path : str or Path
        The ``.fmu`` file to write (whole or not at all: :mod:`tyrelab.io_atomic`).
    tyre : str
        Built-in tyre name or a ``.tir`` / Chrono ``.json`` file (copied into the FMU).
    model : str
        Contact model (``point``, ``volume``, ``enveloping``, ``ring``, ...).
    road : str
        A road name (``cleat:50x50``, ``flat``, a track) or a road file
        ``FILE.crg|.rdf|.obj[@V]`` (copied into the FMU).
    pressure, stiffness, handling, options, relaxation
        As :func:`tyrelab.api.make_tyre_model`; ``options`` must be numbers,
        true/false or texts.
    load : str or float
        Default of the ``INITIAL_LOAD`` parameter [N] (or a load case, ``"LC1"``):
        the static load at which the model's state starts in equilibrium.
    frame : {"C-axis", "road"}
        Default of ``OUTPUT_FRAME``: the frame of ``FX`` ... ``MZ``.
    internal_step : float
        Default of ``INTERNAL_STEP`` [s]; 0: the model's stable step.
    terrain : str, optional
        A soil laid over the road (``--terrain``: a built-in soil's name or a soil
        ``.toml`` file, copied into the FMU), round the wheel's position at
        initialisation: a window of it that follows the wheel anywhere, shared by the
        instances of one ``SOIL_GROUP`` in a process (docs/cosimulation.md).

    Raises
    ------
    InputError
        An unknown tyre, model, road or option, an impossible number, an output
        that cannot be written; nothing is written then.
    """
    from .. import limits
    from ..io_atomic import atomic_write, check_output_path

    out = check_output_path(path, (".fmu",), field="output", inputs=_inputs(tyre, road, terrain))
    tm = make_tyre_model(tyre, model, pressure, stiffness, handling, options, relaxation)
    if frame not in OUTPUT_FRAMES:
        raise InputError(f"unknown frame '{frame}', expected one of {', '.join(OUTPUT_FRAMES)}",
                         field="frame")
    if isinstance(load, str):
        from ..rig.trailer import load_case_wheel_load
        load = load_case_wheel_load(load)
    load = float(load)
    if load != 0.0:
        load = limits.check_wheel_load(load, tm.tyre)
    internal_step = limits.check_number(internal_step, "internal_step", 0.0, limits.MAX_DT, "s",
                                        what="internal step")
    if not isinstance(road, str):
        raise InputError("give the road by its name or file to put it in an FMU", field="road")
    if terrain is None:
        tm.contact_params(rigid_ground(tm, road))  # the model builds on this road
    else:  # the model runs on this ground (a short stretch is laid to check it)
        from ..rig.soil_ground import lay_terrain
        from ..road.spec import road_from_spec
        tm.contact_params(lay_terrain(tm, terrain, road_from_spec(road), 0.0, 1.0)[0])
    from pythonfmu import FmuBuilder
    from pythonfmu import __version__ as pythonfmu_version

    with tempfile.TemporaryDirectory(prefix="tyrelab-fmu-") as tmp:
        folder = Path(tmp) / DATA
        folder.mkdir()
        write_data(folder, tm, tyre, road, load, frame, internal_step, terrain)
        script = Path(tmp) / SCRIPT_NAME
        script.write_text(SCRIPT.format(version=pythonfmu_version), encoding="utf-8")
        try:
            built = FmuBuilder.build_FMU(script, dest=Path(tmp) / "built.fmu", project_files=[folder])
        finally:  # the builder leaves its script's folder on sys.path and the module imported
            while tmp in sys.path:
                sys.path.remove(tmp)
            sys.modules.pop(script.stem, None)
        atomic_write(out, lambda target: shutil.copyfile(built, target), field="output")
    return out
