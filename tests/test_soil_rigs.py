"""The rigs on soil: the trailer and the quarter vehicle carry a wheel on a soil bed laid over
the road, settled into it at the start (tyrelab.rig.soil_ground)."""

from __future__ import annotations

import numpy as np
import pytest

import tyrelab
from tyrelab.rig.quarter_vehicle import QuarterVehicle
from tyrelab.rig.registry import G
from tyrelab.rig.single_wheel import single_wheel
from tyrelab.road.soil.params import Soil
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.model import TyreModel

LOAD = 23.3e3
#: a soil a thousand times stiffer than any in the library: the tyre cannot sink in it
HARD = Soil(n=1.0, kc=0.0, kphi=1e11, cohesion=1e3, friction_angle=0.6, janosi_k=0.01,
            elastic_stiffness=1e12, damping=0.0)


def test_the_quarter_vehicle_starts_at_rest_in_equilibrium_on_soil():
    """Creeping at 10 um/s on sandy loam (5 um in half a second: at rest), the quarter vehicle's
    hub moves by under 0.01 mm and its wheel carries the static load to 0.05 %: it starts
    where the soil, through the tyre, carries it. (At 1 cm/s the hub sinks 1 mm in the same
    time: rolling, the wheel compacts fresh soil ahead.)"""
    tm = TyreModel(load_tyre(), "point")
    mu = tm.tyre.wheel_mass
    quarter = QuarterVehicle(tm, sprung_mass=LOAD / G - mu, unsprung_mass=mu)
    run = quarter.run("flat", 1e-5, 0.5, terrain="sandy-loam", progress=False)
    assert np.ptp(run["Z_WC"].to_numpy()) < 1e-5
    assert run["FZ"].to_numpy() == pytest.approx(LOAD, rel=5e-4)
    assert run.attrs["metadata"]["soil"] == "sandy loam"


def test_the_trailer_starts_in_equilibrium_with_its_test_wheel_sunk_into_the_soil():
    """The left wheel stays on rigid ground, so the frame rolls towards the test wheel sunk
    into dry sand (1.8 deg), inclining both wheels and moving the test wheel's contact 2 cm
    across. Settled upright where the frame did not put it, the test wheel started on soil
    it had not pressed, carrying 74 % of its load. Settled where the frame holds it, each
    wheel carries the static load to 0.1 % at the start (the left one too, settled on its
    rigid ground at that inclination), and creeping at 1 cm/s the test wheel's load stays
    within 2 % over 0.3 s (the frame settles its last millimetre)."""
    run = tyrelab.simulate(model="point", rig="trailer", terrain="dry-sand", road="flat",
                           speed=0.01, duration=0.3, progress=False)
    static = run.attrs["metadata"]["static_wheel_load_N"]
    assert run["FZ"].iloc[0] == pytest.approx(static, rel=1e-3)
    assert run["FZ_LEFT"].iloc[0] == pytest.approx(static, rel=1e-3)
    assert run["ROLL"].iloc[0] > np.radians(1.0)            # the case: the frame does roll
    assert np.all(np.abs(run["FZ"].to_numpy() / static - 1.0) < 0.02)


def test_the_rigs_on_soil_report_the_sinkage_the_soil_bin_measures():
    """SINKAGE, the tyre's contact point below the surface as laid: the soil bin's kernel
    writes it from the bed's compiled heights; the trailer and the quarter vehicle take it
    from the road laid under the soil, in Python. At rest on sandy loam the quarter vehicle's
    wheel, settled as the bin's is, reads the bin's value to rounding; the trailer's, leaning
    0.5 deg as its frame rolls, reads 1.1 mm less (its contact point is on the tread's centre
    line, 200 mm from the shoulder that dips 1.7 mm). A flexible tyre's sinkage is not its
    centre's depth less the radius, which holds its deflection too: the bin's metadata said
    63.7 mm for these 21.7. On the rigid road there is no SINKAGE."""
    kw = dict(model="point", terrain="sandy-loam", road="flat", speed=0.01, duration=0.3,
              progress=False)
    quarter = tyrelab.simulate(rig="quarter-vehicle", **kw)
    trailer = tyrelab.simulate(rig="trailer", **kw)
    load = quarter.attrs["metadata"]["static_wheel_load_N"]
    bin_ = single_wheel(TyreModel(load_tyre(), "point"), "sandy-loam", load, 0.01, duration=0.3,
                        progress=False)
    assert quarter["SINKAGE"].iloc[0] == pytest.approx(bin_["SINKAGE"].iloc[0], rel=1e-9)
    assert bin_.attrs["metadata"]["static_sinkage_m"] == bin_["SINKAGE"].iloc[0]
    deflection = load_tyre().unloaded_radius - bin_["Z_WC"].iloc[0] - bin_["SINKAGE"].iloc[0]
    assert deflection == pytest.approx(bin_["DEFLECT"].iloc[0], rel=1e-6)   # the rest is the tyre's
    assert 0.0 < bin_["SINKAGE"].iloc[0] - trailer["SINKAGE"].iloc[0] < \
        0.5 * load_tyre().width * np.sin(trailer["ROLL"].iloc[0])
    assert "SINKAGE" not in tyrelab.simulate(model="point", road="flat", speed=1.0, duration=0.2,
                                             progress=False)


def test_a_towed_wheel_on_soil_drags_steadily_with_the_work_of_compaction():
    """The quarter vehicle tows the point model over sandy loam at 12 km/h, its spin free. Per
    metre travelled the soil is pressed to the sinkage z over the tyre's width b and springs
    back by sigma / K_e behind: the drag's work is what stays in the soil,
    b (k z^(n+1) / (n+1) - sigma(z)^2 / (2 K_e)) with sigma(z) = k z^n (Bekker's compaction
    resistance less the elastic energy returned; an energy balance whatever the wheel's shape,
    the shear doing no net work on a towed wheel). The drag is that to 5 % (2 % measured),
    and steady: its scatter under 2 % of the load (0.5 %). With a shear that turned at once
    with the sliding, the towed wheel's flat chattered between forward and backward shear:
    +-3.6 kN about a 0.6 kN drag."""
    from tyrelab.road.soil import load_soil
    run = tyrelab.simulate(model="point", rig="quarter-vehicle", terrain="sandy-loam", road="flat",
                           speed=12 / 3.6, duration=2.0, progress=False)
    steady = run[run["RUNTIME"] > 1.0]
    soil, b = load_soil("sandy-loam")[0], load_tyre().width
    z, k = steady["SINKAGE"].mean(), soil.kc / b + soil.kphi
    kept = b * (k * z ** (soil.n + 1) / (soil.n + 1) - (k * z ** soil.n) ** 2 / (2 * soil.elastic_stiffness))
    assert -steady["FX"].mean() == pytest.approx(kept, rel=0.05)
    assert steady["FX"].std() < 0.02 * LOAD
    assert abs(steady["MY"].mean()) < 0.01 * LOAD * load_tyre().unloaded_radius   # towed


def test_the_ring_settles_into_the_soil_before_it_starts():
    """The ring's loads depend on its belt's state, so the soil bin settles it at rest (damped)
    before the run: standing still on sandy loam its centre then moves by under 0.05 mm and
    its load stays within 0.5 % of the dead weight."""
    run = single_wheel(TyreModel(load_tyre(), "ring"), "sandy-loam", LOAD, 1e-4, slip=0.0,
                       duration=0.5, progress=False)
    assert np.ptp(run["Z_WC"].to_numpy()) < 5e-5
    assert run["FZ"].to_numpy() == pytest.approx(LOAD, rel=0.005)


def test_the_trailer_on_a_ground_too_stiff_to_sink_is_the_trailer_on_the_road():
    """The trailer towing the point model at 12 km/h over flat ground: on a soil too stiff to
    sink its test wheel rides at the height it rides on the rigid road (to 1 % of the tyre's
    deflection) and carries the same load (to 0.5 %)."""
    kw = dict(model="point", rig="trailer", road="flat", speed=12 / 3.6, duration=1.0, progress=False)
    road = tyrelab.simulate(**kw)
    soil = tyrelab.simulate(terrain=HARD, **kw)
    deflection = load_tyre().unloaded_radius - road["Z_WC"].mean()
    assert abs(soil["Z_WC"].mean() - road["Z_WC"].mean()) < 0.01 * deflection
    assert soil["FZ"].mean() == pytest.approx(road["FZ"].mean(), rel=0.005)


def test_a_soil_that_throws_the_wheel_off_is_a_divergence_not_a_result(tmp_path, capsys):
    """Soil damping of 1e20 Pa s/m (Chrono's demo: 3e4) at a 1 ms step pushes the single
    wheel with 1e15 kN in its first step; it then flew on with finite numbers, 300 km up
    after 0.5 s, and the slip curve averaged its zero load and pull as a result. A normal
    force over 100 times the static load, more than any tyre carries (the XZL reaches its
    rim at 15.7 times LC1), is a diverged run: an error naming the terrain, from
    tyrelab.simulate and from the slip curve's command, which writes nothing."""
    from tyrelab.cli.main import main
    from tyrelab.rig.simulation import SimulationError

    soil = tmp_path / "viscous.toml"
    soil.write_text("[soil]\nn = 1.1\nkc = 0.0\nkphi = 2e6\ncohesion = 0.0\nfriction_angle = 30.0\n"
                    "janosi_k = 0.01\ndamping = 1e20\n")
    with pytest.raises(SimulationError, match=r"times the static wheel load .* on the terrain"):
        tyrelab.simulate(model="rigid", rig="single-wheel", terrain=str(soil), load=LOAD, speed=1.0,
                         rig_options={"slip": 0.2}, duration=0.5, progress=False)
    out = tmp_path / "curve.csv"
    assert main(["soil", "curve", "--terrain", str(soil), "--slips", "0.2", "--duration", "0.5",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "diverged" in err[0] and "damping" in err[0], err
    assert not out.exists()
