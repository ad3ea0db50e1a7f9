"""Deformable soil: parameters, files and the built-in library (:mod:`.params`)."""

from .params import Soil, load_soil, read_soil, soil_names  # noqa: F401
