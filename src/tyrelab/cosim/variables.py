"""The variables of tyrelab's FMU: one table of names, units, causality and meaning.

The FMU's model description (:mod:`.slave`), docs/cosimulation.md and the
tests read these tuples; nothing else names an FMU variable. Names are the
signal table's TYDEX names (:data:`tyrelab.signal.CHANNELS`) where it has
one; every value is SI; positions and velocities are in the road frame; the
loads are those of the road on the tyre, with the sign convention written in
:mod:`tyrelab.signal`.

Each variable maps to a field of the stepping API's records
(:class:`~.kernel.WheelCentre` for the inputs, :class:`~.kernel.CentreLoads`
for the outputs) or to an argument of :func:`~.stepper.wheel_stepper` for
the parameters.
"""

from __future__ import annotations

from typing import NamedTuple

from ..signal import CHANNELS


class Variable(NamedTuple):
    """One FMU variable: its name, unit (FMI unit name, :data:`UNITS`), meaning and the
    record field (or stepper argument) it carries; ``kind`` is ``"Real"`` or ``"Integer"``."""

    name: str
    unit: str
    description: str
    field: str
    kind: str = "Real"


def _channel(name: str) -> str:
    """The signal table's description of a channel."""
    return CHANNELS[name][1]


#: what the host gives at each communication point: the wheel centre's pose, velocity and spin
INPUTS = (
    Variable("X_WC", "m", _channel("X_WC"), "x"),
    Variable("Y_WC", "m", _channel("Y_WC"), "y"),
    Variable("Z_WC", "m", _channel("Z_WC"), "z"),
    Variable("VX_WC", "m/s", _channel("VX_WC"), "vx"),
    Variable("VY_WC", "m/s", _channel("VY_WC"), "vy"),
    Variable("VZ_WC", "m/s", _channel("VZ_WC"), "vz"),
    Variable("ROTSPEED", "rad/s", _channel("ROTSPEED"), "omega"),
    Variable("INCLANGL", "rad", "inclination of the wheel plane to the road frame's z axis, positive "
             "when the wheel's top leans to its right (TYDEX INCLANGL on a level road)", "inclination"),
    Variable("YAW_WC", "rad", "heading of the wheel plane about the road frame's z axis, 0 along +x, "
             "positive to the left", "yaw"),
)



def _load(name: str, axis: str) -> str:
    """A wheel-centre load's description: the signal table's (C-axis), and the road frame's axis."""
    return f"{_channel(name)} (road-frame {axis} when OUTPUT_FRAME = 1)"


#: what the FMU gives back after each communication step (the loads over the step)
OUTPUTS = (
    Variable("FX", "N", _load("FX", "x"), "fx"),
    Variable("FY", "N", _load("FY", "y"), "fy"),
    Variable("FZ", "N", _load("FZ", "z"), "fz"),
    Variable("MX", "N.m", _load("MX", "x"), "mx"),
    Variable("MY", "N.m", _load("MY", "y"), "my"),
    Variable("MZ", "N.m", _load("MZ", "z"), "mz"),
    Variable("FXW", "N", _channel("FXW"), "fxw"),
    Variable("FYW", "N", _channel("FYW"), "fyw"),
    Variable("FZW", "N", _channel("FZW"), "fzw"),
    Variable("DEFLECT", "m", _channel("DEFLECT"), "deflection"),
    Variable("X_CP", "m", _channel("X_CP"), "px"),
    Variable("Y_CP", "m", _channel("Y_CP"), "py"),
    Variable("Z_CP", "m", _channel("Z_CP"), "pz"),
    Variable("LONGSLIP", "1", _channel("LONGSLIP"), "kappa"),
    Variable("SLIPANGL", "rad", _channel("SLIPANGL"), "alpha"),
    Variable("DMY_DROTSPEED", "N.m.s", "derivative of the C-axis MY (the moment about the spin axis) "
             "with respect to ROTSPEED, for integrating the spin implicitly (the ring's: its "
             "foundation's pull on the rim, which the ring's light rim needs)", "dmy_domega"),
)

#: set before initialisation (fixed); ``field`` names the argument of ``wheel_stepper``
PARAMETERS = (
    Variable("PRESSURE", "Pa", "inflation pressure; a built-in tyre measured at several pressures "
             "takes any pressure between them, an MF-Tyre 6.1/6.2 file with pressure terms any in its "
             "range, any other tyre file only its own", "pressure"),
    Variable("INITIAL_LOAD", "N", "static load at which the model's state starts in equilibrium on a "
             "flat road, rolling at the initial inputs' speed (the rigs' start); 0: unloaded",
             "load"),
    Variable("INTERNAL_STEP", "s", "longest internal step: each communication step runs "
             "ceil(step / INTERNAL_STEP) equal sub-steps; 0: the model's stable step", "max_step"),
    Variable("OUTPUT_FRAME", "", "frame of FX ... MZ: 0 the wheel's TYDEX C-axis system, 1 the road "
             "frame", "frame", "Integer"),
)

#: what the FMU works out for its host at initialisation (FMI calculated parameters, fixed from
#: then on); ``field`` names the :class:`~.stepper.WheelStepper` property that gives it
CALCULATED = (
    Variable("SPIN_INERTIA", "kg.m2", "spin inertia to turn the wheel with when integrating MY into "
             "ROTSPEED, as the rigs do: the wheel's (the tyre file's WHEEL_IYY), or for a model whose "
             "belt turns itself (the ring) the rim's, the wheel's less the tyre's own IYY",
             "spin_inertia"),
    Variable("CARRIED_MASS", "kg", "mass the model's own state moves (the ring's belt; 0 for the "
             "analytic models): its inertia is in the loads, so move the wheel centre with the "
             "wheel's mass less this (its weight stays the wheel's)", "carried_mass"),
)

#: set before initialisation, in an FMU with a terrain only (``export fmu --terrain``)
SOIL_PARAMETERS = (
    Variable("SOIL_GROUP", "", "instances in one process with the same SOIL_GROUP > 0 share one "
             "soil (a vehicle's wheels: the rear ones run in the front ones' ruts); 0: a soil of "
             "its own", "soil_group", "Integer"),
)

#: the values of OUTPUT_FRAME, by the name :func:`~.stepper.wheel_stepper` takes
OUTPUT_FRAMES = ("C-axis", "road")

#: FMI unit name -> exponents of the SI base units (the model description's UnitDefinitions)
UNITS = {
    "m": {"m": 1},
    "kg": {"kg": 1},
    "kg.m2": {"kg": 1, "m": 2},
    "m/s": {"m": 1, "s": -1},
    "rad": {"rad": 1},
    "rad/s": {"rad": 1, "s": -1},
    "N": {"kg": 1, "m": 1, "s": -2},
    "N.m": {"kg": 1, "m": 2, "s": -2},
    "N.m.s": {"kg": 1, "m": 2, "s": -1},
    "Pa": {"kg": 1, "m": -1, "s": -2},
    "s": {"s": 1},
    "1": {},
}
