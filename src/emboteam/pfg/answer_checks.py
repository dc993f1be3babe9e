"""Checks on an LLM's TaskSpec that the schema cannot express, aimed at weak models.

A 0.5B model answers schema-valid JSON that is still wrong in typical ways: it repeats a
subtask until the item limit, and it copies the worked example's subtasks (make coffee,
switch off the light) into a task that never mentions them. In the hybrid front end it
may also "correct" a draft by dropping what the offline parser read with confidence.
Each check returns messages the model can act on; the front ends raise them as
:class:`~emboteam.llm.structured.Rejected`, so they go back as feedback.
"""

from __future__ import annotations

from collections.abc import Collection

from emboteam.pfg.focus import ref_types
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition, Predicate
from emboteam.world.state import WorldState

#: predicates that cannot both hold of one object
OPPOSITES: dict[Predicate, Predicate] = {
    Predicate.open: Predicate.closed, Predicate.closed: Predicate.open,
    Predicate.switched_on: Predicate.switched_off, Predicate.switched_off: Predicate.switched_on,
    Predicate.hot: Predicate.cold, Predicate.cold: Predicate.hot,
    Predicate.clean: Predicate.dirty, Predicate.dirty: Predicate.clean,
}


def repetition_problems(spec: TaskSpec) -> list[str]:
    """A subtask whose goal is another's, or a condition stated twice."""
    problems: list[str] = []
    seen_goal: dict[frozenset[str], str] = {}
    seen_cond: dict[str, str] = {}
    for s in spec.subtasks:
        goal = frozenset(str(c) for c in s.goal)
        if goal in seen_goal:
            problems.append(f"{s.id} repeats {seen_goal[goal]} ({', '.join(sorted(goal))}): "
                            "give each subtask once")
            continue
        seen_goal[goal] = s.id
        for c in s.goal:
            key = str(c)
            if key in seen_cond and s.final:
                problems.append(f"{s.id}: {key} is already a goal of {seen_cond[key]}: state it once")
            elif s.final:
                seen_cond[key] = s.id
    return problems


def copied_problems(spec: TaskSpec, state: WorldState, allowed: Collection[str],
                    example_types: Collection[str]) -> list[str]:
    """Conditions about a type that a worked example shows and that is neither named by
    the instruction, matched to one of its words, nor listed in detail for the task (what
    its named places hold, what its intent touches, what a goal on those needs):
    ``allowed`` is that union. Only such a condition is certainly copied; types the
    examples do not show are left alone (a commonsense reading of "get breakfast ready"
    may name anything). The rule is stated in the system prompt."""
    problems: list[str] = []
    for s in spec.subtasks:
        for c in s.goal:
            subject = ref_types(c.subject, state)
            copied = sorted((subject & set(example_types)) - set(allowed))
            if copied and not subject & set(allowed):
                problems.append(f"{s.id}: {c} is about {', '.join(copied)}, which the instruction neither names "
                                "nor implies and the task's listing does not show (it is from the worked "
                                "example, not this task): remove it")
    return problems


def _same_object(a: Condition, b: Condition) -> bool:
    return a.subject == b.subject


def contradicts(a: Condition, b: Condition) -> bool:
    """Whether ``a`` and ``b`` cannot both hold at the end."""
    if not _same_object(a, b):
        return False
    if OPPOSITES.get(a.predicate) == b.predicate:
        return True
    return (a.predicate == b.predicate == Predicate.inside and a.subject.id is not None
            and a.receptacle != b.receptacle and a.count == b.count == 1
            and a.receptacle is not None and b.receptacle is not None
            and a.receptacle.id is not None and b.receptacle.id is not None)


def sure_condition_problems(corrected: TaskSpec, draft: TaskSpec, unsure: Collection[str]) -> list[str]:
    """What a correction may not do to the draft: drop a condition the parser was sure of,
    or add one that contradicts it. The rule: the offline parser's confident conditions
    are kept as read; a correction may change the unsure ones and add what was unread."""
    final_new = {str(c): c for c in corrected.goal().conditions}
    problems: list[str] = []
    sure = [c for c in draft.goal().conditions if str(c) not in set(unsure)]
    for c in sure:
        if str(c) not in final_new:
            problems.append(f"keep {c}: the instruction says it plainly (only unsure or missing parts may change)")
        clash = [str(n) for n in final_new.values() if contradicts(c, n)]
        if clash:
            problems.append(f"{', '.join(clash)} contradicts {c}, which the instruction says plainly")
    return problems

