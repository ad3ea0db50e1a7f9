"""The static press: the lab tests of thesis 3.3 on a model."""

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.rig.static_press import static_press
from tyrelab.tyre.model import TyreModel
from tyrelab.tyre.library import load_tyre

DEFLECTION_MM = np.arange(0, 81, 10)
TABLE_3_2 = {   # applied load [N] at each 10 mm, thesis Table 3-2
    100e3: [0, 1905, 4716, 7221, 9947, 13415, 17673, 21582, 25616],
    300e3: [0, 3496, 9445, 15559, 21968, 29011, 37581, 45717, 54191],
    550e3: [0, 6354, 15537, 25250, 36872, 48446, 62502, 74730, 88151],
}


@pytest.mark.parametrize("pressure", sorted(TABLE_3_2))
def test_flat_plate_reproduces_table_3_2(pressure):
    model = TyreModel(load_tyre("xzl-16.00R20", pressure))
    result = static_press(model, DEFLECTION_MM / 1e3, "plate")
    np.testing.assert_allclose(result["load"], TABLE_3_2[pressure], rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(result["FX"], 0.0, atol=1e-9)


def test_interpolated_pressure_lies_between():
    model = TyreModel(load_tyre("xzl-16.00R20", 200e3))
    load = static_press(model, [0.05], "plate")["load"].iloc[0]
    assert load == pytest.approx(0.5 * (13415 + 29011))


def test_point_model_sees_a_cleat_top_as_a_plate():
    """A rigid disc pressed onto a cleat touches its top: same law as the plate."""
    model = TyreModel(load_tyre())
    for direction in ("lateral", "longitudinal"):
        r = static_press(model, [0.03, 0.06], "cleat:51x51", direction)
        np.testing.assert_allclose(r["load"], [15559, 37581], rtol=1e-9)


def test_bad_press_requests():
    model = TyreModel(load_tyre())
    with pytest.raises(InputError):
        static_press(model, [0.01], "cleat:51")
    with pytest.raises(InputError):
        static_press(model, [0.01], "cleat:51x51", "diagonal")
    with pytest.raises(InputError):
        static_press(model, [-0.01], "plate")
