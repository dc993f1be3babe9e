"""Grounding: a parsed noun phrase -> object references of the scene, with counts.

Only types the scene has are used ("the table" is a DiningTable in a kitchen and a
CoffeeTable in a living room). What the predicate needs narrows the choice (to switch
"the stove" is to switch its knob; a lamp that is a floor lamp here). Plurals and "all"
mean every instance, split per type; numbers mean "that many of these types";
adjectives ("the dirty mug") and places ("the apple in the fridge") pick object ids when
they single out some instances. Anything that cannot be grounded raises
:class:`GroundingError` naming the phrase and the closest objects of the scene.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from dataclasses import dataclass

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.errors import GroundingError, IncapableError
from emboteam.pfg.offline.phrases import Head
from emboteam.pfg.offline.tagger import NounReading
from emboteam.pfg.offline.text import split_camel
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import ObjectRef
from emboteam.world.scene import Scene
from emboteam.world.state import ObjectState, WorldState

Stat = lx.Stat


#: how close a spelling must be to be suggested (difflib ratio): "aple"/"apple" 0.89,
#: "spatual"/"spatula" 0.86; "sponj"/"spoon" 0.8, "piano"/"pan" 0.75 and "bathtub"/"bottle"
#: 0.46 are no help
SUGGEST_RATIO = 0.82


@dataclass(frozen=True)
class Ref:
    """A grounded noun phrase: one or more (reference, count) groups."""

    label: str
    groups: tuple[tuple[ObjectRef, int], ...]
    plural: bool = False

    @property
    def types(self) -> frozenset[str]:
        """Every type the phrase can stand for, slices folded into their whole."""
        cat = load_catalogue()
        return frozenset(cat.source_type(t) or t for ref, _ in self.groups for t in ref_types(ref))

    def type_names(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys(t for ref, _ in self.groups for t in ref_types(ref)))

    def single(self) -> ObjectRef:
        """All groups as one reference (for a receptacle: any of these)."""
        if len(self.groups) == 1:
            return self.groups[0][0]
        return ObjectRef(types=self.type_names())


#: predicate need -> the catalogue property it asks, and what a thing without it cannot be
NEEDS: dict[str, tuple[str, str]] = {
    "switch": ("toggleable", "switched"), "open": ("openable", "opened or closed"), "slice": ("sliceable", "sliced"),
    "break": ("breakable", "broken"), "cook": ("cookable", "cooked"), "dirty": ("dirtyable", "made dirty"),
    "fill": ("canFillWithLiquid", "filled"), "hold": ("pickupable", "picked up"),
    "receptacle": ("receptacle", "used as a place")}


#: a basin and the fixture it belongs to are one place to people ("the soap on the bath"
#: stands on the Bathtub, "in the bath" is its BathtubBasin)
_SAME_PLACE = {"BathtubBasin": "Bathtub", "Bathtub": "BathtubBasin", "SinkBasin": "Sink", "Sink": "SinkBasin"}


class Grounder:
    """Grounds noun phrases in one scene and state."""

    def __init__(self, scene: Scene, state: WorldState) -> None:
        self.scene = scene
        self.state = state
        self.cat = load_catalogue()
        live = [o for o in state.objects.values() if not o.gone]
        self.present: set[str] = {o.type for o in live} | scene.types()
        self._live = live
        #: references chosen with doubt (a fallback type, one instance picked among several
        #: that match, a vague count made concrete): their conditions are reported unsure
        self.doubts: set[ObjectRef] = set()
        self._fell_back = False

    # ---- helpers -------------------------------------------------------------------
    def instances(self, t: str) -> list[ObjectState]:
        return sorted((o for o in self._live if o.type == t), key=lambda o: _id_key(o.id))

    def count_available(self, t: str) -> int:
        """How many objects of type ``t`` there are or could be (pieces of uncut wholes)."""
        n = len(self.instances(t))
        source = self.cat.source_type(t)
        if source is not None:
            product = self.cat.slice_product(source)
            assert product is not None
            n += product[1] * len(self.instances(source))
        return n

    def has_type(self, t: str) -> bool:
        if t in self.present:
            return True
        source = self.cat.source_type(t)
        return source is not None and source in self.present

    def can(self, t: str, need: str | None) -> bool:
        if need is None:
            return True
        if need == "slice":
            return self.cat.slice_product(t) is not None
        prop = NEEDS[need][0]
        if t not in self.cat.types:
            return False
        if self.cat.type(t).has(prop):
            return True
        product = self.cat.slice_product(t)
        return need == "cook" and product is not None and self.cat.type(product[0]).has(prop)

    def suggestions(self, phrase: str, limit: int = 3) -> list[str]:
        """Scene types closest to a phrase, by the spelling of their names and synonyms
        (difflib's ratio: a typo of a name scores high, an unrelated word low). Only close
        spellings (SUGGEST_RATIO) of the phrase or its head (last) word count, and never
        the very object the phrase names: the error is then not about the spelling, and
        "closest objects: Fridge" after "no fridge can be picked up" helps no one."""
        names: dict[str, str] = {}
        for key, concept in lx.nouns().items():
            for t in (*concept.types, *concept.fallback):
                if t in self.present:
                    names.setdefault(key, t)
                    break
        for t in sorted(self.present):
            names.setdefault(split_camel(t).lower(), t)
        scored: dict[str, float] = {}
        words = phrase.lower().split()
        for query in {phrase.lower(), *words[-1:]}:
            matcher = difflib.SequenceMatcher(None, "", query)
            for key, t in names.items():
                matcher.set_seq1(key)
                if matcher.real_quick_ratio() <= scored.get(t, 0.0):
                    continue
                scored[t] = max(scored.get(t, 0.0), matcher.ratio())
        ranked = sorted(scored.items(), key=lambda kv: (-kv[1], kv[0]))
        return [t for t, score in ranked[:limit] if SUGGEST_RATIO <= score < 1.0]

    def fail(self, message: str, phrase: str) -> GroundingError:
        return GroundingError(message, phrase=phrase, suggestions=lambda: self.suggestions(phrase))

    # ---- candidate types -----------------------------------------------------------
    def candidate_types(self, head: Head, need: str | None) -> list[str]:
        """Types the phrase stands for in this scene, narrowed by what is asked of them."""
        phrase = head.label()
        if head.noun is None and head.liquid == "water" and need == "switch":
            head = Head(text=phrase, noun=NounReading(lx.nouns()["faucet"], "faucet", False))
        if head.noun is None:
            if head.unknown:
                word = " ".join(head.unknown)
                raise self.fail(f"{word!r} names nothing EmboTeam knows", word)
            raise self.fail(f"cannot tell what {phrase!r} refers to", phrase)
        concept = head.noun.concept
        if concept.kind == "room" or (concept.kind == "anything" and not head.location):
            what = "a room, not an object" if concept.kind == "room" else "too vague"
            raise GroundingError(f"{phrase!r} is {what}: say which objects", phrase=phrase,
                                 suggestions=lambda: self.suggestions(phrase), vague=True)
        base: list[str] = list(concept.types)
        if concept.kind == "lights" and (head.quant in ("all", "every", "each") or (head.plural
                                         and head.quant is not None)):
            base += ["DeskLamp", "FloorLamp"]
        if concept.kind == "anything":
            return self._things_at(head)
        types = [t for t in base if self.has_type(t)]
        if not types:
            # fallbacks are in order of preference: "the table" of a kitchen without a
            # dining table is its side table, not "a side table or the counter"
            present = [t for t in concept.fallback if self.has_type(t)]
            able = [t for t in present if need is None or self.can(t, need)]
            types = (able or present)[:1]
            self._fell_back = bool(types)
        if not types:
            # "the curtain" of a bathroom: its one kind of curtain (ShowerCurtain)
            word = head.noun.phrase.split()[-1]
            word = word[:-1] if head.noun.plural and word.endswith("s") else word
            types = self._compound_of((*concept.types, word.capitalize()) if word.isalpha() else concept.types, need)
            self._fell_back = bool(types)
        if not types:
            names = "/".join(concept.types)
            noun = head.noun.phrase
            raise self.fail(f"{self.scene.floor_plan} has no {noun} ({names})", noun)
        if head.piece:
            pieces = []
            for t in types:
                product = self.cat.slice_product(t)
                pieces.append(product[0] if product is not None else t)
            types = pieces
        if need is not None:
            able = [t for t in types if self.can(t, need)]
            if not able and need == "switch":
                able = [s for t in types for s in lx.SWITCHED_BY.get(t, ()) if self.has_type(s)]
                # "the bath running": what runs water into this scene's bath (its tap, when
                # it has one), not every water source a bath can have
                wired = [s for s in able if any(self.state.objects[c].type in types
                                                for o in self.instances(s) for c in o.controls
                                                if c in self.state.objects)]
                able = wired or able
            if not able:
                noun = head.noun.phrase
                raise IncapableError(f"no {noun} in {self.scene.floor_plan} can be {NEEDS[need][1]} "
                                     f"({'/'.join(types)})", phrase=noun,
                                     suggestions=lambda: self.suggestions(noun))
            types = list(dict.fromkeys(able))
        return types

    def _compound_of(self, types: tuple[str, ...], need: str | None) -> list[str]:
        """"Where are the tissues? Bring the box out": in a scene without a plain box, the
        one kind of box it has (TissueBox). Only a single such kind counts: two would be a
        guess."""
        kinds = sorted({o.type for o in self._live for t in types
                        if o.type != t and o.type.endswith(t) and o.type[-len(t) - 1].islower()})
        able = [k for k in kinds if need is None or self.can(k, need)]
        return able if len(able) == 1 else []

    def _things_at(self, head: Head) -> list[str]:
        """"everything on the table": pickupable types found there."""
        places = [self.ground(land, None) for _, land in head.location]
        out: list[str] = []
        for o in self._live:
            if not o.has("pickupable"):
                continue
            chain = self.state.ancestors(o.id) if o.id in self.state.objects else []
            for place in places:
                if any(self.state.objects[c].type in place.type_names() for c in chain) \
                        and o.type not in out:
                    out.append(o.type)
        if not out:
            raise self.fail(f"nothing found for {head.label()!r}", head.label())
        return out

    # ---- filtering and counting ----------------------------------------------------
    def _matches(self, o: ObjectState, head: Head, places: list[Ref]) -> bool:
        for stat, pos in head.filters:
            value = {
                Stat.SWITCH: o.is_on, Stat.OPEN: o.is_open, Stat.HOT: o.temperature == "Hot",
                Stat.COLD: o.temperature == "Cold", Stat.COOKED: o.is_cooked,
                Stat.CLEAN: not o.is_dirty, Stat.BROKEN: o.is_broken, Stat.SLICED: o.is_sliced,
                Stat.FILLED: o.liquid is not None,
            }.get(stat)
            if value is not None and value != pos:
                return False
        for place in places:
            chain = self.state.ancestors(o.id) if o.id in self.state.objects else []
            held = o.held_by is not None
            names = {*place.type_names(), *(_SAME_PLACE[t] for t in place.type_names() if t in _SAME_PLACE)}
            if not held and not any(self.state.objects[c].type in names for c in chain):
                return False
        return True

    def _places(self, head: Head) -> list[Ref]:
        """Where the phrase says its object is (a place not found leaves the object known)."""
        places = []
        for _, land in head.location:
            try:
                places.append(self.ground(land, None))
            except GroundingError:
                continue
        return places

    def ground(self, head: Head, need: str | None) -> Ref:
        """The references a (non-pronoun) noun phrase stands for; a reference chosen with
        doubt is also added to :attr:`doubts`."""
        self._fell_back = False
        ref = self._ground(head, need)
        if self._fell_back:
            self.doubts.update(r for r, _ in ref.groups)
        return ref

    def _ground(self, head: Head, need: str | None) -> Ref:
        types = self.candidate_types(head, need)
        fell_back = self._fell_back
        label = head.label()
        places = self._places(head)
        self._fell_back = fell_back     # the places' grounding does not make this one doubtful
        selective = bool(head.filters or places)
        if selective and not head.piece:
            pool = [o for t in types for o in self.instances(t)]
            chosen = [o for o in pool if self._matches(o, head, places)]
            if chosen and len(chosen) < len(pool):
                many = head.plural or head.quant in ("all", "every", "each") or (head.count or 1) > 1 \
                    or (head.noun is not None and head.noun.concept.kind == "anything")    # "everything on the shelf"
                picked = chosen if many else chosen[:1]
                if head.count is not None and many:
                    picked = chosen[: head.count]
                if len(picked) < len(chosen):
                    self.doubts.update(ObjectRef(id=o.id) for o in picked)
                return Ref(label, tuple((ObjectRef(id=o.id), 1) for o in picked), many)
        if head.ordinal is not None and not head.piece:
            pool = [o for t in types for o in self.instances(t)]
            k = head.ordinal - 1 if head.ordinal > 0 else len(pool) - 1
            if 0 <= k < len(pool):
                return Ref(label, ((ObjectRef(id=pool[k].id), 1),))
        available = sum(self.count_available(t) for t in types)
        if head.count is not None and not (head.quant == "both" and not head.plural):
            n = head.count
            if head.vague_count:
                n = max(1, min(n, available))
                self.doubts.add(ObjectRef(types=tuple(types)))
            if n > available:
                raise self.fail(f"{self.scene.floor_plan} has only {available} {label!r} "
                                f"({'/'.join(types)}), not {n}", label)
            return Ref(label, ((ObjectRef(types=tuple(types)), n),), n > 1)
        every = head.quant in ("all", "every", "each", "everything") or (
            head.plural and not head.piece and not head.vague_count)
        if every:
            groups = []
            for t in types:
                k = len(self.instances(t)) or (1 if self.has_type(t) else 0)
                if k:
                    groups.append((ObjectRef(types=(t,)), k))
            return Ref(label, tuple(groups), True)
        return Ref(label, ((ObjectRef(types=tuple(types)), 1),), False)

    def located(self, types: Iterable[str], head: Head) -> Ref | None:
        """The instance of ``types`` that ``head``'s places single out ("the old one
        that's on the toilet"), None when they single out none or all of them."""
        places = self._places(head)
        pool = [o for t in types for o in self.instances(t)]
        chosen = [o for o in pool if self._matches(o, head, places)] if places else []
        if not chosen or len(chosen) == len(pool):
            return None
        return Ref(head.label(), ((ObjectRef(id=chosen[0].id), 1),))

    def light_sources(self, on: bool = False) -> Ref:
        """The lights to switch to make the room dark: its switch and its lamps; to make it
        bright (``on``) its main light is enough (its lamps where it has no light switch)."""
        groups = []
        kinds = ("LightSwitch",) if on and self.instances("LightSwitch") else (
            "LightSwitch", "DeskLamp", "FloorLamp")
        for t in kinds:
            k = len(self.instances(t))
            if k:
                groups.append((ObjectRef(types=(t,)), k))
        if not groups:
            raise GroundingError(f"{self.scene.floor_plan} has no lights to switch")
        return Ref("the lights", tuple(groups), True)

    def every_instance(self, types: Iterable[str]) -> Ref | None:
        """Every object of these types the scene has, one group per type (None if none)."""
        groups = tuple((ObjectRef(types=(t,)), len(self.instances(t))) for t in types
                       if self.instances(t))
        return Ref("/".join(types), groups, True) if groups else None

    def all_that_are(self, stat: Stat) -> Ref:
        """"everything" that is on (``Stat.SWITCH``) or open (``Stat.OPEN``) now: every
        instance of each type with at least one such object."""
        attr = "is_on" if stat is Stat.SWITCH else "is_open"
        groups: list[tuple[ObjectRef, int]] = []
        for t in sorted({o.type for o in self._live if getattr(o, attr)}):
            every = self.instances(t)
            those = [o for o in every if getattr(o, attr)]
            if len(those) == len(every):
                groups.append((ObjectRef(types=(t,)), len(every)))   # all of them
            else:
                groups += [(ObjectRef(id=o.id), 1) for o in those]   # just the ones that are
        if not groups:
            word = "on" if stat is Stat.SWITCH else "open"
            raise GroundingError(f"nothing in {self.scene.floor_plan} is {word}",
                                 phrase="everything")
        return Ref("everything", tuple(groups), True)

    def types_ref(self, types: Iterable[str], label: str) -> Ref:
        """A reference to one object of any of the given types (those present)."""
        present = tuple(t for t in types if self.has_type(t))
        if not present:
            raise self.fail(f"{self.scene.floor_plan} has no {label}", label)
        return Ref(label, ((ObjectRef(types=present), 1),))


def ref_types(ref: ObjectRef) -> tuple[str, ...]:
    """The type names a reference stands for (an id: its type)."""
    return ref.types if ref.id is None else (ref.id.split("_")[0],)


def _id_key(object_id: str) -> tuple[str, int, int]:
    parts = object_id.split("_")
    num = int(parts[1]) if len(parts) > 1 and parts[1].isdigit() else 0
    piece = int(parts[3]) if len(parts) > 3 and parts[3].isdigit() else 0
    return parts[0], num, piece
