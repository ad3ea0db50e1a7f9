"""Throughput of the compiled Magic Formula (one core).

    python benchmarks/bench_mf.py [--n 2000000] [--cold]

Prints the time of the first call (compilation, or loading numba's cache)
and evaluations per second of

- ``mf_forces`` called from another njit kernel (the rigs' time-step use),
- ``mf_evaluate_many`` (all MFeval outputs, radii and contact patch included),
- ``MagicFormula.steady_state`` (the Python API, same work plus packing).

``--cold`` compiles into a fresh temporary cache directory, so the first-call
time is the true compile time.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TIR = ROOT / "tests" / "data" / "mfeval" / "MagicFormula61_Parameters.tir"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=2_000_000, help="samples per timing run")
    parser.add_argument("--cold", action="store_true", help="compile without numba's cache")
    args = parser.parse_args()
    if args.cold:
        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="bench_mf_")
    os.environ.setdefault("NUMBA_NUM_THREADS", "1")

    import numba
    import numpy as np

    t0 = time.perf_counter()
    from tyrelab.tyre.handling.mf import MagicFormula, mf_evaluate_many, mf_forces
    t_import = time.perf_counter() - t0

    # not cached on purpose: numba's cache of a caller does not notice changes
    # in the callee (mf_forces), and a benchmark must time the current code
    @numba.njit(cache=False)
    def rig_loop(c, fz, kappa, alpha, gamma, vx, out):
        """A rig-like loop: one mf_forces call per step, forces accumulated."""
        f = np.zeros(5)
        for i in range(fz.shape[0]):
            mf_forces(c, 111, fz[i], kappa[i], alpha[i], gamma[i], vx[i], 0.0, f)
            out[0] += f[0]
            out[1] += f[1]
            out[2] += f[4]

    model = MagicFormula.from_tir(TIR)
    c = model.coefficients
    rng = np.random.default_rng(1)
    n = args.n
    fz = rng.uniform(1000.0, 12000.0, n)
    kappa = rng.uniform(-0.3, 0.3, n)
    alpha = rng.uniform(-0.3, 0.3, n)
    gamma = rng.uniform(-0.05, 0.05, n)
    vx = rng.uniform(5.0, 40.0, n)
    acc = np.zeros(3)

    t0 = time.perf_counter()
    rig_loop(c, fz[:10], kappa[:10], alpha[:10], gamma[:10], vx[:10], acc)
    t_first_forces = time.perf_counter() - t0
    full = np.empty((n, 30))
    t0 = time.perf_counter()
    mf_evaluate_many(c, 111, fz[:10], kappa[:10], alpha[:10], gamma[:10], vx[:10], np.zeros(10), full[:10])
    t_first_full = time.perf_counter() - t0

    def rate(fn, repeats=3):
        best = min(_timed(fn) for _ in range(repeats))
        return n / best

    r_forces = rate(lambda: rig_loop(c, fz, kappa, alpha, gamma, vx, acc))
    p = np.zeros(n)
    r_full = rate(lambda: mf_evaluate_many(c, 111, fz, kappa, alpha, gamma, vx, p, full))
    r_api = rate(lambda: model.steady_state(fz, kappa, alpha, gamma, vx), repeats=1)

    print(f"numba {numba.__version__}, python {sys.version.split()[0]}, n = {n:,}, "
          f"cache {'cold (fresh directory)' if args.cold else 'default'}")
    print(f"import of tyrelab.tyre.handling.mf       {t_import:8.2f} s")
    print(f"first call, mf_forces in an njit loop    {t_first_forces:8.2f} s  (compile or cache load)")
    print(f"first call, mf_evaluate_many             {t_first_full:8.2f} s  (compile or cache load)")
    print(f"mf_forces from an njit kernel            {r_forces / 1e6:8.2f} M evaluations/s")
    print(f"mf_evaluate_many (all 30 outputs)        {r_full / 1e6:8.2f} M evaluations/s")
    print(f"MagicFormula.steady_state (Python API)   {r_api / 1e6:8.2f} M evaluations/s")
    return 0


def _timed(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


if __name__ == "__main__":
    sys.exit(main())
