"""Verification of the flexible ring against physics that could fail.

* the in-plane natural frequencies of a plain pre-tensioned ring on an
  elastic foundation (no tread, no bending) against the analytic continuum
  formula (derived in :func:`tyrelab.tyre.ring.modal.ring_frequencies_analytic`),
* an undamped, unloaded ring spinning freely never gains energy,
* interface contract: no NaN, normal force never negative, zero load in the air.
"""

import dataclasses
import math

import numpy as np
import pytest

from tyrelab.road.obstacles import Flat
from tyrelab.tyre.kernel import OUT_SIZE, road_info
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.ring import layout as L
from tyrelab.tyre.ring.belt import belt_potential
from tyrelab.tyre.ring.kernel import ring_wheel_force
from tyrelab.tyre.ring.modal import classify, eigenmodes, linearize, ring_frequencies_analytic
from tyrelab.tyre.ring.model import nominal_state, ring_params
from tyrelab.tyre.ring.parameters import RingParameters


def _plain_ring(**changes):
    """Parameters of a plain ring: no bending, no torsion, no damping."""
    rp = RingParameters(ei=0.0, eio=0.0, gj=0.0, cr=0.0, ct=0.0, cy=0.0, cb=0.0, cea=0.0,
                        kr0=3.0e5, krp=1.5, kt0=1.5e5, ktp=0.5, ea=2.0e6, pressure_width=0.3)
    return dataclasses.replace(rp, **changes)


@pytest.mark.parametrize("pressure", [100e3, 550e3])
def test_in_plane_frequencies_match_analytic_ring(pressure):
    tyre = load_tyre("xzl-16.00R20", pressure)
    rp = _plain_ring()
    cp = ring_params(tyre, None, parameters=rp, n_segments=100, n_blocks=1)
    M, C, K = linearize(cp, nominal_state(cp))
    freq, _, vec = eigenmodes(M, C, K)
    rb = cp[L.CP_RB]
    k = rp.at_pressure(pressure)
    analytic = ring_frequencies_analytic(5, rb, rp.ring_mass / (2 * math.pi * rb), k["kr"],
                                         k["kt"], k["pb"] * rb, rp.ea)
    shapes = [classify(cp, vec[:, j]) for j in range(freq.size)]
    for n, f_low, f_high in analytic:
        numeric = np.array([f for f, (ip, wave, _) in zip(freq, shapes) if ip and wave == n])
        assert numeric.size, f"no in-plane mode with n = {n}"
        for f in (f_low, f_high):
            err = np.min(np.abs(numeric - f)) / f
            assert err < 0.02, f"n={n}: analytic {f:.2f} Hz, nearest numeric " \
                               f"{numeric[np.argmin(np.abs(numeric - f))]:.2f} Hz"


def _energy(cp, ts, omega):
    """Jacobi integral in the rim frame: kinetic + potential - centrifugal potential."""
    n = int(cp[L.CP_N])
    o = L.TS_HEADER
    m = cp[L.CP_M]
    seg = lambda k: ts[o + k * n:o + (k + 1) * n]  # noqa: E731
    kin = 0.5 * m * np.sum(seg(L.S_V1) ** 2 + seg(L.S_V2) ** 2 + seg(L.S_VY) ** 2) \
        + 0.5 * cp[L.CP_J] * np.sum(seg(L.S_VB) ** 2)
    cent = 0.5 * m * omega ** 2 * np.sum(seg(L.S_P1) ** 2 + seg(L.S_P2) ** 2)
    return kin + belt_potential(cp, ts) - cent


def _spin(cp, ts, omega, steps, dt=1e-3):
    grid = Flat().grid()
    zi = road_info(grid)
    out = np.zeros(OUT_SIZE)
    energies = [_energy(cp, ts, omega)]
    for _ in range(steps):
        # rim 0.2 m higher than the tyre reaches: no contact
        ring_wheel_force(3, cp, ts, grid.params, grid.z, zi, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0,
                         0.0, 0.0, 0.0, omega, dt, out)
        assert np.all(np.isfinite(out))
        energies.append(_energy(cp, ts, omega))
    return np.array(energies), out


def _perturbed(cp, seed=1):
    ts = nominal_state(cp)
    n = int(cp[L.CP_N])
    o = L.TS_HEADER
    rng = np.random.default_rng(seed)
    th = 2 * np.pi * np.arange(n) / n
    ts[o + L.S_P1 * n:o + (L.S_P1 + 1) * n] += 0.004 * np.cos(2 * th) * np.cos(th)
    ts[o + L.S_V2 * n:o + (L.S_V2 + 1) * n] += 0.05 * np.sin(3 * th)
    ts[o + L.S_Y * n:o + (L.S_Y + 1) * n] += 0.003 * np.cos(th)
    ts[o + L.S_VB * n:o + (L.S_VB + 1) * n] += 0.2 * rng.standard_normal(n) * 0.1
    return ts


def test_undamped_free_spinning_ring_never_gains_energy():
    tyre = load_tyre("xzl-16.00R20", 300e3)
    rp = dataclasses.replace(RingParameters(), cr=0.0, ct=0.0, cy=0.0, cb=0.0, cea=0.0)
    cp = ring_params(tyre, None, parameters=rp)
    omega = 88 / 3.6 / tyre.unloaded_radius  # top speed
    ts = _perturbed(cp)
    eq = _energy(cp, nominal_state(cp), omega)
    e, _ = _spin(cp, ts, omega, 2000)
    scale = e[0] - eq
    # symplectic (Boris) integration: the energy sampled at the staggered
    # velocities oscillates by O(h omega) but must not drift upwards; the
    # window means may differ by their own sampling noise only
    first, last = e[:200].mean(), e[-200:].mean()
    assert last - first < 0.005 * scale


def test_damped_free_ring_loses_energy():
    tyre = load_tyre("xzl-16.00R20", 300e3)
    cp = ring_params(tyre, None)
    ts = _perturbed(cp)
    e, out = _spin(cp, ts, 10.0, 300)
    assert e[-1] < 0.5 * e[0] or e[-1] - _energy(cp, nominal_state(cp), 10.0) < 0.5 * (
        e[0] - _energy(cp, nominal_state(cp), 10.0))
    assert out[9] < 0 and out[13] == 0.0


def test_ring_params_reject_unknown_option():
    from tyrelab.errors import InputError
    with pytest.raises(InputError):
        ring_params(load_tyre("xzl-16.00R20", 300e3), None, segments=10)


def test_tyre_without_ring_section_is_an_input_error(tmp_path):
    from tyrelab.errors import InputError
    tyre = load_tyre("xzl-16.00R20", 300e3)
    other = dataclasses.replace(tyre, name="other")
    with pytest.raises(InputError, match="FLEXIBLE_RING"):
        ring_params(other, None)
