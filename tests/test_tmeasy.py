"""TMeasy handling forces (G. Rill; Project Chrono's 2023 ChTMeasyTire) and the TMeasy
parameters read from Chrono's JSON files.

References: the curve's construction (its value, slope and curvature at the points where
its pieces join, derived here by hand from Rill's definition); the numbers of Chrono's
files in ``tests/data/tir`` (``van_TMeasyTireFull.json``'s measured-style parameters, typed
from the JSON), and Chrono's guess functions ``GuessTruck80Par`` / ``GuessPassCar70Par``
(their coefficients typed from Chrono's source, commit 7689fbc0).
"""

import math

import numpy as np
import pytest

from tyrelab.api import default_handling, simulate
from tyrelab.errors import InputError
from tyrelab.road.obstacles import Flat
from tyrelab.tyre.chrono_json import read_chrono_tyre
from tyrelab.tyre.handling.tmeasy import characteristic, tmeasy_params, tmeasy_wheel_forces
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

from file_edit import edited
from tmeasy_van import VAN_NOMINAL, VAN_TRAIL, VAN_X, VAN_Y, fixed_van

#: Chrono's ``m_vnum``, the speed TMeasy adds to the transport speed [m/s]
V_NUM = 0.01
@pytest.fixture
def tir_dir(data_dir):
    return data_dir / "tir"


@pytest.fixture
def van(tir_dir, tmp_path):
    return fixed_van(tir_dir, tmp_path)


def forces(params, fz, sx, sy, rolling_speed=10.0, backwards=False):
    """TMeasy at TMeasy's own slips ``sx``, ``sy``: the slip velocities that give them at a
    transport speed ``rolling_speed + V_NUM``."""
    v_t = rolling_speed + V_NUM
    v_sx, v_sy = -sx * v_t, -sy * v_t
    v_long = rolling_speed + v_sx
    if backwards:  # the mirror image: the wheel and the ground both move the other way
        v_long, v_sx = -v_long, -v_sx
        rolling = -rolling_speed
        assert abs((v_long - v_sx) - rolling) < 1e-12
    return tmeasy_wheel_forces(params, fz, v_long, v_sx, v_sy, 0.0)


# --- the characteristic ------------------------------------------------------------------------

def _slope(f, s, h=1e-7):
    return (f(s + h) - f(s - h)) / (2 * h)


@pytest.mark.parametrize("slide,slide_slip", [(1522.8229, 0.66667), (2000.0, 0.2)])
def test_the_characteristic_joins_its_pieces_smoothly(slide, slide_slip):
    """Rill's curve: slope dF0 at 0; the maximum FM at sM with zero slope and the curvature
    -2 a, a = (FM/sM)^2 / (dF0 sM), on both sides; slope continuous where the two parabolas
    meet, s* = sM + (FM - FS) / (a (sS - sM)); FS reached flat at sS and held beyond. The
    second case has s* beyond sS: a cubic step, flat at both ends."""
    df0, fm, sm = 34910.7021, 2145.5102, 0.13913
    def f(s):
        return characteristic(s, df0, fm, sm, slide, slide_slip)
    assert f(0.0) == 0.0
    assert _slope(f, 1e-6) == pytest.approx(df0, rel=1e-4)
    assert f(sm) == pytest.approx(fm, rel=1e-12)
    for side in (-1, 1):
        assert _slope(f, sm + side * 1e-6) == pytest.approx(0.0, abs=1e-4 * df0)
    a = (fm / sm) ** 2 / (df0 * sm)
    h = 1e-4
    for s0 in (sm - h, sm + h):  # the curvature on each side of sM
        curvature = (f(s0 + h / 10) - 2 * f(s0) + f(s0 - h / 10)) / (h / 10) ** 2
        assert curvature == pytest.approx(-2 * a, rel=2e-2)
    s_star = sm + (fm - slide) / (a * (slide_slip - sm))
    if s_star < slide_slip:
        assert _slope(f, s_star - 1e-6) == pytest.approx(_slope(f, s_star + 1e-6), rel=1e-4)
    else:  # the cubic step: flat at sM and at sS, halfway down in the middle
        assert f(0.5 * (sm + slide_slip)) == pytest.approx(0.5 * (fm + slide), rel=1e-12)
    assert _slope(f, slide_slip - 1e-6) == pytest.approx(0.0, abs=1e-3 * df0)
    assert f(slide_slip) == pytest.approx(slide, rel=1e-12)
    assert f(5.0) == slide
    s = np.linspace(0.0, 2.0, 2001)
    values = np.array([f(x) for x in s])
    assert values.max() <= fm * (1 + 1e-12) and values.min() >= 0.0  # FM is the maximum


# --- the van's measured-style parameters -----------------------------------------------------

@pytest.mark.parametrize("level", [0, 1])
def test_pure_slip_peaks_are_the_files_at_both_loads(van, level):
    """At FZ_NOM and 2 FZ_NOM each direction's maximum is the file's, at the file's slip;
    its sliding force the file's from its sliding slip on; its slope at 0 the file's."""
    p = tmeasy_params(van)
    fz = VAN_NOMINAL * (level + 1)
    for curve, pure in ((VAN_X, lambda s: forces(p, fz, s, 0.0)[0]),
                        (VAN_Y, lambda s: forces(p, fz, 0.0, s)[1])):
        assert pure(curve["peak_slip"][level]) == pytest.approx(curve["peak"][level], rel=1e-12)
        assert pure(curve["slide_slip"][level] * 1.5) == pytest.approx(curve["slide"][level], rel=1e-12)
        assert (pure(1e-7) - pure(-1e-7)) / 2e-7 == pytest.approx(curve["slope"][level], rel=1e-6)


def test_the_load_interpolation_vanishes_at_zero_and_stops_at_fz_max(van):
    """Forces grow from zero with the load (the parabola through 0, FM1 at FZ_NOM and FM2
    at twice it: halfway to FZ_NOM it is 3/4 FM1 - 1/8 FM2 + ... by hand) and stop growing at
    FZ_MAX (3.5 FZ_NOM, Chrono's default, as the file gives none)."""
    p = tmeasy_params(van)
    assert p.max_load == pytest.approx(3.5 * VAN_NOMINAL)
    f1, f2 = VAN_X["peak"]
    s1, s2 = VAN_X["peak_slip"]
    q = 0.5
    peak = q * (2 * f1 - f2 / 2 - (f1 - f2 / 2) * q)
    peak_slip = s1 + (s2 - s1) * (q - 1)
    assert forces(p, q * VAN_NOMINAL, peak_slip, 0.0)[0] == pytest.approx(peak, rel=1e-12)
    assert forces(p, 1e-9, 0.1, 0.0)[0] == pytest.approx(0.0, abs=1e-6)
    at_max = forces(p, 3.5 * VAN_NOMINAL, 0.1, 0.2)
    # the forces stop growing; the aligning moment's contact length does not (Chrono's too)
    assert forces(p, 10 * VAN_NOMINAL, 0.1, 0.2)[:2] == pytest.approx(at_max[:2], rel=1e-12)


def test_combined_slip_acts_against_the_slip_on_the_blended_curve(van):
    """Combined slip: the force lies along the slip (TMeasy's isotropy) and its size is the
    curve whose parameters blend the two directions' by the slip's direction; past both
    sliding slips it is hypot(FXS cos phi, FYS sin phi)."""
    p = tmeasy_params(van)
    fz = VAN_NOMINAL
    for sx, sy in ((0.05, 0.03), (-0.2, 0.1), (0.3, -0.6), (-0.02, -0.25)):
        fx, fy, *_ = forces(p, fz, sx, sy)
        s = math.hypot(sx, sy)
        c, n = sx / s, sy / s
        assert fx * sy == pytest.approx(fy * sx, rel=1e-9)
        blend = [math.hypot(VAN_X[k][0] * c, VAN_Y[k][0] * n)
                 for k in ("slope", "peak", "peak_slip", "slide", "slide_slip")]
        assert math.hypot(fx, fy) == pytest.approx(characteristic(s, *blend), rel=1e-12)
        assert fx * sx > 0 and fy * sy > 0
    fx, fy, *_ = forces(p, fz, 2.0, 1.5)
    assert math.hypot(fx, fy) == pytest.approx(math.hypot(VAN_X["slide"][0] * 0.8,
                                                          VAN_Y["slide"][0] * 0.6), rel=1e-12)


def test_aligning_moment_is_the_trail_times_the_lateral_force(van):
    """Mz = -L n Fy: at vanishing lateral slip the trail is PT_NORM of the contact length
    L = 2 sqrt(R0 z), z the deflection of the van's spring curve fitted as Chrono does
    (F = d1 z + d2 z^2 through (0.03 m, 2900 N) and (0.06 m, 6000 N): d1 = 93333.3 N/m,
    d2 = 111111 N/m^2); zero where the trail changes sign; turned over rolling backwards."""
    p = tmeasy_params(van)
    d1, d2 = 2800.0 / 0.03, 200.0 / 0.0018
    assert (p.d1, p.d2) == pytest.approx((d1, d2), rel=1e-9)
    z = (-d1 + math.sqrt(d1 * d1 + 4 * d2 * VAN_NOMINAL)) / (2 * d2)
    length = 2 * math.sqrt(0.376 * z)
    fx, fy, mz, *_ = forces(p, VAN_NOMINAL, 0.0, 1e-6)
    assert mz / fy == pytest.approx(-length * VAN_TRAIL["at_zero"][0], rel=1e-4)
    assert forces(p, VAN_NOMINAL, 0.0, VAN_TRAIL["sign_change"][0])[2] == pytest.approx(0.0, abs=1e-9)
    beyond = forces(p, VAN_NOMINAL, 0.0, 0.4)
    assert beyond[2] * beyond[1] > 0  # past the sign change the trail lies ahead
    back = forces(p, VAN_NOMINAL, 0.0, 0.05, backwards=True)
    ahead = forces(p, VAN_NOMINAL, 0.0, 0.05)
    assert back[1] == pytest.approx(ahead[1], rel=1e-12)
    assert back[2] == pytest.approx(-ahead[2], rel=1e-12)


# --- the wheel on the rigs ---------------------------------------------------------------------

def test_the_slip_stiffness_is_the_spin_moments_derivative(van):
    """The rigs integrate the spin implicitly with d(spin moment)/d(omega) from the handling
    model's slip stiffness: it must be the derivative the wheel step's moments show."""
    model = TyreModel(van, "point", "tmeasy")
    load = 2500.0
    eq = model.equilibrium(load, 8.0)
    wheel = model.wheel(Flat().grid(), load)
    r0 = van.unloaded_radius
    for factor in (1.0, 1.03, 0.9):  # free rolling, driving, braking
        omega = eq.spin * factor
        h = 1e-6 * omega
        poses = [pose(cz=r0 - eq.deflection, velocity=(8.0, 0.0, 0.0), omega=w) for w in (omega, omega + h)]
        a, b = (WheelLoads(*row) for row in loads_table(wheel, np.array(poses)))
        assert a.dspin_domega == pytest.approx((b.my - a.my) / h, rel=1e-3)


def test_a_freely_rolling_wheel_starts_and_stays_free(tir_dir, tmp_path):
    """The rolling rig starts the wheel at V / Re, Re = R0 - z/3 (TMeasy's rolling radius, z
    the deflection of TMeasy's own law d1 z + d2 z^2, the previous test's): no longitudinal
    force at the start, nor after a second of rolling on flat ground. At the loaded radius
    instead (R0 - z) the slip would be 2z / (3 Re), 4.6 %: 1.8 kN at the start. (The van
    without its rolling resistance, whose drag needs a little slip:
    tests/test_rolling_resistance.py.)"""
    van = fixed_van(tir_dir, tmp_path, ('"Rolling Resistance Coefficient": 0.015',
                                        '"Rolling Resistance Coefficient": 0.0'))
    model = TyreModel(van, "point", "tmeasy")
    load, speed = 2500.0, 8.0
    eq = model.equilibrium(load, speed)
    d1, d2 = 2800.0 / 0.03, 200.0 / 0.0018
    z = (-d1 + math.sqrt(d1 * d1 + 4 * d2 * load)) / (2 * d2)
    assert z == pytest.approx(eq.deflection, rel=0.05)  # the tyre's spline through the same rows
    assert eq.spin == pytest.approx(speed / (van.unloaded_radius - z / 3), rel=1e-9)
    out = simulate(van, "point", road="flat", speed=speed, load=load, handling="tmeasy",
                   rig="rolling", duration=1.0)
    assert np.abs(out["FXW"]).max() < 1.0
    assert out["FZW"].to_numpy() == pytest.approx(load, rel=1e-6)


# --- the JSON files ----------------------------------------------------------------------------

def test_the_van_file_is_refused_for_its_misspelt_damping(tir_dir):
    """As published the file names its damping 'Vertical Tire Damping' (Chrono reads 'Tire
    Vertical Damping'): one line naming the key and the line of 'Vertical'."""
    with pytest.raises(InputError, match=r"line 40: Parameters > Vertical > Tire Vertical Damping"):
        read_chrono_tyre(tir_dir / "van_TMeasyTireFull.json")


def test_the_van_files_bottoming_radius_above_its_radius_is_refused(tir_dir, tmp_path):
    path = edited(tir_dir / "van_TMeasyTireFull.json", tmp_path / "van.json",
                  ('"Vertical Tire Damping [Ns/m]"', '"Tire Vertical Damping [Ns/m]"'))
    with pytest.raises(InputError, match=r"bottoming radius 0.396 m must lie between the rim radius "
                                         r"0.1778 m and the unloaded radius 0.376 m"):
        read_chrono_tyre(path)


def test_the_van_files_parameters_reach_the_model(van):
    p = tmeasy_params(van)
    assert (p.nominal_load, p.unloaded_radius) == (VAN_NOMINAL, 0.376)
    for got, want in ((p.longitudinal, VAN_X), (p.lateral, VAN_Y)):
        for level in (0, 1):
            assert got[level]._asdict() == {k: want[k][level] for k in got[level]._fields}
    assert [t.vanish for t in p.trail] == [0.96524, 1.0714]
    assert default_handling(van) == "tmeasy"


# Chrono's GuessTruck80Par / GuessPassCar70Par coefficients (2023), typed from its source:
# forces per newton of the level's load, slips as they stand
TRUCK = {"DFX0": (17.7764, 14.5301), "FXMAX": (0.89965, 0.77751), "FXSLD": (0.46183, 0.42349),
         "SXMAX": (0.10811, 0.12389), "SXSLD": (0.66667, 0.66667), "DFY0": (7.4013, 6.8505),
         "FYMAX": (0.75876, 0.72628), "FYSLD": (0.68276, 0.65319), "SYMAX": (0.33167, 0.33216),
         "SYSLD": (1.0296, 1.0296), "PT_NORM": (0.178, 0.19), "SY_CHSI": (0.36484, 0.36538),
         "SY_ZERO": (1.0296, 1.0296)}
PASSENGER = {"DFX0": (18.3741, 19.4669), "FXMAX": (1.1292, 1.0896), "FXSLD": (0.80149, 0.76917),
             "SXMAX": (0.13913, 0.13913), "SXSLD": (0.66667, 0.66667), "DFY0": (15.9826, 12.8509),
             "FYMAX": (1.0009, 0.91367), "FYSLD": (0.8336, 0.77336), "SYMAX": (0.14852, 0.18504),
             "SYSLD": (0.96524, 1.0714), "PT_NORM": (0.178, 0.19), "SY_CHSI": (0.16337, 0.20355),
             "SY_ZERO": (0.96524, 1.0714)}


def _section(key):
    if key.startswith(("PT_", "SY_")):
        return "ALIGNING_PARAMETERS"
    return {"X": "LONGITUDINAL_PARAMETERS", "Y": "LATERAL_PARAMETERS"}[key.lstrip("DFS")[0]]


@pytest.mark.parametrize("name,pattern,nominal", [
    # load index 108: 1000 kg; 164: 5000 kg at 4.5 of 7.6 bar; 86: 530 kg (ETRTO table)
    ("HMMWV_TMeasyTire.json", TRUCK, 0.5 * 1000 * 9.81),
    ("MAN_5t_TMeasyTire.json", TRUCK, 0.5 * 5000 * 9.81 * (4.5e5 / 7.6e5) ** 0.8),
    ("van_TMeasyTire.json", PASSENGER, 0.5 * 530 * 9.81),
])
def test_a_load_index_gives_chronos_guess(tir_dir, name, pattern, nominal):
    tyre = read_chrono_tyre(tir_dir / name)
    tir = tyre.tir
    assert tir.number("TYRE_LOAD", "FZ_NOM") == pytest.approx(nominal, rel=1e-12)
    assert tir.number("TYRE_LOAD", "FZ_MAX") == pytest.approx(3.5 * nominal, rel=1e-12)
    for key, (one, two) in pattern.items():
        section = _section(key)
        scale = (nominal, 2 * nominal) if key.startswith(("DF", "F")) else (1.0, 1.0)
        assert tir.number(section, f"{key}_1") == pytest.approx(one * scale[0], rel=1e-12), key
        assert tir.number(section, f"{key}_2") == pytest.approx(two * scale[1], rel=1e-12), key
    assert default_handling(tyre) == "tmeasy"
    tmeasy_params(tyre)  # every guess passes the file checks


def test_a_vehicle_type_chrono_does_not_know_is_refused(tir_dir, tmp_path):
    path = edited(tir_dir / "HMMWV_TMeasyTire.json", tmp_path / "t.json",
                  ('"Vehicle Type": "Truck"', '"Vehicle Type": "Tractor"'))
    with pytest.raises(InputError, match=r"Vehicle Type: expected 'Truck' or 'Passenger', found 'Tractor'"):
        read_chrono_tyre(path)


def test_without_a_vehicle_type_the_tyre_has_no_handling(tir_dir, tmp_path):
    tyre = read_chrono_tyre(edited(tir_dir / "HMMWV_TMeasyTire.json", tmp_path / "t.json",
                                   ('"Vehicle Type": "Truck",', "")))
    assert default_handling(tyre) == "none"
    with pytest.raises(InputError, match=r"missing key FZ_NOM in section \[TYRE_LOAD\]"):
        tmeasy_params(tyre)


@pytest.mark.parametrize("key,value,match", [
    ("FXSLD_1", 2500.0, r"FXSLD_1 between 0 and FXMAX_1"),
    ("DFX0_1", 20000.0, r"DFX0_1 >= 2 FXMAX_1 / SXMAX_1 = 30841.8 N"),
    ("SYSLD_2", 0.1, r"SYSLD_2 above SYMAX_2"),
    ("SY_CHSI_1", 2.0, r"0 < SY_CHSI_1 <= SY_ZERO_1"),
])
def test_impossible_parameters_are_refused_at_their_key(van, tmp_path, key, value, match):
    from tyrelab.tyre.params import Tyre
    from tyrelab.tyre.tir import write_tir
    tir = van.tir
    for section in tir.sections.values():
        if key in section.entries:
            section.entries[key] = value
    path = tmp_path / "van.tir"
    write_tir(tir, path)
    tyre = Tyre.from_tir(str(path))
    with pytest.raises(InputError, match=match) as err:
        tmeasy_params(tyre)
    assert err.value.line is not None
