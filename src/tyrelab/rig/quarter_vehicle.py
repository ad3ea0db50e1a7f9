"""Quarter-vehicle rig: a sprung mass on a suspension over one wheel.

For users who have a vehicle rather than a test trailer: the body mass
carried by one wheel, the suspension spring and damper, the wheel (tyre +
rim + hub) as the unsprung mass, rolling at constant speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..road.base import Road
from ..road.spec import road_from_spec
from ..tyre.model import TyreModel
from . import _quarter_kernel as K
from .simulation import drop_road, levelled_grid, run_chunks, to_signal
from .soil_ground import Following, with_sinkage
from .frames import G



@dataclass
class QuarterVehicle:
    """Quarter vehicle (SI).

    Parameters
    ----------
    model : TyreModel
    sprung_mass : float
        Body mass carried by this wheel [kg].
    unsprung_mass : float, optional
        Wheel, hub and half the suspension links [kg]; the tyre's wheel mass
        by default.
    suspension_stiffness, suspension_damping : float
        [N/m], [N s/m]. Defaults: 1.5 Hz body bounce, 30 % of critical.
    """

    model: TyreModel
    sprung_mass: float = 2135.0
    unsprung_mass: float | None = None
    suspension_stiffness: float | None = None
    suspension_damping: float | None = None
    spring_length: float = 0.5

    def __post_init__(self):
        if self.unsprung_mass is None:
            self.unsprung_mass = self.model.tyre.wheel_mass or 0.1 * self.sprung_mass
        ms = self.sprung_mass
        if not (ms > 0 and self.unsprung_mass > 0):
            raise InputError("masses must be positive", field="mass")
        if self.suspension_stiffness is None:
            self.suspension_stiffness = ms * (2 * math.pi * 1.5) ** 2
        if self.suspension_damping is None:
            self.suspension_damping = 0.3 * 2 * math.sqrt(self.suspension_stiffness * ms)

    @property
    def wheel_load(self) -> float:
        """Static wheel load [N]."""
        return (self.sprung_mass + self.unsprung_mass) * G

    def run(self, road: Road | str, speed: float, duration: float | None = None,
            dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None,
            terrain=None):
        """Drive over ``road`` at ``speed`` [m/s] from static equilibrium; signal table.

        With ``terrain`` (a soil's name, file or :class:`~tyrelab.road.soil.params.Soil`)
        the wheel runs on that soil laid over the road (:mod:`.soil_ground`), settled
        into it at the start."""
        road = road_from_spec(road)
        if not (np.isfinite(speed) and speed > 0):
            raise InputError(f"speed must be a positive number, got {speed}", field="speed")
        x0_road = road.run_start
        if duration is None:
            duration = max(road.extent()[1] - x0_road, 1.0) / speed
        tyre = self.model.tyre
        from ..guards import check_reaches_relief
        check_reaches_relief(road, x0_road, speed, duration, tyre.unloaded_radius)
        if terrain is not None:
            from .soil_ground import terrain_wheel
            wheel, ground, zu, ground_meta = terrain_wheel(self.model, terrain, road, x0_road,
                                                 x0_road + speed * duration, self.wheel_load,
                                                 level_at=x0_road, dt=dt)
            return self._run(road, speed, zu, speed / tyre.unloaded_radius, self.wheel_load,
                             duration, dt, output_rate, progress, "quarter-vehicle", wheel.state,
                             wheel, ground_meta, ground)
        # where the model carries the wheel load rolling at this speed
        eq = self.model.equilibrium(self.wheel_load, speed)
        return self._run(road, speed, tyre.unloaded_radius - eq.deflection, eq.spin,
                         self.wheel_load, duration, dt, output_rate, progress, "quarter-vehicle",
                         rolling=eq)

    def drop(self, road: Road | str = "flat", lift: float = 0.0, duration: float = 2.0,
             dt: float = 1e-3, output_rate: float = 1000.0, progress: bool | None = None):
        """A single wheel dropped: the quarter vehicle, standing still, is lifted until
        the tyre just leaves the ground (plus ``lift`` [m]) and released."""
        road = drop_road(road, lift, duration)
        return self._run(road, 0.0, self.model.tyre.unloaded_radius + lift, 0.0, 0.0, duration,
                         dt, output_rate, progress, "wheel-drop")

    def _run(self, road, speed, zu, omega0, wheel_load, duration, dt, output_rate, progress, rig,
             model_state=None, wheel=None, ground_meta=None, ground=None, rolling=None):
        """Drive (or hold, at ``speed`` 0) from hub height ``zu``, suspension at its static
        length, the tyre model in ``model_state`` (default: its static state) or in its rolling
        equilibrium ``rolling``; ``wheel`` the wheel when it is built already (on soil), on its
        Python ``ground``."""
        from ..guards import rig_rim_mass, rig_spin_inertia
        tyre = self.model.tyre
        x0_road = road.run_start
        ms, mu = self.sprung_mass, self.unsprung_mass
        qp = K.QuarterParams(
            speed=float(speed), sprung_mass=float(ms), unsprung_mass=float(mu),
            rim_mass=rig_rim_mass(self.model, mu, "the unsprung mass"),
            stiffness=float(self.suspension_stiffness), damping=float(self.suspension_damping),
            spring_free_length=float(self.spring_length + ms * G / self.suspension_stiffness),
            spin_inertia=rig_spin_inertia(self.model, self.wheel_load), gravity=G,
            x_start=float(x0_road))
        state = np.zeros(K.Q_SIZE)
        state[K.Q.ZU] = zu
        state[K.Q.ZS] = zu + self.spring_length
        state[K.Q.W] = omega0
        wheel = wheel or self.model.wheel(levelled_grid(road, x0_road), wheel_load, state=model_state,
                                          rolling=rolling)
        n_steps = int(round(duration / dt))
        out_every = max(1, int(round(1.0 / (output_rate * dt))))

        follow = Following(ground, x0_road, speed, dt, tyre.unloaded_radius)

        def advance(n, out, row):
            nonlocal wheel
            wheel = follow.wheel(wheel, n)
            return K.quarter_steps(wheel, qp, state, n, dt, out_every, out, row)

        data = run_chunks(advance, n_steps, out_every, K.N_CH, dt, progress)
        meta = {"rig": rig, "tyre": tyre.name, "model": self.model.contact,
                "handling": self.model.handling, "relaxation": self.model.relaxation_used,
                "stiffness": tyre.stiffness, "road": road.name, "speed_m_s": speed,
                **(ground_meta or {}),
                "static_wheel_load_N": self.wheel_load, "pressure_Pa": tyre.pressure, "dt_s": dt,
                "output_rate_Hz": 1.0 / (out_every * dt)}
        data, channels = with_sinkage(data, K.CHANNELS, ground, K.QC)
        return to_signal(data, channels, meta)
