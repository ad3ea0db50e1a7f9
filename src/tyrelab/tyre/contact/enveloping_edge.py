"""The enveloping model as the thesis describes its ADAMS implementation (``enveloping-edge``).

Schmeitz spreads the cams over the patch,
and so does the ``enveloping`` model (``N_LENGTH`` over the base length, eq. 2.6, ``N_WIDTH``
over the width). The thesis describes the ADAMS implementation it ran otherwise:
"the cams were arranged on the outline of the contact patch" (4.4), "the road
input is only evaluated on the edges of the contact patch. Obstacles on the
inside of the contact patch were disregarded" (5.4) -- the cause it gives for
the model's failure on the tracks, amplified by the XZL's long patch. (The ADAMS
manual's words are that the cams' *shape* corresponds to the outside tyre
contour in the contact zone; what ADAMS did cannot be settled from the thesis.)
``cam_layout="outline"`` (the contact model ``enveloping-edge``) is the thesis's
description: the cams stand where they stand here, equally spaced, but only
those on the patch's outline enter the least-squares plane -- every cam of the
outer rows (at the patch's sides, ``N_LENGTH`` each) and the first and last cam
(at its leading and trailing edges) of every row between. A road that does not
vary across (a perpendicular cleat, the bump) looks alike from every row, so
there the outline weighs the front and rear cams more than the grid does; on a
3D road (the Belgian paving, an oblique cleat) the inside of the patch is not
seen. It runs in the built-in campaign beside the grid model as the thesis's
"3D ENV" (docs/consistency.md).

Cost: the rows between the outer two rest only their first and last cam
(:func:`~.enveloping_plane.cam_plane`), so on a 3D road the model rests 46 of the XZL's
150 cams and costs about half the grid model's time (the built-in campaign's 40 runs:
23.5 s against 49.3 s, 2026-11-27); on a road that does not vary across both rest one row.
"""

from __future__ import annotations

from ...errors import InputError
from ..registry import ContactModel, register_contact
from .enveloping import enveloping_contact, enveloping_params
from .enveloping_params import (_DATA, _USER_OPTIONS, FIT_STEPS, EnvelopingParams, cam_option_values,
                                check_width)


def edge_params(tyre, grid, **options) -> EnvelopingParams:
    """The enveloping model's record with the road evaluated on the patch's outline only
    (module docstring)."""
    if options.get("cam_layout", "outline") != "outline":
        raise InputError("the edge enveloping model evaluates the road on the patch's outline; "
                         "for every cam use the model 'enveloping'", field="cam_layout")
    return enveloping_params(tyre, grid, **{**options, "cam_layout": "outline"})


register_contact(ContactModel("enveloping-edge", EnvelopingParams, edge_params,
                              geometry=enveloping_contact,
                              summary="3D enveloping contact with the road evaluated on the "
                                      "patch's edges only, as the thesis describes its ADAMS "
                                      "model (5.4)",
                              options=_USER_OPTIONS, cost=0.011,
                              parameterization=_DATA + " (the cams on the patch's edges only)",
                              fit_steps=FIT_STEPS, terrains=("rigid", "soil"),
                              check_values=cam_option_values, check_tyre=check_width))
