"""Decomposition: clauses and their drafts -> a TaskSpec (ids, dependencies, robots,
final flags).

Ordering rules (docs/offline_parser.md):

- "A then B", "A. After that B", "first A, then B", "once A is done, B": B depends on
  every subtask of A's step;
- "after A, B" / "B after A" / "once A, B" / "when A, B": B depends on A; "before B, A" /
  "A before B": B depends on A;
- "A and B" (or separate sentences): independent, unless B involves an object A works on
  or with ("slice the apple and put it in the fridge", "put the mug in the coffee machine
  and switch it on"): then B depends on A, in the order written;
- a subtask whose condition a later subtask undoes (the apple held, then put away; the
  fridge opened, then closed) is intermediate: ``final=False``; so is a means to an end
  (rinsing a non-dirtyable object in the sink basin under the running faucet, the running
  microwave of "microwave the potato"): the end state need not keep it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from emboteam.errors import UnknownRobotError
from emboteam.pfg.offline.clauses import THEN, Clause
from emboteam.pfg.offline.semantics import Draft
from emboteam.pfg.taskspec import Subtask, TaskSpec
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile

P = Predicate
_OPPOSITES = {
    (P.switched_on, P.switched_off), (P.switched_off, P.switched_on), (P.open, P.closed),
    (P.closed, P.open), (P.clean, P.dirty), (P.dirty, P.clean), (P.hot, P.cold), (P.cold, P.hot),
}


@dataclass
class Node:
    """A draft placed in the instruction: its clause, its step, its dependencies."""

    draft: Draft
    clause: int
    robot: str | None
    after: set[int]


def _done_first(clause: Clause) -> bool:
    """Does the clause end in "first" or "beforehand" ("... open it first")?"""
    words = [i.text for i in clause.items if i.punct is None]
    return bool(words) and words[-1] in ("first", "beforehand") and len(words) > 1


def steps(clauses: Sequence[Clause]) -> list[list[int]]:
    """Clause indices grouped into steps, in execution order: clauses of one step may run
    in parallel, each step after the one before."""
    groups: list[list[int]] = []
    pending: tuple[str, int] | None = None    # a sentence-initial "after X," / "before X,"
    for ci, c in enumerate(clauses):
        link = c.link
        if pending is not None and clauses[pending[1]].sentence == c.sentence and link not in (
                "after", "before"):
            kind, sub = pending
            pending = None
            if kind == "after":
                groups.append([ci])
            else:   # "before X, Y": Y goes before X's step
                pos = next(k for k, g in enumerate(groups) if sub in g)
                groups.insert(pos, [ci])
            continue
        if not groups:
            groups.append([ci])
            if link in ("after", "before") and c.initial:
                pending = (link, ci)
            continue
        if _done_first(c) and link != THEN:
            # "put the fork in the drawer, the drawer needs opening first": this clause's
            # step comes before the step of the clause before it
            pos = next(k for k, g in enumerate(groups) if ci - 1 in g)
            groups.insert(pos, [ci])
        elif link == THEN:
            groups.append([ci])
        elif link in ("after", "before") and c.initial:
            groups.append([ci])
            pending = (link, ci)
        elif link == "after":
            # "B after A": A (this clause) before the step of B (the clause before)
            pos = next(k for k, g in enumerate(groups) if ci - 1 in g)
            groups.insert(pos, [ci])
            if len(groups[pos + 1]) > 1:
                groups[pos + 1].remove(ci - 1)
                groups.insert(pos + 2, [ci - 1])
        elif link == "before":
            groups.append([ci])      # "A before B": B (this clause) after A
        else:
            groups[-1].append(ci)
    return groups


def refs_overlap(a: ObjectRef, b: ObjectRef) -> bool:
    """Can the two references name the same object (a slice type its whole's)?"""
    if a.id is not None and b.id is not None:
        return a.id == b.id
    cat = load_catalogue()
    # a slice is its whole's ("AppleSliced" overlaps "Apple"); a name's prefix is not
    # ("Pot" is no "Potato", "Pen" no "Pencil")
    ta = {cat.source_type(t) or t for t in (a.types if a.id is None else (a.id.split("_")[0],))}
    tb = {cat.source_type(t) or t for t in (b.types if b.id is None else (b.id.split("_")[0],))}
    return bool(ta & tb)


#: what is done to an object that is not held while it happens (it is cut on a surface,
#: cooked in a pan, cleaned in the sink, filled under the tap, chilled in the fridge)
_DONE_WITH_IT = frozenset({P.sliced, P.cooked, P.hot, P.cold, P.clean, P.filled, P.broken,
                           P.inside, P.dirty})


def undoes(later: Condition, earlier: Condition) -> bool:
    """Does ``later`` make ``earlier`` false (about the same object)?"""
    if not refs_overlap(later.subject, earlier.subject):
        return False
    if (earlier.predicate, later.predicate) in _OPPOSITES:
        return True
    if earlier.predicate is P.held and later.predicate in _DONE_WITH_IT:
        return True    # "get the lettuce out of the fridge and slice it": held on the way
    moves = (P.inside, P.held)
    if earlier.predicate in moves and later.predicate in moves:
        if earlier.predicate is P.inside and later.predicate is P.inside:
            assert earlier.receptacle is not None and later.receptacle is not None
            if _carried_into(earlier.receptacle, later.receptacle):
                return False   # "the egg in a bowl, then microwave it": in the bowl, in there
            return not refs_overlap(earlier.receptacle, later.receptacle)
        return earlier.predicate != later.predicate
    return False


def _carried_into(container: ObjectRef, place: ObjectRef) -> bool:
    """Can the container (a bowl, a plate: pickupable) itself go into the place, so that
    what it holds is in both?"""
    cat = load_catalogue()
    inner = container.types if container.id is None else (container.id.split("_")[0],)
    outer = place.types if place.id is None else (place.id.split("_")[0],)
    return all(t in cat.types and cat.type(t).has("pickupable") for t in inner) and all(
        cat.can_place(t, o) for t in inner for o in outer)


def _depends(nodes: list[Node], start: int, target: int) -> bool:
    """Does node ``start`` wait, directly or not, for ``target``?"""
    stack = list(nodes[start].after)
    seen: set[int] = set()
    while stack:
        k = stack.pop()
        if k == target:
            return True
        if k not in seen:
            seen.add(k)
            stack.extend(nodes[k].after)
    return False


def _reaches(nodes: list[Node], start: int, target: int) -> bool:
    """Does node ``start`` depend on ``target`` through a chain of at least two steps
    (``start`` after something that is after ``target``)?"""
    return any(a != target and _depends(nodes, a, target) for a in nodes[start].after)


def robot_name(mention: tuple[str, int] | None, team: Sequence[RobotProfile]) -> str | None:
    """The team member a clause addresses: "robot 5" is the member built from profile 5,
    else the fifth member; "the second robot" is the second member."""
    if mention is None:
        return None
    kind, value = mention
    names = [r.name for r in team]
    if kind == "number" and f"robot{value}" in names:
        return f"robot{value}"
    if kind == "ordinal" and value == -1 and team:
        return names[-1]
    if kind in ("number", "ordinal") and 1 <= value <= len(team):
        return names[value - 1]
    label = f"robot {value}" if kind == "number" else f"robot number {value} in order"
    raise UnknownRobotError(f"the instruction names {label}, but the team is "
                            f"{', '.join(names) or 'empty'}")


def assemble(instruction: str, clauses: Sequence[Clause], drafts: dict[int, list[Draft]],
             team: Sequence[RobotProfile]) -> TaskSpec:
    """Drafts per clause -> a TaskSpec with dependencies and final flags."""
    order = steps(clauses)
    nodes, clause_nodes = _nodes(order, clauses, drafts, team)
    _order(nodes, order, clause_nodes)
    kept = _merge_duplicates(nodes)
    final = _final(nodes, kept)
    ids = {i: f"s{k + 1}" for k, i in enumerate(kept)}
    subtasks = []
    for i in kept:
        node = nodes[i]
        deps = tuple(sorted((ids[a] for a in node.after if a in ids), key=lambda s: int(s[1:])))
        subtasks.append(Subtask(id=ids[i], description=node.draft.description, robot=node.robot,
                                goal=tuple(node.draft.conditions), depends_on=deps,
                                final=final[i]))
    return TaskSpec(instruction=instruction, subtasks=tuple(subtasks))


def _nodes(order: list[list[int]], clauses: Sequence[Clause], drafts: dict[int, list[Draft]],
           team: Sequence[RobotProfile]) -> tuple[list[Node], dict[int, list[int]]]:
    """A node per draft, in step order, and the nodes of each clause."""
    nodes: list[Node] = []
    clause_nodes: dict[int, list[int]] = {}
    for group in order:
        for ci in sorted(group):
            base = len(nodes)
            robot = robot_name(clauses[ci].robot, team)
            for k, d in enumerate(drafts.get(ci, [])):
                nodes.append(Node(d, ci, robot, {base + a for a in d.after}))
                clause_nodes.setdefault(ci, []).append(base + k)
    return nodes, clause_nodes


def _order(nodes: list[Node], order: list[list[int]], clause_nodes: dict[int, list[int]]) -> None:
    """What waits for what: a box shut after what goes in, a step after the one before."""
    # within a clause, a receptacle is shut after what goes into it ("the remote and the
    # card shut away inside the box": placed by one frame, the box shut by another)
    for members in clause_nodes.values():
        for b in members:
            shut = [c.subject for c in nodes[b].draft.conditions if c.predicate is P.closed]
            for a in members:
                if a != b and any(c.predicate is P.inside and c.receptacle is not None
                                  and any(refs_overlap(c.receptacle, x) for x in shut)
                                  for c in nodes[a].draft.conditions):
                    nodes[b].after.add(a)
    # step order: everything of a step after every subtask of the last non-empty step
    previous: list[int] = []
    for group in order:
        members = [n for ci in sorted(group) for n in clause_nodes.get(ci, [])]
        for n in members:
            nodes[n].after |= set(previous)
        # within a step: an object shared with an earlier clause orders the two
        for a in members:
            for b in members:
                if nodes[a].clause < nodes[b].clause and nodes[a].draft.entities & nodes[b].draft.entities:
                    nodes[b].after.add(a)
        if members:
            previous = members


def _merge_duplicates(nodes: list[Node]) -> list[int]:
    """The nodes kept once duplicates are merged (their waits moved to the kept ones)."""
    # duplicates ("make a salad" then "chop the lettuce"): keep the first, unless the
    # second comes after something that comes after the first ("take the mug, fill it
    # and bring it": held, filled, held again) - merging them would make a cycle
    seen: dict[str, int] = {}
    alias: dict[int, int] = {}
    for i, node in enumerate(nodes):
        key = " & ".join(sorted(str(c) for c in node.draft.conditions))
        if key in seen and not node.draft.intermediate and not _reaches(nodes, i, seen[key]):
            alias[i] = seen[key]
        else:
            seen[key] = i
    kept = [i for i in range(len(nodes)) if i not in alias]

    def canon(i: int) -> int:
        while i in alias:
            i = alias[i]
        return i

    for i in kept:
        nodes[i].after = {canon(a) for a in nodes[i].after if canon(a) != i}
    for i, target in alias.items():
        # what the dropped duplicate waited for, the kept one waits for too - unless that
        # already waits for the kept one (two duplicated groups: no cycle)
        keep = canon(target)
        for a in {canon(a) for a in nodes[i].after}:
            if a != keep and not _depends(nodes, a, keep):
                nodes[keep].after.add(a)
    return kept


def _final(nodes: list[Node], kept: list[int]) -> dict[int, bool]:
    """Is each kept node's goal final? A condition undone by a later subtask is intermediate."""
    final = {i: True for i in kept}
    for pos, i in enumerate(kept):
        # objects of one clause are different objects ("the toilet paper goes on the
        # holder, the spare roll in the cabinet"), not one object moved twice
        later = [j for j in kept[pos + 1:] if nodes[j].clause != nodes[i].clause
                 or nodes[j].draft.after]
        for c in nodes[i].draft.conditions:
            if any(undoes(c2, c) for j in later for c2 in nodes[j].draft.conditions
                   if not (nodes[j].draft.another and c.subject.id is None)):
                final[i] = False
        if nodes[i].draft.intermediate:
            final[i] = False
    return final

