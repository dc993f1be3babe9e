"""An unexplained mention's own window: where the scene lets the thing go, by the words
after it ("Pen's on the floor - up, into the mug", "the remote isn't in the drawer where
it belongs", "the frying pan still on its burner", "the pillow, is that on the sofa?
Good, it stays").

The window runs from the mention to the next thing named that is neither a place nor
listed with it ("the card and the keys, from the table to a drawer"), or to the end of
its sentence, and on over the next sentence when that one names no other thing. In it:

- a *keep* cue keeps the thing where it is (its present receptacle);
- a receptacle the catalogue lets it go in (:meth:`Catalogue.can_place`), after a
  *towards* word, not after a *source* word ("from the table") or a negation, and not
  where the thing is already (that is where it lies, not where it goes); a *home* cue
  after the receptacle ("where it belongs") makes it the place even under a negation.

What it finds is strong evidence: the unexplained-mention doubt (:mod:`.unexplained`)
then offers only this goal beside leaving the thing out, with a prior above leaving it.
The cue words are data (``window_cues.json``, schema :class:`WindowCues`).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from pydantic import BaseModel, ConfigDict, Field

from emboteam.pfg.offline.doubts.context import DoubtContext
from emboteam.pfg.offline.doubts.explained import CORRECTIONS
from emboteam.pfg.offline.doubts.mention_cues import said_state
from emboteam.pfg.offline.doubts.mention_words import after_preposition
from emboteam.pfg.offline.doubts.rule_words import Words, find, load_rule_words
from emboteam.pfg.offline.doubts.wants import asked_predicate, one_object, placed
from emboteam.pfg.offline.knowledge import read
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, Predicate

WINDOW_CUES_FILE = Path(__file__).with_name("window_cues.json")
#: the labels of the goals a window gives (priors.json, kind unexplained_mention)
PLACE, KEEP = "window_place", "window_keep"


class WindowCues(BaseModel):
    model_config = ConfigDict(extra="forbid")
    about: str = ""
    towards: list[Words]
    sources: list[Words]
    home: list[Words]
    keep: list[Words]
    #: words that say the place holds already ("the tomato's already in the fridge"): no goal
    described: list[Words]
    #: the longest window, in words
    reach: int = Field(14, ge=2, le=40)
    #: people and animals a ramble names ("my brother", "the dog"): chatter, not things
    beings: list[str]


@cache
def load_window_cues(path: Path = WINDOW_CUES_FILE) -> WindowCues:
    """The cue file, checked by its schema (a malformed entry is a
    :class:`~emboteam.pfg.offline.knowledge.KnowledgeDataError` naming file and entry)."""
    return read(path, WindowCues)


def being(phrase: str | None) -> bool:
    """Whether a phrase that names nothing in the scene is a person or an animal ("my
    brother", "the dog"): chatter in a ramble, not a thing the scene lacks."""
    return phrase is not None and bool(phrase.split()) and phrase.split()[-1] in load_window_cues().beings


def _listed(ctx: DoubtContext, last: int, m: int) -> bool:
    """Whether only determiners, conjunctions, commas and numbers stand between two
    mentions (a list: "the card and the keys")."""
    return all(i.det or i.conj or i.punct == "," or i.number is not None for i in ctx.items[last + 1:m])


def _other_thing(ctx: DoubtContext, m: int, thing: str) -> bool:
    types = ctx.named_types(ctx.items[m])
    return bool(types) and thing not in types and not after_preposition(ctx, m, ctx.clause_bounds(m)[0])


def window(ctx: DoubtContext, k: int, thing: str) -> tuple[int, int]:
    """[k + 1, end) of the words that may say where the thing at ``k`` goes."""
    ends = set(load_rule_words().sentence_ends)
    limit = min(len(ctx.items), k + 1 + load_window_cues().reach)
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


def _present(ctx: DoubtContext, thing: str) -> set[str]:
    """The types of the receptacles the things of the type stand in now."""
    return {ctx.state.obj(o.parent).type for o in ctx.state.of_type(thing) if o.parent is not None}


def _receptacle(ctx: DoubtContext, lo: int, hi: int, thing: str, data: WindowCues) -> str | None:
    """The receptacle of the window the thing goes in (see the module's docstring)."""
    cat, here = load_catalogue(), _present(ctx, thing)
    towards = {e - 1 for _, e in find(ctx.items, lo, hi, data.towards)}
    sources = {e - 1 for _, e in find(ctx.items, lo, hi, data.sources)}
    homes = {s for s, _ in find(ctx.items, lo, hi, data.home)}
    for m in range(lo, hi):
        # a word that may be a verb names a thing after a determiner ("in the bin")
        types = ctx.named_types(ctx.items[m], verbs_too=m > 0 and ctx.items[m - 1].det)
        if not types or types[0] == thing or "receptacle" not in cat.type(types[0]).properties \
                or not cat.can_place(thing, types[0]):
            continue
        lead = range(max(lo, m - 3), m)
        if any(j in homes for j in range(m + 1, min(hi, m + 3))):
            return types[0]
        if types[0] in here or any(j in sources for j in lead) or not any(j in towards for j in lead):
            continue
        if not any(i.neg for i in ctx.items[lo:m]):
            return types[0]
    return None


def window_goal(ctx: DoubtContext, k: int, thing: str) -> tuple[str, tuple[Condition, ...]] | None:
    """(label, goals) the window of the mention at ``k`` gives the thing, or None: its
    place, and a state its words ask beside it ("out and burning on the counter")."""
    if "pickupable" not in load_catalogue().type(thing).properties:
        return None
    data = load_window_cues()
    lo, hi = window(ctx, k, thing)
    if any(i.text in CORRECTIONS and i.text != "no" for i in ctx.items[lo:hi]) or find(ctx.items, lo, hi, data.described):
        return None      # "in the drawer - sorry, the box": the correction rules' (corrections.py)
    said = _count(ctx, k, thing)
    if find(ctx.items, lo, hi, data.keep):
        here = sorted(_present(ctx, thing))
        return (KEEP, (_counted(placed(thing, here[0]), said),)) if len(here) == 1 else None
    dest = _receptacle(ctx, lo, hi, thing, data)
    if dest is None:
        return None
    state = said_state(ctx, k, hi, thing) or _changed(ctx, lo, hi, thing)
    pieces = load_catalogue().slice_product(thing) if state is not None and state.predicate is Predicate.sliced else None
    goal = _counted(placed(pieces[0] if pieces else thing, dest), said)     # "the apple cut up on a plate"
    return PLACE, (goal,) if state is None else (state, goal)


#: what a verb of the window may ask beside the place ("is heating in the microwave",
#: "cut up on a plate"); switch and open states come from :func:`.mention_cues.said_state`
_CHANGES = (Predicate.hot, Predicate.cold, Predicate.sliced, Predicate.cooked, Predicate.clean)


def _changed(ctx: DoubtContext, lo: int, hi: int, thing: str) -> Condition | None:
    pred = next((p for i in ctx.items[lo:hi] if (p := asked_predicate(i)) in _CHANGES), None)
    return None if pred is None else one_object(pred, thing)


def _count(ctx: DoubtContext, k: int, thing: str) -> int | None:
    """How many the mention names: its number ("both vases are up on the dresser"), or
    every one the scene has for a plural ("bats are kept on my bedside table")."""
    said = ctx.items[k - 1].number if k > 0 else None
    if isinstance(said, int):
        return said
    noun = ctx.items[k].noun
    return len(list(ctx.state.of_type(thing))) if noun is not None and noun.plural else None


def _counted(goal: Condition, said: object) -> Condition:
    return goal.model_copy(update={"count": said}) if isinstance(said, int) and said > 1 else goal
