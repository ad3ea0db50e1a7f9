"""tyrelab's FMU in a real FMI host (FMPy): it reproduces the rigs, and its description is valid.

* Exported with ``tyrelab export fmu`` / :func:`tyrelab.cosim.fmu.export_fmu`
  (pythonfmu), the FMU passes FMPy's model-description validation, and its
  variables are the ones :mod:`tyrelab.cosim.variables` lists, with units.
* Open loop: FMPy's ``simulate_fmu`` replays the wheel-centre kinematics of a
  rolling-rig run over ``cleat:50x50`` at 12 km/h; FZ and FX agree with the
  rig's own to 1 % in peak and RMS, and sample by sample to round-off (point,
  volume, enveloping; the ring over the cleat, its full run marked slow).
* Closed loop: the FMU (FMPy's ``FMU2Slave``) in a quarter car that this test
  integrates reproduces tyrelab's quarter-vehicle rig to 1 % (to round-off).
* A host with no Python of its own (a small C program) runs the FMU with the
  Python that has tyrelab preloaded, as the documentation says.
* The tyre's data and the road file travel inside: the FMU runs after the
  road file it was made from is gone; its PRESSURE parameter moves a built-in
  tyre and is refused for a tyre file at another pressure.

The FMU runs in this process's Python (pythonfmu's binary calls into the
interpreter that loaded it), so it uses the tyrelab under test.
"""

from __future__ import annotations

import shutil
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="FMPy (the FMI host of these tests) is not installed")
pytest.importorskip("pythonfmu", reason="pythonfmu (the FMU builder) is not installed")

from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402
from fmpy.validation import validate_fmu  # noqa: E402

from tyrelab.api import make_tyre_model  # noqa: E402
from tyrelab.cli.main import main  # noqa: E402
from tyrelab.cosim import WheelCentre, wheel_stepper  # noqa: E402
from tyrelab.cosim.fmu import export_fmu  # noqa: E402
from tyrelab.cosim.variables import CALCULATED, INPUTS, OUTPUTS, PARAMETERS, UNITS  # noqa: E402
from tyrelab.errors import InputError  # noqa: E402
from tyrelab.rig.quarter_vehicle import QuarterVehicle  # noqa: E402
from tyrelab.rig.rolling import roll  # noqa: E402
from tyrelab.road.spec import road_from_spec  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
#: a tread pattern file (an option the FMU's manifest cannot carry yet)
PATTERN = ROOT / "src" / "tyrelab" / "tyre" / "data" / "xzl-16.00R20_pattern.txt"
SPEED = 12 / 3.6
LC1 = 23.29e3
DT = 1e-3
KINEMATICS = ("X_WC", "Y_WC", "Z_WC", "VX_WC", "VY_WC", "VZ_WC", "ROTSPEED")


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    """One FMU per contact model on cleat:50x50, made when first asked for."""
    folder = tmp_path_factory.mktemp("fmus")
    made = {}

    def get(model: str) -> Path:
        if model not in made:
            made[model] = export_fmu(folder / f"{model}.fmu", model=model, road="cleat:50x50",
                                     load=LC1)
        return made[model]
    return get


def within(a: np.ndarray, b: np.ndarray, what: str, tol: float = 0.01) -> None:
    """Peak and RMS of ``a`` within ``tol`` of ``b``'s (relative; the issue's 1 %), and every
    sample to round-off (1e-6 of the peak): the FMU runs the rig's own kernel."""
    peak_a, peak_b = np.abs(a).max(), np.abs(b).max()
    rms_a, rms_b = np.sqrt(np.mean(a ** 2)), np.sqrt(np.mean(b ** 2))
    assert peak_a == pytest.approx(peak_b, rel=tol), f"{what} peak"
    assert rms_a == pytest.approx(rms_b, rel=tol), f"{what} RMS"
    assert np.abs(a - b).max() <= 1e-6 * peak_b, f"{what} sample by sample"


def test_the_fmu_is_valid_and_says_what_it_carries(fmus):
    path = fmus("point")
    assert validate_fmu(str(path)) == []
    md = read_model_description(str(path))
    assert md.fmiVersion == "2.0" and md.coSimulation is not None and md.modelExchange is None
    by_name = {v.name: v for v in md.modelVariables}
    for kind, table in (("input", INPUTS), ("output", OUTPUTS), ("parameter", PARAMETERS),
                        ("calculatedParameter", CALCULATED)):
        assert [v.name for v in md.modelVariables if v.causality == kind] == [v.name for v in table]
        for v in table:
            assert by_name[v.name].unit == (v.unit or None), v.name
            assert by_name[v.name].description == v.description
    assert {u.name for u in md.unitDefinitions} == set(UNITS)
    assert "tyrelab" in md.description and "Python" in md.description       # what the host needs
    with zipfile.ZipFile(path) as z:
        names = z.namelist()
    assert "resources/tyrelab_data/manifest.json" in names
    assert "resources/tyrelab_data/tyre/xzl-16.00R20.tir" in names


@pytest.mark.parametrize("contact,inertia,carried", [("ring", 50.0 - 46.6, 153.999),
                                                     ("point", 50.0, 0.0)])
def test_the_fmu_tells_its_host_how_to_move_the_wheel(fmus, contact, inertia, carried):
    """SPIN_INERTIA and CARRIED_MASS from the XZL's file: the ring's rim turns with WHEEL_IYY less
    IYY (50 - 46.6 kg m^2), its belt moves RING_MASS (153.999 kg) itself; the point model's
    wheel is all the host's (50 kg m^2, nothing carried)."""
    wheel = FmuWheel(fmus(contact), {"INITIAL_LOAD": LC1}, 1, {"Z_WC": 0.6, "VX_WC": SPEED,
                                                                "ROTSPEED": SPEED / 0.6})
    try:
        assert wheel.calculated("SPIN_INERTIA") == pytest.approx(inertia, rel=1e-9)
        assert wheel.calculated("CARRIED_MASS") == pytest.approx(carried, rel=1e-6)
    finally:
        wheel.close()


# (contact model, start x [m] or None for the road's start, duration [s]); the cleat is at 5 m
REPLAYS = {
    "point": ("point", None, 2.0),
    "volume": ("volume", None, 2.0),
    "enveloping": ("enveloping", None, 2.0),
    "ring": ("ring", 4.3, 0.6),
    "ring-full": pytest.param(("ring", None, 2.0), marks=pytest.mark.slow),
}


@pytest.mark.parametrize("case", REPLAYS.values(), ids=list(REPLAYS))
def test_fmpy_replaying_a_rolling_rig_run_gives_the_rigs_loads(fmus, case):
    contact, x0, duration = case
    model = make_tyre_model("xzl-16.00R20", contact)
    run = roll(model, "cleat:50x50", speed=SPEED, load=LC1, x_start=x0, duration=duration,
               progress=False)
    signals = np.zeros(len(run), dtype=[("time", float)] + [(v.name, float) for v in INPUTS])
    signals["time"] = np.arange(len(run)) * DT
    for name in KINEMATICS:  # the wheel stays level and heads +x: INCLANGL, YAW_WC 0
        signals[name] = run[name].to_numpy()
    result = fmpy.simulate_fmu(str(fmus(contact)), start_time=0.0, stop_time=len(run) * DT,
                               output_interval=DT, input=signals, output=["FX", "FZ"],
                               start_values={"INITIAL_LOAD": LC1}, validate=True)
    # FMI: the outputs recorded at t + dt are the loads over [t, t + dt], the rig's row at t
    fz, fx = result["FZ"][1:], result["FX"][1:]
    assert len(fz) == len(run)
    assert run["FZ"].max() > 1.1 * LC1                             # the cleat was hit
    within(fz, run["FZ"].to_numpy(), "FZ")
    within(fx, run["FX"].to_numpy(), "FX")


class FmuWheel:
    """The FMU as a host holds it: FMPy's FMU2Slave, inputs and outputs by name."""

    def __init__(self, path: Path, parameters: dict, frame: int, centre: dict,
                 integers: dict | None = None):
        self.md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.folder = extract(str(path))
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.folder,
                             modelIdentifier=self.md.coSimulation.modelIdentifier,
                             instanceName="wheel")
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        self.fmu.setReal([self.vr[k] for k in parameters], list(parameters.values()))
        integers = {"OUTPUT_FRAME": frame, **(integers or {})}
        self.fmu.setInteger([self.vr[k] for k in integers], list(integers.values()))
        self.inputs = [self.vr[v.name] for v in INPUTS]
        self.fmu.setReal([self.vr[k] for k in centre], list(centre.values()))
        self.fmu.exitInitializationMode()

    def step(self, t, centre: WheelCentre, dt, outputs) -> list[float]:
        self.fmu.setReal(self.inputs, [getattr(centre, v.field) for v in INPUTS])
        self.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=dt)
        return self.fmu.getReal([self.vr[n] for n in outputs])

    def calculated(self, name: str) -> float:
        """A calculated parameter the FMU worked out at initialisation."""
        return self.fmu.getReal([self.vr[name]])[0]

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.folder, ignore_errors=True)


def quarter_car_with_fmu(path: Path, qv: QuarterVehicle, road, duration: float, dt: float = DT):
    """The quarter car of :mod:`tyrelab.rig.quarter_vehicle`, written out here in plain numpy
    (semi-implicit Euler, the spin linearly implicit in dMY/dROTSPEED), its tyre the FMU; the
    wheel turned with the FMU's SPIN_INERTIA and moved with its mass less the FMU's CARRIED_MASS
    (the ring's belt moves and turns itself), as its model description tells a host.

    Returns arrays of the tyre's FZ, FX (road frame: the wheel is level) and the body height.
    """
    g = 9.80665
    ms, mu = qv.sprung_mass, qv.unsprung_mass
    k, c = qv.suspension_stiffness, qv.suspension_damping
    free = qv.spring_length + ms * g / k
    eq = qv.model.equilibrium(qv.wheel_load, SPEED)      # where the host puts the wheel at rest
    zu, vu = qv.model.tyre.unloaded_radius - eq.deflection, 0.0
    zs, vs, w = zu + qv.spring_length, 0.0, eq.spin
    x0 = road.run_start
    wheel = FmuWheel(path, {"INITIAL_LOAD": qv.wheel_load}, 1,
                     {"X_WC": x0, "Z_WC": zu, "VX_WC": SPEED, "ROTSPEED": w})
    inertia, rim = wheel.calculated("SPIN_INERTIA"), mu - wheel.calculated("CARRIED_MASS")
    n = int(round(duration / dt))
    out = np.empty((n, 3))
    try:
        for i in range(n):
            t = i * dt
            centre = WheelCentre(x0 + SPEED * t, 0.0, zu, SPEED, 0.0, vu, w)
            fz, fx, my, dmy = wheel.step(t, centre, dt, ["FZ", "FX", "MY", "DMY_DROTSPEED"])
            fsp = k * (free - (zs - zu)) + c * (vu - vs)
            a_s, a_u = fsp / ms - g, (fz - fsp - mu * g) / rim
            out[i] = fz, fx, zs
            vs, vu = vs + dt * a_s, vu + dt * a_u
            zs, zu = zs + dt * vs, zu + dt * vu
            w += dt * my / (inertia - dt * min(dmy, 0.0))
    finally:
        wheel.close()
    return out[:, 0], out[:, 1], out[:, 2]


CLOSED = {
    "point": ("point", None, 2.5),
    "ring": ("ring", 4.3, 0.6),
    "volume": pytest.param(("volume", None, 2.5), marks=pytest.mark.slow),
    "enveloping": pytest.param(("enveloping", None, 2.5), marks=pytest.mark.slow),
    "ring-full": pytest.param(("ring", None, 2.5), marks=pytest.mark.slow),
}


@pytest.mark.parametrize("case", CLOSED.values(), ids=list(CLOSED))
def test_the_fmu_in_a_quarter_car_reproduces_the_quarter_vehicle_rig(fmus, case):
    contact, start, duration = case
    model = make_tyre_model("xzl-16.00R20", contact)
    mu = model.tyre.wheel_mass
    qv = QuarterVehicle(model, sprung_mass=LC1 / 9.80665 - mu, unsprung_mass=mu)
    road = road_from_spec("cleat:50x50")
    if start is not None:
        road.run_start = start      # the rig and the host both start the car there
    rig = qv.run(road, SPEED, duration, progress=False)
    fz, fx, body = quarter_car_with_fmu(fmus(contact), qv, road, duration)
    assert rig["FZ"].max() > 1.1 * LC1                              # the cleat was hit
    within(fz, rig["FZ"].to_numpy(), "FZ")
    within(fx, rig["FX"].to_numpy(), "FX")
    travel = rig["Z_BODY"].max() - rig["Z_BODY"].min()
    assert np.abs(body - rig["Z_BODY"].to_numpy()).max() < 0.01 * travel


def test_the_fmu_on_soil_is_the_stepper_on_soil(tmp_path, monkeypatch):
    """Exported with a soil file (``--terrain``), the FMU carries the file and lays the soil
    over its road around the wheel's start, a window of it that follows the wheel (4 m square
    here, moved as the wheel drives): FMPy stepping a vehicle's right wheel (y = -0.91 m, beyond
    the rigs' 2 m strip once its width is counted) 8 m along gets the stepping API's loads on
    the same soil laid the same way, sample by sample to round-off, after the soil file is
    gone. The FMU publishes its initial loads at initialisation (``WheelStepper.loads``): that
    look must leave the soil and the wheel's last deflection as they were (it did not: 13.4 kN
    instead of 21.5 kN at the first step)."""
    from tyrelab.rig.soil_ground import lay_terrain_around
    from tyrelab.road.soil import field

    monkeypatch.setattr(field, "FIELD_SIZE", 4.0)
    soil = ROOT / "src" / "tyrelab" / "road" / "soil" / "data"
    source = tmp_path / "my_soil.toml"
    shutil.copyfile(soil / "sandy-loam.toml", source)
    path = export_fmu(tmp_path / "soil.fmu", model="point", road="flat", terrain=str(source),
                      load=LC1, frame="road")
    source.unlink()                                          # the FMU carries its own copy
    model = make_tyre_model("xzl-16.00R20", "point")
    z, v, x0, y0 = model.tyre.unloaded_radius - 0.04, 4.0, 1.0, -0.91
    start = {"X_WC": x0, "Y_WC": y0, "Z_WC": z, "VX_WC": v, "ROTSPEED": v / z}
    wheel = FmuWheel(path, {"INITIAL_LOAD": LC1}, 1, start)
    ground, _ = lay_terrain_around(model, soil / "sandy-loam.toml", road_from_spec("flat"), x0, y0)
    stepper = wheel_stepper(model=model, road=ground, load=LC1, speed=v, frame="road")
    got, want = [], []
    try:
        for k in range(2000):
            centre = WheelCentre(x0 + v * k * DT, y0, z, v, 0.0, 0.0, v / z)
            got.append(wheel.step(k * DT, centre, DT, ["FZ", "FX"]))
            loads = stepper.step(k * DT, centre, DT)
            want.append((loads.fz, loads.fx))
    finally:
        wheel.close()
    got, want = np.array(got), np.array(want)
    assert ground.held()[0] > 3.0                            # the window moved on
    assert want[:, 0].min() > 1e3                            # pressed into the soil throughout
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * np.abs(want).max())


def test_instances_of_one_soil_group_share_the_soil(tmp_path):
    """A vehicle's front and rear wheel, 3 m apart, as two instances of the soil FMU in one
    process, stepped one after the other: with SOIL_GROUP = 1 both run on one soil laid round
    the first instance's start, the rear wheel in the front wheel's rut, and their loads are
    the stepping API's with both wheels on one field, sample by sample to round-off; the rear
    wheel then rolls with less than half the front's resistance over the same soil. With
    SOIL_GROUP = 0 the rear instance has a soil of its own: its loads are the front's 3 m later.
    An instance whose soil is not the group's is refused in one line; one whose soil is joins
    the group's ground wherever it starts."""
    from tyrelab.cosim.manifest import shared_terrain
    from tyrelab.rig.soil_ground import lay_terrain_around

    path = export_fmu(tmp_path / "soil.fmu", model="rigid", road="flat", terrain="sandy-loam",
                      load=LC1, frame="road")
    model = make_tyre_model("xzl-16.00R20", "rigid")
    z, v, y = model.tyre.unloaded_radius - 0.04, 2.0, 0.5

    def start(x):
        return {"X_WC": x, "Y_WC": y, "Z_WC": z, "VX_WC": v, "ROTSPEED": v / z}

    def drive(group):
        wheels = [FmuWheel(path, {"INITIAL_LOAD": LC1}, 1, start(x), {"SOIL_GROUP": group})
                  for x in (4.0, 1.0)]
        out = []
        try:
            for k in range(3000):
                out.append([w.step(k * DT, WheelCentre(x + v * k * DT, y, z, v, 0.0, 0.0, v / z),
                                   DT, ["FZ", "FX"]) for w, x in zip(wheels, (4.0, 1.0))])
        finally:
            for w in wheels:
                w.close()
        return np.array(out)

    shared, apart = drive(1), drive(0)
    ground = lay_terrain_around(model, "sandy-loam", road_from_spec("flat"), 4.0, y)[0]
    api = [wheel_stepper(model=model, road=ground, load=LC1, speed=v, frame="road")
           for _ in range(2)]
    want = []
    for k in range(3000):
        row = []
        for stepper, x in zip(api, (4.0, 1.0)):
            loads = stepper.step(k * DT, WheelCentre(x + v * k * DT, y, z, v, 0.0, 0.0, v / z), DT)
            row.append((loads.fz, loads.fx))
        want.append(row)
    want = np.array(want)
    np.testing.assert_allclose(shared, want, rtol=0, atol=1e-9 * np.abs(want).max())
    same_soil = slice(2000, 3000)                            # the rear wheel 3 m behind: 1500 steps
    assert 0.0 < shared[same_soil, 1, 1].mean() < 0.5 * shared[500:1500, 0, 1].mean()
    # each on its own soil: the rear wheel's loads are the front's over the same stretch, 3 m
    # later (measured 1.5e-10 N apart)
    np.testing.assert_allclose(apart[same_soil, 1], apart[500:1500, 0], rtol=0,
                               atol=1e-9 * np.abs(apart).max())
    kept = shared_terrain(model, "sandy-loam", "flat", 7, 0.0, 0.0, ("spec", "flat"))
    with pytest.raises(InputError, match="SOIL_GROUP 7 holds another soil"):
        shared_terrain(model, "lete-sand", "flat", 7, 0.0, 0.0, ("spec", "flat"))
    assert kept is shared_terrain(model, "sandy-loam", "flat", 7, 9.0, 1.0, ("spec", "flat"))


def test_many_instances_in_one_process(fmus):
    """pythonfmu's binary (0.6.5-0.7.0) releases a reference to the slave script's namespace
    that it does not own at each instance (tyrelab.cosim.slave.FINDCLASS_DECREF): without the
    script taking one back, the second instance found no slave class and the process crashed at
    a garbage collection. Ten instances, collected between, give the same loads."""
    import gc
    centre = WheelCentre(5.0, 0.0, 0.62, SPEED, 0.0, 0.0, SPEED / 0.62)
    got = []
    for _ in range(10):
        wheel = FmuWheel(fmus("point"), {}, 0, {"Z_WC": 0.62})
        try:
            got.append(wheel.step(0.0, centre, DT, ["FZ"])[0])
        finally:
            wheel.close()
        gc.collect()
    assert got == [got[0]] * 10 and got[0] > LC1     # on the cleat's edge


def test_a_wheel_below_the_road_is_a_warning_in_the_hosts_log(fmus):
    """The stepper's warning (tests/test_cosim_stepper.py) reaches the host through the FMI
    logger, with fmi2Warning status, once, though the wheel stays below the cleat road for
    three steps: a host with z pointing down learns why its tyre pulls the wheel down."""
    from fmpy import simulate_fmu

    log = []

    def logger(component, instance, status, category, message):
        log.append((status, message.decode()))
    simulate_fmu(str(fmus("point")), start_values={"Z_WC": -0.6}, stop_time=3 * DT,
                 output_interval=DT, logger=logger, debug_logging=True)
    found = [(status, m) for status, m in log if "below the road" in m]
    assert len(found) == 1 and found[0][0] == 1, log      # fmi2Warning = 1
    assert "z = -0.6 m under the road's 0 m" in found[0][1]


def test_a_negative_internal_step_is_refused_at_initialisation(fmus):
    """INTERNAL_STEP 0 means the model's stable step; a negative one is a mistake (it used to
    mean the stable step too, silently)."""
    from fmpy import simulate_fmu
    from fmpy.fmi1 import FMICallException

    log = []
    with pytest.raises(FMICallException, match="fmi2ExitInitializationMode"):
        simulate_fmu(str(fmus("point")), start_values={"INTERNAL_STEP": -1.0}, stop_time=DT,
                     logger=lambda *args: log.append(args[-1].decode()), debug_logging=True)
    assert any("internal step -1 s is out of range" in m for m in log), log


def test_the_road_file_travels_inside_the_fmu(tmp_path):
    """Exported from a copy of the CRG road, the FMU runs after the copy is deleted and gives
    the stepping API's loads on the original file."""
    road = tmp_path / "road.crg"
    shutil.copyfile(ROOT / "examples" / "data" / "my_road.crg", road)
    path = export_fmu(tmp_path / "crg.fmu", model="enveloping", road=f"{road}@0.65", load=LC1)
    road.unlink()
    stepper = wheel_stepper(model="enveloping", road=f"{ROOT / 'examples/data/my_road.crg'}@0.65",
                            load=LC1, speed=SPEED)
    z = stepper.model.tyre.unloaded_radius - stepper.equilibrium.deflection
    wheel = FmuWheel(path, {"INITIAL_LOAD": LC1}, 0, {"VX_WC": SPEED})
    try:
        fz = []
        for i in range(400):
            centre = WheelCentre(4.5 + SPEED * i * DT, 0.0, z, SPEED, 0.0, 0.0, SPEED / z)
            got = wheel.step(i * DT, centre, DT, ["FZ"])[0]
            want = stepper.step(i * DT, centre, DT).fz
            assert got == want
            fz.append(got)
    finally:
        wheel.close()
    assert np.ptp(fz) > 0.05 * LC1        # the road's relief is felt


def test_the_transient_slip_travels_inside_the_fmu(tmp_path):
    """The HMMWV's PAC89 tyre exported with relaxation lengths (0.3 m, 0.5 m), driven at 5 %
    slip from free rolling: the FMU gives the stepping API's lagged loads with those lengths,
    step for step; the steady tyre's first step has more than twice its force."""
    load, lengths = 4900.0, (0.3, 0.5)
    path = export_fmu(tmp_path / "lag.fmu", tyre="hmmwv-pac89", model="point", road="flat",
                      load=load, relaxation=lengths)
    lagged = wheel_stepper("hmmwv-pac89", "point", "flat", load=load, speed=SPEED,
                           relaxation=lengths)
    steady = wheel_stepper("hmmwv-pac89", "point", "flat", load=load, speed=SPEED,
                           relaxation="off")
    z = lagged.model.tyre.unloaded_radius - lagged.equilibrium.deflection
    omega = lagged.equilibrium.spin * 1.05
    # started as the stepping API's wheels: rolling at SPEED (the HMMWV's rolling resistance
    # deflects the carcass in that free rolling: its equilibrium at rest has it undeflected)
    wheel = FmuWheel(path, {"INITIAL_LOAD": load}, 0, {"Z_WC": z, "VX_WC": SPEED,
                                                      "ROTSPEED": lagged.equilibrium.spin})
    try:
        for i in range(200):
            centre = WheelCentre(SPEED * i * DT, 0.0, z, SPEED, 0.0, 0.0, omega)
            got = wheel.step(i * DT, centre, DT, ["FX"])[0]
            assert got == lagged.step(i * DT, centre, DT).fx
            if i == 0:
                first = got
    finally:
        wheel.close()
    assert abs(steady.step(0.0, WheelCentre(0.0, 0.0, z, SPEED, 0.0, 0.0, omega), DT).fx) > 2 * abs(first)


def test_the_pressure_parameter(tmp_path):
    """A built-in tyre at PRESSURE = 550 kPa gives the 550 kPa tyre's loads (stiffer: more load at
    the same height); a tyre file at another pressure than its own is refused at initialisation."""
    path = export_fmu(tmp_path / "p.fmu", model="point", road="flat")
    z = 0.6715 - 0.04
    centre = WheelCentre(0.0, 0.0, z, SPEED, 0.0, 0.0, SPEED / z)
    loads = {}
    for kpa in (300, 550):
        wheel = FmuWheel(path, {"PRESSURE": kpa * 1e3}, 0, {"Z_WC": z})
        try:
            loads[kpa] = wheel.step(0.0, centre, DT, ["FZ"])[0]
        finally:
            wheel.close()
        want = wheel_stepper(model="point", road="flat", pressure=kpa * 1e3).step(0.0, centre, DT)
        assert loads[kpa] == want.fz
    assert loads[550] > 1.2 * loads[300]
    own = export_fmu(tmp_path / "file.fmu", tyre=str(ROOT / "examples" / "data" / "my.tir"),
                     model="point", road="flat")
    with pytest.raises(Exception, match="fmi2ExitInitializationMode"):
        FmuWheel(own, {"PRESSURE": 123e3}, 0, {})


def test_the_export_command(tmp_path, capsys):
    out = tmp_path / "tyre.fmu"
    assert main(["export", "fmu", "--tyre", "xzl-16.00R20", "--model", "ring", "--road", "cleat:50x50",
                 "--load", "LC1", "-o", str(out)]) == 0
    assert validate_fmu(str(out)) == []
    md = read_model_description(str(out))
    assert md.coSimulation.modelIdentifier == "tyrelab_ring"
    starts = {v.name: v.start for v in md.modelVariables}
    assert float(starts["INITIAL_LOAD"]) == pytest.approx(LC1, rel=1e-3)
    assert float(starts["PRESSURE"]) == 300e3
    for argv, match in [
        (["--model", "nope"], "unknown model"),
        (["--road", "cleat:zz"], "cannot read sizes"),
        (["--pressure", "5000"], "pressure"),
        (["--load", "1e9"], "onto its rim"),
        (["--terrain", "quicksand"], "unknown terrain"),
        (["--terrain", str(tmp_path / "missing.toml")], "no such soil file"),
        (["--option", f"pattern={PATTERN}", "--model", "ring-tp"], "cannot travel"),
        (["-o", str(tmp_path / "no" / "x.fmu")], "does not exist"),
        (["-o", str(tmp_path / "x.zip")], "must end in .fmu"),
    ]:
        target = tmp_path / "bad.fmu"
        argv = ["export", "fmu", *argv] + ([] if "-o" in argv else ["-o", str(target)])
        capsys.readouterr()
        assert main(argv) == 2, argv
        assert match in capsys.readouterr().err, argv
        assert not target.exists() and not list(tmp_path.glob(".tyrelab-*")), argv


def _libpython() -> Path | None:
    """This Python's shared library, when it has one."""
    import sysconfig
    name = sysconfig.get_config_var("INSTSONAME") or sysconfig.get_config_var("LDLIBRARY")
    folder = sysconfig.get_config_var("LIBDIR")
    if not (sysconfig.get_config_var("Py_ENABLE_SHARED") and name and folder):
        return None
    path = Path(folder) / name
    return path if path.is_file() else None


@pytest.mark.skipif(shutil.which("cc") is None or _libpython() is None or sys.platform != "linux",
                    reason="needs a C compiler, Linux and a Python built with its shared library")
def test_a_host_without_python_runs_the_fmu_with_libpython_preloaded(tmp_path):
    """A 90-line C host (tests/data/cosim/fmi_host.c: dlopen, the FMI 2.0 calls) runs the FMU
    when the Python that has tyrelab is preloaded (LD_PRELOAD, PYTHONHOME, PYTHONPATH), as
    docs/cosimulation.md says, and gets the stepping API's peak FZ over the cleat; without the
    preload the binary does not load (pythonfmu's binary is not linked to a libpython). The
    host ends with exit status 0: the interpreter's shutdown in pythonfmu's thread crashed
    in about one run in five until the slave froze the collector at exit
    (:func:`tyrelab.cosim.slave.leave_objects_to_the_exit`)."""
    import os
    import subprocess
    host = tmp_path / "host"
    subprocess.run(["cc", "-O1", "-o", str(host), str(ROOT / "tests/data/cosim/fmi_host.c"), "-ldl"],
                   check=True, capture_output=True)
    path = export_fmu(tmp_path / "wheel.fmu", model="point", road="cleat:50x50", load=LC1)
    md = read_model_description(str(path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    folder = tmp_path / "unpacked"
    with zipfile.ZipFile(path) as z:
        z.extractall(folder)
    binary = folder / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
    tyre = make_tyre_model("xzl-16.00R20", "point").tyre
    z0 = tyre.unloaded_radius - tyre.static_deflection(LC1)
    args = [str(host), str(binary), (folder / "resources").as_uri(), md.guid,
            *(str(vr[n]) for n in ("X_WC", "Z_WC", "VX_WC", "ROTSPEED", "INITIAL_LOAD", "FZ")),
            repr(z0), repr(SPEED), repr(LC1), "2000", repr(DT)]
    env = {k: v for k, v in os.environ.items() if k not in ("LD_PRELOAD", "PYTHONHOME", "PYTHONPATH")}
    bare = subprocess.run(args, env=env, capture_output=True, text=True, timeout=120)
    assert bare.returncode != 0 and "_Py_NoneStruct" in bare.stdout + bare.stderr
    env.update(LD_PRELOAD=str(_libpython()), PYTHONHOME=sys.base_prefix,
               PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    run = subprocess.run(args, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    peak = float(run.stdout.split("peak FZ")[1].split()[0])
    stepper = wheel_stepper(model="point", road="cleat:50x50", load=LC1)
    want = max(stepper.step(k * DT, WheelCentre(SPEED * k * DT, 0.0, z0, SPEED, 0.0, 0.0, SPEED / z0),
                            DT).fz for k in range(2000))
    assert want > 2 * LC1                                   # the rigid disc hits the cleat
    assert peak == pytest.approx(want, abs=1e-6)
