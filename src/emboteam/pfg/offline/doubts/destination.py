"""The one destination finder of the points of doubt: where a thing goes, by the words
after it ("Pen's on the floor - up, into the mug", "the keys live in a drawer", "plates
don't live on the coffee table - their home is the shelf", "mug -> desk").

The thing's *window* runs from it to the next thing named that is neither a place nor
listed with it ("the card and the keys, from the table to a drawer"), or to the end of
its sentence, and on over the next sentence when that one names no other thing. Its
destination is a receptacle of the window the catalogue lets it go in
(:meth:`Catalogue.can_place`), led by a *towards* cue (:func:`led`), not where the thing
lies now (that is where it is, not where it goes); a *directional* cue ("into") before
another; a negation rules out the first place after it, led or not ("no longer on the
side table - they're in the box"), unless a *home* cue follows the place ("isn't in the
drawer where it belongs"). A place word of several types names the one the thing fits
("the roll onto the holder": the toilet paper hanger). A thing listed after a colon or a
dash whose window says nothing goes to the place the rule before the mark names
(:func:`head_place`: "pocket things live in the box: the phone, the keys and the card").

Its callers: an unexplained mention's window (:func:`.unexplained.window_goal`, strong
evidence), the ``next_place`` doubt (:func:`doubts`: a thing the reader placed
elsewhere), "leave X on Y" (:mod:`.mention_cues`), and :func:`led` for the contents,
resumed lists and affordances' places. One cue list, ``destination_cues.json`` (schema
:class:`DestinationCues`, checked at load): teach a destination phrasing there.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, fitting_first
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.mention_words import after_preposition
from emboteam.pfg.offline.doubts.rule_words import Words, find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import placed
from emboteam.pfg.offline.knowledge import read
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.catalogue import load_catalogue, place_types
from emboteam.world.goals import Predicate

DESTINATION_CUES_FILE = Path(__file__).with_name("destination_cues.json")
KIND = "next_place"


class DestinationCues(BaseModel):
    model_config = ConfigDict(extra="forbid")
    about: str = ""
    towards: list[Words]
    #: the towards cues tried first ("into" before "on")
    directional: list[str]
    #: marks that join a thing to where it goes with the verb left out ("potato and apple:
    #: fridge"): a receptacle right after one (determiners between) is led by it
    links: list[str] = []
    #: words that send a thing where the thing before it went ("the keys go in the same
    #: spot"); not after "back" (that is where it was)
    same_place: list[Words] = []
    #: words that carry the place or state said before over to a verbless stretch, besides
    #: rule_words.json's "too", "as well", "same for" ("the pan: same deal", "incl the teddy")
    carry_over: list[Words] = []
    #: words before a place that make it where the thing is or comes from ("from", "lying on")
    sources: list[str]
    home: list[Words]
    keep: list[Words]
    #: words that say the place holds already ("the tomato's already in the fridge"): no goal
    described: list[Words]
    #: the predicates of the reader's goals a place of the thing's own words may replace
    replaces: list[str]
    #: how many words a towards cue may stand before its place
    lead: int = Field(3, ge=1, le=6)
    #: the longest window, in words, and how far in it a keep cue reaches (in a run-on
    #: transcript a later "can stay" is another thing's)
    reach: int = Field(18, ge=2, le=40)
    keep_reach: int = Field(14, ge=2, le=40)


@cache
def load_destination_cues(path: Path = DESTINATION_CUES_FILE) -> DestinationCues:
    """The cue file, checked by its schema (a malformed entry is a
    :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming file and entry)."""
    return read(path, DestinationCues)


def led(ctx: DoubtContext, m: int, lo: int = 0) -> str | None:
    """The towards cue that leads to the place named at ``m`` (its first word; from ``lo``
    on, with no mark between), or None: none, or a source word before it ("from the table", "lying on") unless
    the cue is a directional one ("out onto the counter")."""
    data = load_destination_cues()
    start = max(lo, m - data.lead)
    # not "on. le frigo", nor "on the counter tomato -> slices" (the cue's place is named before)
    cues = [ctx.items[b].text for b, e in find(ctx.items, start, m, data.towards)
            if e <= m and all(i.punct is None and not ctx.named_types(i) for i in ctx.items[e:m])]
    if not cues:
        cues = _link(ctx, m, start, data.links)
    if not cues or (cues[-1] not in data.directional and any(i.text in data.sources for i in ctx.items[start:m])):
        return None
    return cues[-1]


def _link(ctx: DoubtContext, m: int, lo: int, links: list[str]) -> list[str]:
    """The mark that leads to the place at ``m`` with the verb left out (determiners
    between), as a one-cue list: a link mark with a thing named just before it ("potato
    and apple: fridge"; not "Status: fridge", nor "the one with the laptop: the mug ..."), or a sentence end when the place is a
    sentence of its own ("why is the basketball on the floor? Bed.")."""
    j = m - 1
    while j > lo and ctx.items[j].det:
        j -= 1
    mark = ctx.items[j].punct if j >= lo else None
    if mark is None or j == 0:
        return []
    if mark in links:  # the thing before it is the one placed, not a landmark ("the one with the laptop:")
        return [mark] if any("pickupable" in _props(t) for t in ctx.named_types(ctx.items[j - 1])) \
            and not after_preposition(ctx, j - 1, ctx.clause_bounds(j - 1)[0]) else []
    ends = load_rule_words().sentence_ends
    alone = m + 1 == len(ctx.items) or ctx.items[m + 1].punct in ends
    return [mark] if mark in ends and alone else []


def linked(ctx: DoubtContext, at: int, m: int) -> bool:
    """Whether a mark or a pronoun stands between a thing and a later place (the place is
    then the thing's own: "except the knife, which goes in a drawer")."""
    links = load_rule_words().contents.own_place_links
    if any(i.text in links for i in ctx.items[at + 1:m]):
        return True
    marks = [j for j in range(at + 1, m) if ctx.items[j].punct is not None]
    # not when the sentence's own verb resumes after an aside ("everything - everything
    # except the laptop - goes in the drawers")
    return bool(marks) and not (marks[-1] + 1 < m and ctx.items[marks[-1] + 1].verb is not None
                                and ctx.items[marks[-1] + 1].noun is None)


def _listed(ctx: DoubtContext, last: int, m: int) -> bool:
    """Whether only determiners, conjunctions, commas and numbers stand between two
    mentions (a list: "the card and the keys")."""
    return all(i.det or i.conj or i.punct == "," or i.number is not None for i in ctx.items[last + 1:m])


def _other_thing(ctx: DoubtContext, m: int, thing: str) -> bool:
    types = ctx.named_types(ctx.items[m])     # a place a cue leads to is no other thing ("their home is the shelf")
    return bool(types) and thing not in types and not after_preposition(ctx, m, ctx.clause_bounds(m)[0]) \
        and led(ctx, m) is None


def window(ctx: DoubtContext, k: int, thing: str) -> tuple[int, int]:
    """[k + 1, end) of the words that may say where the thing at ``k`` goes."""
    ends = set(load_rule_words().sentence_ends)
    limit = min(len(ctx.items), k + 1 + load_destination_cues().reach)
    last, breaks, j = k, 0, k + 1
    while j < limit:
        item = ctx.items[j]
        if item.punct in ends:
            breaks += 1
            if breaks > 1:
                break
        elif _other_thing(ctx, j, thing):
            if not (breaks == 0 and _listed(ctx, last, j)):
                break
            last = j
        j += 1
    return k + 1, j


def present(ctx: DoubtContext, thing: str) -> set[str]:
    """The types of the receptacles the things of the type stand in now."""
    return {ctx.state.obj(o.parent).type for o in ctx.state.of_type(thing) if o.parent is not None}


def destination(ctx: DoubtContext, k: int, thing: str, hi: int | None = None) -> tuple[str, ...]:
    """The scene types of the receptacle the thing named at ``k`` goes in, by its window
    (up to ``hi``), the first the likeliest; none when its words say none (see the
    module's docstring)."""
    data, cat, here = load_destination_cues(), load_catalogue(), place_types(tuple(present(ctx, thing)))
    lo, end = window(ctx, k, thing)
    end = end if hi is None else min(end, hi)
    # an excepted thing goes only where its own words send it, past a mark or a pronoun
    # ("except the knife, which goes in a drawer"; not "everything but the mug goes in the sink")
    excepted = bool(find(ctx.items, max(0, k - 4), k, load_rule_words().contents.excluders))
    homes = {s for s, _ in find(ctx.items, lo, end, data.home)}
    since, found = lo, list[tuple[bool, int, tuple[str, ...]]]()
    for m in range(lo, end):
        # a word that may be a verb names a thing after a determiner ("in the bin")
        types = fitting_first(thing, ctx.named_types(ctx.items[m], verbs_too=m > 0 and ctx.items[m - 1].det))
        if not types or types[0] == thing or "receptacle" not in cat.type(types[0]).properties:
            continue
        fits = cat.can_place(thing, types[0])
        if fits and any(j in homes for j in range(m + 1, min(end, m + 3))):
            return types
        cue = led(ctx, m, lo)
        if any(i.neg for i in ctx.items[since:m]):
            since = m + 1     # "pens don't live on the bed, their home is the box", "no longer on the table"
        elif cue is not None and fits and types[0] not in here and not (excepted and not linked(ctx, k, m)):
            found.append((cue not in data.directional, len(found), types))
    return min(found)[2] if found else ()


def place_before(ctx: DoubtContext, at: int, thing: str) -> tuple[str, ...]:
    """The scene types of the nearest place before ``at`` (within the window's reach) a
    towards cue leads to and the thing can go in, not where it is nor after a negation in
    its stretch: the place a thing named before went to (:func:`same_place`, and an
    additive word's, :func:`.unexplained.carried`)."""
    cat, here = load_catalogue(), place_types(tuple(present(ctx, thing)))
    for m in range(at - 1, max(-1, at - 1 - load_destination_cues().reach), -1):
        types = fitting_first(thing, ctx.named_types(ctx.items[m], verbs_too=m > 0 and ctx.items[m - 1].det))
        if types and types[0] != thing and types[0] not in here and cat.can_place(thing, types[0]) \
                and led(ctx, m) is not None and not any(i.neg for i in ctx.items[ctx.clause_bounds(m)[0]:m]):
            return types
    return ()


def same_place(ctx: DoubtContext, k: int, lo: int, hi: int, thing: str) -> tuple[str, ...]:
    """Where the thing at ``k`` goes when its window sends it to "the same place" (its
    words ``lo``-``hi``): the place named before it (:func:`place_before`), or, "as" another
    thing, where the reading puts that one, else where that one is ("the same place as the
    apple")."""
    data = load_destination_cues()
    said = [e for b, e in find(ctx.items, lo, hi, data.same_place)
            if not any(i.text == "back" for i in ctx.items[max(lo, b - 3):b])]
    if not said:
        return ()
    if said[0] < len(ctx.items) and ctx.items[said[0]].text == "as":
        other = next((ts[0] for m, _, ts in ctx.mentions() if said[0] < m <= said[0] + 3), None)
        if other is None:
            return ()
        goes = [c.receptacle.types for c in ctx.goals if c.predicate is Predicate.inside
                and c.subject.types == (other,) and c.receptacle is not None]
        here = sorted(present(ctx, other))
        return tuple(goes[0]) if goes else tuple(here) if len(here) == 1 else ()
    return place_before(ctx, k, thing)


def head_place(ctx: DoubtContext, k: int, thing: str) -> tuple[str, ...]:
    """The place a rule names before a list the thing at ``k`` stands in ("things that fit
    in a pocket live in the box by the door: that's the phone, the keys and the card",
    "sports stuff lives on the bed - the bat and the ball"): the list runs back from the
    thing over list words and other things to a colon or a dash, and the place is the last
    one before the mark, in its sentence, a towards cue leads to and the thing fits."""
    j, fillers = k - 1, 0
    while j >= 0 and ctx.items[j].punct not in (":", ","):
        item = ctx.items[j]
        if not (item.det or item.conj or item.number is not None or ctx.named_types(item)):
            fillers += 1         # "that's"
            if fillers > 2:
                return ()
        j -= 1
    start = sentence_bounds(ctx.items, k)[0]
    if j <= start:
        return ()
    cat, here = load_catalogue(), place_types(tuple(present(ctx, thing)))
    for m in range(j - 1, start - 1, -1):
        types = fitting_first(thing, ctx.named_types(ctx.items[m]))
        if types and types[0] != thing and cat.can_place(thing, types[0]) and types[0] not in here \
                and led(ctx, m) is not None and not any(i.neg for i in ctx.items[start:m]):
            return types
    return ()


def doubts(ctx: DoubtContext) -> list[Doubt]:
    """``next_place``: a thing the reader placed elsewhere (or held, or switched) placed
    where its own words send it ("the remote lives on the sofa and the keys live in a
    drawer"); a self-correction's places are the correction rules' (corrections.py)."""
    if ctx.corrected:
        return []
    replaces = load_destination_cues().replaces
    out: list[Doubt] = []
    seen: set[str] = set()
    for k, item, types in ctx.mentions():
        thing = types[0]
        if thing in seen or "pickupable" not in _props(thing):
            continue
        # the thing itself (not its slices: "slice it, the slices on the plate"), by type
        mine = tuple(c for c in ctx.goals if c.predicate.value in replaces and c.subject.types == (thing,))
        if any(c.predicate in (Predicate.inside, Predicate.held) for c in mine):
            # a thing placed (or carried) and switched: its place is in doubt, not its state
            # ("put it on the counter and light it")
            mine = tuple(c for c in mine if c.predicate in (Predicate.inside, Predicate.held))
        dest = destination(ctx, k, thing) if mine else ()
        if not dest:
            continue      # a later mention may say where it goes ("phones, cards ... So the phone ... up on a shelf")
        seen.add(thing)
        if any(c.receptacle is not None and set(dest) & set(c.receptacle.types) for c in mine):
            continue     # no place said, or the reader's is one the words may name ("holder")
        alt = placed(thing, dest[0])
        counted = max((c.count for c in mine if c.predicate is Predicate.inside), default=1)
        alt = alt.model_copy(update={"count": counted}) if counted > 1 else alt
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, "; ".join(clause(c) for c in mine)),
                                           Choice(KIND, f"{type_name(thing)}: {clause(alt)}",
                                                  drop=mine, add=(alt,)))))
    return out
