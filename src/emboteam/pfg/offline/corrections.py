"""Self-corrections, one mechanism: a marker ("no wait", "sorry", "I mean") splits what was
said into the retracted part and the correcting part; what the correcting part starts with
names the slot it corrects (the place, the thing, a list member taken out / kept / swapped,
the state, a clause said again, the act called off) and only that slot of the retracted part
is replaced: the rest of the earlier request, and what the correcting part goes on to say
("the pen stays on the desk"), stand. Where the slot is in doubt, :func:`correct` also
returns the other readings; the front end offers each as a candidate of kind ``correction``.
Done on the tagged items, before clause segmentation; the words are data (``words.json``,
``corrections``). The table of slots: docs/offline_parser.md, "Self-corrections".
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.lexicon import Act
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.retractions import retract
from emboteam.pfg.offline.tagger import Item
from emboteam.world.catalogue import load_catalogue

#: the kind of the point of doubt a correction's other readings make
KIND = "correction"

_W = word_tables("corrections")
_CALLED_OFF, _RESTART = (pattern_tables("corrections").pattern(name) for name in ("called_off", "restart"))
#: marker word sequences; a bare "no"/"sorry" is a marker only between punctuation
_MARKERS = _W.phrases("markers")
_FIRST_WORDS = frozenset(m[0] for m in _MARKERS)
_FILLERS = _W.phrases("fillers")
_NEGATORS, _ONLY, _ALSO_ONE = _W.set("negators"), _W.set("only"), _W.set("also")
_ALSO = _W.phrases("also")
_SWAPS = _W.phrases("swaps")
_NOT_PLACES = _W.set("not_places")
_PRONOUNS = _W.set("pronouns")
_ARTICLES = _W.set("articles")
_BREAK = frozenset(".!?;:,")
#: acts whose "on" / "off" is a particle, no place ("turn on the lamp")
_SWITCHING = frozenset({Act.SWITCH, Act.SWITCH_ON, Act.SWITCH_OFF, Act.TOGGLE})
_SENTENCE = frozenset(".!?;:")
#: markers that need no punctuation before them
_LOOSE = (("i", "mean"), ("i", "meant"), ("or", "rather"), ("no", "wait"), ("no", "actually"), ("actually", "no"),
          ("nah", "actually"))
#: markers that also open ordinary requests ("actually, could you ..."): they correct only
#: what they name again
_WEAK = (("actually",), ("wait",))
#: at most this many alternative readings per instruction (each costs a reading)
_MOST_ALTERNATIVES = 2


@dataclass(frozen=True)
class Corrected:
    """The instruction as corrected (the first reading) and its other readings: (slot
    label, how, items)."""

    items: list[Item]
    alternatives: tuple[tuple[str, str, list[Item]], ...] = ()


def _phrase_at(items: Sequence[Item], k: int, phrases: Sequence[tuple[str, ...]]) -> int:
    for p in phrases:
        if tuple(x.text for x in items[k:k + len(p)]) == p:
            return len(p)
    return 0


def _marker_at(items: list[Item], k: int) -> int:
    """Length of a correction marker starting at ``items[k]`` (0 if none)."""
    if items[k].text not in _FIRST_WORDS:
        return 0
    for m in _MARKERS:
        if tuple(x.text for x in items[k:k + len(m)]) != m:
            continue
        before = items[k - 1].punct if k > 0 else "."
        after = items[k + len(m)] if k + len(m) < len(items) else None
        if after is None:
            return 0
        restart = m == ("no",) and k > 0 and _RESTART.at(items, k - 1)
        if len(m) == 1 and not restart and after.text != "not" and (before is None or not (
                after.punct == "," or after.prep is not None or after.text in _NEGATORS
                or (after.det and before == ","))):
            continue     # "no one", "sorry to bother you", "rather the mug than ..."
        if restart:
            return len(m)    # "put the spray bottle and the no the soap bar ...": said again
        if before is None and m not in _LOOSE and not (m == ("no",) and after.text == "not"):
            continue     # ("... and the cloth as well no not the cloth": said without a pause)
        if m[0] == "i" and any(x.text == "by" for x in items[max(0, k - 3):k]):
            continue     # "by valuables I mean the watch and the keys": what a word stands for
        return len(m)
    return 0


def _is_np_item(x: Item) -> bool:
    return bool(x.det or x.noun is not None or x.number is not None or x.quant is not None
                or (x.state is not None and x.prep is None and x.particle is None))


def _starts_clause(x: Item) -> bool:
    return x.verb is not None and x.noun is None and x.prep is None and x.verb.form == "base"


@dataclass(frozen=True)
class _Run:
    """A noun phrase of the retracted part: [start, end), its nouns' types, whether a
    preposition puts it in a place (and where that preposition is)."""

    start: int
    end: int
    types: frozenset[str]
    text: str
    prep_at: int | None
    #: after any preposition ("from the desk"): a place or a qualifier, no member of a list
    after_prep: bool = False

    @property
    def place(self) -> bool:
        return self.prep_at is not None or self.after_prep


def _np_word(x: Item) -> bool:
    return _is_np_item(x) and x.prep is None and (x.verb is None or x.noun is not None) and x.punct is None


def _runs(items: Sequence[Item], lo: int, hi: int) -> list[_Run]:
    """The noun phrases of items[lo:hi]."""
    out: list[_Run] = []
    k = lo
    while k < hi:
        if not _np_word(items[k]):
            k += 1
            continue
        end = k
        while end < hi and _np_word(items[end]) and not _new_np(items, k, end):
            end += 1
        types = frozenset(t for x in items[k:end] if x.noun is not None for t in x.noun.concept.types)
        words = " ".join(x.text for x in items[k:end] if x.text not in _ARTICLES)
        # "turn on the lamp": a verb's particle, no place
        verb = items[k - 2].verb if k - 2 >= lo and items[k - 2].noun is None else None
        particle = items[k - 1].particle is not None and verb is not None and verb.sense.act in _SWITCHING
        after = k > lo and items[k - 1].prep is not None and not particle
        prep = k - 1 if after and items[k - 1].text not in _NOT_PLACES else None
        if types or words:
            out.append(_Run(k, end, types, words, prep, after))
        k = end
    return out


def _same(a: _Run, b: _Run) -> bool:
    return bool(a.types & b.types) if a.types and b.types else a.text == b.text


def _props(types: frozenset[str]) -> frozenset[str]:
    cat = load_catalogue()
    out: set[str] = set()
    for t in types:
        try:
            out |= set(cat.type(t).properties)
        except KeyError:
            continue
    return frozenset(out)


def _likeness(a: frozenset[str], b: frozenset[str]) -> float:
    pa, pb = _props(a), _props(b)
    return len(pa & pb) / len(pa | pb) if pa | pb else 0.0


def _region_start(items: Sequence[Item], k: int) -> int:
    """Where the retracted part may start: the sentence of the marker, or the one before
    when the marker opens a sentence (and the one before that when it names no thing:
    "... in the box. Both of them. Actually not the keys, the watch")."""
    j = k
    for _ in range(2):
        end = j
        while j > 0 and items[j - 1].punct is not None:
            j -= 1
        while j > 0 and items[j - 1].punct not in _SENTENCE:
            j -= 1
        if not any(x.punct in _SENTENCE for x in items[j:end]) or any(x.noun is not None for x in items[j:end]):
            break
    return j


def _clause_start(items: Sequence[Item], lo: int, at: int) -> int:
    """The start of the clause holding ``items[at]`` (the last verb or sentence break
    before it, within the region)."""
    for j in range(at - 1, lo - 1, -1):
        if items[j].punct in _SENTENCE or items[j].seq is not None:
            return j + 1
        if _starts_clause(items[j]):
            return j
    return lo


def _clause_end(items: Sequence[Item], at: int) -> int:
    """The end of the clause holding ``items[at]`` (the next verb or sentence break)."""
    for j in range(at + 1, len(items)):
        if items[j].punct in _SENTENCE or items[j].seq is not None or _starts_clause(items[j]):
            return j
    return len(items)


def _members(items: Sequence[Item], runs: list[_Run], run: _Run, lo: int) -> list[_Run]:
    """The things (not places) of the clause of ``run``, a pronoun ("put it in the fridge and
    the tomato too") as one of them."""
    start, end = _clause_start(items, lo, run.start), _clause_end(items, run.start)
    pronouns = [_Run(k, k + 1, frozenset(), items[k].text, None) for k in range(start, end)
                if items[k].pron is not None and not items[k].det and not (k > 0 and items[k - 1].prep is not None)]
    return [r for r in runs if not r.place and start <= r.start < end and r.text not in _PRONOUNS] + pronouns


def _called_back(items: list[Item], lo: int, run: _Run, runs: list[_Run], topic: bool = True) -> list[Item]:
    """The clause of ``run`` called back (its things stay as a topic)."""
    return _as_topic(items, _clause_start(items, lo, run.start), _clause_end(items, run.start), runs, topic)


def _pronoun_in(items: Sequence[Item]) -> bool:
    """Whether the first clause of ``items`` names a thing by a pronoun ("that one goes ...")."""
    stop = next((k for k, i in enumerate(items) if i.punct in _SENTENCE), len(items))
    return any(i.pron is not None for i in items[:stop])


def _drop_member(items: list[Item], run: _Run, lo: int) -> list[Item]:
    """The items without a list member: its joining "and" or comma, a "too" after it, and
    where it is ("... goes in the sink, and the spray bottle on the toilet too") when the
    clause's place was said before it."""
    start, end = run.start, run.end
    said = any(items[j].prep is not None and items[j].text not in _NOT_PLACES
               for j in range(_clause_start(items, lo, start), start))
    if said and end < len(items) and items[end].prep is not None:
        end = _np_end(items, end + 1)
    while end < len(items) and (items[end].text in _ALSO_ONE or _phrase_at(items, end, _ALSO)):
        end += max(1, _phrase_at(items, end, _ALSO))
    if start > lo and (items[start - 1].conj is not None or items[start - 1].punct == ","):
        start -= 1
    elif end < len(items) and (items[end].conj is not None or items[end].punct == ","):
        end += 1
    return [*items[:start], *items[end:]]


def _as_topic(items: list[Item], lo: int, hi: int, runs: list[_Run], topic: bool = True) -> list[Item]:
    """The clause [lo, hi) called back: only its things stay, as a topic a pronoun after
    it can name ("take the tomato to the fridge - no, that one goes in the sink"); without
    ``topic`` nothing stays."""
    things = [x for r in runs if topic and not r.place and lo <= r.start < hi for x in items[r.start:r.end]]
    stop = [Item(".", punct=".")] if things else []
    return [*items[:lo], *things, *stop, *items[hi:]]


def _np_end(items: Sequence[Item], k: int) -> int:
    end = k
    while end < len(items) and _np_word(items[end]) and not _new_np(items, k, end):
        end += 1
    return end


def _new_np(items: Sequence[Item], start: int, k: int) -> bool:
    """"not the microwave the fridge": a determiner after a noun starts another phrase."""
    return k > start and items[k].det and items[k - 1].noun is not None


def _strip_fillers(items: list[Item]) -> list[Item]:
    while items:
        if items[0].punct is not None:
            items = items[1:]
            continue
        n = _phrase_at(items, 0, _FILLERS) or _phrase_at(items, 0, _MARKERS) or int(
            items[0].text in _ONLY and len(items) > 1 and _starts_clause(items[1]))
        if not n or (items[0].text in ("no", "nope") and len(items) > 1 and items[1].det):
            return items
        items = items[n:]
    return items


@dataclass(frozen=True)
class _Edit:
    label: str
    how: str
    before: list[Item]
    fix: list[Item]
    #: what follows a comma after the slot is a sentence of its own (False: the retracted
    #: clause goes on after an aside, "put the pen - no, the pencil, the pen can stay - in ...")
    ends: bool = True


def _destination(runs: list[_Run], items: Sequence[Item]) -> _Run | None:
    """The place the retracted part puts things (the last, not one said with "not")."""
    places = [r for r in runs if r.place and r.prep_at is not None and not (
        r.prep_at > 0 and items[r.prep_at - 1].neg)]
    return places[-1] if places else None


def _slot_edits(before: list[Item], lo: int, fix: list[Item], weak: bool = False,
                nested: bool = False) -> list[_Edit]:
    """The readings of one correction, likeliest first ([] when the correcting part names
    nothing of the retracted part: it stands as said)."""
    runs = _runs(before, lo, len(before))
    dest = _destination(runs, before)
    head = fix[0]
    if (head.text in _NEGATORS or head.neg) and len(fix) > 2 and fix[1].prep is not None and dest is not None:
        end = _np_end(fix, 2)
        if end > 2 and _same(dest, _fix_run(fix[2:end])):
            # "no, not in the bowl, on the plate": the place said after the one taken back
            rest = fix[end + int(end < len(fix) and fix[end].punct == ","):]
            if rest and rest[0].prep is not None:
                return _slot_edits(before, lo, rest, weak, nested)
    if head.text in _NEGATORS or head.neg:
        end = _np_end(fix, 1)
        if end > 1:
            return _taken_out(before, lo, runs, dest, fix[1:end], fix[end:])
    if head.text in _ONLY and len(fix) > 1 and _is_np_item(fix[1]):
        end = _np_end(fix, 1)
        return _only(before, lo, runs, fix[1:end], fix[end:])
    if head.prep is not None and head.text not in _NOT_PLACES and len(fix) > 1 and _is_np_item(fix[1]):
        end = _np_end(fix, 1)
        if dest is not None and dest.prep_at is not None:
            return [_Edit("place", "the place corrected", [*before[:dest.prep_at], *fix[:end], *before[dest.end:]],
                          fix[end:])]
        return [_Edit("place", "the place added", [*before, *fix[:end]], fix[end:])]
    if _is_np_item(head) and head.verb is None:
        end = _np_end(fix, 0)
        if end < len(fix) and (fix[end].neg or fix[end].text in _NEGATORS) and (
                end + 1 == len(fix) or fix[end + 1].punct is not None):
            return _taken_out(before, lo, runs, dest, fix[:end], fix[end + 1:])    # "the keys not"
        swap = _phrase_at(fix, end, _SWAPS)
        if swap and end + swap < len(fix) and _is_np_item(fix[end + swap]):
            end2 = _np_end(fix, end + swap)
            return _swapped(before, lo, runs, fix[:end], fix[end + swap:end2], fix[end2:])
        if end == len(fix) or fix[end].punct is not None or fix[end].text in _ALSO_ONE:
            return _thing_or_place(before, lo, runs, dest, fix[:end], fix[end:])
    if (len(fix) == 1 or fix[1].punct is not None) and head.state is not None and head.noun is None:
        return _state(before, lo, head, fix[1:])
    edits = _clause(before, lo, runs, fix, weak)
    stop = next((k for k, i in enumerate(fix) if i.punct is not None), len(fix))
    if edits or weak or nested or any(r.place and _same(r, o) for r in runs for o in _runs(fix, 0, stop) if o.types):
        return edits     # "- no, in the bowl. hang on, the bowl is shut away ...": a remark on the place
    # "no, the dog sleeps there, into the box with it", "scratch the dresser, it's cluttered,
    # onto the stool": a reason first, the slot after it (a fragment, no clause)
    for comma in (k for k, i in enumerate(fix) if i.punct == "," and k + 1 < len(fix)):
        seg = fix[comma + 1:]
        stop = next((k for k, i in enumerate(seg) if i.punct is not None), len(seg))
        if any(i.verb is not None and i.noun is None for i in seg[:stop]):
            # "..., put it into the box": the request said again (by a pronoun only)
            later = _clause(before, lo, runs, seg) if _pronoun_in(seg[:stop]) else []
        else:
            later = _slot_edits(before, lo, seg, nested=True)
        if later:
            return [_Edit(e.label, e.how, e.before, [*fix[:comma + 1], *e.fix]) for e in later]
    return []


def _fix_run(fix: list[Item]) -> _Run:
    types = frozenset(t for x in fix if x.noun is not None for t in x.noun.concept.types)
    return _Run(0, len(fix), types, " ".join(x.text for x in fix if x.text not in _ARTICLES), None)


def _taken_out(before: list[Item], lo: int, runs: list[_Run], dest: _Run | None, np: list[Item],
               tail: list[Item]) -> list[_Edit]:
    """"not the CD", "the keys not", "scratch the dresser": a member taken out, or the
    destination (then a place said later in the correcting part takes its place)."""
    x = _fix_run(np)
    if dest is not None and _same(dest, x) and dest.prep_at is not None:
        named = _strip_fillers(list(tail))
        if len(named) < len(tail) and named and named[0].det:
            tail = named      # "not the hamper I meant the desk": the place after the marker
        at = 1 if tail and tail[0].punct == "," else 0
        if len(tail) > at and tail[at].det:
            # "not the micro wave (,) the fridge": the place named right after
            end = _np_end(tail, at)
            return [_Edit("place", "the place corrected", [*before[:dest.start], *tail[at:end], *before[dest.end:]],
                          tail[end:])]
        where = next((k for k, i in enumerate(tail) if i.prep is not None and i.text not in _NOT_PLACES
                      and k + 1 < len(tail) and _is_np_item(tail[k + 1])), None)
        if where is not None and not any(i.verb is not None and i.noun is None for i in tail[:where]):
            end = _np_end(tail, where + 1)
            fixed = [*before[:dest.prep_at], *tail[where:end], *before[dest.end:]]
            return [_Edit("place", "the place corrected", fixed, [*tail[:where], *tail[end:]])]
        return [_Edit("place", "the place called back", _called_back(before, lo, dest, runs), tail)]
    hit = [r for r in runs if not r.place and _same(r, x)]
    if not hit:
        return []
    run = hit[-1]
    if len(tail) > 1 and tail[0].punct == "," and tail[1].det:
        end = _np_end(tail, 1)
        if end > 2 and (end == len(tail) or tail[end].punct is not None):
            # "not the keys, the watch": the thing named right after takes the member's place
            return _swapped(before, lo, runs, tail[1:end], np, tail[end:])
    if len(_members(before, runs, run, lo)) > 1:
        out = _drop_member(before, run, lo)
        if _pronoun_in(tail):
            # "... and the cloth as well, no, not the cloth, that goes in the bin", "not the
            # tomato, it goes mushy, leave it on the counter": a topic
            out = [*out, Item(".", punct="."), *before[run.start:run.end], Item(".", punct=".")]
        return [_Edit("member", f"{x.text!r} taken out of the list", out, tail)]
    return [_Edit("member", f"{x.text!r} called back", _called_back(before, lo, run, runs, _pronoun_in(tail)), tail)]


def _only(before: list[Item], lo: int, runs: list[_Run], np: list[Item], tail: list[Item]) -> list[_Edit]:
    """"no, only the pencil": the list cut to the things named."""
    named = [_fix_run([x for x in np if x.conj is None])]
    hit = [r for r in runs if not r.place and any(_same(r, n) for n in named)]
    if not hit:
        return _thing_or_place(before, lo, runs, _destination(runs, before), np, tail)
    out = list(before)
    for r in sorted(_members(before, runs, hit[-1], lo), key=lambda r: -r.start):
        if not any(_same(r, n) for n in named):
            out = _drop_member(out, r, lo)
    return [_Edit("member", "the list cut to " + named[0].text, out, tail)]


def _swapped(before: list[Item], lo: int, runs: list[_Run], new: list[Item], old: list[Item],
             tail: list[Item]) -> list[_Edit]:
    """"the bowl instead of the mug": the old thing or place replaced by the new."""
    y = _fix_run(old)
    hit = [r for r in runs if _same(r, y)]
    if not hit:
        return []
    r = hit[-1]
    return [_Edit("place" if r.place else "thing", f"{_fix_run(new).text!r} instead of {y.text!r}",
                  [*before[:r.start], *new, *before[r.end:]], tail)]


def _thing_or_place(before: list[Item], lo: int, runs: list[_Run], dest: _Run | None, np: list[Item],
                    tail: list[Item]) -> list[_Edit]:
    """A bare noun phrase: the thing (the nearest member, or the whole list) or the
    destination, ordered by what the new thing affords like each."""
    x = _fix_run(np)
    things = [r for r in runs if not r.place and r.text not in _PRONOUNS]
    edits: list[tuple[float, _Edit]] = []
    if dest is not None and "receptacle" in _props(x.types):
        place = [*before[:dest.start], *np, *before[dest.end:]]
        edits.append((_likeness(x.types, dest.types) + 0.01, _Edit("place", f"{x.text!r} as the place", place, tail)))
    if (things and "pickupable" in _props(x.types)) or (things and dest is None):
        last = things[-1]
        members = _members(before, runs, last, lo)
        score = _likeness(x.types, last.types)
        edits.append((score, _Edit("thing", f"{x.text!r} instead of {last.text!r}",
                                   *_aside([*before[:last.start], *np, *before[last.end:]], tail), dest is not None)))
        if len(members) > 1:
            first = members[0]
            edits.append((score - 0.2, _Edit("list", f"{x.text!r} instead of the whole list",
                                             [*before[:first.start], *np, *before[last.end:]], tail)))
    return [e for _, e in sorted(edits, key=lambda e: -e[0])]


def _aside(before: list[Item], tail: list[Item]) -> tuple[list[Item], list[Item]]:
    """"put the pen - no, the pencil, the pen can stay - in the drawer, ...": the retracted
    clause goes on after an aside; the aside follows it as a sentence of its own."""
    commas = [k for k, i in enumerate(tail) if i.punct in (",", ":")]
    for a, b in pairwise(commas):
        nxt = tail[b + 1] if b + 1 < len(tail) else None
        if a == 0 and nxt is not None and nxt.prep is not None and nxt.text not in _NOT_PLACES:
            end = next((k for k in range(b + 1, len(tail)) if tail[k].punct is not None), len(tail))
            return [*before, *tail[b + 1:end]], [*tail[end:], Item(".", punct="."), *tail[1:b]]
    return before, tail


def _state(before: list[Item], lo: int, new: Item, tail: list[Item]) -> list[_Edit]:
    """"turn the tv off, sorry, on": the last state word of the retracted part replaced."""
    at = next((k for k in range(len(before) - 1, lo - 1, -1) if (before[k].state is not None or before[k].particle)
               and before[k].noun is None and before[k].text in ("on", "off", "open", "closed", "shut", "up", "down")),
              None)
    if at is None:
        return []
    return [_Edit("state", f"{new.text!r} instead of {before[at].text!r}", [*before[:at], new, *before[at + 1:]], tail)]


def _clause(before: list[Item], lo: int, runs: list[_Run], fix: list[Item], weak: bool = False) -> list[_Edit]:
    """A correcting clause: the members it names leave the retracted list (the clause
    re-says them); naming none (a pronoun, another thing) it re-says the retracted clause."""
    if _CALLED_OFF.at(fix):
        return []
    stop = next((k for k, i in enumerate(fix) if i.punct in _BREAK), len(fix))
    own = [r for r in _runs(fix, 0, stop) if not r.place and r.text not in _PRONOUNS
           and (r.types or any(_same(r, x) for x in runs))]
    named = [r for r in runs if not r.place and any(_same(r, o) for o in own)]
    if any(r.place and _same(r, o) for r in runs for o in own if o.types):
        return []
    if named:
        out = list(before)
        for r in sorted(named, key=lambda r: -r.start):
            members = _members(out, _runs(out, lo, len(out)), r, lo)
            if any(not any(_same(m, n) for n in named) for m in members):
                out = _drop_member(out, r, lo)
            else:
                out = _called_back(out, lo, r, _runs(out, lo, len(out)), False)
        return [_Edit("member", "the things it names said again", out, fix)]
    things = [r for r in runs if not r.place and r.text not in _PRONOUNS]
    if not things or weak:
        return []
    last = things[-1]
    pronoun = any(i.pron is not None for i in fix[:stop])
    if pronoun and not own:
        later = [j for j in range(last.end, len(before)) if before[j].pron is not None and not before[j].det]
        if later:    # "shower door: open it. Wait no, keep it shut": the pronoun's clause
            start = _clause_start(before, lo, later[-1])
            kept = before[:start]
            while kept and kept[-1].punct is not None:
                kept.pop()
            return [_Edit("clause", "the clause said again", [*kept, *before[_clause_end(before, later[-1]):]], fix)]
        return [_Edit("clause", "the clause said again", _called_back(before, lo, last, runs), fix)]
    again = _called_back(before, lo, last, runs, False)
    if own and (_starts_clause(fix[0]) or len(_members(before, runs, last, lo)) == 1):
        return [_Edit("clause", "the clause said again", again, fix),
                _Edit("keep_first", "both requests stand", before, fix)]
    return []


def _called_off(before: list[Item], fix: list[Item]) -> list[Item]:
    """"turn on the faucet - no wait, don't, just switch off the light": the act before
    is called off (its things stay as a topic for a pronoun), what follows stands."""
    cut = max((i + 1 for i, x in enumerate(before) if x.punct in _BREAK), default=0)
    tail = fix[2:]
    while tail and tail[0].punct is not None:
        tail = tail[1:]
    return [*_as_topic(before, cut, len(before), _runs(before, cut, len(before))), *tail]


def _told_apart(before: list[Item], fix: list[Item]) -> list[Item] | None:
    """"that ladle on the counter, sorry, the one next to the bowl": the same object, told
    apart by another place."""
    if not (len(fix) > 2 and fix[0].det and fix[1].text == "one" and fix[2].prep is not None):
        return None
    place = max((i for i, x in enumerate(before) if x.prep is not None and i > 0
                 and before[i - 1].noun is not None), default=None)
    if place is None:
        return None
    told = list(fix[2:])
    comma = next((i for i, x in enumerate(told) if x.punct == ","), None)
    if comma is not None:
        del told[comma]       # "..., the one next to the bowl, lives in a drawer"
    return [*before[:place], *told]


def _one(out: list[Item], k: int, size: int) -> tuple[list[_Edit], list[Item], list[Item]] | None:
    """The readings of the correction whose marker is at ``k``: (edits, retracted part,
    what follows the correcting sentence); None when it is no correction after all."""
    before = out[:k]
    while before and before[-1].punct is not None:
        before.pop()
    after = _strip_fillers(out[k + size:])
    end = next((i for i, x in enumerate(after) if x.punct in (".", "!", "?", ";")), len(after))
    fix, rest = after[:end], after[end:]
    if not before or not fix:
        return None
    if _CALLED_OFF.at(fix):
        return [_Edit("called_off", "the act called off", _called_off(before, fix), [])], before, rest
    if _starts_clause(before[-1]) and fix[0].det is False and _starts_clause(fix[0]):
        # "crack- well, just put the egg ...": a verb broken off
        return [_Edit("clause", "a verb broken off", before[:-1], fix)], before, rest
    told = _told_apart(before, fix)
    if told is not None:
        return [_Edit("thing", "the same thing told apart", told, [])], before, rest
    lo = _region_start(out, k)
    if k > 0 and out[k].text == "no" and _RESTART.at(out, k - 1) and _starts_clause(fix[0]):
        # "throw the pencil away. no wait, throw the pen away": the request said again
        cut = max((i + 1 for i, x in enumerate(before) if x.punct in _BREAK), default=0)
        return [_Edit("clause", "the request said again", _as_topic(before, cut, len(before), _runs(
            before, cut, len(before)), _pronoun_in(fix)), fix)], before, rest
    edits = [_ended(e) for e in _slot_edits(before, lo, fix, tuple(x.text for x in out[k:k + size]) in _WEAK)]
    if edits and not any(e.label == "keep_first" for e in edits):
        # the rejected side stays a reading: the person may not have meant to take it back
        edits.append(_Edit("keep_first", "the first request stands", before, edits[0].fix))
    return edits, before, rest


def _ended(edit: _Edit) -> _Edit:
    """After a corrected place, thing or state, what follows a comma is a sentence of its
    own ("- no, on the armchair, the sofa is for sitting"), not more of the list."""
    if edit.label in ("place", "thing", "state", "list") and edit.ends and edit.fix and edit.fix[0].punct == ",":
        return _Edit(edit.label, edit.how, edit.before, [Item(".", punct="."), *edit.fix[1:]])
    return edit


def _after_stop(fix: list[Item]) -> list[Item]:
    """The correcting part as a sentence of its own."""
    if not fix or fix[0].punct in _SENTENCE:
        return fix
    return [Item(".", punct="."), *(fix[1:] if fix[0].punct == "," else fix)]


def _not_after_list(items: Sequence[Item], k: int) -> bool:
    """"put the pen, the pencil and the cd in the drawer, not the cd": "not" after a comma
    takes a member out as a correction does (only a member: "not on the floor" is a place
    said as rejected)."""
    return items[k].text == "not" and k > 0 and items[k - 1].punct == "," and k + 1 < len(items) \
        and bool(items[k + 1].det)


def correct(items: list[Item], alternatives: bool = True) -> Corrected:
    """The items with every self-correction applied, and the other readings of the
    corrections whose slot is in doubt; requests undone or redone whole
    (:mod:`.retractions`) first."""
    k = 0
    out = retract(items) if alternatives else list(items)
    alts: list[tuple[str, str, list[Item]]] = []
    while k < len(out):
        size = _marker_at(out, k)
        found = _one(out, k, size) if size or _not_after_list(out, k) else None
        if not found or not found[0] or (not size and found[0][0].label != "member"):
            k += max(size, 1)
            continue
        edits, _, rest = found
        # a correction that opens a sentence keeps the sentence break before it
        stop = any(x.punct in _SENTENCE for x in out[max(0, k - 2):k])
        edits = [_Edit(e.label, e.how, e.before, _after_stop(e.fix) if stop else e.fix) for e in edits]
        first = edits[0]
        fixed = [*first.before, *first.fix, *rest]
        if alternatives:
            for e in edits[1:]:
                if len(alts) < _MOST_ALTERNATIVES:
                    alts.append((e.label, e.how, correct([*e.before, *e.fix, *rest], False).items))
        k = len(first.before)
        out = fixed
    return Corrected(out, tuple(alts))
