"""Benchmark: the towed test trailer over the 50 mm cleat, 10 s simulated at 12 km/h.

    python benchmarks/bench_trailer.py [MODEL ...]      (default: point)

For each contact model prints
- the first-run time (compilation + run) in a fresh process with an empty
  numba cache (NUMBA_CACHE_DIR pointed at a new temporary folder),
- the cached start-up time of a second fresh process (cache loaded from disk),
- the steady run time (median of repeated runs in one process) and the
  real-time factor = simulated time / wall time, on one core.
"""

import os
import statistics
import subprocess
import sys
import tempfile
import time

SIM_TIME = 10.0
SPEED = 12 / 3.6

CHILD = """
import time, sys
t0 = time.perf_counter()
import tyrelab
t1 = time.perf_counter()
tyrelab.simulate(model=sys.argv[1], road="cleat:50x50", speed={speed}, load="LC1", duration={sim})
t2 = time.perf_counter()
print(t1 - t0, t2 - t1)
""".format(speed=SPEED, sim=SIM_TIME)


def fresh_process(model, cache_dir):
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir, NUMBA_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", CHILD, model], capture_output=True, text=True, env=env,
                         check=True)
    imp, first = (float(v) for v in out.stdout.split())
    return imp, first


def steady(model, repeats=21):
    """Median wall time of Trailer.run (tyre model and trailer set up once, as a study does)."""
    from tyrelab.api import make_tyre_model
    from tyrelab.rig.trailer import Trailer
    trailer = Trailer(make_tyre_model(model=model), "LC1")
    trailer.run("cleat:50x50", SPEED, SIM_TIME)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        trailer.run("cleat:50x50", SPEED, SIM_TIME)
        times.append(time.perf_counter() - t)
    return statistics.median(times), min(times)


def main(models):
    print(f"trailer, cleat 50 x 50 mm, {SPEED * 3.6:.0f} km/h, LC1, {SIM_TIME:.0f} s simulated, "
          f"dt = 1 ms, output 1 kHz")
    print(f"{'model':<12}{'compile+run, empty cache':>26}{'run, cached, new process':>26}"
          f"{'steady run (median)':>22}{'x real time':>14}")
    for model in models:
        with tempfile.TemporaryDirectory() as cache:
            _, first = fresh_process(model, cache)
            _, cached = fresh_process(model, cache)
        med, best = steady(model)
        print(f"{model:<12}{first:>24.2f} s{cached:>24.3f} s{med * 1e3:>19.1f} ms{SIM_TIME / med:>14.0f}")


if __name__ == "__main__":
    main(sys.argv[1:] or ["point"])
