"""Characteristic curves of a Magic Formula tyre: Fx(kappa), Fy(alpha), Mz(alpha).

Pure-slip sweeps at several loads (fractions of FNOMIN), zero camber, the
file's inflation pressure and its reference speed LONGVL, evaluated with
:meth:`tyrelab.tyre.handling.mf.MagicFormula.steady_state`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: default loads as fractions of FNOMIN
DEFAULT_LOAD_FACTORS = (0.5, 1.0, 1.5)


def curve_data(model, load_factors=DEFAULT_LOAD_FACTORS, kappa_max=0.3, alpha_max=0.3,
               n=121, use_mode=111) -> dict:
    """Sweeps for the plot: {"kappa", "alpha", "loads", "Fx", "Fy", "Mz"} (SI).

    ``Fx`` etc. have shape (len(loads), n). Slip ranges are limited to the
    file's KPUMIN/KPUMAX and ALPMIN/ALPMAX so that no input is clipped.
    """
    fz0 = model.coefficient("FNOMIN")
    k_hi = min(kappa_max, model.coefficient("KPUMAX"), -model.coefficient("KPUMIN"))
    a_hi = min(alpha_max, model.coefficient("ALPMAX"), -model.coefficient("ALPMIN"))
    kappa = np.linspace(-k_hi, k_hi, n)
    alpha = np.linspace(-a_hi, a_hi, n)
    loads = np.asarray(load_factors, dtype=float) * fz0
    vx = model.coefficient("LONGVL")
    fz = loads[:, None]
    pure_long = model.steady_state(fz, kappa[None, :], 0.0, 0.0, vx, use_mode=use_mode)
    pure_lat = model.steady_state(fz, 0.0, alpha[None, :], 0.0, vx, use_mode=use_mode)
    return {"kappa": kappa, "alpha": alpha, "loads": loads, "Fx": pure_long["Fx"],
            "Fy": pure_lat["Fy"], "Mz": pure_lat["Mz"]}


def plot_curves(model, output, load_factors=DEFAULT_LOAD_FACTORS, use_mode=111, dpi=120,
                pressure_text=None) -> Path:
    """Write a three-panel figure (Fx-kappa, Fy-alpha, Mz-alpha) to ``output`` (atomically);
    ``pressure_text`` (the pressure the file states, "250 kPa") joins the title when given."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = curve_data(model, load_factors, use_mode=use_mode)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.5), constrained_layout=True)
    panels = (("kappa", "Fx", "slip ratio kappa [-]", "Fx [N]", 1.0),
              ("alpha", "Fy", "slip angle alpha [deg]", "Fy [N]", 180.0 / np.pi),
              ("alpha", "Mz", "slip angle alpha [deg]", "Mz [N m]", 180.0 / np.pi))
    for ax, (xname, yname, xlabel, ylabel, scale) in zip(axes, panels):
        for i, load in enumerate(data["loads"]):
            ax.plot(data[xname] * scale, data[yname][i], label=f"Fz = {load:.0f} N")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="0.5", lw=0.6)
        ax.axvline(0.0, color="0.5", lw=0.6)
    axes[0].legend()
    fig.suptitle(f"{Path(model.source).name} -- Magic Formula {model.version}, "
                 f"ISO-W, gamma = 0, Vx = {model.coefficient('LONGVL'):g} m/s, "
                 + (f"{pressure_text}, " if pressure_text else "") + f"use_mode {use_mode}")
    from ..io_atomic import save_figure
    return save_figure(fig, Path(output), dpi=dpi)
