"""Magic Formula 5.2 / 6.1 / 6.2 steady-state tyre model (PAC2002 family).

Agrees with MFeval 4.3.1 (useMode 111 and 121) on the reference tables in
``tests/data/mfeval``. Turn slip is not implemented.

Use modes (MFeval's three digits): 111 -- limit checks and low-speed model
on, alpha* = alpha and gamma* = gamma (as TNO MF-Tyre); 121 -- limit checks
on, alpha* = tan(alpha) sign(Vx), gamma* = sin(gamma) (Pacejka 2012,
eq. 4.E3-4.E4); 211 / 221 -- the same without limit checks. Axes ISO-W
(TYDEX W), forces and moments of the road on the tyre, SI units.

- :class:`MagicFormula` -- ``MagicFormula.from_tir(path)``, ``.coefficients``,
  ``.version``, ``.steady_state(fz, kappa, alpha, gamma, vx, pressure, use_mode)``;
- :func:`mf_forces` -- compiled one-sample Fx, Fy, Mx, My, Mz for other
  ``njit`` kernels.
"""

# numba's cache of these kernels is kept consistent by tyrelab.core.jit_cache
from .coefficients import detect_version, pack
from .kernel import OUTPUTS, mf_evaluate, mf_evaluate_many, mf_forces, mf_forces_many
from .limits import describe_flags
from .model import MFLimitWarning, MagicFormula, SUPPORTED_USE_MODES, check_use_mode

__all__ = ["MagicFormula", "MFLimitWarning", "mf_forces", "mf_forces_many", "mf_evaluate",
           "mf_evaluate_many", "OUTPUTS", "SUPPORTED_USE_MODES", "check_use_mode",
           "describe_flags", "detect_version", "pack"]
