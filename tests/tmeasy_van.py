"""Chrono's van TMeasy file with its full parameters (``tests/data/tir/van_TMeasyTireFull.json``),
mended so that it reads, and its parameters typed from the file: shared by the TMeasy tests."""

from tyrelab.tyre.chrono_json import read_chrono_tyre

from file_edit import edited

#: van_TMeasyTireFull.json's parameters, typed from the file: (at FZ_NOM, at 2 FZ_NOM)
VAN_NOMINAL = 1900.0
VAN_X = {"slope": (34910.7021, 73974.3082), "peak": (2145.5102, 4140.6407),
         "slide": (1522.8229, 2922.8487), "peak_slip": (0.13913, 0.13913),
         "slide_slip": (0.66667, 0.66667)}
VAN_Y = {"slope": (30366.8749, 48833.5824), "peak": (1901.7234, 3471.9636),
         "slide": (1583.8391, 2938.7727), "peak_slip": (0.14852, 0.18504),
         "slide_slip": (0.96524, 1.0714)}
VAN_TRAIL = {"at_zero": (0.178, 0.19), "sign_change": (0.16337, 0.20355)}


def fixed_van(tir_dir, tmp_path, *more):
    """The van's full file with its two faults mended: the damping under the key Chrono
    reads, and no bottoming radius (0.396 m, above its unloaded radius of 0.376 m); ``more``
    further ``(old, new)`` edits."""
    return read_chrono_tyre(edited(tir_dir / "van_TMeasyTireFull.json", tmp_path / "van.json",
                                   ('"Vertical Tire Damping [Ns/m]"', '"Tire Vertical Damping [Ns/m]"'),
                                   ('"Tire Bottoming Radius [m]": 0.396,', ""), *more))


