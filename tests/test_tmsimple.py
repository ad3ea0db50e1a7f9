"""TMsimple handling forces (W. Hirschberg; Project Chrono's 2023 ChTMsimpleTire) and the
parameters read from Chrono's TMsimple JSON files.

References: the characteristic's analytic properties (slope dF0 at zero slip, maximum FM,
FS as the slip grows); Chrono's guess coefficients (``ChTMsimpleTire::GuessTruck80Par``,
``GuessPassCar70Par``, typed from its source, commit 7689fbc0) and the numbers of Chrono's
``van_TMsimpleTireFull.json``, typed from the file.
"""

import math

import numpy as np
import pytest

from tyrelab.api import default_handling, simulate
from tyrelab.errors import InputError
from tyrelab.tyre.chrono_json import read_chrono_tyre
from tyrelab.tyre.handling.tmsimple import simple_characteristic, tmsimple_params, tmsimple_wheel_forces

from file_edit import edited

#: Chrono's m_vnum [m/s]
V_NUM = 0.01
TRUCK = {"DFX0": (19.1677, 15.1285), "FXMAX": (0.91432, 0.79538), "FXSLD": (0.52273, 0.48517),
         "DFY0": (6.8392, 6.4235), "FYMAX": (0.75948, 0.72714), "FYSLD": (0.68739, 0.65594)}
PASSENGER = {"DFX0": (19.9774, 20.8424), "FXMAX": (1.1404, 1.1045), "FXSLD": (0.84482, 0.82041),
             "DFY0": (16.7895, 12.9866), "FYMAX": (1.0107, 0.91902), "FYSLD": (0.84864, 0.78702)}


@pytest.fixture
def tir_dir(data_dir):
    return data_dir / "tir"


@pytest.fixture
def van(tir_dir, tmp_path):
    """van_TMsimpleTireFull.json without its bottoming radius (0.396 m, above its 0.376 m)."""
    return read_chrono_tyre(edited(tir_dir / "van_TMsimpleTireFull.json", tmp_path / "van.json",
                                   ('"Tire Bottoming Radius [m]": 0.396,', "")))


def forces(params, fz, sx, sy, rolling_speed=10.0):
    """TMsimple at TMeasy's slips ``sx``, ``sy`` (transport speed ``rolling_speed + V_NUM``)."""
    v_t = rolling_speed + V_NUM
    v_sx, v_sy = -sx * v_t, -sy * v_t
    return tmsimple_wheel_forces(params, fz, rolling_speed + v_sx, v_sx, v_sy, 0.0)


def test_the_characteristic_starts_at_its_slope_peaks_and_slides():
    df0, fm, fs = 48550.5, 2912.91, 2278.85
    def f(s):
        return simple_characteristic(s, df0, fm, fs)
    assert (f(1e-7) - f(0.0)) / 1e-7 == pytest.approx(df0, rel=1e-5)
    values = [f(s) for s in np.linspace(0.0, 3.0, 30001)]
    assert max(values) == pytest.approx(fm, rel=1e-6)
    assert f(50.0) == pytest.approx(fs, rel=1e-9)


def test_the_van_files_parameters_by_hand(van):
    """At FZ_NOM (2599.65 N) the pure curves are the file's first values; at twice it the
    second; the combined force lies along the slip; no aligning moment."""
    p = tmsimple_params(van)
    assert p.nominal_load == 2599.65
    x = [(48550.5, 2912.91, 2278.85), (104900.0, 5573.65, 4286.82)]
    y = [(38957.8, 2621.49, 2182.17), (52255.6, 4679.53, 3992.13)]
    for level in (0, 1):
        fz = 2599.65 * (level + 1)
        for s in (0.02, 0.1, 0.4):
            dfx, fxm, fxs = x[level]
            b = math.pi - math.asin(fxs / fxm)
            want = fxm * math.sin(b * (1 - math.exp(-s * dfx / (fxm * b))))
            assert forces(p, fz, s, 0.0)[0] == pytest.approx(want, rel=1e-12)
            dfy, fym, fys = y[level]
            b = math.pi - math.asin(fys / fym)
            want = fym * math.sin(b * (1 - math.exp(-s * dfy / (fym * b))))
            assert forces(p, fz, 0.0, s)[1] == pytest.approx(want, rel=1e-12)
    fx, fy, mz, *_ = forces(p, 3000.0, 0.05, -0.08)
    assert fx * -0.08 == pytest.approx(fy * 0.05, rel=1e-12) and mz == 0.0


def test_tmsimple_reads_its_own_damping_key(van):
    """Chrono's TMsimple reader takes 'Vertical Tire Damping [Ns/m]' (its TMeasy reader 'Tire
    Vertical Damping'): the van file's 1801.74 N s/m. Before, the TMeasy key was asked for."""
    assert van.vertical_damping == 1801.74
    assert default_handling(van) == "tmsimple"


@pytest.mark.parametrize("name,pattern,capacity_kg", [
    ("HMMWV_TMsimpleTire.json", TRUCK, 1000.0), ("van_TMsimpleTire.json", PASSENGER, 530.0)])
def test_a_load_index_gives_chronos_tmsimple_guess(tir_dir, name, pattern, capacity_kg):
    tyre = read_chrono_tyre(tir_dir / name)
    tir = tyre.tir
    nominal = 0.5 * capacity_kg * 9.81
    assert tir.number("TYRE_LOAD", "FZ_NOM") == pytest.approx(nominal, rel=1e-12)
    section = {"X": "LONGITUDINAL_PARAMETERS", "Y": "LATERAL_PARAMETERS"}
    for key, (one, two) in pattern.items():
        sec = section[key.lstrip("DF")[0]]
        assert tir.number(sec, f"{key}_1") == pytest.approx(one * nominal, rel=1e-12), key
        assert tir.number(sec, f"{key}_2") == pytest.approx(two * 2 * nominal, rel=1e-12), key
    assert not tir.has("LONGITUDINAL_PARAMETERS", "SXMAX_1")  # TMsimple has no slips
    assert default_handling(tyre) == "tmsimple"


def test_a_freely_rolling_wheel_stays_free(van):
    """Its axle free of torque, the wheel carries the rolling resistance's drag and no more:
    FXW = -c Fz R0 / r with the van's "Rolling Resistance Coefficient" c = 0.015, R0 = 0.376 m
    and r = R0 - z the contact point's lever, from start to end."""
    load = 2500.0
    out = simulate(van, "point", road="flat", speed=8.0, load=load, handling="tmsimple",
                   rig="rolling", duration=1.0)
    r = 0.376 - van.static_deflection(load)
    np.testing.assert_allclose(out["FXW"], -0.015 * load * 0.376 / r, rtol=1e-9)


def test_a_sliding_force_above_the_maximum_is_refused(van, tmp_path):
    from tyrelab.tyre.params import Tyre
    from tyrelab.tyre.tir import read_tir, write_tir

    van.tir.sections["LATERAL_PARAMETERS"].entries["FYSLD_2"] = 5000.0
    path = tmp_path / "v.tir"
    write_tir(van.tir, path)
    with pytest.raises(InputError, match=r"line \d+: FYSLD_2: expected FYSLD_2 between 0 and FYMAX_2"):
        tmsimple_params(Tyre.from_tir(read_tir(path)))
