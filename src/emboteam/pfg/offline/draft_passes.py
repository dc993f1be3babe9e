"""Passes over the drafts of one instruction, before dependencies are assembled: a draft
that another makes unnecessary is no subtask of its own (a wish a later act fulfils,
holding on the way to a place, a placement of one object that a later one supersedes),
and a draft the scene cannot satisfy is dropped with a note when others stay.
"""

from __future__ import annotations

from collections.abc import Callable

from emboteam.pddl.errors import ImpossibleGoalError
from emboteam.pddl.goal_compiler import compile_condition, shared_view, slicing_targets
from emboteam.pfg.offline.decompose import refs_overlap
from emboteam.pfg.offline.grounding import Grounder
from emboteam.pfg.offline.semantics import Draft
from emboteam.world.checker import GoalValidationError, validate_goal
from emboteam.world.goals import Goal, ObjectRef, Predicate
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

#: what a later act brings about: a wished state it makes true needs no subtask of its own
_FULFILS: dict[Predicate, frozenset[Predicate]] = {
    Predicate.hot: frozenset({Predicate.hot, Predicate.cooked}),
    Predicate.cold: frozenset({Predicate.cold}),
    Predicate.cooked: frozenset({Predicate.cooked}),
    Predicate.clean: frozenset({Predicate.clean}),
    Predicate.filled: frozenset({Predicate.filled}),
}


def drop_drafts(drafts: dict[int, list[Draft]], gone_of: Callable[[int, Draft], bool]) -> None:
    """Remove the drafts ``gone_of(clause, draft)`` picks, keeping the others' order
    (their ``after`` indices renumbered)."""
    for ci in sorted(drafts):
        gone = {k for k, d in enumerate(drafts[ci]) if gone_of(ci, d)}
        if not gone:
            continue
        kept = [k for k in range(len(drafts[ci])) if k not in gone]
        index = {old: new for new, old in enumerate(kept)}
        out = []
        for k in kept:
            d = drafts[ci][k]
            d.after = [index[a] for a in d.after if a in index]
            out.append(d)
        if out:
            drafts[ci] = out
        else:
            del drafts[ci]


def drop_guessed_water(drafts: dict[int, list[Draft]]) -> None:
    """"Make a coffee in the mug, and once the mug's full switch the machine off": "full"
    said no liquid and water was the guess; another draft fills the same thing with
    something else (coffee), so the guess goes (a mug holds one liquid)."""
    def guessed(ci: int, d: Draft) -> bool:
        others = [c for ds in drafts.values() for e in ds if e is not d for c in e.conditions
                  if c.predicate is Predicate.filled and c.liquid not in (None, "water")]
        return bool(d.conditions) and all(
            c.predicate is Predicate.filled and c.liquid == "water"
            and any(refs_overlap(c.subject, o.subject) for o in others) for c in d.conditions)
    drop_drafts(drafts, guessed)


def drop_fulfilled_wishes(drafts: dict[int, list[Draft]]) -> None:
    """"I'd love a warm slice of bread - toast some for me": the wish introduces what a
    later clause says how to make; toasting makes it warm (cooking heats), so the wish adds
    no subtask of its own."""
    def fulfilled(ci: int, d: Draft) -> bool:
        later = [c for cj, ds in drafts.items() if cj > ci for e in ds if not e.wished
                 for c in e.conditions]
        return d.wished and all(any(c2.predicate in _FULFILS.get(c.predicate, frozenset())
                                    and refs_overlap(c.subject, c2.subject) for c2 in later)
                                for c in d.conditions)
    drop_drafts(drafts, fulfilled)


def drop_superseded_placements(drafts: dict[int, list[Draft]],
                               grounder: Grounder) -> list[tuple[int, Draft, int, Draft]]:
    """"Pick the pillow and the paper up - pillow on the sofa, paper on the coffee table":
    an object placed twice ends where it is placed last; the earlier placement of one
    object (an id, or a kind the scene has one of) is no goal (both cannot hold at the
    end). "The toilet paper on the holder, the spare roll on the shelf" is two rolls.
    Returns (clause, dropped draft, clause, the draft that supersedes it) for each, which
    consistency.check_placements turns into an error or a note."""
    order = [(ci, k, d) for ci in sorted(drafts) for k, d in enumerate(drafts[ci])]
    dropped: list[tuple[int, Draft, int, Draft]] = []

    def one_object(ref: ObjectRef) -> bool:
        return ref.id is not None or sum(len(grounder.instances(t)) for t in ref.types) == 1

    def superseded(ci: int, d: Draft) -> bool:
        if d.intermediate or not d.conditions or any(
                c.predicate is not Predicate.inside or c.count != 1 or not one_object(c.subject)
                for c in d.conditions):
            return False
        at = next(i for i, (_, _, e) in enumerate(order) if e is d)
        later = [c for _, _, e in order[at + 1:] if not e.intermediate for c in e.conditions
                 if c.predicate is Predicate.inside]
        if not all(any(refs_overlap(c.subject, c2.subject) and c2.receptacle != c.receptacle
                       for c2 in later) for c in d.conditions):
            return False
        if _used_there(d, [e for _, _, e in order[at + 1:]]):
            # "potato in the microwave, switch it on, then put it on a plate": a step
            d.intermediate = True
            return False
        cj, by = next((cj, e) for cj, _, e in order[at + 1:] if not e.intermediate and any(
            c2.predicate is Predicate.inside and refs_overlap(c.subject, c2.subject) and c2.receptacle != c.receptacle
            for c in d.conditions for c2 in e.conditions))
        dropped.append((ci, d, cj, by))
        return True
    drop_drafts(drafts, superseded)
    return dropped


def _used_there(placed: Draft, after: list[Draft]) -> bool:
    """Does a draft after ``placed``, before the object is moved on, act on the receptacle
    it was put in (the microwave switched on, the fridge closed)?"""
    for e in after:
        if any(c.predicate is Predicate.inside and any(refs_overlap(c.subject, p.subject) for p in placed.conditions)
               for c in e.conditions):
            return False
        if any(c.predicate is not Predicate.inside and p.receptacle is not None and refs_overlap(c.subject, p.receptacle)
               for c in e.conditions for p in placed.conditions):
            return True
    return False


def drop_self_placements(drafts: dict[int, list[Draft]]) -> None:
    """"Coffee in the mug that's on the table": the coffee's vessel is the mug, so the
    placement read from "coffee in the mug" is the mug in itself. A thing is never put in
    or on itself; the condition goes (the fill it stands for is read already)."""
    emptied: set[int] = set()
    for ds in drafts.values():
        for d in ds:
            kept = [c for c in d.conditions if not (
                c.predicate is Predicate.inside and c.subject == c.receptacle)]
            if len(kept) < len(d.conditions):
                d.conditions = kept
                if not kept:
                    emptied.add(id(d))
    drop_drafts(drafts, lambda ci, d: id(d) in emptied)


def drop_holds_before_placing(drafts: dict[int, list[Draft]]) -> None:
    """"Take the sponge and the towels out of the cupboard and put them on the counter":
    holding is how they get there, not a goal of its own (and two things held "at once"
    would ask for two free hands)."""
    placed = [(ci, k, c) for ci, ds in drafts.items() for k, d in enumerate(ds) for c in d.conditions
              if c.predicate is Predicate.inside]

    def before_placing(ci: int, d: Draft) -> bool:
        # "the wine goes in the fridge - the strong robot should carry it": a placement
        # before "carry it" makes the carrying its means too
        return bool(d.conditions) and all(
            c.predicate is Predicate.held and any(
                (cj >= ci or d.carried) and refs_overlap(c.subject, p.subject) for cj, _, p in placed)
            for c in d.conditions)
    drop_drafts(drafts, before_placing)


def drop_impossible(drafts: dict[int, list[Draft]], scene: Scene, state: WorldState) -> list[tuple[str, str]]:
    """Drafts whose conditions the scene cannot satisfy ("get the shower running so it's
    warm" read as hot(ShowerHead)) go, with why, when something else of the instruction
    stays: one misread phrase does not sink the task. The goal compiler decides, as the
    planner will (with the pieces the whole reading cuts). Returns (description, why)."""
    conditions = [c for ds in drafts.values() for d in ds for c in d.conditions]
    robots = list(state.robots)
    view = shared_view(state)     # one for every draft: the state does not change meanwhile
    slices = slicing_targets(conditions, state, robots, view)

    def why_not(d: Draft) -> str | None:
        try:
            validate_goal(Goal(conditions=tuple(d.conditions)), scene)
            for c in d.conditions:
                compile_condition(c, state, robots, slices=slices, narrow=False, view=view)
        except (GoalValidationError, ImpossibleGoalError) as exc:
            return str(exc)
        return None

    failing = {id(d): why for ds in drafts.values() for d in ds if d.conditions and (why := why_not(d))}
    if not failing or len(failing) == sum(1 for ds in drafts.values() for d in ds if d.conditions):
        return []       # nothing to drop, or nothing would be left: the planner says why
    dropped = [(d.description, failing[id(d)]) for ds in drafts.values() for d in ds if id(d) in failing]
    drop_drafts(drafts, lambda ci, d: id(d) in failing)
    return dropped
