"""Clause segmentation: an instruction -> clauses, each with how it attaches to what came
before (in parallel, after it, before it) and the robot it is addressed to.

Boundaries are sentence punctuation, sequence markers ("then", "after that"),
subordinators ("after", "before", "once", "when", "while", "by" + gerund, "if"), and
"and"/"," when what follows starts with a verb ("slice the apple and put it ..." is two
clauses, "slice the apple and the tomato" is one).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import first_rule, pattern_tables
from emboteam.pfg.offline.roles import role_subject, without_role
from emboteam.pfg.offline.tagger import Item

#: how a clause attaches to the one before it
AND, THEN = "and", "then"


@dataclass
class Clause:
    items: list[Item]
    #: "and" (parallel), "then" (after the previous step), or a subordinator relation
    #: "after"/"before"/"while"/"by"/"if"/"purpose" (the clause is subordinate)
    link: str = AND
    robot: tuple[str, int] | None = None
    sentence: int = 0
    #: position of a subordinate clause: first in its sentence ("After X, Y") or not
    initial: bool = False
    extra: dict[str, str] = field(default_factory=dict)

    @property
    def text(self) -> str:
        return " ".join(i.text for i in self.items if i.punct is None)


_SENTENCE_END = frozenset(".!?;:")
_W = word_tables("clauses")
_P = pattern_tables("clauses")
#: what starts a new clause after a comma or "and" (more in :func:`_starts_new`)
_NEW_CLAUSE = _P.table("new_clause")
#: what follows a subject when it has a predicate of its own: which kind
_SUBJECT_PREDICATE = _P.table("subject_predicate")
(_ADVERB_THEN_PLACE, _LEFT_IN_A_STATE, _QUESTION_MODALS, _MAKE_SURE, _TOO_AT_END, _MODAL_PREDICATE,
 _ASK_SOMEONE, _COORDINATOR, _ONLY_THE, _SO_I_WAS, _DESCRIBED_MEMBER, _PLACE_NOT_STATE, _RUN_ON_STATE) = (
    _P.pattern(name) for name in (
        "adverb_then_place", "left_in_a_state", "question_modals", "make_sure", "too_at_end", "modal_predicate",
        "ask_someone", "coordinator", "only_the", "so_i_was", "described_member", "place_not_state",
        "run_on_state"))
_RELATIVE_PLACE, _SECOND_STATE, _STATE_OF_PLACED, _PERSON_ACTS, _IT_IS, _READY_STATE, _RUN_ON_IT, _RUN_ON_VERB = (
    _P.pattern(name) for name in ("relative_place", "second_state", "state_of_placed", "person_acts", "it_is",
                                  "ready_state", "run_on_it", "run_on_verb"))
_STATE_THEN_THING, _NOUN_THEN_THING = _P.pattern("state_then_thing"), _P.pattern("noun_then_thing")
#: ordinals that number the steps of a spoken list
_LIST_ORDINALS = _W.set("list_ordinals")
_HUMAN = _W.set("human")
#: a verb-or-noun word that takes an object (so it is a verb)
_TAKES_OBJECT, _VERB_CUES, _VERB_HERE = _P.pattern("takes_object"), _P.pattern("verb_cues"), _P.table("verb_here")


def verb_here(items: list[Item], j: int) -> bool:
    """Is ``items[j]`` (after optional cues like "also", "please") the verb of a new clause?"""
    j = _VERB_CUES.end(items, j) or j
    rule = first_rule(_VERB_HERE, items, j)
    return rule is not None and (rule.then == "verb" or (rule.then == "object" and _TAKES_OBJECT.at(items, j)))


#: words that only introduce a robot: "have robot 2 ...", "the second robot", "ask robot 1 to"
_ROBOT_INTRO = _W.set("robot_intro")


def _without_robot_words(items: list[Item]) -> list[Item]:
    """The clause without its robot names and the words that introduce them."""
    drop: set[int] = set()
    for k, x in enumerate(items):
        if x.robot is None:
            continue
        drop.add(k)
        m = k - 1
        while m >= 0 and items[m].text in _ROBOT_INTRO:
            drop.add(m)
            m -= 1
    return [x for k, x in enumerate(items) if k not in drop]


def _sentences(items: list[Item]) -> list[tuple[list[Item], str | None]]:
    """The sentences, each with the punctuation that ends it."""
    out: list[tuple[list[Item], str | None]] = [([], None)]
    for it in items:
        if it.punct in _SENTENCE_END:
            if out[-1][0]:
                marker = out[-1][0][-1]
                if it.punct == "." and len(out[-1][0]) > 1 and marker.number is not None \
                        and marker.noun is None and out[-1][0][-2].number is None:
                    # "1. telly off 2. lamp on": "2." numbers the next item, not this one
                    out[-1][0].pop()
                    out[-1] = (out[-1][0], it.punct)
                    out.append(([marker], None))
                    out[-1] = (out[-1][0], it.punct)
                    out.append(([], None))
                    continue
                out[-1] = (out[-1][0], it.punct)
                out.append(([], None))
            continue
        out[-1][0].append(it)
    return [(s, end) for s, end in out if s]


#: team members named without a number: "one of you", "the other", "another robot"
TEAM_SUBJECTS = _W.phrases("team_subjects")
_LONGEST_TEAM_SUBJECT = max(map(len, TEAM_SUBJECTS), default=0)


def team_subject(items: list[Item], j: int) -> int:
    """The index after a team-member subject at ``j`` ("one of you", "the other"), else
    ``j``."""
    said = tuple(x.text for x in items[j:j + _LONGEST_TEAM_SUBJECT])    # the words once, not per phrase
    for words in TEAM_SUBJECTS:
        if said[:len(words)] == words:
            return j + len(words)
    # "the strong robot": described by its build; "whoever has the knife skills": by its role
    return _DESCRIBED_MEMBER.end(items, j) or role_subject(items, j)


#: "I'd like my phone brought over": the verb after the object is the wished state
_WISH_VERBS = _W.set("wish_verbs")


def _has_predicate(items: list[Item]) -> bool:
    """Has the clause so far a predicate of its own? "the bread on the counter" (and ...
    need to go in the fridge) has not: the next subject shares the predicate."""
    items = items[_MAKE_SURE.end(items) or 0:]
    items = items[_QUESTION_MODALS.end(items) or 0:]
    if not items:
        return False
    last = items[-1]
    # a state word is a verb of its own at the head of an order ("open the fridge, ...")
    # ... and so is a word that is also a noun when it takes an object there ("bin the
    # spray bottle, and the candle ... should go on a side table")
    return any(x.copula or (x.verb is not None and x.noun is None and (x.state is None or k == 0))
               for k, x in enumerate(items)) or verb_here(items, 0) or last.particle is not None or (
        last.state is not None and last.prep is None)


def _starts_new(items: list[Item], j: int, current: list[Item] | None = None,
                comma: bool = True) -> bool:
    """A boundary before ``items[j]`` (after ',' or 'and')? ``current``: the clause so
    far; ``comma``: a comma came before (a new subject needs one: "I need the tomato and
    the lettuce sliced" is one clause, "turn the TV off, the lights too" two)."""
    it = items[j]
    if any(rule.at(items, j) and (comma or rule.then != "after_comma") for rule in _NEW_CLAUSE):
        return True
    if current and _SECOND_STATE.at(items, j) and (current[-1].state is not None or current[-1].particle is not None) \
            and not (current[-1].text in ("on", "off") and it.text in ("on", "off")):
        return True     # "should be left switched off and closed": a second state, of the same thing
    if comma and current and current[-1].noun is not None and _STATE_OF_PLACED.at(items, j):
        return True     # "the laptop goes on the dresser, closed, ...": the state of what was placed
    k = team_subject(items, j)
    if k > j and k < len(items) and (items[k].verb is not None or items[k].copula):
        return True     # ", the other should put ...", "while another turns off ..."
    if comma and it.pron in ("it", "that", "this", "they") and j + 1 < len(items) and items[j + 1].noun is None \
            and items[j + 1].verb is None and items[j + 1].prep is None and items[j + 1].text.endswith("s") \
            and len(items[j + 1].text) > 3 and items[j + 1].text not in lx.vocabulary():
        return True     # "..., it glares on the screen": a clause of its own with a verb we do not know
    if it.verb is not None and it.verb.form == "s" and it.noun is None and current \
            and any(x.verb is not None and x.verb.form == "s" and x.noun is None for x in current) \
            and _TAKES_OBJECT.at(items, j):
        return True     # "robot 1 closes it and turns off the light": the same subject's next act
    asked = current is not None and _QUESTION_MODALS.at(current)
    kind = subject_here(items, j, asked)
    if kind == "state" and comma and _ends_with_place(current or []):
        return True     # "candle in the box, box shut, lamp on": terse items, each complete
    return verb_here(items, j) or (kind is not None and (comma or kind != "state" or _ends_with_place(current or []))
                                   and _has_predicate(current or []))


def _ends_with_place(items: list[Item]) -> bool:
    """Does the clause so far end with where something goes ("... should end up in the
    fridge")? Then "and the fridge closed" is another subject with its state, not a second
    object of the same verb ("I need the tomato and the lettuce sliced")."""
    p = max((k for k, x in enumerate(items) if x.prep in ("in", "on", "into", "onto", "inside", "to", "at")), default=-1)
    return p > 0 and p + 1 < len(items) and _skip_np(items, p + 1) == len(items)


_NP_WORDS = _W.set("np_words")
#: adjectives inside a subject ("the big floor lamp's still on")
_NP_ADJECTIVES = _W.set("np_adjectives")
#: nouns plural in form though the lexicon lists them as one thing ("the keys live in a
#: drawer": a plural subject takes the verb's base form)
_PLURAL_IN_FORM = _W.set("plural_in_form")


def _skip_np(items: list[Item], j: int) -> int:
    """The index after a simple noun phrase at ``j`` (``j`` when there is none)."""
    k = j
    named = False
    while k < len(items):
        x = items[k]
        if x.noun is not None or x.pron in ("it", "they", "them", "this", "that"):
            named = True
        elif not (x.det or x.quant is not None or x.number is not None or x.ordinal is not None
                  or x.text in _NP_WORDS or x.text in lx.MEASURE_WORDS or x.text in _NP_ADJECTIVES
                  or (x.state is not None and x.prep is None and x.particle is None)):
            break
        if x.punct is not None or x.conj is not None or (x.verb is not None and x.noun is None):
            break
        k += 1
    return k if named or (k > j and items[k - 1].number is not None) else j


def _skip_relative(items: list[Item], k: int) -> int:
    """The index after a relative clause of where a subject is ("that are lying on the
    desk"), ``k`` when there is none."""
    start = _RELATIVE_PLACE.end(items, k)
    if start is None or _skip_np(items, start - 1) == start - 1:
        return k
    return _skip_np(items, start - 1)


def subject_here(items: list[Item], j: int, asked: bool = False) -> str | None:
    """Does a subject with its own predicate start at ``j``? Which kind: "copula" (",
    the microwave is fine", ", all three need to be cold"), "verb" ("and the fork goes in
    the drawer") or "state" ("- lights off, blinds down"); None when not. A noun phrase
    followed by a place or by another noun phrase is not one ("put the apple, the egg in
    the fridge"). ``asked``: the sentence is a question with a modal, whose later subjects
    take the verb's base form ("could the mug go ..., and the book go on the bed?")."""
    n = len(items)
    k = _skip_np(items, j)
    if k == j or k >= n:
        return None
    while True:
        # a subject: noun phrases with where they are, coordinated ("my phone off the desk
        # and the keys that are lying on the other desk should go ...")
        k = _skip_relative(items, k)
        k += 1 if _ADVERB_THEN_PLACE.at(items, k) else 0
        while k + 1 < n and items[k].prep in _SUBJECT_PLACES and _skip_np(items, k + 1) > k + 1:
            k = _skip_np(items, k + 1)
        if k + 1 < n and items[k].conj == "and" and _skip_np(items, k + 1) > k + 1:
            k = _skip_np(items, k + 1)
            continue
        break
    if k >= n:
        return None
    k += 1 if _LEFT_IN_A_STATE.at(items, k) else 0
    it = items[k]
    predicate = first_rule(_SUBJECT_PREDICATE, items, k)
    if predicate is not None:
        return predicate.then
    plural = items[j].text in ("they", "these", "those", "both", "all") or any(
        x.conj == "and" or (x.noun is not None and (x.noun.plural or x.noun.phrase in _PLURAL_IN_FORM))
        for x in items[j:k])
    if it.verb is not None and (it.verb.form == "s" or ((plural or asked) and it.verb.form == "base")) \
            and it.noun is None \
            and it.verb.sense.act is lx.Act.GO:
        return "verb"       # "and the fork goes in the drawer", ", they both go in the fridge"
    while k < n and items[k].text in ("both", "all", "each"):
        k += 1      # "they both want to go in the basket"
    if k < n and _MODAL_PREDICATE.at(items, k) and items[j].text not in ("that", "which", "who"):
        return "verb"       # ", the egg in the sink wants to go in the fridge"
    return None


def _also_item(items: list[Item], j: int) -> bool:
    """Is ``items[j:]`` a noun phrase and "too" ("and the lettuce too", "the mug as
    well"), up to the end of the clause?"""
    m = _skip_np(items, j)
    n = len(items)
    if m == j or m >= n:
        return False
    if items[m].prep in _SUBJECT_PLACES and m + 1 < n and _skip_np(items, m + 1) > m + 1:
        m = _skip_np(items, m + 1)      # "and the spray bottle on the toilet too"
    return _TOO_AT_END.at(items, m)


def _with_a_place(items: list[Item], j: int) -> bool:
    """After "with": a thing and where it is to be ("with the remote on the sofa")."""
    k = _skip_np(items, j)
    return j < k < len(items) and items[k].prep in ("on", "in", "inside", "onto", "into")


def _state_item_here(items: list[Item], j: int) -> bool:
    """Does a "thing state" item start at ``j`` ("tap running", "light off")?"""
    k = _skip_np(items, j)
    if k == j or k >= len(items):
        return False
    return not _PLACE_NOT_STATE.at(items, k) and _RUN_ON_STATE.at(items, k)


#: places that may describe a subject ("the potato on the table by the coffee machine")
_SUBJECT_PLACES = _W.set("subject_places")

def _sentence_adverb(it: Item) -> bool:
    """"..., but honestly the egg has gone off": an adverb that comments on the clause
    (no reading of its own, ends in -ly) does not hide where the clause starts."""
    return it.text.endswith("ly") and len(it.text) > 4 and not it.is_content() and it.prep is None \
        and it.number is None and it.seq is None and it.sub is None


def _after_commas(items: list[Item], j: int) -> int:
    while j < len(items) and items[j].punct == ",":
        j += 1
    return j


class _Cut(NamedTuple):
    """A boundary rule's decision: the link of the clause that starts (None: no boundary
    after all), how many items the boundary takes, and whether the new clause is "only"
    ("..., only the floor lamp")."""

    link: str | None
    skip: int = 0
    only: bool = False


def _content(items: list[Item]) -> bool:
    return any(x.is_content() for x in items)


def _numbered_item(sentence: list[Item], j: int) -> bool:
    """"three things: 1) the wine goes in the fridge, 2) the phone on the counter": a
    number between punctuation numbers an item of a list."""
    return sentence[j].number is not None and (j == 0 or sentence[j - 1].punct is not None) \
        and j + 1 < len(sentence) and sentence[j + 1].punct is not None


def _ordinal_step(sentence: list[Item], j: int) -> bool:
    """"first open the fridge, second take out the egg, third close it": an ordinal before
    a verb numbers the steps of a list."""
    it = sentence[j]
    return it.seq is None and it.text in _LIST_ORDINALS and (j == 0 or not sentence[j - 1].det) \
        and verb_here(sentence, _after_commas(sentence, j + 1))


def _trailing_sequence(sentence: list[Item], j: int) -> bool:
    """"open a drawer and shut it after(wards)": a sequence word that ends its sentence
    orders its own clause after the one before, as a "then" before it would."""
    it = sentence[j]
    return (it.seq is not None or it.text == "after") and not any(
        x.is_content() or x.pron is not None or x.copula for x in sentence[j + 1:])


def _sequence_marker(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    if sentence[j].seq is not None:
        return _Cut(THEN, 1)
    if _ordinal_step(sentence, j):
        return _Cut(THEN, _after_commas(sentence, j + 1) - j)
    return None


def _person_then_request(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"when I come back I want the light off": the main clause after a subordinate one,
    without a comma between them."""
    if current.link not in (AND, THEN) and _PERSON_ACTS.at(sentence, j) \
            and any(x.verb is not None or x.particle is not None for x in current.items):
        return _Cut(AND)
    return None


def _persons_act_then_request(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"before you go put the apple in the fridge", "while you're at it switch the TV off":
    a person's act, then the request."""
    it, items = sentence[j], current.items
    if current.link not in (AND, THEN) and len(items) >= 2 and items[0].text in _HUMAN \
            and any((x.verb is not None and x.noun is None) or x.particle is not None
                    or (x.copula and k + 1 < len(items)) for k, x in enumerate(items[1:], 1)) \
            and it.verb is not None and verb_here(sentence, j) \
            and items[-1].text not in ("have", "has", "had", "ve", "to") \
            and not any(x.verb is not None and x.verb.lemma in _WISH_VERBS for x in items) \
            and (it.noun is None or items[-1].pron is not None):
        return _Cut(AND)
    return None


#: what opens a time clause besides a subordinator ("by the time I'm back ...")
_TIME_OPENERS = _W.phrases("time_openers")
_OPENER_WORDS = frozenset(p[0] for p in _TIME_OPENERS)


def _time_then_subject(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"by the time I'm back the keys are in the box", "when I get home the TV is on": a
    subject with its own predicate after a time clause of the speaker's own doing (a person,
    a verb, no thing named), without a comma between them."""
    it, timed = sentence[j], current.link not in (AND, THEN, None)
    if not (it.det or it.noun is not None) or not (timed or (current.items and current.items[0].text in _OPENER_WORDS)):
        return None     # (most places: no subject here, or no time clause before it)
    words = [x for x in current.items if x.punct is None]
    opener = next((len(p) for p in _TIME_OPENERS if tuple(x.text for x in words[:len(p)]) == p), 0)
    if not (opener or timed):
        return None
    rest = words[opener:]
    if not (len(rest) >= 2 and rest[0].text in _HUMAN and any(x.verb is not None or x.copula for x in rest[1:])
            and not any(x.noun is not None and x.noun.concept.kind != "room" for x in rest)):
        return None
    last = rest[-1]
    if (last.verb is not None and not last.copula and last.verb.sense.act is not lx.Act.GO) or last.det \
            or last.quant is not None or (last.prep is not None and last.particle is None):
        return None     # "when I get (home)", "when I open the (box)": its object or place is still to come
    if (it.noun is not None and it.noun.concept.kind == "room") or subject_here(sentence, j) is None:
        return None
    return _Cut(AND)


def _state_then_request(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"once it's sliced stick a couple of the slices in the fridge", "once the mug's full
    switch the coffee maker off": the state, then the request."""
    it, items = sentence[j], current.items
    if current.link not in (AND, THEN) and len(items) >= 3 \
            and (_IT_IS.at(items) or (_skip_np(items, 0) == len(items) - 2 and items[-2].copula)) \
            and _READY_STATE.at(items, len(items) - 1) \
            and it.verb is not None and (it.noun is None or _TAKES_OBJECT.at(sentence, j)) \
            and it.verb.form == "base" and verb_here(sentence, j):
        return _Cut(AND)
    return None


def _condition_then_state(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"if the floor lamp's on, off with it", "if it's shut, open": after the condition's
    state and a comma, a bare state word is the branch, said without a verb."""
    items = current.items
    if current.link == "if" and sentence[j].punct == "," and len(items) >= 2 and items[-1].state is not None \
            and any(i.copula for i in items) and j + 1 < len(sentence) and sentence[j + 1].state is not None:
        return _Cut(AND)
    return None


def _robot_named(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    return _Cut(AND) if sentence[j].robot is not None and _content(current.items) else None


def _run_on_request(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"bring me the book from the desk put it on the bed": a run-on request; "the remote
    is on the tv stand can you put it on the sofa": a run-on statement, then the request."""
    items = current.items
    if not items:       # (asked at every word: the cheap tests first)
        return None
    if items[-1].noun is not None \
            and (_RUN_ON_IT.at(sentence, j) or (_RUN_ON_VERB.at(sentence, j) and items[0].verb is not None
                                                and items[0].noun is None)) \
            and any(x.verb is not None and x.noun is None for x in items):
        return _Cut(AND)
    if _ASK_SOMEONE.at(sentence, j) and _content(items) and any(x.copula or x.verb is not None for x in items):
        return _Cut(AND)
    return None


def _coordination(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """A comma, "and", "but", "plus", "as well as": a boundary when what follows starts a
    clause of its own (:func:`_starts_new`)."""
    if not _COORDINATOR.at(sentence, j):
        return None
    k = j + 1
    while k < len(sentence) and (sentence[k].punct == "," or sentence[k].text in ("and", "but")
                                 or _sentence_adverb(sentence[k])):
        k += 1
    comma = any(sentence[x].punct == "," for x in range(j, k))
    if _ONLY_THE.at(sentence, k) and any(x.neg for x in current.items):
        # "don't turn off the desk lamp, only the floor lamp": the act, not negated, on
        # what follows
        return _Cut(AND, k + 1 - j, only=True)
    if k < len(sentence) and _starts_new(sentence, k, current.items, comma):
        return _Cut(AND, k - j)
    if _also_item(sentence, k) and _content(current.items):
        return _Cut(AND, k - j)     # "the egg in the fridge, and the lettuce too": the act before, on it
    if comma and k + 1 < len(sentence) and sentence[k].prep == "with" \
            and _with_a_place(sentence, k + 1) and _has_predicate(current.items):
        return _Cut(AND, k + 1 - j)     # "..., with the remote on the sofa": and the remote on the sofa
    return _Cut(None, 1)


def _subordinator(sentence: list[Item], j: int, current: Clause) -> _Cut | None:
    """"after", "before", "when", "if", "by" + gerund, "so that", "to" (a purpose)."""
    it = sentence[j]
    if it.sub is None:
        return None
    nxt = sentence[j + 1] if j + 1 < len(sentence) else None
    is_sub = it.sub != "by" or (nxt is not None and nxt.verb is not None and nxt.verb.form == "ing")
    if it.text == "as" and nxt is not None and nxt.text in ("to", "well", "soon"):
        is_sub = nxt.text != "well"
    skip = 2 if it.text == "so" and nxt is not None and nxt.text == "that" else 1
    link = it.sub if is_sub else None
    if it.text == "after" and nxt is not None and nxt.verb is not None and nxt.verb.form == "base" \
            and (nxt.noun is None or _TAKES_OBJECT.at(sentence, j + 1)):
        link = THEN     # "... and after close the box": afterwards
    if _SO_I_WAS.at(sentence, j):
        link = AND      # "so I was going to bake": what happened, no purpose
    return _Cut(link, skip)


def _run_on_states(sentence: list[Item], j: int, current: Clause) -> bool:
    """"soap in the sink tap running light off": states typed without commas, each after
    its own subject."""
    return j > 1 and (_STATE_THEN_THING.at(sentence, j - 2) or (
        _NOUN_THEN_THING.at(sentence, j - 1) and _ends_with_place(current.items))) \
        and _state_item_here(sentence, j) and _content(current.items)


#: the rules that say whether a clause starts at an item, in order: the first that applies
#: decides (its link may be None: no boundary after all)
BOUNDARY_RULES: tuple[Callable[[list[Item], int, Clause], _Cut | None], ...] = (
    _sequence_marker, _person_then_request, _persons_act_then_request, _time_then_subject, _state_then_request,
    _condition_then_state, _robot_named, _run_on_request, _coordination, _subordinator,
)


def _boundary(sentence: list[Item], j: int, current: Clause) -> _Cut:
    cut = next((c for rule in BOUNDARY_RULES if (c := rule(sentence, j, current)) is not None), _Cut(None, 1))
    if cut.link is None and _run_on_states(sentence, j, current):
        return _Cut(AND)
    return cut


def segment(items: list[Item]) -> list[Clause]:
    """Clauses in textual order (:data:`BOUNDARY_RULES` say where each starts)."""
    clauses: list[Clause] = []
    robot: tuple[str, int] | None = None
    for s_index, (sentence, end) in enumerate(_sentences(items)):
        current = Clause([], AND, None, s_index, initial=True)
        first_in_sentence = True
        j = 0
        while j < len(sentence):
            if _numbered_item(sentence, j):
                if _content(current.items):
                    clauses.append(current)
                    current = Clause([], AND, None, s_index, initial=False)
                j += 2
                continue
            if _ordinal_step(sentence, j) and not _content(current.items):
                j = _after_commas(sentence, j + 1)
                continue
            if _content(current.items) and _trailing_sequence(sentence, j):
                current.link = THEN if current.link == AND else current.link
                j += 1
                continue
            cut = _boundary(sentence, j, current)
            if cut.link is None:
                current.items.append(sentence[j])
                j += 1
                continue
            link = current.link if not current.items and cut.link == AND else cut.link  # ", and then ,"
            if current.items:
                clauses.append(current)
                first_in_sentence = False
            current = Clause([], link, None, s_index, initial=first_in_sentence)
            if cut.only:
                current.extra["only"] = "1"
            j += cut.skip
        if end == ":":
            current.extra["colon"] = "1"     # "Bed: pillow and teddy": a label for what follows
        if end == "?":
            for c in [*(c for c in clauses if c.sentence == s_index), current]:
                c.extra["question"] = "1"
        if current.items:
            clauses.append(current)
        robot = _address(clauses, s_index, robot)
    for c in clauses:
        c.items = without_role(c.items)     # "whoever has the knife skills": a robot, no thing
    return [c for c in clauses if c.items]


def _address(clauses: list[Clause], s_index: int, robot: tuple[str, int] | None) -> tuple[str, int] | None:
    """"robot 2, open the box" addresses its clause and the rest of the sentence; a clause
    that is only a robot name ("Robot 1:") addresses everything until the next robot is
    named. Returns the robot addressed from here on."""
    sentence_robot: tuple[str, int] | None = None
    for c in clauses:
        if c.sentence != s_index:
            continue
        named = [x.robot for x in c.items if x.robot is not None]
        if named:
            sentence_robot = named[-1]
            c.items = _without_robot_words(c.items)
            if not _content(c.items):
                robot = sentence_robot
        c.robot = sentence_robot if sentence_robot is not None else robot
    return robot
