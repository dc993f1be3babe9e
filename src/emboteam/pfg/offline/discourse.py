"""Discourse: what the instruction has mentioned so far, for pronouns ("it", "them",
"all three", "the lot", "the slices") and for singling out instances ("close the drawer
again" after "the remote is in one of the drawers" is the drawer that holds the remote;
"the cabinet it's in"; "put it back" returns it where it came from).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.errors import GroundingError, OfflineParseError
from emboteam.pfg.offline.grounding import Grounder, Ref, ref_types
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.phrases import Head
from emboteam.pfg.offline.tagger import NounReading
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import ObjectRef
from emboteam.world.state import ObjectState

_W = word_tables("discourse")
#: words that make "one" another instance of the kind just named ("a fresh one", "a new one")
OTHER_WORDS = _W.set("other_words")
#: pronouns of several things: "them" is the last coordinated objects
_PLURAL_PRONOUNS = _W.set("plural_pronouns")


@dataclass
class Mention:
    ref: Ref
    head: Head
    clause: int
    group: int
    #: "object" (what a verb acts on), "dest" (where something was just put) or "place"
    #: (where things are, what they come from, the means)
    role: str = "object"


class Discourse:
    """The mention history of one instruction and the instances it singles out."""

    def __init__(self, grounder: Grounder) -> None:
        self.g = grounder
        self.cat = load_catalogue()
        self.history: list[Mention] = []
        #: type -> the instance the conversation singles out ("the drawer" it is in)
        self.salient: dict[str, str] = {}
        #: where a mentioned object was taken from or said to be: "put it back" goes there
        self.origins: dict[frozenset[str], Head] = {}
        #: mentions that named nothing in the scene (the reason a later "it" fails)
        self.unresolved: list[GroundingError] = []

    def objects(self, ref: ObjectRef) -> list[ObjectState]:
        """The objects of the state a reference stands for."""
        if ref.id is not None:
            return [self.g.state.objects[ref.id]]
        return [o for t in ref.types for o in self.g.instances(t)]

    def fits(self, ref: Ref, need: str | None) -> bool:
        """Can the referent do what the verb asks ("switch it on": something switchable)?"""
        return need is None or any(self.g.can(t, need) for t in ref.type_names())

    def resolve(self, head: Head, need: str | None, prefer: str = "object") -> Ref:
        """The antecedent of "it", "them", "some", "the slices"; "one" is one of it."""
        ref = self._resolve(head, need, prefer)
        if head.text.split()[-1:] == ["one"] and head.location:
            # "turn off the little one on the desk": the kind named before, there
            named = next((m.head for m in reversed(self.history) if m.ref.groups == ref.groups
                          and m.head.noun is not None), None)
            if named is not None:
                named = self._as_sized(named, head)
                try:
                    return self.g.ground(replace(named, location=list(head.location), filters=[]), need)
                except OfflineParseError:
                    pass
            else:       # "a spare ... bin the old one that's on the toilet": the kind, there
                there = self.g.located(ref.type_names(), head)
                if there is not None:
                    return there
        if (head.pron == "one" or head.count == 1) and head.text.split() in (["one"], ["one", "of", "them"]) \
                and ref.groups and ref.groups[0][0].id is None:
            # "the drawers are all shut, so open one": one of them
            return Ref(head.label(), ((ref.groups[0][0], 1),))
        return ref

    @staticmethod
    def _as_sized(named: Head, one: Head) -> Head:
        """"the tall lamp ... the little one": the kind named before ("lamp"), with the size
        said now ("little lamp") when the lexicon has that compound."""
        assert named.noun is not None       # (the caller picks a mention with a noun)
        base = named.noun.phrase.split()[-1]
        for word in one.text.split()[:-1]:
            concept = lx.nouns().get(f"{word} {base}")
            if concept is not None:
                return replace(named, noun=NounReading(concept, f"{word} {base}", False), text=f"the {word} {base}")
        return named

    def _resolve(self, head: Head, need: str | None, prefer: str = "object") -> Ref:
        if not self.history:
            if self.unresolved:
                raise self.unresolved[-1]
            raise OfflineParseError(f"{head.label()!r} refers to nothing mentioned before",
                                    phrase=head.label())
        for rule in (self._another_one, self._pieces_of, self._slices, self._where_things_went,
                     self._it_again, self._last_group, self._coordinated_place, self._place_pronoun,
                     self._by_role, self._last_that_fits, self._whole_of_pieces, self._named_before):
            ref = rule(head, need, prefer)
            if ref is not None:
                return ref
        if self.unresolved:
            raise self.unresolved[-1]
        raise OfflineParseError(f"cannot tell what {head.label()!r} refers to", phrase=head.label())

    def _slices(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"the slices": pieces of the last thing that can be cut (of each of the things cut
        together: "slice the apple and the tomato, put the slices in a bowl")."""
        if not head.piece or head.pron is not None:
            return None
        for m in reversed(self.history):
            if any(self.cat.slice_product(t) for t in m.ref.type_names()):
                cut = [x for x in self.history if x.group == m.group and x.role == "object"
                       and any(self.cat.slice_product(t) for t in x.ref.type_names())]
                wholes = list(dict.fromkeys(t for x in cut or [m] for r, _ in x.ref.groups
                                            for t in ref_types(r)
                                            if self.cat.slice_product(t) is not None))
                if len(wholes) > 1 and head.count is None:
                    groups = tuple((ObjectRef(types=(p[0],)), 1) for t in wholes
                                   if (p := self.cat.slice_product(t)) is not None)
                    return Ref(head.label(), groups, True)
                product = [self.cat.slice_product(t) for t in m.ref.type_names()]
                types = tuple(p[0] for p in product if p is not None)
                n = head.count or 1
                return Ref(head.label(), ((ObjectRef(types=types), n),), n > 1)
        return None

    def _where_things_went(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"put the books in the drawer and close it", "put the mug in the coffee machine and
        switch it on": where things just went - unless something named after it can do it
        ("..., the laptop's been left open so shut it")."""
        if need not in ("open", "switch"):
            return None
        for m in reversed(self.history):
            if m.role == "dest":
                return m.ref if self.fits(m.ref, need) else None
            if m.role == "object" and m.head.pron is None and m.head.noun is not None and self.fits(m.ref, need):
                return m.ref
        return None

    def _it_again(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """A chain of "it"s keeps its referent ("pack the pens into the box, close it, and
        put it on the shelf": the box both times), as long as it fits the verb."""
        if head.pron != "it":
            return None
        last = next((x for x in reversed(self.history) if x.role == "object"), None)
        return last.ref if last is not None and last.head.pron == "it" and self.fits(last.ref, need) else None

    def _last_group(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"them", "all three": the last coordinated objects ("the fork and the spoon ...
        them"), not the place they went to; named objects, not an earlier "they" that a
        verb's need narrowed. "they" skips singular things named since ("my phone and my
        keys ... on the desk next to the laptop. They go in the safe")."""
        if head.pron not in _PLURAL_PRONOUNS:
            return None
        m = next((x for x in reversed(self.history) if x.role == "object" and x.head.pron is None and (
            x.ref.plural or sum(1 for y in self.history if y.group == x.group and y.role == "object"
                                and y.head.pron is None) > 1)), None) \
            or next((x for x in reversed(self.history) if x.role == "object" and x.head.pron is None),
                    next((x for x in reversed(self.history) if x.role == "object"), self.history[-1]))
        group = [x for x in self.history if x.group == m.group and x.head.pron is None
                 and x.role == "object" and self.fits(x.ref, need)]
        if len(group) < 2 and (head.quant == "both" or "both" in head.text.split()):
            # "the lettuce is in the sink and the tomato's on a plate. Both of those ...":
            # the last two things named, across clauses
            pair: list[Mention] = []
            for x in reversed(self.history):
                if x.role == "object" and x.head.pron is None and self.fits(x.ref, need) \
                        and all(x.ref.groups != y.ref.groups for y in pair):
                    pair.append(x)
                if len(pair) == 2:
                    return Ref(head.label(), tuple(g for y in reversed(pair) for g in y.ref.groups), True)
        if len(group) > 1:
            return Ref(head.label(), tuple(g for x in group for g in x.ref.groups), True)
        return m.ref if m.ref.plural and self.fits(m.ref, need) else None

    def _by_role(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """What the last clauses acted on before where they put it ("put the lettuce in the
        fridge after washing it": the lettuce), unless only a place fits ("close it")."""
        order = ("object", "place") if prefer == "object" else ("place", "object")
        for role in order:
            for m in reversed(self.history):
                kind = "place" if m.role == "dest" else m.role
                if kind == role and self.fits(m.ref, need) and (
                        (m.head.noun is None and m.head.piece)          # "a slice off it ... pop that in"
                        # "get the spare one out of the drawer and put it on the holder"
                        or (m.head.noun is None and m.head.pron in ("one", "it") and OTHER_WORDS & set(m.head.text.split()))
                        or (m.head.noun is not None and m.head.noun.concept.kind not in ("room", "anything"))):
                    if role != order[0]:    # not what the verb prefers: maybe a guess
                        self._doubt_unless_alone(m.ref, need)
                    return m.ref
        return None

    def _last_that_fits(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """The last resort: the last thing mentioned that can do what the verb asks."""
        for m in reversed(self.history):
            if self.fits(m.ref, need):
                self._doubt_unless_alone(m.ref, need)
                return m.ref
        return None

    def _named_before(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"is the stove on? turn it off": the stove mentioned as such, switched by what
        switches it (its knobs), as the grounder reads "turn the stove off"."""
        for m in reversed(self.history):
            if m.head.noun is not None and m.head.pron is None and need is not None:
                try:
                    return self.g.ground(m.head, need)
                except OfflineParseError:
                    continue
        return None

    def _coordinated_place(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"Put the potato and the tomato on it (a plate), leave it on the counter": "it"
        is not one of two things acted on together (that would be "them"), but where they
        went."""
        if head.pron != "it":
            return None
        last = next((x for x in reversed(self.history) if x.role == "object"), None)
        if last is None:
            return None
        together = {x.ref.groups for x in self.history if x.group == last.group and x.role == "object"}
        if len(together) < 2:
            return None
        dest = next((x for x in reversed(self.history) if x.group == last.group and x.role == "dest"), None)
        return dest.ref if dest is not None and self.fits(dest.ref, need) else None

    def _whole_of_pieces(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"Three slices of apple on the plate - cut it first": the whole the last pieces
        come from, when only it can do what the verb asks."""
        for m in reversed(self.history):
            wholes = tuple(dict.fromkeys(w for t in m.ref.type_names() if (w := self.cat.source_type(t))))
            if wholes and any(self.g.can(w, need) for w in wholes if need is not None):
                return Ref(" ".join(wholes), ((ObjectRef(types=wholes), 1),))
        return None

    def _another_one(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"The loo roll on the floor goes in the bin and a fresh one on the holder": the
        same kind, another instance than the one just singled out."""
        if head.pron not in ("one", "it", "them", "ones") or not OTHER_WORDS & set(head.text.split()):
            return None
        same = self.resolve(replace(head, text=head.pron or ""), need, prefer)
        other = self._another_instance(same)
        if other is None and len(same.groups) == 1 and same.groups[0][0].id is None:
            # "both rolls ... one of them on the holder and the other on the counter", "the
            # other two": more of the kind, as many as said (one when no number)
            n = head.count or 1
            return Ref(head.label(), ((same.groups[0][0], n),), n > 1)
        return other

    def _pieces_of(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"Cut it up and put two pieces of it in the bowl": the pieces of what "it" is."""
        if not head.piece or head.pron not in ("it", "them"):
            return None
        of = replace(head, piece=False, count=None)
        try:        # pieces come from something that can be cut ("a slice off it": the loaf)
            whole = self.resolve(of, "slice", prefer)
        except OfflineParseError:
            whole = self.resolve(of, None, prefer)
        products = [self.cat.slice_product(t) for t in whole.type_names()]
        kinds = tuple(p[0] for p in products if p is not None)
        if not kinds:
            return whole
        n = head.count or 1
        return Ref(head.label(), ((ObjectRef(types=kinds), n),), n > 1)

    def _place_pronoun(self, head: Head, need: str | None, prefer: str) -> Ref | None:
        """"See the box on the table? Put the watch in it." (the thing described, not the
        landmark); "open a drawer and put the keys in it" (the last thing named that can
        take them, when it was acted on), when a place is preferred: else None, and the
        usual order decides."""
        if prefer == "object":
            return None
        described = self._described_place(need)
        if described is not None:
            return described
        sources = {id(land) for x in self.history for prep, land in x.head.location if prep == "from"}
        recent = next((m for m in reversed(self.history) if m.head.noun is not None and m.head.pron is None
                       and m.head.noun.concept.kind not in ("room", "anything")
                       and id(m.head) not in sources      # "the egg from the sink into it"
                       and self.fits(m.ref, need)), None)
        if recent is not None and recent.role == "dest":
            return self._moved_receptacle(recent, need)
        return recent.ref if recent is not None and recent.role == "object" else None

    def _moved_receptacle(self, dest: Mention, need: str | None) -> Ref | None:
        """"Get the pan on the stove and crack an egg into it": a receptacle just put *on*
        a surface is what "in it" means, not the surface (a container it was put *in*,
        "the bowl in the fridge ... in it", stays for the usual order to decide)."""
        if any(t in self.cat.in_receptacles for t in dest.ref.type_names()):
            return None
        k = self.history.index(dest)
        moved = next((m for m in reversed(self.history[:k]) if m.role == "object"), None)
        if moved is None or moved.clause != dest.clause or not self.fits(moved.ref, need):
            return None
        return moved.ref

    def _another_instance(self, ref: Ref) -> Ref | None:
        """Another object of the kind ``ref`` singled out by its id, or None when ``ref``
        names no instance (a kind is a kind: "another one" is any of them)."""
        ids = {r.id for r, _ in ref.groups if r.id is not None}
        if not ids or len(ref.groups) != 1:
            return None
        kind = next(iter(ids)).split("_")[0]
        others = [o.id for o in self.g.instances(kind) if o.id not in ids]
        if not others:
            return None
        return Ref(f"another {kind}", ((ObjectRef(id=others[0]), 1),))

    def _described_place(self, need: str | None) -> Ref | None:
        """"See the box on the coffee table? Put the watch in it.": a place pronoun means
        the thing last described by where it is, not the landmark that describes it."""
        last_place = next((m for m in reversed(self.history)
                           if m.role != "object" and m.head.pron is None), None)
        if last_place is None:
            return None
        for m in reversed(self.history):
            if m.role == "object" and m.head.location and self.fits(m.ref, need) and any(
                    land is last_place.head for _, land in m.head.location):
                return m.ref
        return None

    def _doubt_unless_alone(self, ref: Ref, need: str | None) -> None:
        """A pronoun resolved by a fallback is a guess when something else mentioned
        could also be meant: its references are recorded as doubtful."""
        others = {x.ref.groups for x in self.history if self.fits(x.ref, need)} - {ref.groups}
        if others:
            self.g.doubts.update(r for r, _ in ref.groups)

    def remember_places(self, ref: Ref, head: Head) -> None:
        """Where a mentioned object is said to be ("the remote is in one of the drawers",
        "take the mug out of the cabinet"): the receptacle instance that holds it now
        becomes *the* drawer / cabinet of the conversation, and the place it came from is
        where "put it back" returns it."""
        for prep, land in head.location:
            if prep == "from":
                self.origins[ref.types] = land
            try:
                place = self.g.ground(land, None)
            except GroundingError:
                continue
            if prep != "from":
                self.origins.setdefault(ref.types, land)
            kinds = set(place.type_names())
            found: dict[str, set[str]] = {}
            for r, _ in ref.groups:
                for o in self.objects(r):
                    for anc in self.g.state.ancestors(o.id):
                        t = self.g.state.objects[anc].type
                        if t in kinds:
                            found.setdefault(t, set()).add(anc)
            for t, holders in found.items():
                if len(holders) == 1:
                    self.salient[t] = next(iter(holders))

    def bind_salient(self, ref: Ref, head: Head) -> Ref:
        """"close the drawer again" after "the remote is in one of the drawers": the drawer
        that holds the remote (an instance id), not any drawer - ``closed(Drawer)`` may
        already hold for another one and the planner would do nothing."""
        if not head.definite or head.plural or head.count is not None or head.ordinal is not None \
                or head.location or head.filters or head.quant is not None or len(ref.groups) != 1:
            return ref
        r, _ = ref.groups[0]
        if r.id is not None:
            return ref
        hits = [t for t in r.types if t in self.salient and len(self.g.instances(t)) > 1]
        if len(hits) != 1:
            return ref
        return Ref(ref.label, ((ObjectRef(id=self.salient[hits[0]]), 1),))

    def container(self, head: Head, need: str | None) -> Ref:
        """"the cabinet it's in", "the drawer they are in": the receptacle instance holding
        what the pronoun refers to."""
        types = set(self.g.candidate_types(head, need))
        inner = head.container_of
        assert inner is not None
        held = self.resolve(inner, "hold") if inner.pron is not None else self.g.ground(inner, None)
        holders: list[str] = []
        for r, _ in held.groups:
            for o in self.objects(r):
                holders += [a for a in self.g.state.ancestors(o.id)
                            if self.g.state.objects[a].type in types and a not in holders]
        if len(holders) == 1:
            return Ref(head.label(), ((ObjectRef(id=holders[0]), 1),))
        return self.g.ground(replace(head, container_of=None), need)
