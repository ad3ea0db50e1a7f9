"""Output rows, rig states and result rows are written through names, never by number.

Each flat array has one tuple of names (``WHEEL_CHANNELS`` and a rig's ``CHANNELS``, a
rig's ``STATE``, ``PRESS_COLUMNS``, the MF ``OUTPUTS``); the code indexes it through
``core.named_index`` records made from that tuple. These tests check that the records
follow their tuples, that the values land under the channel the tuple names, and that
no bare number indexes those arrays again in the kernels' sources.
"""

from __future__ import annotations

import copy
import pickle
import re
from pathlib import Path

import numpy as np
import pytest

import tyrelab
from tyrelab.core.named_index import named_index
from tyrelab.rig import _quarter_kernel, _trailer_kernel, frames, rolling
from tyrelab.tyre import model as tyre_model
from tyrelab.tyre import static
from tyrelab.tyre.handling.mf import kernel as mf_kernel
from tyrelab.tyre.wheel import WheelLoads, WheelPose

PACKAGE = Path(tyrelab.__file__).resolve().parent


def test_named_index_gives_each_name_its_position():
    ix = named_index("Probe", ("A", "B_2", "C"))
    assert (ix.A, ix.B_2, ix.C) == (0, 1, 2) and ix._fields == ("A", "B_2", "C")
    assert type(ix).__name__ == "Probe"
    assert pickle.loads(pickle.dumps(ix)) == ix and copy.deepcopy(ix) == ix
    with pytest.raises(ValueError, match="repeated"):
        named_index("Bad", ("A", "A"))
    with pytest.raises(ValueError, match="field name"):
        named_index("Bad", ("A", "not a name"))


@pytest.mark.parametrize("names,index", [
    (frames.WHEEL_CHANNELS, frames.WC), (frames.C_AXIS, frames.CA),
    (_trailer_kernel.CHANNELS, _trailer_kernel.TC), (_trailer_kernel.STATE, _trailer_kernel.S),
    (_quarter_kernel.CHANNELS, _quarter_kernel.QC), (_quarter_kernel.STATE, _quarter_kernel.Q),
    (rolling.STATE, rolling.R), (static.PRESS_COLUMNS, static.PC), (static.ROLL_STATE, static.RS),
    (tyre_model.POSE_COLUMNS, tyre_model.PO), (mf_kernel.OUTPUTS, mf_kernel.MFO),
], ids=lambda v: type(v).__name__ if hasattr(v, "_fields") else None)
def test_every_index_record_follows_its_tuple(names, index):
    assert index._fields == tuple(names)
    assert list(index) == list(range(len(names)))


def test_rig_channels_begin_with_the_wheel_channels():
    """``wheel_row`` writes through ``WC`` into every rig's row: each rig's own channels
    must come after the wheel's, whatever is added to either tuple."""
    for module in (_trailer_kernel, _quarter_kernel, rolling):
        assert module.CHANNELS[:frames.N_WHEEL] == frames.WHEEL_CHANNELS
        assert module.N_CH == len(module.CHANNELS) == len(set(module.CHANNELS))
    assert _trailer_kernel.S_SIZE == len(_trailer_kernel.STATE)
    assert _quarter_kernel.Q_SIZE == len(_quarter_kernel.STATE)
    assert mf_kernel.COL == {name: i for i, name in enumerate(mf_kernel.OUTPUTS)}
    # mf_forces fills rows of 5 or 6 (its callers' arrays): its outputs must stay OUTPUTS' first six
    assert mf_kernel.OUTPUTS[:6] == ("Fx", "Fy", "Mx", "My", "Mz", "flags")


def test_wheel_row_writes_each_value_under_its_channel():
    """A pose and loads of distinct values: each lands in the slot the tuple names."""
    pose = WheelPose(1.1, 2.2, 3.3, 0.0, 1.0, 0.0, 4.4, 5.5, 6.6, 7.7)   # level axis: C-axis = road
    loads = WheelLoads(*(10.0 + k for k in range(len(WheelLoads._fields))))
    row, cax = np.full(frames.N_WHEEL, np.nan), np.full(frames.N_C_AXIS, np.nan)
    frames.wheel_row(row, 0.25, 8.8, pose, loads, cax, 0.5)
    got = dict(zip(frames.WHEEL_CHANNELS, row))
    expect = {"RUNTIME": 0.25, "DISTANCE": 8.8, "FXW": loads.fxw, "FYW": loads.fyw, "FZW": loads.fzw,
              "X_WC": 1.1, "Y_WC": 2.2, "Z_WC": 3.3, "VX_WC": 4.4, "VY_WC": 5.5, "VZ_WC": 6.6,
              "ROTSPEED": 7.7, "DEFLECT": loads.deflection, "X_CP": loads.px, "Y_CP": loads.py + 0.5,
              "Z_CP": loads.pz, "LONGSLIP": loads.kappa, "SLIPANGL": loads.alpha,
              "INCLANGL": 0.0,                            # the level axis: no inclination
              # C-axis of a level wheel heading +x: x, y, z are the road's
              "FX": loads.fx, "FY": loads.fy, "FZ": loads.fz, "MX": loads.mx, "MY": loads.my,
              "MZ": loads.mz}
    assert set(expect) == set(frames.WHEEL_CHANNELS)
    for name, value in expect.items():
        assert got[name] == pytest.approx(value, abs=1e-12), name
    assert dict(zip(frames.C_AXIS, cax)) == {c: got[c] for c in frames.C_AXIS}


def test_a_run_has_its_own_channels_where_they_are_named():
    """The quarter vehicle's body channels and the trailer's frame channels, by name."""
    run = tyrelab.simulate(model="point", road="flat", rig="quarter-vehicle", duration=0.05,
                           progress=False)
    assert list(run.columns[:len(_quarter_kernel.CHANNELS)]) == list(_quarter_kernel.CHANNELS)
    assert np.allclose(run["RUNTIME"], np.arange(len(run)) * 1e-3)
    assert np.all(run["Z_BODY"] > run["Z_WC"])          # the body rides above the hub
    assert np.abs(run["VZ_BODY"]).max() < 1e-3         # and stays put on a flat road
    assert 0.0 < run["F_SUSP"].iloc[0] < run["FZ_HUB"].iloc[0]   # the hub carries the wheel too


@pytest.mark.parametrize("path,index,names", [
    ("rig/frames.py", "WC", frames.WHEEL_CHANNELS),
    ("rig/_trailer_kernel.py", "TC", _trailer_kernel.CHANNELS[frames.N_WHEEL:]),
    ("rig/_quarter_kernel.py", "QC", _quarter_kernel.CHANNELS[frames.N_WHEEL:]),
    ("tyre/static.py", "PC", static.PRESS_COLUMNS),
    ("tyre/handling/mf/kernel.py", "MFO", mf_kernel.OUTPUTS),
])
def test_every_named_slot_is_written(path, index, names):
    """A name added to a tuple must also be given its value (rows start as zeros or
    ``np.empty``: an unwritten slot would pass unnoticed)."""
    text = (PACKAGE / path).read_text(encoding="utf-8")
    unwritten = [n for n in names if not re.search(rf"\b{index}\.{n}\] *[+]?= ", text)]
    assert not unwritten, unwritten


#: (file, names of the arrays that are rows, states or result records in it)
RECORD_ARRAYS = {
    "rig/frames.py": "o|out|cax",
    "rig/_trailer_kernel.py": "o|out|state|cax",
    "rig/_quarter_kernel.py": "o|out|state|cax",
    "rig/rolling.py": "out|state",
    "rig/trailer.py": "state|states|data",
    "rig/quarter_vehicle.py": "state|data",
    "rig/static_press.py": "out|res",
    "tyre/static.py": "res|state",
    "tyre/model.py": "p|poses",
    "tyre/handling/mf/kernel.py": "out|r",
    "tyre/handling/mf/wheel.py": "out",
    "tyre/handling/mf/model.py": "out",
}


@pytest.mark.parametrize("path", sorted(RECORD_ARRAYS))
def test_no_bare_number_indexes_a_record_array(path):
    """``o[3]``, ``out[:, 2]``, ``state[1]``, ``o[N_WHEEL + 2]``: a position decided by hand."""
    names = RECORD_ARRAYS[path]
    bare = re.compile(rf"\b(?:{names})\[(?:[\w.]+, *|:, *)?(?:N_\w+ *\+ *)?\d+\]")
    hits = [f"{path}:{n}: {line.strip()}"
            for n, line in enumerate((PACKAGE / path).read_text(encoding="utf-8").splitlines(), 1)
            if bare.search(line.split("#")[0])]
    assert not hits, "\n".join(hits)
