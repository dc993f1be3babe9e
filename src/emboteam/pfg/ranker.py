"""A transparent ranker: points of doubt -> at most a few complete, checked candidates.

Each doubt's alternatives get their prior from data (``Priors``, normalised over the
alternatives the doubt has); a candidate settles every doubt one way and scores the sum
of the log-priors of its choices. Candidates come best first from a k-best walk over the
choices (the classic lazy enumeration of a product of independent factors: start from
every doubt's best choice, then each successor moves one doubt to its next choice), each
checked by the caller's ``feasible`` (scene, placement rules, team) before it counts. The
reader's own reading is always among them; it comes first unless the priors say another
settling of some doubt is likelier, which is the only reason the reading changes.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from emboteam.pfg.candidates import AS_READ, Candidate, Choice, Doubt, Resolution
from emboteam.pfg.sentences import sentence
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Condition

if TYPE_CHECKING:    # (a type only: importing the offline reader here would be a cycle)
    from emboteam.pfg.offline.doubts.priors import Priors

#: how many combinations the walk looks at before it stops (keeps the reader within
#: its time budget on long, doubtful instructions)
MAX_EXPANSIONS = 80


@dataclass(frozen=True)
class _Factor:
    doubt: Doubt
    order: tuple[int, ...]          # choice indexes, likeliest first
    logp: tuple[float, ...]         # log-prior of each choice, by choice index


def _factor(doubt: Doubt, priors: Priors, gain: Callable[[Choice], float] | None = None) -> _Factor:
    raw = [priors.prior(doubt.kind, c.label) for c in doubt.choices]
    total = sum(raw)
    logp = tuple(math.log(p / total) + (gain(c) if gain is not None else 0.0) for p, c in zip(raw, doubt.choices,
                                                                                               strict=True))
    # ties keep the reading as read first (index 0), then the rule's own order
    order = tuple(sorted(range(len(raw)), key=lambda i: (-logp[i], i)))
    return _Factor(doubt, order, logp)


def apply_choices(goals: Sequence[Condition], choices: Sequence[Choice]) -> tuple[Condition, ...] | None:
    """The goal with every choice's edit made, or None when two choices clash (one drops
    what another already dropped or changed)."""
    out = list(goals)
    for choice in choices:
        for c in choice.drop:
            if c not in out:
                return None
            out.remove(c)
        out.extend(c for c in choice.add if c not in out)
    return tuple(out)


def edit_spec(spec: TaskSpec, goals: tuple[Condition, ...],
              base: Sequence[Condition] | None = None) -> TaskSpec | None:
    """The reader's TaskSpec with its goal changed to ``goals``: a subtask keeps the
    conditions still wanted, a replaced condition takes its place, the rest become new
    subtasks. None when nothing is left. ``base``: ``spec.goal().conditions`` when the
    caller has them (the walk asks for many candidates of one spec)."""
    wanted = set(goals)    # a set to ask of (conditions hash once): the order is ``goals``'
    if wanted == set(base if base is not None else spec.goal().conditions):
        return spec
    stays = [(s, still) for s in spec.subtasks if (still := tuple(c for c in s.goal if c in wanted or not s.final))]
    ids = {s.id for s, _ in stays}
    kept = [s.model_copy(update={"goal": still, "depends_on": tuple(d for d in s.depends_on if d in ids)})
            for s, still in stays]
    present = {c for s in kept if s.final for c in s.goal}    # a step's condition is no end state
    n = len(spec.subtasks)
    for c in goals:
        if c not in present:
            n += 1
            kept.append(Subtask(id=f"s{n}", description=sentence([c]).rstrip("."), goal=(c,)))
    if not any(s.final for s in kept):
        return None
    return spec.model_copy(update={"subtasks": tuple(kept)})


def coverage_gain(base: tuple[Condition, ...], coverage: Callable[[Sequence[Condition]], int] | None,
                  weight: float) -> Callable[[Choice], float] | None:
    """A choice's coverage feature: ``weight`` times how many more instruction words the
    goal accounts for with that choice made alone (the combination adds them up)."""
    if coverage is None or weight == 0:
        return None
    here = coverage(base)

    def gain(choice: Choice) -> float:
        if choice.as_read:
            return 0.0
        goals = apply_choices(base, [choice])
        return 0.0 if goals is None else weight * (coverage(goals) - here)
    return gain


def rank(spec: TaskSpec, doubts: Sequence[Doubt], priors: Priors,
         feasible: Callable[[tuple[Condition, ...]], bool],
         coverage: Callable[[Sequence[Condition]], int] | None = None) -> tuple[Candidate, ...]:
    """The candidates, best first (at most ``priors.max_candidates``); the reader's own
    reading is always one of them. A candidate's score is the sum of its choices'
    log-priors plus, with ``coverage``, ``priors.coverage_weight`` per instruction word it
    accounts for beyond the reading as read."""
    base = tuple(spec.goal().conditions)
    gain = coverage_gain(base, coverage, priors.coverage_weight)
    factors = [_factor(d, priors, gain) for d in doubts]
    base_score = sum(f.logp[0] for f in factors)
    start = tuple(0 for _ in factors)    # position in each factor's order
    heap: list[tuple[float, tuple[int, ...]]] = [(-_score(factors, start), start)]
    seen = {start}
    found: dict[frozenset[Condition], Candidate] = {}
    # goals already found (a likelier settling reached them) or already refused are not
    # checked again: their candidate would be dropped, or refused again
    refused: set[tuple[Condition, ...]] = set()
    expansions = 0
    while heap and len(found) < priors.max_candidates and expansions < MAX_EXPANSIONS:
        neg, pos = heapq.heappop(heap)
        expansions += 1
        chosen = [f.doubt.choices[f.order[p]] for f, p in zip(factors, pos, strict=True)]
        goals = apply_choices(base, chosen)
        if goals is not None and goals not in refused and (key := frozenset(goals)) not in found:
            candidate = _candidate(spec, base, factors, chosen, goals, -neg, feasible)
            if candidate is None:
                refused.add(goals)
            else:
                found[key] = candidate
        for i, f in enumerate(factors):
            if pos[i] + 1 < len(f.order):
                nxt = (*pos[:i], pos[i] + 1, *pos[i + 1:])
                if nxt not in seen:
                    seen.add(nxt)
                    heapq.heappush(heap, (-_score(factors, nxt), nxt))
    as_read = Candidate(goals=base, sentence=sentence(base), score=base_score, spec=spec)
    if frozenset(base) not in found:
        if len(found) >= priors.max_candidates:
            found.pop(next(reversed(found)))
        found[frozenset(base)] = as_read
    return tuple(sorted(found.values(), key=lambda c: (-c.score, not c.as_read)))


def _score(factors: Sequence[_Factor], pos: tuple[int, ...]) -> float:
    return sum(f.logp[f.order[p]] for f, p in zip(factors, pos, strict=True))


def _candidate(spec: TaskSpec, base: tuple[Condition, ...], factors: Sequence[_Factor], chosen: Sequence[Choice],
               goals: tuple[Condition, ...], score: float,
               feasible: Callable[[tuple[Condition, ...]], bool]) -> Candidate | None:
    if not goals:
        return None
    if goals != base and not feasible(goals):
        return None
    edited = edit_spec(spec, goals, base)
    if edited is None:
        return None
    resolves = tuple(Resolution(f.doubt.kind, f.doubt.span, c.label, c.how)
                     for f, c in zip(factors, chosen, strict=True) if c.label != AS_READ and not c.as_read)
    return Candidate(goals=goals, sentence=sentence(goals), score=score, spec=edited, resolves=resolves)


def close_calls(candidates: Sequence[Candidate], margin: float) -> tuple[Candidate, ...]:
    """The candidates within ``margin`` (log-prior) of the best: what is still close."""
    if not candidates:
        return ()
    best = candidates[0].score
    return tuple(c for c in candidates if best - c.score <= margin)
