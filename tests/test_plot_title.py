"""``tyrelab plot``'s title says the run's conditions as a person writes them."""

import numpy as np
import pytest

from tyrelab.report.plots import plot_runs
from tyrelab.signal import make_signal


@pytest.mark.parametrize("load_case, words", [("LC1", ", LC1"), ("4000.0", ", 4000 N")])
def test_the_title_names_road_speed_and_load(load_case, words):
    """A run at a load given in newtons keeps it as text in its metadata ("4000.0"); the title
    reads "4000 N" (it read "4000.0"), a load case as named."""
    run = make_signal({"RUNTIME": np.arange(3) * 0.1, "FZW": np.full(3, 4e3)})
    run.attrs["metadata"] = {"road": "cleat 50 x 50 mm", "speed_m_s": 30 / 3.6, "load_case": load_case}
    title = plot_runs([run]).axes[0].get_title()
    assert title.endswith(f"cleat 50 x 50 mm, 30 km/h{words}")
