"""Self-corrections: "put the bread in the fridge? No, on the counter", "put the phone on
the desk... I mean, in the drawer", "put the racket in the corner, no wait, on the bed".
The words after a correction marker replace the part of what came before that they
match: a place replaces the last place, a noun phrase the last noun phrase, a whole new
clause the clause before. Done on the tagged items, before clause segmentation, so that
everything downstream sees the corrected instruction only.
"""

from __future__ import annotations

from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.tagger import Item

_W = word_tables("corrections")
_CALLED_OFF, _RESTART = (pattern_tables("corrections").pattern(name) for name in ("called_off", "restart"))
#: marker word sequences; a bare "no"/"sorry" is a marker only between punctuation
_MARKERS = _W.phrases("markers")
_BREAK = frozenset(".!?;:,")


def _marker_at(items: list[Item], k: int) -> int:
    """Length of a correction marker starting at ``items[k]`` (0 if none)."""
    for m in _MARKERS:
        words = [x.text for x in items[k:k + len(m)]]
        if tuple(words) != m:
            continue
        before = items[k - 1].punct if k > 0 else "."
        after = items[k + len(m)] if k + len(m) < len(items) else None
        if after is None:
            return 0
        restart = m == ("no",) and k > 0 and _RESTART.at(items, k - 1)
        if len(m) == 1 and not restart and (before is None or not (after.punct == "," or after.prep is not None)):
            continue     # "no one", "sorry to bother you", "rather the mug than ..."
        if restart:
            return len(m)    # "put the spray bottle and the no the soap bar ...": said again
        if before is None and m not in (("i", "mean"), ("or", "rather"), ("no", "wait")):
            continue
        return len(m)
    return 0


def _is_np_item(x: Item) -> bool:
    return bool(x.det or x.noun is not None or x.number is not None or x.quant is not None
                or (x.state is not None and x.prep is None and x.particle is None))


def _starts_clause(x: Item) -> bool:
    return x.verb is not None and x.noun is None and x.prep is None and x.verb.form == "base"


def apply_corrections(items: list[Item]) -> list[Item]:
    """The items with every self-correction applied (unchanged when there is none)."""
    k = 0
    out = list(items)
    while k < len(out):
        size = _marker_at(out, k)
        if not size:
            k += 1
            continue
        before = out[:k]
        while before and before[-1].punct is not None:
            before.pop()
        after = out[k + size:]
        while after and after[0].punct is not None:
            after.pop(0)
        end = next((i for i, x in enumerate(after) if x.punct in (".", "!", "?", ";")), len(after))
        fix, rest = after[:end], after[end:]
        if not before or not fix:
            k += size
            continue
        head = fix[0]
        cut: int | None = None
        if _CALLED_OFF.at(fix):
            # "turn on the faucet - no wait, don't, just switch off the light": the act
            # before is called off, what follows stands
            cut = max((i + 1 for i, x in enumerate(before) if x.punct in _BREAK), default=0)
            tail = fix[2:]
            while tail and tail[0].punct is not None:
                tail = tail[1:]
            out = [*before[:cut], *tail, *rest]
            k = cut
            continue
        if len(fix) > 2 and head.det and fix[1].text == "one" and fix[2].prep is not None:
            # "that ladle on the counter, sorry, the one next to the bowl": the same object,
            # told apart by another place
            place = max((i for i, x in enumerate(before) if x.prep is not None and i > 0
                         and before[i - 1].noun is not None), default=None)
            if place is not None:
                told = list(fix[2:])
                comma = next((i for i, x in enumerate(told) if x.punct == ","), None)
                if comma is not None:
                    del told[comma]       # "..., the one next to the bowl, lives in a drawer"
                out = [*before[:place], *told, *rest]
                k = place + len(told)
                continue
        if _starts_clause(head):
            # "put the phone on the desk... I mean, put it in the drawer": a new clause
            cut = max((i + 1 for i, x in enumerate(before) if x.punct in _BREAK), default=0)
        elif head.prep is not None:
            cut = max((i for i, x in enumerate(before) if x.prep is not None
                       and x.prep not in ("of", "with")), default=None)
        elif _is_np_item(head):
            i = len(before)
            while i > 0 and _is_np_item(before[i - 1]):
                i -= 1
            cut = i if i < len(before) else None
        if cut is None:
            k += size
            continue
        out = [*before[:cut], *fix, *rest]
        k = cut + len(fix)
    return out
