"""tyrelab's wheel as an FMI 2.0 co-simulation slave (pythonfmu's ``Fmi2Slave``).

The FMU that :func:`tyrelab.cosim.fmu.export_fmu` writes holds a short
script importing :class:`TyrelabWheel` (and calling :func:`hold_namespace`),
the manifest and data of :mod:`.manifest`, and pythonfmu's binary, which runs
this class in the Python of the process that loads the FMU (a Python host
such as FMPy) or in the preloaded libpython it initialises. So the host needs
a Python 3 with tyrelab installed; the FMU carries no Python of its own.

At ``exitInitializationMode`` the instance builds its wheel
(:func:`.manifest.build_stepper`: the parameters, and the initial inputs'
speed for the equilibrium), and publishes the loads of the initial state at
the initial inputs; each ``doStep(t, h)`` is one
:meth:`~.stepper.WheelStepper.step` from the inputs at ``t``, the outputs
being the loads over ``[t, t + h]``. Variables: :mod:`.variables`.
"""

from __future__ import annotations

import atexit
import gc
import math
from xml.etree.ElementTree import Element, SubElement

from pythonfmu import DefaultExperiment, Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real
from pythonfmu.enums import Fmi2Status

from .._version import __version__
from ..errors import InputError
from .kernel import WheelCentre
from .manifest import build_stepper, read_manifest
from .variables import CALCULATED, INPUTS, OUTPUT_FRAMES, OUTPUTS, PARAMETERS, SOIL_PARAMETERS, UNITS


def leave_objects_to_the_exit():
    """Collect nothing more once the interpreter is ending (registered with :mod:`atexit`).

    A host without a Python of its own (a C program with libpython preloaded) has pythonfmu's
    binary end the interpreter, in that binary's own thread, when the FMU is unloaded at the
    host's exit. The final garbage collection of that shutdown cleared scipy's ``_uarray``
    objects and freed memory twice: the host died of SIGSEGV after its last step in about one
    run in five (``tests/test_cosim_fmu.py``; 0 in 110 with this, 4 in 20 without, 2026-11-27).
    Frozen, the objects are left to the operating system, as any process's exit leaves
    them; Python does not promise finalizers of objects alive at exit either."""
    gc.freeze()


atexit.register(leave_objects_to_the_exit)

#: the communication step the model description suggests [s]: the rigs' default step
SUGGESTED_STEP = 1e-3


def host_requirements(version: str = __version__) -> str:
    """What a host needs to run the FMU, in words (the model description and the docs say it)."""
    return (f"Needs a Python 3 with tyrelab {version} installed (pip install tyrelab) in the process "
            "that loads the FMU: a Python host (FMPy, OMSimulator's Python API) runs it in its own "
            "interpreter; any other host must have that Python's libpython loaded "
            "(Linux: LD_PRELOAD=.../libpython3.X.so) and find its standard library and tyrelab "
            "(PYTHONHOME, PYTHONPATH).")


class TyrelabWheel(Fmi2Slave):
    """A tyrelab tyre model on its road, stepped by the FMU's host (pythonfmu slave)."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        manifest = read_manifest(self.resources)
        self._manifest = manifest
        self._stepper = None
        self._start_time = 0.0
        tyre = manifest["tyre"]
        self.modelName = _identifier(f"tyrelab_{manifest['model']}")
        self.author = "tyrelab"
        self.version = manifest["tyrelab"]
        road = manifest["road"].get("spec") or manifest["road"]["file"]
        terrain = manifest.get("terrain")
        if terrain is not None:  # soil laid over the road round the wheel's start
            road += f" under {terrain.get('spec') or terrain['file']} (round the wheel's start)"
        self.description = (f"tyrelab {manifest['tyrelab']}: tyre {tyre['file']} "
                            f"({_kpa(tyre['pressure'])}), contact model {manifest['model']}, "
                            f"handling {manifest['handling']}, road {road}. SI units; road frame "
                            "x along the road, y left, z up; loads of the road on the tyre "
                            "(TYDEX C-axis, tyrelab.signal). " + host_requirements(manifest["tyrelab"]))
        self.default_experiment = DefaultExperiment(start_time=0.0, step_size=SUGGESTED_STEP)
        for v in INPUTS:
            # start: at rest, level, heading +x, the centre where the vertical law carries the
            # initial load on a level road at z = 0
            setattr(self, v.name, float(manifest["z_start"]) if v.field == "z" else 0.0)
            self.register_variable(Real(v.name, causality=Fmi2Causality.input,
                                        variability=Fmi2Variability.continuous,
                                        description=v.description))
        for v in OUTPUTS:
            setattr(self, v.name, 0.0)
            self.register_variable(Real(v.name, causality=Fmi2Causality.output,
                                        variability=Fmi2Variability.continuous,
                                        description=v.description))
        starts = {"pressure": tyre["pressure"] or 0.0, "load": manifest["load"],
                  "max_step": manifest["internal_step"],
                  "frame": OUTPUT_FRAMES.index(manifest["frame"]), "soil_group": 0}
        for v in CALCULATED:   # worked out at initialisation (exit_initialization_mode)
            setattr(self, v.name, 0.0)
            self.register_variable(Real(v.name, causality=Fmi2Causality.calculatedParameter,
                                        variability=Fmi2Variability.fixed,
                                        description=v.description))
        for v in PARAMETERS + (SOIL_PARAMETERS if terrain is not None else ()):
            kind = Integer if v.kind == "Integer" else Real
            setattr(self, v.name, starts[v.field])
            self.register_variable(kind(v.name, causality=Fmi2Causality.parameter,
                                        variability=Fmi2Variability.fixed, description=v.description))

    # --- the FMI calls --------------------------------------------------------------------

    def setup_experiment(self, start_time, stop_time=None, tolerance=None):
        self._start_time = float(start_time)

    def exit_initialization_mode(self):
        frame = int(self.OUTPUT_FRAME)
        if frame not in range(len(OUTPUT_FRAMES)):
            raise InputError(f"OUTPUT_FRAME {frame}: expected 0 (C-axis) or 1 (road frame)",
                             field="OUTPUT_FRAME")
        centre = self._centre()
        speed = centre.vx * math.cos(centre.yaw) + centre.vy * math.sin(centre.yaw)
        self._stepper = build_stepper(self.resources, self._manifest, float(self.PRESSURE),
                                      float(self.INITIAL_LOAD), float(self.INTERNAL_STEP),
                                      OUTPUT_FRAMES[frame], speed, self._start_time,
                                      x_start=centre.x, y_start=centre.y,
                                      soil_group=int(getattr(self, "SOIL_GROUP", 0)))
        # a wheel the host puts below the road or onto its rim: a warning in the host's log
        self._stepper.warn = lambda message: self.log(message, Fmi2Status.warning)
        for v in CALCULATED:
            setattr(self, v.name, float(getattr(self._stepper, v.field)))
        self._publish(self._stepper.loads(centre))

    def do_step(self, current_time, step_size):
        self._publish(self._stepper.step(current_time, self._centre(), step_size))
        return True

    def terminate(self):
        self._stepper = None

    # --- between the FMI variables and the stepping API's records ------------------------

    def _centre(self) -> WheelCentre:
        return WheelCentre(**{v.field: float(getattr(self, v.name)) for v in INPUTS})

    def _publish(self, loads) -> None:
        for v in OUTPUTS:
            setattr(self, v.name, getattr(loads, v.field))

    def to_xml(self, model_options=None) -> Element:
        """pythonfmu's model description plus what it leaves out: the unit of every real
        variable (UnitDefinitions) and the outputs and calculated parameters as initial
        unknowns (calculated at initialisation from the inputs and parameters)."""
        root = super().to_xml(model_options or {})
        units = Element("UnitDefinitions")  # after CoSimulation, as the schema orders them
        for name, exponents in UNITS.items():
            unit = SubElement(units, "Unit", {"name": name})
            if exponents:
                SubElement(unit, "BaseUnit", {k: str(e) for k, e in exponents.items()})
        root.insert(list(root).index(root.find("CoSimulation")) + 1, units)
        unit_of = {v.name: v.unit for v in INPUTS + OUTPUTS + PARAMETERS + CALCULATED if v.unit}
        for sv in root.find("ModelVariables"):
            real = sv.find("Real")
            if real is not None and sv.get("name") in unit_of:
                real.set("unit", unit_of[sv.get("name")])
        structure = root.find("ModelStructure")
        initial = SubElement(structure, "InitialUnknowns")
        calculated = {v.name for v in CALCULATED}
        indices = {unknown.get("index") for unknown in structure.find("Outputs")}
        indices |= {str(k) for k, sv in enumerate(root.find("ModelVariables"), 1)
                    if sv.get("name") in calculated}
        for index in sorted(indices, key=int):   # outputs and calculated parameters, in order
            SubElement(initial, "Unknown", {"index": index})
        return root


#: pythonfmu releases whose binary, making an instance, runs the slave script's code in its
#: module's namespace and then releases a reference to that namespace which it does not own
#: (``findClass``: ``Py_DECREF`` of the borrowed ``PyModule_GetDict``; in its sources from 0.6.5,
#: Sep 2024, to 0.7.0). A namespace with one reference is freed at the first instance while the
#: module still uses it: the next instance finds no slave class, or the process crashes at its
#: next garbage collection (both seen with FMPy)
FINDCLASS_DECREF = ((0, 6, 5), (0, 7, 0))


def hold_namespace(namespace: dict, packed_by: str) -> None:
    """Take the reference that pythonfmu's binary will release from the slave script's namespace
    (:data:`FINDCLASS_DECREF`). The script calls this each time its code runs, which the binary
    does before each release (once more at the first import: one reference too many, kept)."""
    import ctypes

    try:
        release = tuple(int(p) for p in packed_by.split(".")[:3])
    except ValueError:
        return
    if FINDCLASS_DECREF[0] <= release <= FINDCLASS_DECREF[1]:
        ctypes.pythonapi.Py_IncRef(ctypes.py_object(namespace))


def _identifier(text: str) -> str:
    """A C identifier (the FMI modelIdentifier) from ``text``."""
    out = "".join(c if c.isalnum() or c == "_" else "_" for c in text)
    return out if not out[0].isdigit() else "_" + out


def _kpa(pressure) -> str:
    return "pressure not stated" if pressure is None else f"{pressure / 1e3:g} kPa"
