"""What a cycle needs that does not change between runs: the scene, the models, the humanoid
(:class:`CycleContext`, :func:`prepare`), and the humanoid of a run's operator
(:func:`operator_context`). Metres, seconds."""

from __future__ import annotations

import copy
import hashlib
import pickle
from dataclasses import dataclass, field, replace
from pathlib import Path

import mujoco

from mjwalk.arms.reach import load_endpoint_model
from mjwalk.arms.reachdefault import default_reach_model
from mjwalk.body.humanoid import JointMap, attach_humanoid
from mjwalk.cycle.levelsite import ground_height, spec_on_levels
from mjwalk.cycle.memo import Memo, ScratchData
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.standing import StandZone, StandZones
from mjwalk.cycle.standoff import ArmClearance
from mjwalk.cycle.stepup import step_up_of
from mjwalk.cycle.types import TASK_KINDS, CycleSpec
from mjwalk.errors import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.gait.model import StepModel
from mjwalk.gait.walker import REFERENCE_CADENCE, Walker
from mjwalk.plan.grid import plan_grid
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.levelgrid import level_grid_route
from mjwalk.plan.occupancy import OccupancyGrid, occupancy_grid
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.params import goal_discs
from mjwalk.plan.walkpath import WalkPath
from mjwalk.world.workplace import Workplace, shared_workplace

#: The goal area (m) of a planner built without a stand zone (:meth:`CycleContext.planner`);
#: a cycle's walks end in their stand zones (:mod:`mjwalk.cycle.standing`).
GOAL_TOLERANCE = 0.1
#: Planners and stand zones a context keeps (the oldest go first). Both depend on the run's
#: operator (stature and step length), so every run of a population adds its own, about 1.6 MB
#: per station cycle: the bound keeps a worker's memory flat (joblib restarts a worker whose
#: memory keeps growing). A run uses one per walk (seven at the station).
KEPT_PER_CONTEXT = 64


class Planners:
    """The hybrid-A* planners of a cycle's walks, kept by the key (goal site, stand zone), at
    most :data:`KEPT_PER_CONTEXT` of them (:meth:`get`).

    Args:
        workplace: the scene.
        step_model: the step model every planner walks with.
        radius: the cycle's body radius (m).
    """

    def __init__(self, workplace: Workplace, step_model: StepModel, radius: float):
        self._workplace, self._step_model, self._radius = workplace, step_model, radius
        self._memo: Memo[tuple[str, StandZone | None], HybridPlanner] = Memo(
            self._make, KEPT_PER_CONTEXT
        )
        # the planners without a zone, one per goal: what every zone's planner of the goal
        # shares (grids, distance field, kernel vectors: for_goal_area)
        self._sites: Memo[str, HybridPlanner] = Memo(self._make_site, KEPT_PER_CONTEXT)

    def get(self, goal: str, zone: StandZone | None = None) -> HybridPlanner:
        """The planner of walks to site ``goal`` ending in ``zone`` (made on first use, kept by the
        key (goal, zone)).

        Args:
            goal: the goal site's name.
            zone: the stand zone the walk ends in; None: within :data:`GOAL_TOLERANCE` of the site.

        Returns:
            The :class:`~mjwalk.plan.hybrid.HybridPlanner`.
        """
        return self._memo.get((goal, zone))

    def _make(self, key: tuple[str, StandZone | None]) -> HybridPlanner:
        goal, zone = key
        site = self._sites.get(goal)
        return site if zone is None else for_goal_area(site, zone.radius, zone.discs)

    def _make_site(self, goal: str) -> HybridPlanner:
        options = PlannerOptions(
            radius=self._radius,
            goal_tolerance=GOAL_TOLERANCE,
            # one distance field per site whatever the operator's zone
            field_tolerance=GOAL_TOLERANCE,
        )
        return HybridPlanner(self._workplace, goal, self._step_model, options)


def for_goal_area(planner: HybridPlanner, tolerance: float, within) -> HybridPlanner:
    """``planner`` with another goal area: within ``tolerance`` (m) of its goal and inside
    the discs ``within`` ((x, y, radius), metres), the planner that ``HybridPlanner(workplace,
    goal, model, options)`` would build with those two options changed, sharing ``planner``'s
    grids, distance field (its ``field_tolerance`` is the same), clearance field and kernel
    vectors (:meth:`~mjwalk.plan.params.KernelParams.for_goal_area`). A stand zone changes
    with every operator: building each zone's planner anew cost about 1 ms a station cycle,
    and its kernel vectors were made again for every one.

    Args:
        planner: a planner of the goal.
        tolerance: the goal area's radius (m).
        within: the goal area's discs ((x, y, radius), metres).

    Returns:
        The goal area's :class:`~mjwalk.plan.hybrid.HybridPlanner`.

    Raises:
        PlanningError: the goal outside one of the discs.
    """
    out = copy.copy(planner)
    out.options = replace(planner.options, goal_tolerance=tolerance, goal_within=within)
    out.goal_within = goal_discs(out.options, planner.goal)
    out.params = planner.params.for_goal_area(out.options, out.goal_within)
    return out


class GridRoutes:
    """The grid-A* routes (:func:`~mjwalk.plan.grid.plan_grid`) of a scene at the cycle's body
    radius: the occupancy grid (built on first use) and the route lengths between sites, kept
    by the key (site, site).

    Args:
        workplace: the scene.
        radius: the cycle's body radius (m).
    """

    def __init__(self, workplace: Workplace, radius: float):
        self._workplace, self._radius = workplace, radius
        self._grid: Memo[None, OccupancyGrid] = Memo(
            lambda _: occupancy_grid(workplace, radius=radius)
        )
        self._lengths: Memo[tuple[str, str], float] = Memo(
            lambda ab: plan_grid(workplace, ab[0], ab[1], radius=radius, grid=self.grid()).length
        )

    def grid(self) -> OccupancyGrid:
        """The occupancy grid of the scene at the body radius (built once).

        Returns:
            The :class:`~mjwalk.plan.occupancy.OccupancyGrid`.
        """
        return self._grid.get(None)

    def length(self, a: str, b: str) -> float:
        """Metres of the grid-A* route from site ``a`` to site ``b`` (kept per pair).

        Args:
            a: the start site's name.
            b: the goal site's name.

        Returns:
            The route's length (m).
        """
        return self._lengths.get((a, b))

    def over_levels(
        self, path: WalkPath, walker: Walker, max_riser: float | None
    ) -> WalkPath | None:
        """The grid-A* route over levels (:func:`~mjwalk.plan.levelgrid.level_grid_route`)
        between a walk over levels' own ends, at the heights it stands at (not kept).

        Args:
            path: the walk (its ``z``: the surface heights above the floor).
            walker: the operator (the route over levels is theirs).
            max_riser: the operator's step-up limit, metres (None: the default limit).

        Returns:
            The route, or None when there is none.
        """
        assert path.z is not None  # a walk over levels
        a, b = ((*path.xy[k], self._workplace.floor_z + path.z[k]) for k in (0, -1))
        try:
            return level_grid_route(
                self._workplace, a, b, walker=walker, max_riser=max_riser, radius=self._radius
            )
        except PlanningError:
            return None

    def route(self, start, end) -> WalkPath | None:
        """The grid-A* route between two points, a walk's own ends (not kept).

        Args:
            start: (x, y) world frame, metres.
            end: (x, y) world frame, metres.

        Returns:
            The route, or None when the grid planner finds none (an end nearer an obstacle than
            the radius, or no grid route between them).
        """
        try:
            return plan_grid(self._workplace, start, end, radius=self._radius, grid=self.grid())
        except PlanningError:
            return None


@dataclass(frozen=True)
class CycleContext:
    """Everything a cycle needs that does not change between runs (built once per process):
    the cycle, its scene and models, the humanoid (a frozen record), and the caches its walks
    fill (:class:`Planners`, :class:`~mjwalk.cycle.standing.StandZones`, :class:`GridRoutes`:
    held, never replaced, shared by the operators' contexts of :func:`operator_context`).

    Args:
        spec: the cycle.
        workplace: its scene.
        step_model: the step model of the cycle's humanoid.
        reach_model: the left arm's reach model.
        model: the scene with the humanoid attached.
        jointmap: the humanoid's joint map.
        clearance: the reach's clearance check of ``model``
            (:class:`~mjwalk.cycle.standoff.ArmClearance`).
        planners: the walks' planners.
        zones: the walks' stand zones.
        routes: the grid-A* routes.
        turn_rate: the operator's turning speed on the spot over the reference adult's.
        reach_model_right: the right arm's reach model (``[models] reach_right``), None:
            ``reach_model`` mirrored.
        on_levels: whether a standing site of the cycle stands on a raised level (a platform,
            a mezzanine: :func:`~mjwalk.cycle.levelsite.spec_on_levels`); False for every
            cycle of a flat scene, which then never builds the scene's levels.
    """

    spec: CycleSpec
    workplace: Workplace
    step_model: StepModel
    reach_model: object
    model: mujoco.MjModel
    jointmap: JointMap
    clearance: ArmClearance
    planners: Planners
    zones: StandZones
    routes: GridRoutes
    turn_rate: float = 1.0
    reach_model_right: object | None = None
    on_levels: bool = False
    # the scratch MjData of ``model`` (set with the context, never replaced; not copied by
    # dataclasses.replace: an operator's context may have its own humanoid model): one per
    # model layout and thread (:func:`_scratch_of`), shared by the contexts of those models
    _data: mujoco.MjData = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_data", _scratch_of(self.model))

    def reach_model_for(self, side: str):
        """The reach model of the ``side`` arm: both are left-arm-frame models, a right arm's reach
        mirrors the one it gets (:func:`~mjwalk.arms.reach.reach_for_side`).

        Args:
            side: "left" or "right".

        Returns:
            ``reach_model_right`` for the right arm when the spec gives one, else ``reach_model``.
        """
        if side == "right" and self.reach_model_right is not None:
            return self.reach_model_right
        return self.reach_model

    def scratch(self) -> mujoco.MjData:
        """An MjData for ``model``'s forward kinematics in this context (made for a model of its
        sizes, :func:`_scratch_of`; every user sets the whole qpos before each use and passes
        ``model`` to MuJoCo).

        Returns:
            The context's scratch :class:`mujoco.MjData`.
        """
        return self._data

    def planner(self, goal: str, zone: StandZone | None = None) -> HybridPlanner:
        """The planner of walks to ``goal``, ending in ``zone`` (:mod:`mjwalk.cycle.standing`). One
        per goal and zone (:class:`Planners`).

        Args:
            goal: the goal site's name.
            zone: the stand zone; None: within :data:`GOAL_TOLERANCE` of the site.

        Returns:
            The :class:`~mjwalk.plan.hybrid.HybridPlanner`.
        """
        return self.planners.get(goal, zone)

    def zone(self, i: int, stature: float, step_length: float) -> StandZone:
        """The stand zone of the walk that is task ``i`` (:func:`~mjwalk.cycle.standing.work_zone`),
        kept per operator size.

        Args:
            i: the walk's index in ``spec.tasks``.
            stature: the operator's stature (m).
            step_length: the operator's step length (m).

        Returns:
            The :class:`~mjwalk.cycle.standing.StandZone`.
        """
        return self.zones.get(i, stature, step_length)

    def baseline(self, a: str, b: str) -> float:
        """Metres of the grid-A* route from site ``a`` to site ``b`` (kept per pair).

        Args:
            a: the start site's name.
            b: the goal site's name.

        Returns:
            The route's length (m).
        """
        return self.routes.length(a, b)

    def baseline_route(self, start, end) -> WalkPath | None:
        """The grid-A* route (:func:`~mjwalk.plan.grid.plan_grid`, the cycle's body radius) between
        two points (:meth:`GridRoutes.route`).

        Args:
            start: (x, y) world frame, metres.
            end: (x, y) world frame, metres.

        Returns:
            The route, or None when there is none.
        """
        return self.routes.route(start, end)

    def baseline_over_levels(self, path: WalkPath, walker: Walker | None) -> WalkPath | None:
        """The grid-A* route over levels between a walk's own ends, for the operator (their
        group's step-up limit, :func:`~mjwalk.cycle.stepup.step_up_of`), :meth:`GridRoutes.
        over_levels`.

        Args:
            path: the walk (with ``z``).
            walker: the operator (None: the cycle's reference adult).

        Returns:
            The route, or None when there is none.
        """
        limit = step_up_of(self.spec.population, walker)
        who = Walker(stature=self.spec.stature) if walker is None else walker
        return self.routes.over_levels(path, who, limit)

    def ground(self, xy) -> float:
        """The world height of the walk surface under a standing operator: the floor's
        (``Workplace.floor_z``) plus the surface's height above it
        (:func:`~mjwalk.cycle.levelsite.ground_height`; the floor's alone in a flat cycle).

        Args:
            xy: (x, y) world, metres.

        Returns:
            World z, metres.
        """
        return self.workplace.floor_z + ground_height(self.workplace, xy, self.on_levels)

    def occupancy(self) -> OccupancyGrid:
        """The grid A*'s occupancy grid of the scene at the cycle's body radius (built once).

        Returns:
            The :class:`~mjwalk.plan.occupancy.OccupancyGrid`.
        """
        return self.routes.grid()


#: Scratch MjData kept per thread: as many model layouts as the humanoid cache holds models
#: (:data:`HUMANOIDS`' limit), the one kept longest dropped first. What a run computes does not
#: depend on which MjData it gets (its users set the qpos and compute the kinematics they read;
#: tests/cycle/test_memo.py runs a cycle in a fresh and in a used one).
SCRATCH = ScratchData(64)


def _scratch_of(model: mujoco.MjModel) -> mujoco.MjData:
    """The scratch MjData of ``model`` for this thread (:data:`SCRATCH`): the humanoids of every
    stature in one scene have the same sizes (:func:`~mjwalk.cycle.memo.data_layout`), so the
    operators' contexts share one. A run makes a context for its operator
    (:func:`operator_context`); making its MjData cost about 0.8 ms a run (the station's
    humanoid: a 17.8 MB arena), and its first contacts touched the arena's pages anew."""
    return SCRATCH.of(model)


def _load_step_model(spec: CycleSpec) -> StepModel:
    if spec.step_model == "default":
        return default_model()
    return StepModel.load(spec.step_model)


def _load_reach_model(path: str):
    if path == "default":
        return default_reach_model()
    # the spec checked this file when it was loaded: the same object comes back
    return load_endpoint_model(path, f"reach model {path}")


@dataclass(frozen=True)
class _PickledSpec:
    """An in-memory spec as a memo key: equal by the digest of its pickle (a CycleSpec holds
    lists, so it is not hashable itself), carrying the spec to prepare."""

    digest: str
    spec: CycleSpec = field(compare=False)


class SpecContexts:
    """The prepared contexts (:func:`prepare`) of this process, the last ``limit`` of each kind
    of key: a spec file by its path as given (``str(path)``, read with
    :func:`~mjwalk.cycle.spec.load_cycle_spec`), an in-memory :class:`CycleSpec` by the SHA-1
    digest of its pickle (so an edited copy is a new key). A joblib worker prepares each spec
    once and reuses it for every run it is given.

    Safe across runs: a context is made from its spec alone, is frozen, and what it keeps
    (planners, stand zones, grid routes: :class:`CycleContext`) are values of their own keys,
    so a run finds the same context whichever runs came before it.

    Args:
        limit: how many contexts of each kind of key are kept (the oldest go first).
    """

    def __init__(self, limit: int):
        self._files: Memo[str, CycleContext] = Memo(
            lambda path: prepare(load_cycle_spec(path)), limit
        )
        self._specs: Memo[_PickledSpec, CycleContext] = Memo(lambda key: prepare(key.spec), limit)

    def get(self, spec: CycleSpec | str | Path) -> CycleContext:
        """The context of ``spec`` (prepared now when it is not kept).

        Args:
            spec: a spec file's path, or a :class:`CycleSpec` used as it is in memory.

        Returns:
            The kept (or newly prepared) :class:`CycleContext`.
        """
        if not isinstance(spec, CycleSpec):
            return self._files.get(str(spec))
        return self._specs.get(_PickledSpec(hashlib.sha1(pickle.dumps(spec)).hexdigest(), spec))


class Humanoids:
    """The humanoids of this process's operators, by the key (scene path as a string, stature in
    metres rounded to the millimetre): the scene with the humanoid attached
    (:func:`~mjwalk.body.humanoid.attach_humanoid`) and its reach clearance check
    (:class:`~mjwalk.cycle.standoff.ArmClearance`), the last ``limit`` of each. A population's
    statures come in centimetres and attaching one takes about 15 ms, so a worker builds each
    stature once.

    Safe across runs: a value depends on its key alone (the scene file and the stature), and
    callers share the models read-only (every user of a model's MjData sets the whole qpos
    before each use), so a run gets the same humanoid whichever runs came before it.

    Args:
        limit: how many humanoids (and clearance checks) are kept (the oldest go first).
    """

    def __init__(self, limit: int):
        self._models: Memo[tuple[str, float], tuple[mujoco.MjModel, JointMap]] = Memo(
            self._attach, limit
        )
        # each scene's file parsed once (attach_humanoid copies it, never changes it): parsing
        # the station's XML again was about 0.5 ms of each new stature's 6 ms
        self._scenes: Memo[str, mujoco.MjSpec | None] = Memo(_parsed_scene, SCENES_KEPT)
        self._clearances: Memo[tuple[str, float], ArmClearance] = Memo(
            lambda key: ArmClearance(*self._models.get(key)), limit
        )

    def _attach(self, key: tuple[str, float]) -> tuple[mujoco.MjModel, JointMap]:
        """The humanoid of ``key`` (scene, stature) attached to the parsed scene (the same model
        as attaching it to the file: the same bytes, ``tests/cycle/test_context.py``); a file
        that does not parse is given to :func:`~mjwalk.body.humanoid.attach_humanoid` by its
        path, which reports it."""
        scene, stature = key
        parsed = self._scenes.get(scene)
        return attach_humanoid(Path(scene) if parsed is None else parsed, stature)

    def model(self, scene: str, stature: float) -> tuple[mujoco.MjModel, JointMap]:
        """The scene with a humanoid of ``stature`` attached.

        Args:
            scene: the scene's MJCF path, as a string.
            stature: the humanoid's stature (m), rounded to the millimetre by the caller.

        Returns:
            (model, joint map) of the scene with the humanoid.
        """
        return self._models.get((scene, stature))

    def clearance(self, scene: str, stature: float) -> ArmClearance:
        """The reach's clearance check of the humanoid of :meth:`model`.

        Args:
            scene: the scene's MJCF path, as a string.
            stature: the humanoid's stature (m), rounded to the millimetre by the caller.

        Returns:
            The :class:`~mjwalk.cycle.standoff.ArmClearance` of that humanoid in the scene.
        """
        return self._clearances.get((scene, stature))


#: Parsed scene files :class:`Humanoids` keeps (a process runs one or a few scenes).
SCENES_KEPT = 4


def _parsed_scene(path: str) -> mujoco.MjSpec | None:
    """The scene file ``path`` parsed (read-only for its users), or None when MuJoCo cannot
    parse it (:func:`~mjwalk.body.humanoid.attach_humanoid` then reports the file)."""
    try:
        return mujoco.MjSpec.from_file(path)
    except Exception:  # mujoco raises ValueError with the XML parser's message
        return None


#: The contexts of the specs this process ran (:func:`context_of`), the last 4 of each kind.
SPEC_CONTEXTS = SpecContexts(limit=4)
#: The operators' humanoids of this process (:func:`operator_context`), the last 64 statures: a
#: population's statures in centimetres span some 25-50 values (60 station runs of the shipped
#: population drew 25; with 16 kept, 34 humanoids were built, each about 15 ms), so a worker
#: builds each once. About 1.9 MB each with its clearance check (measured), at most 125 MB.
HUMANOIDS = Humanoids(limit=64)


def context_of(spec: CycleSpec | str | Path) -> CycleContext:
    """The context of ``spec`` for a worker (prepared once per process and spec:
    :data:`SPEC_CONTEXTS`).

    A path is read with :func:`~mjwalk.cycle.spec.load_cycle_spec`; a :class:`CycleSpec` is used
    as it is, so a spec edited in memory (``dataclasses.replace(spec, reach_model=...)``) runs
    with its edits, not with the file it was read from.

    Args:
        spec: a spec file's path, or a :class:`CycleSpec`.

    Returns:
        The spec's :class:`CycleContext`.
    """
    return SPEC_CONTEXTS.get(spec)


def operator_context(ctx: CycleContext, walker: Walker | None) -> CycleContext:
    """``ctx`` for a run of ``walker``: the humanoid (and ``spec.stature``) of the walker's
    stature (:data:`HUMANOIDS`), and their turning speed (``turn_rate``: a turn on the spot is
    made of steps, so it goes at the walker's cadence over
    :data:`~mjwalk.gait.walker.REFERENCE_CADENCE`); planners, grid-A* baselines and models are
    shared with ``ctx``.

    Args:
        ctx: the cycle's context.
        walker: the run's operator; None: ``ctx`` itself.

    Returns:
        The operator's :class:`CycleContext`.
    """
    if walker is None:
        return ctx
    rate = walker.cadence / REFERENCE_CADENCE
    if abs(walker.stature - ctx.spec.stature) < 1e-9:
        return replace(ctx, turn_rate=rate)
    scene, stature = str(ctx.spec.scene), round(walker.stature, 3)
    model, jm = HUMANOIDS.model(scene, stature)
    return replace(
        ctx,
        spec=replace(ctx.spec, stature=walker.stature),
        model=model,
        jointmap=jm,
        clearance=HUMANOIDS.clearance(scene, stature),
        turn_rate=rate,
    )


def prepare(spec: CycleSpec) -> CycleContext:
    """Load the scene, the models and the humanoid of ``spec`` (reused by every run).

    Args:
        spec: the cycle.

    Returns:
        Its :class:`CycleContext`, with empty caches.
    """
    workplace = shared_workplace(spec.scene)
    model, jm = attach_humanoid(spec.scene, spec.stature)
    step_model = _load_step_model(spec)
    return CycleContext(
        spec=spec,
        workplace=workplace,
        step_model=step_model,
        reach_model=_load_reach_model(spec.reach_model),
        reach_model_right=(
            None if spec.reach_model_right is None else _load_reach_model(spec.reach_model_right)
        ),
        model=model,
        jointmap=jm,
        clearance=ArmClearance(model, jm),
        planners=Planners(workplace, step_model, spec.radius),
        zones=StandZones(spec, workplace, KEPT_PER_CONTEXT),
        routes=GridRoutes(workplace, spec.radius),
        on_levels=spec_on_levels(workplace, _standing_sites(spec)),
    )


def _standing_sites(spec: CycleSpec) -> list[str]:
    """The cycle's start site and every walk's goal site."""
    walks = [t.site for t in spec.tasks if TASK_KINDS[t.kind].motion == "walk" and t.site]
    return [spec.start, *walks]
