"""A team member named by its role or ability: "whoever has the knife skills slices it",
"the one that does switches turns my lamp off", "the one that only does doors opens the
fridge". Such a subject names a robot, not a thing of the scene: its nouns (the knife, the
switches, the doors) get no goal, and the verb after it is the act. The words are data
(``words.json`` -> ``roles``); the subject ends at the first verb in the third person that
takes an object, before any punctuation ("whichever of you has the hands that grab: the
lettuce goes ..." is no subject: a colon comes first).
"""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.tagger import Item

_W = word_tables("roles")
#: openers that name a team member outright ("whoever", "the one who")
_MEMBERS = _W.phrases("members")
#: openers that name a member only with an ability verb after them ("the one that does ...":
#: "the one that is on the table" is a thing)
_ONES = _W.phrases("ones")
_ABILITIES = _W.phrases("abilities")
_ADVERBS = _W.set("adverbs")
_TAKES_OBJECT = pattern_tables("clauses").pattern("takes_object")
#: how many words a role may take before its verb ("whoever has the knife skills")
_REACH = 8


def _starts(items: Sequence[Item], j: int, phrases: tuple[tuple[str, ...], ...]) -> int:
    """The index after the longest phrase of ``phrases`` at ``items[j]``, else ``j``."""
    best = j
    first = items[j].text if 0 <= j < len(items) else None
    for words in phrases:
        if words and j >= 0 and words[0] != first:     # most phrases start with another word
            continue
        if tuple(x.text for x in items[j:j + len(words)]) == words:
            best = max(best, j + len(words))
    return best


def role_subject(items: Sequence[Item], j: int) -> int:
    """The index of the verb after a role subject at ``j`` ("whoever has the knife skills
    | slices it"), else ``j``."""
    start = _starts(items, j, _MEMBERS)
    if start == j:
        k = _starts(items, j, _ONES)
        if k == j:
            return j
        while k < len(items) and items[k].text in _ADVERBS:
            k += 1
        start = _starts(items, k, _ABILITIES)
        if start == k:
            return j
    for k in range(start + 1, min(len(items), start + _REACH)):
        it = items[k]
        if it.punct is not None:
            return j
        if it.verb is not None and it.verb.form == "s" and _TAKES_OBJECT.at(list(items), k):
            return k
    return j


def without_role(items: list[Item]) -> list[Item]:
    """The clause without a role subject at its start (after "and", "then"): its words are
    no mention of a thing, so no pronoun later takes them ("... slices it, it stays out")."""
    j = 0
    while j < len(items) and (items[j].conj is not None or items[j].seq is not None):
        j += 1
    k = role_subject(items, j)
    if k == j:
        return items
    if _restates_role(items, j, k):
        return items[:j]
    return [*items[:j], *items[k:]]


def _restates_role(items: Sequence[Item], j: int, k: int) -> bool:
    """Does the clause only say who acts ("whoever opens drawers | opens them")? Its verb
    repeats the role's own verb on a pronoun for the role's things: a division of labour,
    not an end state."""
    verb = items[k].verb
    rest = [x for x in items[k + 1:] if x.punct is None]
    return (verb is not None and any(x.verb is not None and x.verb.lemma == verb.lemma for x in items[j:k])
            and len(rest) == 1 and rest[0].pron is not None)


def in_role(items: Sequence[Item], k: int) -> bool:
    """Is ``items[k]`` a word of a role subject ("the knife" of "whoever has the knife
    skills slices it")?"""
    return any(role_subject(items, s) > k for s in range(max(0, k - _REACH), k))
