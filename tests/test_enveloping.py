"""3D enveloping contact: Schmeitz's elliptical cams (thesis 2.3.3, 4.4).

The XZL's cams are ellipses (PCE = 2): a cam that rests on a sharp corner at
distance d from its lowest point stands at ``H - e(d)`` with
``e(d) = b_e (1 - sqrt(1 - (d/a_e)^2))``. With that and eqs. 2.3 and 2.6 the
effective plane over a cleat or a step is computed here by hand.
"""

import math

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.road.grid import RoadGrid
from tyrelab.road.obstacles import Flat, Step
from tyrelab.tyre.contact.enveloping import (contact_patch, effective_road, enveloping_geometry,
                                             enveloping_params)
from tyrelab.tyre.contact.point import point_geometry
from tyrelab.tyre.library import load_tyre
from tyrelab.tyre.wheel import ContactGeometry
from tyrelab.tyre.tir import parse_tir

R0, W0 = 0.6715, 0.438
AE_, BE_ = 0.72 * R0, 1.0 * R0   # thesis 4.4: PAE 0.72, PBE 1, PCE 2
H = 0.05


def drop(d):
    d = abs(d)
    return BE_ * (1 - math.sqrt(1 - (d / AE_) ** 2)) if d < AE_ else math.inf


def half_length(rho):
    """Eq. 2.3 with PA1 = 0.15, PA2 = 7.06."""
    x = rho / R0
    return 0.15 * R0 * (x + 7.06 * math.sqrt(x))


class GridRoad:
    """A road given directly as a grid (so the test owns every node)."""

    def __init__(self, grid):
        self._grid = grid

    def grid(self):
        return self._grid


def cleat(width=0.05, height=H, dx=0.005):
    """A square cleat from x = 0 to x = width; top corners on nodes, faces one cell wide."""
    n0, n1 = 400, 400 + int(round(width / dx))
    z = np.zeros(801)
    z[n0:n1 + 1] = height
    return GridRoad(RoadGrid(-n0 * dx, -2.0, dx, 4.0, np.column_stack([z, z])))


def geometry(road, x, cz, tyre=None, **options):
    """The contact geometry at wheel centre (x, 0, cz), heading +x: a ContactGeometry
    of arrays when x is an array."""
    tyre = tyre or load_tyre("xzl-16.00R20", 300e3)
    table = enveloping_geometry(tyre, road.grid(), x, 0.0, cz, **options)
    fields = [table[name].to_numpy() for name in ContactGeometry._fields]
    return ContactGeometry(*(f if np.ndim(x) else f[0] for f in fields))


def cam_heights(tyre, grid, x):
    """Heights of a single cam (1 x 1 cams) at x on the line y = 0, heading +x: the
    effective height of one cam is that cam's height."""
    return effective_road(tyre, grid, x, n_width=1, n_length=1)["height"].to_numpy()


def test_flat_road_is_the_effective_plane():
    for road in (Flat(), Step(0.05, start=20.0)):
        geo = geometry(road, 1.3, R0 - 0.047)
        assert geo.deflection == pytest.approx(0.047, abs=1e-12)
        np.testing.assert_allclose([geo.px, geo.py, geo.pz, geo.nx, geo.ny, geo.nz],
                                   [1.3, 0.0, 0.0, 0.0, 0.0, 1.0], atol=1e-12)


def test_one_cam_rests_on_the_corner_of_a_step():
    grid = Step(H, start=0.0).grid()
    xs = np.array([-0.4, -0.2, -0.1, -0.03, -0.001])
    for x, w in zip(xs, cam_heights(load_tyre(), grid, xs)):
        assert w == pytest.approx(max(0.0, H - drop(x)), abs=1e-6)
    assert cam_heights(load_tyre(), grid, 0.2)[0] == pytest.approx(H, abs=1e-12)


def expected_on_cleat(xc, cz, left=0.0, right=H):
    """Deflection by hand for the 15 x 10 cams with the wheel centre at xc over the
    cleat [left, right] (symmetric rows: a 2D road; no tilt across)."""
    def cam(u):
        d = 0.0 if left <= u <= right else min(abs(u - left), abs(u - right))
        return max(0.0, H - drop(d))
    rho0 = R0 - (cz - cam(xc))        # the centre cam sizes the patch
    ls = 2 * 0.9 * half_length(rho0)   # eq. 2.6
    u = np.linspace(-ls / 2, ls / 2, 15)
    w = np.array([cam(xc + ui) for ui in u])
    su = (u * w).sum() / (u * u).sum()
    s_star = su * AE_ ** 2 / math.sqrt(BE_ ** 2 + su ** 2 * AE_ ** 2)  # where the contour has slope su
    w0 = w.mean() - (su * s_star - drop(s_star))
    return R0 - (cz - w0) / math.sqrt(1 + su * su), su


@pytest.mark.parametrize("xc", [-0.45, -0.2, 0.0, 0.025, 0.1, 0.3])
def test_cleat_effective_plane_by_hand(xc):
    cz = R0 - 0.05
    geo = geometry(cleat(), xc, cz)
    rho, su = expected_on_cleat(xc, cz)
    assert geo.deflection == pytest.approx(rho, abs=2e-6)
    # forward slope su tilts the normal back: n = (-su, 0, 1) / |.|
    np.testing.assert_allclose([geo.nx, geo.ny, geo.nz], np.array([-su, 0, 1]) / math.sqrt(1 + su * su),
                               atol=1e-5)


def test_swallowing_peak_below_the_rigid_disc():
    """Over the 50 mm cleat the rigid disc (point model) is lifted the full 50 mm; the
    cams are lifted less: the mean over cams of which only those near the cleat rise."""
    tyre = load_tyre("xzl-16.00R20", 300e3)
    grid = cleat().grid()
    cz = R0 - 0.05
    xs = np.linspace(-0.8, 0.85, 331)
    env = geometry(cleat(), xs[::10], cz).deflection
    assert np.all(env >= 0.05 - 1e-12)
    point = point_geometry(tyre, grid, xs, 0.0, cz)["deflection"].to_numpy()
    assert max(point) == pytest.approx(0.05 + H, abs=1e-12)
    by_hand = np.array([expected_on_cleat(x, cz)[0] for x in xs[::10]])
    np.testing.assert_allclose(env, by_hand, atol=2e-6)
    assert by_hand.max() < 0.05 + 0.7 * H
    k = tyre.vertical_stiffness
    assert k * env.max() < k * max(point)


def test_lengthening_over_a_long_step():
    """The effective height starts to rise when the foremost cam reaches the step
    (ls/2 + a_e before it; the rigid disc only at sqrt(R0^2 - (R0 - H)^2) = 0.25 m)
    and is complete only when the rearmost cam has passed it (ls/2 after; the
    rigid disc is on top at the step)."""
    cz = R0 - 0.05
    ls_low = 2 * 0.9 * half_length(0.05)
    ls_top = 2 * 0.9 * half_length(0.10)
    start = -(ls_low / 2 + AE_)
    disc_reach = math.sqrt(R0 ** 2 - (R0 - H) ** 2)
    dx = 0.005
    xs = np.arange(-1.0, 0.6, dx)
    rho = geometry(Step(H, start=0.0), xs, cz).deflection
    assert np.all(np.abs(rho[xs < start - dx] - 0.05) < 1e-12)
    assert rho[np.searchsorted(xs, -disc_reach - 0.05)] > 0.05 + 1e-4  # before the disc touches
    on_top = xs[rho >= 0.10 - 1e-9]
    assert on_top.min() >= ls_top / 2 - dx
    assert on_top.min() <= ls_top / 2 + 2 * dx
    assert np.all(np.diff(rho) > -1e-9)  # no overshoot on a step


def test_contact_patch_formulas():
    params = enveloping_params(load_tyre(), Flat().grid())
    a, b = contact_patch(params, 0.06)
    assert a == pytest.approx(half_length(0.06), rel=1e-12)
    # the thesis's PB fit gives ~1.9 m at 60 mm: clipped to half the tyre width
    x = 0.06 / R0
    assert 0.0017 * W0 * (x + 16006.5 * math.sqrt(x) - 77819.1 * x * math.sqrt(x)) > 1.5
    assert b == pytest.approx(W0 / 2)


TIR = """
[UNITS]
LENGTH = 'meter'
[DIMENSION]
UNLOADED_RADIUS = 0.5
WIDTH = 0.3
[VERTICAL]
VERTICAL_STIFFNESS = 3e5
[CONTACT_PATCH]
{patch}
[CONTACT_WIDTH_CURVE]
0.00 0.05
0.04 0.13
0.08 0.11
"""


def tyre_from(patch, table=True):
    from tyrelab.tyre.params import Tyre
    text = TIR.format(patch=patch)
    if not table:
        text = text[:text.index("[CONTACT_WIDTH_CURVE]")]
    return Tyre.from_tir(parse_tir(text, "test.tir"))


@pytest.mark.filterwarnings("ignore:.*no \\[CONTACT_PATCH\\] value")   # the MF-Swift file's cams are assumed
def test_width_table_and_swift_keys():
    adams = tyre_from("PA1 = 0.2\nPA2 = 5.0\nPAE = 0.9\nPBE = 1.1\nPCE = 1.7\nPLS = 0.8\n"
                      "N_WIDTH = 4\nN_LENGTH = 6")
    swift = tyre_from("PA1 = 0.2\nPA2 = 5.0\nELLIPS_LENGTH = 0.9\nELLIPS_HEIGHT = 1.1\n"
                      "ELLIPS_ORDER = 1.7\nELLIPS_SHIFT = 0.8\nELLIPS_NWIDTH = 4\nELLIPS_NLENGTH = 6")
    grid = Flat().grid()
    for name, a, s in zip(enveloping_params(adams, grid)._fields, enveloping_params(adams, grid),
                          enveloping_params(swift, grid)):
        np.testing.assert_array_equal(a, s, err_msg=name)
    params = enveloping_params(adams, grid)
    assert contact_patch(params, 0.02)[1] == pytest.approx(0.09)   # table, by hand: 0.05 + 0.5 * 0.08
    assert contact_patch(params, 0.06)[1] == pytest.approx(0.12)
    assert contact_patch(params, 0.2)[1] == pytest.approx(0.11)    # clamped at the last row
    # MF-Swift length law: a = R0 (Q_RA2 x + Q_RA1 sqrt x)
    mf = tyre_from("Q_RA1 = 0.6\nQ_RA2 = 1.2\nQ_RB1 = 0.5\nQ_RB2 = 0.1", table=False)
    params = enveloping_params(mf, grid)
    x = 0.03 / 0.5
    a, b = contact_patch(params, 0.03)
    assert a == pytest.approx(0.5 * (1.2 * x + 0.6 * math.sqrt(x)))
    assert b == pytest.approx(0.3 * (0.1 * x + 0.5 * x ** (1 / 3)))
    with pytest.raises(InputError):
        enveloping_params(mf, grid, width_table=True)
    with pytest.raises(InputError):
        enveloping_params(mf, grid, bogus=True)


def test_max_step_limits_what_a_cam_sees():
    """ELLIPS_MAX_STEP = 10 mm: a cam ignores road it could only reach by rising more."""
    patch = "PAE = 0.72\nPBE = 1.0\nPCE = 2.0\nELLIPS_MAX_STEP = 0.01"
    tyre = tyre_from(patch, table=False)
    grid = Step(H, start=0.0).grid()
    ae, be = 0.72 * 0.5, 0.5
    reach = ae * math.sqrt(1 - (1 - 0.01 / be) ** 2)   # where e(s) = 10 mm
    assert enveloping_params(tyre, grid).cam_reach == pytest.approx(reach)
    assert cam_heights(tyre, grid, -(reach + 0.01))[0] == 0.0
    assert cam_heights(tyre, grid, -(reach - 0.01))[0] > 0.0


def paved_row_road(seed=7, dx=0.01):
    """A 3 m x 5-row road of flat-topped blocks (random heights, one-cell faces,
    some blocks with a slope on top): plateaus, kinks and pieces of every slope."""
    rng = np.random.default_rng(seed)
    nx, ny = 301, 5
    z = np.zeros((nx, ny))
    for j in range(ny):
        k = 0
        while k < nx:
            n = int(rng.integers(6, 18))
            z[k:k + n, j] = rng.normal(0.0, 0.015) + rng.choice([0.0, 0.0, 0.004]) * np.arange(
                min(n, nx - k))
            k += n + 1
    return RoadGrid(-1.5, -0.02, dx, 0.01, z)


@pytest.mark.parametrize("max_step", [None, 0.004])
@pytest.mark.parametrize("blocks", [True, False])
def test_row_of_cams_is_the_exact_maximum(max_step, blocks):
    """Each cam of a row rests at max over |x - xc| <= cap of h(x) - e(x - xc): checked
    against a dense search of the piecewise-linear row (200 samples per cell, plus the
    window's ends) with the cam contour of eq. 2.5 in closed form."""
    from tyrelab.tyre.contact.cams import cam_row
    patch = "PAE = 0.72\nPBE = 1.0\nPCE = 2.0" + (f"\nELLIPS_MAX_STEP = {max_step}" if max_step else "")
    tyre = tyre_from(patch, table=False)
    grid = paved_row_road()
    params = enveloping_params(tyre, grid)
    ae, be, cap = params.cam_half_length, params.cam_half_height, params.cam_reach
    assert params.row_block_max.size > 0 and (max_step is None) == (cap == ae)
    if not blocks:
        params = params._replace(row_block_max=np.zeros((0, grid.z.shape[1] - 1)))
    j, wy = 2, 0.3
    nodes = grid.x0 + grid.dx * np.arange(grid.z.shape[0])
    row = grid.z[:, j] * (1 - wy) + grid.z[:, j + 1] * wy
    dense = np.linspace(nodes[0], nodes[-1], 200 * (nodes.size - 1) + 1)
    for x_first, pitch in ((-1.2, 0.026), (-0.8, 0.026), (-0.3, 0.011), (0.1, 0.031), (0.4, 0.0)):
        out = np.zeros(15)
        cam_row(params, grid.surface(), j, wy, x_first, pitch, 15, row.max(), out)
        for i, w in enumerate(out):
            xc = x_first + i * pitch
            xs = np.r_[dense[np.abs(dense - xc) <= cap], xc - cap, xc + cap]
            s = np.clip(np.abs(xs - xc) / ae, 0, 1)
            expected = np.max(np.interp(xs, nodes, row) - be * (1 - np.sqrt(1 - s * s)))
            assert w == pytest.approx(expected, abs=1e-6)


def test_driving_the_other_way_on_the_turned_road_is_the_same_contact():
    """Turning the road half a revolution about the vertical axis and the wheel with
    it (heading -x) must give the same deflection and the turned contact point and
    normal (the cams of a row are searched in grid order, then put back in order)."""
    grid = paved_row_road(seed=3)
    turned = RoadGrid(grid.x0, grid.y0, grid.dx, grid.dy, np.ascontiguousarray(grid.z[::-1, ::-1]))
    tyre = load_tyre()
    for x, y, depth in ((0.13, 0.004, 0.04), (-0.41, -0.007, 0.06), (0.72, 0.0, 0.02)):
        h = float(np.max(grid.z[140:160]))
        cz = h + R0 - depth
        a = enveloping_geometry(tyre, grid, x, y, cz, axis=(0.0, 1.0, 0.0)).iloc[0]
        b = enveloping_geometry(tyre, turned, -x, -y, cz, axis=(0.0, -1.0, 0.0)).iloc[0]
        same, turned_over = ["deflection", "pz", "nz", "curvature"], ["px", "py", "nx", "ny"]
        np.testing.assert_allclose(b[same].to_numpy(float), a[same].to_numpy(float), atol=1e-9)
        np.testing.assert_allclose(b[turned_over].to_numpy(float), -a[turned_over].to_numpy(float),
                                   atol=1e-9)


def steepest_cam_slope(height):
    """The steepest slope S_H a cam of the XZL's shape can show over a road whose heights
    span ``height`` [m].

    A cam rests at w(x) = max_s [h(x + s) - e(s)]. Where it rests at s*, w rises as
    fast as its contour there, |w'(x)| = e'(|s*|), and e(s*) = h(x + s*) - w(x) <= the
    height span H (w(x) >= h(x)). As e' grows with s, |w'| <= e'(e^-1(H)); for the
    ellipse (PCE = 2) with q = 1 - H / b_e that is (b_e / a_e) sqrt(1 - q^2) / q.
    """
    q = 1.0 - height / BE_
    return BE_ / AE_ * math.sqrt(1.0 - q * q) / q


# (road, height span [m], speed [km/h], duration [s]); the obstacles start at x = 5 m
LEAVING_CASES = [(road, h, kmh, 2.5) for road, h in (("cleat:50x50", 0.05), ("cleat:76.3x76.3", 0.0763))
                 for kmh in (12.0, 27.0, 42.0)]
CREEPING_CASES = [("cleat:150x150", 0.15, 1.0, 22.0), ("step:200", 0.2, 1.0, 22.0)]


@pytest.mark.parametrize("road,height,kmh,duration", LEAVING_CASES + CREEPING_CASES)
def test_the_effective_road_changes_no_faster_than_the_wheel_travels_over_it(road, height, kmh,
                                                                              duration):
    """Issue 15: leaving the 50 mm cleat at 12 km/h the deflection fell from 31 mm to 0
    in one 1 ms step (FZW 11.6 kN -> 0), and creeping at 1 km/h onto a 150 mm cleat or
    a 200 mm step FZW fell from up to 80 kN to 0 in one step, again and again: the
    patch, sized at the deflection of the one cam under the centre, shrank to a point
    while the tyre rested on the corner, and the cams' plane jumped.

    The bound. The deflection is the wheel's penetration of the effective road; in one
    step the wheel moves dx forward and dz up. No cam rises faster than S_H per metre
    it travels (:func:`steepest_cam_slope`: from the cam's shape and the obstacle's
    height alone), nor does the cams' least-squares slope exceed S_H, so a road the
    cams can present changes the penetration by no more than the wheel's own travel
    over it explains -- as a rigid wheel on any road of slopes up to S_H:

        |d DEFLECT| <= |dz| + S_H |dx| + 1 um

    (1 um: rounding and the trailer's roll, ~1e-5 rad a step; dx = v dt, the trailer
    is towed at constant speed). The deflection, not the plane's height at the patch
    centre, is checked: that height is the plane extrapolated from where the cams
    rest, and it swings with the plane's tilt while the plane where the wheel meets
    it barely moves. At 1 km/h the point and volume models never lose the road over
    these obstacles; neither may the cams.
    """
    import tyrelab
    run = tyrelab.simulate(model="enveloping", road=road, speed=kmh / 3.6, load="LC1",
                           duration=duration, progress=False)
    x, z = run["X_WC"].to_numpy(), run["Z_WC"].to_numpy()
    rho, fz = run["DEFLECT"].to_numpy(), run["FZW"].to_numpy()
    assert x[-1] > 5.0 + height + 0.5  # past the obstacle's far edge (or well onto the step)
    bound = np.abs(np.diff(z)) + steepest_cam_slope(height) * np.abs(np.diff(x)) + 1e-6
    jump = np.abs(np.diff(rho))
    k = int(np.argmax(jump - bound))
    assert np.all(jump <= bound), (f"DEFLECT {rho[k] * 1e3:.2f} -> {rho[k + 1] * 1e3:.2f} mm at "
                                   f"x = {x[k]:.4f} m; bound {bound[k] * 1e3:.2f} mm")
    if kmh <= 1.0:
        assert np.all(fz > 0.0)


def _feda_copy(data_dir, tmp_path, name, extra="", magic_formula=True):
    """The FEDA 335/65R22.5 (no [CONTACT_PATCH]) under a fresh name, ``extra`` appended; without
    its Magic Formula's version keys (FITTYP, PROPERTY_FILE_FORMAT) unless ``magic_formula``:
    an MF 5.x file has a contact length and width of its own."""
    text = (data_dir / "tir" / "335_65R22_5_G275MSA_95psi.tir").read_text(encoding="latin-1")
    if not magic_formula:
        text = "\n".join(line for line in text.splitlines()
                         if not line.startswith(("FITTYP", "PROPERTY_FILE_FORMAT")))
    path = tmp_path / name
    path.write_text(text + extra, encoding="latin-1")
    return path


def test_a_tyre_without_contact_patch_data_is_told_it_gets_the_xzls(data_dir, tmp_path):
    """The enveloping models size their patch and cams from [CONTACT_PATCH]; a file without
    one (Chrono's FEDA) took the XZL's values without a word. Now one warning per file and
    process says which quantities were assumed; the XZL's own file says nothing."""
    import warnings

    from tyrelab.api import make_tyre_model

    def said(tyre, **options):
        with warnings.catch_warnings(record=True) as found:
            warnings.simplefilter("always")
            model = make_tyre_model(tyre, "enveloping", handling="none", options=options)
            model.contact_params(Flat().grid())
        return [str(w.message) for w in found if "[CONTACT_PATCH]" in str(w.message)]

    bare = _feda_copy(data_dir, tmp_path, "bare.tir", magic_formula=False)
    first = said(str(bare))
    assert len(first) == 1 and "bare.tir" in first[0] and "XZL 16.00R20" in first[0]
    assert "PA1 0.15, PA2 7.06" in first[0] and "the whole section width" in first[0]
    assert "N_WIDTH 10" in first[0] and "N_LENGTH 15" in first[0]
    assert said(str(bare)) == []                                   # once per file and process
    lengths = _feda_copy(data_dir, tmp_path, "lengths.tir",
                         "\n[CONTACT_PATCH]\nPA1 = 0.2\nPA2 = 5.0\nELLIPS_NWIDTH = 8\n", magic_formula=False)
    (text,) = said(str(lengths), n_length=5)
    assert "length law" not in text and "N_WIDTH" not in text and "N_LENGTH" not in text
    assert "PAE 0.72" in text and "the width law" in text
    assert said("xzl-16.00R20") == []
    (mf5,) = said(str(_feda_copy(data_dir, tmp_path, "mf5.tir")))   # MF-Tyre 5.0: its own length
    assert "length law" not in mf5 and "width law" not in mf5 and "PAE 0.72" in mf5
