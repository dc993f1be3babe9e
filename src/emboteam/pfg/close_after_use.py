"""The team closes what it opens: a closed receptacle a reading puts things into is closed
again at the end, unless the instruction asks for it open.

People rarely say "and shut the fridge after"; they expect it, and a written ground truth
often says it (``closed(Fridge)`` beside ``inside(Egg, Fridge)``). A reading that drops the
unstated close leaves the fridge open and fails such a task although it read every request
right. This is a policy of the pipeline, not of the reader: the reading stays what the words
say, and the pipeline adds one closing subtask per receptacle type, after every subtask that
puts into it or takes out of it. It is added only where it cannot contradict the reading
(nothing asks that type open), restores the start (every instance of the type starts
closed) and the team can do it (a robot with CloseObject). It applies to the offline and
hybrid front ends' readings (not to the oracle's ground truth, nor to an LLM's own spec, nor
to the LaMMA-P baseline); ``RunConfig.close_after_use`` (``--leave-open``) turns it off.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.actions import Skill
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.state import WorldState


def close_after_use(spec: TaskSpec, state: WorldState, team: Sequence[RobotProfile]) -> tuple[TaskSpec, list[str]]:
    """``spec`` with a closing subtask per closed receptacle type it puts into, and a note
    for each (the person sees what was added and why)."""
    if not any(r.can(Skill.CloseObject) for r in team):
        return spec, []
    asked_open = {t for c in _conditions(spec) if c.predicate is Predicate.open for t in c.subject.types}
    added: list[Subtask] = []
    notes: list[str] = []
    for rtype in _destinations(spec):
        if rtype in asked_open or any(c.predicate is Predicate.closed and rtype in c.subject.types
                                      for c in _conditions(spec)):
            continue
        if not _all_start_closed(state, rtype):
            continue
        after = _touching(spec, state, rtype)
        sid = _fresh_id(spec, added, f"close_{rtype}")
        added.append(Subtask(id=sid, description=f"close {rtype} after use",
                             goal=(Condition(predicate=Predicate.closed, subject=ObjectRef(types=(rtype,))),),
                             depends_on=after))
        notes.append(f"added closed({rtype}): the team closes what it opens "
                     f"(--leave-open keeps it as the plan leaves it)")
    if not added:
        return spec, []
    return TaskSpec(instruction=spec.instruction, subtasks=spec.subtasks + tuple(added)), notes


def _conditions(spec: TaskSpec) -> Iterable[Condition]:
    return (c for s in spec.subtasks for c in s.goal)


def _destinations(spec: TaskSpec) -> list[str]:
    """Receptacle types things are put into by final subtasks, in reading order."""
    seen: dict[str, None] = {}
    for s in spec.subtasks:
        for c in s.goal:
            if s.final and c.predicate is Predicate.inside and c.receptacle is not None:
                for t in c.receptacle.types:
                    seen.setdefault(t, None)
    return list(seen)


def _all_start_closed(state: WorldState, rtype: str) -> bool:
    """Every instance of the type is an openable receptacle, closed at the start."""
    found = [o for o in state.objects.values() if o.type == rtype]
    return bool(found) and all(o.has("openable") and not o.is_open for o in found)


def _touching(spec: TaskSpec, state: WorldState, rtype: str) -> tuple[str, ...]:
    """Subtasks that may open the type: those naming it, or moving a thing that starts in it."""
    inside = {o.type for o in state.objects.values()
              if o.parent is not None and o.parent in state.objects and state.objects[o.parent].type == rtype}

    def touches(c: Condition) -> bool:
        names = set(c.subject.types) | (set(c.receptacle.types) if c.receptacle else set())
        return rtype in names or (c.predicate is Predicate.inside and bool(inside & set(c.subject.types)))

    return tuple(s.id for s in spec.subtasks if any(touches(c) for c in s.goal))


def _fresh_id(spec: TaskSpec, added: Sequence[Subtask], base: str) -> str:
    taken = {s.id for s in spec.subtasks} | {s.id for s in added}
    sid, n = base, 1
    while sid in taken:
        n += 1
        sid = f"{base}_{n}"
    return sid


__all__ = ["close_after_use"]
