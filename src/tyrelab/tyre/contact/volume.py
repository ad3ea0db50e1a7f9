"""3D equivalent volume contact (thesis 2.3.2, 4.3) -- placeholder until built.

Interface (kept by the implementation):

``volume_params(tyre, grid, **options) -> float64 array`` packs what the
kernel needs; ``volume_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo)``
(numba, cache=True) writes deflection, contact point and unit normal into
``geo`` like :func:`tyrelab.tyre.contact.point.point_contact`.
"""

import numba as nb
import numpy as np

from ...errors import InputError


def volume_params(tyre, grid, **options):
    raise InputError("the volume contact model is not available yet", field="model")


@nb.njit(cache=True)
def volume_contact(cp, gp, z, zinfo, cx, cy, cz, ax, ay, az, geo):
    geo[0] = -1.0
