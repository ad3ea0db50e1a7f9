"""The towed single-axle tyre test trailer of thesis 3.4 and 5.2.

A rigid frame without suspension carries two wheels. The right wheel is the
test wheel and runs on the road under test; the left wheel runs on flat
ground. A towing vehicle pulls the hitch along a straight line at constant
speed; the frame pitches and rolls about the hitch (the towing vehicle holds
yaw). The six load cells of the real trailer measured the forces and
moments between the test wheel's sub-frame and the main frame; here they
are the ``*_HUB`` channels, and the tyre's own loads at the wheel centre
are the TYDEX channels ``FX`` ... ``MZ``.

The thesis does not publish the trailer's geometry, mass or inertia. The
values below are assumptions, chosen so the static test-wheel load equals
the load cases of Table 3-4 exactly (the ballast's position along the frame
is solved for); they are listed in ARCHITECTURE.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..tyre.library import load_cases
from ..tyre.model import Equilibrium, TyreModel
from ..road.base import Road
from ..road.obstacles import Flat
from ..road.spec import road_from_spec
from . import _trailer_kernel as K
from .simulation import drop_road, levelled_grid, run_chunks, to_signal
from .soil_ground import Following, with_sinkage
from .trailer_balance import balanced_loads
from .frames import G

#: on soil, the test wheel's sinkage and the frame's pitch and roll are found together in
#: rounds of settling until the height changes by under 10 x the settling's tolerance (the
#: point model: 4 rounds on dry sand and LETE sand, 5 on snow), at most this many
MAX_SETTLE_ROUNDS = 30


@dataclass
class TrailerGeometry:
    """Assumed geometry and masses of the test trailer (SI).

    Attributes
    ----------
    hitch_to_axle : float
        Horizontal distance from the hitch to the axle [m].
    track : float
        Distance between the wheel centres [m] (wider than the towing
        vehicle's, thesis 3.4).
    frame_cg_behind_hitch, frame_cg_height : float
        Bare trailer (frame, sub-frame, both wheels) centre of mass, behind
        and above the hitch [m].
    frame_gyration : tuple
        Radii of gyration of the bare trailer about its centre of mass
        (roll, pitch, yaw) [m].
    ballast_height : float
        Height of the ballast's centre of mass above the hitch [m].
    ballast_size : tuple
        Ballast block length, width, height [m] (for its inertia).
    """

    hitch_to_axle: float = 3.0
    track: float = 2.4
    frame_cg_behind_hitch: float = 2.7
    frame_cg_height: float = 0.3
    frame_gyration: tuple = (0.9, 1.1, 1.2)
    ballast_height: float = 0.6
    ballast_size: tuple = (1.2, 1.5, 0.5)


@dataclass
class TrailerSetup:
    """Masses and ballast solved for one load case; ``pitch0`` the frame's pitch at
    which the ballast was placed (the vertical law's deflection). A run starts at the
    pitch its wheels' equilibria give (:meth:`Trailer.run`)."""

    wheel_load: float
    frame_mass: float
    ballast_mass: float
    ballast_behind_hitch: float
    hitch_height: float
    pitch0: float
    inertia: np.ndarray
    mass: float
    cg: np.ndarray


def _block_inertia(m, a, b, c):
    return np.diag([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])


def _about_point(m, r, I_cg):
    r = np.asarray(r, float)
    return I_cg + m * (np.dot(r, r) * np.eye(3) - np.outer(r, r))


def load_case_wheel_load(load_case: str) -> float:
    """Static wheel load [N] of a load case of thesis Table 3-4."""
    cases = load_cases()
    key = str(load_case).upper()
    if key not in cases.index:
        raise InputError(f"unknown load case '{load_case}', expected one of "
                         f"{', '.join(cases.index)} or a wheel load in N", field="load")
    return float(cases.loc[key, "wheel_load_N"])


def trailer_setup(tyre, geometry: TrailerGeometry, load_case: str | float,
                  reference_load: float) -> TrailerSetup:
    """Solve the frame and ballast masses so the static test-wheel load is exact.

    The bare trailer is sized so that each wheel carries ``reference_load``
    (LC1) with the frame level; the ballast of the load case (Table 3-4) is
    placed along the frame where it brings the wheel load to the table
    value at the pitch the tyre's deflection gives.
    """
    gm = geometry
    L = gm.hitch_to_axle
    if isinstance(load_case, str):
        target = load_case_wheel_load(load_case)
        ballast = float(load_cases().loc[load_case.upper(), "ballast_kg"])
    else:
        target = float(load_case)
        if not (np.isfinite(target) and target > 0):
            raise InputError(f"wheel load must be a positive number of newtons, got {load_case}",
                             field="load")
        ballast = None
    r0 = tyre.unloaded_radius
    hitch_z = r0 - tyre.static_deflection(reference_load)   # level frame at the reference load
    # bare trailer: two wheels carry 2 * reference_load with the frame level
    frame_mass = 2.0 * reference_load * L / (G * gm.frame_cg_behind_hitch)
    defl = tyre.static_deflection(target)
    s = (r0 - defl - hitch_z) / L
    if abs(s) >= 0.5:
        raise InputError(f"load {target:.0f} N deflects the tyre {defl * 1e3:.0f} mm: the trailer "
                         "cannot stand level enough on its hitch", field="load")
    theta = math.asin(s)  # positive: rear up
    c, sn = math.cos(theta), math.sin(theta)

    def x_lever(xb, zb):  # horizontal distance behind the hitch after pitching
        return xb * c - zb * sn

    frame_lever = x_lever(gm.frame_cg_behind_hitch, gm.frame_cg_height)
    wheel_lever = L * c
    needed = 2.0 * target * wheel_lever / G - frame_mass * frame_lever  # kg m from ballast
    if ballast is None:  # a load in N: ballast over the axle when the bare trailer is too light
        ballast = max(needed / (L * c), 0.0)
    if ballast > 0.0:
        # solve x_lever(xb, ballast_height) = needed / ballast
        xb = (needed / ballast + gm.ballast_height * sn) / c
        return _finish(gm, target, frame_mass, ballast, xb, hitch_z, theta)
    # no ballast: the bare trailer's centre of mass sits where its weight gives the load
    frame_lever_needed = 2.0 * target * wheel_lever / (G * frame_mass)
    x_frame = (frame_lever_needed + gm.frame_cg_height * sn) / c
    return _finish(gm, target, frame_mass, 0.0, 0.0, hitch_z, theta, frame_cg_x=x_frame)


def _finish(gm, target, frame_mass, ballast, xb, hitch_z, theta, frame_cg_x=None):
    fx = gm.frame_cg_behind_hitch if frame_cg_x is None else frame_cg_x
    kx, ky, kz = gm.frame_gyration
    r_frame = np.array([-fx, 0.0, gm.frame_cg_height])
    inertia = _about_point(frame_mass, r_frame, np.diag([frame_mass * kx ** 2,
                                                          frame_mass * ky ** 2,
                                                          frame_mass * kz ** 2]))
    mass = frame_mass + ballast
    cg = frame_mass * r_frame
    if ballast > 0:
        r_b = np.array([-xb, 0.0, gm.ballast_height])
        inertia = inertia + _about_point(ballast, r_b, _block_inertia(ballast, *gm.ballast_size))
        cg = cg + ballast * r_b
    return TrailerSetup(target, frame_mass, ballast, xb, hitch_z, theta, inertia, mass, cg / mass)


class Trailer:
    """The towed tyre test trailer, driving a tyre model over a road.

    Parameters
    ----------
    model : TyreModel
        Tyre and contact model of the test (right) wheel, and of the left wheel unless
        ``left`` is given.
    geometry : TrailerGeometry, optional
        Assumed frame geometry (defaults documented in ARCHITECTURE.md).
    load_case : str or float
        ``"LC1"``, ``"LC2"``, ``"LC3"`` (thesis Table 3-4) or a wheel load [N].
    left : TyreModel, optional
        Model of the left wheel, which runs on flat ground (e.g. the point model of the
        same tyre: the same vertical law and damping at a fraction of a ring's cost). Its
        tyre must be the test wheel's.
    """

    def __init__(self, model: TyreModel, load_case="LC1", geometry: TrailerGeometry | None = None,
                 left: TyreModel | None = None):
        if left is not None and left.tyre is not model.tyre:
            raise InputError("the left wheel must use the test wheel's tyre (same property file "
                             "and pressure)", field="left")
        self.model = model
        self.left = left if left is not None else model
        self.geometry = geometry or TrailerGeometry()
        reference = float(load_cases().loc["LC1", "wheel_load_N"])
        self.setup = trailer_setup(model.tyre, self.geometry, load_case, reference)
        self.load_case = load_case

    def params(self, speed: float) -> K.TrailerParams:
        """The :class:`~._trailer_kernel.TrailerParams` record at towing ``speed`` [m/s].

        The frame's inertia counts both wheels whole; a tyre model whose own state moves part of
        its wheel (the ring's belt) has that part's taken out, a point mass at its wheel centre
        (the weight stays the frame's: the belt has none of its own)."""
        from ..guards import carried_inertia, rig_rim_mass, rig_spin_inertia
        s, gm, ty = self.setup, self.geometry, self.model.tyre
        inertia = np.array(s.inertia, np.float64)
        for model, side in ((self.model, -1.0), (self.left, 1.0)):
            belt = carried_inertia(model).mass
            if belt > 0.0:
                centre = (-gm.hitch_to_axle, side * 0.5 * gm.track, 0.0)
                inertia = _about_point(-belt, centre, inertia)
        return K.TrailerParams(
            speed=float(speed), hitch_to_axle=float(gm.hitch_to_axle), track=float(gm.track),
            hitch_height=float(s.hitch_height), mass=float(s.mass),
            cg=np.ascontiguousarray(s.cg, np.float64),
            inertia=np.ascontiguousarray(inertia),
            spin_inertia=rig_spin_inertia(self.model, s.wheel_load),
            wheel_mass=rig_rim_mass(self.model, float(ty.wheel_mass)) if ty.wheel_mass > 0 else 0.0,
            gravity=G, road_y=0.5 * float(gm.track))

    def run(self, road: Road | str, speed: float, duration: float | None = None,
            dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None,
            terrain=None):
        """Tow the trailer over ``road`` at ``speed`` [m/s]; returns the signal table.

        The test wheel starts at x = 0 in static equilibrium. Without
        ``duration`` the run lasts until the test wheel reaches the end of
        the road's extent. With ``terrain`` (a soil's name, file or
        :class:`~tyrelab.road.soil.params.Soil`) the test wheel runs on that soil laid
        over the road (:mod:`.soil_ground`), settled into it at the start; the
        left wheel stays on flat rigid ground.
        """
        road = road_from_spec(road)
        if not (np.isfinite(speed) and speed > 0):
            raise InputError(f"speed must be a positive number, got {speed}", field="speed")
        if not (dt > 0 and output_rate > 0):
            raise InputError("time step and output rate must be positive", field="dt")
        x0_road = road.run_start
        xmax = road.extent()[1]
        if duration is None:
            duration = max(xmax - x0_road, 1.0) / speed
        if not (np.isfinite(duration) and duration > 0):
            raise InputError(f"duration must be a positive number of seconds, got {duration}",
                             field="duration")
        from ..guards import check_level_for_trailer, check_reaches_relief
        check_level_for_trailer(road, x0_road, x0_road + speed * duration, self.geometry.track)
        check_reaches_relief(road, x0_road, speed, duration, self.model.tyre.unloaded_radius)
        s = self.setup
        # each wheel where its model carries the load rolling at this speed (the
        # ring's own load-deflection and centrifugal growth; the vertical law's
        # static deflection for the analytic models); the frame pitches and
        # rolls to put the wheel centres there
        grid = levelled_grid(road, x0_road)
        test_wheel = ground_meta = ground = None
        if terrain is None and not (self.model.contact_model.has_state
                                    or self.left.contact_model.has_state):
            # the loads at which the tyres' own forces at zero slip leave the frame still
            # (trailer_balance: the MF offsets, a rolling resistance), each wheel in its
            # equilibrium at its load
            built = self.model.wheel(grid, s.wheel_load, side="right")
            pitch, roll, (right, left) = balanced_loads(
                self, speed, built, self.left.wheel(Flat().grid(), s.wheel_load, side="left"), dt, x0_road)
            test_wheel = self.model.rolling_from(built, right)
        else:
            left = self.left.equilibrium(s.wheel_load, speed)
            r0 = self.model.tyre.unloaded_radius
            z_left = r0 - left.deflection
            if terrain is None:
                right = self.model.equilibrium(s.wheel_load, speed)
                z_right = r0 - right.deflection
            else:
                test_wheel, ground, z_right, z_left, ground_meta = self._settled_on(
                    terrain, road, x0_road, x0_road + speed * duration, left.state, z_left, dt)
                right = Equilibrium(r0 - z_right, speed / r0, test_wheel.state)
            pitch, roll = self.frame_angles(z_right, z_left)
        return self._run(road, speed, pitch, (right.spin, left.spin), s.wheel_load, duration,
                         dt, output_rate, progress, "trailer", roll, (right, left),
                         test_wheel, ground_meta, ground, grid)

    def frame_angles(self, z_right: float, z_left: float) -> tuple[float, float]:
        """``(pitch, roll)`` [rad] of the frame with its wheel centres at these heights [m]."""
        pitch = math.asin((0.5 * (z_right + z_left) - self.setup.hitch_height)
                          / self.geometry.hitch_to_axle)
        roll = math.asin((z_left - z_right) / (self.geometry.track * math.cos(pitch)))
        return pitch, roll

    def _settled_on(self, terrain, road, x0: float, x1: float, left_state, z_left: float,
                    dt: float):
        """``(wheel, ground, z_right, z_left, meta)``: the test wheel on ``terrain`` laid over
        ``road`` from ``x0`` to ``x1`` [m] (:func:`.soil_ground.lay_terrain`), settled under
        its load where the frame will hold it, and the left wheel's centre height [m].

        The left wheel stays on rigid ground (its upright equilibrium at ``z_left``), so the
        frame rolls towards the sunk test wheel and inclines both (the axle's spin axis is
        the frame's y axis, ``_trailer_kernel._rotation``) and moves the test wheel's contact
        across. Settled upright where the frame did not put it, the test wheel started on
        soil it had not pressed, 26 % light on dry sand, 30 % on snow. So the sinkage and the
        frame's pitch and roll are found together, each round settling on a copy of the
        ground at the pose the last one gave (the rounds change the height by a factor of
        about -0.3 each on snow, 11 deg of roll), then the ground is pressed there (and a
        ring settles at rest, :func:`.soil_ground.settle`). Each round also settles the left
        wheel on its level ground at that inclination: a wide tyre's shoulder dips as it
        leans (the ring by 12 mm at 3 deg), a disc's lowest point rises to ``R cos(roll)``."""
        from .soil_ground import SETTLE_TOLERANCE, UPRIGHT, lay_terrain, settle

        ground, meta = lay_terrain(self.model, terrain, road, x0, x1, level_at=x0)
        load, r0 = self.setup.wheel_load, self.model.tyre.unloaded_radius
        wheel = self.model.wheel(ground, load, side="right")
        dynamic = self.model.contact_model.has_state
        half = 0.5 * self.geometry.track
        # the left wheel on its level rigid ground, in the state it starts in (the trials
        # leave a ring's belt as it is: they do not step it)
        level = Flat().grid()
        left = self.left.wheel(level, load, state=left_state, side="left")
        x, y, axis, z_right, roll = x0, 0.0, UPRIGHT, None, 0.0
        for _ in range(MAX_SETTLE_ROUNDS):
            # the trials static (the ring's dynamic settling, up to SETTLE_TIME of its steps,
            # comes once, at the end)
            try:
                z = settle(wheel, ground, load, x, r0, y=y, dt=dt, axis=axis, press=False)
            except InputError as exc:
                if roll == 0.0:
                    raise
                raise InputError(f"{exc.reason}, leaning {math.degrees(roll):.3g} deg as the "
                                 "trailer's frame rolls towards it (its left wheel on rigid "
                                 "ground)", field=exc.field) from None
            done = z_right is not None and abs(z - z_right) < 10 * SETTLE_TOLERANCE
            z_right = z
            pitch, roll = self.frame_angles(z_right, z_left)
            sp, cp, sr, cr = math.sin(pitch), math.cos(pitch), math.sin(roll), math.cos(roll)
            # where the frame puts the test wheel on its road, and its spin axis (the body's y
            # axis, column 1 of Ry(pitch) Rx(roll)); the wheel sits half a track to the right
            # of the hitch, which runs over the road's y = 0
            x, y, axis = x0 - half * sp * sr, half * (1.0 - cr), (sp * sr, cr, cp * sr)
            if done:
                break
            # the left wheel where its model carries the load inclined as the frame holds it (a
            # wide tyre's shoulder dips: not the disc's cos(roll))
            z_left = settle(left, level, load, 0.0, self.left.tyre.unloaded_radius, axis=axis)
        z_right = settle(wheel, ground, load, x, r0, y=y, dynamic=dynamic, dt=dt, axis=axis)
        return wheel, ground, z_right, z_left, meta

    def drop(self, road: Road | str = "flat", lift: float = 0.0, duration: float = 3.0,
             dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None):
        """The drop test of thesis 3.4.1; returns the signal table.

        The trailer, standing still on its hitch, is lifted until both
        wheels just lose contact with the ground (wheel centres at the
        unloaded radius, plus ``lift`` [m]) and dropped; the rim's vertical
        motion (``Z_WC``) then decays to the static equilibrium -- the
        record from which the thesis finds the tyre's damping (eqs. 3.1-3.7).
        """
        road = drop_road(road, lift, duration)
        s = self.setup
        sine = (self.model.tyre.unloaded_radius + lift - s.hitch_height) / self.geometry.hitch_to_axle
        if abs(sine) >= 0.5:
            raise InputError(f"a lift of {lift} m tilts the trailer too far", field="lift")
        return self._run(road, 0.0, math.asin(sine), (0.0, 0.0), 0.0, duration, dt, output_rate,
                         progress, "trailer-drop")

    def _run(self, road, speed, pitch0, spins, wheel_load, duration, dt, output_rate, progress,
             rig, roll0=0.0, rolling=None, right_wheel=None, ground_meta=None, ground=None,
             grid=None):
        """Tow (or hold, at ``speed`` 0) the trailer from ``pitch0``, ``roll0`` [rad] at rest,
        the wheels spinning at ``spins`` (right, left) [rad/s], in the models' equilibria
        ``rolling`` (right, left; :meth:`TyreModel.equilibrium`, their states and slips);
        ``right_wheel`` the test wheel when it is built already (on a terrain, its Python
        ``ground``, named in ``ground_meta`` for the metadata); ``grid`` the test wheel's road
        levelled at its start when it is built already."""
        x0_road = road.run_start
        grid = levelled_grid(road, x0_road) if grid is None else grid
        tp = self.params(speed)
        L = self.geometry.hitch_to_axle
        state = np.zeros(K.S_SIZE)
        state[K.S.THETA] = pitch0
        state[K.S.PHI] = roll0
        state[K.S.WR], state[K.S.WL] = spins
        x_start = x0_road + L * math.cos(pitch0)  # test wheel centre starts at run_start
        n_steps = int(round(duration / dt))
        out_every = max(1, int(round(1.0 / (output_rate * dt))))

        right_eq, left_eq = rolling or (None, None)
        right = right_wheel or self.model.wheel(grid, wheel_load, rolling=right_eq, side="right")
        left = self.left.wheel(Flat().grid(), wheel_load, rolling=left_eq, side="left")

        follow = Following(ground, x_start, speed, dt, self.model.tyre.unloaded_radius)

        def advance(n, out, row):
            nonlocal right
            right = follow.wheel(right, n)
            return K.trailer_steps(right, left, tp, state, n, dt, out_every, out, row, x_start)

        data = run_chunks(advance, n_steps, out_every, K.N_CH, dt, progress)
        data[:, K.TC.DISTANCE] = data[:, K.TC.X_WC] - x0_road
        s = self.setup
        meta = {"rig": rig, "tyre": self.model.tyre.name, "model": self.model.contact,
                "left_wheel": self.left.contact,
                "handling": self.model.handling, "relaxation": self.model.relaxation_used,
                "stiffness": self.model.tyre.stiffness, "road": road.name, "speed_m_s": speed,
                **(ground_meta or {}),
                "load_case": str(self.load_case), "static_wheel_load_N": s.wheel_load,
                "pressure_Pa": self.model.tyre.pressure, "dt_s": dt,
                "output_rate_Hz": 1.0 / (out_every * dt)}
        data, channels = with_sinkage(data, K.CHANNELS, ground, K.TC, tp.road_y)
        return to_signal(data, channels, meta)
