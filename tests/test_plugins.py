"""Plugins: a distribution installed with pip into a temporary environment adds a contact model,
a rig and a road file format, which reach the command line, a study spec and the study's Dask
workers (tyrelab.plugins, entry-point group tyrelab.plugins).

The demonstration plugin (tests/data/demo_plugin) is built into a wheel here and installed with
``pip install --target``; the commands run with that folder on PYTHONPATH. Its model preloads
the point contact by ``preload``, its rig raises the rolling rig's axle by RAISE = 5 mm above
the model's equilibrium height, its road format reads an x-z profile. Combined on a flat road,
the tyre is pressed ``preload`` deeper by the model and lifted by its equilibrium ``preload`` and
by the rig RAISE: its normal load is the vertical law's at the static deflection less RAISE, and
after a step of height H in the profile, at that deflection plus H.
"""

from __future__ import annotations

import base64
import hashlib
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tyrelab.rig.trailer import load_case_wheel_load
from tyrelab.tyre.library import load_tyre

PLUGIN = Path(__file__).parent / "data" / "demo_plugin"
RAISE = 0.005          # the plugin rig's lift [m] (tyrelab_demo_plugin.RAISE)
PRELOAD = 0.012        # given as the model's option [m]
SPEED_KMH = 18.0
STEP_X = 5.0           # where the profile steps up [m]


def _wheel(out: Path) -> Path:
    """The plugin as a wheel (a zip with its .dist-info and a RECORD of hashes, PEP 427)."""
    name = "tyrelab_demo_plugin-1.0"
    source = PLUGIN / "tyrelab_demo_plugin" / "__init__.py"
    files = {"tyrelab_demo_plugin/__init__.py": source.read_bytes(),
             f"{name}.dist-info/METADATA": b"Metadata-Version: 2.1\nName: tyrelab-demo-plugin\n"
                                           b"Version: 1.0\n",
             f"{name}.dist-info/WHEEL": b"Wheel-Version: 1.0\nGenerator: tyrelab-tests\n"
                                        b"Root-Is-Purelib: true\nTag: py3-none-any\n",
             f"{name}.dist-info/entry_points.txt": (PLUGIN / "entry_points.txt").read_bytes()}
    record = []
    for path, content in files.items():
        digest = base64.urlsafe_b64encode(hashlib.sha256(content).digest()).rstrip(b"=").decode()
        record.append(f"{path},sha256={digest},{len(content)}")
    record.append(f"{name}.dist-info/RECORD,,")
    files[f"{name}.dist-info/RECORD"] = ("\n".join(record) + "\n").encode()
    wheel = out / f"{name}-py3-none-any.whl"
    with zipfile.ZipFile(wheel, "w") as z:
        for path, content in files.items():
            z.writestr(path, content)
    return wheel


@pytest.fixture(scope="module")
def plugin_env(tmp_path_factory):
    """Environment variables of a process that sees the plugin installed (and nothing else new)."""
    root = tmp_path_factory.mktemp("plugin_env")
    site = root / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--no-index",
                    "--disable-pip-version-check", "--target", str(site), str(_wheel(root))],
                   check=True, capture_output=True)
    env = dict(os.environ)
    others = [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p]
    env["PYTHONPATH"] = os.pathsep.join([str(site), *others])
    return env


def _tyrelab(env, *args, cwd=None):
    return subprocess.run([sys.executable, "-m", "tyrelab.cli.main", *args], env=env, cwd=cwd,
                          capture_output=True, text=True, timeout=900)


def _profile(path: Path, step: float) -> Path:
    """A flat profile with a step of ``step`` [m] at STEP_X (1 cm ramp)."""
    path.write_text(f"# x z [m]\n-1 0\n{STEP_X} 0\n{STEP_X + 0.01} {step}\n40 {step}\n")
    return path


def _expected_fzw(load: float, step: float) -> float:
    """The vertical law's force at the static deflection under ``load``, less RAISE, plus ``step``."""
    tyre = load_tyre("xzl-16.00R20")
    return float(tyre.vertical_law.static_load(tyre.static_deflection(load) - RAISE + step))


def _check_run(table: pd.DataFrame, load: float, step: float) -> None:
    t = table["RUNTIME"].to_numpy()
    fzw = table["FZW"].to_numpy()
    x = table["X_WC"].to_numpy()
    before = fzw[(t > 0.1) & (x < STEP_X - 1.0)]
    after = fzw[x > STEP_X + 1.0]
    assert before.size > 50 and after.size > 50
    np.testing.assert_allclose(before, _expected_fzw(load, 0.0), rtol=1e-6)
    np.testing.assert_allclose(after, _expected_fzw(load, step), rtol=1e-6)


def test_the_plugins_extensions_are_listed(plugin_env):
    done = _tyrelab(plugin_env, "models")
    assert done.returncode == 0, done.stderr
    listed = done.stdout
    for name in ("preloaded-point", "raised-rolling", ".xz", "slick", "demo"):
        assert name in listed, listed
    without = _tyrelab({k: v for k, v in plugin_env.items() if k != "PYTHONPATH"}, "models")
    assert "preloaded-point" not in without.stdout and "point" in without.stdout


def test_the_plugin_runs_through_the_command_line(plugin_env, tmp_path):
    road = _profile(tmp_path / "road.xz", 0.02)
    out = tmp_path / "run.csv"
    done = _tyrelab(plugin_env, "simulate", "--model", "preloaded-point", "--option", f"preload={PRELOAD}",
                    "--rig", "raised-rolling", "--road", str(road), "--speed", str(SPEED_KMH),
                    "--duration", "1.8", "--load", "LC1", "-o", str(out))
    assert done.returncode == 0, done.stderr
    _check_run(pd.read_csv(out, comment="#"), load_case_wheel_load("LC1"), 0.02)
    # without the plugin the same command is one clear line naming the model, exit 2
    plain = {k: v for k, v in plugin_env.items() if k != "PYTHONPATH"}
    refused = _tyrelab(plain, "simulate", "--model", "preloaded-point", "--road", str(road), "-o",
                       str(tmp_path / "no.csv"))
    assert refused.returncode == 2 and "unknown model 'preloaded-point'" in refused.stderr
    assert not (tmp_path / "no.csv").exists()


def test_the_plugins_terrain_reaches_the_command_line(plugin_env, tmp_path):
    """``--terrain slick:0`` (the plugin's rigid ground, the road's heights, friction scaled by
    0): the trailer's test wheel (the HMMWV tyre, Pacejka '89 as ADAMS has it: without
    Chrono's rolling resistance, a hysteresis moment that acts without friction) rides exactly
    as on the plain road up to the cleat (same heights, same normal load), but its longitudinal
    force, scaled by the ground's friction, is nil, where over the cleat on the plain road it
    is not. An unknown terrain lists what each kind takes."""
    from importlib import resources
    shipped = resources.files("tyrelab.tyre").joinpath("data", "hmmwv-pac89.tir").read_text()
    adams = tmp_path / "hmmwv-adams-pac89.tir"
    adams.write_text(shipped.split("\n[ROLLING_COEFFICIENTS]")[0] + "\n")  # Chrono's additions last
    assert "\n[STRUCTURAL]" not in adams.read_text() and "\n[ALIGNING_COEFFICIENTS]" in adams.read_text()
    runs = {}
    for terrain in (None, "slick:0"):
        out = tmp_path / f"{terrain or 'road'}.csv".replace(":", "_")
        args = ["simulate", "--tyre", str(adams), "--model", "point", "--handling", "pac89",
                "--rig", "trailer", "--road", "cleat:50x50", "--speed", "12", "--duration", "2.5",
                "-o", str(out)]
        done = _tyrelab(plugin_env, *args, *(["--terrain", terrain] if terrain else []))
        assert done.returncode == 0, done.stderr
        runs[terrain] = pd.read_csv(out, comment="#")
    road, slick = runs[None], runs["slick:0"]
    before = road["RUNTIME"] < 1.0                       # rolling freely, ahead of the cleat
    np.testing.assert_allclose(slick["FZW"][before], road["FZW"][before], rtol=1e-6)
    assert np.abs(road["FXW"]).max() > 500.0 and np.abs(slick["FXW"]).max() == 0.0
    refused = _tyrelab(plugin_env, "simulate", "--rig", "trailer", "--terrain", "tarmac", "-o",
                       str(tmp_path / "no.csv"))
    assert refused.returncode == 2 and "slick:MU" in refused.stderr and "soil" in refused.stderr


def test_the_plugin_runs_in_a_two_worker_study(plugin_env, tmp_path):
    """A study spec naming the plugin's model, rig, road file and terrain: the runs are computed
    by two Dask worker processes, which load the plugin themselves. Editing the road file
    changes the road runs' keys (the format's identity is the file's digest): a rerun computes
    them again. On the plugin's rigid ``slick`` ground the soil bin's wheel (the preloaded
    model at 23.3 kN) carries its dead weight with its axle ``preload`` higher than the
    vertical law's static deflection puts it, as on the road, and sinks nowhere."""
    road = _profile(tmp_path / "road.xz", 0.02)
    spec = tmp_path / "plugin.toml"
    spec.write_text(f"""
[study]
name = "plugin"
output = "out"
store = "lossless"

[[tyre]]
name = "XZL"
file = "xzl-16.00R20"

[[model]]
name = "preloaded"
contact = "preloaded-point"
options = {{ preload = {PRELOAD} }}

[[test]]
name = "profile step"
road = "road.xz"
rig = "raised-rolling"
speeds_kmh = [{SPEED_KMH}]
loads = ["LC1", "LC2"]
duration = 1.8

[[test]]
name = "slick bin"
rig = "single-wheel"
terrain = "slick:0.5"
slips = [0.1]
speeds_kmh = [3.6]
loads = [23300]
duration = 1.0
""")
    from tyrelab.study.store import Store

    seen: set = set()
    for step in (0.02, 0.03):
        _profile(road, step)
        done = _tyrelab(plugin_env, "study", str(spec), "--workers", "2", cwd=tmp_path)
        assert done.returncode == 0, done.stderr
        # read through the store: this process has no plugin, so it cannot parse the spec
        store = Store(tmp_path / "out")
        index = store.index()
        new = index[~index["key"].isin(seen)]
        road_runs = new[new["test"] == "profile step"]
        assert len(road_runs) == 2 and set(new["status"]) == {"done"}   # computed again after the edit
        for _, row in road_runs.iterrows():
            _check_run(store.signal(row["key"]), load_case_wheel_load(row["load"]), step)
        assert len(new) == (3 if not seen else 2)       # the slick run's key has no road file
        seen |= set(new["key"])
    bin_key = index.loc[index["test"] == "slick bin", "key"].item()
    run = store.signal(bin_key)
    tyre = load_tyre("xzl-16.00R20")
    steady = run[run["RUNTIME"] > 0.5]
    np.testing.assert_allclose(steady["FZW"], 23300.0, rtol=1e-3)
    np.testing.assert_allclose(steady["DEFLECT"], tyre.static_deflection(23300.0), rtol=1e-3)
    # the model's tyre is pressed PRELOAD before it touches: its axle rides that much higher
    np.testing.assert_allclose(steady["Z_WC"], tyre.unloaded_radius - tyre.static_deflection(23300.0)
                               + PRELOAD, atol=1e-4)
    assert steady["SINKAGE"].max() == 0.0


def test_a_broken_plugin_is_a_warning_and_the_rest_works(monkeypatch):
    """An entry point whose load raises: one PluginWarning naming it; the built-in models stay."""
    from tyrelab import plugins
    from tyrelab.tyre.registry import contact_models

    class Broken:
        name, value, group = "broken", "no_such_module:register", plugins.GROUP
        dist = None

        def load(self):
            raise ModuleNotFoundError("No module named 'no_such_module'")

    monkeypatch.setattr(plugins.metadata, "entry_points",
                        lambda group: [Broken()] if group == plugins.GROUP else [])
    monkeypatch.setattr(plugins, "_state", {"loaded": False, "loading": False})
    monkeypatch.setattr(plugins, "LOADED", {})
    with pytest.warns(plugins.PluginWarning, match="plugin 'broken'.*no_such_module"):
        plugins.load()
    assert "broken" not in plugins.LOADED
    assert "point" in contact_models()


def test_an_edited_plugin_gets_a_fresh_compile_cache(plugin_env, tmp_path):
    """The plugin's record enters the cached rig loops' signatures and its code is compiled into
    them: the cache folder's digest covers the installed plugins' Python files, so a plugin edited
    (or upgraded) in place never meets loops compiled with its old code."""
    def digest(env) -> str:
        code = "from tyrelab.core.jit_cache import kernel_digest; print(kernel_digest())"
        return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                              check=True).stdout.strip()

    plain = {k: v for k, v in plugin_env.items() if k != "PYTHONPATH"}
    site = Path(plugin_env["PYTHONPATH"].split(os.pathsep)[0])
    source = site / "tyrelab_demo_plugin" / "__init__.py"
    with_plugin = digest(plugin_env)
    assert with_plugin != digest(plain)
    original = source.read_text()
    try:
        source.write_text(original.replace("RAISE = 0.005", "RAISE = 0.006"))
        assert digest(plugin_env) not in (with_plugin, digest(plain))
    finally:
        source.write_text(original)
    assert digest(plugin_env) == with_plugin
