"""Benchmark: the study store's Parquet form -- size on disk, write/read time, metric change.

    python benchmarks/store_format.py [--study FOLDER] [--work DIR] [--runs N] [--keep]

Re-encodes every finished run of a study folder (default ``/work/runs/def1``,
the built-in campaign; read only) in each candidate form below, into
``--work`` (default ``/tmp/store_study``), and prints one row per form: its
size (sum of the files' sizes, and scaled to all the runs of the study's
spec), the write and read times of all the runs (a float64 DataFrame in, one
out, :func:`tyrelab.signal.read_signal`), the largest relative change of a
stored value and, for every form that is not lossless on every channel, the
largest relative change of each metric of :func:`tyrelab.study.evaluate.evaluate_study`
recomputed from the re-encoded runs (a copy of the study folder per form)
against the metrics of today's form (evaluated the same way, from today's files).

Forms (all from pyarrow; ``bss``: byte-stream split of the float columns,
``eval``: only the channels the study's evaluation and report read,
:data:`tyrelab.study.store.COMPACT_CHANNELS`):

* today: snappy, dictionary encoding, float64 (``write_signal``'s default, ``store = "full"``)
* zstd-N [+ bss]: lossless, float64 (``store = "lossless"`` is zstd-3 + bss)
* f32: every channel rounded to float32, zstd-3 + bss
* eval f64 / eval f32: the evaluated channels only, float64 or float32 (time too, or not)
* eval f32, t+force f64: the evaluated channels, time and compared force float64
  (``store = "compact"``, the default; its row is written by the store itself)
"""

from __future__ import annotations

import argparse
import json
import shutil
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from tyrelab.signal import read_signal
from tyrelab.study import evaluate as ev
from tyrelab.study import store as st
from tyrelab.study.results import Study
from tyrelab.validate.compare import METRICS


@dataclass(frozen=True)
class Form:
    name: str
    compression: str = "snappy"
    level: int | None = None
    bss: bool = False
    channels: tuple | None = None      # None: every channel
    float32: bool = False              # stored as float32 ...
    keep64: tuple = ()                 # ... except these
    storage: str | None = None         # written by tyrelab.study.store in this form instead

    @property
    def lossy(self) -> bool:
        return self.float32 or self.channels is not None or self.storage == st.COMPACT


EVAL = st.COMPACT_CHANNELS
FORMS = [
    Form("today: snappy f64 (store=full)", storage=st.FULL),
    Form("zstd-3 f64 (no bss)", "zstd", 3),
    Form("zstd-1 + bss f64", "zstd", 1, True),
    Form("zstd-3 + bss f64 (store=lossless)", storage=st.LOSSLESS),
    Form("zstd-9 + bss f64", "zstd", 9, True),
    Form("f32 zstd-3 + bss", "zstd", 3, True, float32=True),
    Form("eval f64 zstd-3 + bss", "zstd", 3, True, EVAL),
    Form("eval f32 zstd-3 + bss", "zstd", 3, True, EVAL, True),
    Form("eval f32, time f64, zstd-3 + bss", "zstd", 3, True, EVAL, True, ("RUNTIME",)),
    Form("eval f32, t+force f64, zstd-1", "zstd", 1, True, EVAL, True, ("RUNTIME", "FZ_HUB")),
    Form("eval f32, t+force f64, zstd-9", "zstd", 9, True, EVAL, True, ("RUNTIME", "FZ_HUB")),
    Form("eval f32, t+force f64 (store=compact)", storage=st.COMPACT),
]


def write_form(df: pd.DataFrame, path: Path, form: Form) -> None:
    """Write ``df`` in ``form`` (the store's own writer for its named forms)."""
    if form.storage is not None:
        st.write_run(df, path, form.storage)
        return
    cols = [c for c in df.columns if form.channels is None or c in form.channels]
    out = df[cols].copy()
    if form.float32:
        for c in cols:
            if c not in form.keep64:
                out[c] = out[c].to_numpy().astype(np.float32)
    table = pa.Table.from_pandas(out, preserve_index=False)
    meta = json.dumps({"units": df.attrs.get("units", {}), "metadata": df.attrs.get("metadata", {})})
    table = table.replace_schema_metadata({**(table.schema.metadata or {}), b"tyrelab": meta.encode()})
    kw = {"compression": form.compression, "compression_level": form.level}
    if form.bss:
        kw.update(use_dictionary=False, use_byte_stream_split=[c for c in cols])
    pq.write_table(table, path, **kw)


def relative_change(new: np.ndarray, old: np.ndarray, floor: float = 0.0) -> float:
    """Largest |new - old| / max(|old|, floor) (where that is 0: |new - old|); inf where NaN
    differs. Values: ``floor`` float32's smallest normal number (a value below it, 1e-90 N m
    of a moment at rest, keeps float32's absolute resolution, 1.4e-45, not its relative one)."""
    new, old = np.asarray(new, dtype=float), np.asarray(old, dtype=float)
    if not np.array_equal(np.isnan(new), np.isnan(old)):
        return float("inf")
    ok = ~np.isnan(old)
    d = np.abs(new[ok] - old[ok])
    scale = np.maximum(np.abs(old[ok]), floor)
    scale[scale == 0] = 1.0
    return float(np.max(d / scale)) if d.size else 0.0


TINY = float(np.finfo(np.float32).tiny)


def measured_keys(spec, store, first: int | None) -> list[str]:
    """The finished runs' keys in the spec's order; with ``first``, the first ``first`` runs
    and the reference runs they are compared with (so that their metrics can be computed)."""
    keys = spec.run_keys()
    out = []
    for run in spec.runs():
        if first is not None and len(out) >= first:
            break
        ref = spec.reference_run(run)
        for key in (keys[ref] if ref is not None else None, keys[run]):
            if key is not None and key not in out and store.is_finished(key):
                out.append(key)
    return out


def copy_study(study: Path, folder: Path) -> None:
    """A study folder at ``folder`` with ``study``'s spec and records, no tables yet."""
    (folder / "runs").mkdir(parents=True, exist_ok=True)
    for name in ("spec.toml", "study.json"):
        shutil.copy2(study / name, folder / name)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--study", default="/work/runs/def1", help="a finished study folder (read only)")
    ap.add_argument("--work", default="/tmp/store_study/bench", help="scratch folder (rewritten)")
    ap.add_argument("--runs", type=int, default=None, help="only the first N runs (a quick look)")
    ap.add_argument("--no-metrics", action="store_true", help="sizes and times only")
    ap.add_argument("--keep", action="store_true", help="keep the re-encoded runs")
    args = ap.parse_args()
    study, work = Path(args.study), Path(args.work)
    source = Study(study)  # read only: its store is never written
    spec = source.spec
    keys = list(dict.fromkeys(spec.run_keys().values()))
    have = measured_keys(spec, source.store, args.runs)
    print(f"{study}: {len(keys)} runs in the spec, {len(have)} measured", flush=True)
    if work.exists():
        shutil.rmtree(work)
    folders = {f: work / f"form{i}" for i, f in enumerate(FORMS)}
    for folder in folders.values():
        copy_study(study, folder)
    size = dict.fromkeys(FORMS, 0)
    t_write = dict.fromkeys(FORMS, 0.0)
    t_read = dict.fromkeys(FORMS, 0.0)
    change = dict.fromkeys(FORMS, 0.0)
    rows = 0
    for n, key in enumerate(have):
        df = read_signal(source.store.signal_path(key))
        rows += len(df)
        record = source.store.record_path(key)
        for form, folder in folders.items():
            path = folder / "runs" / f"{key}.parquet"
            t0 = time.perf_counter()
            write_form(df, path, form)
            t_write[form] += time.perf_counter() - t0
            size[form] += path.stat().st_size
            t0 = time.perf_counter()
            back = read_signal(path)
            t_read[form] += time.perf_counter() - t0
            assert all(back[c].dtype == np.float64 for c in back.columns)
            for c in back.columns:
                change[form] = max(change[form], relative_change(back[c], df[c], TINY))
            shutil.copy2(record, folder / "runs" / record.name)
        if (n + 1) % 20 == 0:
            print(f"  {n + 1} runs re-encoded", flush=True)
    scale = len(keys) / len(have)
    metric_change = {}
    if not args.no_metrics:
        base = folders[FORMS[0]]
        t0 = time.perf_counter()
        ref = ev.evaluate_study(Study(base).spec, Study(base).store, progress=False)
        print(f"  metrics of today's form: {time.perf_counter() - t0:.0f} s", flush=True)
        for form in FORMS:
            if form.lossy:
                s = Study(folders[form])
                new = ev.evaluate_study(s.spec, s.store, progress=False)
                assert list(new["key"]) == list(ref["key"])
                metric_change[form] = {m: relative_change(new[m], ref[m]) for m in METRICS}
                metric_change[form]["segments"] = max(relative_change(new[c], ref[c])
                                                      for c in ev.SEGMENT_COLUMNS)
                metric_change[form]["errors"] = int((new["error"] != "").sum())
        errors = int((ref["error"] != "").sum())
    channels = len(df.columns)
    today = size[FORMS[0]]
    print(f"\n{len(have)} runs, {rows} samples ({rows * channels * 8 / 1e6:.0f} MB as raw float64, "
          f"{channels} channels); campaign = {len(keys)} runs (x{scale:.3g})\n")
    print("| form | MB per run (mean) | campaign MB | today / form | write s | read s | "
          "max value change | max metric change |")
    print("|---|---|---|---|---|---|---|---|")
    for form in FORMS:
        mc = metric_change.get(form)
        if mc is None:
            mtxt = "bit-identical (lossless)" if not form.lossy else "not evaluated"
        else:
            worst = max(v for k, v in mc.items() if k in METRICS)
            mtxt = "bit-identical" if worst == 0 else f"{worst:.1e}"
        vtxt = "0" if change[form] == 0 else f"{change[form]:.1e}"
        print(f"| {form.name} | {size[form] / len(have) / 1e6:.2f} | {size[form] * scale / 1e6:.0f} | "
              f"{today / size[form]:.1f} | {t_write[form]:.1f} | {t_read[form]:.1f} | "
              f"{vtxt} | {mtxt} |")
    if metric_change:
        print(f"\nlargest relative change per metric (vs today's form, whose metrics have {errors} "
              "rows with an error; 0 = bit-identical; segments: the disturbance and response "
              "start and end times):\n")
        names = [f.name for f in metric_change]
        print("| metric | " + " | ".join(names) + " |")
        print("|---|" + "---|" * len(names))
        for m in (*METRICS, "segments", "errors"):
            print(f"| {m} | " + " | ".join(f"{metric_change[f][m]:.1e}" if m != "errors"
                                           else str(metric_change[f][m]) for f in metric_change) + " |")
    if not args.keep:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
