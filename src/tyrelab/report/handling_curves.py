"""Pure-slip curves of any handling model: Fx(kappa), Fy(alpha), Mz(alpha) at several loads,
several tyres side by side (e.g. one tyre as three files parameterise it).

The curves are the handling model's compiled forces (:class:`~tyrelab.tyre.registry.HandlingModel`)
at the ISO slips every model reports, ``kappa = -V_sx / V``, ``tan alpha = V_sy / V``, at a
forward speed ``V``, zero camber, the ground's friction scale 1.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: default loads as fractions of a file's nominal load (FNOMIN, FZ_NOM)
DEFAULT_LOAD_FACTORS = (0.5, 1.0, 1.5)
#: the slip ranges swept: |kappa| and |alpha| [rad] up to these
KAPPA_MAX = 0.3
ALPHA_MAX = 0.3


@dataclass
class CurveSet:
    """One tyre's sweeps: ``label``, its handling model's name, the ``loads`` [N] and the
    forces [N] and moment [N m] of shape (loads, slips) at ``kappa`` and ``alpha`` [rad]."""

    label: str
    handling: str
    loads: np.ndarray
    kappa: np.ndarray
    alpha: np.ndarray
    fx: np.ndarray
    fy: np.ndarray
    mz: np.ndarray


def nominal_load(tyre) -> float | None:
    """The load [N] a property file calls nominal: MF's ``[VERTICAL] FNOMIN`` or TMeasy's
    ``[TYRE_LOAD] FZ_NOM``; None when it names none (PAC89, Fiala)."""
    tir = tyre.tir
    for section, key in (("VERTICAL", "FNOMIN"), ("TYRE_LOAD", "FZ_NOM")):
        if tir.has(section, key):
            return tir.number(section, key)
    return None


def curve_set(tyre, handling: str, loads, speed: float, label: str, n: int = 121) -> CurveSet:
    """The pure-slip sweeps of ``tyre`` under handling model ``handling`` at ``loads`` [N] and
    forward speed ``speed`` [m/s]."""
    from ..tyre.registry import handling_model

    model = handling_model(handling)
    params = model.build(tyre)
    kappa = np.linspace(-KAPPA_MAX, KAPPA_MAX, n)
    alpha = np.linspace(-ALPHA_MAX, ALPHA_MAX, n)
    loads = np.asarray(loads, float)
    fx = np.empty((loads.size, n))
    fy = np.empty((loads.size, n))
    mz = np.empty((loads.size, n))
    for i, fz in enumerate(loads):
        for j in range(n):
            fx[i, j] = model.at_slips(params, fz, speed, kappa[j], 0.0)[0]
            _, fy[i, j], mz[i, j], *_ = model.at_slips(params, fz, speed, 0.0, np.tan(alpha[j]))
    return CurveSet(label, handling, loads, kappa, alpha, fx, fy, mz)


def plot_curve_sets(sets: list[CurveSet], output, speed: float, dpi: int = 120) -> Path:
    """A three-panel figure (Fx-kappa, Fy-alpha, Mz-alpha) of every set, written atomically:
    a colour per tyre, a line style per load."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.8), constrained_layout=True)
    panels = (("kappa", "fx", "slip ratio kappa [-]", "FXW [N]", 1.0),
              ("alpha", "fy", "slip angle alpha [deg]", "FYW [N]", 180.0 / np.pi),
              ("alpha", "mz", "slip angle alpha [deg]", "MZW [N m]", 180.0 / np.pi))
    styles = ("-", "--", ":", "-.")
    for ax, (xname, yname, xlabel, ylabel, scale) in zip(axes, panels):
        for k, s in enumerate(sets):
            for i, load in enumerate(s.loads):
                ax.plot(getattr(s, xname) * scale, getattr(s, yname)[i], color=f"C{k}",
                        ls=styles[i % len(styles)], label=f"{s.label} ({s.handling}), Fz = {load:.0f} N")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="0.5", lw=0.6)
        ax.axvline(0.0, color="0.5", lw=0.6)
    axes[0].legend(fontsize="small")
    fig.suptitle(f"pure-slip curves, W-axis (ISO), gamma = 0, V = {speed:g} m/s")
    from ..io_atomic import save_figure
    return save_figure(fig, Path(output), dpi=dpi)
