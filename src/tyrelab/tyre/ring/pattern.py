"""Tread-block layout: evenly spaced, or from a tread pattern (thesis 4.5, "FTire TP").

The thesis built two FTire models of the XZL: contact elements "arranged
equally" and "arranged according to the tread pattern" (Figure 4-20). Here a
pattern is one pitch of rubber/groove, repeated around the circumference,
given either

* declaratively: ``{"pitch": m, "width": m, "rows": ["##..##", ...]}``
  (rows around the circumference, first row leading; columns across the
  tread; ``#`` rubber, ``.`` groove),
* as a text bitmap file of that form (``PITCH =``/``WIDTH =`` lines, then
  the rows; see ``data/xzl-16.00R20_pattern.txt``), or
* as an image (PNG; dark = rubber) with ``pitch`` and ``width`` given.

Each block cell (segment length x tread width / NB) is sampled on a fine
grid; its block sits at the centroid of the rubber in the cell and carries
the rubber area. The areas are scaled so the mean stiffness per footprint
area equals the even layout's (the identification holds for both), while
groove cells carry nothing -- the contact pressure concentrates on the lugs.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np

from ...errors import InputError
from .parameters import contour_height, tread_half_width

BUILT_IN_PATTERN = {"xzl-16.00R20": "xzl-16.00R20_pattern.txt"}
#: samples per block cell and direction
SAMPLES = 6


def even_blocks(tyre, rp, n: int, nb: int):
    """Evenly spaced blocks across the width: ``(y, s, h, area)``, each N*NB.

    Along the segment the blocks are staggered, block j at
    ``s = L0 ((3 j mod NB) + 1/2) / NB - L0/2``, so they enter and leave the
    contact one at a time rather than a segment at once: on a level road
    the vertical force then ripples with the block pitch ``L0/NB``, not the
    segment pitch (at 3 km/h, +-0.5 % of the load with all blocks at the
    segment centre).
    """
    half = tread_half_width(tyre, rp)
    rb = tyre.unloaded_radius - rp.tread_depth
    l0 = 2.0 * np.pi * rb / n
    y1 = -half + (np.arange(nb) + 0.5) * 2.0 * half / nb
    y = np.tile(y1, n)
    step = 3 if nb % 3 else 1   # 3 is coprime to NB unless NB is a multiple of 3
    s1 = l0 * (((step * np.arange(nb)) % nb + 0.5) / nb - 0.5)
    s = np.tile(s1, n)
    h = np.tile(contour_height(tyre, rp, y1), n)
    area = np.full(n * nb, l0 * 2.0 * half / nb)
    return y, s, h, area


def read_pattern(source) -> dict:
    """A pattern description from a dict, a text bitmap or an image path."""
    if isinstance(source, dict):
        desc = dict(source)
    else:
        path = Path(str(source))
        if not path.is_file():
            raise InputError("no such tread pattern file", source=str(path), field="pattern")
        if path.suffix.lower() in (".png", ".bmp", ".jpg", ".jpeg"):
            import matplotlib.image as mpimg
            img = np.asarray(mpimg.imread(path), float)
            if img.ndim == 3:
                img = img[..., :3].mean(axis=2)
            rubber = img < 0.5 * (img.max() + img.min())
            return {"rubber": rubber, "pitch": None, "width": None, "source": str(path)}
        desc = {"rows": []}
        for k, line in enumerate(path.read_text().splitlines(), 1):
            text = line.strip()
            if not text:
                continue
            if set(text) <= set("#."):
                desc["rows"].append(text)
            elif text.startswith("#"):
                continue  # a comment
            elif "=" in text:
                key, value = (t.strip() for t in text.split("=", 1))
                try:
                    desc[key.lower()] = float(value.split("$")[0])
                except ValueError:
                    raise InputError(f"expected a number, found '{value}'", source=str(path),
                                     line=k, field=key) from None
            else:
                raise InputError(f"unexpected line '{text}'", source=str(path), line=k,
                                 field="pattern")
        desc["source"] = str(path)
    rows = desc.get("rows") or []
    if not rows or len({len(r) for r in rows}) != 1:
        raise InputError("a tread pattern needs rows of '#' and '.' of equal length",
                         source=desc.get("source"), field="pattern")
    for key in ("pitch", "width"):
        if not (desc.get(key) or 0) > 0:
            raise InputError(f"a tread pattern needs a positive {key.upper()} [m]",
                             source=desc.get("source"), field=key)
    rubber = np.array([[c == "#" for c in r] for r in rows])
    return {"rubber": rubber, "pitch": float(desc["pitch"]), "width": float(desc["width"]),
            "source": desc.get("source")}


def default_pattern(tyre):
    """The built-in pattern of a built-in tyre, else :class:`InputError`."""
    key = {k.lower(): k for k in BUILT_IN_PATTERN}.get(str(tyre.name).lower())
    if key is None:
        raise InputError("the ring-tp model needs a tread pattern (option pattern=...)",
                         field="pattern")
    with resources.as_file(resources.files("tyrelab.tyre").joinpath("data", BUILT_IN_PATTERN[key])) as p:
        return read_pattern(p)


def rubber_at(pattern: dict, s, y, width: float) -> np.ndarray:
    """True where the pattern has rubber at arc length ``s`` and lateral ``y`` [m]."""
    rub = pattern["rubber"]
    nr, nc = rub.shape
    pitch = pattern["pitch"] or width * nr / nc
    w = pattern["width"] or width
    r = np.floor(np.mod(s, pitch) / pitch * nr).astype(int) % nr
    c = np.floor((np.asarray(y) + 0.5 * w) / w * nc).astype(int)
    inside = (c >= 0) & (c < nc)
    out = np.zeros(np.broadcast(r, c).shape, bool)
    out[inside] = rub[r[inside], c[inside]]
    return out


def pattern_blocks(tyre, rp, n: int, nb: int, pattern: dict):
    """Blocks placed on the rubber of a tread pattern: ``(y, s, h, area)``, each N*NB."""
    half = tread_half_width(tyre, rp)
    r0 = tyre.unloaded_radius
    rb = r0 - rp.tread_depth
    l0 = 2.0 * np.pi * rb / n
    cw = 2.0 * half / nb
    u = (np.arange(SAMPLES) + 0.5) / SAMPLES - 0.5
    y = np.empty(n * nb)
    s = np.zeros(n * nb)
    area = np.zeros(n * nb)
    for i in range(n):
        s_centre = r0 * 2.0 * np.pi * i / n  # arc length at the tread surface
        for j in range(nb):
            yc = -half + (j + 0.5) * cw
            ss, yy = np.meshgrid(s_centre + u * l0 * r0 / rb, yc + u * cw, indexing="ij")
            rub = rubber_at(pattern, ss, yy, 2.0 * half)
            k = i * nb + j
            frac = rub.mean()
            area[k] = frac * l0 * cw
            if frac > 0:
                y[k] = yy[rub].mean()
                s[k] = (ss[rub].mean() - s_centre) * rb / r0
            else:
                y[k] = yc
    total = area.sum()
    if total <= 0:
        raise InputError("the tread pattern has no rubber", source=pattern.get("source"),
                         field="pattern")
    area *= (n * l0 * 2.0 * half) / total
    h = contour_height(tyre, rp, y)
    return y, s, h, area
