"""Array layouts shared by the compiled ring kernels and the Python side.

``cp`` (parameters, built by :func:`tyrelab.tyre.ring.model.ring_params`)
-------------------------------------------------------------------------
A header of :data:`CP_HEADER` scalars (SI, per belt segment where it says
so), then the per-segment and per-block tables whose offsets are stored in
the header. ``ts`` (state, relative to the rim) has a header of
:data:`TS_HEADER` scalars, then 8 arrays of N (segment positions and
velocities in the rim-fixed, rotating wheel-plane axes), 2 arrays of N*NB
(tangential deflections of the tread blocks in the road plane) and a
scratch area for the segment forces (4 arrays of N), so a time step
allocates nothing.
"""

# --- cp header --------------------------------------------------------------
(CP_N, CP_NB, CP_R0, CP_RB, CP_P, CP_M, CP_J,
 CP_KR, CP_KT, CP_KY, CP_KB, CP_CR, CP_CT, CP_CY, CP_CB,
 CP_T0, CP_EA, CP_CEA, CP_EI, CP_EIO, CP_GJ, CP_PB,
 CP_KTR, CP_KNL, CP_CTR, CP_KSH, CP_CSH, CP_MU,
 CP_DTMAX, CP_RELAX, CP_L0, CP_DTH, CP_HMAX, CP_HALFW,
 CP_OFF_COS, CP_OFF_SIN, CP_OFF_BY, CP_OFF_BC, CP_OFF_BH, CP_OFF_BK,
 CP_NLAT) = range(41)
CP_HEADER = 48

# --- ts header --------------------------------------------------------------
TS_PSI, TS_INIT, TS_VX, TS_VY, TS_VZ, TS_OMEGA, TS_TIME, TS_SPARE = range(8)
TS_HEADER = 8
# segment arrays, in units of N after the header
S_P1, S_P2, S_V1, S_V2, S_Y, S_VY, S_B, S_VB = range(8)
N_SEG_ARRAYS = 8
N_SCRATCH = 4
#: fixed scratch after the force arrays: contact accumulators and one block result
N_SCRATCH_FIXED = 16


def ts_size(n: int, nb: int) -> int:
    """Length of the state array for ``n`` segments of ``nb`` blocks."""
    return TS_HEADER + (N_SEG_ARRAYS + N_SCRATCH) * n + 2 * n * nb + N_SCRATCH_FIXED


def block_offset(n: int) -> int:
    """Index of the first tangential block deflection in ``ts``."""
    return TS_HEADER + N_SEG_ARRAYS * n


def scratch_offset(n: int, nb: int) -> int:
    """Index of the scratch force arrays in ``ts``."""
    return TS_HEADER + N_SEG_ARRAYS * n + 2 * n * nb
