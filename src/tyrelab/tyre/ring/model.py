"""Ring model parameters -- placeholder until built."""

from ...errors import InputError


def ring_params(tyre, grid, tread_pattern=False, **options):
    raise InputError("the ring model is not available yet", field="model")


def ring_initial_state(tyre, load, tread_pattern=False, **options):
    raise InputError("the ring model is not available yet", field="model")
