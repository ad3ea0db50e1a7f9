"""TYDEX and mapped-CSV reading and writing: round trips, units, malformed files."""

import math

import numpy as np
import pandas as pd
import pytest

from tyrelab.errors import InputError
from tyrelab.measure import read_mapped_csv, read_run, read_tydex, write_tydex
from tyrelab.measure.columns import read_column_map
from tyrelab.signal import make_signal


def cleat_run(n=400, fs=200.0):
    """Half-sine pulse then a damped sine: a hand-made cleat response."""
    t = np.arange(n) / fs
    fz = np.full(n, 30e3)
    t0, T = 0.5, 0.1
    pulse = (t >= t0) & (t < t0 + T)
    fz[pulse] += 20e3 * np.sin(np.pi * (t[pulse] - t0) / T)
    after = t >= t0 + T
    ta = t[after] - (t0 + T)
    fz[after] += -8e3 * np.exp(-3.0 * ta) * np.sin(2 * np.pi * 4.0 * ta)
    return make_signal({"RUNTIME": t, "FZ": fz, "FX": 0.1 * fz - 1234.5,
                        "ROTSPEED": np.full(n, 5.25), "INCLANGL": np.full(n, 0.01)},
                       {"name": "cleat50", "speed_kmh": 18, "tyre": "XZL 16.00R20"})


def test_round_trip_is_identical(tmp_path):
    df = cleat_run()
    path = tmp_path / "run.tdx"
    write_tydex(df, path)
    back = read_tydex(path)
    assert list(back.columns) == list(df.columns)
    pd.testing.assert_frame_equal(back, df, check_exact=True)
    assert back.attrs["units"] == df.attrs["units"]
    meta = {k: v for k, v in back.attrs["metadata"].items() if k != "tydex"}
    assert meta == df.attrs["metadata"]
    assert back.attrs["metadata"]["tydex"]["header"]["RELEASE"] == "1.3"


def test_round_trip_through_non_si_units(tmp_path):
    df = cleat_run()
    path = tmp_path / "run_kn.tdx"
    write_tydex(df, path, units={"FZ": "kN", "INCLANGL": "deg", "ROTSPEED": "rpm"})
    text = path.read_text()
    # the file holds kN: the static 30 kN load is written as 30.0
    assert "\n0.0 " in text and " 30.0 " in text
    back = read_tydex(path)
    np.testing.assert_allclose(back["FZ"], df["FZ"], rtol=1e-14)
    np.testing.assert_allclose(back["INCLANGL"], df["INCLANGL"], rtol=1e-14)
    assert back.attrs["units"]["FZ"] == "N"


def test_write_rejects_unit_of_other_quantity(tmp_path):
    with pytest.raises(InputError, match="FZ"):
        write_tydex(cleat_run(), tmp_path / "x.tdx", units={"FZ": "mm"})
    assert not (tmp_path / "x.tdx").exists()


HAND = """**HEADER
RELEASE   Release of TYDEX format       -         1.3
MEASID    Measurement ID                -         hand made
**COMMENTS
a file written by hand
**CONSTANTS
NOMPRES   Nominal inflation pressure    kPa       300
FNOMIN    Nominal wheel load            kN        35
**MEASURCHANNELS
RUNTIME   Running time                  ms        1
FZ        Vertical force                kN        0.001     5
LONGVEL   Longitudinal velocity         km/h      1
SLIPANGL  Slip angle                    deg       1
**MEASURDATA
0    30000  18   1.5
10   31000  18   NOTAVAIL
20   29000
     36     -2
**END
"""


def test_hand_written_file_converts_to_si(tmp_path):
    path = tmp_path / "hand.tdx"
    path.write_text(HAND)
    df = read_tydex(path)
    # RUNTIME in ms -> s
    np.testing.assert_allclose(df["RUNTIME"], [0.0, 0.010, 0.020])
    # FZ: raw * 0.001 + 5 kN -> N: 30000 -> 35 kN -> 35000 N
    np.testing.assert_allclose(df["FZ"], [35e3, 36e3, 34e3])
    np.testing.assert_allclose(df["LONGVEL"], [5.0, 5.0, 10.0])  # km/h -> m/s
    assert df["SLIPANGL"].iloc[0] == pytest.approx(1.5 * math.pi / 180)
    assert df["SLIPANGL"].iloc[2] == pytest.approx(-2 * math.pi / 180)
    assert np.isnan(df["SLIPANGL"].iloc[1])  # NOTAVAIL
    consts = df.attrs["metadata"]["tydex"]["constants"]
    assert consts["NOMPRES"]["value"] == pytest.approx(3e5)
    assert consts["FNOMIN"]["unit"] == "N" and consts["FNOMIN"]["value"] == 35e3
    assert df.attrs["units"]["LONGVEL"] == "m/s"


@pytest.mark.parametrize("old,new,line,field", [
    ("20   29000\n", "20   2x9000\n", 17, "FZ"),                      # not a number
    ("     36     -2\n", "     36     -2  7\n", 18, None),               # record too long
    ("km/h      1\n", "furlong   1\n", 12, "LONGVEL"),                  # unknown unit
    ("kN        0.001     5\n", "kN        abc\n", 11, "FZ"),           # bad factor
    ("kN        0.001     5\n", "kN        0\n", 11, "FZ"),             # zero factor
    ("SLIPANGL  Slip angle", "FZ        Slip angle", 13, "FZ"),          # channel twice
])
def test_malformed_file_names_line(tmp_path, old, new, line, field):
    assert old in HAND
    path = tmp_path / "bad.tdx"
    path.write_text(HAND.replace(old, new, 1))
    with pytest.raises(InputError) as err:
        read_tydex(path)
    assert err.value.line == line
    assert err.value.field == field
    assert str(path) in str(err.value)


def test_truncated_record_and_missing_sections(tmp_path):
    path = tmp_path / "trunc.tdx"
    path.write_text(HAND.replace("     36     -2\n", ""))
    with pytest.raises(InputError) as err:
        read_tydex(path)
    assert err.value.line == 17 and "expected 4" in str(err.value)
    path.write_text(HAND.split("**MEASURDATA")[0])
    with pytest.raises(InputError, match="missing section"):
        read_tydex(path)
    path.write_text("hello\n" + HAND)
    with pytest.raises(InputError) as err:
        read_tydex(path)
    assert err.value.line == 1
    with pytest.raises(InputError, match="no such file"):
        read_tydex(tmp_path / "absent.tdx")


def test_a_file_cut_before_its_end_line_is_read_with_a_warning(tmp_path):
    """A file that lost its closing **END (a copy or a write cut short) still holds whole
    records; they are read, and the warning names the last record's line."""
    path = tmp_path / "cut.tdx"
    path.write_text(HAND.replace("**END\n", ""))
    with pytest.warns(UserWarning, match=r"cut.tdx: no closing \*\*END.*3 records, the last on line 17"):
        df = read_tydex(path)
    np.testing.assert_allclose(df["FZ"], [35e3, 36e3, 34e3])


def test_lower_case_channel_names_are_the_tydex_channels(tmp_path):
    """'fz' spells the TYDEX channel FZ; a name tyrelab does not know keeps its own spelling."""
    path = tmp_path / "lower.tdx"
    path.write_text(HAND.replace("FZ        Vertical", "fz        Vertical")
                    .replace("LONGVEL   Long", "longvelx  Long"))
    df = read_tydex(path)
    assert list(df.columns) == ["RUNTIME", "FZ", "longvelx", "SLIPANGL"]
    np.testing.assert_allclose(df["FZ"], [35e3, 36e3, 34e3])


def test_mapped_csv(tmp_path):
    path = tmp_path / "logger.csv"
    path.write_text("# exported by a logger\nTime [ms];Fz_hub (kN);junk\n"
                    "0;30;a\n5;31.5;b\n10;;c\n")
    cmap = {"Time [ms]": ("RUNTIME", "ms"), "Fz_hub (kN)": ("FZ", "kN")}
    df = read_mapped_csv(path, cmap, delimiter=";")
    np.testing.assert_allclose(df["RUNTIME"], [0.0, 0.005, 0.010])
    np.testing.assert_allclose(df["FZ"].iloc[:2], [30e3, 31.5e3])
    assert np.isnan(df["FZ"].iloc[2])
    assert list(df.columns) == ["RUNTIME", "FZ"]
    assert df.attrs["units"] == {"RUNTIME": "s", "FZ": "N"}
    mpath = tmp_path / "map.csv"
    mpath.write_text("source,channel,unit\nTime [ms],RUNTIME,ms\nFz_hub (kN),FZ,kN\n")
    assert read_column_map(mpath) == cmap


def test_mapped_csv_errors(tmp_path):
    path = tmp_path / "logger.csv"
    path.write_text("t,fz\n0,1\n1,oops\n")
    with pytest.raises(InputError) as err:
        read_mapped_csv(path, {"t": ("RUNTIME", "s"), "fz": ("FZ", "N")})
    assert (err.value.line, err.value.field) == (3, "fz")
    with pytest.raises(InputError) as err:
        read_mapped_csv(path, {"t": ("RUNTIME", "s"), "Fz": ("FZ", "N")})
    assert (err.value.line, err.value.field) == (1, "Fz")
    with pytest.raises(InputError, match="unknown unit"):
        read_mapped_csv(path, {"t": ("RUNTIME", "fortnight")})


def test_read_run_dispatch(tmp_path):
    df = cleat_run()
    write_tydex(df, tmp_path / "a.tdx")
    assert read_run(tmp_path / "a.tdx").equals(df)
    with pytest.raises(InputError, match="unknown run format"):
        read_run(tmp_path / "a.xyz")


def test_other_layouts_header_value_in_unit_columns_and_free_channel_lines(tmp_path):
    # header value in columns 41-50, text constant, whitespace-separated channel lines
    text = ("**HEADER\n"
            + "MEASID    Measurement ID                " + "run7\n"
            + "**CONSTANTS\n"
            + "TRAJECT   Trajectory                    -         straight\n"
            + "**MEASURCHANNELS\n"
            + "RUNTIME Running_time s 1\n"
            + "FZ Vertical_force kN 2\n"
            + "**MEASURDATA\n"
            + "0.000     1.500\n"
            + "0.001     1.750\n"
            + "**END\n")
    path = tmp_path / "other.tdx"
    path.write_text(text)
    df = read_tydex(path)
    np.testing.assert_allclose(df["FZ"], [3000.0, 3500.0])   # 2 * raw kN
    np.testing.assert_allclose(df["RUNTIME"], [0.0, 0.001])
    tdx = df.attrs["metadata"]["tydex"]
    assert tdx["header"]["MEASID"] == "run7"
    assert tdx["constants"]["TRAJECT"]["value"] == "straight"
