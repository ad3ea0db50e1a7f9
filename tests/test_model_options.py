"""A contact model's options from every front door: ``simulate(options=...)``, ``--option``.

The options a user may set are the registry's (:attr:`ContactModel.options`, name and
type); the same option reaches the model whichever door it came through. Checked by an
identity: the enveloping model told ``cam_layout="outline"`` is, to the last bit, the
registered ``enveloping-edge`` model; and by the cams' count changing the run.
(Study specs: ``tests/test_study_spec.py::test_model_options_reach_the_run_and_its_key``.)
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import tyrelab
from tyrelab.cli.main import main
from tyrelab.errors import InputError

RUN = dict(road="cleat:50x50", speed=12 / 3.6, load="LC1", duration=1.8, progress=False)


def test_an_option_reaches_the_model_through_simulate():
    edge = tyrelab.simulate(model="enveloping-edge", **RUN)
    told = tyrelab.simulate(model="enveloping", options={"cam_layout": "outline"}, **RUN)
    assert edge["FZ_HUB"].to_numpy().tobytes() == told["FZ_HUB"].to_numpy().tobytes()
    grid = tyrelab.simulate(model="enveloping", **RUN)
    one = tyrelab.simulate(model="enveloping", options={"n_length": 1, "n_width": 1}, **RUN)
    # one cam under the centre envelops the cleat less than 15 x 10 spread over the patch
    assert one["FZ_HUB"].max() > grid["FZ_HUB"].max() + 1e3
    # TOML and the command line read 1e0 as a float: a whole float is the integer it names
    whole = tyrelab.simulate(model="enveloping", options={"n_length": 1.0, "n_width": 1e0}, **RUN)
    assert whole["FZ_HUB"].to_numpy().tobytes() == one["FZ_HUB"].to_numpy().tobytes()


@pytest.mark.parametrize("model, options, words", [
    ("volume", {"n_length": 5}, ["unknown option(s) n_length of the 'volume' model", "discs, step"]),
    ("point", {"discs": 4}, ["of the 'point' model", "it takes: none"]),
    ("enveloping", {"n_length": 2.5}, ["option n_length", "expected a whole number, got 2.5"]),
    ("enveloping", {"n_width": True}, ["expected a whole number, got True"]),
    ("ring", {"friction": "high"}, ["option friction", "expected a number, got 'high'"]),
])
def test_unknown_or_mistyped_options_are_refused_before_any_work(model, options, words):
    with pytest.raises(InputError) as err:
        tyrelab.simulate(model=model, options=options, **RUN)
    assert err.value.field == "options"
    for w in words:
        assert w in str(err.value)


def test_the_option_flag_of_the_command_line(tmp_path, capsys):
    out = tmp_path / "run.parquet"
    assert main(["simulate", "--model", "enveloping", "--option", "cam_layout=outline",
                 "--duration", "1.8", "-o", str(out)]) == 0
    edge = tyrelab.simulate(model="enveloping-edge", **RUN)
    np.testing.assert_array_equal(pd.read_parquet(out)["FZ_HUB"].to_numpy(), edge["FZ_HUB"].to_numpy())
    capsys.readouterr()
    for args, words in [(["--option", "n_lenght=5"], "--option: unknown option(s) n_lenght"),
                        (["--option", "n_length"], "expected KEY=VALUE"),
                        (["--option", "n_length=five"], "expected a whole number, got 'five'"),
                        (["--option", "n_length=1e9"], "1000000000 is out of range; allowed: 1 to 100")]:
        assert main(["simulate", "--model", "enveloping", *args, "-o", str(out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and words in err[0], err
