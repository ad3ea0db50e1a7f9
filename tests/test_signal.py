"""The signal table: SI columns with units, files that are complete or absent."""

import numpy as np
import pandas as pd
import pytest

from tyrelab.errors import InputError
from tyrelab.signal import make_signal, read_signal, write_signal


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_round_trip_keeps_values_units_and_metadata(tmp_path, suffix):
    t = np.linspace(0, 1, 101)
    df = make_signal({"RUNTIME": t, "FZW": 1e4 + 100 * np.sin(t), "EXTRA": t ** 2},
                     {"road": "cleat 50 x 50 mm", "speed_m_s": 3.33})
    path = tmp_path / ("run" + suffix)
    write_signal(df, path)
    back = read_signal(path)
    np.testing.assert_allclose(back.to_numpy(), df.to_numpy(), rtol=1e-8)
    assert list(back.columns) == ["RUNTIME", "FZW", "EXTRA"]
    assert back.attrs["units"]["FZW"] == "N"
    assert back.attrs["metadata"] == {"road": "cleat 50 x 50 mm", "speed_m_s": 3.33}


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_reading_some_channels_gives_those_of_the_whole_table(tmp_path, suffix):
    t = np.linspace(0, 1, 101)
    df = make_signal({"RUNTIME": t, "FZW": 1e4 + 100 * np.sin(t), "EXTRA": t ** 2})
    path = tmp_path / ("run" + suffix)
    write_signal(df, path)
    part = read_signal(path, ("RUNTIME", "EXTRA"))
    assert list(part.columns) == ["RUNTIME", "EXTRA"] and set(part.attrs["units"]) == {"RUNTIME", "EXTRA"}
    np.testing.assert_array_equal(part.to_numpy(), read_signal(path)[["RUNTIME", "EXTRA"]].to_numpy())
    with pytest.raises(InputError, match="not a readable signal table"):
        read_signal(path, ("RUNTIME", "FX"))


def test_failed_write_leaves_nothing(tmp_path):
    class Boom(pd.DataFrame):
        def to_csv(self, *a, **k):
            raise RuntimeError("disk full")

    df = Boom({"RUNTIME": [0.0, 1.0]})
    with pytest.raises(RuntimeError):
        write_signal(df, tmp_path / "run.csv")
    assert list(tmp_path.iterdir()) == []


def test_unknown_format(tmp_path):
    with pytest.raises(InputError, match="expected .parquet or .csv"):
        write_signal(make_signal({"RUNTIME": [0.0]}), tmp_path / "run.xlsx")
