"""The enveloping model's parameter record and its constants (:mod:`.enveloping`).

What the cams need, read once from the property file and the ground by
:func:`~.enveloping.enveloping_params`: the ``[CONTACT_PATCH]`` keys (the
module docstring of :mod:`.enveloping` lists them), the cam's tables
(:func:`~.cams.cam_tables`) and the ground's block bounds per row
(:meth:`~tyrelab.road.terrain.Ground.row_maxima`, which let a row of cams
skip road it cannot touch). Split from :mod:`.enveloping` to keep each file
short.
"""

from __future__ import annotations

from functools import partial
from typing import NamedTuple

import numpy as np

from ...limits import MAX_CAMS, SAMPLING_STEP, Bound, bounded_options
from ..params import Tyre

#: length of the ground's blocks whose bounds let cams skip road they cannot touch [m]
BLOCK = 0.05
#: default floor of the deflection that sizes the patch, a fraction of R0 (:mod:`.enveloping`)
MIN_PATCH_DEFLECTION = 0.015
_OTHER_OPTIONS = ("discs",)
#: the options a user sets, by type (tyrelab.tyre.registry.check_options)
_USER_OPTIONS = {"n_length": int, "n_width": int, "width_table": bool, "step": float,
                 "min_patch_deflection": float}

#: what the model must be given, measured (thesis chapter 4)
_DATA = ("load-deflection curve + contact-patch length and width vs load (footprints) + cam "
         "(ellipse) parameters from cleat tests")
#: the steps of ``tyrelab fit`` that identify it: the patch sizes the cams, the shape their sections
FIT_STEPS = ("vertical", "damping", "patch", "shape")
#: which cams make the effective plane: the whole grid, or only those on the patch's outline
CAM_LAYOUTS = ("grid", "outline")
#: the enveloping models' check of a tyre: the cams stand across its width
#: (:attr:`~tyrelab.tyre.registry.ContactModel.check_tyre`)
check_width = partial(Tyre.require_width, what="the enveloping model")


#: the bounded options of the enveloping models (``cam_option_values``)
CAM_BOUNDS = {"n_width": Bound("cams across the width", 1, MAX_CAMS, whole=True),
              "n_length": Bound("cams along the length", 1, MAX_CAMS, whole=True),
              "step": SAMPLING_STEP,
              "min_patch_deflection": Bound(None, 0.0, unit="m")}
#: the enveloping models' option values, checked (``ContactModel.check_values``)
cam_option_values = partial(bounded_options, bounds=CAM_BOUNDS)


def swift_coefficients(tyre) -> tuple[float, float]:
    """``(swift_c1, swift_c2)`` of :class:`EnvelopingParams` for ``tyre``: its vertical law's
    load over ``Cz = VERTICAL_STIFFNESS (1 + PFZ1 dpi)`` when the law is MF-Tyre 6.x's quadratic
    (:attr:`~tyrelab.tyre.params.Tyre.quadratic_in_use`); (1, 0) for the linear law, whose load over
    Cz is the deflection. A ``[DEFLECTION_LOAD_CURVE]`` law is taken as (1, 0) too (its load over
    Cz would need the table in the kernel)."""
    k1k2 = tyre.quadratic_in_use
    if k1k2 is None:
        return 1.0, 0.0
    cz = tyre.vertical_stiffness * tyre.pressure_factor
    return k1k2[0] / cz, k1k2[1] / cz


class EnvelopingParams(NamedTuple):
    """Parameters of the enveloping (tandem cams) contact model.

    Built by :func:`enveloping_params`; lengths in metres.

    * ``unloaded_radius`` R0, ``width`` the tyre width W;
    * ``length_law``: 0 eq. 2.3 (``length_c1, length_c2`` = PA1, PA2), 1
      MF-Swift (= Q_RA1, Q_RA2);
    * ``width_law``: 0 eq. 2.4 (``width_c1..3`` = PB1-PB3), 1 MF-Swift
      (= Q_RB1, Q_RB2, 0), 2 the table ``width_table``; the half width is
      clipped to ``max_half_width`` (W / 2);
    * ``cam_half_length`` a_e = PAE R0, ``cam_half_height`` b_e = PBE R0,
      ``cam_exponent`` PCE (eq. 2.5); ``base_length_factor`` PLS (eq. 2.6);
    * ``n_width`` x ``n_length`` cams; ``min_patch_deflection``: the patch
      is sized at no less than this deflection;
    * ``cam_reach``: how far from its centre a cam looks (a_e, less with
      ELLIPS_MAX_STEP); ``step``: sampling step along cam lines that do not
      run along x;
    * ``profile_road``: the ground does not vary across
      (:meth:`~tyrelab.road.terrain.Ground.uniform_across`), so every row of
      cams sees the same road;
    * ``cam_drop``, ``cam_window``, ``cam_touch``: the cam's tables
      (:func:`tyrelab.tyre.contact.cams.cam_tables`);
    * ``width_table``: (deflection, half width) rows, shape (rows, 2), empty
      unless ``width_law`` is 2;
    * ``block_per``: break lines per block, ``row_block_max``: the ground's
      bounds per block and row handle, shape (blocks, rows)
      (:meth:`~tyrelab.road.terrain.Ground.row_maxima`), empty when there is
      nothing to bound (a grid of two x nodes);
    * ``outline_only``: only the cams on the patch's outline enter the plane
      (:mod:`.enveloping_edge`); False: every cam;
    * ``swift_c1``, ``swift_c2``: the MF-Swift laws are written in ``Fz / (Cz R0)``, the
      load over the file's (pressure-corrected) stiffness (Besselink et al. 2010, eqs. 9 and
      10; MFeval's contact patch), so they take ``x = (swift_c1 rho + swift_c2 rho^2) / R0``:
      1 and 0 for a linear law (x = rho / R0), MF-Tyre 6.x's quadratic law over Cz
      (:func:`swift_coefficients`). The thesis laws (eqs. 2.3, 2.4) take ``rho / R0``.
    """

    unloaded_radius: float
    width: float
    min_patch_deflection: float
    length_law: int
    length_c1: float
    length_c2: float
    width_law: int
    width_c1: float
    width_c2: float
    width_c3: float
    max_half_width: float
    cam_half_length: float
    cam_half_height: float
    cam_exponent: float
    base_length_factor: float
    n_width: int
    n_length: int
    cam_reach: float
    step: float
    profile_road: bool
    cam_drop: np.ndarray
    cam_window: np.ndarray
    cam_touch: np.ndarray
    width_table: np.ndarray
    block_per: int
    row_block_max: np.ndarray
    outline_only: bool = False
    swift_c1: float = 1.0
    swift_c2: float = 0.0
