"""How a study store keeps its runs (tyrelab.study.store: "compact", "lossless", "full").

One real short run (the point model over the 50 mm cleat, the trailer's 6 s, 31
channels) written in each form and read back; a table written as every store was
before the forms existed; the spec's ``[study] store`` key; and a tiny study whose
metrics, computed from a compact store and from a full one, are bit-identical.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

import tyrelab
from tyrelab.errors import InputError
from tyrelab.signal import FLOAT32_RELATIVE_ERROR, make_signal, read_signal, write_signal
from tyrelab.study import evaluate as ev
from tyrelab.study import tasks
from tyrelab.study.spec import parse_spec
from tyrelab.study.store import (COMPACT, COMPACT_CHANNELS, DEFAULT_STORAGE, FULL, LOSSLESS,
                                 STORAGE, Store, write_run)
from tyrelab.validate.compare import METRICS

#: float32's absolute resolution below its smallest normal number (half its smallest step)
TINY_ERROR = 2.0 ** -150


@pytest.fixture(scope="module")
def run():
    return tyrelab.simulate(model="point", road="cleat:50x50", progress=False)


def write_as_before(df: pd.DataFrame, path) -> None:
    """A signal table written as tyrelab wrote every one before the store's forms (the code
    of write_signal then): pyarrow's defaults, units and metadata in the schema metadata."""
    meta = {"units": df.attrs.get("units", {}), "metadata": df.attrs.get("metadata", {})}
    table = pa.Table.from_pandas(df, preserve_index=False)
    table = table.replace_schema_metadata({**(table.schema.metadata or {}),
                                           b"tyrelab": json.dumps(meta).encode()})
    pq.write_table(table, path)


def column_chunks(path) -> dict:
    """{column: (physical type, compression, encodings)} of a Parquet file's first row group."""
    md = pq.read_metadata(path)
    out = {}
    for i in range(md.num_columns):
        c = md.row_group(0).column(i)
        out[c.path_in_schema] = (c.physical_type, c.compression, set(c.encodings))
    return out


def test_the_default_is_compact():
    assert DEFAULT_STORAGE == COMPACT and STORAGE == (COMPACT, LOSSLESS, FULL)


def test_lossless_reads_back_bit_identical(run, tmp_path):
    path = tmp_path / "run.parquet"
    write_run(run, path, LOSSLESS)
    back = read_signal(path)
    pd.testing.assert_frame_equal(back, run, check_exact=True)
    assert back.attrs["units"] == run.attrs["units"]
    assert back.attrs["metadata"] == run.attrs["metadata"]
    chunks = column_chunks(path)
    assert list(chunks) == list(run.columns)
    for col, (physical, compression, encodings) in chunks.items():
        assert (physical, compression) == ("DOUBLE", "ZSTD"), col
        assert "BYTE_STREAM_SPLIT" in encodings and "RLE_DICTIONARY" not in encodings, col


def test_compact_keeps_the_evaluated_channels_within_float32_rounding(run, tmp_path):
    path = tmp_path / "run.parquet"
    write_run(run, path, COMPACT)
    back = read_signal(path)
    assert list(back.columns) == [c for c in run.columns if c in COMPACT_CHANNELS]
    assert set(back.columns) == set(COMPACT_CHANNELS)  # the trailer has every one of them
    assert all(back[c].dtype == np.float64 for c in back.columns)  # read as float64
    chunks = column_chunks(path)
    for col in back.columns:
        new, old = back[col].to_numpy(), run[col].to_numpy()
        if col in ("RUNTIME", "FZ_HUB"):  # time and the compared force: exact
            assert np.array_equal(new, old), col
            assert chunks[col][0] == "DOUBLE"
        else:  # rounded to the nearest float32, no further
            assert chunks[col][0] == "FLOAT", col
            assert np.array_equal(new, old.astype(np.float32).astype(np.float64)), col
            bound = np.maximum(np.abs(old) * FLOAT32_RELATIVE_ERROR, TINY_ERROR)
            assert np.all(np.abs(new - old) <= bound), col
        assert chunks[col][1] == "ZSTD" and "BYTE_STREAM_SPLIT" in chunks[col][2], col
    assert back.attrs["metadata"] == run.attrs["metadata"]
    assert set(back.attrs["units"]) == set(back.columns)
    storage = back.attrs["storage"]
    assert storage["form"] == COMPACT
    assert storage["dropped"] == [c for c in run.columns if c not in COMPACT_CHANNELS]
    assert storage["float32"] == [c for c in back.columns if c not in ("RUNTIME", "FZ_HUB")]


def test_compact_without_a_load_cell_keeps_fz_exact(tmp_path):
    """A rig without FZ_HUB: the evaluation compares FZ, so FZ stays float64."""
    t = np.arange(2000) * 1e-3
    df = make_signal({"RUNTIME": t, "FZ": 2e4 + np.pi * np.sin(7 * t), "X_WC": 3.3 * t,
                      "Z_WC": 0.6 + 1e-3 * np.cos(t), "FX": np.cos(t)})
    write_run(df, tmp_path / "run.parquet", COMPACT)
    back = read_signal(tmp_path / "run.parquet")
    assert list(back.columns) == ["RUNTIME", "FZ", "X_WC", "Z_WC"]
    assert np.array_equal(back["FZ"].to_numpy(), df["FZ"].to_numpy())
    assert not np.array_equal(back["Z_WC"].to_numpy(), df["Z_WC"].to_numpy())  # float32


def test_full_is_the_form_of_before_byte_for_byte(run, tmp_path):
    write_run(run, tmp_path / "full.parquet", FULL)
    write_as_before(run, tmp_path / "before.parquet")
    assert (tmp_path / "full.parquet").read_bytes() == (tmp_path / "before.parquet").read_bytes()
    chunks = column_chunks(tmp_path / "full.parquet")
    assert list(chunks) == list(run.columns)
    assert {v[:2] for v in chunks.values()} == {("DOUBLE", "SNAPPY")}
    assert "storage" not in read_signal(tmp_path / "full.parquet").attrs
    # write_signal's own default (tyrelab simulate -o) is that form too
    write_signal(run, tmp_path / "default.parquet")
    assert (tmp_path / "default.parquet").read_bytes() == (tmp_path / "before.parquet").read_bytes()


def test_an_old_store_still_reads(run, tmp_path):
    """A store folder written before the forms: its table reads back identically."""
    store = Store(tmp_path / "old")
    write_as_before(run, store.signal_path("k1"))
    store.record_path("k1").write_text(json.dumps({"key": "k1", "status": "done"}))
    back = store.signal("k1")
    pd.testing.assert_frame_equal(back, run, check_exact=True)
    assert back.attrs["units"] == run.attrs["units"]
    assert back.attrs["metadata"] == run.attrs["metadata"]


def test_compact_is_a_fraction_of_the_size_of_before(run, tmp_path):
    """Measured (benchmarks/store_format.py): the campaign's 200 runs 19x smaller compact,
    1.8x lossless; this 6 s point run 14x and 1.6x. The bounds leave a margin."""
    sizes = {}
    for form in STORAGE:
        write_run(run, tmp_path / f"{form}.parquet", form)
        sizes[form] = (tmp_path / f"{form}.parquet").stat().st_size
    assert sizes[COMPACT] <= sizes[FULL] / 10
    assert sizes[LOSSLESS] <= sizes[FULL] / 1.4


def test_float32_keeps_a_column_beyond_its_range_as_float64(tmp_path):
    df = make_signal({"RUNTIME": [0.0, 1.0, 2.0], "A": [1.0, 1e300, np.nan], "B": [0.1, 0.2, np.nan]})
    write_signal(df, tmp_path / "t.parquet", compression="zstd", float32=["A", "B"])
    back = read_signal(tmp_path / "t.parquet")
    assert np.array_equal(back["A"].to_numpy(), df["A"].to_numpy(), equal_nan=True)
    assert np.isnan(back["B"].iloc[2]) and back["B"].iloc[0] == np.float32(0.1)
    assert back.attrs["storage"]["float32"] == ["B"]
    with pytest.raises(ValueError, match="Parquet files only"):
        write_signal(df, tmp_path / "t.csv", float32=["B"])


# ---------------------------------------------------------------------------
# the spec's option and the store

SPEC = """[study]
name = "forms"
{store}
[[tyre]]
name = "xzl"
file = "xzl-16.00R20"
pressure_kpa = 300

[[model]]
name = "OPC lk"
contact = "point"
stiffness = "linear"
handling = "none"

[[model]]
name = "OPC nlk"
contact = "point"
stiffness = "table"
handling = "none"

[[test]]
name = "cleat"
group = "discrete obstacles"
road = "cleat:50x50"
speeds_kmh = [18]
loads = ["LC1"]
duration = 2.0
reference = {{ model = "OPC nlk" }}
"""


def test_the_spec_option_and_its_error(tmp_path):
    default = parse_spec(SPEC.format(store=""), base=tmp_path)
    assert default.store == COMPACT
    for form in STORAGE:
        spec = parse_spec(SPEC.format(store=f'store = "{form}"'), base=tmp_path)
        assert spec.store == form
        assert spec.run_keys() == default.run_keys()  # the form is not part of a run's key
    with pytest.raises(InputError) as err:
        parse_spec(SPEC.format(store='store = "float16"'), "spec.toml", base=tmp_path)
    text = str(err.value)
    assert "study.store" in text and "float16" in text and "line 3" in text
    assert all(form in text for form in STORAGE)


def test_a_study_writes_the_form_its_spec_names(tmp_path):
    """``tyrelab.study.run`` hands the spec's ``[study] store`` to its store: a spec saying
    "full" gets snappy float64 tables of every channel; a store given no form writes compact;
    an unknown form is refused listing the allowed ones."""
    from tyrelab.study import run as run_study
    assert Store(tmp_path / "plain").storage == COMPACT
    spec = parse_spec(SPEC.format(store='store = "full"'), base=tmp_path)
    study = run_study(spec, workers=1, output=tmp_path / "s", progress=False)
    tables = sorted((tmp_path / "s" / "runs").glob("*.parquet"))
    assert len(tables) == 2 and len(study.index) == 2
    for path in tables:
        chunks = column_chunks(path)
        assert len(chunks) > len(COMPACT_CHANNELS)
        assert {v[:2] for v in chunks.values()} == {("DOUBLE", "SNAPPY")}
    with pytest.raises(InputError, match='"compact", "lossless", "full"'):
        Store(tmp_path / "bad", storage="float32")


def test_metrics_from_a_compact_store_are_bit_identical(tmp_path):
    """Two models over the cleat, one the other's reference: every metric and segment time
    computed from the compact store equals the one from the full store, bit for bit."""
    spec = parse_spec(SPEC.format(store=""), base=tmp_path)
    stores = {form: Store(tmp_path / form, storage=form) for form in (COMPACT, FULL)}
    for task in tasks(spec):
        table = tyrelab.simulate(**task["simulate"], progress=False)
        for store in stores.values():
            store.save(task["key"], task["spec"], table, wall_time=1.0)
    compact, full = (ev.evaluate_study(spec, stores[f], progress=False) for f in (COMPACT, FULL))
    assert (full["error"] == "").all() and len(full) == 2
    assert np.isfinite(full.loc[~full["is_reference"], "mRE_disturbance_pct"]).all()
    pd.testing.assert_frame_equal(compact, full, check_exact=True)
    assert set(METRICS) <= set(full.columns)
