"""Point of doubt: a self-correction of the thing, "put the pen - no, the pencil, the pen
can stay - in the drawer": the reader may keep the rejected side.

After a correction cue, a thing named right after it (of another type, in no goal)
replaces the thing named right before it in that thing's goals; when the rejected thing
is then said to stay ("the pen can stay"), its present place joins the alternative (two
edits at once: the wrong goal dropped and the right one added). The cues are data
(``rule_words.json``, ``correction_object``).
"""

from __future__ import annotations

from emboteam.pfg.candidates import AS_READ, Choice, Doubt
from emboteam.pfg.offline.doubts.context import DoubtContext, ref_types
from emboteam.pfg.offline.doubts.rule_words import load_rule_words, sentence_bounds
from emboteam.pfg.offline.doubts.stays import present
from emboteam.pfg.offline.doubts.wants import with_subject
from emboteam.pfg.sentences import type_name
from emboteam.world.catalogue import load_catalogue

KIND = "correction_object"


def _pickupable(type_: str) -> bool:
    return "pickupable" in load_catalogue().type(type_).properties


def doubts(ctx: DoubtContext) -> list[Doubt]:
    words = load_rule_words()
    rule = words.correction_object
    keepers = set(words.stays.keepers)
    things = [(k, ts[0]) for k, _, ts in ctx.mentions() if _pickupable(ts[0])]
    out: list[Doubt] = []
    for cue, item in enumerate(ctx.items):
        if item.text not in rule.cues or cue == 0:
            continue
        before = [(k, t) for k, t in things if cue - rule.reach <= k < cue]
        after = [(k, t) for k, t in things if cue < k <= cue + rule.reach]
        if not before or not after:
            continue
        (_, old), (at, new) = before[-1], after[0]
        if old == new or new in ctx.goal_types():
            continue
        mine = tuple(c for c in ctx.goals if old in ref_types(c.subject))
        if not mine:
            continue
        add = [with_subject(c, new) for c in mine]
        _, end = sentence_bounds(ctx.items, at)
        again = [k for k, t in things if t == old and at < k < end]
        if again and any(i.text in keepers for i in ctx.items[again[0]:min(end, again[0] + 4)]):
            add += [c for c in present(ctx, old) if c not in add]
        out.append(Doubt(KIND, f"{ctx.items[before[-1][0]].text} - {ctx.items[at].text}", (
            Choice(AS_READ, f"the {type_name(old)} as read"),
            Choice("other_thing", f"the {type_name(new)} instead of the {type_name(old)}", drop=mine,
                   add=tuple(add)))))
    return out
