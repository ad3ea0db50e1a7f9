"""The flexible ring tyre model (FTire class): belt segments, tread blocks.

See ``docs/ring.md`` for the equations. Public entry points: the records
:class:`~.records.RingParams` and :class:`~.records.RingState`,
:func:`~.model.ring_params`, :func:`~.model.ring_initial_state`, the
compiled step :func:`~.kernel.ring_step` (behind
:func:`tyrelab.tyre.wheel.wheel_step`; the models "ring" and "ring-tp"
register in :mod:`.model`), :func:`~.static.settle` (static states),
:func:`~.modal.ring_modal`, :class:`~.parameters.RingParameters`. The static
press, footprint and rolling test are the rigs' (:mod:`tyrelab.rig`), as for
every model.
"""

from .parameters import RingParameters, ring_parameters  # noqa: F401
