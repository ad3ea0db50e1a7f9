"""MF-Tyre 6.x's vertical law: the load-deflection law in Q_FZ2, its pressure and speed terms.

Oracle: MFeval 4.3.1's reference table for its MF 6.1 example (tests/data/mfeval; README
there), whose ``rho`` column is the deflection MFeval solves from Pacejka (2012) eq. A3.3,
``Fz = (1 + Q_V2 R0/V0 |omega| - (Q_FCX Fx/Fz0)^2 - (Q_FCY Fy/Fz0)^2) (Q_FZ1 x + Q_FZ2 x^2)
(1 + PFZ1 dpi) Fz0``, x = rho/R0. Values typed from the file: R0 0.3943 m, FNOMIN 6752 N,
VERTICAL_STIFFNESS 314931.2969 N/m, Q_FZ2 20.7558, Q_V2 0.034092, LONGVL 16.6 m/s,
Q_FCX -0.020112, Q_FCY 0.26033, PFZ1 0.88241, NOMPRES = INFLPRES 260 kPa.
"""

import math

import numpy as np
import pandas as pd
import pytest

from tyrelab.api import make_tyre_model
from tyrelab.errors import InputError
from tyrelab.rig.rolling import roll
from tyrelab.tyre.params import Tyre
from tyrelab.tyre.tir import read_tir
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

R0, FZ0, CZ, Q_FZ2, Q_V2, V0 = 0.3943, 6752.0, 314931.2969, 20.7558, 0.034092, 16.6
Q_FCX, Q_FCY, PFZ1 = -0.020112, 0.26033, 0.88241


@pytest.fixture(scope="module")
def mf61_path(data_dir):
    return data_dir / "mfeval" / "MagicFormula61_Parameters.tir"


@pytest.fixture(scope="module")
def mf61(mf61_path):
    return Tyre.from_tir(mf61_path)


@pytest.fixture(scope="module")
def mfeval(data_dir):
    return pd.read_csv(data_dir / "mfeval" / "MagicFormula61_Parameters.mode111.csv.gz")


def _edited(tmp_path, path, section, key, value, drop=False):
    """A copy of the property file with ``key`` in ``[section]`` set to ``value`` (or dropped)."""
    out, inside, done = [], False, False
    for line in path.read_text().splitlines():
        if line.strip().startswith("["):
            inside = line.strip().upper() == f"[{section}]"
        if inside and line.split("=")[0].strip().upper() == key:
            done = True
            if drop:
                continue
            line = f"{key} = {value}"
        out.append(line)
    assert done, key
    target = tmp_path / f"{key}_{value}.tir".replace("-", "m")
    target.write_text("\n".join(out) + "\n")
    return target


def test_the_law_is_mfevals_at_every_row_of_its_table(mf61, mfeval):
    """At MFeval's own deflection and spin, the law gives MFeval's load once the terms it leaves
    out (the Fx and Fy softening, taken from the table's own forces) are added back."""
    law = mf61.vertical_law
    rho, omega = mfeval["rho"].to_numpy(), mfeval["omega"].to_numpy()
    rolling = np.array([law.static_load(r, w) for r, w in zip(rho, omega)])
    standing = law.static_load(rho)
    softening = (Q_FCX * mfeval["Fx"] / FZ0) ** 2 + (Q_FCY * mfeval["Fy"] / FZ0) ** 2
    np.testing.assert_allclose(rolling - standing * softening, mfeval["Fz"], rtol=1e-12)


def test_the_wheel_carries_mfevals_load_under_its_forces(mf61, mfeval):
    """Every row without camber (507; combined slip to |kappa| = |alpha| = 0.3): the point
    model's wheel at MFeval's deflection, spin and speed (Vx, Vx tan alpha) carries MFeval's
    load and forces. The forces soften the law by up to 14 % of the load here (Q_FCY Fy /
    FNOMIN)^2: without that term the load was up to 16 % high, and the forces with it."""
    from tyrelab.road.spec import road_from_spec

    # MFeval is steady state; the file's USE_MODE 124 asks for relaxation, which the table's
    # poses (no time passing) would leave at an undeflected carcass
    model = make_tyre_model(mf61, "point", handling="mf", relaxation="off")
    wheel = model.wheel(road_from_spec("flat").grid(), FZ0)
    rows = mfeval[mfeval.gamma == 0]
    poses = [pose(cz=R0 - r.rho, velocity=(r.Vx, r.Vx * math.tan(r.alpha), 0.0), omega=r.omega)
             for r in rows.itertuples()]
    loads = loads_table(wheel, poses)
    column = {name: loads[:, k] for k, name in enumerate(WheelLoads._fields)}
    softening = (Q_FCX * rows.Fx / FZ0) ** 2 + (Q_FCY * rows.Fy / FZ0) ** 2
    assert softening.max() > 0.13
    np.testing.assert_allclose(column["fzw"], rows.Fz, rtol=1e-6)
    np.testing.assert_allclose(column["fxw"], rows.Fx, rtol=1e-5, atol=1e-3)
    np.testing.assert_allclose(column["fyw"], rows.Fy, rtol=1e-5, atol=1e-3)


def test_free_rolling_deflection_is_mfevals(mf61, mfeval):
    """At zero slip (|Fx|, |Fy| <= 172 N, whose softening is below 2e-5 of the load) the
    deflection that carries each load at MFeval's spin is MFeval's rho."""
    free = mfeval[(mfeval.kappa == 0) & (mfeval.alpha == 0) & (mfeval.gamma == 0)]
    assert len(free) == 3
    ours = [mf61.vertical_law.deflection_at(fz, w) for fz, w in zip(free.Fz, free.omega)]
    np.testing.assert_allclose(ours, free["rho"], rtol=5e-5)


def test_quadratic_law_from_the_file_values(mf61):
    """Q_FZ1 = sqrt((Cz R0/Fz0)^2 - 4 Q_FZ2), typed: the law at 10 and 30 mm, and its slope at
    FNOMIN is VERTICAL_STIFFNESS (the condition Q_FZ1 is chosen by)."""
    q1 = math.sqrt((CZ * R0 / FZ0) ** 2 - 4 * Q_FZ2)
    for rho in (0.01, 0.03):
        x = rho / R0
        assert mf61.vertical_law.static_load(rho) == pytest.approx((q1 * x + Q_FZ2 * x * x) * FZ0,
                                                                   rel=1e-12)
    law = mf61.vertical_law
    d0, h = law.deflection_at(FZ0), 1e-6
    slope = (law.static_load(d0 + h) - law.static_load(d0 - h)) / (2 * h)
    assert slope == pytest.approx(CZ, rel=1e-8)
    assert mf61.stiffness == "table" and mf61.has_nonlinear_law
    # the linear mode is VERTICAL_STIFFNESS (11.4 % above the file's law at 10 mm)
    linear = mf61.with_stiffness("linear").vertical_law
    assert linear.static_load(0.01) == pytest.approx(CZ * 0.01, rel=1e-12)


def test_the_wheel_stiffens_with_its_spin(mf61):
    """The compiled contact: the same deflection carries 1 + Q_V2 R0/V0 |omega| times the load
    of a wheel that does not spin (bottoming, at the rim, is far)."""
    model = make_tyre_model(mf61, "point", handling="none")
    from tyrelab.road.spec import road_from_spec
    wheel = model.wheel(road_from_spec("flat").grid(), FZ0)
    centre = R0 - 0.02
    loads = loads_table(wheel, [pose(cz=centre, omega=w) for w in (0.0, 40.0, -70.0)])
    fz = loads[:, 2]
    np.testing.assert_allclose(fz[1:] / fz[0], [1 + Q_V2 * R0 / V0 * w for w in (40.0, 70.0)],
                               rtol=1e-12)


def test_a_rolling_wheel_starts_where_it_carries_its_load_at_its_spin(mf61):
    """At 100 km/h the law is 5.8 % stiffer than standing: the rolling rig starts at the
    deflection that carries the load at the free-rolling spin, so the force stays flat."""
    model = make_tyre_model(mf61, "point", handling="none")
    speed = 100 / 3.6
    eq = model.equilibrium(FZ0, speed)
    assert eq.spin == pytest.approx(speed / (R0 - eq.deflection), rel=1e-12)
    assert mf61.vertical_law.static_load(eq.deflection, eq.spin) == pytest.approx(FZ0, rel=1e-9)
    assert eq.deflection < 0.96 * mf61.static_deflection(FZ0)
    run = roll(model, "flat", speed, load=FZ0, duration=0.5, progress=False)
    assert np.abs(run["FZ"].to_numpy() / FZ0 - 1).max() < 1e-6


def test_the_pressure_scales_the_law(tmp_path, mf61_path, mf61):
    """INFLPRES 20 % above NOMPRES: both laws 1 + PFZ1 0.2 times stiffer (Besselink eq. 5)."""
    edited = Tyre.from_tir(_edited(tmp_path, mf61_path, "OPERATING_CONDITIONS", "INFLPRES", 312000))
    factor = 1 + PFZ1 * 0.2
    assert edited.vertical_law.static_load(0.02) == pytest.approx(
        factor * mf61.vertical_law.static_load(0.02), rel=1e-12)
    assert edited.with_stiffness("linear").vertical_law.static_load(0.02) == pytest.approx(
        factor * CZ * 0.02, rel=1e-12)


def test_a_file_without_q_fz2_keeps_its_linear_law(tmp_path, mf61_path):
    tyre = Tyre.from_tir(_edited(tmp_path, mf61_path, "VERTICAL", "Q_FZ2", 0, drop=True))
    assert tyre.quadratic_law is None and tyre.stiffness == "linear"
    assert tyre.vertical_law.static_load(0.01) == pytest.approx(CZ * 0.01, rel=1e-12)
    with pytest.raises(InputError, match="Q_FZ2"):
        tyre.with_stiffness("table")


@pytest.mark.parametrize("key, section, value, message", [
    ("Q_FZ2", "VERTICAL", 90, r"Q_FZ2 90 is too large .* allowed: Q_FZ2 <= 84\.5"),
    ("Q_FZ2", "VERTICAL", -60, "Q_FZ2 -60 makes the load fall before the tyre is pressed to the rim"),
    ("Q_V2", "VERTICAL", -0.1, "Q_V2 -0.1 makes the tyre softer"),
    ("PFZ1", "VERTICAL", -1e6, "PFZ1 -1e\\+06 takes the vertical stiffness"),
])
def test_an_impossible_vertical_law_is_refused_at_its_line(tmp_path, mf61_path, key, section, value,
                                                             message):
    path = mf61_path
    if key == "PFZ1":   # the pressure term acts only away from the nominal pressure
        path = _edited(tmp_path, path, "OPERATING_CONDITIONS", "INFLPRES", 312000)
    bad = _edited(tmp_path, path, section, key, value)
    line = next(i for i, text in enumerate(bad.read_text().splitlines(), 1)
                if text.startswith(f"{key} ="))
    with pytest.raises(InputError, match=message) as err:
        Tyre.from_tir(read_tir(bad))
    assert err.value.line == line and err.value.field == key


def test_q_fz2_needs_fnomin(tmp_path, mf61_path):
    with pytest.raises(InputError, match="Q_FZ2 needs FNOMIN"):
        Tyre.from_tir(_edited(tmp_path, mf61_path, "VERTICAL", "FNOMIN", 0, drop=True))


def test_the_force_softening_needs_fnomin(tmp_path, mf61_path):
    no_q_fz2 = _edited(tmp_path, mf61_path, "VERTICAL", "Q_FZ2", 0, drop=True)
    with pytest.raises(InputError, match=r"line \d+: Q_FCX: Q_FCX and Q_FCY need FNOMIN"):
        Tyre.from_tir(_edited(tmp_path, no_q_fz2, "VERTICAL", "FNOMIN", 0, drop=True))


def test_the_force_softening_is_the_files(mf61):
    assert mf61.force_softening == pytest.approx(((Q_FCX / FZ0) ** 2, (Q_FCY / FZ0) ** 2), rel=1e-15)
    law = mf61.vertical_law
    assert (law.force_softening_x, law.force_softening_y) == mf61.force_softening


@pytest.mark.parametrize("stiffness", ["table", "linear"])
def test_the_enveloping_patch_is_mfevals_at_each_load(mf61, mfeval, stiffness):
    """MF-Swift's patch laws are written in Fz / (Cz R0) (Besselink et al. 2010, eqs. 9, 10):
    at the static deflection that carries each load, in either law, the enveloping model's
    patch is MFeval's contact length 2a and width 2b."""
    from tyrelab.road.spec import road_from_spec
    from tyrelab.tyre.contact.enveloping import contact_patch

    tyre = mf61.with_stiffness(stiffness)
    params = make_tyre_model(tyre, "enveloping", handling="none").contact_params(
        road_from_spec("flat").grid())
    rows = mfeval.groupby("Fz").first()
    for fz, row in rows.iterrows():
        a, b = contact_patch(params, tyre.static_deflection(fz))
        assert 2 * a == pytest.approx(row["contact_length_2a"], rel=1e-9)
        assert 2 * b == pytest.approx(row["contact_width_2b"], rel=1e-9)


def test_the_magic_formulas_slip_is_taken_at_its_effective_rolling_radius(mf61, mfeval):
    """MFeval's free-rolling rows (kappa = alpha = gamma = 0, Vx = 16.7 m/s) give the spin at
    which the Magic Formula's slip is zero: omega = Vx / Re, Re from BREFF, DREFF, FREFF. The
    point model's wheel at that spin, pressed to MFeval's deflection, has zero slip and
    MFeval's Fx (to 1e-6). The contact point's lever, the loaded radius, is 1.1-5.8 % shorter
    than Re at these loads: the slip taken there was -1.1 to -5.8 % and FXW -1.0 to -10.1 kN,
    a braked wheel where MFeval's rolls freely (27 to 172 N)."""
    from tyrelab.road.spec import road_from_spec

    # MFeval is steady state; the file's USE_MODE 124 asks for relaxation, which the table's
    # poses (no time passing) would leave at an undeflected carcass
    model = make_tyre_model(mf61, "point", handling="mf", relaxation="off")
    wheel = model.wheel(road_from_spec("flat").grid(), FZ0)
    free = mfeval[(mfeval.kappa == 0) & (mfeval.alpha == 0) & (mfeval.gamma == 0)]
    # at MFeval's own deflection, which its small Fx and Fy soften (Q_FCX, Q_FCY)
    poses = [pose(cz=R0 - rho, velocity=(16.7, 0.0, 0.0), omega=w)
             for rho, w in zip(free.rho, free.omega)]
    loads = loads_table(wheel, poses)
    column = {name: loads[:, k] for k, name in enumerate(WheelLoads._fields)}
    np.testing.assert_allclose(column["kappa"], 0.0, atol=1e-9)
    np.testing.assert_allclose(column["fxw"], free["Fx"], rtol=1e-6)
    # the rigs' search for the torque-free spin starts there (tests/test_rolling_resistance.py
    # then takes it to where Fx r + My = 0): the spin of zero slip is MFeval's
    for fz, w in zip(free.Fz, free.omega):
        assert model._free_rolling(fz, 16.7)[1] == pytest.approx(w, rel=1e-9)


@pytest.mark.filterwarnings("ignore:.*no \\[CONTACT_PATCH\\] value")   # its cams are assumed
@pytest.mark.parametrize("name", ["CityBus_Pac02Tire", "MagicFormula52_Parameters"])
def test_an_mf52_files_own_contact_length_sizes_the_enveloping_patch(data_dir, name):
    """An MF 5.2 file without [CONTACT_PATCH] has its own contact length,
    a = R0 (Q_A2 z + Q_A1 sqrt z), z = Fz / FNOMIN (Q_A1, Q_A2 MFeval's estimate from
    R0 Cz / FNOMIN when the file has neither), and the whole width: the enveloping patch at
    each load is MFeval's 2a and 2b. Before, the thesis XZL's length law sized it (the CityBus's
    at 35 kN 27 % longer), and the warning said so; it now names the cams only."""
    from tyrelab.road.spec import road_from_spec
    from tyrelab.tyre.contact.enveloping import contact_patch
    from tyrelab.tyre.contact.patch_laws import assumed_patch

    tyre = Tyre.from_tir(data_dir / "mfeval" / f"{name}.tir")
    said = " ".join(assumed_patch(tyre.tir))   # what the (once per file) warning lists
    assert "PAE" in said and "length law" not in said and "width law" not in said
    params = make_tyre_model(tyre, "enveloping", handling="none").contact_params(
        road_from_spec("flat").grid())
    rows = pd.read_csv(data_dir / "mfeval" / f"{name}.mode111.csv.gz").groupby("Fz").first()
    for fz, row in rows.iterrows():
        a, b = contact_patch(params, tyre.static_deflection(fz))
        assert 2 * a == pytest.approx(row["contact_length_2a"], rel=1e-9)
        assert 2 * b == pytest.approx(row["contact_width_2b"], rel=1e-12)
