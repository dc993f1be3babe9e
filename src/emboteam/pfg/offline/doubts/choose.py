"""The offline reading as a choice: its points of doubt, its ranked candidates and the
mentions nothing explains (the hook :class:`~emboteam.pfg.offline.frontend.OfflineFrontend`
calls once it has read an instruction)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from emboteam.pfg.candidates import Candidate, Choice, Doubt
from emboteam.pfg.offline.corrections import KIND as CORRECTION
from emboteam.pfg.offline.discourse import Mention
from emboteam.pfg.offline.doubts import find_doubts, reading_doubts
from emboteam.pfg.offline.doubts.check import FeasibilityCheck
from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.coverage import Coverage
from emboteam.pfg.offline.doubts.from_mentions import from_mentions
from emboteam.pfg.offline.doubts.priors import Priors, load_priors
from emboteam.pfg.offline.doubts.unexplained import unexplained_spans
from emboteam.pfg.offline.surface import surface_doubts
from emboteam.pfg.offline.tagger import Item
from emboteam.pfg.ranker import rank
from emboteam.pfg.sentences import sentence
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.goals import Condition
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState


@dataclass(frozen=True)
class Choices:
    candidates: tuple[Candidate, ...]
    unexplained: tuple[str, ...]
    doubts: tuple[Doubt, ...]


def choices(spec: TaskSpec, items: Sequence[Item], scene: Scene, state: WorldState,
            team: Sequence[RobotProfile], history: Sequence[Mention] = (), priors: Priors | None = None,
            surface: Sequence[tuple[str, str, tuple[Condition, ...]]] = (),
            corrections: Sequence[tuple[str, str, tuple[Condition, ...]]] = (),
            extra: Sequence[Doubt] = ()) -> Choices:
    """The candidates of a reading (best first, the reader's own among them) and the
    words of each mention nothing explains; ``surface``: the readings of the instruction
    with the surface's guesses made (:func:`~emboteam.pfg.offline.surface.surface_doubts`),
    ``corrections``: with a self-correction's slot read another way (:mod:`..corrections`);
    ``extra``: doubts the reader found itself (a settled contradiction's other side)."""
    ctx = DoubtContext(items=items, goals=tuple(spec.goal().conditions), scene=scene, state=state,
                       history=history, steps=tuple(c for s in spec.subtasks if not s.final for c in s.goal))
    priors = priors or load_priors()
    corrected = [*surface_doubts(ctx.goals, corrections, CORRECTION), *extra]
    doubts = [*_not_corrections(find_doubts(ctx, priors), corrected), *surface_doubts(ctx.goals, surface),
              *corrected]
    check = FeasibilityCheck(scene, state, team, ctx.goals)    # the reader's own: checked already
    ranked = rank(spec, doubts, priors, check, Coverage(ctx))
    # the team check for the candidates that may run or be offered (the best and the close ones)
    best = ranked[0].score
    ranked = tuple(c for c in ranked if c.as_read or best - c.score > priors.close_margin or check.team_can(c.goals))
    return Choices(ranked, tuple(words for _, words, _ in unexplained_spans(ctx)), tuple(doubts))


def _edit(choice: Choice) -> tuple[frozenset[Condition], frozenset[Condition]]:
    return frozenset(choice.drop), frozenset(choice.add)


def _not_corrections(found: Sequence[Doubt], corrected: Sequence[Doubt]) -> list[Doubt]:
    """``found`` without the alternatives a self-correction already offers: the side a
    person took back is the correction's to offer, under its kind (whose prior, and whether
    the local model may judge it, are the correction's), not a destination guess's."""
    taken = {_edit(c) for d in corrected for c in d.choices[1:]}
    if not taken:
        return list(found)
    kept = [Doubt(d.kind, d.span, (d.choices[0], *(c for c in d.choices[1:] if _edit(c) not in taken)))
            for d in found]
    return [d for d in kept if len(d.choices) > 1]


def _from_words(ctx: DoubtContext, feasible: Callable[[tuple[Condition, ...]], bool],
                text: str) -> tuple[TaskSpec, list[Doubt]] | None:
    """A reading from the reading-level doubts alone (:func:`.reading_doubts`: an exclusion
    over a receptacle's contents, an exclusive purpose ...): the first whose likeliest
    alternative is feasible, with the other doubts of that reading."""
    for doubt in reading_doubts(ctx):
        for choice in doubt.choices[1:]:
            if choice.add and feasible(choice.add):
                spec = TaskSpec(instruction=text, subtasks=tuple(
                    Subtask(id=f"s{i}", description=sentence([c]).rstrip("."), goal=(c,))
                    for i, c in enumerate(choice.add, 1)))
                return spec, []
    return None


def from_mentions_choices(text: str, items: Sequence[Item], scene: Scene, state: WorldState,
                          team: Sequence[RobotProfile], priors: Priors | None = None,
                          words_only: bool = False) -> tuple[TaskSpec, Choices] | None:
    """When the reader found nothing to act on: the reading that gives each unexplained
    mention its likeliest goal (:mod:`.from_mentions`), or else the one a reading-level
    doubt gives (only that with ``words_only``: the reader's error was about a phrase, and
    only the words' own structure may overrule it), and its candidates; None when neither
    proposes anything feasible."""
    priors = priors or load_priors()
    ctx = DoubtContext(items=items, goals=(), scene=scene, state=state)
    check = FeasibilityCheck(scene, state, team)

    def can(goals: tuple[Condition, ...]) -> bool:
        return check(goals) and check.team_can(goals)

    made = None if words_only else from_mentions(ctx, priors, can, Coverage(ctx), text)
    if made is None:
        made = _from_words(ctx, can, text)
    if made is None:
        return None
    spec, doubts = made
    read = DoubtContext(items=items, goals=tuple(spec.goal().conditions), scene=scene, state=state)
    doubts = [*doubts, *reading_doubts(read)]
    ranked = rank(spec, doubts, priors, check, Coverage(ctx))
    best = ranked[0].score
    ranked = tuple(c for c in ranked if c.as_read or best - c.score > priors.close_margin or check.team_can(c.goals))
    return ranked[0].spec, Choices(ranked, (), tuple(doubts))
