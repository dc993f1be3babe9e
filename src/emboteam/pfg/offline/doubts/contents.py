"""Point of doubt: a receptacle's contents named as a set ("everything on X except Y goes
in Z", "clear the shelf onto the bed, all but the lamp", "whatever is in the basin goes in
a cupboard, the knife excepted - that one lives in a drawer").

Every quantifier or emptying verb of the instruction is tried (not only the first): its
source is the receptacle after a source preposition (or right after the emptying verb;
"up there", "empty it": the receptacle named last before), its destination a receptacle
after a placing preposition (or the bin for a throwing verb), and its exceptions the things
named after an excluder ("except the mug") or before a post-positive one ("the knife
excepted"). The set is resolved against the scene: the pickupable objects whose parent is
the source now, minus the excepted ones. When the source type has several instances the
set is that of the instance holding an excepted thing, of all of them for a plural
("the shelves"), else one alternative per instance that holds something (the point of
doubt: "everything up there" with two shelves). An excepted thing keeps its present place
(a goal), unless its own words send it somewhere ("..., which goes in a drawer"). The
words are data (``rule_words.json``, ``contents``).

The things may be picked out by a property instead of a name (:mod:`.properties`,
``properties.json``): "everything small on the stand" narrows the set, "apart from what's
plugged in" leaves its things out, "anything on it that runs on electricity stays" keeps
them out of another phrase's set over the same receptacle, and "all the breakables into
the box" with no receptacle named takes them from the whole room. A vague property
("small") offers each of its tests as an alternative.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import replace

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.context import type_props as _props
from emboteam.pfg.offline.doubts.destination import destination, led, linked
from emboteam.pfg.offline.doubts.properties import Picked, Test, alternatives, properties_in
from emboteam.pfg.offline.doubts.rule_words import Contents, find, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import one_object, placed
from emboteam.pfg.offline.morphology import verb_lemma
from emboteam.pfg.sentences import type_name
from emboteam.world.catalogue import load_catalogue, place_types
from emboteam.world.goals import Condition, Predicate
from emboteam.world.state import ObjectState

KIND = "contents"
#: the goals a contents choice never replaces: a device's state is told for itself
DEVICE_STATES = frozenset({Predicate.open, Predicate.closed, Predicate.switched_on, Predicate.switched_off})
#: the label of a vague property's less likely tests (its prior in priors.json)
OTHER_TEST = "other_property_test"
#: how many per-instance alternatives a source of several instances may offer
MAX_SOURCES = 3


def _emptying(text: str, words: Contents) -> bool:
    """An emptying verb in any form ("clears", "emptied"; not all are lexicon verbs)."""
    found = verb_lemma(text)
    forms = {text, found[0] if found is not None else text, text.removesuffix("s"), text.removesuffix("es"),
             text.removesuffix("ed"), text.removesuffix("ied") + "y", text.removesuffix("ing")}
    return bool(forms & set(words.emptying_verbs))


def _triggers(ctx: DoubtContext, words: Contents) -> list[int]:
    return [k for k, item in enumerate(ctx.items) if item.text in words.quantifiers or _emptying(item.text, words)]


def _named(ctx: DoubtContext, j: int) -> tuple[str, ...]:
    """The scene types a word names; after a determiner also a word that may be a verb
    ("the shelves")."""
    return ctx.named_types(ctx.items[j], verbs_too=j > 0 and ctx.items[j - 1].det)


def _place_before(ctx: DoubtContext, k: int, words: Contents) -> tuple[int, str] | None:
    """The receptacle named last before ``k``; not a landmark of it ("the counter by the
    sink ... empty it": the counter)."""
    before = [(m, ts[0]) for m, _, ts in ctx.mentions() if m < k and "receptacle" in _props(ts[0])]
    while len(before) > 1 and before[-1][0] - before[-2][0] <= 3 and \
            any(i.text in words.landmark_preps for i in ctx.items[before[-2][0] + 1:before[-1][0]]):
        before.pop()
    return before[-1] if before else None


def _source(ctx: DoubtContext, k: int, end: int, words: Contents) -> tuple[int, str] | None:
    """The receptacle whose contents are meant: after a source preposition (or right after
    an emptying verb) within reach; "in there", "up there", "empty it": the receptacle
    named last before."""
    emptying = _emptying(ctx.items[k].text, words)
    for j in range(k + 1, min(end, k + 3 + 3 * _remainder(ctx, k, words))):     # "the rest of what's on it"
        if ctx.items[j].text in words.pronoun_sources or (ctx.items[j].text in words.pronoun_places and (
                emptying or ctx.items[j - 1].text in words.source_preps
                or (j == k + 1 and ctx.items[j].text in words.pronoun_places_after))):
            # what is left of the place an emptying verb named before ("clear that sofa:
            # ..., and the rest of what's on it")
            emptied = [found for e in _triggers(ctx, words) if e < k and _emptying(ctx.items[e].text, words)
                       and (found := _source(ctx, e, end, words)) is not None] if _remainder(ctx, k, words) else []
            return emptied[-1] if emptied else _place_before(ctx, k, words)
    for m in range(k + 1, min(end, k + words.reach)):
        types = _named(ctx, m)
        if types and not _is_class(ctx, m):
            if "receptacle" not in _props(types[0]):
                return None     # "all three vases on the counter": things, not contents
            lead = [i.text for i in ctx.items[max(k + 1, m - 2):m]]
            if emptying or any(w in words.source_preps for w in lead):
                return m, types[0]
    return None


def _remainder(ctx: DoubtContext, k: int, words: Contents) -> bool:
    """Whether the trigger names what is left ("the rest", "everything else")."""
    return any(i.text in words.remainder for i in ctx.items[k:k + 2])


def _aside(ctx: DoubtContext, j: int, end: int) -> set[int]:
    """The things an aside right after the quantified phrase lists as examples of the set
    ("everything in it - the cloth, the soap, the whole shebang - goes to the counter"):
    between two marks (a dash, a bracket; not a colon's list: "clear the desk: the pen goes
    in the drawer") up to the phrase's verb, no place a cue leads to."""
    while j < end and ctx.items[j].punct is None and ctx.items[j].verb is None and not ctx.named_types(ctx.items[j]):
        j += 1
    if j >= end or ctx.items[j].punct != ",":
        return set()
    out: set[int] = set()
    for m in range(j + 1, end):
        item = ctx.items[m]
        if item.verb is not None and item.noun is None:     # closed by a mark after the last thing
            return out if out and any(i.punct is not None for i in ctx.items[max(out) + 1:m]) else set()
        types = ctx.named_types(item)
        if types and (led(ctx, m) is not None or "pickupable" not in _props(types[0])):
            break
        if types:
            out.add(m)
    return set()


def _span_end(ctx: DoubtContext, j: int, end: int, words: Contents) -> int:
    """Where an excepted list ends: a verb, a sequence word or the sentence's end
    (marks between the things do not end it); a link word right after the excluder is a
    determiner ("except that bar of soap")."""
    first = j
    while j < end:
        item = ctx.items[j]
        if item.verb is not None and item.noun is None and j > first and ctx.items[j - 1].punct is not None:
            # an aside between marks with the list going on after it ("except the candle
            # (lit, please) and the soap bottle")
            resume = next((n + 1 for n in range(j + 1, min(end, j + 4)) if ctx.items[n].punct is not None
                           and n + 1 < end and ctx.items[n + 1].conj), None)
            if resume is not None:
                j = resume
                continue
        if item.seq is not None or (item.verb is not None and item.noun is None) \
                or (item.text in words.own_place_links and j > first):
            return j
        j += 1
    return end


def _excluding(ctx: DoubtContext, start: int, end: int, words: Contents) -> list[tuple[int, int]]:
    """The excluders between ``start`` and ``end``; not a "not" after a copula, which says
    what a named thing is not ("the sponge is not food"), not what is left out ("anything
    that isn't a pillow")."""
    return [(b, e) for b, e in find(ctx.items, start, end, words.excluders)
            if not (b > 1 and ctx.items[b].text == "not" and ctx.items[b - 1].text in words.copulas
                    and ctx.named_types(ctx.items[b - 2]))]


def _excepted(ctx: DoubtContext, start: int, end: int, words: Contents) -> list[tuple[int, tuple[str, ...]]]:
    """(position, types) of each thing excepted: named after an excluder ("except the
    watch", "all but the mug and the phone") or just before a post-positive one ("the
    knife excepted"); every pickupable type the word may name ("the dishes")."""
    spots: list[tuple[int, tuple[str, ...]]] = []
    for _, after in _excluding(ctx, start, end, words):
        stop = _span_end(ctx, after, end, words)
        spots += [(m, ctx.named_types(ctx.items[m], verbs_too=True)) for m in range(after, stop)]
    for at, _ in find(ctx.items, start, end, words.post_excluders):
        named = [(m, types) for m, _, types in ctx.mentions() if start <= m < at]
        spots += named[-1:]
    return [(m, types) for m, types in spots if types]


def _staying(ctx: DoubtContext, start: int, end: int, words: Contents) -> list[tuple[int, tuple[str, ...]]]:
    """The things said to stay ("..., the soap bottle stays by the sink"): out of the set,
    but, unlike an excepted thing, no sign of which instance of the source is meant ("the
    laptop stays put on the other stand")."""
    return _pickupable([(m, types) for m, _, types in ctx.mentions() if start <= m < end
                        and any(i.text in words.stay_verbs for i in ctx.items[m + 1:m + 3])])


def _pickupable(spots: list[tuple[int, tuple[str, ...]]]) -> list[tuple[int, tuple[str, ...]]]:
    return [(m, tuple(t for t in types if "pickupable" in _props(t))) for m, types in spots
            if any("pickupable" in _props(t) for t in types)]


def _which(types: tuple[str, ...], present: set[str]) -> list[str]:
    """The types an excepted word means: those the source holds ("the dishes": plates
    and bowls), else the likeliest."""
    return [t for t in types if t in present] or [types[0]]


def _destination(ctx: DoubtContext, k: int, src_at: int, end: int, source: str,
                 skip: set[int], excepted: set[str], words: Contents) -> str | None:
    """The receptacle a placing preposition leads to after the trigger, with only excepted
    things named between ("clear my desk: the mug goes on ..." is a list, not contents)."""
    for m, _, types in ctx.mentions():
        if not min(k, src_at) < m < end or m == src_at or types[0] == source or m in skip:
            continue
        if "receptacle" in _props(types[0]) and \
                led(ctx, m, min(k, src_at) + 1) is not None:
            return types[0]
        if "pickupable" in _props(types[0]) and m > max(k, src_at) and not set(types) & excepted:
            return None
    start, _ = sentence_bounds(ctx.items, k)
    if any(i.verb is not None and i.verb.sense.act.value in words.trash_acts for i in ctx.items[start:end]):
        return words.trash_place
    return None


def _holders(ctx: DoubtContext, source: str, kinds: frozenset[str] | None = None) -> list[ObjectState]:
    """The instances of the source type, those holding most pickupable things first; a
    sink or a tub is also its basin ("everything in the sink": on the sink or in its basin),
    of ``kinds`` when the word names only one of them ("in the basin")."""
    held = Counter(o.parent for o in ctx.state.objects.values() if o.parent is not None and o.has("pickupable"))
    objs = [o for t in sorted(place_types((source,)) if kinds is None else kinds)
            for o in ctx.state.of_type(t) if held[o.id]]
    return sorted(objs, key=lambda o: -held[o.id])


def _source_sets(ctx: DoubtContext, src_at: int, source: str, excepted: set[str]) -> list[list[ObjectState]]:
    """The instances of the source meant: all of them for a plural ("the shelves"), else
    each instance that holds something, as alternatives, those holding more of the
    excepted things first ("everything on the TV stand except the TV": the TV's stand),
    then the fuller ones."""
    holders = _holders(ctx, source, frozenset({source, *(set(_named(ctx, src_at)) & place_types((source,)))}))
    item = ctx.items[src_at]
    if len(holders) <= 1 or (item.noun is not None and item.noun.plural):
        return [holders] if holders else []
    # a sink and its basin are one place
    ids = {h.id for h in holders}
    groups = [[h, *(b for b in holders if b.parent == h.id)] for h in holders if h.parent not in ids]

    def excepted_there(group: list[ObjectState]) -> int:
        here = {h.id for h in group}
        return len({o.type for o in ctx.state.objects.values() if o.parent in here} & excepted)
    return sorted(groups, key=lambda g: -excepted_there(g))[:MAX_SOURCES]


def _inside(ctx: DoubtContext, holders: Sequence[ObjectState]) -> list[str]:
    ids = {h.id for h in holders}
    return [o.id for o in ctx.state.objects.values()
            if o.parent in ids and o.has("pickupable")]


def _now(ctx: DoubtContext, type_: str, source: str) -> str:
    """Where an excepted thing is now: the source's instance holding it (the sink, not
    its basin, for a sponge on the sink's edge), else the source."""
    cat = load_catalogue()
    here = {ctx.state.obj(o.parent).type for o in ctx.state.objects.values()
            if (cat.source_type(o.type) or o.type) == type_ and o.parent is not None}
    return next(iter(sorted(here & place_types((source,)))), source)


def _goal(type_: str, place: str, count: int) -> Condition:
    c = placed(type_, place)
    return c.model_copy(update={"count": count}) if count > 1 else c


def _closed_again(ctx: DoubtContext, source: str) -> list[Condition]:
    """A source that is closed now is closed again once emptied (the fridge, a cabinet:
    taking things out opens it; the person left it shut)."""
    objs = list(ctx.state.of_type(source))
    if objs and all(o.has("openable") and not o.is_open for o in objs):
        return [one_object(Predicate.closed, source)]
    return []


def _placed_elsewhere(ctx: DoubtContext, start: int, end: int, places: set[str]) -> list[Condition]:
    """The placements another sentence gives things ("clear the counter into the drawers.
    ... toilet roll from the counter -> holder"): their things are no part of the set."""
    inside = {t for m, _, ts in ctx.mentions() if start <= m < end for t in ts}
    outside = {t for m, _, ts in ctx.mentions() if not start <= m < end for t in ts}
    return [c for c in ctx.goals if c.predicate is Predicate.inside and c.receptacle is not None
            and not ref_types(c.receptacle) & places and ref_types(c.subject) & outside
            and not ref_types(c.subject) & inside]


def _assigned(ctx: DoubtContext, o: ObjectState, holders: Sequence[ObjectState], goals: list[Condition]) -> bool:
    """Whether a placement of another sentence is about this object: by its id, or by its
    type when no instance of the type stands outside the source."""
    here = {h.id for h in holders}
    alone = all(x.parent in here for x in ctx.state.of_type(o.type))
    return any(c.subject.id == o.id or (c.subject.id is None and o.type in c.subject.types and alone)
               for c in goals)


def _choice(ctx: DoubtContext, holders: list[ObjectState], source: str, dest: str,
            excepted: dict[str, str | None], elsewhere: list[Condition],
            having: tuple[str, Callable[[ObjectState], bool]] | None = None,
            stays: Callable[[ObjectState], bool] | None = None) -> Choice | None:
    cat = load_catalogue()
    objs = [ctx.state.obj(o) for o in _inside(ctx, holders)]
    # a property picks the things out ("everything small on it"): the others stay
    objs = [o for o in objs if having is None or having[1](o)]
    types = Counter(cat.source_type(o.type) or o.type for o in objs if not _assigned(ctx, o, holders, elsewhere))
    # what cannot go there is no part of the set ("everything into the cabinet": not the knife)
    moved = {t: n for t, n in types.items()
             if t not in excepted and t != dest and cat.can_place(t, dest)}
    if not moved:
        return None
    # an excepted thing keeps its place, also on another instance of the source
    all_holders = {h.id for h in _holders(ctx, source)}
    every = Counter(cat.source_type(ctx.state.obj(o).type) or ctx.state.obj(o).type
                    for o in _inside(ctx, _holders(ctx, source)))
    # also what stands on those things ("the tomato on the plate on the counter")
    nested = {o.type for o in ctx.state.objects.values() if o.has("pickupable")
              and set(ctx.state.ancestors(o.id)) & all_holders}
    kept = {t: n for t, n in every.items() if t in excepted}
    add = [_goal(t, dest, n) for t, n in moved.items()]
    add += [_goal(t, excepted[t] or _now(ctx, t, source), n) for t, n in kept.items()]
    add += [placed(t, p) for t, p in excepted.items() if p is not None and t not in kept]
    # what a keep by property names stays, also a thing nobody carries ("anything on it
    # that runs on electricity stays where it is")
    add += [placed(o.type, source) for o in ctx.state.objects.values()
            if stays is not None and o.parent in {h.id for h in holders} and stays(o)]
    add += _closed_again(ctx, source)
    touched = set(moved) | set(kept) | {t for t, p in excepted.items() if p is not None}
    # a goal for a touched type is replaced when it is about the same things: the type has
    # no instance outside the source ("the loo roll stays on the loo" beside a counter's)
    outside = {cat.source_type(o.type) or o.type for o in ctx.state.objects.values()
               if o.parent is not None and o.parent not in {h.id for h in holders}}
    # ... and so is a goal sending another instance's contents there (the reader took
    # every shelf; this alternative is one of them)
    # (not a device's state: "shut the laptop" stays whatever the set is)
    drop = tuple(c for c in ctx.goals if c not in add and c.predicate not in DEVICE_STATES and (
        (ref_types(c.subject) & touched and not (ref_types(c.subject) & outside and c.receptacle is not None
                                                  and not ref_types(c.receptacle) & {source, dest}))
        or (ref_types(c.subject) & (set(every) | nested) and c.receptacle is not None
            and dest in ref_types(c.receptacle))))
    how = f"what is in/on the {type_name(source)} goes to the {type_name(dest)}" + (
        f", except {', '.join(type_name(t) for t in excepted)}" if excepted else "") + (
        f", those {having[0]}" if having is not None else "")
    return Choice("all_contents", how, drop=drop, add=tuple(dict.fromkeys(add)))


def _having(ctx: DoubtContext, k: int, src_at: int, end: int, exc: tuple[int, int] | None = None,
            ) -> list[tuple[str, Callable[[ObjectState], bool]]]:
    """The ways of reading the properties that pick the things out, from the quantifier to
    the phrase's verb ("everything small on the stand", "anything on it that runs on
    electricity"; ``properties.json``), and those that leave things out, after an
    excluder in ``exc`` ("apart from what's plugged in")."""
    stop = k + 1
    while stop < min(end, max(k, src_at) + 10):
        item = ctx.items[stop]
        if stop > src_at + 1 and item.verb is not None and item.noun is None:
            break
        stop += 1
    stop += 4       # a property phrase may open with its verb ("runs on electricity")

    def thing(j: int) -> bool:
        return bool(ctx.named_types(ctx.items[j]))
    words = load_rule_words().contents
    spans = [] if exc is None else [(after, _span_end(ctx, after, exc[1], words))
                                    for _, after in _excluding(ctx, exc[0], exc[1], words)]
    # after an excluder the property names the things left alone ("apart from what's plugged in")
    left_out = [replace(p, negated=True) for lo, hi in spans for p in properties_in(ctx.items, lo, hi, thing)]
    picked = [p for p in [*properties_in(ctx.items, k + 1, min(end, stop), thing), *_classes(ctx, k + 1, min(end, stop))]
              if not any(lo <= p.start < hi for lo, hi in spans)]
    return alternatives(picked + left_out)


def _is_class(ctx: DoubtContext, j: int) -> bool:
    """Whether the word at ``j`` names a class of things ("fruit and veg", "cutlery"; a
    lexicon category): under a quantifier it picks the set out like a property."""
    noun = ctx.items[j].noun
    return noun is not None and noun.concept.kind == "category" and bool(ctx.named_types(ctx.items[j]))


def _classes(ctx: DoubtContext, lo: int, hi: int) -> list[Picked]:
    """The class nouns between ``lo`` and ``hi``, each as a property: its types."""
    return [Picked(j, j + 1, noun.concept.name, (Test(types=list(noun.concept.types)),))
            for j in range(lo, hi) if _is_class(ctx, j) and (noun := ctx.items[j].noun) is not None]


def _left_alone(ctx: DoubtContext, k: int, source: str, words: Contents,
                ways: list[tuple[str, Callable[[ObjectState], bool]]],
                ) -> tuple[list[tuple[str, Callable[[ObjectState], bool]]], Callable[[ObjectState], bool] | None]:
    """``ways`` without the things another quantified phrase keeps by a property on the
    same receptacle ("anything on it that runs on electricity stays where it is;
    everything else on the desk goes into the box"), and the test of the kept ones."""
    kept: list[tuple[str, Callable[[ObjectState], bool]]] = []
    for k2 in _triggers(ctx, words):
        _, end2 = sentence_bounds(ctx.items, k2)
        found = _source(ctx, k2, end2, words) if k2 != k else None
        if found is None or found[1] != source or \
                not any(i.text in words.stay_verbs for i in ctx.items[k2:end2]):
            continue
        kept += _having(ctx, k2, found[0], end2)[:1]
        # "..., and so do the book and the bowl": named things kept beside them
        also = {t for _, after in find(ctx.items, k2, end2, words.stay_too)
                for m, _, ts in ctx.mentions() if after <= m < _span_end(ctx, after, end2, words) for t in ts}
        if also:
            kept.append((", ".join(sorted(also)), lambda o, also=also: o.type in also))  # type: ignore[misc]
    if not kept:
        return ways, None

    def stays(o: ObjectState) -> bool:
        return any(t(o) for _, t in kept)

    def without(how: str, test: Callable[[ObjectState], bool]) -> tuple[str, Callable[[ObjectState], bool]]:
        return f"{how}, not {', '.join(h for h, _ in kept)}", lambda o: test(o) and not stays(o)
    return [without(h, t) for h, t in ways or [("all", lambda o: True)]], stays


def _sentence_with_exceptions(ctx: DoubtContext, k: int, words: Contents) -> tuple[int, int, int]:
    """The trigger's sentence, and where its exceptions may end: the next sentence too
    when it opens with an excluder ("clear the counter. NOT the candle") or adds a keep to
    them ("... except the soap. Wait, no, the spray stays out too")."""
    start, end = sentence_bounds(ctx.items, k)
    if end + 1 < len(ctx.items):
        after = sentence_bounds(ctx.items, end + 1)[1]
        if find(ctx.items, end + 1, end + 2, words.excluders) or (
                any(i.text in words.stay_verbs for i in ctx.items[end + 1:after])
                and find(ctx.items, end + 1, after, words.also_stays)):
            return start, end, after
    return start, end, end


def _enumerated(ctx: DoubtContext, k: int, end: int) -> list[str]:
    """The things a list after a colon names when the quantified phrase heads it
    ("everything small in here goes in the safe: the keys, the phone"): the list, not the
    property, is the set."""
    colon = next((j for j in range(k + 1, end) if ctx.words[j] == ":"), None)
    if colon is None:
        return []
    return list(dict.fromkeys(t for j in range(colon + 1, end) for t in ctx.named_types(ctx.items[j])[:1]))


def _anywhere(ctx: DoubtContext, k: int, start: int, end: int, exc_end: int, words: Contents) -> Doubt | None:
    """Things picked out by a property alone, wherever they are ("all the breakables into
    the box", "anything in here over four kilos goes onto the bed"): every carriable thing
    of the room that satisfies it goes to the destination, the excepted ones stay."""
    ways = _having(ctx, k, k, end, (start, exc_end))
    if not ways:
        return None
    cat = load_catalogue()
    listed = _enumerated(ctx, k, end)
    if listed:
        named = set(listed)
        ways = [(f"listed ({', '.join(type_name(t) for t in listed)})",
                 lambda o: (cat.source_type(o.type) or o.type) in named)]
    excepted = {t for _, types in _excepted(ctx, start, exc_end, words) for t in types}
    classes = {j for j in range(k + 1, end) if _is_class(ctx, j)}
    dest = _destination(ctx, k, k, end, "", classes, excepted, words)
    if dest is None:
        return None
    # a thing the reading already places is named, not picked out by the property (nor
    # placed by the class noun's own reading: "every bit of fruit" read as the apple)
    by_name = {t for m, _, ts in ctx.mentions() if not _is_class(ctx, m) for t in ts}
    placed_already = {t for c in ctx.goals if c.predicate is Predicate.inside for t in ref_types(c.subject) & by_name}
    choices: list[Choice] = []
    for i, (how, test) in enumerate(ways):
        found = Counter(cat.source_type(o.type) or o.type for o in ctx.state.objects.values()
                        if o.has("pickupable") and not o.gone and test(o) and o.type not in excepted | placed_already
                        and o.type != dest and cat.can_place(o.type, dest))
        if not found:
            continue
        add = tuple(_goal(t, dest, n) for t, n in sorted(found.items()))
        if set(add) <= set(ctx.goals):
            continue        # the reading as read (a vague property's other tests are still offered)
        drop = tuple(c for c in ctx.goals if c.predicate is Predicate.inside and c not in add
                     and ref_types(c.subject) and ref_types(c.subject) <= set(found))
        c = Choice("all_contents" if i == 0 else OTHER_TEST, f"what is {how} goes to the {type_name(dest)}", drop, add)
        if all((c.add, c.drop) != (o.add, o.drop) for o in choices):
            choices.append(c)
    return Doubt(KIND, ctx.items[k].text, (Choice(AS_READ, "the things as read"), *choices)) if choices else None


def _doubt_at(ctx: DoubtContext, k: int, words: Contents) -> Doubt | None:
    start, end, exc_end = _sentence_with_exceptions(ctx, k, words)
    found = _source(ctx, k, end, words)
    if found is None:
        # a quantifier with a property and no receptacle: the whole room ("all the
        # breakables"); an emptying verb names its receptacle ("clear what's loose on it")
        return _anywhere(ctx, k, start, end, exc_end, words) if ctx.items[k].text in words.quantifiers else None
    src_at, source = found
    excepting = _excepted(ctx, start, exc_end, words)
    spots = excepting + _staying(ctx, start, exc_end, words)
    named = {t for _, types in spots for t in types}
    # a place after an excepted thing is its own ("except the knife, which goes in a
    # drawer"); not for a thing nobody moves ("so not the telly itself, goes into the box")
    own = {m for m, _, ts in ctx.mentions() if spots and m > spots[0][0] and linked(ctx, spots[0][0], m)
           and any("pickupable" in _props(t) for t in spots[0][1])}
    rest = _remainder(ctx, k, words)
    dest = _destination(ctx, k, max(k, src_at) if rest else src_at, end, source,
                        own | _aside(ctx, max(k, src_at) + 1, end), named, words)
    if dest is None:
        return None
    # what is left: every thing the reading places elsewhere is out ("paper onto the
    # coffee table, and the rest of what's on it onto the armchair")
    elsewhere = [c for c in ctx.goals if c.predicate is Predicate.inside and c.receptacle is not None
                 and not ref_types(c.receptacle) & {source, dest}] if rest \
        else _placed_elsewhere(ctx, start, exc_end, {source, dest})
    choices: list[Choice] = []
    # the instance holding the things excepted, or those placed elsewhere when the rest is meant
    marks = {t for _, types in excepting for t in types} | {t for c in elsewhere if rest for t in ref_types(c.subject)}
    found_ways, stays = _left_alone(ctx, k, source, words, _having(ctx, k, src_at, end, (start, exc_end)))
    ways: list[tuple[str, Callable[[ObjectState], bool]] | None] = [*found_ways] or [None]
    for holders in _source_sets(ctx, src_at, source, marks):
        present = {ctx.state.obj(o).type for o in _inside(ctx, holders)}
        # a thing nobody can carry has no place of its own ("not the telly itself, goes into the box"),
        # nor is an excepted thing's own place where the set goes ("all but the book - goes in the drawers")
        excepted = {t: next((d for d in destination(ctx, m, t, exc_end) if d != dest), None)
                    if "pickupable" in _props(t) else None for m, types in spots for t in _which(types, present)}
        for having in ways:
            c = _choice(ctx, holders, source, dest, excepted, elsewhere, having, stays)
            if c is not None and having is not ways[0]:
                c = replace(c, label=OTHER_TEST)     # a vague property read less likely ("small": under 200 g)
            if c is not None and not c.drop and set(c.add) <= set(ctx.goals):
                if not choices and len(ways) == 1:
                    return None     # the likeliest set is the reading as read
                continue            # (a vague property's other tests are still offered)
            if c is not None and all((c.add, c.drop) != (o.add, o.drop) for o in choices):
                choices.append(c)
    if not choices:
        return None
    return Doubt(KIND, ctx.items[k].text, (Choice(AS_READ, "the things as read"), *choices))


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().contents
    out: list[Doubt] = []
    seen: set[tuple[Condition, ...]] = set()
    for k in _triggers(ctx, words):
        d = _doubt_at(ctx, k, words)
        if d is not None and d.choices[1].add not in seen:
            seen.add(d.choices[1].add)
            out.append(d)
    return out
