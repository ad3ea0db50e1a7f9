"""tyrelab: a virtual tyre test lab for rough and off-road terrain.

Three lines from a notebook::

    import tyrelab
    run = tyrelab.simulate(model="point", road="cleat:50x50", speed=12 / 3.6, load="LC1")
    run.plot(x="RUNTIME", y="FZW")

Units are SI everywhere in Python; the command line takes km/h and kPa.
See ARCHITECTURE.md for the layers and the sign conventions
(:mod:`tyrelab.signal`).
"""

from .core.jit_cache import configure as _configure_jit_cache

_configure_jit_cache()  # before any kernel module is imported: see tyrelab.core.jit_cache

from ._version import __version__  # noqa: E402
from .api import make_tyre_model, simulate  # noqa: E402
from .errors import InputError  # noqa: E402
from .signal import read_signal, write_signal  # noqa: E402
from .tyre.library import load_tyre  # noqa: E402

__all__ = ["simulate", "make_tyre_model", "load_tyre", "read_signal", "write_signal", "InputError"]
