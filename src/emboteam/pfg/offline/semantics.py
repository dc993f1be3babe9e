"""Semantics: a frame with grounded objects -> draft subtasks with goal conditions.

The verb -> condition table of docs/offline_parser.md lives here: put X in Y is
``inside(X, Y)``, slice is ``sliced``, heat is ``hot`` (and "microwave X" adds an
intermediate step that puts X in the running microwave), toast is ``sliced`` then
``cooked``, wash is ``clean`` for dirtyable objects and otherwise a rinse (the object in
the sink basin under the running faucet) ... Pronouns are resolved here too, because
what the verb needs ("switch it on": something that switches) decides the antecedent.
"""

from __future__ import annotations

import contextlib
import itertools
from dataclasses import dataclass, field

from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.errors import GroundingError, OfflineParseError
from emboteam.pfg.offline.frames import Frame, Head, Target
from emboteam.pfg.offline.grounding import Grounder, Ref
from emboteam.pfg.offline.tagger import NounReading
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.state import ObjectState

Act = lx.Act
Stat = lx.Stat
P = Predicate


@dataclass
class Draft:
    """A subtask before ids and dependencies across clauses are known."""

    conditions: list[Condition]
    description: str
    entities: frozenset[str]
    #: indices (into the same frame's drafts) that must finish first
    after: list[int] = field(default_factory=list)
    #: a means to an end (the rinse before "put it on the counter", the microwave step)
    intermediate: bool = False


@dataclass
class Mention:
    ref: Ref
    head: Head
    clause: int
    group: int
    #: "object" (what a verb acts on) or "place" (where things go, where they are)
    role: str = "object"


#: which capability a role needs, for grounding and for choosing a pronoun's antecedent
ACT_NEEDS: dict[Act, str | None] = {
    Act.PLACE: "hold", Act.TRASH: "hold", Act.HOLD: "hold", Act.SLICE: "slice",
    Act.BREAK: "break", Act.OPEN: "open", Act.CLOSE: "open", Act.SWITCH_ON: "switch",
    Act.SWITCH_OFF: "switch", Act.TOGGLE: "switch", Act.WATCH: "switch", Act.HEAT: "hold",
    Act.MICROWAVE: "hold", Act.COOK: "cook", Act.TOAST: "cook", Act.COOL: "hold",
    Act.CLEAN: None, Act.DIRTY: "dirty", Act.FILL: "fill", Act.WATER: "fill",
    Act.POUR: None, Act.DIM: "switch", Act.BRIGHTEN: "switch",
}

STAT_NEEDS: dict[Stat, str | None] = {
    Stat.SWITCH: "switch", Stat.OPEN: "open", Stat.HOT: None, Stat.COLD: None,
    Stat.COOKED: "cook", Stat.CLEAN: None, Stat.SLICED: "slice", Stat.BROKEN: "break",
    Stat.FILLED: "fill", Stat.HELD: "hold", Stat.BRIGHT: None, Stat.TOASTED: None,
}

_VERBS_TO_HAND = frozenset({"bring", "fetch", "take", "get", "give", "hand", "carry", "grab",
                            "deliver", "collect", "retrieve", "find", "send"})
_VERBS_TO_BIN = frozenset({"throw", "toss", "dump", "chuck"})

_PHRASES: dict[Predicate, str] = {
    P.sliced: "slice {s}", P.broken: "break {s}", P.switched_on: "switch on {s}",
    P.switched_off: "switch off {s}", P.open: "open {s}", P.closed: "close {s}",
    P.hot: "heat {s}", P.cold: "chill {s}", P.cooked: "cook {s}", P.clean: "clean {s}",
    P.dirty: "make {s} dirty", P.held: "pick up {s}", P.filled: "fill {s}",
}


def describe(conditions: list[Condition]) -> str:
    """A short imperative description of what the conditions ask for."""
    parts = []
    for c in conditions:
        subj = f"{c.count} x {c.subject}" if c.count > 1 else str(c.subject)
        if c.predicate is P.inside:
            parts.append(f"put {subj} in/on {c.receptacle}")
        elif c.predicate is P.filled:
            parts.append(f"fill {subj} with {c.liquid or 'liquid'}")
        else:
            parts.append(_PHRASES[c.predicate].format(s=subj))
    return "; ".join(parts)


def cond(pred: Predicate, ref: ObjectRef, count: int = 1, receptacle: ObjectRef | None = None,
         liquid: str | None = None) -> Condition:
    return Condition(predicate=pred, subject=ref, count=count if ref.id is None else 1,
                     receptacle=receptacle, liquid=liquid)


class Semantics:
    """Turns frames into drafts, keeping the mention history for pronouns."""

    def __init__(self, grounder: Grounder) -> None:
        self.g = grounder
        self.cat = load_catalogue()
        self.history: list[Mention] = []
        self._group = 0

    # ---- pronouns ------------------------------------------------------------------
    def _fits(self, ref: Ref, need: str | None) -> bool:
        return need is None or any(self.g.can(t, need) for t in ref.type_names())

    def resolve(self, head: Head, need: str | None, prefer: str = "object") -> Ref:
        """The antecedent of "it", "them", "some", "the slices"."""
        if not self.history:
            raise OfflineParseError(f"{head.label()!r} refers to nothing mentioned before",
                                    phrase=head.label())
        plural = head.pron in ("them", "they", "these", "those", "themselves", "ones")
        if head.piece and head.pron is None:
            # "the slices": pieces of the last thing that can be cut
            for m in reversed(self.history):
                if any(self.cat.slice_product(t) for t in m.ref.type_names()):
                    product = [self.cat.slice_product(t) for t in m.ref.type_names()]
                    types = tuple(p[0] for p in product if p is not None)
                    n = head.count or 1
                    return Ref(head.label(), ((ObjectRef(types=types), n),), n > 1)
        if plural:
            last_group = self.history[-1].group
            for m in reversed(self.history):
                group = [x for x in self.history if x.group == m.group and x.head.pron is None
                         and self._fits(x.ref, need)]
                if len(group) > 1 or (m.ref.plural and self._fits(m.ref, need)):
                    if len(group) > 1:
                        return Ref(head.label(), tuple(g for x in group for g in x.ref.groups), True)
                    return m.ref
                del last_group
                break
        # what the last clauses acted on before where they put it ("put the lettuce in the
        # fridge after washing it": the lettuce), unless only a place fits ("close it")
        for role in ("object", "place") if prefer == "object" else ("place", "object"):
            for m in reversed(self.history):
                if m.role == role and self._fits(m.ref, need) and m.head.noun is not None and \
                        m.head.noun.concept.kind not in ("room", "anything"):
                    return m.ref
        for m in reversed(self.history):
            if self._fits(m.ref, need):
                return m.ref
        raise OfflineParseError(f"cannot tell what {head.label()!r} refers to", phrase=head.label())

    def ground(self, head: Head, need: str | None, group: int, clause: int,
               role: str = "object") -> Ref:
        if head.pron is not None or (head.piece and head.noun is None):
            ref = self.resolve(head, need, role)
        else:
            ref = self.g.ground(head, need)
            if head.alternatives:
                alts = [self.g.ground(a, need) for a in head.alternatives if a.pron is None]
                types = tuple(dict.fromkeys([*ref.type_names(), *(t for a in alts for t in a.type_names())]))
                ref = Ref(head.label(), ((ObjectRef(types=types), 1),))
        self.history.append(Mention(ref, head, clause, group, role))
        return ref

    def note(self, head: Head, clause: int, role: str = "object") -> None:
        """Record a mention of a clause that produced nothing (for later pronouns)."""
        if head.pron is not None or head.noun is None:
            return
        with contextlib.suppress(GroundingError):   # an unknown word is no antecedent
            self.history.append(Mention(self.g.ground(head, None), head, clause, -1, role))

    # ---- frames ----------------------------------------------------------------------
    def frame(self, frame: Frame, clause: int) -> list[Draft]:
        self._group += 1
        act = frame.act
        state = frame.state
        if act in (Act.VAGUE,):
            raise OfflineParseError(
                f"{frame.verb!r} is too vague for the offline parser: say which objects go "
                "where (e.g. 'put the book on the shelf')", phrase=frame.verb)
        if act is Act.EMPTY:
            raise OfflineParseError("emptying a container cannot be stated as a goal here",
                                    phrase=frame.verb)
        # complaints and negations turn into the opposite state
        flip = frame.negated
        if frame.report or frame.too:
            flip = not flip if not (frame.report and frame.too) else True
            if frame.report and frame.negated:
                return []      # "nobody is watching it": a remark, not a wish
        if (act in (None, Act.CAUSE, Act.MAKE) and state is not None) or (act is Act.SWITCH and state):
            return self._state(frame, state, flip, clause)
        if act is None:
            return []
        if flip:
            st = lx.ACT_STATE.get(act)
            if st is None or st[0] not in lx.INVERTIBLE:
                return []      # "don't break the vase": a prohibition, no goal
            return self._state(frame, (st[0], not st[1]), False, clause)
        if frame.report:
            return []
        drafts = self._act(frame, act, clause)
        for _, positive in frame.room_states:
            # "open a book in a well lit room"
            pred = P.switched_on if positive else P.switched_off
            drafts = concat(drafts, self._each(pred, self.g.light_sources(positive)))
        return drafts

    def _targets(self, frame: Frame) -> list[Target]:
        return [t for t in frame.targets if not t.head.is_empty or t.head.pron is not None]

    def _state(self, frame: Frame, state: tuple[Stat, bool], flip: bool, clause: int) -> list[Draft]:
        stat, positive = state
        if flip:
            if stat not in lx.INVERTIBLE:
                return []
            positive = not positive
        out: list[Draft] = []
        for t in self._targets(frame):
            head = t.head
            if stat is Stat.BRIGHT or (head.noun is not None and head.noun.concept.kind == "room"):
                ref = self._light_ref(head, clause, positive)
                out += self._each(P.switched_on if positive else P.switched_off, ref)
                continue
            if stat is Stat.TOASTED:
                out += self._act(Frame(Act.TOAST, "toast", [t]), Act.TOAST, clause)
                continue
            if stat is Stat.CLEAN and positive:
                out += self._act(Frame(Act.CLEAN, "clean", [t]), Act.CLEAN, clause)
                continue
            ref = self.ground(head, STAT_NEEDS[stat], self._group, clause)
            pred = _stat_predicate(stat, positive)
            if pred is None:
                continue
            liquid = "water" if pred is P.filled else None
            out += self._each(pred, ref, liquid=liquid)
        if not out and stat is Stat.BRIGHT:
            ref = self.g.light_sources(positive)
            out += self._each(P.switched_on if positive else P.switched_off, ref)
        return out

    def _light_ref(self, head: Head, clause: int, on: bool) -> Ref:
        """"the lamp is too bright": that lamp; "it is too dark", "the room is dark": every
        light of the room."""
        concept = head.noun.concept if head.noun is not None else None
        if concept is not None and (concept.kind in ("lights", "lamps") or concept.types[:1] in (
                ("LightSwitch",), ("DeskLamp",), ("FloorLamp",))):
            return self.ground(head, "switch", self._group, clause)
        return self.g.light_sources(on)

    def _each(self, pred: Predicate, ref: Ref, *others: Ref, receptacle: ObjectRef | None = None,
              liquid: str | None = None) -> list[Draft]:
        """One draft per (reference, count) group, so the planner can give each object to
        a different robot."""
        return [self._draft([cond(pred, r, n, receptacle, liquid)], Ref(ref.label, ((r, n),)), *others)
                for r, n in ref.groups]

    def _draft(self, conditions: list[Condition], *refs: Ref, intermediate: bool = False) -> Draft:
        ents: set[str] = set()
        for r in refs:
            ents |= r.types
        for c in conditions:
            for ref in (c.subject, c.receptacle):
                if ref is not None:
                    ents |= set(ref.types) if ref.id is None else {ref.id.split("_")[0]}
        return Draft(conditions, describe(conditions), frozenset(ents), intermediate=intermediate)

    def _act(self, frame: Frame, act: Act, clause: int) -> list[Draft]:
        targets = self._targets(frame)
        g = self._group
        if act in (Act.DIM, Act.BRIGHTEN) and not targets:
            ref = self.g.light_sources(act is Act.BRIGHTEN)
            pred = P.switched_off if act is Act.DIM else P.switched_on
            return self._each(pred, ref)
        if act is Act.WATER and not targets:
            targets = [Target(Head(text="plant", noun=_noun("plant")))]
        if act is Act.MAKE:
            return self._make(frame, targets, clause)
        if act is Act.POUR:
            return self._pour(frame, targets, clause)
        if act is Act.CAUSE:
            if any(t.dest for t in targets):
                act = Act.PLACE
            elif any(t.head.recipe or t.head.contents or (t.head.liquid and t.head.noun is None)
                     for t in targets):
                return self._make(frame, targets, clause)   # "get a mug of coffee going"
            elif frame.recipient or frame.verb == "get":
                act = Act.HOLD
            else:
                for t in targets:
                    self.note(t.head, clause)
                return []
        if not targets:
            if act in (Act.SWITCH_OFF, Act.SWITCH_ON) and frame.verb in ("dim", "kill"):
                ref = self.g.light_sources()
                return self._each(P.switched_off, ref)
            raise OfflineParseError(f"{frame.verb!r} needs an object: what should be "
                                    f"{frame.verb}ed?", phrase=frame.text)
        if act is Act.GO:
            act = Act.PLACE if any(t.dest for t in targets) else act
            if act is Act.GO:
                return []
        # "put the book on the bed and the pillow too": a later object without a place
        # goes where the one before it went
        for prev, t in itertools.pairwise(targets):
            if prev.dest and not t.dest and act in (Act.PLACE, Act.CAUSE, Act.HOLD):
                t.dest, t.prep = prev.dest, prev.prep
        out: list[Draft] = []
        for t in targets:
            # "microwave a plate containing an egg": first the egg on the plate
            before = [self._draft([cond(P.inside, r, n, c.single())], held, c)
                      for c, held in self._contents(t, g, clause) for r, n in held.groups]
            main = self._one(frame, act, t, g, clause)
            for d in main:
                d.after = [a + len(before) for a in d.after] + list(range(len(before)))
            out = concat(out, before + main)
        return out

    def _contents(self, t: Target, g: int, clause: int) -> list[tuple[Ref, Ref]]:
        if not t.head.holds:
            return []
        container = self.ground(t.head, "receptacle", g, clause)
        return [(container, self.ground(h, "hold", g, clause)) for h in t.head.holds]

    def _one(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        head = t.head
        if head.noun is None and head.liquid is not None and t.dest and act in (
                Act.FILL, Act.PLACE, Act.POUR):
            # "fill water in the kettle", "put some water in the pot"
            out: list[Draft] = []
            for d in t.dest:
                ref = self.ground(d, "fill", g, clause, "place")
                out += self._each(P.filled, ref, liquid=head.liquid)
            return out
        if head.noun is not None and head.noun.concept.kind == "room" and act in (
                Act.CLEAN, Act.DIRTY):
            raise OfflineParseError(f"'{frame.verb} {head.label()}' is too vague for the offline "
                                    "parser: say which objects to clean", phrase=head.label())
        if act in (Act.DIM, Act.BRIGHTEN) and head.noun is not None and \
                head.noun.concept.kind == "room":
            return self._each(P.switched_off if act is Act.DIM else P.switched_on,
                              self.g.light_sources(act is Act.BRIGHTEN))
        if act is Act.PLACE and not t.dest:
            if frame.state is not None:
                return self._state(Frame(None, frame.verb, [t]), frame.state, False, clause)
            if frame.verb == "hang":
                obj = self.ground(head, "hold", g, clause)
                holders = [r for r, types in self.cat.receptacle_whitelist.items()
                           if set(types) & set(obj.type_names()) and r.endswith(("Holder", "Hanger"))]
                dest = self.g.types_ref(holders, "its holder")
                return self._each(P.inside, obj, dest, receptacle=dest.single())
            if frame.verb in _VERBS_TO_BIN:
                act = Act.TRASH
            elif frame.verb in _VERBS_TO_HAND or frame.recipient:
                act = Act.HOLD
            else:
                raise OfflineParseError(f"where should {head.label()!r} go? "
                                        f"('{frame.verb or 'put'} {head.label()} in/on ...')",
                                        phrase=frame.text)
        if act is Act.HOLD and t.dest:
            act = Act.PLACE
        need = ACT_NEEDS.get(act)
        if act is Act.PLACE:
            return self._place(frame, t, g, clause)
        if act is Act.TRASH:
            obj = self.ground(head, "hold", g, clause)
            can = self.g.types_ref(("GarbageCan",), "garbage can")
            return self._each(P.inside, obj, can, receptacle=can.single())
        if act is Act.WATCH:
            obj = self.ground(head, "switch", g, clause)
            return self._each(P.switched_on, obj)
        if act is Act.CLEAN:
            return self._clean(head, g, clause)
        if act is Act.TOAST:
            obj = self.ground(head, "cook", g, clause)
            drafts: list[Draft] = []
            # toast is cooked slices: cut what is whole first ("toast a slice of bread" too)
            wholes = [_whole(r) for r, _ in obj.groups]
            sliceable = [w for w in wholes if any(self.cat.slice_product(x) for x in _names(w))]
            if sliceable:
                drafts.append(self._draft([cond(P.sliced, w) for w in dict.fromkeys(sliceable)], obj))
            cooked = self._draft([cond(P.cooked, _whole(r), n) for r, n in obj.groups], obj)
            if drafts:
                cooked.after = [0]
            return [*drafts, cooked]
        if act in (Act.HEAT, Act.MICROWAVE):
            obj = self.ground(head, None, g, clause)
            hot = self._draft([cond(P.hot, r, n) for r, n in obj.groups], obj)
            means = frame.means or (t.dest[0] if t.dest else None)
            use_microwave = act is Act.MICROWAVE or (
                means is not None and means.noun is not None and "Microwave" in means.noun.concept.types)
            if use_microwave and self.g.has_type("Microwave"):
                mw = self.g.types_ref(("Microwave",), "microwave")
                step = self._draft([*(cond(P.inside, r, n, mw.single()) for r, n in obj.groups),
                                    cond(P.switched_on, mw.single())], obj, mw, intermediate=True)
                hot.after = [0]
                return [step, hot]
            return [hot]
        if act is Act.FILL:
            obj = self.ground(head, "fill", g, clause)
            liquid = frame.liquid or head.contents or "water"
            return self._each(P.filled, obj, liquid=liquid)
        if act is Act.WATER:
            obj = self.ground(head, "fill", g, clause)
            return self._each(P.filled, obj, liquid="water")
        if act is Act.TOGGLE:
            obj = self.ground(head, "switch", g, clause)
            flipped = []
            for r, n in obj.groups:
                on = all(o.is_on for o in self._objects(r))
                flipped.append(cond(P.switched_off if on else P.switched_on, r, n))
            return [self._draft(flipped, obj)]
        pred: Predicate | None = {
            Act.SLICE: P.sliced, Act.BREAK: P.broken, Act.OPEN: P.open, Act.CLOSE: P.closed,
            Act.SWITCH_ON: P.switched_on, Act.SWITCH_OFF: P.switched_off, Act.COOK: P.cooked,
            Act.COOL: P.cold, Act.DIRTY: P.dirty, Act.HOLD: P.held,
            Act.DIM: P.switched_off, Act.BRIGHTEN: P.switched_on,
        }.get(act)
        if pred is None:
            return []
        obj = self.ground(head, need, g, clause)
        return self._each(pred, obj)

    def _objects(self, ref: ObjectRef) -> list[ObjectState]:
        if ref.id is not None:
            return [self.g.state.objects[ref.id]]
        return [o for t in ref.types for o in self.g.instances(t)]

    def _place(self, frame: Frame, t: Target, g: int, clause: int) -> list[Draft]:
        obj = self.ground(t.head, "hold", g, clause)
        dest_heads = t.dest
        if t.prep == "under":
            raise OfflineParseError("'under' cannot be stated as a goal (only in/on)",
                                    phrase=frame.text)
        if t.prep == "near":
            dest = self._beside(dest_heads[0], g, clause)
        else:
            refs = [self.ground(d, "receptacle", g, clause, "place") for d in dest_heads]
            types = tuple(dict.fromkeys(x for r in refs for x in r.type_names()))
            dest = Ref(" or ".join(r.label for r in refs),
                       ((ObjectRef(types=types), 1),) if len(refs) > 1 or len(refs[0].groups) > 1
                       else refs[0].groups)
        dest_ref = dest.single()
        drafts: list[Draft] = []
        for r, n in obj.groups:
            conditions: list[Condition] = []
            subject, where = r, dest_ref
            if where.id is None:
                names = _names(r)
                fitting = [d for d in where.types if any(self.cat.can_place(x, d) for x in names)]
                # "the hand towel on its holder": of the holders, the one it fits
                if fitting and len(fitting) < len(where.types):
                    where = ObjectRef(types=tuple(fitting))
                elif not fitting and r.id is None:
                    # "the bread in the toaster": what goes there is a slice of it
                    pieces = tuple(p[0] for x in r.types if (p := self.cat.slice_product(x)))
                    if pieces and any(self.cat.can_place(x, d) for x in pieces for d in where.types):
                        subject = ObjectRef(types=pieces)
            conditions.append(cond(P.inside, subject, n, where))
            liquid = frame.liquid or t.head.contents
            if liquid is not None:
                conditions.append(cond(P.filled, subject, n, liquid=liquid))
            drafts.append(self._draft(conditions, Ref(obj.label, ((r, n),)), dest))
        return drafts

    def _beside(self, landmark: Head, g: int, clause: int) -> Ref:
        """"next to the bread": on whatever the bread is on."""
        ref = self.ground(landmark, None, g, clause, "place")
        places: list[str] = []
        for r, _ in ref.groups:
            for o in self._objects(r):
                parent = getattr(o, "parent", None)
                if parent is not None:
                    places.append(self.g.state.objects[parent].type)
        if not places:
            raise GroundingError(f"cannot tell where {landmark.label()!r} stands",
                                 phrase=landmark.label())
        return self.g.types_ref(dict.fromkeys(places), f"beside {landmark.label()}")

    def _clean(self, head: Head, g: int, clause: int) -> list[Draft]:
        obj = self.ground(head, None, g, clause)
        dirtyable = [(r, n) for r, n in obj.groups if all(self.g.can(x, "dirty") for x in _names(r))]
        rest = [(r, n) for r, n in obj.groups if (r, n) not in dirtyable]
        out: list[Draft] = []
        if dirtyable:
            out += self._each(P.clean, Ref(obj.label, tuple(dirtyable)))
        if rest:
            basin, faucet = self._sink()
            conds = [cond(P.inside, r, n, basin) for r, n in rest]
            out.append(self._draft([*conds, cond(P.switched_on, faucet)], obj, intermediate=True))
        return out

    def _sink(self) -> tuple[ObjectRef, ObjectRef]:
        """The sink basin and the faucet that runs water into it."""
        basins = self.g.instances("SinkBasin")
        faucets = [f for f in self.g.instances("Faucet")
                   if any(b.id in f.controls for b in basins)]
        if not basins or not faucets:
            raise GroundingError(f"{self.g.scene.floor_plan} has no sink with a faucet to rinse in",
                                 phrase="sink")
        if len(basins) == 1 and len(self.g.instances("Faucet")) == 1:
            return ObjectRef(types=("SinkBasin",)), ObjectRef(types=("Faucet",))
        f = faucets[0]
        basin = next(b for b in basins if b.id in f.controls)
        return ObjectRef(id=basin.id), ObjectRef(id=f.id)

    def _make(self, frame: Frame, targets: list[Target], clause: int) -> list[Draft]:
        out: list[Draft] = []
        for t in targets:
            drink = t.head.contents or (t.head.liquid if t.head.noun is None else None)
            recipe = t.head.recipe or (lx.RECIPES.get(drink) if drink else None)
            if recipe is None and t.head.noun is not None:
                recipe = lx.RECIPES.get(t.head.noun.phrase)
            if recipe is None:
                if frame.state is not None:
                    out += self._state(Frame(None, frame.verb, [t]), frame.state, False, clause)
                    continue
                raise OfflineParseError(
                    f"'{frame.verb} {t.head.label()}' is too vague for the offline parser",
                    phrase=t.head.label())
            out += self._recipe(recipe, clause)
        return out

    def _recipe(self, recipe: str, clause: int) -> list[Draft]:
        g = self.g
        if recipe == "coffee":
            mug = g.types_ref(("Mug",), "mug")
            if not g.has_type("CoffeeMachine"):
                raise GroundingError(f"{g.scene.floor_plan} has no coffee machine", phrase="coffee")
            self.history.append(Mention(mug, Head(text="mug"), clause, self._group))
            return [self._draft([cond(P.filled, mug.single(), liquid="coffee"),
                                 cond(P.hot, mug.single())], mug)]
        if recipe == "toast":
            bread = g.types_ref(("Bread",), "bread")
            self.history.append(Mention(bread, Head(text="bread"), clause, self._group))
            cooked = self._draft([cond(P.cooked, bread.single())], bread)
            cooked.after = [0]
            return [self._draft([cond(P.sliced, bread.single())], bread), cooked]
        if recipe == "salad":
            out = []
            for t in ("Lettuce", "Tomato"):
                if g.has_type(t):
                    ref = g.types_ref((t,), t.lower())
                    out.append(self._draft([cond(P.sliced, ref.single())], ref))
            if not out:
                raise GroundingError(f"{g.scene.floor_plan} has nothing to make a salad with",
                                     phrase="salad")
            return out
        if recipe in ("egg", "potato"):
            ref = g.types_ref((recipe.capitalize(),), recipe)
            return [self._draft([cond(P.cooked, ref.single())], ref)]
        raise OfflineParseError(f"no recipe for {recipe!r}", phrase=recipe)

    def _pour(self, frame: Frame, targets: list[Target], clause: int) -> list[Draft]:
        out: list[Draft] = []
        liquid = frame.liquid
        for t in targets:
            liquid = t.head.liquid or t.head.contents or liquid
            if t.dest:
                for d in t.dest:
                    ref = self.ground(d, "fill", self._group, clause)
                    out.append(self._draft([cond(P.filled, r, n, liquid=liquid or "water")
                                            for r, n in ref.groups], ref))
            elif t.head.noun is not None:
                ref = self.ground(t.head, "fill", self._group, clause)
                out.append(self._draft([cond(P.filled, r, n, liquid=liquid or "water")
                                        for r, n in ref.groups], ref))
        return out


def concat(first: list[Draft], second: list[Draft]) -> list[Draft]:
    """Two draft lists as one; ``after`` indices of the second are shifted."""
    for d in second:
        d.after = [a + len(first) for a in d.after]
    return [*first, *second]


def _names(ref: ObjectRef) -> tuple[str, ...]:
    return ref.types if ref.id is None else (ref.id.split("_")[0],)


def _whole(ref: ObjectRef) -> ObjectRef:
    """A slice type reference as its whole ("toast" is cooked bread)."""
    if ref.id is not None:
        return ref
    cat = load_catalogue()
    return ObjectRef(types=tuple(dict.fromkeys(cat.source_type(t) or t for t in ref.types)))


def _noun(phrase: str) -> NounReading:
    return NounReading(lx.nouns()[phrase], phrase, False)


def _stat_predicate(stat: Stat, positive: bool) -> Predicate | None:
    table: dict[tuple[Stat, bool], Predicate] = {
        (Stat.SWITCH, True): P.switched_on, (Stat.SWITCH, False): P.switched_off,
        (Stat.OPEN, True): P.open, (Stat.OPEN, False): P.closed, (Stat.HOT, True): P.hot,
        (Stat.COLD, True): P.cold, (Stat.COOKED, True): P.cooked, (Stat.CLEAN, True): P.clean,
        (Stat.CLEAN, False): P.dirty, (Stat.SLICED, True): P.sliced,
        (Stat.BROKEN, True): P.broken, (Stat.FILLED, True): P.filled, (Stat.HELD, True): P.held,
    }
    return table.get((stat, positive))
