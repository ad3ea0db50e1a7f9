"""MFeval's MF 6.1 reference rows without camber, driven through the point model's wheel.

Shared by the tests that hold a moment the wheel step adds at the contact point against
MFeval's (tests/test_rolling_resistance.py: My; tests/test_overturning.py: Mx).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from tyrelab.api import make_tyre_model
from tyrelab.road.spec import road_from_spec
from tyrelab.tyre.wheel import WheelLoads, loads_table, pose

DATA = Path(__file__).parent / "data"
MF61 = DATA / "mfeval" / "MagicFormula61_Parameters.tir"


def mfeval_rows_on_the_wheel():
    """``(rows, loads, centres)``: MFeval's 507 rows without camber (combined slip to 0.3), the
    point model's :class:`WheelLoads` fields (name -> array) at each row's deflection, spin and
    speed, and the wheel centres (one row each)."""
    table = pd.read_csv(DATA / "mfeval" / "MagicFormula61_Parameters.mode111.csv.gz")
    rows = table[table.gamma == 0]
    model = make_tyre_model(MF61, "point", handling="mf", relaxation="off")
    r0 = model.tyre.unloaded_radius
    wheel = model.wheel(road_from_spec("flat").grid(), 4000.0)
    poses = [pose(cz=r0 - r.rho, velocity=(r.Vx, r.Vx * math.tan(r.alpha), 0.0), omega=r.omega)
             for r in rows.itertuples()]
    loads = loads_table(wheel, poses)
    centres = np.column_stack([np.zeros(len(rows)), np.zeros(len(rows)), r0 - rows.rho])
    return rows, {name: loads[:, k] for k, name in enumerate(WheelLoads._fields)}, centres
