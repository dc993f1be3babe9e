"""A mention's own words: its stretch of the sentence, the cue words around it and
whether they frame it as chatter.

Split from ``mention_cues`` (the doubt rule) so that ``explained`` can ask whether a
mention is chatter without importing the rule that itself asks ``explained`` why a
mention needs no goal (the two used to import each other).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cache
from pathlib import Path
from typing import Literal

from pydantic import Field, field_validator

from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.rule_words import Words, sentence_bounds, starts_at
from emboteam.pfg.offline.knowledge import Strict as _Closed
from emboteam.pfg.offline.knowledge import known_types, read

MENTION_CUES_FILE = Path(__file__).with_name("mention_cues.json")
#: how far back (in words) an excluder or a place preposition reaches
REACH = 4


class SidedCue(_Closed):
    words: Words = Field(min_length=1)
    #: where the cue stands from the thing: "the lamp stays" (after), "leave the lamp" (before)
    side: Literal["before", "after", "either"]


class MentionCues(_Closed):
    about: str = ""
    keep: list[SidedCue]
    #: words that are a state only with no place after them ("stays on" / "stays on the shelf")
    place_preps: list[str]
    #: words that say a state as it is (with the tagger's copulas): "its broken anyway"
    copulas: list[str]
    #: words between a copula and a state that make it wanted: "should be", "is always on"
    wishes: list[str]
    #: words that start a condition: a state after one is not asked of the thing
    condition_words: list[str]
    #: things switched as a group ("lights off"): one kept out of its group's switch is an exception
    groups: list[list[str]]
    #: keeping cues that name the start state itself ("stays how it is", "the way it is"):
    #: a thing kept so keeps its start switch state, never read as an exception to its group
    as_is: list[SidedCue] = Field(default_factory=list)
    chatter: list[SidedCue]
    #: how far from the thing a keeping cue may stand ("the keys stay on the little table")
    cue_reach: int = Field(6, ge=1, le=20)
    chatter_reach: int = Field(4, ge=1, le=12)
    #: people and animals a ramble names ("my brother", "the dog"): chatter, not things
    beings: list[str]


    @field_validator("groups")
    @classmethod
    def _known(cls, v: list[list[str]]) -> list[list[str]]:
        return [known_types(group) for group in v]


@cache
def load_mention_cues(path: Path = MENTION_CUES_FILE) -> MentionCues:
    """The cue file, checked by its schema (a malformed entry is a
    :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming file and entry)."""
    return read(path, MentionCues)


def being(phrase: str | None) -> bool:
    """Whether a phrase that names nothing in the scene is a person or an animal ("my
    brother", "the dog"): chatter in a ramble, not a thing the scene lacks."""
    return phrase is not None and bool(phrase.split()) and phrase.split()[-1] in load_mention_cues().beings


def after_preposition(ctx: DoubtContext, k: int, start: int) -> bool:
    """Whether the mention at ``k`` is the object of a preposition: one stands before it
    within reach, with no verb, state word or conjunction between ("to the box", not
    "to an open the blinds": a preposition governs its noun phrase, not past a verb)."""
    for j in range(k - 1, max(start, k - REACH) - 1, -1):
        item = ctx.items[j]
        if item.prep is not None and item.noun is None:
            return True
        if item.verb is not None or item.state is not None or item.conj is not None:
            return False
        if item.det and j > start and not (ctx.items[j - 1].prep or ctx.items[j - 1].det):
            return False     # a new noun phrase: "by dinner time the potato ...", "round here the watch"
    return False


def _is_place(ctx: DoubtContext, m: int) -> bool:
    return after_preposition(ctx, m, ctx.clause_bounds(m)[0])


def answers(ctx: DoubtContext) -> dict[object, object]:
    """This module's answers for one context, kept on it (the rules and the explanations
    ask the same mentions and stretches many times per instruction; the context is frozen,
    so they are stored as its cached properties are, in its ``__dict__``)."""
    return ctx.__dict__.setdefault("_mention_cues_memo", {})     # type: ignore[no-any-return]


def segment(ctx: DoubtContext, k: int) -> tuple[int, int]:
    """[start, end) of the mention's own words: its sentence, cut at the nearest mentions
    of other things that are not places (a place belongs to the stretch of its thing; a
    clause after a comma is still about it: "the phone, which stays on the desk")."""
    memo = answers(ctx)
    if ("segment", k) not in memo:
        memo["segment", k] = _segment(ctx, k)
    return memo["segment", k]      # type: ignore[return-value]


def _segment(ctx: DoubtContext, k: int) -> tuple[int, int]:
    start, end = sentence_bounds(ctx.items, k)
    thing = set(ctx.named_types(ctx.items[k], verbs_too=True))
    # every word that may name another thing cuts, a verb-like one too ("- microwave's fine")
    for m in range(start, end):
        types = ctx.named_types(ctx.items[m], verbs_too=True)
        if m == k or not types or set(types) & thing or _is_place(ctx, m):
            continue
        if m < k:
            start = m + 1
        else:
            end = m
            break
    return start, end


def found(ctx: DoubtContext, lo: int, hi: int, words: Words) -> list[int]:
    """Where the words start between ``lo`` and ``hi`` (the whole phrase inside)."""
    # only where the first word stands (every cue of every mention is looked for)
    return [s for s in _positions(ctx).get(words[0], ()) if lo <= s <= hi - len(words)
            and starts_at(ctx.items, s, words)]


def _positions(ctx: DoubtContext) -> dict[str, list[int]]:
    """Each word of the instruction -> where it stands, in order (kept on the context:
    its items do not change)."""
    memo = answers(ctx)
    if "positions" not in memo:
        at: dict[str, list[int]] = {}
        for k, item in enumerate(ctx.items):
            at.setdefault(item.text, []).append(k)
        memo["positions"] = at
    return memo["positions"]      # type: ignore[return-value]


def side(ctx: DoubtContext, k: int, lo: int, hi: int, cues: Sequence[SidedCue]) -> str | None:
    """On which side of ``k`` ("before", "after") a cue stands within [lo, hi) (and
    ``cue_reach`` words), not right after a negation; None when none does."""
    reach = load_mention_cues().cue_reach
    lo, hi = max(lo, k - reach), min(hi, k + 1 + reach)
    said = _positions(ctx)
    for cue in cues:
        if cue.words[0] not in said:
            continue        # not in the instruction at all
        starts = []
        if cue.side in ("before", "either"):
            starts += found(ctx, lo, k, cue.words)
        if cue.side in ("after", "either"):
            starts += found(ctx, k + 1, hi, cue.words)
        for s in starts:
            if not any(i.neg for i in ctx.items[max(lo, s - 2):s]):
                return "before" if s < k else "after"
    return None


def sided(ctx: DoubtContext, k: int, lo: int, hi: int, cues: Sequence[SidedCue]) -> bool:
    return side(ctx, k, lo, hi, cues) is not None


def chatter(ctx: DoubtContext, k: int) -> bool:
    """Whether a chatter cue frames the mention ("we used to have a magazine rack")."""
    data = load_mention_cues()
    start, end = segment(ctx, k)
    return sided(ctx, k, max(start, k - data.chatter_reach), min(end, k + 1 + data.chatter_reach), data.chatter)


