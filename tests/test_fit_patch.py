"""Contact-patch laws (eqs. 2.3, 2.4, the half-width table) and footprint images (thesis 3.3.3, 4.4).

Round trips: points on eq. 2.3 / 2.4 with known parameters come back
exactly, the thesis's own PA and PB among them (its measured points are only
in Figures 4-2 and 4-3); an analytic ellipse and the volume model's
geometric footprint rendered to black-and-white bitmaps with a 100 mm
calibration line are measured back to a pixel. Noise degrades them by
stated bounds.
"""

import numpy as np
import pytest

from tyrelab.errors import InputError
from tyrelab.fit.footprint_image import (measure_footprint, read_footprint_image, render_footprint,
                                         write_bitmap)
from tyrelab.fit.patch import (contact_half_length, contact_half_width, contact_width_table,
                               fit_contact_length, fit_contact_width)

R0, W0 = 0.6715, 0.438
#: thesis 4.4 (tyre.toml [contact_patch])
PA1, PA2 = 0.15, 7.06
PB1, PB2, PB3 = 0.0017, 16006.5, -77819.1
D = np.arange(20, 86, 5) / 1e3


def test_eq_2_3_by_hand():
    q = 0.04 / R0
    assert contact_half_length(0.04, PA1, PA2, R0) == pytest.approx(PA1 * R0 * (q + PA2 * q ** 0.5))


def test_thesis_pa1_pa2_come_back_from_their_own_curve():
    fit = fit_contact_length(D, contact_half_length(D, PA1, PA2, R0), R0)
    assert (fit.pa1, fit.pa2) == pytest.approx((PA1, PA2), rel=1e-9)
    assert fit.rms < 1e-12


def test_thesis_pb1_pb3_come_back_from_their_own_curve():
    """The thesis's PB set is recovered from widths on its own eq. 2.4 curve -- which is
    1.6-2.1 m of half width on a 0.438 m tyre (b / W0 = 3.7 to 4.8): section 4.4 found the
    formula unfit for this tyre, and no physical width data can give those numbers."""
    b = contact_half_width(D, PB1, PB2, PB3, R0, W0, clip=False)
    assert 3.5 < (b / W0).min() and (b / W0).max() < 5.0
    fit = fit_contact_width(D, b, R0, W0)
    assert (fit.pb1, fit.pb2, fit.pb3) == pytest.approx((PB1, PB2, PB3), rel=1e-6)


def test_noise_on_the_lengths_degrades_pa_gracefully():
    """2 mm of noise on each half length (14 footprints): the fitted curve stays within 2 mm
    RMS of the true one over 20-85 mm, and the fit's residual is the noise's part outside
    the law.

    The law is linear in (PA1, PA1 PA2) with the basis [x, sqrt(x)] (n = 14 points, p = 2), and
    the true half lengths lie on it, so a least-squares fit leaves exactly the residual
    (I - H) e of the noise e (H: the projection onto the basis) and moves the curve by H e.
    For Gaussian e of sigma 2 mm: |H e|^2 / sigma^2 is chi-squared with p = 2 degrees of
    freedom and n rms^2 / sigma^2 with n - p = 12."""
    sigma, n, p = 0.002, D.size, 2
    a = contact_half_length(D, PA1, PA2, R0)
    noise = np.random.default_rng(3).normal(0.0, sigma, n)
    fit = fit_contact_length(D, a + noise, R0)
    err = contact_half_length(D, fit.pa1, fit.pa2, R0) - a
    # RMS(H e) >= 2 mm means chi2(2) >= n: probability exp(-n / 2) = 1e-3 over seeds
    assert np.sqrt(np.mean(err ** 2)) < sigma
    # the residual, computed from the noise alone (QR projection, not the fit's lstsq on the data)
    x = D / R0
    q, _ = np.linalg.qr(np.column_stack([x, np.sqrt(x)]))
    residual = noise - q @ (q.T @ noise)
    assert fit.rms == pytest.approx(np.sqrt(np.mean(residual ** 2)), rel=1e-9)
    np.testing.assert_allclose(err, noise - residual, rtol=0, atol=1e-12)   # the curve moved by H e
    # over many noise draws, the mean of rms^2 / sigma^2 is (n - p) / n = 0.857 (a fit that
    # missed the least-squares optimum would leave more; a residual divided by n - p instead
    # of n would give 1.0). One draw of n rms^2 / sigma^2 has a standard deviation of
    # sqrt(2 (n - p)) = 4.9, i.e. +-41 % about its mean of 12: a single seed cannot check this
    # to better than a factor of about 2. The mean of 400 draws has a standard error of
    # sqrt(2 (n - p)) / n / sqrt(400) = 0.0175; the bound is 4 standard errors (6e-5 of seeds).
    draws = 400
    rng = np.random.default_rng(4)
    rms2 = np.array([fit_contact_length(D, a + rng.normal(0.0, sigma, n), R0).rms ** 2
                     for _ in range(draws)]) / sigma ** 2
    standard_error = np.sqrt(2 * (n - p)) / n / np.sqrt(draws)
    assert abs(rms2.mean() - (n - p) / n) < 4 * standard_error


def test_lengths_that_shrink_with_deflection_are_refused():
    """Patch lengths that fall as the tyre is pressed (columns swapped, say: 250, 240, 230 mm at
    20, 30, 40 mm) have no physical eq. 2.3: the least squares give PA1 = -5.2, a patch that
    shrinks from 24 mm on and is negative past 96 mm. Refused, saying why; before, written."""
    with pytest.raises(InputError, match="does not grow with deflection.*250 mm at 20 mm to 230 mm at 40 mm"):
        fit_contact_length([0.02, 0.03, 0.04], [0.125, 0.12, 0.115], 0.6715)


def test_width_table_and_line():
    d = np.array([0.02, 0.04, 0.04, 0.06])
    b = np.array([0.18, 0.19, 0.20, 0.20])
    wt = contact_width_table(d, b)
    assert wt.table.ravel() == pytest.approx([0.02, 0.18, 0.04, 0.195, 0.06, 0.20])
    slope, intercept = np.polyfit(d, b, 1)
    assert (wt.slope, wt.intercept) == pytest.approx((slope, intercept))
    assert wt.rms == pytest.approx(np.sqrt(2 * 0.005 ** 2 / 4))


def _ellipse(a, b):
    return lambda x, y: (x / a) ** 2 + (y / b) ** 2 <= 1.0


@pytest.mark.parametrize("scale", [0.001, 0.0005])
@pytest.mark.parametrize("red", [False, True])
def test_ellipse_bitmap_round_trip(tmp_path, scale, red):
    """Length, width within two pixels, inked area within 1 %, the outline's area within 1.5 %
    of pi a b, whatever the scale and the line's colour."""
    a, b = 0.21, 0.16
    write_bitmap(tmp_path / "fp.png", render_footprint(_ellipse(a, b), 2 * a, 2 * b, scale=scale,
                                                       red_line=red))
    fp = read_footprint_image(tmp_path / "fp.png", line_length=0.1)
    assert fp.scale == pytest.approx(scale, rel=0.01)
    assert fp.length == pytest.approx(2 * a, abs=2 * scale)
    assert fp.width == pytest.approx(2 * b, abs=2 * scale)
    assert fp.area == pytest.approx(np.pi * a * b, rel=0.01)
    assert fp.gross_area == pytest.approx(np.pi * a * b, rel=0.015)
    x, y = fp.outline[:, 0], fp.outline[:, 1]
    assert np.ptp(x) == pytest.approx(2 * a, abs=2 * scale)
    assert np.ptp(y) == pytest.approx(2 * b, abs=2 * scale)


def test_travel_axis_and_tread_blocks():
    """A patch of separate tread blocks, travel drawn horizontally: the extents along and across."""
    a, b = 0.2, 0.15
    lugs = lambda x, y: _ellipse(a, b)(x, y) & (np.mod(x + 1.0, 0.04) < 0.03)  # noqa: E731
    img = render_footprint(lugs, 2 * a, 2 * b, scale=0.001)
    fp = measure_footprint(np.transpose(img, (1, 0, 2)), travel="horizontal")
    assert fp.length == pytest.approx(2 * a, abs=0.011)    # the outermost lugs, 10 mm gaps
    assert fp.width == pytest.approx(2 * b, abs=0.003)
    assert fp.area == pytest.approx(0.75 * np.pi * a * b, rel=0.05)


@pytest.mark.parametrize("turn", [12.0, -30.0])
def test_a_print_turned_on_the_glass_is_measured_along_its_own_axes(turn):
    """A rounded-square print (|x/a|^4 + |y/b|^4 <= 1, as a truck tyre's) photographed turned
    ``turn`` degrees from the image's travel axis: its length and width within three pixels,
    the turn within half a degree, the outline's extents the same. Along the image's axes a
    20 deg turn read 414 x 423 mm for 368 x 381."""
    a, b = 0.19, 0.16
    t = np.radians(turn)

    def inside(x, y):   # the print's own coordinates, turned by ``turn`` in the image
        u, v = np.cos(t) * x + np.sin(t) * y, -np.sin(t) * x + np.cos(t) * y
        return (u / a) ** 4 + (v / b) ** 4 <= 1.0

    img = render_footprint(inside, 2.6 * a, 2.6 * a, scale=0.001)
    fp = measure_footprint(img)
    assert fp.length == pytest.approx(2 * a, abs=0.003)
    assert fp.width == pytest.approx(2 * b, abs=0.003)
    assert np.degrees(abs(fp.angle)) == pytest.approx(abs(turn), abs=0.5)
    assert np.ptp(fp.outline[:, 0]) == pytest.approx(2 * a, abs=0.003)
    assert np.ptp(fp.outline[:, 1]) == pytest.approx(2 * b, abs=0.003)


def test_geometric_footprint_of_the_volume_model_round_trip(xzl):
    """The undeformed Table 4-1 carcass cut by the plate at 40 mm (the volume model's
    footprint, tyrelab.rig.static_press) drawn as a bitmap: its length and width come back."""
    from tyrelab.rig.static_press import geometric_footprint
    g = geometric_footprint(xzl, 0.04, 22000.0)
    half = {}
    for yy, xx in zip(np.round(g["y"], 6), g["x"]):
        half[yy] = max(half.get(yy, 0.0), abs(xx))
    ys = np.array(sorted(half))
    disc_w = g["cell"][1] if np.ndim(g["cell"]) else np.min(np.diff(ys))
    pitch = 0.005  # the cells' length along x (FOOTPRINT_PITCH)

    def inside(x, y):
        k = np.abs(y[..., None] - ys).argmin(axis=-1)
        near = np.abs(y - ys[k]) <= 0.5 * disc_w
        return near & (np.abs(x) <= np.array([half[v] for v in ys])[k] + 0.5 * pitch)

    img = render_footprint(inside, g["length"], g["width"], scale=0.001)
    fp = measure_footprint(img)
    assert fp.length == pytest.approx(g["length"], abs=0.003)
    assert fp.width == pytest.approx(g["width"], abs=0.003)


def test_specks_are_not_contact():
    """Salt-and-pepper noise on 1 % of the pixels: specks of fewer than 4 pixels are dropped,
    white holes in the patch only thin the inked area (within 2 %)."""
    a, b = 0.2, 0.15
    img = render_footprint(_ellipse(a, b), 2 * a, 2 * b, scale=0.001)
    rng = np.random.default_rng(5)
    flip = rng.random(img.shape[:2]) < 0.01
    img[flip] = 1.0 - img[flip]
    fp = measure_footprint(img)
    assert fp.length == pytest.approx(2 * a, abs=0.003)
    assert fp.width == pytest.approx(2 * b, abs=0.003)
    assert fp.area == pytest.approx(np.pi * a * b, rel=0.02)


def test_image_without_a_line_is_refused(tmp_path):
    img = np.ones((200, 200, 3))
    img[50:150, 60:140] = 0.0
    write_bitmap(tmp_path / "noline.png", img)
    with pytest.raises(InputError, match="noline.png.*(calibration|one dark region)"):
        read_footprint_image(tmp_path / "noline.png")
    img[180:183, 20:40] = 0.0       # a short blob: not a line (7 x 3)
    write_bitmap(tmp_path / "noline.png", img)
    with pytest.raises(InputError, match="no calibration line"):
        read_footprint_image(tmp_path / "noline.png")
