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
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.ring.belt import belt_potential
from tyrelab.tyre.ring.modal import classify, eigenmodes, linearize, ring_frequencies_analytic
from tyrelab.tyre.ring.model import nominal_state, ring_params
from tyrelab.tyre.ring.parameters import RingParameters
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose


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
    rb = cp.belt_radius
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
    m = cp.segment_mass
    kin = 0.5 * m * np.sum(ts.v1 ** 2 + ts.v2 ** 2 + ts.vy ** 2) \
        + 0.5 * cp.segment_twist_inertia * np.sum(ts.vbeta ** 2)
    cent = 0.5 * m * omega ** 2 * np.sum(ts.p1 ** 2 + ts.p2 ** 2)
    return kin + belt_potential(cp, ts) - cent


def _spin(cp, ts, omega, steps, dt=1e-3):
    tyre = load_tyre("xzl-16.00R20", 300e3)
    wheel = TyreModel(tyre, "ring").wheel(Flat().grid())._replace(contact=cp, state=ts)
    energies = [_energy(cp, ts, omega)]
    for _ in range(steps):
        # rim 0.2 m higher than the tyre reaches: no contact
        out = loads_table(wheel, pose(0.0, 0.0, 1.0, omega=omega), dt)[0]
        assert np.all(np.isfinite(out))
        energies.append(_energy(cp, ts, omega))
    return np.array(energies), WheelLoads(*out)


def _perturbed(cp, seed=1):
    ts = nominal_state(cp)
    n = cp.n_segments
    rng = np.random.default_rng(seed)
    th = 2 * np.pi * np.arange(n) / n
    ts.p1[:] += 0.004 * np.cos(2 * th) * np.cos(th)
    ts.v2[:] += 0.05 * np.sin(3 * th)
    ts.y[:] += 0.003 * np.cos(th)
    ts.vbeta[:] += 0.2 * rng.standard_normal(n) * 0.1
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
    assert out.deflection < 0 and out.fzw == 0.0


def test_ring_params_reject_unknown_option():
    from tyrelab.errors import InputError
    with pytest.raises(InputError):
        ring_params(load_tyre("xzl-16.00R20", 300e3), None, segments=10)


def test_tyre_without_ring_section_is_an_input_error(tmp_path):
    from tyrelab.errors import InputError
    tyre = load_tyre("xzl-16.00R20", 300e3)
    other = dataclasses.replace(tyre, name="other")
    with pytest.raises(InputError, match="FLEXIBLE_RING") as err:
        ring_params(other, None)
    # the fix as a command the user can type, with the file's own name
    assert "tyrelab fit ring CAMPAIGN --into xzl-16.00R20_300kPa.tir" in str(err.value)


def test_an_unconverged_equilibrium_says_so(monkeypatch):
    """The static equilibrium search held to 2 corrections, a tolerance and a warning threshold
    no float meets: one
    PhysicsWarning with the force reached, and the state returned is the one pressed at the
    height returned (its block forces carry the force the warning reports). At the default
    tolerance the same search is silent."""
    import warnings

    from tyrelab.guards import PhysicsWarning
    from tyrelab.tyre.ring import model
    tyre = load_tyre("xzl-16.00R20")
    with warnings.catch_warnings():
        warnings.simplefilter("error", PhysicsWarning)
        model.ring_static_equilibrium(tyre, 23291.0 + 0.123)
    monkeypatch.setattr(model, "EQUILIBRIUM_TOLERANCE", 1e-15)
    monkeypatch.setattr(model, "EQUILIBRIUM_WARNING", 1e-15)
    monkeypatch.setattr(model, "EQUILIBRIUM_ITERATIONS", 2)
    with pytest.warns(PhysicsWarning, match=r"static equilibrium under 23\.29 kN ended at") as rec:
        height, state = model.ring_static_equilibrium(tyre, 23291.0 + 0.456)
    reached = float(str(rec[0].message).split("ended at ")[1].split(" kN")[0]) * 1e3
    assert float(state.block_force.sum()) == pytest.approx(reached, rel=1e-3)
    assert 0.6 < height < tyre.unloaded_radius
