"""Conditions the scene's start state settles: "if the floor lamp's on, switch it off; if
it's off, on", "if the blinds aren't up, raise them; if not, leave them"; and one said after its act: "the
standing lamp off if it's on", "shut the basket if it's open".

A condition is a device state (on/off, open/shut) of one named thing under "if", followed
in its sentence by what to do (its branch), maybe then "otherwise"/"if not" and another
branch. The reader knows how the scene starts, so it checks the condition: the branch
whose condition holds gives its goals, the other gives none, and the condition's own state
is no goal of its own (unless the branch only keeps it: "if the TV is off, that's how it
should stay"). A condition it cannot check (no such thing, several that disagree, a
state told for later: "if the light's off when you finish") is left as the grammar read it.
A condition after its act ("X if it's Y") asks about the thing of that act: whether or not
it holds, the condition itself is no goal; where it fails the act's state is the one the
thing is in already (a keep), so the act stays.
"""

from __future__ import annotations

from dataclasses import dataclass

from emboteam.pfg.offline.clauses import AND, THEN, Clause
from emboteam.pfg.offline.errors import OfflineParseError
from emboteam.pfg.offline.grounding import Grounder, ref_types
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.lexicon import Act, Stat
from emboteam.pfg.offline.phrases import Head, ParsedClause
from emboteam.pfg.offline.semantics import Draft
from emboteam.world.checker import check_condition

_W = word_tables("start_conditions")
#: words that open the other branch ("otherwise leave it", "else on")
_OTHERWISE = _W.set("otherwise")
#: the words of an "if" clause that only denies the condition before ("if not", "if it hasn't")
_DENIAL = _W.set("denial")
_CHECKED = {Stat.SWITCH: ("switch", "is_on"), Stat.OPEN: ("open", "is_open")}


@dataclass(frozen=True)
class Conditional:
    """One "if": the thing and state it asks about, its clause and its two branches."""

    head: Head
    state: tuple[Stat, bool]
    condition: int
    then: tuple[int, ...]
    otherwise: tuple[int, ...]
    #: the act is said before the "if" ("the lamp off if it's on")
    after: bool = False


def _words(c: Clause) -> list[str]:
    return [i.text for i in c.items if i.punct is None]


def _branch(clauses: list[Clause], k: int) -> list[int]:
    """The clauses after ``k`` that its "if" governs: coordinated, in its sentence, up to
    the next "if" or "otherwise"."""
    out: list[int] = []
    j = k + 1
    while j < len(clauses) and clauses[j].sentence == clauses[k].sentence and clauses[j].link in (AND, THEN) \
            and not (_words(clauses[j])[:1] and _words(clauses[j])[0] in _OTHERWISE):
        out.append(j)
        j += 1
    return out


def _denial(c: Clause) -> bool:
    return c.link == "if" and bool(_words(c)) and set(_words(c)) <= _DENIAL and "not" in _words(c)


def _condition(c: Clause, p: ParsedClause, before: Head | None) -> tuple[Head, tuple[Stat, bool]] | None:
    """The thing and the state an "if" clause asks about, if it is one device state (a
    state it was left in too: "if the microwave has been left running")."""
    if c.link != "if" or len(p.frames) != 1:
        return None
    f = p.frames[0]
    if f.state is None or f.state[0] not in _CHECKED or len(f.targets) != 1 or f.act not in (None, Act.CAUSE) \
            or f.report or f.past:
        return None
    head = f.targets[0].head
    if head.pron is not None:
        if before is None:
            return None
        head = before
    return head, (f.state[0], f.state[1] != f.negated)


def _act_before(clauses: list[Clause], parsed: list[ParsedClause], k: int) -> Head | None:
    """The one thing the clause just before ``k`` acts on, in its sentence ("the box shut"
    before "if it's open"): what a pronoun of a condition after it names."""
    if k == 0 or clauses[k - 1].sentence != clauses[k].sentence or clauses[k - 1].link == "if":
        return None
    heads = [t.head for f in parsed[k - 1].frames for t in f.targets]
    return heads[0] if len(heads) == 1 and heads[0].pron is None and heads[0].noun is not None else None


def _after(clauses: list[Clause], parsed: list[ParsedClause], k: int) -> Conditional | None:
    """A condition said after its act: "the standing lamp off if it's on"."""
    c = clauses[k]
    acted = _act_before(clauses, parsed, k)
    if acted is None or len(parsed[k].frames) != 1 or parsed[k].frames[0].targets[:1] == [] \
            or parsed[k].frames[0].targets[0].head.pron is None:
        return None
    read = _condition(c, parsed[k], acted)
    if read is None:
        return None
    return Conditional(read[0], read[1], k, (k - 1,), (), after=True)


def _paired(clauses: list[Clause], k: int, then: list[int]) -> bool:
    """"the box shut if it's open, left alone if it's shut": the clause after the "if" is
    the act of the next "if" of its sentence."""
    j = then[0] + 1
    return len(then) == 1 and j < len(clauses) and clauses[j].link == "if" and clauses[j].sentence == clauses[k].sentence


def conditionals(clauses: list[Clause], parsed: list[ParsedClause]) -> list[Conditional]:
    """The conditions of the instruction that the start state can settle (read before the
    clause passes empty the condition clauses)."""
    out: list[Conditional] = []
    before: Head | None = None
    for k, (c, p) in enumerate(zip(clauses, parsed, strict=True)):
        if out and clauses[out[-1].condition].sentence < c.sentence - 1:
            before = None   # "it" is the thing of the "if" just before ("...; if it's off, on")
        read = _condition(c, p, before)
        then = _branch(clauses, k) if read is not None else []
        if (not then or _paired(clauses, k, then)) and (late := _after(clauses, parsed, k)):
            # no act after the "if", or "X if Y, Z if W": the act is the one before it
            out.append(late)
            before = late.head
            continue
        if read is None:
            continue
        nxt = then[-1] + 1 if then else k + 1
        if not then or (nxt < len(clauses) and clauses[nxt].sentence == c.sentence
                        and clauses[nxt].link not in (AND, THEN, "if")):
            continue    # no branch, or a time clause after it ("if not, off when you go")
        otherwise: list[int] = []
        if nxt < len(clauses) and clauses[nxt].sentence == c.sentence and (
                _denial(clauses[nxt]) or (clauses[nxt].link in (AND, THEN) and _words(clauses[nxt])[:1]
                                          and _words(clauses[nxt])[0] in _OTHERWISE)):
            otherwise = [nxt, *_branch(clauses, nxt)] if not _denial(clauses[nxt]) else _branch(clauses, nxt)
        before = read[0]
        out.append(Conditional(read[0], read[1], k, tuple(then), tuple(otherwise)))
    return out


def _holds(g: Grounder, head: Head, state: tuple[Stat, bool]) -> bool | None:
    """Whether the thing is in that state at the start (None: cannot tell)."""
    need, attr = _CHECKED[state[0]]
    doubts = set(g.doubts)
    try:
        ref = g.ground(head, need)
    except OfflineParseError:
        return None
    finally:
        g.doubts = doubts
    seen: set[bool] = set()
    for obj, _ in ref.groups:
        objects = [o for o in g.state.objects.values() if o.id == obj.id] if obj.id is not None \
            else [o for t in ref_types(obj) for o in g.instances(t)]
        seen |= {bool(getattr(o, attr)) for o in objects}
    return (state[1] in seen) if len(seen) == 1 else None


def _holds_now(g: Grounder, drafts: list[Draft]) -> bool:
    """Whether every goal of these drafts holds at the start already (a keep)."""
    goals = [c for d in drafts for c in d.conditions]
    return bool(goals) and all(check_condition(c, g.state).holds for c in goals)


def settle(found: list[Conditional], drafts: dict[int, list[Draft]], g: Grounder) -> None:
    """Drop the goals of the branch whose condition does not hold at the start, and the
    condition's own state; unless nothing would be left ("if the fridge is open, close
    it" with the fridge shut: its goal holds already, and a reading needs one). A failed
    branch that asks what holds already ("if the hamper's open, close it" with it shut)
    is kept as the thing's keep, unless another condition on the thing held (its branch
    says what the thing ends as: "if the lamp's on, off with it; if it's off, on")."""
    kept = dict(drafts)
    settled = [(cond, _holds(g, cond.head, cond.state)) for cond in found]
    taken = {cond.head.text for cond, holds in settled if holds}
    for cond, holds in settled:
        if holds is None:
            continue
        if cond.after:
            kept.pop(cond.condition, None)
            continue
        if not holds or any(k in kept for k in cond.then):
            # (kept when it holds and the branch says nothing more: "if the toaster is off,
            # that's how it should stay" keeps it off)
            kept.pop(cond.condition, None)
        for k in cond.otherwise if holds else cond.then:
            if holds or cond.head.text in taken or not _holds_now(g, drafts.get(k, [])):
                kept.pop(k, None)
    if kept:
        for k in set(drafts) - set(kept):
            del drafts[k]
