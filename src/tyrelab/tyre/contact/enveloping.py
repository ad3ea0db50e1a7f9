"""3D enveloping contact, Schmeitz tandem cams (thesis 2.3.3, 4.4) -- placeholder until built.

Interface (kept by the implementation):

``enveloping_params(tyre, grid, **options) -> float64 array`` packs what the
kernel needs; ``enveloping_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)``
(numba, cache=True) writes deflection, contact point and unit normal into
``geo`` like :func:`tyrelab.tyre.contact.point.point_contact`.
"""

import numba as nb
import numpy as np

from ...errors import InputError


def enveloping_params(tyre, grid, **options):
    raise InputError("the enveloping contact model is not available yet", field="model")


@nb.njit(cache=True)
def enveloping_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    geo[0] = -1.0
