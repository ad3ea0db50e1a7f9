"""Benchmark of co-simulation (plain script, prints figures): what a communication step costs.

For each model the rolling rig's run over the 50 mm cleat at 12 km/h (LC1,
2 s, 1 ms) is replayed three ways, and the wall time per step is printed:

* ``rig``: the rolling rig's own compiled loop (``tyrelab.rig.rolling.roll``),
  the model's cost with no co-simulation around it;
* ``stepper``: the stepping API from Python, one ``WheelStepper.step`` per
  1 ms step (``tyrelab.cosim``);
* ``fmu``: the exported FMU in FMPy at a 1 ms communication step, as a host
  drives it: ``fmi2SetReal`` of the 9 inputs, ``fmi2DoStep``, ``fmi2GetReal``
  of the 6 loads (FMPy's ``FMU2Slave``, pythonfmu's binary, the slave class).

``fmu - rig`` is the FMU's overhead per communication step; ``RT`` is wall
time over simulated time at a 1 ms communication step (< 1: faster than real
time). Compilation, the FMU's instantiation and the ring's equilibrium are
outside the timed loops (a warm-up run first); each figure is the fastest of
three runs (the machine is shared).

    NUMBA_NUM_THREADS=1 python benchmarks/bench_cosim.py [--quick]
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402

from tyrelab.api import make_tyre_model  # noqa: E402
from tyrelab.cosim import WheelCentre, wheel_stepper  # noqa: E402
from tyrelab.cosim.fmu import export_fmu  # noqa: E402
from tyrelab.cosim.variables import INPUTS  # noqa: E402
from tyrelab.rig.rolling import roll  # noqa: E402

SPEED, LOAD, DURATION, DT = 12 / 3.6, 23.29e3, 2.0, 1e-3
KINEMATICS = ("X_WC", "Y_WC", "Z_WC", "VX_WC", "VY_WC", "VZ_WC", "ROTSPEED")
LOADS = ["FX", "FY", "FZ", "MX", "MY", "MZ"]


def best(f, repeats=3) -> float:
    """The fastest wall time [s] of ``repeats`` calls of ``f`` (which returns its own timing)."""
    return min(f() for _ in range(repeats))


def time_rig(model) -> float:
    def once():
        t0 = time.perf_counter()
        roll(model, "cleat:50x50", speed=SPEED, load=LOAD, duration=DURATION, progress=False)
        return time.perf_counter() - t0
    return best(once)


def centres(model) -> list[WheelCentre]:
    run = roll(model, "cleat:50x50", speed=SPEED, load=LOAD, duration=DURATION, progress=False)
    return [WheelCentre(*row) for row in run[list(KINEMATICS)].to_numpy()]


def time_stepper(model, path) -> float:
    def once():
        stepper = wheel_stepper(model=model, road="cleat:50x50", load=LOAD, speed=SPEED)
        t0 = time.perf_counter()
        for k, c in enumerate(path):
            stepper.step(k * DT, c, DT)
        return time.perf_counter() - t0
    return best(once)


def time_fmu(fmu_path: Path, path) -> float:
    md = read_model_description(str(fmu_path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    inputs = [vr[v.name] for v in INPUTS]
    outputs = [vr[n] for n in LOADS]

    def once():
        folder = extract(str(fmu_path))
        fmu = FMU2Slave(guid=md.guid, unzipDirectory=folder,
                        modelIdentifier=md.coSimulation.modelIdentifier, instanceName="wheel")
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        c0 = path[0]
        fmu.setReal([vr["INITIAL_LOAD"]] + inputs, [LOAD, *c0])
        fmu.exitInitializationMode()
        t0 = time.perf_counter()
        for k, c in enumerate(path):
            fmu.setReal(inputs, list(c))
            fmu.doStep(currentCommunicationPoint=k * DT, communicationStepSize=DT)
            fmu.getReal(outputs)
        wall = time.perf_counter() - t0
        fmu.terminate()
        fmu.freeInstance()
        shutil.rmtree(folder, ignore_errors=True)
        return wall
    return best(once)


def main(argv=None):
    quick = "--quick" in (argv or sys.argv[1:])
    models = ["point", "ring"] if quick else ["point", "volume", "enveloping", "ring"]
    steps = int(round(DURATION / DT))
    print(f"rolling rig over cleat:50x50 at 12 km/h, LC1, {DURATION:g} s at {DT * 1e3:g} ms, one core")
    print(f"{'model':>10} {'rig_us':>7} {'stepper_us':>10} {'fmu_us':>7} {'fmu-rig_us':>10} "
          f"{'stepper-rig_us':>14} {'fmu_RT':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        for name in models:
            model = make_tyre_model("xzl-16.00R20", name)
            fmu_path = export_fmu(Path(tmp) / f"{name}.fmu", model=name, road="cleat:50x50", load=LOAD)
            path = centres(model)               # also the warm-up: compilation, equilibrium
            time_stepper(model, path[:10])
            rig = time_rig(model) / steps
            stepper = time_stepper(model, path) / steps
            fmu = time_fmu(fmu_path, path) / steps
            print(f"{name:>10} {rig * 1e6:7.1f} {stepper * 1e6:10.1f} {fmu * 1e6:7.1f} "
                  f"{(fmu - rig) * 1e6:10.1f} {(stepper - rig) * 1e6:14.1f} {fmu / DT:7.3f}")


if __name__ == "__main__":
    main()
