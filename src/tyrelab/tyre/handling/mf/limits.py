"""Input limits and the low-speed model of MFeval (useMode hundreds digit 1).

With limit checks on, MFeval (Solver.parseInputs) clips slip angle, camber,
load (upper limit only for the forces), pressure and slip ratio to the
file's ranges, and below VXLOW scales slips and some shifts down towards
standstill. The compiled code cannot warn, so each clip sets a bit of an
integer flag word; :func:`describe_flags` turns the word into the messages
that :meth:`MagicFormula.steady_state` passes to ``warnings.warn``.
"""

from __future__ import annotations

import math

import numba

from . import coefficient_index as C

# flag bits
ALPHA_LOW, ALPHA_HIGH = 1, 2
CAMBER_LOW, CAMBER_HIGH = 4, 8
LOAD_LOW, LOAD_HIGH = 16, 32
PRESSURE_LOW, PRESSURE_HIGH = 64, 128
KAPPA_LOW, KAPPA_HIGH = 256, 512
LOW_SPEED = 1024
CURVATURE_CLIPPED = 2048
NEGATIVE_MUY = 4096
NON_FINITE = 8192

_MESSAGES = (
    (ALPHA_LOW, "slip angle below ALPMIN; values have been saturated"),
    (ALPHA_HIGH, "slip angle above ALPMAX; values have been saturated"),
    (CAMBER_LOW, "inclination angle below CAMMIN; values have been saturated"),
    (CAMBER_HIGH, "inclination angle above CAMMAX; values have been saturated"),
    (LOAD_LOW, "vertical load below FZMIN; moments and radii use the FZMIN load reductions"),
    (LOAD_HIGH, "vertical load above FZMAX; values have been saturated"),
    (PRESSURE_LOW, "pressure below PRESMIN; values have been saturated"),
    (PRESSURE_HIGH, "pressure above PRESMAX; values have been saturated"),
    (KAPPA_LOW, "slip ratio below KPUMIN; values have been saturated"),
    (KAPPA_HIGH, "slip ratio above KPUMAX; values have been saturated"),
    (LOW_SPEED, "speed |Vx| at or below VXLOW; low-speed model activated"),
    (CURVATURE_CLIPPED, "a curvature factor (Ex, Ey, Et, Exa or Eyk) exceeded 1 and was set to 1"),
    (NEGATIVE_MUY, "negative lateral friction coefficient muy reported as its absolute value"),
    (NON_FINITE, "the equations gave a non-finite value far outside the file's range; "
                 "it was replaced by 0"),
)


def describe_flags(flags: int) -> list[str]:
    """Messages for the bits set in a flag word (or in the OR of many)."""
    return [text for bit, text in _MESSAGES if int(flags) & bit]


@numba.njit(cache=True, error_model="numpy")
def decode_use_mode(use_mode):
    """(limit checks on, alpha_star on) from MFeval's 3-digit useMode.

    Hundreds digit: 1 limit checks and low-speed model on, 2 off.
    Tens digit: 1 alpha* = alpha, gamma* = gamma (TNO MF-Tyre); 2 alpha* =
    tan(alpha) sign(Vx), gamma* = sin(gamma) (Pacejka 2012, eq. 4.E3-4.E4).
    Units digit: 1 combined slip without turn slip (2, turn slip, is not
    implemented and is treated as 1; the Python API refuses it).
    """
    hundreds = use_mode // 100
    tens = (use_mode // 10) % 10
    return hundreds != 2, tens == 2


@numba.njit(cache=True, error_model="numpy")
def _clip(x, lo, hi, flags, bit_lo, bit_hi):
    """x limited to [lo, hi], with the matching flag bit set."""
    if x < lo:
        return lo, flags | bit_lo
    if x > hi:
        return hi, flags | bit_hi
    return x, flags


@numba.njit(cache=True, error_model="numpy")
def prepare_inputs(c, check, fz, kappa, alpha, gamma, vx, p):
    """Limited inputs as MFeval's parseInputs makes them.

    Returns (fz_u, fz, fz_low, kappa, kappa_out, alpha, alpha_out, gamma, p,
    low_speed, reduction_smooth, flags):

    - fz_u: load with negatives set to 0 (used by Re, My, contact patch);
    - fz: fz_u clipped to FZMAX (forces); fz_low: also raised to FZMIN
      (aligning moment residuals, loaded radius);
    - kappa/alpha: low-speed reduced and clipped; kappa_out is the reduced,
      unclipped slip ratio and alpha_out the unclipped slip angle (0 at Vx = 0)
      that MFeval reports;
    - reduction_smooth = 1 - 0.5 (1 + cos(pi Vx / VXLOW)) below VXLOW.
    """
    flags = 0
    if fz < 0.0:
        fz = 0.0
    fz_u = fz
    kappa_out = kappa
    alpha_out = 0.0 if vx == 0.0 else alpha
    fz_low = fz
    low = False
    smooth = 1.0
    if check:
        vxlow = c[C.VXLOW]
        if vxlow > 0.0 and abs(vx) <= vxlow:
            low = True
            flags |= LOW_SPEED
            smooth = 1.0 - 0.5 * (1.0 + math.cos(math.pi * vx / vxlow))
            linear = abs(vx / vxlow)
            kappa_out = kappa * linear
            kappa = kappa * linear
        speed_sum = abs(vx) + abs(math.tan(alpha) * vx)
        if vxlow > 0.0 and speed_sum < vxlow:
            alpha = alpha * speed_sum / vxlow
        alpha, flags = _clip(alpha, c[C.ALPMIN], c[C.ALPMAX], flags, ALPHA_LOW, ALPHA_HIGH)
        gamma, flags = _clip(gamma, c[C.CAMMIN], c[C.CAMMAX], flags, CAMBER_LOW, CAMBER_HIGH)
        if fz > c[C.FZMAX]:
            fz = c[C.FZMAX]
            flags |= LOAD_HIGH
        fz_low = fz
        if fz < c[C.FZMIN]:
            fz_low = c[C.FZMIN]
            flags |= LOAD_LOW
        p, flags = _clip(p, c[C.PRESMIN], c[C.PRESMAX], flags, PRESSURE_LOW, PRESSURE_HIGH)
        kappa, flags = _clip(kappa, c[C.KPUMIN], c[C.KPUMAX], flags, KAPPA_LOW, KAPPA_HIGH)
    return fz_u, fz, fz_low, kappa, kappa_out, alpha, alpha_out, gamma, p, low, smooth, flags
