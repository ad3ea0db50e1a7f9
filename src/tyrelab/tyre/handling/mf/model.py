"""The Python face of the Magic Formula model: :class:`MagicFormula`."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from ....errors import InputError
from ...tir import TirFile
from . import coefficients as C
from .kernel import COL, MFO, N_OUTPUTS, mf_evaluate_many
from .limits import describe_flags

#: use modes checked against MFeval (turn slip, units digit 2, is not implemented)
SUPPORTED_USE_MODES = (111, 121, 211, 221)


class MFLimitWarning(UserWarning):
    """An input exceeded the property file's range and was limited (or low-speed mode ran)."""


def check_use_mode(use_mode) -> int:
    """``use_mode`` as an int, or a clear error naming what is supported."""
    try:
        mode = int(use_mode)
    except (TypeError, ValueError):
        mode = None
    if mode is None or mode != use_mode or mode not in SUPPORTED_USE_MODES:
        hint = " (turn slip, units digit 2, is not implemented)" if mode and mode % 10 == 2 else ""
        raise InputError(f"unsupported use_mode {use_mode!r}{hint}; expected one of "
                         f"{', '.join(map(str, SUPPORTED_USE_MODES))}", field="use_mode")
    return mode


class MagicFormula:
    """Magic Formula 5.2 / 6.1 / 6.2 steady-state tyre model (agrees with MFeval 4.3.1).

    Attributes
    ----------
    coefficients : numpy.ndarray
        All coefficients packed (SI), for :func:`.kernel.mf_forces`.
    version : str
        "5.2", "6.1" or "6.2".
    source : str
        The property file the model came from.
    """

    def __init__(self, coefficients: np.ndarray, version: str, source: str = "<memory>",
                 tir: TirFile | None = None):
        self.coefficients = np.ascontiguousarray(coefficients, dtype=np.float64)
        self.version = version
        self.source = source
        self.tir = tir

    @classmethod
    def from_tir(cls, path_or_tir) -> "MagicFormula":
        """Build the model from a ``.tir`` path or a parsed :class:`TirFile`."""
        values, version, tir = C.load(path_or_tir)
        return cls(values, version, tir.source, tir)

    def __repr__(self) -> str:
        return f"MagicFormula(version={self.version!r}, source={Path(self.source).name!r})"

    def coefficient(self, name: str) -> float:
        """One coefficient by its property-file name (after defaults and SI conversion)."""
        try:
            return float(self.coefficients[C.INDEX[name.upper()]])
        except KeyError:
            raise InputError(f"unknown Magic Formula coefficient {name}", field=name) from None

    @property
    def nominal_load(self) -> float:
        return self.coefficient("FNOMIN")

    def steady_state(self, fz, kappa, alpha, gamma, vx, pressure=None, use_mode=111) -> dict:
        """Steady-state forces, moments and the other MFeval outputs.

        Inputs broadcast against each other: ``fz`` (N), ``kappa`` (-),
        ``alpha``, ``gamma`` (rad), ``vx`` (m/s), ``pressure`` (Pa, default
        the file's INFLPRES; values <= 0 also mean INFLPRES). ``use_mode``: 111 (limit checks, no alpha*,
        as TNO MF-Tyre), 121 (limit checks, alpha* = tan(alpha) sign(Vx),
        gamma* = sin(gamma)), 211 / 221 (the same without limit checks).

        Returns a dict of float64 arrays named like MFeval's outputs: Fx, Fy,
        Fz, Mx, My, Mz, kappa, alpha, gamma, phit, Vx, P, Re, rho,
        contact_length_2a, t, mux, muy, omega, Rl, contact_width_2b, Mzr, Cx,
        Cy, Cz, Kya, sigmax, sigmay, iKya, Kxk (ISO-W axes, SI units). Inputs
        beyond the file's limits are clipped with an :class:`MFLimitWarning`.
        """
        mode = check_use_mode(use_mode)
        if pressure is None:
            pressure = self.coefficient("INFLPRES")
        arrays = np.broadcast_arrays(*(np.asarray(v, dtype=np.float64)
                                       for v in (fz, kappa, alpha, gamma, vx, pressure)))
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(a.ravel()) for a in arrays]
        for name, a in zip(("fz", "kappa", "alpha", "gamma", "vx", "pressure"), flat):
            if not np.all(np.isfinite(a)):
                raise InputError(f"{name} contains NaN or infinite values", field=name)
        out = np.empty((flat[0].size, N_OUTPUTS))
        mf_evaluate_many(self.coefficients, mode, *flat, out)
        self._warn(out[:, MFO.flags])
        return self._pack_outputs(out, shape)

    def _warn(self, flags: np.ndarray) -> None:
        if flags.size == 0:
            return
        combined = int(np.bitwise_or.reduce(flags.astype(np.int64)))
        for message in describe_flags(combined):
            warnings.warn(f"{Path(self.source).name}: {message}", MFLimitWarning, stacklevel=3)

    @staticmethod
    def _pack_outputs(out: np.ndarray, shape) -> dict:
        result = {}
        order = ("Fx", "Fy", "Fz", "Mx", "My", "Mz", "kappa", "alpha", "gamma", "phit", "Vx", "P",
                 "Re", "rho", "contact_length_2a", "t", "mux", "muy", "omega", "Rl",
                 "contact_width_2b", "Mzr", "Cx", "Cy", "Cz", "Kya", "sigmax", "sigmay", "iKya", "Kxk")
        for name in order:
            if name == "phit":
                result[name] = np.zeros(shape)
            elif name == "iKya":
                result[name] = _instantaneous_kya(out[:, MFO.Fy], out[:, MFO.alpha_used]).reshape(shape)
            else:
                result[name] = out[:, COL[name]].reshape(shape)
        return result


def _instantaneous_kya(fy: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """dFy/dalpha between consecutive samples, last value repeated (MFeval's iKya).

    Where consecutive slip angles are equal the slope is undefined; 0 is
    returned there instead of MFeval's Inf/NaN.
    """
    if fy.size < 2:
        return np.zeros_like(fy)
    dfy, dal = np.diff(fy), np.diff(alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(dal != 0.0, dfy / np.where(dal != 0.0, dal, 1.0), 0.0)
    return np.append(slope, slope[-1])
