"""Positions within the speaker's own list: people name things, then refer back by their
order or by what is left ("the remote and the book: the former goes onto the sofa, the
latter into the box"; "the teddy, the phone and the keys - the first and the last go in the
safe, the middle one stays"; "apple, bread, potato, tomato - the potato and the tomato go in
the fridge, the other half stay"). Each such reference is replaced by the noun phrases of
the items it picks, before the clause grammar reads the words, so they read as if named.

A list is two or more noun phrases of things joined by commas or "and" (places after a
preposition are not items; a plural head before them, "the two soaps, the bar and the
bottle", only names their kind). A reference reaches back to the latest list at most
``window_sentences`` sentences before it; a list that only names items of the list
before it ("half of them, the potato and the tomato") is not a new list. What cannot be
resolved (no list, a count that does not fit, nothing left for "the rest") stays as said.
The words are data: ``data/list_positions.json``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from emboteam.pfg.offline.knowledge import Strict, load
from emboteam.pfg.offline.tagger import Item, tag


class ListPositionsFile(Strict):
    """``data/list_positions.json``."""

    about: str = ""
    #: position words and their place in the list (1 = the first, -1 = the last)
    positions: dict[str, int]
    middle: frozenset[str]
    #: "1 st", "3 rd": a number with its ordinal ending (split off by normalisation)
    number_suffixes: frozenset[str]
    #: "the rest", "the others": the items no later words picked
    remainders: frozenset[str]
    #: "the other one", "the other two", "the other half" (a bare "the other" is as often
    #: the other robot: "leave the lifting to the other")
    counted_remainders: frozenset[str]
    #: words after a position that name no thing ("the last ones", "the other half")
    units: frozenset[str]
    #: "the second of those"
    of_those: frozenset[str]
    #: words between "the" and the position: "the one I mentioned first", "the ones I named last"
    named_as: tuple[tuple[str, ...], ...]
    #: a position said as a number: "number three (on my list)"
    number_words: frozenset[str]
    #: words after a reference that say where it points: "on my list", "in that list"
    list_words: tuple[tuple[str, ...], ...]
    #: nouns after a position that make it no reference ("the first time")
    not_heads: frozenset[str]
    joiners: frozenset[str]
    window_sentences: int


_DATA = load("list_positions.json", ListPositionsFile)
#: the label of the other reading (a surface alternative: doubts/priors.json ``surface``)
EARLIER_LIST = "earlier_list"
_SENTENCE_ENDS = frozenset(".!?")
#: words without which no reference is said (a quick test before any work)
_TRIGGERS = frozenset(_DATA.positions) | _DATA.middle | _DATA.remainders | _DATA.counted_remainders \
    | _DATA.number_suffixes | _DATA.number_words


@dataclass
class _List:
    """A list the speaker named: each item's noun phrase, where the list ends, its sentence."""

    members: list[list[Item]]
    end: int
    sentence: int
    picked: set[int] = field(default_factory=set)


def _plain(it: Item) -> bool:
    """A word with no reading of its own (an adjective, a name the lexicon lacks)."""
    return it.text.isalpha() and not (it.noun or it.verb or it.state or it.prep or it.particle or it.det
                                      or it.quant or it.pron or it.conj or it.seq or it.sub or it.copula
                                      or it.punct or it.number is not None or it.ordinal is not None)


def _np_start(items: list[Item], head: int) -> int:
    """Where the noun phrase whose head is at ``head`` starts (determiners, numbers, adjectives)."""
    j = head
    while j > 0 and (items[j - 1].det or items[j - 1].number is not None or _plain(items[j - 1])) \
            and items[j - 1].text not in _DATA.joiners:
        j -= 1
    return j


def _heads(items: list[Item]) -> list[int]:
    """The heads of noun phrases that are not the object of a preposition."""
    out = []
    for k, it in enumerate(items):
        if (it.noun is None or not it.noun.concept.types or it.quant or it.pron) \
                and not (k > 0 and items[k - 1].det and _plain(it)):
            continue     # no thing ("everything"), unless a name its list's kind may give
        s = _np_start(items, k)
        if s > 0 and items[s - 1].prep is not None:
            continue
        out.append(k)
    return out


def _joined(items: list[Item], a: int, b: int) -> bool:
    """Do the words between one item's head ``a`` and the next one's start ``b`` only place
    the first ("on the floor") and join them (a comma, "and")?"""
    gap = items[a + 1:b]
    if not gap or gap[-1].text not in _DATA.joiners:
        return False
    return all(g.text in _DATA.joiners or g.prep is not None or g.det or g.noun is not None or _plain(g)
               for g in gap) and not any(g.verb is not None and g.noun is None for g in gap)


def _kind_named(word: Item, header: Item) -> Item | None:
    """"the bar" of "the two soaps": the word and the kind together as one noun of the lexicon."""
    kinds = tuple(dict.fromkeys((header.text, header.text.removesuffix("s"), header.text.removesuffix("es"))))
    for phrase in [f"{k} {word.text}" for k in kinds] + [f"{word.text} {k}" for k in kinds]:
        got = tag(phrase)
        if len(got) == 1 and got[0].noun is not None:
            return got[0]
    return None


def _unseen_item(items: list[Item], j: int, step: int) -> bool:
    """Is there a joiner at ``j`` and, past it, a word the reader does not know (an item of
    the list it cannot see, so positions counted from that end would be wrong)?"""
    return 0 <= j + step < len(items) and items[j].text in _DATA.joiners and _plain(items[j + step])


def _lists(items: list[Item], sentence_of: list[int]) -> list[_List]:
    """Every list the words name, in order."""
    heads = _heads(items)
    runs: list[list[int]] = []
    for h in heads:
        if runs and _joined(items, runs[-1][-1], _np_start(items, h)):
            runs[-1].append(h)
        else:
            runs.append([h])
    out: list[_List] = []
    for run in runs:
        if _unseen_item(items, _np_start(items, run[0]) - 1, -1) or _unseen_item(items, run[-1] + 1, 1):
            continue     # "la tarjeta, the keys, the laptop": an item the reader cannot see
        header = None
        if len(run) > 2 and _plural(items[_np_start(items, run[0]):run[0] + 1]):
            header, run = items[run[0]], run[1:]     # "the two soaps, the bar and the bottle"
        members: list[list[Item]] = []
        for h in run:
            np = [replace(i, extra=dict(i.extra)) for i in items[_np_start(items, h):h + 1]]
            named = _kind_named(np[-1], header) if header is not None else None
            if named is None and np[-1].noun is None:
                break
            np[-1] = named or np[-1]     # "the bottle" of "the two soaps": the soap bottle
            members.append(np)
        else:
            if len(members) >= 2:
                out.append(_List(members, run[-1], sentence_of[run[-1]]))
    return out


def _plural(np: list[Item]) -> bool:
    """Does the noun phrase name more than one thing ("both rolls", "the two soaps")?"""
    noun = np[-1].noun
    return noun is not None and (noun.plural or any(i.number not in (None, 1) or i.quant for i in np))


def _concept(np: list[Item]) -> str | None:
    noun = np[-1].noun
    return noun.concept.name if noun is not None else None


def _reference(items: list[Item], k: int) -> tuple[int, str, int, int | None] | None:
    """A reference by position at ``k`` ("the", a position, a count, "one"...): its end,
    its kind (``pos``, ``middle`` or ``rest``), the position and the count it names."""
    if not (items[k].det or items[k].text in _DATA.number_words) or k + 1 >= len(items):
        return None
    j = k + 1
    if items[k].text in _DATA.number_words:       # "number three on my list"
        end, number = _at(items, j + 1, _DATA.list_words), items[j].number
        return None if end is None or number is None else (end, "pos", number, None)
    j = _at(items, j, _DATA.named_as) or j
    w = items[j].corrected_from or items[j].text
    if w in _DATA.positions:
        kind, pos = "pos", _DATA.positions[w]
    elif w in _DATA.middle:
        kind, pos = "middle", 0
    elif w in _DATA.remainders or w in _DATA.counted_remainders:
        kind, pos = "rest", 0
    elif (number := items[j].number) is not None and j + 1 < len(items) \
            and items[j + 1].text in _DATA.number_suffixes:
        kind, pos = "pos", number
        j += 1
    else:
        return None
    j += 1
    count = None
    if j < len(items) and items[j].text in _DATA.units:
        j += 1
    elif j < len(items) and items[j].number is not None:
        count = items[j].number
        j += 1
        j += j < len(items) and items[j].text in _DATA.units
    if j + 1 < len(items) and items[j].prep == "of" and items[j + 1].text in _DATA.of_those:
        j += 2
    j = _at(items, j, _DATA.list_words) or j
    if w in _DATA.counted_remainders and j == k + 2:
        return None     # "the other" alone
    if j < len(items) and (items[j].noun is not None or items[j].text in _DATA.not_heads or items[j].prep == "of"):
        return None     # "the first drawer", "the first time", "the rest of the food"
    return j, kind, pos, count


def _at(items: list[Item], j: int, phrases: tuple[tuple[str, ...], ...]) -> int | None:
    """The end of the first of ``phrases`` said at ``j``, if any."""
    for p in phrases:
        if tuple(i.text for i in items[j:j + len(p)]) == p:
            return j + len(p)
    return None


def _picked(ref: tuple[int, str, int, int | None], lst: _List) -> list[int] | None:
    """The indices of the list's items a reference picks (None: it does not fit)."""
    _, kind, pos, count = ref
    n = len(lst.members)
    if kind == "rest":
        left = [i for i in range(n) if i not in lst.picked]
        if count == 1 and len(left) == 1 and _plural(lst.members[left[0]]):
            return None     # "both rolls ... one roll on the holder, the other one": one of them
        return left if lst.picked and left and count in (None, len(left)) else None
    k = count or 1
    if kind == "middle":     # centred, or what lies between the ends already picked
        left = [i for i in range(n) if i not in lst.picked]
        if not (n - k) % 2 and k < n:
            return list(range((n - k) // 2, (n + k) // 2))
        return left if len(left) == k and left[0] > 0 and left[-1] < n - 1 else None
    start = n - k if pos == -1 else pos - 1
    if start < 0 or start + k > n:
        return None
    return list(range(start, start + k))


def resolve_list_positions(items: list[Item]) -> list[Item]:
    """The items with every reference to a position in the speaker's latest list replaced by
    the noun phrases of the items it picks (joined by "and")."""
    return _resolve(items, earlier=False)[0]


def earlier_list_reading(items: list[Item]) -> list[Item] | None:
    """The items with a reference that also fits the list named before the latest one
    ("the pen and the book ..., the mug and the plate ...: the first goes ...") resolved to
    that earlier list: the other reading of a point of doubt; None when no reference fits two."""
    out, ambiguous = _resolve(items, earlier=True)
    return out if ambiguous else None


def has_references(items: list[Item]) -> bool:
    """Whether any word may refer to a position in a list ("first", "latter", "rest"): the
    cheap test before anything is resolved or read again."""
    return any((i.corrected_from or i.text) in _TRIGGERS for i in items)


def _resolve(items: list[Item], earlier: bool) -> tuple[list[Item], bool]:
    """The items with the references resolved (to the earlier of two lists that fit, when
    ``earlier``), and whether any reference fitted two lists."""
    if not has_references(items):
        return items, False
    sentence_of, s = [], 0
    for it in items:
        sentence_of.append(s)
        s += it.punct is not None and it.punct in _SENTENCE_ENDS
    pending = _lists(items, sentence_of)
    named: list[_List] = []     # the lists named so far, the latest last
    and_item, the = tag("and the")     # a reference back is definite: "an apple" -> "the apple"
    out: list[Item] = []
    ambiguous = False
    k = 0
    while k < len(items):
        while pending and pending[0].end < k:
            new = pending.pop(0)
            if not named or not {_concept(m) for m in new.members} <= {_concept(m) for m in named[-1].members}:
                named.append(new)
        ref = _reference(items, k) if named else None
        fits = [(lst, picked) for lst in reversed(named[-2:]) if ref is not None
                and sentence_of[k] - lst.sentence <= _DATA.window_sentences
                and (picked := _picked(ref, lst)) is not None]
        if ref is not None and fits:
            ambiguous |= len(fits) > 1
            lst, picked = fits[-1] if earlier else fits[0]
            for n, i in enumerate(picked):
                out.extend([and_item] if n else [])
                out.extend(the if x.det else replace(x, extra=dict(x.extra)) for x in lst.members[i])
            lst.picked.update(picked)
            k = ref[0]
            continue
        if named and k > named[-1].end and items[k].noun is not None:
            # named again after the list ("half of them, the potato and the tomato"): picked
            named[-1].picked.update(i for i, m in enumerate(named[-1].members) if _concept(m) == _concept([items[k]]))
        out.append(items[k])
        k += 1
    return out, ambiguous
