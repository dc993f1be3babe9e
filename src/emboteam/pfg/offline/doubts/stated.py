"""Point of doubt: a state said as it should be, not complained about.

"When I walk in tonight the laptop is closed and the TV is already on": a narrative of
the end state (or a rule stated as a fact) says the states it wants; the reader takes a
bare "the TV is on" as a complaint and asks for the opposite. The alternative gives the
thing the state its own words say (a state word right after it), when a narrative cue
frames the instruction ("by the time", "will find", "like that again"); without one a
bare state is the reader's complaint. The cues are data (``rule_words.json``, ``stated``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import Stated, load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.wants import asked_predicate, one_object
from emboteam.pfg.sentences import clause, type_name
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Predicate

KIND = "stated"
P = Predicate
#: the states a narrative says of a thing, with the property the thing needs for each
_FAMILIES = {P.switched_on: "toggleable", P.switched_off: "toggleable", P.open: "openable", P.closed: "openable"}


def _stated(ctx: DoubtContext, k: int, words: Stated) -> P | None:
    """The switch or open state a state word right after position ``k`` says (before the
    next thing named, a conjunction or the end of the sentence; not a complaint, "still
    on", nor under a negation)."""
    start, end = sentence_bounds(ctx.items, k)
    named = {m for m, _, _ in ctx.mentions()}
    if any(i.neg for i in ctx.items[max(start, k - 4):k]):
        return None
    for j in range(k + 1, min(end, k + 1 + words.reach)):
        item = ctx.items[j]
        if j in named or item.conj is not None or item.punct is not None or item.text in words.complaint_words:
            return None
        if item.state is not None and (p := asked_predicate(item)) in _FAMILIES:
            return p
    return None


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words().stated
    if not ctx.narrative:
        return []     # without a narrative, a bare "the TV is on" is a complaint: the reader's
    out: list[Doubt] = []
    seen: set[str] = set()
    # "the light's off": a noun that may be a verb ("light") names the thing here too
    named = [(k, item, ts) for k, item in enumerate(ctx.items) if (ts := ctx.named_types(item, verbs_too=True))]
    for k, item, types in named:
        thing = types[0]
        p = _stated(ctx, k, words)
        if p is None or thing in seen or _FAMILIES[p] not in load_catalogue().type(thing).properties:
            continue
        seen.add(thing)
        mine = tuple(c for c in ctx.goals if c.predicate in _FAMILIES and thing in ref_types(c.subject))
        want = one_object(p, thing)
        if want in ctx.goals:
            continue
        label = "as_stated_narrative"
        out.append(Doubt(KIND, item.text, (Choice(AS_READ, "; ".join(clause(c) for c in mine) or "no goal"),
                                           Choice(label, f"{type_name(thing)}: {clause(want)}", drop=mine,
                                                  add=(want,)))))
    return out
