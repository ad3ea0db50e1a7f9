"""Whole comparisons, repeatability, tables and the ``validate`` command."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab.cli.main import main
from tyrelab.errors import InputError
from tyrelab.measure import write_tydex
from tyrelab.signal import make_signal, write_signal
from tyrelab.validate import (beside_repeatability, compare_runs, metrics_table, rank_models,
                              repeatability, summary_markdown, summary_table, table_html,
                              table_markdown)

DATA = Path(__file__).parent / "data" / "tydex"


def cleat(fs=500.0, duration=3.0, t0=1.0, T=0.1, amp=20e3, ring=8e3, f_ring=4.0,
          delay=0.0):
    t = np.arange(int(duration * fs)) / fs
    tt = t - delay
    y = np.full(t.size, 30e3)
    on = (tt >= t0) & (tt < t0 + T)
    y[on] += amp * np.sin(np.pi * (tt[on] - t0) / T)
    after = tt >= t0 + T
    ta = tt[after] - (t0 + T)
    y[after] += -ring * np.exp(-2.0 * ta) * np.sin(2 * np.pi * f_ring * ta)
    return make_signal({"RUNTIME": t, "FZ": y}, {"name": "cleat"})


def test_identical_runs_give_zero_errors():
    m = cleat()
    res = compare_runs(m, m, segments="auto")
    for key in ("mRE_disturbance_pct", "RE80_disturbance_pct", "rms_disturbance_N",
                "mRE_response_pct", "rms_response_N", "mean_error_pct", "std_error_pct",
                "SG_M", "SG_C", "R_C", "max_error_pct", "damage_ratio_log10", "psd_lsd_dB"):
        assert res[key] == pytest.approx(0.0, abs=1e-6), key
    assert res["details"]["segments"].disturbance == pytest.approx((1.0, 1.1), abs=1e-9)


def test_larger_prediction_has_known_disturbance_error():
    meas = cleat()
    sim = cleat(amp=22e3)  # pulse 10 % higher, same response
    res = compare_runs(sim, meas, segments="auto")
    # on the pulse |p - m| / m = 2e3 sin / (30e3 + 20e3 sin): the largest is at the crest
    assert res["RE80_disturbance_pct"] < 2e3 / 50e3 * 100 + 1e-9
    assert res["RE80_disturbance_pct"] > 0
    assert res["mRE_response_pct"] == pytest.approx(0.0, abs=1e-9)


def test_auto_shift_removes_a_delay():
    meas = cleat()
    sim = cleat(delay=-0.05)  # simulation 50 ms early
    plain = compare_runs(sim, meas, segments="auto")
    shifted = compare_runs(sim, meas, segments="auto", shift="auto")
    assert shifted["details"]["shift_s"] == pytest.approx(0.05, abs=0.002)
    assert shifted["mRE_disturbance_pct"] < 0.2 * plain["mRE_disturbance_pct"]


def test_auto_shift_finds_a_run_logged_on_its_own_clock():
    """A logger started 2.5 s before the simulation's run-up and ran on for 0.5 s after it, its
    clock reading 50 s at its first sample: the shift is found (52.5 s, to 2 ms) and the
    comparison is the aligned one's. Before, the search stopped at a quarter of the shorter
    record from the clocks' zero: 'do not overlap in time'."""
    sim = cleat()
    late = cleat(duration=6.0, delay=2.5)
    meas = make_signal({"RUNTIME": late["RUNTIME"].to_numpy() + 50.0, "FZ": late["FZ"].to_numpy()},
                       {"name": "logged"})
    res = compare_runs(sim, meas, segments="auto", shift="auto")
    assert res["details"]["shift_s"] == pytest.approx(52.5, abs=0.002)
    assert res["mRE_disturbance_pct"] == pytest.approx(0.0, abs=0.5)


def test_repeatability_and_model_beside_it():
    a, b = cleat(), cleat(amp=20.5e3, ring=8.2e3)
    scatter = repeatability(a, b, segments="auto")
    model = compare_runs(cleat(amp=26e3, ring=5e3, f_ring=5.0), b, segments="auto")
    table = beside_repeatability(model, scatter, name="model X")
    assert list(table.index) == ["model X", "measured repeatability", "ratio"]
    r = table.loc["ratio", "mRE_disturbance_pct"]
    assert r == pytest.approx(model["mRE_disturbance_pct"] / scatter["mRE_disturbance_pct"])
    assert r > 1  # the model is worse than the measurement's own scatter
    zero = beside_repeatability(model, compare_runs(a, a, segments="auto"))
    assert zero.loc["ratio", "rms_disturbance_N"] == "scatter is zero"


def thesis_table(number):
    df = pd.read_csv(DATA / "thesis_cleat_metrics.csv")
    sel = df[df["table"] == number].set_index("model")
    return sel[["mRE_disturbance_pct", "RE80_disturbance_pct", "rms_disturbance_N",
                "mRE_response_pct", "rms_response_N"]].astype(float)


def test_ranking_marks_thesis_table_5_2_best():
    # thesis 5.2.1: FTire TP "shows the best result for every disturbance metric"
    # and 3D ENV nlk has the best response m%RE (6 %)
    table = metrics_table(thesis_table("5-2").to_dict(orient="index"))
    ranks = rank_models(table)
    for col in ("mRE_disturbance_pct", "RE80_disturbance_pct", "rms_disturbance_N"):
        assert ranks.at["FTire TP", col] == 1
    assert ranks["mRE_response_pct"].idxmin() == "3D ENV nlk"
    md = table_markdown(table)
    assert "| FTire TP | **6.00** (1) | **10.0** (1) | **752** (1) |" in md
    assert md.count("(1)") == 5
    html = table_html(table)
    assert html.count("#7fd17f") == 5          # one green (best) cell per metric
    assert html.count("<tr>") == 1 + len(table)


def test_ties_share_rank_and_nan_rejected():
    t = metrics_table({"a": {"e": 1.0}, "b": {"e": -1.0}, "c": {"e": 2.0}})
    assert list(rank_models(t)["e"]) == [1, 1, 3]
    with pytest.raises(InputError, match="NaN"):
        metrics_table({"a": {"e": np.nan}})


def test_summary_rules():
    rows = []
    for speed, (a, b, c) in {12: (5, 30, 15), 18: (8, 12, 40)}.items():
        for model, e in (("A", a), ("B", b), ("C", c)):
            rows.append({"group": "discrete obstacles", "obstacle": "cleat",
                         "speed_kmh": speed, "model": model,
                         "mRE_disturbance_pct": e, "mRE_response_pct": 10.0})
    rows.append({"group": "rough tracks", "obstacle": "paving", "speed_kmh": 3, "model": "A",
                 "mean_error_pct": 1.0, "std_error_pct": -60.0})
    rows.append({"group": "rough tracks", "obstacle": "paving", "speed_kmh": 3, "model": "B",
                 "mean_error_pct": 2.0, "std_error_pct": 24.0})
    s = summary_table(pd.DataFrame(rows))
    assert s.loc[("discrete obstacles", "cleat"), "A"] == "comparable, best"
    assert s.loc[("discrete obstacles", "cleat"), "B"] == "comparable, under certain conditions"
    assert s.loc[("discrete obstacles", "cleat"), "C"] == "comparable, under certain conditions"
    assert s.loc[("rough tracks", "paving"), "A"] == "not representative"
    assert s.loc[("rough tracks", "paving"), "B"] == "comparable, best"
    assert s.loc[("rough tracks", "paving"), "C"] == "not tested"
    assert "| rough tracks | paving | not representative |" in summary_markdown(s)


def test_summary_of_thesis_cleats_names_ftire_best():
    df = pd.read_csv(DATA / "thesis_cleat_metrics.csv")
    df = df[df["model"].isin(["FTire TP", "3D ENV nlk", "3D VC nlk", "OPC nlk"])]
    df = df[df["obstacle"].str.startswith("cleat")].assign(group="discrete obstacles",
                                                           obstacle="cleats")
    s = summary_table(df)
    # thesis Table 5-15: FTire best on cleats, OPC not representative
    assert s.loc[("discrete obstacles", "cleats"), "FTire TP"].endswith("best")
    assert s.loc[("discrete obstacles", "cleats"), "OPC nlk"] == "not representative"
    assert s.loc[("discrete obstacles", "cleats"), "3D VC nlk"] == "not representative"
    assert s.loc[("discrete obstacles", "cleats"), "3D ENV nlk"].startswith("comparable")


def test_cli_validate_writes_page(tmp_path, capsys):
    write_signal(cleat(fs=1000.0, amp=22e3), tmp_path / "sim.parquet")
    write_tydex(cleat(), tmp_path / "meas.tdx", units={"FZ": "kN"})
    write_tydex(cleat(amp=20.4e3), tmp_path / "meas2.tdx")
    out = tmp_path / "page.html"
    code = main(["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "meas.tdx"),
                 "--html", str(out), "--repeat", str(tmp_path / "meas2.tdx")])
    printed = capsys.readouterr().out
    assert code == 0
    assert "mRE_disturbance_pct" in printed and "measured repeatability" in printed
    text = out.read_text()
    assert text.count("data:image/png;base64,") == 4
    assert "Relative error over time" in text


def test_cli_bad_measurement_is_one_line_error(tmp_path, capsys):
    write_signal(cleat(), tmp_path / "sim.parquet")
    (tmp_path / "bad.tdx").write_text("**MEASURCHANNELS\nRUNTIME   t     s\nFZ   f   N\n"
                                      "**MEASURDATA\n0 1\n1 x\n**END\n")
    out = tmp_path / "page.html"
    code = main(["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "bad.tdx"),
                 "--html", str(out)])
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and "line 6" in err and "FZ" in err
    assert not out.exists()
    code = main(["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "bad.tdx"),
                 "--segments", "2:1"])
    assert code == 2


def test_cli_geometry_segments(tmp_path, capsys):
    # cleat() pulse is 1.0-1.1 s; at 5 m/s from x0 = 0 with a zero-height obstacle at
    # 5.0-5.5 m and a tyre circle that just reaches the road (R = HC): reach 0
    write_signal(cleat(amp=21e3), tmp_path / "sim.parquet")
    write_tydex(cleat(), tmp_path / "meas.tdx")
    code = main(["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "meas.tdx"),
                 "--segments", "geometry", "--obstacle", "5.0:5.5:0.0", "--tyre", "0.8:0.8",
                 "--speed", "5", "--html", str(tmp_path / "p.html")])
    out = capsys.readouterr().out
    assert code == 0
    assert "disturbance 1-1.1 s" in out and "(geometry)" in out
    code = main(["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "meas.tdx"),
                 "--segments", "geometry", "--obstacle", "5.0:5.5"])
    assert code == 2


def test_track_comparison_without_segments():
    rng = np.random.default_rng(5)
    t = np.arange(20000) / 200.0
    m = 30e3 + 3e3 * rng.standard_normal(t.size)
    p = m.mean() + 1.2 * (m - m.mean())
    res = compare_runs(make_signal({"RUNTIME": t, "FZ": p}), make_signal({"RUNTIME": t, "FZ": m}))
    assert "mRE_disturbance_pct" not in res
    assert res["mean_error_pct"] == pytest.approx(0.0, abs=1e-9)
    assert res["std_error_pct"] == pytest.approx(20.0, rel=1e-9)
    assert res["psd_lsd_dB"] == pytest.approx(20 * np.log10(1.2), rel=1e-6)
    assert all(np.isfinite(v) for k, v in res.items() if k != "details")


def test_summary_html_and_cli_csv_with_column_map(tmp_path, capsys):
    from tyrelab.validate import summary_html
    s = summary_table(pd.DataFrame([{"group": "rough tracks", "obstacle": "paving <1>",
                                     "model": "A", "mean_error_pct": 1.0,
                                     "std_error_pct": 5.0}]))
    html = summary_html(s)
    assert "paving &lt;1&gt;" in html and "comparable, best" in html
    meas = cleat()
    csv = tmp_path / "logger.csv"
    csv.write_text("t_ms,fz_kN\n" + "".join(f"{t * 1e3!r},{f / 1e3!r}\n" for t, f in
                                           zip(meas["RUNTIME"], meas["FZ"])))
    cmap = tmp_path / "map.csv"
    cmap.write_text("t_ms,RUNTIME,ms\nfz_kN,FZ,kN\n")
    write_signal(cleat(amp=21e3), tmp_path / "sim.parquet")
    code = main(["validate", str(tmp_path / "sim.parquet"), str(csv), "--column-map", str(cmap),
                 "--html", str(tmp_path / "p.html")])
    assert code == 0
    code = main(["validate", str(tmp_path / "sim.parquet"), str(csv), "--column-map", str(cmap),
                 "--channel", "FY", "--html", str(tmp_path / "q.html")])
    err = capsys.readouterr().err
    assert code == 2 and "sim.parquet" in err and "FY" in err
    assert not (tmp_path / "q.html").exists()


def test_a_logger_on_the_opposite_axis_is_warned_and_read_with_a_minus(tmp_path, capsys):
    """A load cell logging the road's force on the tyre along z down (ISO W-axis) gives FZ < 0.
    Compared as given, the prediction is the exact negative of the measurement, so its mean is
    off by 200 % of the measured mean. The comparison warns, naming the column map's '-FZ';
    read with '-FZ', the same file matches the prediction exactly, without a warning."""
    meas = cleat()
    csv = tmp_path / "logger.csv"
    csv.write_text("t_s,fz_kN\n" + "".join(f"{t!r},{-f / 1e3!r}\n" for t, f in
                                          zip(meas["RUNTIME"], meas["FZ"])))
    write_signal(meas, tmp_path / "sim.parquet")
    sim = str(tmp_path / "sim.parquet")
    plain, minus = tmp_path / "plain.csv", tmp_path / "minus.csv"
    plain.write_text("t_s,RUNTIME,s\nfz_kN,FZ,kN\n")
    minus.write_text("t_s,RUNTIME,s\nfz_kN,-FZ,kN\n")
    code = main(["validate", sim, str(csv), "--column-map", str(plain),
                 "--segments", "none", "--html", str(tmp_path / "a.html")])
    out, err = capsys.readouterr()
    assert code == 0 and "| mean_error_pct | % | -200 |" in out
    assert "warning:" in err and "logger.csv: the measured FZ has on average the opposite sign" in err
    assert "(negative against positive)" in err
    assert "'-FZ' in the column map" in err
    code = main(["validate", sim, str(csv), "--column-map", str(minus),
                 "--segments", "none", "--html", str(tmp_path / "b.html")])
    out, err = capsys.readouterr()
    assert code == 0 and "warning" not in err
    from tyrelab.measure.io import read_run
    res = compare_runs(meas, read_run(csv, column_map=minus))
    assert res["SG_C"] == pytest.approx(0.0, abs=1e-9)
    assert res["mean_error_pct"] == pytest.approx(0.0, abs=1e-9)
    (tmp_path / "time.csv").write_text("t_s,-RUNTIME,s\nfz_kN,FZ,kN\n")
    code = main(["validate", sim, str(csv), "--column-map", str(tmp_path / "time.csv")])
    assert code == 2 and "'-RUNTIME'" in capsys.readouterr().err


def test_a_signal_without_a_disturbance_names_the_file_and_the_way_out(tmp_path, capsys):
    """A constant measurement has no disturbance for the automatic segmentation to find, and
    no energy about its mean for the Sprague-Geers magnitude: both refusals name the file."""
    m = cleat()
    write_signal(m, tmp_path / "sim.parquet")
    flat = make_signal({"RUNTIME": m["RUNTIME"], "FZ": np.full(len(m), 30e3)})
    write_signal(flat, tmp_path / "flat.parquet")
    args = ["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "flat.parquet"),
            "--html", str(tmp_path / "p.html")]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "flat.parquet: FZ: --segments auto:" in err
    assert "--segments none" in err
    assert main(args + ["--segments", "none"]) == 2
    err = capsys.readouterr().err
    assert "sim.parquet vs" in err and "flat.parquet" in err and "the measurement equals" in err
    assert not (tmp_path / "p.html").exists()


def test_missing_measured_samples_say_why_the_psd_is_left_out(tmp_path, capsys):
    """NaN samples dropped from the measurement leave an uneven time base, on which Welch's PSD
    is not defined: the PSD metrics are absent and the notes say why, rather than vanish."""
    m = cleat()
    gappy = m.copy()
    gappy.loc[100:149, "FZ"] = np.nan
    write_signal(m, tmp_path / "sim.parquet")
    write_signal(gappy, tmp_path / "gappy.parquet")
    code = main(["validate", str(tmp_path / "sim.parquet"), str(tmp_path / "gappy.parquet"),
                 "--html", str(tmp_path / "p.html")])
    out = capsys.readouterr().out
    assert code == 0 and "psd_lsd_dB" not in out
    assert "no PSD metrics: 50 measured samples are missing (NaN)" in out


def test_a_psd_of_fewer_samples_than_its_shortest_segment_is_one_welch_window():
    """The Welch segment never exceeds the record (scipy would warn and shorten it): seven
    samples asked for in two-second segments at 1 Hz are one periodic-Hann window, whose
    one-sided PSD summed over its four bins (df = fs / 7) is, by the discrete Parseval
    theorem, the windowed mean square of the mean-removed record."""
    import warnings

    from scipy.signal import get_window

    from tyrelab.validate import psd
    y = np.sin(np.arange(7) * 0.9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        f, pxx = psd(y, fs=1.0, segment_seconds=2.0)
    w, yd = get_window("hann", 7), y - y.mean()
    assert f.size == 4
    assert pxx.sum() / 7 == pytest.approx(np.sum((w * yd) ** 2) / np.sum(w ** 2), rel=1e-12)
