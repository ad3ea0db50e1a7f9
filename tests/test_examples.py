"""The examples gallery (``examples/*.py``) runs, writes what it says, and prints physics that holds.

Each script runs as a user would run it: ``python examples/NAME.py`` (a fresh
process, forked off a server that has imported tyrelab: ``tests/cli_process.py``) in a
fresh temporary folder holding a copy of ``examples/`` (its ``data/`` is the
shipped example data), writing into that folder. What it prints is read back
and checked against a physical fact, so an example that still runs but shows
nonsense fails too. The documentation shows these scripts and their figures
(docs/examples/); ``tests/test_docs.py`` runs the commands on those pages.
"""

from __future__ import annotations

import os
import re
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from cli_process import python_file

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
#: a script that has not finished in this time has hung [s]
TIMEOUT = 300


def _env() -> dict:
    env = dict(os.environ)
    env["MPLBACKEND"] = "Agg"
    return env


@pytest.fixture()
def workdir(tmp_path):
    """A fresh folder holding a copy of examples/ (as a user's working copy)."""
    shutil.copytree(EXAMPLES, tmp_path / "examples", ignore=shutil.ignore_patterns("__pycache__"))
    return tmp_path


def run_example(workdir: Path, script: str) -> str:
    """Run ``python examples/<script>`` in ``workdir``; return its standard output."""
    proc = python_file(f"examples/{script}", cwd=workdir, env=_env(), timeout=TIMEOUT)
    assert proc.returncode == 0, f"{script} failed ({proc.returncode}):\n{proc.stdout}\n{proc.stderr[-3000:]}"
    return proc.stdout


def _metrics_table(page: str) -> dict[str, dict[str, float]]:
    """The first metrics table of an HTML page: ``{model: {metric: value as shown}}``."""
    import html
    table = re.search(r"<table class='metrics'>(.*?)</table>", page, re.S)
    assert table, "no metrics table"
    head = re.search(r"<tr><th>model</th>(.*?)</tr>", table.group(1)).group(1)
    names = re.findall(r"<th>(.*?)</th>", head)
    out = {}
    for model, cells in re.findall(r"<tr><th>(.*?)</th>(<td.*?)</tr>", table.group(1)):
        values = [float(v) for v in re.findall(r"<td[^>]*>(.*?)</td>", cells)]
        out[html.unescape(model)] = dict(zip(names, values))
    return out


def number(pattern: str, text: str) -> float:
    """The number captured by ``pattern`` in ``text`` (it must be there)."""
    match = re.search(pattern, text)
    assert match, f"'{pattern}' not in the output:\n{text}"
    return float(match.group(1))


def _image(png: Path) -> np.ndarray:
    """The RGB pixels (0-1) of a PNG file (it must be one)."""
    import matplotlib.image as mpimg
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", png
    return mpimg.imread(png)[..., :3]


def _in_hue(img: np.ndarray, colour: str) -> np.ndarray:
    """Pixels of ``colour``'s hue and clearly coloured: a line drawn in it, antialiased edges
    included (black text, grey grid lines and white paper are not)."""
    import matplotlib.colors as mcolors
    hsv = mcolors.rgb_to_hsv(img)
    hue = mcolors.rgb_to_hsv(np.array(mcolors.to_rgb(colour)))[0]
    dh = np.abs(hsv[..., 0] - hue)
    return (np.minimum(dh, 1 - dh) < 0.02) & (hsv[..., 1] > 0.35) & (hsv[..., 2] > 0.3)


#: pixels of a line's colour that make a drawn curve: a legend's sample line alone has ~50
CURVE_PIXELS = 300


def _curves_drawn(png: Path, colours) -> None:
    img = _image(png)
    for colour in colours:
        assert _in_hue(img, colour).sum() > CURVE_PIXELS, (png.name, colour)


def _curve_as_data(png: Path, colour: str, x: np.ndarray, y: np.ndarray):
    """The pixels of the line drawn in ``colour`` in the one axes of ``png``, as data coordinates,
    and the size of a pixel in x and y. The axes' frame is where the black spines are; its limits
    are matplotlib's autoscale of the plotted data (``x``, ``y``): their range plus 5 % margins."""
    img = _image(png)
    dark = img.max(axis=2) < 0.25
    cols, rows = dark.sum(axis=0), dark.sum(axis=1)
    left, right = np.flatnonzero(cols > 0.5 * cols.max())[[0, -1]]
    top, bottom = np.flatnonzero(rows > 0.5 * rows.max())[[0, -1]]
    line = _in_hue(img, colour)
    line[:top + 1], line[bottom:], line[:, :left + 1], line[:, right:] = False, False, False, False
    (x0, x1), (y0, y1) = [(v.min() - 0.05 * np.ptp(v), v.max() + 0.05 * np.ptp(v)) for v in (x, y)]
    r, c = np.nonzero(line)
    dx, dy = (x1 - x0) / (right - left), (y1 - y0) / (bottom - top)
    return x0 + (c - left) * dx, y1 - (r - top) * dy, dx, dy


def test_every_example_is_tested_and_in_the_gallery():
    scripts = {p.name for p in EXAMPLES.glob("*.py")} - {"run_all.py"}
    tested = {name[len("test_"):] + ".py" for name in globals() if name.startswith("test_")}
    assert scripts <= tested, f"examples without a test: {sorted(scripts - tested)}"
    sys.path.insert(0, str(EXAMPLES))
    try:
        from run_all import EXAMPLES as GALLERY
    finally:
        sys.path.remove(str(EXAMPLES))
    assert set(GALLERY) == scripts
    for script, figures in GALLERY.items():  # each figure is shown on the script's page
        page = (ROOT / "docs" / "examples" / script.replace(".py", ".md")).read_text()
        assert f'--8<-- "examples/{script}"' in page
        for fig in figures:
            assert f"img/{fig}" in page and (ROOT / "docs" / "examples" / "img" / fig).is_file()


def test_cleat_run(workdir):
    out = run_example(workdir, "cleat_run.py")
    static = number(r"static load ([\d.]+) kN", out)
    peak = number(r"peak ([\d.]+) kN", out)
    assert static == pytest.approx(23.3, abs=0.1)            # LC1, thesis Table 3-4: 23.29 kN
    assert peak > 2.0 * static                                # a 50 mm cleat hits hard
    import tyrelab
    run = tyrelab.read_signal(workdir / "cleat_run.parquet")
    assert run["FZW"].max() / 1e3 == pytest.approx(peak, abs=0.05)
    assert run["FZW"].min() >= 0.0                            # no tension
    # the figure, read back from its pixels, shows this run: the curve's highest point at the
    # peak's time, and the curve before the cleat at the static load (to two pixels)
    t, fz = run["RUNTIME"].to_numpy(), run["FZW"].to_numpy() / 1e3
    xs, ys, dx, dy = _curve_as_data(workdir / "cleat_run.png", "C0", t, fz)
    assert xs[ys == ys.max()].mean() == pytest.approx(t[fz.argmax()], abs=2 * dx)
    assert np.median(ys[xs < 1.0]) == pytest.approx(static, abs=2 * dy + 0.05)   # static as printed


def test_model_comparison(workdir):
    out = run_example(workdir, "model_comparison.py")
    peak = {m: number(rf"{re.escape(m)}\s+peak FZ\s+([\d.]+) kN", out) for m in ("OPC", "3D VC", "3D ENV")}
    static = 23.3
    # the rigid disc follows the cleat's edges, the cams swallow part of it, the
    # volume's area-based penetration lets a short cleat in slowest
    assert peak["OPC"] > peak["3D ENV"] > peak["3D VC"] > static
    # the synthetic measurement is the enveloping model plus 1 % noise: it must match it
    assert number(r"3D ENV .*m%RE disturbance\s+([\d.]+) %", out) < 5.0
    assert number(r"measured peak FZ\s+([\d.]+) kN", out) == pytest.approx(peak["3D ENV"], rel=0.05)
    _curves_drawn(workdir / "model_comparison.png", ("C0", "C1", "C2"))      # the three models
    assert (workdir / "model_comparison.md").read_text().count("\n|") >= 4    # header, rule, 3 models
    page = (workdir / "model_comparison.html").read_text()
    assert page.count("data:image/png;base64,") >= 3          # overlay, error, distributions
    # the page's metrics table: the enveloping model, which made the synthetic measurement,
    # is the closest by far, as printed
    table = _metrics_table(page)
    assert set(table) == {"OPC", "3D VC", "3D ENV"}
    mre = {m: row["mRE_disturbance_pct"] for m, row in table.items()}
    assert mre["3D ENV"] == pytest.approx(number(r"3D ENV .*m%RE disturbance\s+([\d.]+) %", out), abs=0.05)
    assert mre["3D ENV"] < 5.0 < mre["OPC"] and mre["3D ENV"] < 5.0 < mre["3D VC"]


def test_roads(workdir):
    out = run_example(workdir, "roads.py")
    assert number(r"pothole floor at x = 5.3 m, y = 0: (-?[\d.]+) mm", out) == pytest.approx(-60.0, abs=0.01)
    assert number(r"highest point ([\d.]+) m", out) == pytest.approx(4.9, abs=0.01)
    low = number(r"my_road.crg at v = 0.5 m: FZW ([\d.]+) to", out)
    high = number(r"my_road.crg at v = 0.5 m: FZW [\d.]+ to ([\d.]+) kN", out)
    static = number(r"my_road.crg at v = 0.5 m: FZW .*\(static ([\d.]+) kN\)", out)
    assert low < static < high                              # the wheel drops in and hits the far edge
    assert high > 1.5 * static
    # the heightmap shows the pothole in the colour map's lowest colour (its floor is the road's
    # lowest point), the cut at y = 0 below it; the profiles figure draws both runs
    import matplotlib
    img = _image(workdir / "roads_crg.png")
    lowest = np.array(matplotlib.colormaps["terrain"](0.0)[:3])
    assert np.all(np.abs(img - lowest) < 0.02, axis=2).sum() > 500    # measured 1500 pixels
    _curves_drawn(workdir / "roads_crg.png", ("C0",))
    _curves_drawn(workdir / "roads_profiles.png", ("C0", "C1"))


def test_fit_tyre(workdir):
    out = run_example(workdir, "fit_tyre.py")
    c_fit = number(r"damping\s+identified ([\d.]+) N s/mm", out)
    c_file = number(r"damping\s+identified [\d.]+ N s/mm, tyre file ([\d.]+) N s/mm", out)
    k_fit = number(r"stiffness identified ([\d.]+) N/mm", out)
    k_file = number(r"stiffness identified [\d.]+ N/mm, tyre file ([\d.]+) N/mm", out)
    assert c_file == pytest.approx(2.66)                      # thesis 3.4.1
    # the thesis's pendulum procedure gives back the simulated tyre's own numbers
    assert c_fit == pytest.approx(c_file, rel=0.05)
    assert k_fit == pytest.approx(k_file, rel=0.05)
    assert 2.0 < number(r"natural frequency ([\d.]+) Hz", out) < 3.5    # the trailer's 2-3 Hz bounce
    # the campaign's drop trace was made with 2.66 N s/mm (thesis 3.4.1): the fit finds it again,
    # and the fitted file drives the enveloping model over the cleat as the built-in file does
    assert number(r"campaign fit: .*damping ([\d.]+) N s/mm", out) == pytest.approx(2.66, rel=0.05)
    assert 550 < number(r"campaign fit: stiffness ([\d.]+) N/mm", out) < 750
    peaks = [number(rf"{name}: peak FZW over the 50 mm cleat ([\d.]+) kN", out)
             for name in ("built-in XZL", "fitted from the campaign")]
    assert peaks[1] == pytest.approx(peaks[0], rel=0.05) and peaks[1] > 2 * 23.3
    import tyrelab
    fitted = tyrelab.load_tyre(workdir / "xzl_fitted.tir")
    assert fitted.unloaded_radius == pytest.approx(0.6715)
    # the fit report states what the written file holds, and the contact-patch stand-in's
    # generating PA1 = 0.15, PA2 = 7.06 come back: its lengths are eq. 2.3 rounded to 0.1 mm,
    # which alone spreads both by 0.3 % (1 sigma, linear least squares); 1 % is 3.5 sigma
    report = (workdir / "xzl_fitted_fit.html").read_text()
    assert number(r"VERTICAL_STIFFNESS</td><td>([\d.]+) N/mm", report) == \
        pytest.approx(fitted.vertical_stiffness / 1e3, abs=0.5)
    assert number(r"VERTICAL_DAMPING</td><td>([\d.]+) N s/mm", report) == \
        pytest.approx(fitted.vertical_damping / 1e3, abs=5e-4)
    assert number(r"PA1, PA2</td><td>([\d.]+),", report) == pytest.approx(0.15, rel=0.01)
    assert number(r"PA1, PA2</td><td>[\d.]+, ([\d.]+)<", report) == pytest.approx(7.06, rel=0.01)
    assert report.count("data:image/png;base64,") == report.count("<img")
    _curves_drawn(workdir / "fit_tyre.png", ("C0", "C1"))    # both cleat runs (C0 also the drop)


def test_small_campaign(workdir):
    import distributed  # noqa: F401 -- a required dependency: missing, this test fails, never skips
    out = run_example(workdir, "small_campaign.py")
    assert out.count(" done") == 2, out
    rows = {m: [float(v) for v in re.search(rf"^{re.escape(m)}\s+([-\d.]+)\s+([-\d.]+)\s+([-\d.]+)\s*$",
                                               out, re.M).groups()]
            for m in ("OPC lk", "3D ENV nlk")}
    # the reference is the enveloping model plus noise: that variant is far closer to it
    assert abs(rows["3D ENV nlk"][0]) < 5.0
    assert abs(rows["OPC lk"][0]) > 2 * abs(rows["3D ENV nlk"][0])
    # the report: plotly.js inside (it works offline), the metrics printed, the verdict
    report = (workdir / "small_study" / "report.html").read_text()
    # plotly.js embedded once (gzip-compressed, unpacked by the page) and the figures drawn by it
    assert report.count("id='tyrelab-plotly'") == 1 and "Plotly.newPlot" in report
    table = _metrics_table(report)
    for model, printed in rows.items():
        assert table[model]["mRE_disturbance_pct"] == pytest.approx(printed[0], abs=0.05), model
    verdict = re.search(r"<table class='summary'>.*?</table>", report, re.S).group(0)
    assert re.search(r"<td>not representative</td><td>comparable, best</td>", verdict), verdict
    _curves_drawn(workdir / "small_campaign.png", ("C0", "C1"))


def test_make_data_rebuilds_the_shipped_example_data(tmp_path):
    """examples/data/make_data.py still makes what is shipped (to the written rounding)."""
    from tyrelab.measure import read_run
    from tyrelab.road.spec import road_from_spec

    proc = python_file(EXAMPLES / "data" / "make_data.py", tmp_path, env=_env(), timeout=TIMEOUT)
    assert proc.returncode == 0, proc.stderr[-3000:]
    shipped = EXAMPLES / "data"
    assert (tmp_path / "my.tir").read_bytes() == (shipped / "my.tir").read_bytes()
    new, old = read_run(tmp_path / "measured.tdx"), read_run(shipped / "measured.tdx")
    assert list(new.columns) == list(old.columns) and len(new) == len(old)
    for col in new.columns:  # forces kept to 1 N, so allow a unit in the last place
        np.testing.assert_allclose(new[col].to_numpy(), old[col].to_numpy(), rtol=0, atol=1.01)
    text = (shipped / "measured.tdx").read_text()
    assert "SYNTHETIC DATA, NOT A MEASUREMENT" in text.split("**CONSTANTS")[0]
    a, b = road_from_spec(str(tmp_path / "my_road.crg")), road_from_spec(str(shipped / "my_road.crg"))
    ga, gb = a.grid(), b.grid()
    assert ga.z.shape == gb.z.shape and np.array_equal(ga.z, gb.z)
