"""The ring model's Python side: parameter packing and the initial state.

:func:`ring_params` packs everything the compiled kernel needs into one
float array ``cp`` (layout in :mod:`.layout`), at the tyre's inflation
pressure; :func:`ring_initial_state` returns the belt in static equilibrium
on a flat road at the rig's starting height ``R0 - static_deflection(load)``.
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import InputError
from . import layout as L
from .parameters import ring_parameters, stable_step, tread_half_width
from .pattern import default_pattern, even_blocks, pattern_blocks, read_pattern

#: default discretisation (thesis 2.3.4: 100-200 belt elements, 10-100 blocks each)
N_SEGMENTS = 100
N_BLOCKS = 10
#: relaxation damping rate [1/s] used to find static equilibria
RELAX_RATE = 250.0

_OPTIONS = ("n_segments", "n_blocks", "friction", "dt_max", "pattern", "parameters", "relax",
            "lateral_samples")


def ring_params(tyre, grid=None, tread_pattern=False, n_segments=N_SEGMENTS, n_blocks=N_BLOCKS,
                friction=None, dt_max=None, pattern=None, parameters=None, relax=0.0,
                lateral_samples=1, **options) -> np.ndarray:
    """Kernel parameters ``cp`` of the flexible ring for ``tyre`` at ``tyre.pressure``.

    Parameters
    ----------
    tyre : Tyre
        Dimensions, carcass shape, pressure; ring parameters from its
        ``[FLEXIBLE_RING]`` or the built-in identified file.
    grid : RoadGrid, optional
        Not needed (the contact search adapts to any road).
    tread_pattern : bool
        Place blocks from the tread ``pattern`` ("ring-tp") instead of evenly.
    n_segments, n_blocks : int
        Belt segments N and blocks per segment NB.
    friction : float, optional
        Overrides FRICTION.
    dt_max : float, optional
        Internal step [s]; default :func:`stable_step`.
    pattern : dict or path, optional
        Tread pattern (default: the tyre's built-in pattern).
    parameters : RingParameters, optional
        Overrides the parameters read from files (identification uses it).
    relax : float
        Extra velocity damping rate [1/s] (static relaxation only).
    lateral_samples : int
        Samples across a block's width where the road is uneven under it
        (see :mod:`.tread`); 1 = along the strip only.
    """
    unknown = set(options) - set(_OPTIONS)
    if unknown:
        raise InputError(f"unknown ring option(s) {', '.join(sorted(unknown))}; expected "
                         f"{', '.join(_OPTIONS)}", field="model")
    n = int(n_segments)
    nb = int(n_blocks)
    if n < 12 or nb < 1:
        raise InputError("the ring needs at least 12 segments and 1 block per segment",
                         field="n_segments")
    rp = parameters if parameters is not None else ring_parameters(tyre)
    p = float(tyre.pressure)
    if not (math.isfinite(p) and p > 0):
        raise InputError("the ring model needs the inflation pressure (INFLPRES)",
                         source=tyre.tir.source, field="INFLPRES")
    r0 = tyre.unloaded_radius
    rb = r0 - rp.tread_depth
    dth = 2.0 * math.pi / n
    l0 = 2.0 * rb * math.sin(0.5 * dth)
    ks = rp.at_pressure(p)
    if tread_pattern:
        pat = read_pattern(pattern) if pattern is not None else default_pattern(tyre)
        y, s, h, area = pattern_blocks(tyre, rp, n, nb, pat)
    else:
        y, s, h, area = even_blocks(tyre, rp, n, nb)
    half = tread_half_width(tyre, rp)
    m = rp.ring_mass / n
    seg = rb * dth  # arc length per segment, for the per-length quantities
    cp = np.zeros(L.CP_HEADER + 2 * n + 4 * n * nb)
    cp[L.CP_N] = n
    cp[L.CP_NB] = nb
    cp[L.CP_R0] = r0
    cp[L.CP_RB] = rb
    cp[L.CP_P] = p
    cp[L.CP_M] = m
    cp[L.CP_J] = m * (2.0 * half) ** 2 / 12.0
    cp[L.CP_KR] = ks["kr"] * seg
    cp[L.CP_KT] = ks["kt"] * seg
    cp[L.CP_KY] = ks["ky"] * seg
    cp[L.CP_KB] = ks["kb"] * seg
    cp[L.CP_CR] = rp.cr * seg
    cp[L.CP_CT] = rp.ct * seg
    cp[L.CP_CY] = rp.cy * seg
    cp[L.CP_CB] = rp.cb * seg
    # pre-tension in exact equilibrium with the pressure on the polygon
    cp[L.CP_T0] = ks["pb"] * rb * math.cos(0.5 * dth)
    cp[L.CP_EA] = rp.ea
    cp[L.CP_CEA] = rp.cea
    cp[L.CP_EI] = rp.ei
    cp[L.CP_EIO] = rp.eio
    cp[L.CP_GJ] = rp.gj
    cp[L.CP_PB] = ks["pb"]
    cp[L.CP_KTR] = rp.tread_stiffness
    cp[L.CP_KNL] = rp.tread_progression
    cp[L.CP_CTR] = rp.tread_damping
    cp[L.CP_KSH] = rp.tread_shear_stiffness
    cp[L.CP_CSH] = rp.tread_shear_damping
    cp[L.CP_MU] = rp.friction if friction is None else float(friction)
    step = stable_step(rp, tyre, n, nb) if dt_max is None else float(dt_max)
    if relax > 0:
        step = min(step, 0.5 / relax)
    cp[L.CP_DTMAX] = step
    cp[L.CP_RELAX] = relax
    cp[L.CP_L0] = l0
    cp[L.CP_DTH] = dth
    cp[L.CP_HMAX] = float(h.max())
    cp[L.CP_HALFW] = half
    cp[L.CP_NLAT] = max(1, int(lateral_samples))
    o = L.CP_HEADER
    th = dth * np.arange(n)
    cp[L.CP_OFF_COS] = o
    cp[o:o + n] = np.cos(th)
    cp[L.CP_OFF_SIN] = o + n
    cp[o + n:o + 2 * n] = np.sin(th)
    o += 2 * n
    for key, arr in ((L.CP_OFF_BY, y), (L.CP_OFF_BC, s), (L.CP_OFF_BH, h), (L.CP_OFF_BK, area)):
        cp[key] = o
        cp[o:o + n * nb] = arr
        o += n * nb
    return cp


def nominal_state(cp: np.ndarray) -> np.ndarray:
    """The unloaded, undeformed belt at rest (``ts`` with p_i = Rb (cos, sin))."""
    n = int(cp[L.CP_N])
    nb = int(cp[L.CP_NB])
    ts = np.zeros(L.ts_size(n, nb))
    o = L.TS_HEADER
    rb = cp[L.CP_RB]
    oc, os_ = int(cp[L.CP_OFF_COS]), int(cp[L.CP_OFF_SIN])
    ts[o + L.S_P1 * n:o + (L.S_P1 + 1) * n] = rb * cp[oc:oc + n]
    ts[o + L.S_P2 * n:o + (L.S_P2 + 1) * n] = rb * cp[os_:os_ + n]
    return ts


_CACHE: dict = {}


def ring_initial_state(tyre, load, tread_pattern=False, **options) -> np.ndarray:
    """Belt state in static equilibrium on a flat road under ``load`` [N].

    The rim is lowered onto a flat road to the centre height
    ``R0 - tyre.static_deflection(load)`` (where the rigs start it) and the
    belt relaxes there (:func:`tyrelab.tyre.ring.static.settle`).
    """
    from ...road.obstacles import Flat
    from .static import settle
    grid = Flat().grid()
    relaxed = dict(options)
    relaxed["relax"] = RELAX_RATE
    cp = ring_params(tyre, grid, tread_pattern=tread_pattern, **relaxed)
    height = tyre.unloaded_radius - tyre.static_deflection(float(load)) if load > 0 else \
        tyre.unloaded_radius + 0.01
    key = (cp.tobytes(), round(height, 9))
    if key not in _CACHE:
        ts = nominal_state(cp)
        settle(cp, ts, grid, [height])
        if len(_CACHE) > 16:
            _CACHE.clear()
        _CACHE[key] = ts
    ts = _CACHE[key].copy()
    o = L.TS_HEADER
    n = int(cp[L.CP_N])
    for k in (L.S_V1, L.S_V2, L.S_VY, L.S_VB):
        ts[o + k * n:o + (k + 1) * n] = 0.0
    ts[L.TS_INIT] = 0.0
    ts[L.TS_TIME] = 0.0
    return ts
