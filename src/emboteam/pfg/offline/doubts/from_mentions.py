"""A reading from the things an instruction names, when the grammar finds nothing to act on.

The reader raises when no clause gives a goal ("If the telly is off it should be on",
"candles are the only light allowed in here"). Before it does, every mention of a scene
thing that nothing explains (:mod:`.explained`) proposes the goals its words and the
scene allow (:mod:`.unexplained`: a state word or verb of its stretch, a place named near
it, the state it is not in). Each mention gets its likeliest proposal (by the priors and
the coverage feature); that is the reading, marked unsure, and each mention is a point
of doubt (kind ``from_mentions``) between its proposals and leaving it out. None of this
runs when the mentions propose nothing feasible: the reader's own error stands.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts import unexplained
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.explained import NEGATED, explanation
from emboteam.pfg.offline.doubts.priors import Priors
from emboteam.pfg.sentences import clause, sentence
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.checker import check_condition
from emboteam.world.goals import Condition

KIND = "from_mentions"
#: with nothing else read, a thing named in a condition is what the rule is about ("if
#: the telly is off it should be on")
RULES = frozenset({"a condition"})


def _proposals(ctx: DoubtContext, doubt: Doubt, priors: Priors, score: Callable[[Choice], float],
               feasible: Callable[[tuple[Condition, ...]], bool]) -> list[Choice]:
    """The doubt's feasible proposals (each adds one goal) that are not true already
    ("the mug's in one of the cupboards" asks nothing), likeliest first."""
    excluded = {t for k, _, ts in ctx.mentions() if explanation(ctx, k, ts, goals=False) == NEGATED for t in ts}
    out = [c for c in doubt.choices if not c.as_read and feasible(c.add)
           and not all(check_condition(g, ctx.state).holds for g in c.add)
           and not any(ref_types(g.subject) & excluded for g in c.add)]
    return sorted(out, key=lambda c: -(math.log(priors.prior(unexplained.KIND, c.label)) + score(c)))


def from_mentions(ctx: DoubtContext, priors: Priors, feasible: Callable[[tuple[Condition, ...]], bool],
                  coverage: Callable[[Sequence[Condition]], int], text: str) -> tuple[TaskSpec, list[Doubt]] | None:
    """The reading that gives each unexplained mention its likeliest goal, and its doubts;
    None when no mention proposes a feasible goal."""
    def gain(c: Choice) -> float:
        return priors.coverage_weight * coverage(c.add)

    chosen: list[tuple[Choice, list[Choice]]] = []
    for d in unexplained.doubts(ctx, unless=RULES):
        ranked = _proposals(ctx, d, priors, gain, feasible)
        if ranked and not any(set(ranked[0].add) & set(c.add) for c, _ in chosen):
            chosen.append((ranked[0], ranked[1:3]))
    if not chosen:
        return None
    goals = tuple(c for first, _ in chosen for c in first.add)
    spec = TaskSpec(instruction=text, subtasks=tuple(
        Subtask(id=f"s{i}", description=sentence([c]).rstrip("."), goal=(c,)) for i, c in enumerate(goals, 1)))
    doubts = []
    for first, others in chosen:
        g = first.add[0]
        choices = [Choice(AS_READ, clause(g)), *(Choice("other_goal", o.how, drop=(g,), add=o.add) for o in others)]
        if len(chosen) > 1:
            choices.append(Choice("leave", f"not {clause(g)}", drop=(g,)))
        doubts.append(Doubt(KIND, first.how.split(":")[0], tuple(choices)))
    return spec, [d for d in doubts if len(d.choices) > 1]
