"""Run a merged plan in the simulator, robots concurrently, to validate it and time it.

Each robot runs its steps in order; a step starts once the steps it waits for (``after``)
have ended and its interaction spot is free (the simulator rejects a second robot at a
busy spot, so the scheduler waits instead, as the behavior trees do with their locks).
No faults: this checks the plan, not the robots. The result gives every step's start and
end (``est_start``/``est_end``), the makespan, the lower bound
``max(critical path, busiest robot's work)`` over the measured durations (it takes the
plan's own allocation and waits as given: a ratio near 1 says little about them), and the
*resource-aware* bound :func:`resource_bound`, which takes neither: any schedule of these
actions, by any robots, needs at least max(total work / robots, the longest subtask one
robot does, the busiest interaction spot's serial time with the least time before its
first use and after its last, the serial time on the busiest object, the work done into a
carried box after its put-down).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from emboteam.hp.carry_bound import carry_bound
from emboteam.hp.plan import MergedPlan, PlanStep
from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Skill
from emboteam.world.checker import check_goal
from emboteam.world.goals import Goal
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class ResourceBound:
    """A lower bound on the makespan of any schedule of a plan's actions (their measured
    durations), whoever does them and in whatever order. A *job* is one robot's steps for
    one subtask, done in their order. The components:

    - ``work``: every robot's work must be done by the team;
    - ``subtask``: a job's steps run one after another;
    - ``spot_window``: a spot (the fridge, the microwave) serves one robot at a time, and
      no job reaches it before the steps it does first or leaves after it the steps it
      does last: for any set of jobs using the spot, least head + their time at the spot
      + least tail (the one-machine relaxation of job-shop scheduling, which holds with
      interruptions too);
    - ``object``: an object is acted on by one robot at a time: the steps aimed at it and
      the steps of a robot holding it (carrying it, putting it, slicing with it) cannot
      overlap, since the simulator refuses acting on an object another robot holds and
      an object not held is reached from its spot, which one robot holds at a time; with
      heads and tails as for a spot (``object_window``);
    - ``carry``: work done into (or on) a receptacle at the place a robot carried it to
      cannot start before its put-down, which ends no earlier than the least drive to the
      receptacle plus the carry (:mod:`emboteam.hp.carry_bound`; only with the start state).
    """

    value: float = 0.0
    #: total work / robots
    work: float = 0.0
    #: the longest work one robot does for one subtask
    subtask: float = 0.0
    #: serial time at the busiest spot, and that spot
    spot: float = 0.0
    spot_name: str = ""
    #: the largest one-machine bound over the spots (>= ``spot``), and its spot
    spot_window: float = 0.0
    window_name: str = ""
    #: serial time on the busiest object, and that object
    object: float = 0.0
    object_name: str = ""
    #: the largest one-machine bound over the objects (>= ``object``), and its object
    object_window: float = 0.0
    object_window_name: str = ""
    #: the put-down of a carried receptacle, then the work at its new place, and that receptacle
    carry: float = 0.0
    carry_name: str = ""


def resource_bound(plan: MergedPlan, durations: dict[str, float], spots: dict[str, str],
                   holding: dict[str, str] | None = None, start: WorldState | None = None) -> ResourceBound:
    """:class:`ResourceBound` of ``plan``; ``spots`` maps the id of each step that holds an
    interaction spot (every step but GoToObject) to the spot it held; ``holding`` the id
    of each step to the object its robot held when it began (when not given: followed
    through the plan's pickups and puts, robots starting empty-handed); ``start``: the
    state the plan starts from, for the ``carry`` term (0 without it)."""
    if holding is None:
        holding = _holding(plan)
    total = 0.0
    jobs: dict[tuple[str, str], list[str]] = {}
    at: dict[str, float] = {}
    on: dict[str, float] = {}
    objects: dict[str, set[str]] = {}
    for s in plan.steps:
        d = durations.get(s.id, 0.0)
        total += d
        jobs.setdefault((s.subtask, s.robot), []).append(s.id)
        if s.id in spots:
            at[spots[s.id]] = at.get(spots[s.id], 0.0) + d
        mine = {s.action.target} if s.action.skill is not Skill.GoToObject else set()
        if s.id in holding:
            mine.add(holding[s.id])
        objects[s.id] = mine
        for o in mine:
            on[o] = on.get(o, 0.0) + d
    busiest = max(at, key=lambda k: (at[k], k), default="")
    work = total / max(len(plan.robots), 1)
    subtask = max((sum(durations.get(i, 0.0) for i in ids) for ids in jobs.values()), default=0.0)
    spot = at.get(busiest, 0.0)
    window, window_name = _window(jobs, durations, {i: {sp} for i, sp in spots.items()})
    obj = max(on, key=lambda k: (on[k], k), default="")
    obj_window, obj_window_name = _window(jobs, durations, objects)
    value = max(work, subtask, spot, window, on.get(obj, 0.0), obj_window)
    carry, carry_name = (0.0, "") if start is None else carry_bound(plan, durations, spots, start, value)
    return ResourceBound(max(value, carry), work, subtask, spot, busiest, window, window_name, on.get(obj, 0.0), obj,
                         obj_window, obj_window_name, carry, carry_name)


def _holding(plan: MergedPlan) -> dict[str, str]:
    out: dict[str, str] = {}
    hand: dict[str, str] = {}
    for s in plan.steps:
        if s.robot in hand:
            out[s.id] = hand[s.robot]
        if s.action.skill is Skill.PickupObject:
            hand[s.robot] = s.action.target
        elif s.action.skill in (Skill.PutObject, Skill.ThrowObject, Skill.DropHandObject):
            hand.pop(s.robot, None)
    return out


def _window(jobs: dict[tuple[str, str], list[str]], durations: dict[str, float],
            uses: dict[str, set[str]]) -> tuple[float, str]:
    """The one-machine bound over the machines of ``uses`` (step id -> the spots, or the
    objects, it occupies): for every machine, max over sets S of the jobs using it of
    min head + the time S spends on it + min tail, where a job's head (tail) is its
    steps before its first (after its last) step on the machine. The sets worth trying
    are "every job with head >= a and tail >= b" for a, b among the jobs' heads and
    tails: O(n^2 log n) per machine."""
    per: dict[str, list[tuple[float, float, float]]] = {}
    for ids in jobs.values():
        d = [durations.get(i, 0.0) for i in ids]
        mine: dict[str, list[int]] = {}
        for k, i in enumerate(ids):
            for m in uses.get(i, ()):
                mine.setdefault(m, []).append(k)
        for m, ks in mine.items():
            per.setdefault(m, []).append((sum(d[:ks[0]]), sum(d[k] for k in ks), sum(d[ks[-1] + 1:])))
    best, name = 0.0, ""
    for m in sorted(per):
        js = per[m]
        for b in sorted({q for _, _, q in js}):
            run = 0.0
            for r, p, _ in sorted((j for j in js if j[2] >= b), key=lambda j: -j[0]):
                run += p
                if r + run + b > best + 1e-9:
                    best, name = r + run + b, m
    return best, name


@dataclass
class Timing:
    ok: bool
    failure: str = ""
    #: id of the step that failed ("" when none did: a cycle, or the goal unmet at the end)
    failed_step: str = ""
    times: dict[str, tuple[float, float]] = field(default_factory=dict)
    makespan: float = 0.0
    lower_bound: float = 0.0
    resources: ResourceBound = field(default_factory=ResourceBound)
    final: WorldState | None = None
    unmet: tuple[str, ...] = ()


def lower_bound(plan: MergedPlan, durations: dict[str, float]) -> float:
    """max(longest path through robot orders and waits, busiest robot's total work)."""
    finish: dict[str, float] = {}
    last: dict[str, str] = {}
    work: dict[str, float] = {}
    for s in plan.steps:  # a topological order
        ready = max([finish[p] for p in s.after if p in finish] + [finish[last[s.robot]] if s.robot in last else 0.0])
        finish[s.id] = ready + durations.get(s.id, 0.0)
        last[s.robot] = s.id
        work[s.robot] = work.get(s.robot, 0.0) + durations.get(s.id, 0.0)
    return max([*finish.values(), *work.values(), 0.0])


@dataclass
class _Run:
    """One simulation in progress: each robot's queue and running step, and what each
    step found when it began (the spot it held, its robot's hand), which the bounds read."""

    sim: Simulator
    queues: dict[str, list[PlanStep]]
    ended: set[str] = field(default_factory=set)
    running: dict[str, PlanStep] = field(default_factory=dict)
    starts: dict[str, float] = field(default_factory=dict)
    held: dict[str, str] = field(default_factory=dict)
    holding: dict[str, str] = field(default_factory=dict)
    times: dict[str, tuple[float, float]] = field(default_factory=dict)
    #: the robots in name order (the order steps start in), sorted once: it is gone
    #: through at every event, hundreds of times a simulation of a 32-robot plan
    order: list[str] = field(init=False)

    def __post_init__(self) -> None:
        self.order = sorted(self.queues)

    def _next(self, robot: str) -> PlanStep | None:
        """The robot's next step if it may start now: robot idle, waits ended, and its
        spot not held by another robot (the scheduler waits, as the behavior trees do)."""
        queue = self.queues[robot]
        if robot in self.running or not queue:
            return None
        step = queue[0]
        if not all(p in self.ended for p in step.after):
            return None
        target = step.action.receptacle or step.action.target
        if step.action.skill is Skill.GoToObject or target not in self.sim.state.objects:
            return step
        holder = self.sim.locks.get(self.sim.state.spot_of(target))
        return None if holder is not None and holder != robot else step

    def start_ready(self) -> None:
        """Start every step that may start, robots in name order (a start may take a
        spot, so the order decides who gets it: fixed for the same plan)."""
        for robot in self.order:
            if robot in self.running:
                continue
            step = self._next(robot)
            if step is None:
                continue
            self.queues[robot].pop(0)
            self.running[robot] = step
            self.starts[step.id] = self.sim.now
            where = step.action.receptacle or step.action.target
            if step.action.skill is not Skill.GoToObject and where in self.sim.state.objects:
                self.held[step.id] = self.sim.state.spot_of(where)
            hand = self.sim.state.robots[robot].holding
            if hand is not None:
                self.holding[step.id] = hand
            self.sim.start(robot, step.action)

    def advance(self) -> Timing | None:
        """Run to the next event; the failed timing if a running step failed there."""
        t = self.sim.next_event_time()
        assert t is not None
        for outcome in self.sim.advance(t):
            if outcome.robot not in self.running:
                continue
            step = self.running.pop(outcome.robot)
            if not outcome.success:
                return Timing(ok=False, failure=f"{step.id} {outcome}", failed_step=step.id, times=self.times,
                              final=self.sim.state)
            self.ended.add(step.id)
            self.times[step.id] = (self.starts[step.id], outcome.end)
        return None


def _timing(plan: MergedPlan, run: _Run, start: WorldState) -> Timing:
    """The timing of a run that ended (from ``start``): failed if steps were left waiting,
    else the makespan and both lower bounds over the measured durations."""
    left = [s.id for q in run.queues.values() for s in q]
    if left:
        return Timing(ok=False, failure=f"steps {', '.join(left[:5])} never became ready (their waits "
                      "form a cycle or name unknown steps)", times=run.times, final=run.sim.state)
    times = run.times
    makespan = max((e for _, e in times.values()), default=0.0)
    durations = {k: e - s for k, (s, e) in times.items()}
    return Timing(ok=True, times=times, makespan=makespan, lower_bound=lower_bound(plan, durations),
                  resources=resource_bound(plan, durations, run.held, run.holding, start), final=run.sim.state)


def simulate(plan: MergedPlan, state: WorldState, goal: Goal | None = None, *,
             sim: Simulator | None = None) -> Timing:
    """Execute ``plan`` from ``state`` (not modified). ``ok`` when every step succeeds and
    ``goal`` (if given) holds at the end. ``sim``: run in this simulator (made from
    ``state``; e.g. one with avoidance, whose paths the caller reads) instead of a new one."""
    sim = sim or Simulator(load_scene(state.floor_plan), [], state=state)
    queues: dict[str, list[PlanStep]] = {r: plan.for_robot(r) for r in plan.robots}
    for s in plan.steps:
        queues.setdefault(s.robot, [])
    run = _Run(sim, queues)
    while True:
        run.start_ready()
        if not run.running:
            break
        failed = run.advance()
        if failed is not None:
            return failed
    timing = _timing(plan, run, state)
    if timing.ok and goal is not None:
        report = check_goal(goal, sim.state)
        if not report.success:
            timing.ok = False
            timing.unmet = tuple(str(c) for c in report.unmet())
            timing.failure = "the goal does not hold at the end: " + ", ".join(timing.unmet)
    return timing


def with_times(plan: MergedPlan, timing: Timing) -> MergedPlan:
    steps = tuple(s.model_copy(update={"est_start": round(timing.times[s.id][0], 3),
                                       "est_end": round(timing.times[s.id][1], 3)})
                  if s.id in timing.times else s for s in plan.steps)
    return plan.model_copy(update={"steps": steps, "makespan": round(timing.makespan, 3),
                                   "lower_bound": round(timing.lower_bound, 3),
                                   "resource_bound": round(timing.resources.value, 3)})


def estimate(plan: MergedPlan, seconds: dict[str, float]) -> MergedPlan:
    """Times from nominal durations without simulating (for unvalidated plans): each
    step starts when its robot and its waits are done."""
    finish: dict[str, float] = {}
    last: dict[str, str] = {}
    steps = []
    for s in plan.steps:
        start = max([finish[p] for p in s.after if p in finish] + [finish[last[s.robot]] if s.robot in last else 0.0])
        finish[s.id] = start + seconds.get(s.id, 0.0)
        last[s.robot] = s.id
        steps.append(s.model_copy(update={"est_start": round(start, 3), "est_end": round(finish[s.id], 3)}))
    makespan = max(finish.values(), default=0.0)
    return plan.model_copy(update={"steps": tuple(steps), "makespan": round(makespan, 3),
                                   "lower_bound": round(lower_bound(plan, seconds), 3)})
