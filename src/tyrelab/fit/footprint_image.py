"""Footprint bitmaps: length, width, area and outline of a contact patch (thesis 3.3.3).

The thesis photographs the patch through a glass plate and prepares each
image as a black-and-white bitmap -- the contact black on white -- scaled by a
line of known length (100 mm) that does not touch the patch; FTire/fit takes
that line in red. Both are read here:

* a red calibration line (red pixels: R > 0.5, G and B < 0.35) anywhere;
* in a pure black-and-white image, the line is the dark connected region
  (8-connected) that is longest for its thickness (at least 8 times longer
  than thick); everything else dark, bar specks (regions of fewer than
  ``min_pixels`` or than 0.05 % of the dark pixels), is the patch (tread
  blocks need not touch each other).

Scale: the line's extent along its own principal axis, ``s = L_line /
n_pixels`` [m per pixel]. The patch's length is its extent along the
direction of travel (``travel``: the image's vertical or horizontal axis),
its width the extent across, both in whole pixels times ``s``; its area the
dark pixels times ``s^2`` (the net, inked area) and, for the gross area, the
area inside the outline: the convex hull of the patch's pixel corners.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..errors import InputError

#: a dark region at least this many times longer than thick may be the calibration line
LINE_ASPECT = 8.0
#: dark regions smaller than this share of all dark pixels (or than ``min_pixels``) are specks
SPECK = 5e-4
TRAVELS = ("vertical", "horizontal")


class Footprint(NamedTuple):
    """A measured footprint (SI)."""

    #: extent along the direction of travel and across it [m]
    length: float
    width: float
    #: dark (inked) area and the area inside the outline [m^2]
    area: float
    gross_area: float
    #: closed outline, (k, 2) of (x along travel, y across) [m] about the patch's centre
    outline: np.ndarray
    #: metres per pixel, and the calibration line's length in pixels
    scale: float
    line_pixels: float
    #: the patch's centre in the image (row, column) [pixels]
    centre: tuple = (0.0, 0.0)
    #: the patch's own travel axis turned from the image's [rad] (row, column order; the
    #: outline and the extents are along the patch's axes)
    angle: float = 0.0


def read_bitmap(path) -> np.ndarray:
    """An image file as an ``(rows, columns, 3)`` float array in [0, 1] (matplotlib's reader)."""
    import matplotlib.image as mpimg
    try:
        img = mpimg.imread(str(path))
    except (OSError, ValueError, SyntaxError) as exc:
        raise InputError(f"not a readable image ({exc})", source=str(path)) from None
    img = np.asarray(img, float)
    if img.dtype.kind in "iu" or img.max() > 1.0:  # 8-bit formats read as 0-255
        img = img / 255.0
    if img.ndim == 2:
        img = np.repeat(img[:, :, None], 3, axis=2)
    if img.ndim != 3 or img.shape[2] < 3:
        raise InputError(f"expected a grey or colour image, got an array of shape {img.shape}",
                         source=str(path))
    return img[:, :, :3]


def _principal_extent(rows, cols):
    """Extent [pixels] of a set of pixels along its principal axis (a pixel spans
    |cos| + |sin| of a unit square along a direction)."""
    pts = np.column_stack([cols, rows]).astype(float)
    centred = pts - pts.mean(axis=0)
    if len(pts) < 2:
        return 1.0, 1.0
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    axis = vt[0]
    along = centred @ axis
    across = centred @ vt[1] if vt.shape[0] > 1 else np.zeros(len(pts))
    spread = abs(axis[0]) + abs(axis[1])
    return float(np.ptp(along) + spread), float(np.ptp(across) + spread)


def calibration_scale(line_mask, line_length=0.1, source=None) -> tuple[float, float]:
    """``(metres per pixel, line length in pixels)`` of a calibration line's pixels.

    The length runs along the line's principal axis over the stretch where the
    line has at least half its median thickness, so a speck stuck to an end
    does not lengthen it."""
    rows, cols = np.nonzero(line_mask)
    if rows.size < 2:
        raise InputError("no calibration line found (a red line, or a thin dark line apart from "
                         "the patch)", source=source, field="calibration")
    pts = np.column_stack([cols, rows]).astype(float)
    centred = pts - pts.mean(axis=0)
    axis = np.linalg.svd(centred, full_matrices=False)[2][0]
    along = centred @ axis
    counts = np.bincount(np.round(along - along.min()).astype(int))
    full = np.flatnonzero(counts >= 0.5 * np.median(counts[counts > 0]))
    pixels = float(full[-1] - full[0]) + abs(axis[0]) + abs(axis[1])
    return line_length / pixels, pixels


def split_line(dark, red, min_pixels=4, source=None):
    """``(patch mask, line mask)`` of an image's dark and red pixels (module docstring)."""
    from scipy import ndimage
    labels, n = ndimage.label(dark, structure=np.ones((3, 3), bool))
    sizes = ndimage.sum(dark, labels, index=np.arange(1, n + 1))
    min_pixels = max(min_pixels, SPECK * float(dark.sum()))
    if red.sum() >= 2:
        line = red
        keep = np.r_[False, sizes >= min_pixels]
        patch = keep[labels]
    else:
        if n < 2:
            raise InputError("the image holds one dark region only: the patch and the calibration "
                             "line must not touch (thesis 3.3.3), or draw the line in red",
                             source=source, field="calibration")
        best, best_aspect = 0, 0.0
        for k, box in enumerate(ndimage.find_objects(labels), start=1):
            if sizes[k - 1] < max(min_pixels, 2):
                continue
            rows, cols = np.nonzero(labels[box] == k)
            length, thick = _principal_extent(rows, cols)
            aspect = length / max(thick, 1.0)
            if aspect > best_aspect:
                best, best_aspect = k, aspect
        if best_aspect < LINE_ASPECT:
            raise InputError(f"no calibration line: no dark region is {LINE_ASPECT:g} times longer than "
                             "thick (draw it apart from the patch, or in red)", source=source,
                             field="calibration")
        line = labels == best
        keep = np.zeros(n + 1, bool)
        keep[1:] = sizes >= min_pixels
        keep[best] = False
        patch = keep[labels]
    if patch.sum() == 0:
        raise InputError("no contact patch (no dark pixels besides the calibration line)", source=source)
    return patch, line


def _extremes(a, b):
    """For each value of ``a``, the smallest and largest ``b``: ``(a values, b values)``."""
    order = np.lexsort((b, a))
    a, b = a[order], b[order]
    first = np.r_[True, a[1:] != a[:-1]]
    last = np.r_[a[1:] != a[:-1], True]
    return np.r_[a[first], a[last]], np.r_[b[first], b[last]]


def _outline(patch):
    """Convex hull [pixels] of the corners of the patch's outermost pixels (per row and column):
    ``(closed ring of (row, column), area)``."""
    from scipy.spatial import ConvexHull
    rows, cols = np.nonzero(patch)
    r1, c1 = _extremes(rows, cols)
    c2, r2 = _extremes(cols, rows)
    pts = np.unique(np.column_stack([np.r_[r1, r2], np.r_[c1, c2]]), axis=0).astype(float)
    corners = np.vstack([pts + [dr, dc] for dr in (-0.5, 0.5) for dc in (-0.5, 0.5)])
    hull = ConvexHull(corners)
    ring = corners[hull.vertices]
    return np.vstack([ring, ring[:1]]), float(hull.volume)


def _image_axis(travel: str) -> np.ndarray:
    """The image's travel axis as a (row, column) unit vector."""
    return np.array([1.0, 0.0]) if travel == "vertical" else np.array([0.0, 1.0])


def _across(along: np.ndarray, travel: str) -> np.ndarray:
    """The axis across ``along``: the column axis for vertical travel, the row axis for
    horizontal, turned alike."""
    return np.array([-along[1], along[0]]) if travel == "vertical" else np.array([along[1], -along[0]])


def patch_axes(ring, travel="vertical"):
    """The patch's own axes from its outline ``ring`` ((row, column) points [pixels]): the
    smallest-area rectangle around it (rotating calipers: one side lies on a hull edge),
    ``(along, across)`` unit vectors in (row, column), ``along`` the rectangle's axis nearest
    the image's travel axis. A print photographed turned on the glass keeps its length and
    width; a patch square to the image gets the image's axes exactly."""
    pts = np.asarray(ring, float)
    image_axis = _image_axis(travel)
    best, axes = np.inf, None
    for e in np.diff(pts, axis=0):
        n = float(np.hypot(*e))
        if n == 0:
            continue
        u = e / n
        v = np.array([-u[1], u[0]])
        area = float(np.ptp(pts @ u) * np.ptp(pts @ v))
        if area < best * (1 - 1e-12):
            best, axes = area, (u, v)
    u, v = axes
    along = u if abs(u @ image_axis) >= abs(v @ image_axis) else v
    along = along if along @ image_axis >= 0 else -along
    if abs(abs(along @ image_axis) - 1.0) < 1e-12:   # square to the image: its axes exactly
        along = image_axis
    return along, _across(along, travel)


def outline_in_image(fp: Footprint, travel="vertical"):
    """The outline of ``fp`` back in its image: ``(rows, columns)`` [pixels]."""
    turn = np.array([[np.cos(fp.angle), -np.sin(fp.angle)], [np.sin(fp.angle), np.cos(fp.angle)]])
    along = turn @ _image_axis(travel)
    o = fp.outline / fp.scale
    pts = np.asarray(fp.centre) + o[:, :1] * along + o[:, 1:] * _across(along, travel)
    return pts[:, 0], pts[:, 1]


def measure_footprint(image, line_length=0.1, travel="vertical", threshold=0.5, min_pixels=4,
                      source=None) -> Footprint:
    """Length, width, area and outline of the patch in an image array (module docstring).

    Parameters
    ----------
    image : ndarray
        ``(rows, columns, 3)`` in [0, 1] (:func:`read_bitmap`).
    line_length : float
        True length of the calibration line [m] (thesis: 100 mm).
    travel : {"vertical", "horizontal"}
        The image axis along the wheel's direction of travel.
    threshold : float
        Grey level below which a pixel is contact.
    """
    if travel not in TRAVELS:
        raise InputError(f"travel must be one of {', '.join(TRAVELS)}, got '{travel}'", field="travel")
    img = np.asarray(image, float)
    grey = img.mean(axis=2)
    red = (img[:, :, 0] > 0.5) & (img[:, :, 1] < 0.35) & (img[:, :, 2] < 0.35)
    dark = (grey < threshold) & ~red
    patch, line = split_line(dark, red, min_pixels, source)
    scale, pixels = calibration_scale(line, line_length, source)
    ring, hull_area = _outline(patch)
    along, across = patch_axes(ring, travel)
    a, c = ring @ along, ring @ across      # the outline (pixel corners) on the patch's axes
    mid_a, mid_c = 0.5 * (a.min() + a.max()), 0.5 * (c.min() + c.max())
    centre = mid_a * along + mid_c * across
    outline = np.column_stack([a - mid_a, c - mid_c]) * scale     # (along travel, across)
    image_axis = _image_axis(travel)
    angle = float(np.arctan2(image_axis[0] * along[1] - image_axis[1] * along[0], image_axis @ along))
    return Footprint(float(np.ptp(a)) * scale, float(np.ptp(c)) * scale,
                     float(patch.sum()) * scale ** 2, hull_area * scale ** 2, outline, scale, pixels,
                     (float(centre[0]), float(centre[1])), angle)


def read_footprint_image(path, line_length=0.1, travel="vertical", threshold=0.5) -> Footprint:
    """:func:`measure_footprint` of an image file (PNG; other formats as matplotlib reads them)."""
    return measure_footprint(read_bitmap(path), line_length, travel, threshold, source=str(path))


def render_footprint(inside, length, width, scale=0.001, line_length=0.1, margin=0.05,
                     red_line=False) -> np.ndarray:
    """A black-and-white footprint bitmap as the thesis prepares them (for tests and examples).

    ``inside(x, y)`` says, for arrays of points [m] about the patch centre (x
    along travel, drawn vertically), which are in contact; the patch spans at
    most ``length`` x ``width`` [m]; ``scale`` is metres per pixel; a
    horizontal calibration line of ``line_length`` [m], 3 pixels thick, is
    drawn below the patch (in red with ``red_line``).
    """
    rows = int(np.ceil((length + 3 * margin) / scale))
    cols = int(np.ceil((max(width, line_length) + 2 * margin) / scale))
    r, c = np.mgrid[0:rows, 0:cols]
    x = (r + 0.5) * scale - (margin + 0.5 * length)
    y = (c + 0.5) * scale - 0.5 * cols * scale
    img = np.ones((rows, cols, 3))
    img[np.asarray(inside(x, y), bool)] = 0.0
    n = int(round(line_length / scale))
    r0 = int(round((2 * margin + length) / scale))
    c0 = (cols - n) // 2
    img[r0:r0 + 3, c0:c0 + n] = (1.0, 0.0, 0.0) if red_line else 0.0
    return img


def write_bitmap(path, image) -> None:
    """Write an image array as a PNG (atomically, :mod:`tyrelab.io_atomic`)."""
    import matplotlib.image as mpimg

    from ..io_atomic import atomic_write
    atomic_write(path, lambda tmp: mpimg.imsave(tmp, np.clip(image, 0.0, 1.0), format="png"))
