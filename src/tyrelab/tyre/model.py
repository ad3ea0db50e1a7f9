"""A tyre with the models that drive it: the Python side of the wheel interface.

:class:`TyreModel` composes a :class:`~tyrelab.tyre.params.Tyre` with a
contact model and a handling model chosen by name from the registry
(:mod:`tyrelab.tyre.registry`), and builds the :class:`~tyrelab.tyre.wheel.Wheel`
record a rig's compiled loop takes. :func:`contact_geometry_table` is the
plain function behind each model's own ``*_geometry`` function: the
deflection, contact point and normal at given wheel positions over a road.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numba as nb
import numpy as np
import pandas as pd

from ..core.named_index import named_index
from ..errors import InputError
from ..road.grid import RoadGrid
from ..road.obstacles import Flat
from ..road.spec import road_from_spec
from .handling.relaxation import SlipLag, no_lag, slip_lag
from .params import Tyre
from .registry import ContactModel, HandlingModel, contact_model, handling_model
from .wheel import ContactGeometry, Wheel, WheelLoads, WheelPose, contact_geometry, loads_table, pose


#: Newton steps at most to the spin of a freely rolling wheel (:meth:`TyreModel._torque_free`)
MAX_TORQUE_FREE_STEPS = 20
#: the largest change of the slip in one of those steps: a slope read where the forces
#: level off (a clipped slip range) must not throw the spin out of the tyre's range
MAX_TORQUE_FREE_SLIP = 0.02


class Equilibrium(NamedTuple):
    """A wheel in equilibrium on a flat road (:meth:`TyreModel.equilibrium`)."""

    #: deflection R0 - centre height [m]
    deflection: float
    #: free-rolling spin [rad/s]
    spin: float
    #: the model's internal state (empty for analytic models)
    state: object
    #: the transient slip's carcass deflections ``(u, v)`` [m] in that free rolling
    #: (:mod:`.handling.relaxation`: ``u = -sigma_kappa kappa``, the little slip a handling
    #: model's force offsets and rolling resistance need; :meth:`TyreModel._torque_free`)
    carcass: tuple = (0.0, 0.0)
    #: the effective rolling radius ``speed / spin`` [m] (0 at rest): what a model with no
    #: slip law of its own (the ring) measures its kinematic slip against
    rolling_radius: float = 0.0


@dataclass
class TyreModel:
    """A tyre with the models that drive it.

    Parameters
    ----------
    tyre : Tyre
        Parameters (from a ``.tir`` or :func:`tyrelab.tyre.library.load_tyre`).
    contact : str
        Contact model: a name registered in :mod:`tyrelab.tyre.registry`
        (``point``, ``volume``, ``enveloping``, ``ring``, ``ring-tp``, ...).
    handling : str
        Handling model: ``"none"``, ``"pac89"``, ``"mf"``, ...
    options : dict
        Options of the contact model's ``build`` (e.g. ``n_width`` for the
        enveloping model, ``n_segments`` for the ring).
    relaxation : str or (float, float)
        Transient slip of the handling forces (:mod:`.handling.relaxation`):
        ``"auto"`` as the property file asks (its ``USE_MODE`` +10, for a
        handling model with lengths of its own: the Magic Formula, Fiala),
        ``"off"``, ``"file"`` (the handling model's own relaxation lengths) or
        two lengths ``(sigma_kappa, sigma_alpha)`` [m].
        The ring's tread makes its own transients and takes no handling model.
    """

    tyre: Tyre
    contact: str = "point"
    handling: str = "none"
    options: dict = field(default_factory=dict)
    relaxation: object = "auto"

    def __post_init__(self):
        self.contact_model  # unknown names fail here, listing the known ones
        self.handling_model
        self.slip_lag()  # and an impossible relaxation

    @property
    def contact_model(self) -> ContactModel:
        return contact_model(self.contact)

    @property
    def handling_model(self) -> HandlingModel:
        return handling_model(self.handling)

    @property
    def has_state(self) -> bool:
        """True for models with their own dynamics (the ring)."""
        return self.contact_model.has_state

    def contact_params(self, grid, static: bool = False):
        """The contact model's parameter record for a road grid.

        ``static`` adds the model's options for static tests (e.g. the
        ring's relaxation damping).
        """
        options = dict(self.options)
        if static:
            extra = self.contact_model.static_options
            for key, value in (extra(grid) if callable(extra) else extra).items():
                options.setdefault(key, value)
        from .contact.soil_wheel import wheel_params  # on soil an analytic model is a flexible wheel
        return wheel_params(self.contact_model, self.tyre, grid, options)

    def handling_params(self, side: str | None = None):
        """The handling model's parameter record; ``side`` ("left", "right") the side of a
        vehicle a rig mounts the wheel on: the tyre mirrored where that is not the side its
        file states it was measured on (``[MODEL] TYRESIDE``, :func:`measured_side`) and the
        model can mirror (:attr:`~.registry.HandlingModel.mirror`, the Magic Formula's), as
        MF-Tyre and Chrono mount it. No side (a test rig, the FMU): the tyre as measured."""
        params = self.handling_model.build(self.tyre)
        measured = measured_side(self.tyre.tir)
        if side is not None and measured is not None and side != measured and self.handling_model.mirror:
            params = self.handling_model.mirror(params)
        return params

    def slip_lag(self, carcass=(0.0, 0.0)) -> SlipLag:
        """The transient slip of a new wheel, its carcass deflected by ``carcass`` [m] (an
        equilibrium's, :attr:`Equilibrium.carcass`)."""
        lag = slip_lag(self.tyre, self.handling_model, self.relaxation)
        lag.deflection[:] = carcass
        return lag

    @property
    def relaxation_used(self) -> str:
        """The transient slip a run uses, in words (its metadata): ``"off"``, ``"file"`` or
        the two lengths ``"SIGMA_KAPPA,SIGMA_ALPHA"`` [m]."""
        lag = self.slip_lag()
        if lag.from_model:
            return "file"
        return f"{lag.length_x:g},{lag.length_y:g}" if lag.active else "off"

    def initial_state(self, load: float, params=None):
        """Internal state in static equilibrium at ``load`` [N] on a flat road."""
        if params is None:
            params = self.contact_params(Flat().grid())
        return self.contact_model.initial_state(self.tyre, float(load), params, **self.options)

    def equilibrium(self, load: float, speed: float = 0.0, params=None) -> Equilibrium:
        """Where a rig starts this wheel: carrying ``load`` [N] while rolling freely
        at ``speed`` [m/s] on a flat road (see :class:`Equilibrium`).

        ``params`` the contact record the wheel will run with (default: built
        for a flat road). Analytic models stand at the vertical law's
        deflection at the free-rolling spin (:meth:`_free_rolling`); a model
        with its own load-deflection (the ring) finds
        its own (registry hook ``equilibrium``).
        """
        if params is None:
            params = self.contact_params(Flat().grid())
        load = float(load)
        hook = self.contact_model.equilibrium
        if hook is not None and load > 0:
            deflection, spin, state = hook(self.tyre, load, float(speed), params, **self.options)
            return Equilibrium(float(deflection), float(spin), state,
                               rolling_radius=float(speed) / float(spin) if spin > 0 else 0.0)
        deflection, spin = self._free_rolling(load, float(speed))
        carcass = (0.0, 0.0)
        if load > 0 and speed > 0 and self.handling != "none":
            deflection, spin, carcass = self._torque_free(load, float(speed), deflection, spin,
                                                          params)
        return Equilibrium(deflection, spin, self.initial_state(load, params), carcass,
                           float(speed) / spin if spin > 0 else 0.0)

    def _torque_free(self, load: float, speed: float, deflection: float, spin: float, params):
        """``(deflection, spin, carcass)`` where the wheel's moment about its axle
        vanishes (and the transient slip's steady carcass deflections there), from
        the spin at ``speed / R`` (:meth:`_free_rolling`): a handling model whose force is not
        zero at zero slip (the Magic Formula's offsets SHx, SVx) or that has a rolling
        resistance (:attr:`~.registry.HandlingModel.rolling_resistance`) rolls freely at a
        little slip. Newton on the spin with the step's own slope (``dspin_domega``) on a flat
        road, steady slip, to 1e-9 of ``load R0``; the deflection follows the spin (the law's
        speed stiffening). A wheel already free (no offset, no rolling resistance) keeps its
        spin exactly. The carcass's longitudinal deflection is ``-sigma_kappa kappa`` at the
        load the wheel carries there (its lengths may depend on it). ``params`` the contact
        record on a flat road."""
        r0 = self.tyre.unloaded_radius
        wheel = Wheel(self.tyre.vertical_law, params, self.handling_params(), Flat().grid().surface(),
                      self.initial_state(load, params), no_lag())
        tolerance = 1e-9 * load * r0
        largest = MAX_TORQUE_FREE_SLIP * spin  # a Newton step's largest change of the spin
        slip = 0.0
        for _ in range(MAX_TORQUE_FREE_STEPS):
            at = pose(cz=r0 - deflection, velocity=(speed, 0.0, 0.0), omega=spin)
            loads = WheelLoads(*loads_table(wheel, np.array([at]))[0])
            slip = loads.kappa
            if abs(loads.my) <= tolerance:
                break
            if not loads.dspin_domega < 0.0:  # the force stopped growing with the slip
                raise self._no_free_rolling(load, speed, loads.my, slip)
            spin -= min(max(loads.my / loads.dspin_domega, -largest), largest)
            deflection = self.tyre.vertical_law.deflection_at(load, spin)
        else:
            raise self._no_free_rolling(load, speed, loads.my, slip)
        lag = self.slip_lag()
        length = lag.length_x
        if lag.from_model:
            length = self.handling_model.relaxation_lengths(wheel.handling, loads.fzw, speed, 0.0)[0]
        return deflection, spin, (-length * slip if lag.active else 0.0, 0.0)

    def _no_free_rolling(self, load: float, speed: float, moment: float, slip: float) -> InputError:
        """The error of a wheel whose handling forces cannot hold its moment about the axle."""
        return InputError(f"the wheel finds no free-rolling spin at {load:.0f} N and {speed:.3g} m/s: "
                          f"its {self.handling} forces leave {moment:.3g} N m about the axle at slip "
                          f"{slip:.3g} (a slip range KPUMIN..KPUMAX that excludes the braking slip "
                          "its rolling resistance needs?)", source=self.tyre.name, field="tyre")

    def _free_rolling(self, load: float, speed: float) -> tuple[float, float]:
        """``(deflection, spin)`` of an analytic model's wheel carrying ``load`` [N] rolling
        freely at ``speed`` [m/s]: the spin ``speed / R`` with R the handling model's
        effective rolling radius (:attr:`~tyrelab.tyre.registry.HandlingModel.rolling_radius`),
        else the loaded radius ``R0 - deflection``; the deflection the vertical law's at that
        spin (its speed stiffening, :attr:`Tyre.speed_stiffening`). Each needs the other:
        fixed point, to 1e-12."""
        tyre, law = self.tyre, self.tyre.vertical_law
        r0 = tyre.unloaded_radius
        deflection = law.deflection_at(load) if load > 0 else 0.0
        radius = self.handling_model.rolling_radius if load > 0 else None
        handling = self.handling_params() if radius is not None else None
        spin = speed / (r0 - deflection)
        for _ in range(100):
            lever = r0 - deflection if radius is None else radius(handling, load, spin)
            new_spin = speed / lever
            new = law.deflection_at(load, new_spin) if load > 0 else 0.0
            done = abs(new - deflection) <= 1e-12 and abs(new_spin - spin) <= 1e-12 * abs(new_spin)
            deflection, spin = new, new_spin
            if done:
                break
        return deflection, spin

    def wheel(self, grid, load: float = 0.0, static: bool = False, state=None,
              rolling: Equilibrium | None = None, side: str | None = None) -> Wheel:
        """The :class:`Wheel` record of this tyre on road ``grid`` at static ``load`` [N],
        mounted on ``side`` of a vehicle (:meth:`handling_params`).

        ``state`` the model's internal state to start from; default the static one.
        ``rolling`` an equilibrium (:meth:`equilibrium`) to start in instead: its state, and
        the transient slip's carcass deflections; a model whose record keeps a
        ``rolling_radius`` (the ring) measures its kinematic slip against that equilibrium's.
        """
        params = self.contact_params(grid, static)
        if rolling is not None:
            state = rolling.state
        if state is None:
            state = self.initial_state(load, params)
        wheel = Wheel(self.tyre.vertical_law, params, self.handling_params(side), grid.surface(),
                      state, self.slip_lag())
        return wheel if rolling is None else self.rolling_from(wheel, rolling)

    def rolling_from(self, wheel: Wheel, rolling: Equilibrium) -> Wheel:
        """``wheel`` (a record of this model's) started in the equilibrium ``rolling``
        instead: its state, the transient slip's carcass deflections (fresh arrays) and, for
        a model whose record keeps one (the ring), its rolling radius."""
        params = wheel.contact
        if rolling.rolling_radius > 0 and "rolling_radius" in getattr(params, "_fields", ()):
            params = params._replace(rolling_radius=rolling.rolling_radius)
        state = wheel.state if rolling.state is None else rolling.state
        return wheel._replace(contact=params, state=state, lag=self.slip_lag(rolling.carcass))


#: number of fields of a :class:`ContactGeometry`
N_GEOMETRY = len(ContactGeometry._fields)
#: columns of the ``poses`` of :func:`wheel_positions`: a :class:`WheelPose`'s centre
#: and spin axis
POSE_COLUMNS = ("CX", "CY", "CZ", "AX", "AY", "AZ")
PO = named_index("PoseColumnIndex", POSE_COLUMNS)


@nb.njit(cache=True)
def _geometry_many(params, road, poses, out):
    for k in range(poses.shape[0]):
        p = poses[k]
        geo = contact_geometry(params, road, WheelPose(p[PO.CX], p[PO.CY], p[PO.CZ],
                                                       p[PO.AX], p[PO.AY], p[PO.AZ],
                                                       0.0, 0.0, 0.0, 0.0))
        for j in range(N_GEOMETRY):
            out[k, j] = geo[j]


def contact_geometry_table(model: TyreModel, road, x, y=0.0, z=None, axis=(0.0, 1.0, 0.0)):
    """Contact geometry of an analytic model at wheel centres ``(x, y, z)`` over ``road``.

    Parameters
    ----------
    model : TyreModel
        An analytic contact model (point, volume, enveloping).
    road : str, Road or RoadGrid
        A road name (:func:`tyrelab.road.spec.road_from_spec`), road or grid.
    x, y : array_like
        Wheel-centre positions [m] (broadcast).
    z : array_like, optional
        Wheel-centre heights [m]; default: the unloaded radius above the road
        straight below the centre (the tyre just touching a level road).
    axis : 3 floats
        Unit spin axis (default level, heading +x).

    Returns
    -------
    pandas.DataFrame
        One row per position: ``x, y, z`` and the :class:`ContactGeometry`
        fields (``deflection`` [m], ``px, py, pz`` contact point, ``nx, ny,
        nz`` normal, ``curvature`` [1/m]).
    """
    if model.has_state:
        raise TypeError(f"model '{model.contact}' has its own dynamics; use a rig "
                        "(tyrelab.rig.static_press, tyrelab.rig.rolling) instead")
    grid, poses = wheel_positions(road, x, y, z, axis, model.tyre.unloaded_radius)
    out = np.empty((poses.shape[0], N_GEOMETRY))
    _geometry_many(model.contact_params(grid), grid.surface(), poses, out)
    return positions_table(poses, out, ContactGeometry._fields)


def measured_side(tir) -> str | None:
    """The side of a vehicle ("left", "right") a property file's tyre was measured on, its
    ``[MODEL] TYRESIDE``; None for 'UNKNOWN', 'SYMMETRIC' or no key (nothing to mirror by:
    Chrono reads 'UNKNOWN' as left, an assumption not made here)."""
    value = tir.get("MODEL", "TYRESIDE") if tir is not None else None
    word = value.strip().lower() if isinstance(value, str) else ""  # the reader strips the quotes
    return word if word in ("left", "right") else None


def wheel_positions(road, x, y=0.0, z=None, axis=(0.0, 1.0, 0.0), unloaded_radius=0.0):
    """``(grid, poses)`` for evaluating a model at wheel centres ``(x, y, z)``.

    ``road`` a name, Road or RoadGrid; ``x, y`` broadcast; ``z`` defaults to
    ``unloaded_radius`` above the road straight below the centre. ``poses``
    rows are :data:`POSE_COLUMNS` (``cx, cy, cz, ax, ay, az``).
    """
    grid = road if isinstance(road, RoadGrid) else road_from_spec(road).grid()
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    x, y = x.ravel(), y.ravel()
    if z is None:
        z = grid.height(x, y) + float(unloaded_radius)
    poses = np.empty((x.size, len(POSE_COLUMNS)))
    poses[:, PO.CX], poses[:, PO.CY] = x, y
    poses[:, PO.CZ] = np.broadcast_to(np.asarray(z, float), x.shape)
    poses[:, [PO.AX, PO.AY, PO.AZ]] = np.asarray(axis, float)
    return grid, poses


def positions_table(poses, values, columns) -> pd.DataFrame:
    """A table of ``x, y, z`` (from ``poses``) and the named ``values`` columns."""
    table = pd.DataFrame(values, columns=list(columns))
    for k, name in ((PO.CZ, "z"), (PO.CY, "y"), (PO.CX, "x")):
        table.insert(0, name, poses[:, k])
    return table
