"""Fit the offline ranker's priors on the development rounds, write them, report.

Development data only: ``tests/data/blind_r*/dev`` (SMART-LLM format), the development
jsonl sets (``tests/data/offline_dev*.jsonl``) and any ``--extra DIR`` of development
rounds. Never the held-out halves, the held-out round or ``tests/data/unseen_tasks.json``.

For every task the reader's own reading and its points of doubt are computed once; a
doubt's alternative is *right* when it brings the goal closer to the ground truth (more
of its conditions right, fewer wrong, under the equivalences of
:mod:`emboteam.bench.offline_accuracy`) and no other alternative of the doubt does better;
``as_read`` is right when none improves. A prior is (right + 0.5) / (offered + 1).
An alternative whose prior would put it above the reading as read (so that it changes
the reader's first candidate) is kept only if no round's top-1 gets worse; else it is
capped below ``as_read``.

Reports per round: tasks, today's accuracy (the reading as read), top-1 and candidate
recall with the fitted priors, and the share of tasks with an unexplained mention.

    PYTHONPATH=src .venv/bin/python benchmarks/fit_reading_priors.py            # fit, write, report
    PYTHONPATH=src .venv/bin/python benchmarks/fit_reading_priors.py --check    # report with the shipped file
    ... --json   # one JSON object
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter, defaultdict
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.bench.offline_accuracy import goal_keys, initial_state, load_records
from emboteam.errors import EmboTeamError
from emboteam.pfg.candidates import AS_READ, Candidate, Doubt
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.check import feasible
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.coverage import Coverage
from emboteam.pfg.offline.doubts.priors import PRIORS_FILE, Priors, load_priors
from emboteam.pfg.offline.tagger import tag
from emboteam.pfg.ranker import apply_choices, rank
from emboteam.pfg.taskspec import TaskSpec
from emboteam.task import BenchTask
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition
from emboteam.world.robots import RobotProfile, parse_team
from emboteam.world.scene import Scene, load_scene
from emboteam.world.state import WorldState

DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
#: rounds from this one on are held out (r42) or being written (r43, r44): never read here
FIRST_HELD_OUT = 42
#: the coverage weights tried (doubts/coverage.py): of those with no round's top-1 below
#: the reading as read (the priors' own guard), the one with the best top-1 over all
#: development tasks is kept, the smallest on a tie
COVERAGE_WEIGHTS = (0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 3.0)


@dataclass
class Case:
    round: str
    instruction: str
    scene: Scene
    state: WorldState
    team: tuple[RobotProfile, ...]
    truth: frozenset[tuple[object, ...]]
    spec: TaskSpec | None = None           # the reading as read
    doubts: tuple[Doubt, ...] = ()
    unexplained: tuple[str, ...] = ()
    feasible_cache: dict[frozenset[Condition], bool] = field(default_factory=dict)
    coverage: Callable[[Sequence[Condition]], int] | None = None
    #: ground-truth conditions true from the start (a thing left where it is): met by a
    #: reading that does not touch their object
    held: tuple[tuple[frozenset[str], tuple[object, ...]], ...] = ()

    def keys(self, goals: Sequence[Condition]) -> frozenset[tuple[object, ...]]:
        return goal_keys(goals, self.scene)

    def right(self, goals: Sequence[Condition]) -> bool:
        """Whether the reading meets the ground truth (the conditions true from the start
        count as met unless the reading names their object)."""
        named = {t for c in goals for t in ref_types(c.subject)}
        truth = self.truth - {key for types, key in self.held if not types & named}
        return satisfies(self.keys(goals), truth)

    def check(self, goals: tuple[Condition, ...]) -> bool:
        key = frozenset(goals)
        if key not in self.feasible_cache:
            self.feasible_cache[key] = feasible(goals, self.scene, self.state, self.team)
        return self.feasible_cache[key]


def task_case(round_: str, task: BenchTask) -> Case:
    """A SMART-LLM task with ground truth as a case."""
    assert task.ground_truth is not None
    scene = load_scene(task.floor_plan)
    state = task.initial_state()
    truth = task.ground_truth.conditions
    held = tuple((ref_types(c.subject), next(iter(goal_keys([c], scene)))) for c in truth
                 if check_condition(c, state).holds)
    return Case(round_, task.instruction, scene, state, task.team(), goal_keys(truth, scene), held=held)


def dev_cases(extra: Sequence[Path]) -> list[Case]:
    cases: list[Case] = []
    rounds = sorted((p for p in DATA.glob("blind_r*/dev") if int(p.parent.name.removeprefix("blind_r")) < FIRST_HELD_OUT),
                    key=lambda p: int(p.parent.name.removeprefix("blind_r")))
    for d in [*rounds, *extra]:
        name = d.parent.name if d.name == "dev" else d.name
        cases += [task_case(name, t) for t in import_smart_llm(d).tasks if t.ground_truth is not None]
    for path in sorted(DATA.glob("offline_dev*.jsonl")):
        for rec in load_records(path):
            if "goal" not in rec:
                continue
            scene = load_scene(str(rec["scene"]))
            team = parse_team(str(rec.get("robots", "1,2,3")))
            goal = [Condition.parse(str(g)) for g in rec["goal"]]  # type: ignore[attr-defined]
            cases.append(Case(path.stem, str(rec["instruction"]), scene, initial_state(rec, scene, team),
                              tuple(team), goal_keys(goal, scene)))
    return cases


def read_all(cases: list[Case]) -> None:
    """The reading as read and its doubts, once per case (priors that never move it)."""
    frontend = OfflineFrontend(priors=load_priors().model_copy(update={"priors": {}, "default_prior": 1e-6}))
    for case in cases:
        try:
            reading = frontend.parse(case.instruction, case.scene, case.state, case.team)
        except EmboTeamError:
            continue
        own = reading.as_read
        case.spec = own.spec if own is not None else reading.spec
        case.doubts, case.unexplained = reading.doubts, reading.unexplained
        ctx = DoubtContext(items=tag(case.instruction.strip()), goals=(), scene=case.scene, state=case.state)
        case.coverage = Coverage(ctx)


_OPPOSITE = {"open": "closed", "closed": "open", "switched_on": "switched_off", "switched_off": "switched_on",
             "clean": "dirty", "dirty": "clean"}


def _implies(got: tuple[object, ...], want: tuple[object, ...]) -> bool:
    """A goal key that, once true, makes another true: the same state and place for the
    same or fewer kinds of object (an object id for its type), at least as many."""
    if got == want:
        return True
    pred, subject, count, place, liquid = got
    wpred, wsubject, wcount, wplace, wliquid = want
    # a ground truth "FILLED" names no liquid (stored as water): any liquid meets it
    if (pred, place) != (wpred, wplace) or (liquid != wliquid and wliquid != "water"):
        return False
    names = {str(x).split("_")[0] for x in subject}   # type: ignore[attr-defined]
    wanted = {str(x).split("_")[0] for x in wsubject}  # type: ignore[attr-defined]
    if any("_" in str(x) for x in wsubject) and subject != wsubject:
        return False
    if len(names) > 1 and count >= len(names) and wanted <= names:   # type: ignore[operator]
        return True     # "both lamps": switched_off(DeskLamp|FloorLamp, 2) is each of them
    return bool(names) and names <= wanted and count >= wcount   # type: ignore[operator]


def satisfies(keys: frozenset[tuple[object, ...]], truth: frozenset[tuple[object, ...]]) -> bool:
    """Whether a reading, once achieved, meets the ground truth: every true condition is
    implied by one of the reading's and none of the reading's is its opposite. (The
    ground truth of the blind rounds lists end states only; a reading may add the
    intermediate ones it states, "open the fridge", and still succeed.)"""
    if not all(any(_implies(g, w) for g in keys) for w in truth):
        return False
    return not any(_OPPOSITE.get(str(g[0])) == w[0] and g[1] == w[1] for g in keys for w in truth)


def _closeness(case: Case, goals: Sequence[Condition]) -> int:
    """2 per true condition met, -1 per condition not in the truth (unless it holds
    already at the start: a thing kept where it is asks nothing wrong), +100 when right."""
    keys = case.keys(goals)
    idle = case.keys([c for c in goals if check_condition(c, case.state).holds])
    met = sum(any(_implies(g, w) for g in keys) for w in case.truth)
    return 2 * met - len(keys - case.truth - idle) + (100 if case.right(goals) else 0)


def fit(cases: list[Case], base: Priors) -> Priors:
    offered: Counter[tuple[str, str]] = Counter()
    right: Counter[tuple[str, str]] = Counter()
    for case in cases:
        if case.spec is None:
            continue
        goals = case.spec.goal().conditions
        here = _closeness(case, goals)
        for d in case.doubts:
            best, best_gain = AS_READ, 0
            for c in d.choices[1:]:
                edited = apply_choices(goals, [c])
                gain = _closeness(case, edited) - here if edited is not None else -1
                if gain > best_gain:
                    best, best_gain = c.label, gain
            for label in dict.fromkeys(c.label for c in d.choices):
                offered[d.kind, label] += 1
            right[d.kind, best] += 1
    table: dict[str, dict[str, float]] = defaultdict(dict)
    for (kind, label), n in offered.items():
        table[kind][label] = round((right[kind, label] + 0.5) / (n + 1), 4)
    return base.model_copy(update={"priors": dict(table)})


@dataclass
class RoundScore:
    tasks: int = 0
    as_read: int = 0
    top1: int = 0
    recall: int = 0
    unexplained: int = 0
    candidates: int = 0


def score(cases: list[Case], priors: Priors) -> dict[str, RoundScore]:
    out: dict[str, RoundScore] = defaultdict(RoundScore)
    for case in cases:
        s = out[case.round]
        s.tasks += 1
        if case.spec is None:
            continue
        ranked = candidates(case, priors)
        s.as_read += case.right(case.spec.goal().conditions)
        s.top1 += case.right(ranked[0].goals)
        s.recall += any(case.right(c.goals) for c in ranked)
        s.unexplained += bool(case.unexplained)
        s.candidates += len(ranked)
    return dict(out)


def candidates(case: Case, priors: Priors) -> tuple[Candidate, ...]:
    assert case.spec is not None
    return rank(case.spec, case.doubts, priors, case.check, case.coverage)


def _promoting(priors: Priors) -> list[tuple[str, str]]:
    """Alternatives whose prior beats their kind's as_read (they can change top-1)."""
    return [(k, label) for k, table in priors.priors.items() for label, p in table.items()
            if label != AS_READ and p > table.get(AS_READ, priors.default_prior)]


def guard(cases: list[Case], priors: Priors, kinds: set[str] | None = None,
          floor: dict[str, int] | None = None) -> Priors:
    """Cap promoting alternatives (of ``kinds`` only, when given), most harmful first,
    until no round's top-1 is below the reading as read (or below ``floor``, a top-1 per
    round: the shipped priors' when only some kinds are refitted)."""
    while True:
        scores = score(cases, priors)
        worse = {r for r, s in scores.items() if s.top1 < (s.as_read if floor is None else floor[r])}
        promoting = [kl for kl in _promoting(priors) if kinds is None or kl[0] in kinds]
        if not worse or not promoting:
            return priors
        harm: Counter[tuple[str, str]] = Counter()
        for case in cases:
            if case.round in worse and case.spec is not None:
                top = candidates(case, priors)[0]
                if not case.right(top.goals):
                    for r in top.resolves:
                        harm[r.kind, r.label] += 1
        kind, label = max(promoting, key=lambda kl: harm[kl])
        table = {k: dict(v) for k, v in priors.priors.items()}
        table[kind][label] = round(table[kind].get(AS_READ, priors.default_prior) * 0.9, 4)
        priors = priors.model_copy(update={"priors": table})


#: how many tasks of one round a refit of some kinds may lose (a task's reading can turn on
#: a tie between two near-equal candidates); the total over all development tasks may not drop
NOISE_TASKS = 1


def lowers(before: dict[str, RoundScore], after: dict[str, RoundScore], noise: int = NOISE_TASKS) -> list[str]:
    """Why ``after`` is worse than ``before`` (empty when it is not): a lower top-1 over all
    rounds, or a round's top-1 lower by more than ``noise`` tasks."""
    why = []
    total_before = sum(s.top1 for s in before.values())
    total_after = sum(s.top1 for s in after.values())
    if total_after < total_before:
        why.append(f"top-1 over all rounds {total_before} -> {total_after}")
    why += [f"{r} top-1 {s.top1} -> {after[r].top1 if r in after else 0} of {s.tasks}"
            for r, s in sorted(before.items()) if (after[r].top1 if r in after else 0) < s.top1 - noise]
    return why


Scorer = Callable[[list[Case], Priors], dict[str, RoundScore]]


def refit_kinds(cases: list[Case], shipped: Priors, kinds: set[str], scorer: Scorer | None = None) -> Priors:
    """The shipped priors with only ``kinds`` refitted (and guarded), the rest as shipped.

    The whole fit's guard, against the shipped priors: the promoting alternatives of
    ``kinds`` are capped until no round's top-1 is below the shipped one's; then a kind's
    refit is taken only if, added to those already taken (best first), it lowers neither
    the top-1 over all rounds nor any round's beyond :data:`NOISE_TASKS` (:func:`lowers`).
    A kind whose refit would is kept as shipped, and said on stderr."""
    scorer = scorer or score
    fitted = fit(cases, shipped)
    base = scorer(cases, shipped)
    floor = {r: s.top1 for r, s in base.items()}

    def with_kinds(priors: Priors, ks: set[str]) -> Priors:
        table = {k: dict(v) for k, v in priors.priors.items()}
        table.update({k: dict(v) for k, v in fitted.priors.items() if k in ks})
        return priors.model_copy(update={"priors": table})

    refits = {k: with_kinds(shipped, {k}) for k in sorted(kinds) if k in fitted.priors}
    if scorer is score:   # the guard's capping needs the reader's candidates
        refits = {k: guard(cases, p, {k}, floor) for k, p in refits.items()}
        fitted = fitted.model_copy(update={"priors": {**fitted.priors, **{k: p.priors[k] for k, p in refits.items()}}})
    gain = {k: sum(s.top1 for s in scorer(cases, p).values()) for k, p in refits.items()}
    priors, taken = shipped, set[str]()
    for k in sorted(refits, key=lambda k: (-gain[k], k)):
        trial = with_kinds(priors, {k})
        why = lowers(base, scorer(cases, trial))
        if why:
            print(f"refit of {k} refused: {'; '.join(why)}", file=sys.stderr, flush=True)
            continue
        priors, taken = trial, taken | {k}
    print(f"refitted: {sorted(taken) or 'none'}", file=sys.stderr, flush=True)
    rounds = sorted({*shipped.fitted_on, *(c.round for c in cases)}) if taken else list(shipped.fitted_on)
    return priors.model_copy(update={"fitted_on": rounds})


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check", action="store_true", help="report with the shipped priors, write nothing")
    parser.add_argument("--extra", type=Path, nargs="*", default=[], help="more development rounds (dirs)")
    parser.add_argument("--json", action="store_true", help="one JSON object on stdout")
    parser.add_argument("--out", type=Path, default=PRIORS_FILE, help="where to write the priors")
    parser.add_argument("--kinds", nargs="*", default=[],
                        help="refit only these kinds of doubt (the other priors and the coverage weight kept)")
    args = parser.parse_args(argv)
    cases = dev_cases(args.extra)
    read_all(cases)
    shipped = load_priors()
    if args.check:
        priors = shipped
    elif args.kinds:
        priors = refit_kinds(cases, shipped, set(args.kinds))
        args.out.write_text(json.dumps(priors.model_dump(), indent=1) + "\n")
    else:
        fitted = fit(cases, shipped)
        tried = []
        for w in COVERAGE_WEIGHTS:
            p = guard(cases, fitted.model_copy(update={"coverage_weight": w}))
            scores = score(cases, p)
            top1 = sum(s.top1 for s in scores.values())
            worse = sorted(r for r, s in scores.items() if s.top1 < s.as_read)
            print(f"coverage weight {w}: top-1 {top1} of {len(cases)}; rounds below as read: {worse}",
                  file=sys.stderr, flush=True)
            if not worse or w == 0:
                tried.append((top1, -w, p))
        priors = max(tried, key=lambda t: (t[0], t[1]))[2]
        priors = priors.model_copy(update={"fitted_on": sorted({c.round for c in cases})})
        args.out.write_text(json.dumps(priors.model_dump(), indent=1) + "\n")
    scores = score(cases, priors)
    report = {r: {"tasks": s.tasks, "as_read": round(s.as_read / s.tasks, 3), "top1": round(s.top1 / s.tasks, 3),
                  "recall": round(s.recall / s.tasks, 3), "unexplained_share": round(s.unexplained / s.tasks, 3),
                  "mean_candidates": round(s.candidates / s.tasks, 2)} for r, s in scores.items()}
    n = sum(s.tasks for s in scores.values())
    total = {"tasks": n, "as_read": round(sum(s.as_read for s in scores.values()) / n, 3),
             "top1": round(sum(s.top1 for s in scores.values()) / n, 3),
             "recall": round(sum(s.recall for s in scores.values()) / n, 3),
             "unexplained_share": round(sum(s.unexplained for s in scores.values()) / n, 3)}
    if args.json:
        print(json.dumps({"rounds": report, "total": total, "priors": str(args.out)}))
        return 0
    print(f"{'round':24} {'tasks':>5} {'as read':>8} {'top-1':>6} {'recall':>7} {'unexpl.':>8} {'cands':>6}")
    for r, v in report.items():
        print(f"{r:24} {v['tasks']:5} {v['as_read']:8.3f} {v['top1']:6.3f} {v['recall']:7.3f} "
              f"{v['unexplained_share']:8.3f} {v['mean_candidates']:6.2f}")
    print(f"{'all':24} {total['tasks']:5} {total['as_read']:8.3f} {total['top1']:6.3f} {total['recall']:7.3f} "
          f"{total['unexplained_share']:8.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
