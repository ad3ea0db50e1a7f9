"""A parsed study spec: plain records in SI units (made by :mod:`tyrelab.study.spec`).

:class:`StudySpec` expands into :class:`RunSpec` s (:meth:`StudySpec.runs`), one
simulation each, which :func:`tyrelab.study.keys.run_key` names by everything
that decides its result.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..resources import model_cost
from ..rig.registry import rig_named
from .keys import relaxation_in_effect, run_key, tyre_digest


@dataclass(frozen=True)
class TyreSpec:
    """A tyre of the study.

    Attributes
    ----------
    name : str
        Label.
    file : str
        The built-in tyre's name (as :data:`tyrelab.tyre.library` spells it)
        or the absolute path of a ``.tir`` file.
    pressure : float or None
        Inflation pressure [Pa] of a built-in tyre, or of an MF-Tyre 6.x file with pressure
        terms (None: its default, or the file's own).
    builtin : bool
        Whether ``file`` names a built-in tyre.
    """

    name: str
    file: str
    pressure: float | None = None
    builtin: bool = True


@dataclass(frozen=True)
class ModelSpec:
    """A model variant: contact model, vertical stiffness and handling model (None: default),
    the contact model's options, ``(name, value)`` pairs sorted by name, and the transient
    slip of the handling forces (:attr:`tyrelab.tyre.model.TyreModel.relaxation`)."""

    name: str
    contact: str
    stiffness: str | None = None
    handling: str | None = None
    options: tuple = ()
    relaxation: str | tuple = "auto"


@dataclass(frozen=True)
class ReferenceFile:
    """A measured reference file for one condition of a test (``speed`` [m/s])."""

    path: Path
    speed: float
    load: str | float
    column_map: Path | None = None  # a CSV's column map (tyrelab.measure.read_mapped_csv)


@dataclass(frozen=True)
class TestSpec:
    """One ``[[test]]``: an obstacle or track driven at several speeds and loads.

    ``road`` is what :func:`tyrelab.simulate` takes (a ``.crg`` path made
    absolute); ``speeds`` [m/s]; ``loads`` load-case names or wheel loads
    [N]; ``duration`` [s] or None (the rig's default); the reference is
    ``reference_model`` (a model label) or ``reference_files`` or neither.
    """

    __test__ = False  # not a pytest class

    name: str
    group: str
    road: str
    speeds: tuple[float, ...]
    loads: tuple[str | float, ...]
    rig: str = "trailer"
    duration: float | None = None
    reference_model: str | None = None
    reference_files: tuple[ReferenceFile, ...] = ()
    models: tuple[str, ...] = ()
    terrain: str | None = None
    slips: tuple[float, ...] = ()
    #: driving torques [N m] instead of slips: the wheel spins freely under each
    torques: tuple[float, ...] = ()

    @property
    def speeds_kmh(self) -> tuple[float, ...]:
        return tuple(v * 3.6 for v in self.speeds)

    @property
    def is_soil_test(self) -> bool:
        """A slip curve on soil (drawbar pull, torque and sinkage against slip; the
        single-wheel tester at prescribed slips or driving torques), evaluated by
        :mod:`tyrelab.study.soil`, not chapter 5."""
        return bool(self.slips or self.torques)

    def drives(self) -> tuple[tuple[float | None, float | None], ...]:
        """``(slip, torque)`` of each run of a condition: the slips, the torques, or one
        ``(None, None)`` (a rigid-road test)."""
        if self.slips:
            return tuple((s, None) for s in self.slips)
        if self.torques:
            return tuple((None, t) for t in self.torques)
        return ((None, None),)


@dataclass(frozen=True)
class RunSpec:
    """One simulation: everything :func:`tyrelab.simulate` needs, plus its labels.

    ``speed`` [m/s], ``load`` a load-case name or a wheel load [N],
    ``duration`` [s] or None, ``dt`` [s], ``output_rate`` [Hz]; ``terrain`` the
    deformable ground (None: the rigid road) and ``slip`` the prescribed slip of a
    soil test's run (None: the rig's own, free rolling), or ``torque`` [N m] the driving
    torque it spins freely under instead.
    """

    tyre: TyreSpec
    model: ModelSpec
    test: str
    group: str
    road: str
    speed: float
    load: str | float
    rig: str
    duration: float | None
    dt: float
    output_rate: float
    left_wheel: str | None = None
    terrain: str | None = None
    slip: float | None = None
    torque: float | None = None

    @property
    def speed_kmh(self) -> float:
        return self.speed * 3.6

    @property
    def is_soil_run(self) -> bool:
        """A run of a soil test: at a prescribed slip or driving torque."""
        return self.slip is not None or self.torque is not None

    @property
    def drive(self) -> tuple[float | None, float | None]:
        """``(slip, torque)``, as :meth:`TestSpec.drives` gives them."""
        return self.slip, self.torque

    @property
    def left_contact(self) -> str | None:
        """The other wheel's contact model of a two-wheel rig (the trailer's left) when it
        differs from the test wheel's (None: the same model, or a rig with one wheel)."""
        if rig_named(self.rig).wheels < 2 or self.left_wheel in (None, self.model.contact):
            return None
        return self.left_wheel

    def simulate_kwargs(self) -> dict:
        """Keyword arguments of :func:`tyrelab.simulate` for this run."""
        drive = {k: v for k, v in (("slip", self.slip), ("torque", self.torque)) if v is not None}
        return {"tyre": self.tyre.file, "model": self.model.contact, "road": self.road,
                "speed": self.speed, "load": self.load, "pressure": self.tyre.pressure,
                "stiffness": self.model.stiffness, "handling": self.model.handling,
                "rig": self.rig, "duration": self.duration, "dt": self.dt,
                "output_rate": self.output_rate, "left_wheel": self.left_contact,
                "options": dict(self.model.options) or None,
                # only when set: the keyword arguments of a rigid-road run stay as they were
                **({"terrain": self.terrain} if self.terrain is not None else {}),
                **({"relaxation": self.model.relaxation} if self.model.relaxation != "auto"
                   else {}),
                **({"rig_options": drive} if drive else {})}


@dataclass(frozen=True)
class StudySpec:
    """A parsed, validated study (SI units).

    ``output`` is an absolute folder; ``limits`` ``{group: {metric: limit}}``
    (defaults filled in); ``source`` the spec file.
    """

    name: str
    output: Path
    dt: float
    output_rate: float
    tyres: tuple[TyreSpec, ...]
    models: tuple[ModelSpec, ...]
    tests: tuple[TestSpec, ...]
    limits: dict = field(hash=False)
    source: Path | str = "<string>"
    left_wheel: str | None = None
    #: the spec's text and the folder its relative paths start from (kept with the results)
    text: str = field(default="", repr=False, compare=False)
    base: Path | None = None
    #: how the store keeps each run's table (``[study] store``; tyrelab.study.store.STORAGE)
    store: str = "compact"

    def runs(self) -> tuple[RunSpec, ...]:
        """Every tyre x test x speed x load x model (x slip or torque, for a soil test), in that nesting
        (outermost first).

        Deterministic: the order of the spec's tables and lists. The runs of
        one condition (test, speed, load) are adjacent, the models in the
        test's order (:meth:`test_models`), each model's slips in the test's
        order; a reference model's runs appear once, as any model's.
        """
        out = []
        for tyre in self.tyres:
            for test in self.tests:
                for speed in test.speeds:
                    for load in test.loads:
                        for model in self.test_models(test):
                            for slip, torque in test.drives():
                                out.append(RunSpec(tyre, model, test.name, test.group, test.road, speed,
                                                   load, test.rig, test.duration, self.dt,
                                                   self.output_rate, self.left_wheel, test.terrain,
                                                   slip, torque))
        return tuple(out)

    def test_models(self, test: TestSpec) -> tuple[ModelSpec, ...]:
        """The model variants ``test`` runs: those its ``models`` lists, in that order, or
        every model of the spec in the spec's order."""
        return tuple(self.model(name) for name in test.models) if test.models else self.models

    def model(self, name: str) -> ModelSpec:
        """The model variant labelled ``name``."""
        for m in self.models:
            if m.name == name:
                return m
        raise KeyError(name)

    def test_of(self, run: RunSpec) -> TestSpec:
        """The ``[[test]]`` table ``run`` comes from."""
        for test in self.tests:
            if (test.name == run.test and run.speed in test.speeds and run.load in test.loads
                    and run.drive in test.drives()):
                return test
        raise KeyError(run.test)

    def reference_run(self, run: RunSpec) -> RunSpec | None:
        """The run ``run`` is compared with when its test's reference is a model.

        None when the test has no model reference, or ``run`` is a run of
        the reference model itself.
        """
        test = self.test_of(run)
        if test.reference_model is None or test.reference_model == run.model.name:
            return None
        return RunSpec(run.tyre, self.model(test.reference_model), run.test, run.group, run.road,
                       run.speed, run.load, run.rig, run.duration, run.dt, run.output_rate,
                       run.left_wheel, run.terrain, run.slip, run.torque)

    def reference_files(self, run: RunSpec) -> tuple[Path, ...]:
        """The measured files ``run`` is compared with (repeats of its condition); () if none."""
        test = self.test_of(run)
        return tuple(f.path for f in test.reference_files
                     if f.speed == run.speed and f.load == run.load)

    def column_map(self, path: Path) -> Path | None:
        """The column map of the measured reference file ``path`` (None: TYDEX, or a file
        tyrelab wrote)."""
        for test in self.tests:
            for f in test.reference_files:
                if f.path == path:
                    return f.column_map
        return None

    def run_keys(self) -> dict[RunSpec, str]:
        """:func:`run_key` of every run (each tyre's digest and each tyre and model's transient
        slip found once)."""
        digests = {tyre: tyre_digest(tyre) for tyre in self.tyres}
        lags = {(tyre, model): relaxation_in_effect(tyre, model)
                for tyre in self.tyres for model in self.models}
        return {run: run_key(run, digests[run.tyre], lags[run.tyre, run.model])
                for run in self.runs()}


#: length assumed for a road run to its end (the thesis tracks are 100 m)
_TRACK_LENGTH = 100.0


def expected_cost(run: RunSpec) -> float:
    """A rough estimate of a run's wall time [s]: simulated time x the model's cost."""
    simulated = run.duration if run.duration is not None else _TRACK_LENGTH / run.speed
    # the model's cost per simulated second (the registry's, resources.model_cost) orders the runs
    from ..tyre.registry import contact_model
    return simulated * model_cost(contact_model(run.model.contact))


def kernel_kind(run: RunSpec) -> str:
    """What compiled code a run needs, as a label: runs with equal labels share their kernels
    (the rig's loop over the tyre's contact and handling models, the left wheel's and the
    ground's types). Road, speed, load and pressure are values, not types: they share code.

    A contact or handling model is named by its parameter record, the type the compiled code
    is chosen by (:class:`tyrelab.tyre.registry.ContactModel`), not by its name: the ring and
    the ring with its tread pattern are one ring kernel, the enveloping model and its edge
    variant one enveloping kernel. Labelled by name, a fresh install's campaign started a ring
    and a ring-tp run at once, and the second worker sat on the ring's compile lock for about
    30 s instead of compiling and running the other models (:class:`KernelWaves
    <tyrelab.study.runner.KernelWaves>`). Two labels for the same code only cost such a wait or
    a second compile, never a wrong result."""
    from ..tyre.registry import contact_model, handling_model

    def record(model):  # by module too: two plugins may both call theirs "Params"
        return None if model is None else f"{model.record.__module__}.{model.record.__qualname__}"

    handling = run.model.handling
    return "|".join(str(part) for part in (
        run.tyre.file, record(contact_model(run.model.contact)),
        record(None if handling is None else handling_model(handling)), run.rig,
        record(None if run.left_contact is None else contact_model(run.left_contact)),
        run.terrain))
