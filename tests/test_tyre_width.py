"""A property file without [DIMENSION] WIDTH: the models that spread their contact across the
tyre refuse it, naming the file and the key. Before, the volume model ran it as one disc and the
enveloping model with a patch of zero width (its cams in one line), without a word."""

import pytest

from tyrelab.api import make_tyre_model
from tyrelab.errors import InputError
from tyrelab.road.spec import road_from_spec
from tyrelab.study.spec import parse_spec

from spec_text import study_spec


@pytest.fixture
def no_width(tmp_path, data_dir):
    text = (data_dir / "mfeval" / "MagicFormula61_Parameters.tir").read_text().splitlines()
    kept = [line for line in text if not line.startswith("WIDTH ")]
    assert len(kept) == len(text) - 1
    path = tmp_path / "no_width.tir"
    path.write_text("\n".join(kept) + "\n")
    return path


@pytest.mark.parametrize("contact, what", [("volume", "the volume model"),
                                           ("enveloping", "the enveloping model"),
                                           ("enveloping-edge", "the enveloping model")])
def test_a_model_across_the_width_refuses_a_tyre_without_one(no_width, contact, what):
    model = make_tyre_model(no_width, contact, handling="none")
    with pytest.raises(InputError, match=f"{what} needs the tyre's width") as err:
        model.contact_params(road_from_spec("cleat:50x50").grid())
    assert err.value.field == "WIDTH" and err.value.source.endswith("no_width.tir")
    # the point model reads the road in the wheel plane only: it runs
    point = make_tyre_model(no_width, "point", handling="none").contact_params(road_from_spec("flat").grid())
    assert point.unloaded_radius == pytest.approx(0.3943)


def test_a_study_refuses_it_before_any_run(no_width, tmp_path):
    spec = study_spec(f'name = "mf61"\nfile = "{no_width}"', (("A", "point"), ("B", "volume")), "A")
    with pytest.raises(InputError, match="tyre 'mf61' cannot run the volume model: the volume "
                                         "model needs the tyre's width") as err:
        parse_spec(spec, tmp_path / "spec.toml")
    assert err.value.line == 14
