"""Co-simulation: a tyrelab wheel stepped by the user's vehicle model, in Python or as an FMU.

* :mod:`.stepper` -- the stepping API: :func:`wheel_stepper` builds a
  :class:`WheelStepper` from a tyre, a contact model and a road;
  ``step(time, WheelCentre(...), dt)`` returns the :class:`CentreLoads`.
* :mod:`.kernel` -- its compiled step (the rigs' :func:`~tyrelab.tyre.wheel.wheel_step`,
  sub-stepped) and the records that cross it.
* :mod:`.variables` -- the FMU's variables: names, units, causality.
* :mod:`.fmu` -- :func:`export_fmu`: an FMI 2.0 co-simulation FMU (pythonfmu), the
  tyre's data and the road file inside; :mod:`.slave` is its slave class.

docs/cosimulation.md has the variables, frames, sign conventions and examples.
"""

from .kernel import CentreLoads, WheelCentre
from .stepper import WheelStepper, wheel_stepper

__all__ = ["CentreLoads", "WheelCentre", "WheelStepper", "wheel_stepper"]
