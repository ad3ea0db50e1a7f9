"""The flexible ring tyre model (FTire class): belt segments, tread blocks.

See ``docs/ring.md`` for the equations. Public entry points:
:func:`~.model.ring_params`, :func:`~.model.ring_initial_state`,
:func:`~.kernel.ring_wheel_force`, :func:`~.static.ring_static_press`,
:func:`~.static.ring_footprint`, :func:`~.modal.ring_modal`,
:class:`~.parameters.RingParameters`.
"""

from .parameters import RingParameters, ring_parameters  # noqa: F401
