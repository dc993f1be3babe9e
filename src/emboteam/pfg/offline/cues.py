"""Reading a clause the grammar could not, from its cue words and what the scene allows.

The clause grammar (:mod:`~emboteam.pfg.offline.frames`) must accept a clause to read it;
people do not always say things in a shape it knows ("I just need the pan in the sink",
"if you could get a potato cooked and onto a plate"). Such a clause still carries cues:
an act or a state word, the objects it names and the places they go. This reader turns
the cues into candidate frames of three kinds (the clause's act, a state word, a
placement), most specific first, and lets the semantics
(:class:`~emboteam.pfg.offline.semantics.Semantics`) decide: a candidate the scene cannot
ground (no such object, no receptacle that takes it) is dropped, and the first of each
kind that grounds is kept. Whatever it gives is marked unsure (the hybrid front end shows
it to the LLM) and reported with a note saying it was read from its cue words. It never
reads a statement ("the mug's in the cupboard"), a prohibition, or an object after
"except", "not", "instead of".

Kept apart from the grammar on purpose: it never decides what the grammar reads, it only
reads what the grammar left unread.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.clauses import Clause
from emboteam.pfg.offline.errors import OfflineParseError
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.phrases import Frame, Head, Target, np_start, parse_np
from emboteam.pfg.offline.semantics import Draft, Semantics, concat
from emboteam.pfg.offline.tagger import Item

Act = lx.Act
Stat = lx.Stat

_W = word_tables("cues")
#: prepositions (canonical, :data:`lexicon.PREPOSITIONS`) that introduce where an object goes
_PLACE_PREPS = _W.set("place_preps")
#: acts that say nothing about the goal on their own ("get", "leave", "go"): a cue only
#: together with a state word or a place
_GENERIC_ACTS = frozenset({Act.CAUSE, Act.GO, Act.MAKE, Act.VAGUE})
#: words after which a noun phrase is what is NOT meant ("all but the apple", "not the
#: knife", "instead of the cup")
_EXCLUDING = _W.set("excluding")
#: nouns that name no object ("everything", "the room")
_NOT_OBJECTS = _W.set("not_objects")


#: forms of "be": a clause with one and no act is a statement about how things are
_BE = _W.set("be")
#: "should be", "needs to be": a wished state, not a statement
_MODAL_BEFORE_BE = _W.set("modal_before_be")


#: words that open a relative clause ("the potato that's in the sink")
_RELATIVE = _W.set("relative")
#: words that open a subordinate clause ("once it's on there")
_SUBORDINATE = _W.set("subordinate")


def _embedded_be(items: list[Item], k: int) -> bool:
    """Is the "be" at ``k`` inside a relative or subordinate clause ("the potato that's in
    the sink", "once it's on there")? Then it says nothing about the main clause."""
    if k >= 2 and items[k - 1].text in _RELATIVE:
        return True     # "the potato that's ...": a relative clause (not "that's the one")
    return k >= 2 and items[k - 2].text in _SUBORDINATE and (items[k - 1].pron is not None or items[k - 1].noun is not None)


#: past participles of "have gone off" kind (the regular ones end in -ed)
_PARTICIPLES = _W.set("participles")
_PERFECT, _ONGOING = (pattern_tables("cues").pattern(name) for name in ("perfect", "ongoing"))


def _perfect(items: list[Item], k: int) -> bool:
    """Is "have"/"has" at ``k`` a perfect ("the egg and the apple have both gone off"): a
    report of what happened, with no modal before it ("should have")?"""
    after = _PERFECT.end(items, k)
    if after is None:
        return False
    m = after - 1
    verb = items[m].verb
    return items[m].text in _PARTICIPLES or (verb is not None and verb.form == "ed") or (
        verb is None and items[m].noun is None and len(items[m].text) > 4 and items[m].text.endswith("ed"))


def is_statement(items: list[Item]) -> bool:
    """Does the clause say how things are ("the mug is in the cupboard", "the egg has gone
    off")? A form of "be" that no modal turns into a wish ("should be", "needs to be") and
    that is not inside a relative or subordinate clause, a perfect, or how things go on
    ("my keys keep going missing", "the fork sitting in the sink")."""
    return any((it.text in _BE and not (k > 0 and items[k - 1].text in _MODAL_BEFORE_BE)
                and not _embedded_be(items, k)) or (k > 0 and (_perfect(items, k) or _ONGOING.at(items, k - 1)))
               for k, it in enumerate(items))


@dataclass
class Cues:
    """What a clause says, word by word, without its structure."""

    acts: list[tuple[Act, str]] = field(default_factory=list)
    states: list[tuple[Stat, bool]] = field(default_factory=list)
    #: noun phrases acted on, in order
    objects: list[Head] = field(default_factory=list)
    #: noun phrases after a place preposition, with that preposition
    places: list[tuple[str, Head]] = field(default_factory=list)
    negated: bool = False


def _act_of(it: Item, nxt: Item | None) -> Act | None:
    """The act a verb names, a switch verb resolved by its particle ("turn ... off")."""
    if it.verb is None:
        return None
    act = it.verb.sense.act
    if act is Act.SWITCH and nxt is not None and nxt.particle in ("on", "off"):
        return Act.SWITCH_ON if nxt.particle == "on" else Act.SWITCH_OFF
    return act


def collect(items: list[Item]) -> Cues:
    """The cues of a clause: verbs, state words, noun phrases and the places they go."""
    cues = Cues()
    j, n = 0, len(items)
    prep: str | None = None
    excluded = False
    while j < n:
        it = items[j]
        if it.neg and not excluded:
            cues.negated = True
        if it.text in _EXCLUDING:
            excluded = True        # "everything except the apple": the apple is left alone
            j += 1
            continue
        if it.prep is not None and lx.PREPOSITIONS.get(it.text) in _PLACE_PREPS \
                and j + 1 < n and np_start(items[j + 1]):
            prep = lx.PREPOSITIONS[it.text]
            j += 1
            continue
        if np_start(it) and not (it.verb is not None and it.det is False and it.noun is None):
            head, k = parse_np(items, j)
            if head is not None and k > j:
                if excluded:
                    if cues.objects:     # "all the fruit except the apple"
                        cues.objects[-1].excluded.append(head)
                elif head.noun is not None and head.noun.concept.kind in _NOT_OBJECTS:
                    pass           # "leave everything else": no object to act on
                elif prep is not None:
                    cues.places.append((prep, head))
                else:
                    cues.objects.append(head)
                prep = None
                excluded = False
                j = k
                continue
        prep = None
        if it.punct is not None and cues.objects and not cues.places:
            cues.objects = []      # "leave the rest, I need the pan in the sink": the span with the place
        act = _act_of(it, items[j + 1] if j + 1 < n else None)
        if act is not None and it.noun is None:
            cues.acts.append((act, it.text))
        elif it.state is not None and (it.verb is None or it.prep is None):
            cues.states.append(it.state)
        j += 1
    return cues


def _targets(objects: list[Head], places: list[tuple[str, Head]]) -> list[Target]:
    """One target per object, every object going to the last place named."""
    if not places:
        return [Target(h) for h in objects]
    prep, dest = places[-1]
    role = "in" if prep == "in" else "near" if prep in ("near", "by") else "on"
    return [Target(h, [dest], role) for h in objects]


def candidate_frames(clause: Clause) -> list[tuple[str, Frame]]:
    """Frames the clause's cues allow, each with its kind, most specific first: the
    clause's own act on its objects ("act"), a state word asked of them ("state"), a
    placement when places are said ("place"). The caller keeps at most one of each kind,
    and no placement beside an act that already places."""
    if is_statement(clause.items):
        return []      # "the mug's in one of the cupboards, I think": where it is, not a request
    cues = collect(clause.items)
    if cues.negated or not cues.objects:
        return []      # "don't ...": a prohibition is no goal; no object: nothing to act on
    text = clause.text
    out: list[tuple[str, Frame]] = []
    for act, verb in cues.acts:
        if act in _GENERIC_ACTS or (act is Act.PLACE and not cues.places):
            continue
        places = cues.places if act in (Act.PLACE, Act.TRASH) else []
        out.append(("act", Frame(act, verb, _targets(cues.objects, places), text=text)))
    for state in cues.states:
        out.append(("state", Frame(Act.CAUSE, "get", [Target(h) for h in cues.objects], state=state,
                                   text=text)))
    if cues.places:
        out.append(("place", Frame(Act.PLACE, "put", _targets(cues.objects, cues.places), text=text)))
    return out


def cue_mentions(clause: Clause) -> list[Head]:
    """The noun phrases of a clause the grammar found none in ("where's the pot?")."""
    cues = collect(clause.items)
    return [*cues.objects, *(h for _, h in cues.places)]


def read_cues(clause: Clause, semantics: Semantics, ci: int) -> list[Draft]:
    """The drafts of a clause read from its cue words (:mod:`~emboteam.pfg.offline.cues`):
    the first candidate of each kind that the scene grounds, no placement beside an act
    that already places."""
    out: list[Draft] = []
    kinds: set[str] = set()
    for kind, frame in candidate_frames(clause):
        if kind in kinds or (kind == "place" and "places" in kinds):
            continue
        try:
            got = semantics.frame(frame, ci)
        except OfflineParseError:
            continue
        if got:
            out = concat(out, got)
            kinds.add(kind)
            if frame.act in (Act.PLACE, Act.TRASH):
                kinds.add("places")
    return out
