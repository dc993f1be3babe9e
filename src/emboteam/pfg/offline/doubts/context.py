"""What every point-of-doubt rule reads: the tagged words, the reading's goal, the scene.

The rules run after the reader has made its reading (they never change it): each looks at
the words and the goal and says where else the words could lead. The helpers here answer
the questions several rules ask: which scene types a word names, where a goal condition's
object is mentioned, which clause a word stands in.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

from emboteam.pfg.offline.discourse import Mention
from emboteam.pfg.offline.tagger import Item
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, ObjectRef
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

#: concept kinds that name objects of the scene
_THING_KINDS = frozenset({"object", "category", "lights", "lamps"})


def type_props(type_: str) -> frozenset[str]:
    """The catalogue's properties of an AI2-THOR type ("receptacle", "toggleable", ...)."""
    return load_catalogue().type(type_).properties


def ref_types(ref: ObjectRef) -> frozenset[str]:
    """The types a reference names, slices folded into their whole."""
    cat = load_catalogue()
    names = ref.types if ref.id is None else (ref.id.split("_")[0],)
    return frozenset(cat.source_type(t) or t for t in names)


def fitting_first(thing: str, types: tuple[str, ...]) -> tuple[str, ...]:
    """A place word's types with those the thing can go in first: a category names the
    member that takes it ("the roll onto the holder": the toilet paper hanger, not the
    towel holder the category lists first)."""
    cat = load_catalogue()
    fits = tuple(t for t in types if t != thing and "receptacle" in type_props(t) and cat.can_place(thing, t))
    return (*fits, *(t for t in types if t not in fits))


def condition_types(c: Condition) -> frozenset[str]:
    """Every type a condition names (its object and its place)."""
    out = ref_types(c.subject)
    return out | ref_types(c.receptacle) if c.receptacle is not None else out


@dataclass(frozen=True)
class DoubtContext:
    """One instruction as read: its tagged words, its goal and the scene."""

    items: Sequence[Item]
    goals: tuple[Condition, ...]
    scene: Scene
    state: WorldState
    history: Sequence[Mention] = ()
    #: the conditions of the reading's intermediate steps ("rinse the tomato": in the sink,
    #: the tap on): their things are accounted for too
    steps: tuple[Condition, ...] = ()

    @cached_property
    def scene_types(self) -> frozenset[str]:
        return frozenset(self.scene.types())

    @cached_property
    def words(self) -> tuple[str, ...]:
        return tuple(i.text for i in self.items)

    def named_types(self, item: Item, verbs_too: bool = False) -> tuple[str, ...]:
        """The scene's types a word names, in the lexicon's order of preference (its
        fallbacks after), none when it names no thing or nothing of this scene (nor, unless
        ``verbs_too``, when it may be a verb: "watch")."""
        if item.noun is None or (item.verb is not None and not verbs_too) or \
                item.noun.concept.kind not in _THING_KINDS:
            return ()
        concept = item.noun.concept
        return tuple(t for t in dict.fromkeys((*concept.types, *concept.fallback)) if t in self.scene_types)

    @cached_property
    def _mentions(self) -> list[tuple[int, Item, tuple[str, ...]]]:
        from emboteam.pfg.offline.doubts.sound_alike import heard

        read = [(k, i, types) for k, i in enumerate(self.items)
                if (types := self.named_types(i, verbs_too=self.noun_slot(k)))]
        misheard = [(k, self.items[k], types) for k, types in heard(self.items, self.scene_types)]
        return sorted(read + misheard + self._pieces(read), key=lambda m: m[0])

    def _pieces(self, read: list[tuple[int, Item, tuple[str, ...]]]) -> list[tuple[int, Item, tuple[str, ...]]]:
        """A piece word after a determiner or a number ("one slice in the toaster", "its
        slices"): the slices of the things the instruction names that cut up into slices,
        the nearest named before it first (an egg's piece is no slice)."""
        from emboteam.pfg.offline.doubts.rule_words import load_rule_words

        pieces, cat = set(load_rule_words().nouns.pieces), load_catalogue()
        wholes = [(m, p[0]) for m, _, ts in read if not ts[0].startswith("Egg") and (p := cat.slice_product(ts[0]))]
        out = []
        for k, item in enumerate(self.items):
            if item.text in pieces and k > 0 and (self.items[k - 1].det or self.items[k - 1].number is not None):
                near = sorted(wholes, key=lambda w: (w[0] > k, abs(w[0] - k)))
                if near:
                    out.append((k, item, tuple(dict.fromkeys(t for _, t in near))))
        return out

    def noun_slot(self, k: int) -> bool:
        """Whether the word at ``k`` stands where only a noun can: after a determiner, a
        number or a quantifier, over at most one untagged word ("the spare roll", "two
        rolls", "my watch"), or right after an attributive adjective ("spare roll",
        ``rule_words.json``, ``nouns``), so a word that is also a verb names a thing there: a thing
        one picks up (a fixed device's word stays the verb it was read as: "the telly's
        light enough", "do the switches")."""
        noun = self.items[k].noun
        if noun is None or noun.concept.kind != "object" or not noun.concept.types or \
                "pickupable" not in type_props(noun.concept.types[0]):
            return False
        from emboteam.pfg.offline.doubts.rule_words import load_rule_words

        for back, item in enumerate(reversed(self.items[max(0, k - 2):k])):
            if item.det or item.number is not None or item.quant is not None or \
                    (not back and item.text in load_rule_words().nouns.attributes):
                return True
            if back or item.is_content() or item.prep is not None or item.punct is not None or item.pron is not None:
                return False
        return False

    def mentions(self) -> list[tuple[int, Item, tuple[str, ...]]]:
        """(position, word, scene types) of every word that names a thing of the scene,
        also a misheard, split or texted name the tagger could not read (:mod:`.sound_alike`)."""
        return self._mentions

    def clause_bounds(self, k: int) -> tuple[int, int]:
        """The positions [start, end) of the stretch of words around ``k`` between
        punctuation marks or sequence/conjunction-led breaks."""
        start = k
        while start > 0 and self.items[start - 1].punct is None and self.items[start - 1].seq is None:
            start -= 1
        end = k + 1
        while end < len(self.items) and self.items[end].punct is None and self.items[end].seq is None:
            end += 1
        return start, end

    def position_of(self, c: Condition) -> int | None:
        """Where the instruction first names the object of a goal condition."""
        subject = ref_types(c.subject)
        return next((k for k, _, types in self.mentions() if subject & set(types)), None)

    @cached_property
    def narrative(self) -> bool:
        """Whether a narrative cue frames the instruction ("by the time", "will find":
        ``rule_words.json``, ``stated``), asked by several rules: found once."""
        from emboteam.pfg.offline.doubts.rule_words import find, load_rule_words

        return bool(find(self.items, 0, len(self.items), load_rule_words().stated.narrative_cues))

    @cached_property
    def corrected(self) -> bool:
        """Whether a self-correction cue was said (``rule_words.json``, ``correction``)."""
        from emboteam.pfg.offline.doubts.rule_words import load_rule_words

        cues = set(load_rule_words().correction.cues)
        return any(i.text in cues for i in self.items)

    @cached_property
    def _goal_types(self) -> frozenset[str]:
        # a slice's goal counts for its whole, and for the slices themselves ("one slice ...")
        return frozenset(t for c in (*self.goals, *self.steps) for t in (*condition_types(c), *c.subject.types))

    def goal_types(self) -> frozenset[str]:
        return self._goal_types
