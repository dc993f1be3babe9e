"""Semantics: a frame with grounded objects -> draft subtasks with goal conditions.

The verb -> condition table of docs/offline_parser.md lives here: put X in Y is
``inside(X, Y)``, slice is ``sliced``, heat is ``hot`` (and "microwave X" adds an
intermediate step that puts X in the running microwave), toast is ``sliced`` then
``cooked``, wash is ``clean`` for dirtyable objects and otherwise a rinse (the object in
the sink basin under the running faucet) ... Pronouns are resolved here too, because
what the verb needs ("switch it on": something that switches) decides the antecedent
(:mod:`~emboteam.pfg.offline.discourse` keeps the mentions).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass, field, replace

from emboteam.pfg.inflection import past_participle
from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.offline.acts import (
    ACT_NEEDS,
    ACT_PREDICATE,
    COOKWARE,
    DESCRIBE,
    DISHES,
    STAT_NEEDS,
    STAT_PREDICATE,
    STOVE_VESSELS,
    WISHED_NEEDS,
    Dish,
)
from emboteam.pfg.offline.discourse import OTHER_WORDS, Discourse, Mention
from emboteam.pfg.offline.errors import GroundingError, IncapableError, OfflineParseError
from emboteam.pfg.offline.grounding import Grounder, Ref, ref_types
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.phrases import DESIRABLE, Frame, Head, Target
from emboteam.pfg.offline.tagger import NounReading
from emboteam.pfg.offline.text import split_camel
from emboteam.world.catalogue import BREWERS, load_catalogue
from emboteam.world.goals import Condition, ObjectRef, Predicate

Act = lx.Act
Stat = lx.Stat
P = Predicate
_names = ref_types


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
    #: a state wished for an object ("I'd love a warm slice of bread"): dropped when a
    #: later clause's act brings it about ("... toast some for me")
    wished: bool = False
    #: "bin the loo roll and put a new one on the holder": another instance of a kind
    #: named before, so it undoes nothing done to the first
    another: bool = False
    #: "... so the strong robot should carry it": holding what a pronoun names, for no one
    #: (a placement of the same object elsewhere makes it the means, not a goal)
    carried: bool = False


_W = word_tables("semantics")
#: verbs of carrying: with a pronoun and no place, who carries what is placed elsewhere
_CARRYING = _W.set("carrying")

_VERBS_TO_HAND = _W.set("verbs_to_hand")
_VERBS_TO_BIN = _W.set("verbs_to_bin")


def describe(conditions: list[Condition]) -> str:
    """A short imperative description of what the conditions ask for (``acts.json``,
    ``describe``)."""
    return "; ".join(DESCRIBE[c.predicate].format(
        s=f"{c.count} x {c.subject}" if c.count > 1 else str(c.subject), r=c.receptacle,
        liquid=c.liquid or "liquid") for c in conditions)


def cond(pred: Predicate, ref: ObjectRef, count: int = 1, receptacle: ObjectRef | None = None,
         liquid: str | None = None) -> Condition:
    return Condition(predicate=pred, subject=ref, count=count if ref.id is None else 1,
                     receptacle=receptacle, liquid=liquid)


#: verbs that discard alone ("chuck it") but move to a place when one is said
_THROWING = _W.set("throwing")


#: cooking verbs that happen in a pan: the food ends up in it
_PAN_VERBS = _W.set("pan_verbs")


class Semantics:
    """Turns frames into drafts, keeping the mention history for pronouns."""

    def __init__(self, grounder: Grounder) -> None:
        self.g = grounder
        self.cat = load_catalogue()
        self.discourse = Discourse(grounder)
        #: every mention so far (shared with the discourse, which resolves pronouns)
        self.history: list[Mention] = self.discourse.history
        self._group = 0
        #: objects of an act that could not be read while the act's other objects could
        self.skipped: list[OfflineParseError] = []
        #: what each act asks of one object (acts not here: :meth:`_plain_act`)
        self._act_rules: dict[Act, Callable[[Frame, Act, Target, int, int], list[Draft]]] = {
            Act.PLACE: self._place_act, Act.TRASH: self._trash_act,
            Act.CLEAN: self._clean_act, Act.TOAST: self._toast_act, Act.HEAT: self._heat_act,
            Act.MICROWAVE: self._heat_act, Act.COOK: self._heat_act, Act.FILL: self._fill_act,
            Act.WATER: self._fill_act, Act.TOGGLE: self._toggle_act,
        }

    def ground(self, head: Head, need: str | None, group: int, clause: int,
               role: str = "object") -> Ref:
        if head.pron is not None or (head.piece and head.noun is None):
            ref = self.discourse.resolve(head, need, role)
        elif head.container_of is not None:
            ref = self.discourse.container(head, need)
        elif (named := self._shortened(head)) is not None:
            ref = named
        else:
            ref = self.g.ground(head, need)
            if head.alternatives:
                alts = [self.g.ground(a, need) for a in head.alternatives if a.pron is None]
                types = tuple(dict.fromkeys([*ref.type_names(), *(t for a in alts for t in a.type_names())]))
                ref = Ref(head.label(), ((ObjectRef(types=types), 1),))
            elif role == "object":
                ref = self.discourse.bind_salient(ref, head)
        if head.excluded:
            ref = self._without(ref, head.excluded)
        self.history.append(Mention(ref, head, clause, group, role))
        self.discourse.remember_places(ref, head)
        return ref

    def _shortened(self, head: Head) -> Ref | None:
        """"the spray bottle ... take the bottle out": a definite noun that ends a compound
        named before is that thing again (not any bottle)."""
        if not head.definite or head.noun is None or head.location or head.filters or head.count is not None \
                or head.plural or len(head.noun.phrase.split()) != 1:
            return None
        word = head.noun.phrase
        return next((m.ref for m in reversed(self.history) if m.head.noun is not None and m.head.pron is None
                     and m.head.noun.phrase.endswith(" " + word) and len(m.ref.groups) == 1), None)

    def _without(self, ref: Ref, excluded: list[Head]) -> Ref:
        """"all the lights except the desk lamp": the reference less the types left out
        (a left-out phrase that names nothing here leaves it as it is)."""
        gone: set[str] = set()
        for h in excluded:
            try:
                gone |= set(self.g.ground(h, None).type_names())
            except OfflineParseError:
                continue
        groups = []
        for r, n in ref.groups:
            if r.id is not None:
                if r.id.split("_")[0] not in gone:
                    groups.append((r, n))
                continue
            kept = tuple(t for t in r.types if t not in gone)
            if kept:
                groups.append((ObjectRef(types=kept), n))
        if not groups:
            raise OfflineParseError(f"nothing is left of {ref.label!r} once "
                                    f"{', '.join(h.label() for h in excluded)} is left out",
                                    phrase=ref.label)
        return Ref(ref.label, tuple(groups), ref.plural)

    def note(self, head: Head, clause: int, role: str | None = None) -> None:
        """Record a mention of a clause that produced nothing (for later pronouns):
        "There's a bottle of wine in the cupboard. Put it in the fridge." """
        if head.pron is not None or head.noun is None:
            return
        try:
            ref = self.g.ground(head, None)
        except GroundingError as exc:
            # an unknown or absent object is no antecedent; if a later "it" finds nothing
            # else, this is why ("my phone is on the counter. Get it." with no phone)
            self.discourse.unresolved.append(exc)
            return
        self.history.append(Mention(ref, head, clause, -1 - clause, role or head.role))
        self.discourse.remember_places(ref, head)

    # ---- frames ----------------------------------------------------------------------
    def frame(self, frame: Frame, clause: int) -> list[Draft]:
        self._group += 1
        act = frame.act
        state = frame.state
        if act in (Act.VAGUE, Act.CLEAN) and self._umbrella(frame):
            # "straighten up in here - laptop on the dresser, remote on the sofa": the
            # placements listed after the umbrella verb are what it asks
            placed = [t for t in frame.targets if t.dest]
            return self._act(replace(frame, act=Act.PLACE, verb="put", targets=placed),
                             Act.PLACE, clause)
        if act is Act.VAGUE and frame.verb == "sort" and self._switched_thing(frame):
            # "sort out the lamp" (the one lamp is on): the one thing a lamp can be put
            # right in is its switch, so the other state
            return self._act(replace(frame, act=Act.TOGGLE), Act.TOGGLE, clause)
        if act in (Act.VAGUE,):
            raise OfflineParseError(
                f"{frame.verb!r} is too vague for the offline parser: say which objects go "
                "where (e.g. 'put the book on the shelf')", phrase=frame.verb, vague=True)
        if act is Act.EMPTY:
            raise OfflineParseError("emptying a container cannot be stated as a goal here",
                                    phrase=frame.verb, vague=True)
        if act is Act.PLACE and state == (Stat.SWITCH, True) and frame.particle == "on" and frame.targets \
                and all(not t.dest for t in frame.targets) and not any(self._switches(t.head) for t in frame.targets) \
                and self._stranded_place(frame, frame.targets[0].head) is not None:
            # "take a spare roll from the shelf and put it on": on the holder named before,
            # not switched on
            frame = replace(frame, state=None, targets=[replace(t, state=None, particle=None) for t in frame.targets])
            state = None
        flip = frame.negated
        if frame.report or frame.too:
            flip = not flip if not (frame.report and frame.too) else True
            if frame.report and frame.negated:
                return self._missing(frame, clause)
        if (act in (None, Act.CAUSE, Act.MAKE) and state is not None) or (act is Act.SWITCH and state):
            return self._state(frame, state, flip, clause)
        if act is None:
            return []
        if flip:
            st = lx.ACT_STATE.get(act)
            if st is None or st[0] not in lx.INVERTIBLE:
                return []      # "don't break the vase": a prohibition, no goal
            # "don't switch the TV on": the particle's state on the object is what is
            # refused, not wanted
            frame = replace(frame, targets=[replace(t, state=None) if t.state == st else t for t in frame.targets])
            return self._state(frame, (st[0], not st[1]), False, clause)
        drafts = self._act(frame, act, clause)
        for _, positive in frame.room_states:
            # "open a book in a well lit room"
            pred = P.switched_on if positive else P.switched_off
            drafts = concat(drafts, self._each(pred, self.g.light_sources(positive)))
        return drafts

    def _missing(self, frame: Frame, clause: int) -> list[Draft]:
        """A complaint that something was not done or is not so asks for it: "nobody
        closed the fridge" (a past act not done), "the bread isn't sliced yet" (a state
        missing); "nobody is watching the TV" (an act not going on) asks for the state that
        ends it (the TV off)."""
        if frame.act is not None and frame.past and frame.state is None:
            return self._act(frame, frame.act, clause)
        if frame.act is None and frame.state is not None:
            return self._state(frame, frame.state, False, clause)
        st = lx.ACT_STATE.get(frame.act) if frame.act is not None else None
        if st is None or st[0] not in lx.INVERTIBLE:
            return []
        if frame.act is Act.WATCH:
            # "nobody's using the laptop or those lamps": what opens is shut (a laptop),
            # what only switches is switched off; each thing named ("or" is "and" here)
            targets = [Target(replace(h, alternatives=[]), t.dest, t.prep, t.particle,
                              (Stat.OPEN, False) if self._opens(h) else None)
                       for t in frame.targets for h in (t.head, *t.head.alternatives)]
            frame = replace(frame, targets=targets)
        return self._state(frame, (st[0], not st[1]), False, clause)

    def _opens(self, head: Head) -> bool:
        return head.noun is not None and any(self.g.has_type(x) and self.g.can(x, "open")
                                             for x in head.noun.concept.types)

    def _switched_thing(self, frame: Frame) -> bool:
        """Are the frame's objects one named light or lamp (nothing else to put right)?"""
        targets = self._targets(frame)
        return len(targets) == 1 and not targets[0].dest and targets[0].head.pron is None \
            and targets[0].head.noun is not None and targets[0].head.noun.concept.kind in ("lights", "lamps")

    def _umbrella(self, frame: Frame) -> bool:
        """Is the act an umbrella over the placements listed after it? A vague verb, or
        cleaning something that is no object ("clean up the desk, pen in the drawer"),
        followed by objects with places."""
        if not any(t.dest for t in frame.targets):
            return False
        if frame.act is Act.VAGUE:
            return True
        first = frame.targets[0]
        if first.dest or first.head.noun is None:
            return False
        try:
            return not any(self.g.can(t, "hold") for t in self.g.candidate_types(first.head, None))
        except GroundingError:
            return first.head.noun.concept.kind == "room"

    def _targets(self, frame: Frame) -> list[Target]:
        return [t for t in frame.targets if not t.head.is_empty or t.head.pron is not None]

    def _state(self, frame: Frame, state: tuple[Stat, bool], flip: bool, clause: int) -> list[Draft]:
        out: list[Draft] = []
        failed: list[OfflineParseError] = []
        targets = self._targets(frame)
        own_states = any(t.state is not None for t in targets)
        for t in targets:
            try:
                placed = bool(t.dest) and not (frame.report or flip)
                if (t.state or state) == (Stat.OPEN, False) and frame.particle == "away" and not t.dest \
                        and t.head.noun is not None \
                        and not any(self.g.can(x, "open") for x in t.head.noun.concept.types):
                    # "the remote shut away inside the box": the clause's other frame put it
                    # in the box; the box is what is shut
                    box = next((m for m in reversed(self.history) if m.clause == clause and m.role == "dest"
                                and any(self.g.can(x, "open") for x in m.ref.type_names())), None)
                    if box is not None:
                        out = concat(out, self._each(P.closed, box.ref))
                        continue
                if not (placed and own_states and t.state is None):
                    # "get the bread sliced and the egg into the fridge": the egg has only
                    # its place; "get a potato cooked and onto a plate": both
                    out = concat(out, self._with_contents(t, self._state_of(t, state, flip, clause),
                                                          frame.report or flip, clause))
                if placed:
                    out = concat(out, self._place(frame, t, self._group, clause))
            except OfflineParseError as exc:
                failed.append(exc)      # "ugh, the light is on": the light still is
        if flip and frame.report:
            # "the egg has gone off": a report of a state the object cannot be put out of
            # is a statement about something else, not a complaint
            failed = [e for e in failed if not isinstance(e, IncapableError)]
            if not failed and not out:
                return out
        if failed and not out:
            raise failed[0]
        self.skipped.extend(failed)
        if not out and state[0] is Stat.BRIGHT and not self._targets(frame):
            out += self._lighting(state[1] != flip)
        return out

    def _with_contents(self, t: Target, drafts: list[Draft], described: bool, clause: int) -> list[Draft]:
        """"I want the fridge shut with the apple in it": what the object is to hold goes
        in first, then the object gets its state (in a report or a complaint, "with the
        apple in it" only describes)."""
        if described or not drafts:
            return drafts
        return then(self._filled_first(t, self._group, clause), drafts)

    def _state_of(self, t: Target, state: tuple[Stat, bool], flip: bool, clause: int) -> list[Draft]:
        """The drafts that give one object its state ("leave the fridge closed and the
        light on": each object its own state)."""
        out: list[Draft] = []
        stat, positive = t.state or state
        if flip:
            if stat in (Stat.HOT, Stat.COLD) and self._perishable(t.head):
                # "the wine's going to be warm by dinner", "my tea's gone cold": food or
                # drink at the wrong temperature asks for the other one
                stat, positive = (Stat.COLD, True) if stat is Stat.HOT else (Stat.HOT, True)
            elif stat not in lx.INVERTIBLE or (stat is Stat.CLEAN and positive):
                return []       # "it's clean": good news, no complaint
            else:
                positive = not positive
        head = t.head
        if stat is Stat.BRIGHT and not self._is_light(head) and head.noun is not None \
                and head.noun.concept.kind == "object" and self._switched_not_opened(head):
            # "the picture box is all dark": a screen that is dark is off
            return self._each(P.switched_on if positive else P.switched_off,
                              self.ground(head, "switch", self._group, clause))
        if stat is Stat.BRIGHT or (head.noun is not None and head.noun.concept.kind == "room"):
            if self._is_light(head):
                ref = self.ground(head, "switch", self._group, clause)
                out += self._each(P.switched_on if positive else P.switched_off, ref)
            else:
                out += self._lighting(positive)
            return out
        if _is_everything(head) and (stat, positive) in _ALL_OF:
            out += self._everything(stat)
            return out
        if head.noun is None and head.recipe is not None:
            # "I want my coffee hot": the dish, then the state of what it is served in
            out += self._recipe(head.recipe, clause, head)
            pred = STAT_PREDICATE.get((stat, positive))
            if pred is not None:
                out += self._each(pred, self.history[-1].ref)
            return out
        if stat is Stat.TOASTED:
            out += self._act(Frame(Act.TOAST, "toast", [t]), Act.TOAST, clause)
            return out
        if stat is Stat.CLEAN and positive:
            out += self._act(Frame(Act.CLEAN, "clean", [t]), Act.CLEAN, clause)
            return out
        if head.noun is None and head.liquid is not None and head.pron is None and stat is Stat.HOT:
            # "fill the kettle ... so the water's hot": the water is in what was filled
            head = Head(text=head.text, pron="it")
            ref = self.discourse.resolve(head, "fill")
        else:
            ref = self.ground(head, STAT_NEEDS[stat], self._group, clause)
        pred = STAT_PREDICATE.get((stat, positive))
        if pred is None:
            return out
        liquid = "water" if pred is P.filled else None
        out += self._each(pred, ref, liquid=liquid)
        return out

    @staticmethod
    def _is_light(head: Head) -> bool:
        """"the lamp is too bright", "dim the lights": the lights named, not the room."""
        concept = head.noun.concept if head.noun is not None else None
        return concept is not None and (concept.kind in ("lights", "lamps") or concept.types[:1] in (
            ("LightSwitch",), ("DeskLamp",), ("FloorLamp",)))

    def _lighting(self, bright: bool) -> list[Draft]:
        """"make it dark": every light source off and the blinds closed where the room has
        them (daylight counts); "make it bright": the main light on (minimal sufficient)."""
        out = self._each(P.switched_on if bright else P.switched_off, self.g.light_sources(bright))
        blinds = self.g.every_instance(("Blinds",))
        if not bright and blinds is not None:
            out += self._each(P.closed, blinds)
        return out

    def _everything(self, stat: Stat) -> list[Draft]:
        """"turn everything off", "close everything": every switchable object that is on
        (every openable one that is open) now, all instances of each such type."""
        ref = self.g.all_that_are(stat)
        pred = P.switched_off if stat is Stat.SWITCH else P.closed
        return self._each(pred, ref)

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
        """The drafts of an act on the frame's objects: acts that need none (dim the room,
        water the plant), dishes and pouring, an elided object, then each object."""
        targets = self._targets(frame)
        g = self._group
        if act in (Act.DIM, Act.BRIGHTEN) and not targets:
            return self._lighting(act is Act.BRIGHTEN)
        if act is Act.WATER and not targets:
            targets = [Target(Head(text="plant", noun=NounReading(lx.nouns()["plant"], "plant", False)))]
        if act is Act.MAKE:
            return self._make(frame, targets, clause)
        if act is Act.POUR:
            return self._pour(frame, targets, clause)
        if act is Act.CAUSE and _nothing_asked(frame, targets):
            for t in targets:      # "keep the apple": nothing asked of it
                self.note(t.head, clause)
            return []
        if not targets and self.history and act is not Act.CAUSE and (
                act not in (Act.PLACE, Act.GO) or frame.means is not None):
            act, targets = self._elided_object(frame, act)
        if not targets:
            if act in (Act.SWITCH_OFF, Act.SWITCH_ON) and frame.verb in ("dim", "kill"):
                return self._each(P.switched_off, self.g.light_sources())
            # "I want to watch a movie": no object, maybe said better by another clause
            raise OfflineParseError(f"{frame.verb!r} needs an object: what should be "
                                    f"{past_participle(frame.verb)}?", phrase=frame.text, vague=True)
        if act is Act.GO and not any(t.dest for t in targets):
            return []
        act = Act.PLACE if act is Act.GO else act
        return self._per_object(frame, act, targets, g, clause)

    def _per_object(self, frame: Frame, act: Act, targets: list[Target], g: int, clause: int) -> list[Draft]:
        """The act on each object in turn."""
        # "put the book on the bed and the pillow too": a later object without a place
        # goes where the one before it went
        for prev, t in itertools.pairwise(targets):
            if prev.dest and not t.dest and act in (Act.PLACE, Act.CAUSE, Act.HOLD):
                t.dest, t.prep = prev.dest, prev.prep
        out: list[Draft] = []
        failed: list[OfflineParseError] = []
        for t in targets:
            try:
                out = concat(out, self._target(frame, act, t, g, clause))
            except OfflineParseError as exc:
                # "put the apple in the frobnicator and the tomato in the fridge": one
                # object or place that cannot be read does not sink the others
                failed.append(exc)
        if failed and not out:
            raise failed[0]
        self.skipped.extend(failed)
        return out

    def _elided_object(self, frame: Frame, act: Act) -> tuple[Act, list[Target]]:
        """"wash the apple and put in the fridge", "the bread needs to be sliced and put on
        a plate", "the vases - all four - go in the box": the object is elided, it is the
        one just acted on (a place said as the means is where it goes)."""
        last = next((m for m in reversed(self.history) if m.role == "object"), None)
        word = "them" if last is not None and last.ref.plural else "it"
        act = Act.PLACE if act is Act.GO else act
        place = [frame.means] if act is Act.PLACE and frame.means is not None else []
        if place:
            place[0].role = "dest"
            frame.means = None
        return act, [Target(Head(text=word, pron=word), place, "in" if place else None)]

    def _target(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """The drafts of one object of an act: what it must be first (its wanted states,
        its contents, the dish it is), then the act itself."""
        wanted = self._wanted(frame, act, t.head)
        said = t
        if wanted:
            t = Target(replace(t.head, filters=[f for f in t.head.filters if f not in wanted]),
                       t.dest, t.prep)
        one: Act | None = act
        if act is Act.CAUSE:
            one = self._wish_act(frame, t, wanted, clause)
            if one is Act.MAKE:
                return self._make(frame, [said], clause)
        # "microwave a plate containing an egg": first the egg on the plate; "bring me a
        # chilled tomato on a plate": first the tomato cold
        before = self._filled_first(t, g, clause)
        if t.head.recipe is not None and t.head.pron is None and one in (
                Act.PLACE, Act.HOLD, Act.TRASH):
            # "put the toast on a plate", "bring me a coffee": the dish is made first,
            # then what it is served in is moved
            before = concat(before, self._recipe(t.head.recipe, clause, t.head))
            t = Target(Head(text=t.head.label(), pron="it"), t.dest, t.prep)
        for stat, positive in wanted:
            for d in self._state(Frame(None, frame.verb, [t]), (stat, positive), False, clause):
                d.wished = True
                before.append(d)
        main = self._one(frame, one, t, g, clause) if one is not None else []
        if t.head.pron in ("one", "it", "them", "ones") and OTHER_WORDS & set(t.head.text.split()):
            for d in main:
                d.another = True
        if t.head.pron is not None and not t.dest and not frame.recipient and frame.verb in _CARRYING:
            for d in main:
                d.carried = all(c.predicate is P.held for c in d.conditions)
        return then(before, main)

    def _wanted(self, frame: Frame, act: Act, head: Head) -> list[tuple[Stat, bool]]:
        """States an object is asked *to have* rather than picked by: an indefinite noun
        phrase in a wish, a request to bring or place ("I'd like a cold apple", "bring me a
        chilled tomato", "put a clean plate on the table"); "the dirty mug" (definite) is
        the one that is dirty."""
        if head.definite or head.pron is not None or not head.filters:
            return []
        if not (frame.wish or frame.ready or frame.recipient
                or act in (Act.PLACE, Act.HOLD, Act.CAUSE, Act.MAKE)):
            return []
        out: list[tuple[Stat, bool]] = []
        for stat, positive in head.filters:
            if stat not in DESIRABLE or not positive:
                continue
            try:
                types = self.g.candidate_types(replace(head, filters=[]), WISHED_NEEDS[stat])
            except GroundingError:
                continue       # "a clean apple": an apple is never dirty, nothing to ask
            if types:
                out.append((stat, positive))
        return out

    def _wish_act(self, frame: Frame, t: Target, wanted: list[tuple[Stat, bool]],
                  clause: int) -> Act | None:
        """What "I'd like X", "can I have X", "get X ready" asks for X: a placement when a
        place is named, the dish when X is one, its wanted states, else X in hand."""
        head = t.head
        if t.dest:
            return Act.PLACE
        if head.pron is not None:
            return Act.HOLD       # "get it out", "can I have it"
        if head.recipe or head.contents or (head.liquid and head.noun is None):
            return Act.MAKE
        if wanted and not frame.recipient:
            return None
        if frame.ready and not wanted:
            self.note(head, clause)
            return None
        try:
            self.g.candidate_types(head, "hold")
        except GroundingError:
            if frame.recipient or frame.verb == "get":
                raise
            self.note(head, clause)     # "I'd like some light": not something to hand over
            return None
        return Act.HOLD

    def _filled_first(self, t: Target, g: int, clause: int) -> list[Draft]:
        """What the object is to hold ("a plate containing an egg"), each put in it."""
        if not t.head.holds:
            return []
        container = self.ground(t.head, "receptacle", g, clause)
        held = [self.ground(h, "hold", g, clause) for h in t.head.holds]
        return [self._draft([cond(P.inside, r, n, container.single())], h, container)
                for h in held for r, n in h.groups]

    def _one(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """The drafts of one act on one object: the act is first made precise by the
        object and the words around it (a particle, a missing place, water to boil, the
        microwave as means), then the act's rule (:attr:`_act_rules`) says what it asks."""
        if act in (Act.SWITCH_ON, Act.SWITCH_OFF) and t.particle in ("on", "off"):
            act = Act.SWITCH_ON if t.particle == "on" else Act.SWITCH_OFF
        if act in (Act.OPEN, Act.CLOSE) and not t.dest and self._switched_not_opened(t.head):
            # "open the light", "close the TV", "open the water": in many languages one
            # verb opens doors and switches things on
            act = Act.SWITCH_ON if act is Act.OPEN else Act.SWITCH_OFF
        special = self._whole_reading(frame, act, t, g, clause)
        if special is not None:
            return special
        if act is Act.PLACE and not t.dest:
            placed = self._place_unsaid(frame, t, g, clause)
            if isinstance(placed, list):
                return placed
            act = placed
        if (act is Act.COOK and self._is_water(t.head)) or (
                act is Act.HEAT and t.head.noun is None and t.head.liquid == "water"):
            return self._boil(frame, t, g, clause)
        if act is Act.HOLD and t.dest:
            act = Act.PLACE
        if act is Act.PLACE and frame.timed and t.dest and t.dest[0].noun is not None and \
                "Microwave" in t.dest[0].noun.concept.types:
            act = Act.MICROWAVE     # "pop the potato in the microwave for a couple of minutes"
        if act in (Act.SLICE, Act.BREAK) and t.dest:
            return self._cut_into(frame, act, t, g, clause)
        if act in (Act.SLICE, Act.BREAK) and (t.head.noun is None or "Egg" in t.head.noun.concept.types) \
                and (there := self._stranded_place(frame, t.head)) is not None \
                and "Egg" in (obj := self.ground(t.head, "slice", g, clause)).type_names():
            # "the pan's on the stove, crack the egg (it) in there": into the pan
            cut = self._draft([cond(P.sliced, r, n) for r, n in obj.groups], obj)
            pieces = ObjectRef(types=tuple(p[0] for x in obj.type_names() if (p := self.cat.slice_product(x))))
            into = self._draft([cond(P.inside, pieces, 1, there.single())], obj, there)
            into.after = [0]
            return [cut, into]
        if act is Act.SLICE and t.head.piece and (t.head.noun is not None or t.head.pron is not None):
            return self._cut_pieces(frame, t, g, clause)
        if act is Act.CLOSE and t.dest and t.prep in ("in", "inside", "into"):
            return self._shut_in(frame, t, g, clause)
        rule = self._act_rules.get(act, self._plain_act)
        return rule(frame, act, t, g, clause)

    def _switches(self, head: Head) -> bool:
        """Can what the phrase names be switched (by itself or its knobs)?"""
        try:
            names = head.noun.concept.types if head.noun is not None else \
                self.discourse.resolve(head, None).type_names()
        except OfflineParseError:
            return True
        return any(self.g.has_type(x) and (self.g.can(x, "switch") or lx.SWITCHED_BY.get(x)) for x in names)

    def _perishable(self, head: Head) -> bool:
        """Is the phrase food or drink (or what holds a drink), whose temperature matters:
        a wine bottle, a tomato, a mug; not a pan, a kettle or an appliance?"""
        if head.noun is not None:
            names: tuple[str, ...] = head.noun.concept.types
        elif head.pron is not None and self.history:
            try:
                names = self.discourse.resolve(head, None).type_names()     # "it's warm": the wine
            except OfflineParseError:
                return False
        else:
            return head.recipe is not None
        types = [x for x in names if x in self.cat.types]
        return bool(types) and all(self.cat.type(x).has("pickupable") and x not in COOKWARE for x in types)

    def _switched_not_opened(self, head: Head) -> bool:
        """Does the phrase name only things that switch and none that open (a lamp, the
        TV, running water), in this scene?"""
        if head.noun is None:
            return head.liquid == "water" and self.g.has_type("Faucet")
        types = [x for x in (*head.noun.concept.types, *head.noun.concept.fallback) if self.g.has_type(x)]
        return bool(types) and not any(self.g.can(x, "open") for x in types) \
            and any(self.g.can(x, "switch") for x in types)

    def _shut_in(self, frame: Frame, t: Target, g: int, clause: int) -> list[Draft]:
        """"Lock my keys in the safe": the keys go in, then the safe is shut."""
        placed = self._place(frame, t, g, clause)
        return then(placed, self._plain_act(frame, Act.CLOSE, Target(t.dest[0]), g, clause))

    def _cut_pieces(self, frame: Frame, t: Target, g: int, clause: int) -> list[Draft]:
        """"Cut two slices of bread (and put them on the plate)": the bread is what is cut,
        and the pieces are what a pronoun after it means."""
        whole = Target(replace(t.head, piece=False, count=None), t.dest, t.prep, t.particle, t.state)
        out = self._plain_act(frame, Act.SLICE, whole, g, clause)
        cut = next((m.ref for m in reversed(self.history) if m.head is whole.head), None)
        products = [p for p in (self.cat.slice_product(x) for x in (cut.type_names() if cut else ())) if p]
        self.history[:] = [m for m in self.history if m.head is not whole.head]
        if products:
            n = t.head.count or 1
            pieces = Ref(t.head.label(), ((ObjectRef(types=tuple(p[0] for p in products)), n),), n > 1)
            self.history.append(Mention(pieces, t.head, clause, g, "object"))
        return out

    def _whole_reading(self, frame: Frame, act: Act, t: Target, g: int,
                       clause: int) -> list[Draft] | None:
        """Objects that change what the act means: a liquid poured into its destination
        ("fill water in the kettle"), a room ("clean the kitchen": too vague; "dim the
        room": its lights), "everything" switched off or closed, the blinds' particle."""
        head = t.head
        if head.noun is None and head.liquid is not None and t.dest and act in (
                Act.FILL, Act.PLACE, Act.POUR):
            out: list[Draft] = []
            for d in t.dest:
                ref = self.ground(d, "fill", g, clause, "place")
                out += self._each(P.filled, ref, liquid=head.liquid)
            return out
        room = head.noun is not None and head.noun.concept.kind == "room"
        if room and act in (Act.CLEAN, Act.DIRTY):
            raise OfflineParseError(f"'{frame.verb} {head.label()}' is too vague for the offline "
                                    "parser: say which objects to clean", phrase=head.label(),
                                    vague=True)
        if room and act in (Act.DIM, Act.BRIGHTEN):
            return self._lighting(act is Act.BRIGHTEN)
        if _is_everything(head) and act in (Act.SWITCH_OFF, Act.CLOSE):
            return self._everything(Stat.SWITCH if act is Act.SWITCH_OFF else Stat.OPEN)
        blind = self._blinds_particle(frame, act, head)
        if blind is not None:
            return self._state(Frame(None, frame.verb, [t]), (Stat.OPEN, blind), False, clause)
        return None

    def _place_unsaid(self, frame: Frame, t: Target, g: int, clause: int) -> list[Draft] | Act:
        """A placement without a place: a state said instead ("leave the fridge closed"),
        a place the verb names ("hang the towel", "shelve the book"), "put it back"; else
        the verb says whether it goes in the bin or to the person, or where is unknown."""
        head = t.head
        if frame.state is not None:
            return self._state(Frame(None, frame.verb, [t]), frame.state, False, clause)
        if frame.verb == "hang" or frame.verb in lx.VERB_PLACES:
            obj = self.ground(head, "hold", g, clause)
            places = lx.VERB_PLACES.get(frame.verb) or [     # "hang the towel": a holder that takes it
                r for r, types in self.cat.receptacle_whitelist.items()
                if set(types) & set(obj.type_names()) and r.endswith(("Holder", "Hanger"))]
            dest = self.g.types_ref(places, "its holder" if frame.verb == "hang" else frame.verb)
            return self._each(P.inside, obj, dest, receptacle=dest.single())
        if frame.particle == "back":
            return self._put_back(frame, t, g, clause)
        stranded = self._stranded_place(frame, head)
        if stranded is not None:
            obj = self.ground(head, "hold", g, clause)
            if head.pron is not None and obj.types & stranded.types:
                # "put the watch in the box, close the box when it's in": "it" is what goes
                # in, not the place it goes in
                inner = next((m.ref for m in reversed(self.history) if m.role == "object"
                              and m.head.noun is not None and not m.ref.types & stranded.types), None)
                if inner is None:
                    return []
                obj = inner
            return self._each(P.inside, obj, stranded, receptacle=stranded.single())
        if frame.verb in _VERBS_TO_BIN:
            return Act.TRASH
        if frame.verb in _VERBS_TO_HAND or frame.recipient:
            return Act.HOLD
        if head.pron is None and head.noun is not None:
            self.g.candidate_types(head, "hold")  # a thing the room lacks: say that, not "where"
        raise OfflineParseError(f"where should {head.label()!r} go? "
                                f"('{frame.verb or 'put'} {head.label()} in/on ...')",
                                phrase=frame.text, vague=True)

    def _stranded_place(self, frame: Frame, head: Head) -> Ref | None:
        """"Open a drawer, put the keys in, and close it": a preposition left at the end
        of the clause points at the last thing mentioned that can take the object."""
        words = frame.text.split()
        if not words or words[-1] not in ("in", "inside", "on", "there", "onto", "into"):
            return None
        types = head.noun.concept.types if head.noun is not None else ()
        # where a thing named stands is not where "in there" points ("the pan's on the
        # stove, crack it in there": the pan)
        landmarks = {id(land) for m in self.history for _, land in m.head.location}
        # ... unless nothing else can take it ("the tomato's in the fridge, put the egg in
        # there with it": the fridge)
        for skip_landmarks in (True, False):
            for m in reversed(self.history):
                places = [r for r in m.ref.type_names()
                          if r in self.cat.types and self.cat.types[r].has("receptacle")]
                if m.head is head or m.head.noun is None or not places or (
                        skip_landmarks and id(m.head) in landmarks and m.role == "place"):
                    continue
                if not types or any(self.cat.can_place(t, r) for t in types for r in places):
                    return m.ref
        return None

    # ---- one rule per act (the verb -> condition table of docs/offline_parser.md) ---------
    def _place_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        return self._place(frame, t, g, clause)

    def _trash_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """Into the garbage can, unless a verb of motion has a place: "chuck the apple in
        the fridge" puts it there; "throw away the cloth in the tub" and "bin the cloth in
        the tub" discard it (the place says which cloth)."""
        if t.dest and frame.verb in _THROWING and frame.particle is None:
            return self._place(frame, t, g, clause)
        stranded = self._stranded_place(frame, t.head) if frame.verb in _THROWING else None
        obj = self.ground(t.head, "hold", g, clause)
        # "open the hamper, throw the pillow in": in the hamper
        can = stranded if stranded is not None else self.g.types_ref(("GarbageCan",), "garbage can")
        return self._each(P.inside, obj, can, receptacle=can.single())

    def _toast_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """Toast is cooked slices: cut what is whole first ("toast a slice of bread" too);
        one slice: ``cooked(Bread)`` (any slice of it); more: that many cooked slices."""
        obj = self.ground(t.head, "cook", g, clause)
        drafts: list[Draft] = []
        wholes = [_whole(r) for r, _ in obj.groups]
        sliceable = [w for w in wholes if any(self.cat.slice_product(x) for x in _names(w))]
        if sliceable:
            drafts.append(self._draft([cond(P.sliced, w) for w in dict.fromkeys(sliceable)], obj))
        cooked = self._draft([cond(P.cooked, _whole(r) if n == 1 else r, n)
                              for r, n in obj.groups], obj)
        if drafts:
            cooked.after = [0]
        return [*drafts, cooked]

    def _heat_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """Heat / cook X, with the microwave as the means when it is named ("in the
        microwave", "using the microwave", "the microwave is fine"): the appliance is an
        intermediate step, never a goal object."""
        obj = self.ground(t.head, "cook" if act is Act.COOK else None, g, clause)
        result = P.cooked if act is Act.COOK else P.hot
        done = self._draft([cond(result, r, n) for r, n in obj.groups], obj)
        means = [m for m in (frame.means, *(t.dest[:1]), *frame.instruments) if m is not None]
        use_microwave = act is Act.MICROWAVE or any(
            m.noun is not None and "Microwave" in m.noun.concept.types for m in means)
        if use_microwave and self.g.has_type("Microwave"):
            mw = self.g.types_ref(("Microwave",), "microwave")
            step = self._draft([*(cond(P.inside, r, n, mw.single()) for r, n in obj.groups),
                                cond(P.switched_on, mw.single())], obj, mw, intermediate=True)
            done.after = [0]
            return [step, done]
        vessel = next((x for m in means if m.noun is not None for x in m.noun.concept.types if x in ("Pan", "Pot")),
                      None)
        if vessel is None and frame.verb in _PAN_VERBS and not means:
            vessel = "Pan"
        if act is Act.COOK and t.head.pron is None and vessel is not None \
                and self.g.has_type(vessel) and vessel not in obj.type_names():
            # "fry me an egg", "cook the potato in the pan (pot)": what is cooked ends up in
            # the pan or pot, cooked there
            pan = self.g.types_ref((vessel,), vessel.lower())
            done.conditions = [*(cond(P.inside, r, n, pan.single()) for r, n in obj.groups),
                               *done.conditions, *self._on_the_stove(pan.single())]
        return [done]

    def _fill_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        obj = self.ground(t.head, "fill", g, clause)
        liquid = "water" if act is Act.WATER else frame.liquid or t.head.contents or "water"
        return self._each(P.filled, obj, liquid=liquid)

    def _toggle_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """"toggle the lamp": each group to the opposite of how it is now."""
        obj = self.ground(t.head, "switch", g, clause)
        flipped = []
        for r, n in obj.groups:
            on = all(o.is_on for o in self.discourse.objects(r))
            flipped.append(cond(P.switched_off if on else P.switched_on, r, n))
        return [self._draft(flipped, obj)]

    def _plain_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """An act that is one state of its object (slice, open, switch off, chill, ...)."""
        pred = ACT_PREDICATE.get(act)
        if pred is None:
            return []
        return self._each(pred, self.ground(t.head, ACT_NEEDS.get(act), g, clause))

    @staticmethod
    def _blinds_particle(frame: Frame, act: Act, head: Head) -> bool | None:
        """"pull the blinds down", "blinds up": up is open, down is closed."""
        if frame.particle not in ("up", "down") or head.noun is None or \
                "Blinds" not in head.noun.concept.types or act not in (
                    Act.PLACE, Act.CAUSE, Act.HOLD, Act.OPEN, Act.CLOSE):
            return None
        return frame.particle == "up"

    def _cut_into(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        """"crack an egg into the pan", "slice the tomato into the bowl": cut, then the
        pieces in the place."""
        obj = self.ground(t.head, "slice", g, clause)
        pieces = tuple(p[0] for x in obj.type_names() if (p := self.cat.slice_product(x)))
        pieces = pieces or obj.type_names()     # already pieces: they are what goes there
        cut = self._draft([cond(P.sliced, r, n) for r, n in obj.groups], obj)
        slices = Ref(f"pieces of {obj.label}", ((ObjectRef(types=pieces), 1),))
        placed = self._place(frame, Target(Head(text=slices.label), t.dest, t.prep), g, clause,
                             slices)
        for d in placed:
            d.after = [0]
        return [cut, *placed]

    def _put_back(self, frame: Frame, t: Target, g: int, clause: int) -> list[Draft]:
        """"take the apple out of the fridge, slice it and put it back": back where it was
        taken from (or said to be)."""
        obj = self.ground(t.head, "hold", g, clause)
        origin = self.discourse.origins.get(obj.types)
        if origin is None:
            raise OfflineParseError(f"where should {t.head.label()!r} go back to? "
                                    f"('put {t.head.label()} back in/on ...')",
                                    phrase=frame.text, vague=True)
        return self._place(frame, Target(t.head, [origin], "in"), g, clause, obj)

    def _is_water(self, head: Head) -> bool:
        """"boil water", "boil the kettle" (or "boil it", the kettle): water is no object,
        what holds it is."""
        if head.pron is not None and head.noun is None:
            try:
                self.discourse.resolve(head, "cook")
                return False           # "put the egg in the pot and boil it": the egg
            except OfflineParseError:
                pass
            try:
                meant = self.discourse.resolve(head, "fill").type_names()
            except OfflineParseError:
                return False
            return bool(meant) and all(self.g.can(x, "fill") and not self.g.can(x, "cook") for x in meant)
        if head.noun is None:
            return head.liquid == "water"
        if head.contents is not None:
            return False       # "boil the pot of coffee": the coffee is what is heated
        try:
            types = self.g.candidate_types(head, None)
        except GroundingError:
            return False
        return all(self.g.can(x, "fill") and not self.g.can(x, "cook") for x in types)

    def _boil(self, frame: Frame, t: Target, g: int, clause: int) -> list[Draft]:
        """"boil water in the pot": the pot filled with water and hot (a kettle, else a pot,
        when no container is named)."""
        if t.head.noun is not None:
            vessel = self.ground(t.head, "fill", g, clause)
        else:
            named = [m for m in (*t.dest, frame.means, *frame.instruments) if m is not None]
            if named:
                vessel = self.ground(named[0], "fill", g, clause, "place")
            else:
                kinds = [k for k in ("Kettle", "Pot") if self.g.has_type(k)]
                vessel = self.g.types_ref(kinds[:1] or ("Kettle",), "kettle")
                self.history.append(Mention(vessel, Head(text="kettle"), clause, g))
        return [self._draft([cond(P.filled, r, n, liquid="water"), cond(P.hot, r, n), *self._on_the_stove(r)], vessel)
                for r, n in vessel.groups]

    def _on_the_stove(self, vessel: ObjectRef) -> list[Condition]:
        """A pot, kettle or pan that boils or fries does it on a burner, and stays there
        (else a planner may heat it elsewhere and leave it in the sink)."""
        names = _names(vessel)
        if not self.g.has_type("StoveBurner") or not names or not all(x in STOVE_VESSELS for x in names):
            return []
        return [cond(P.inside, vessel, 1, ObjectRef(types=("StoveBurner",)))]

    def _place(self, frame: Frame, t: Target, g: int, clause: int,
               obj: Ref | None = None) -> list[Draft]:
        obj = obj if obj is not None else self.ground(t.head, "hold", g, clause)
        dest_heads = t.dest
        if t.prep == "under" and not any(
                set(d.noun.concept.types) & BREWERS for d in dest_heads if d.noun is not None):
            raise OfflineParseError("'under' cannot be stated as a goal (only in/on)",
                                    phrase=frame.text)      # "under the coffee maker" is in it
        if t.prep == "near":
            dest = self._beside(dest_heads[0], g, clause)
        else:
            refs = [self._dest_ref(d, obj, g, clause) for d in dest_heads]
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

    def _dest_ref(self, d: Head, obj: Ref, g: int, clause: int) -> Ref:
        """Where a placement goes; "it" is never the thing placed itself ("open the cabinet
        and put the bowl from the table in it": the cabinet, not the bowl)."""
        ref = self.ground(d, "receptacle", g, clause, "dest")
        moved = [obj.groups, *(m.ref.groups for m in self.history if m.clause == clause and m.role == "object")]
        if d.pron is None or ref.groups not in moved:
            return ref
        sources = {id(land) for m in self.history for prep, land in m.head.location if prep == "from"}
        other = next((m.ref for m in reversed(self.history) if m.ref.groups not in moved and m.head.pron is None
                      and m.head.noun is not None and m.head.noun.concept.kind not in ("room", "anything")
                      and id(m.head) not in sources and self.discourse.fits(m.ref, "receptacle")), None)
        return other if other is not None else ref

    def _beside(self, landmark: Head, g: int, clause: int) -> Ref:
        """"next to the bread": on whatever the bread is on."""
        ref = self.ground(landmark, None, g, clause, "place")
        places: list[str] = []
        for r, _ in ref.groups:
            for o in self.discourse.objects(r):
                parent = getattr(o, "parent", None)
                if parent is not None:
                    places.append(self.g.state.objects[parent].type)
                elif self.g.has_type("Floor") and not o.has("pickupable"):
                    places.append("Floor")      # "next to the toilet": on the floor by it
        if not places:
            raise GroundingError(f"cannot tell where {landmark.label()!r} stands",
                                 phrase=landmark.label())
        return self.g.types_ref(dict.fromkeys(places), f"beside {landmark.label()}")

    def _clean_act(self, frame: Frame, act: Act, t: Target, g: int, clause: int) -> list[Draft]:
        head = t.head
        in_sink = any(d.noun is not None and {"SinkBasin", "Sink"} & set(d.noun.concept.types) for d in t.dest)
        obj = self.ground(head, None, g, clause)
        dirtyable = [(r, n) for r, n in obj.groups if all(self.g.can(x, "dirty") for x in _names(r))]
        # "wash the cloth in the sink" when no such cloth is dirty: clean already holds, so
        # what is asked is the washing itself (in the sink under running water), as a goal
        already = [(r, n) for r, n in dirtyable if in_sink and not any(o.is_dirty for o in self.discourse.objects(r))]
        dirtyable = [(r, n) for r, n in dirtyable if (r, n) not in already]
        rest = [(r, n) for r, n in obj.groups if (r, n) not in dirtyable and (r, n) not in already]
        out: list[Draft] = []
        if dirtyable:
            out += self._each(P.clean, Ref(obj.label, tuple(dirtyable)))
        if already:
            basin, faucet = self._sink()
            out.append(self._draft([*(cond(P.inside, r, n, basin) for r, n in already),
                                    cond(P.switched_on, faucet)], obj))
        if rest and not all(self.g.can(x, "hold") for r, _ in rest for x in _names(r)):
            # "clean up the desk", "wipe the counter": not a state the goal can name, an
            # umbrella for whatever the other clauses say
            raise OfflineParseError(f"'clean {head.label()}' is too vague for the offline "
                                    "parser: say which objects to put where or wash",
                                    phrase=head.label(), vague=True)
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
                wanted = self._wanted(frame, Act.MAKE, t.head)
                plain = Target(replace(t.head, filters=[]), t.dest, t.prep)
                if t.head.contents is not None and t.head.noun is not None:
                    # "a cold glass of water": the glass filled, then as wished
                    out += self._one(frame, Act.FILL, plain, self._group, clause)
                    for st in wanted:
                        out += self._state(Frame(None, frame.verb, [plain]), st, False, clause)
                    if frame.recipient:
                        out += self._one(frame, Act.HOLD, plain, self._group, clause)
                    continue
                if wanted:
                    # "make me a boiled egg": the egg, cooked
                    for st in wanted:
                        out += self._state(Frame(None, frame.verb, [plain]), st, False, clause)
                    continue
                raise OfflineParseError(
                    f"'{frame.verb} {t.head.label()}' is too vague for the offline parser",
                    phrase=t.head.label(), vague=True)
            out += self._recipe(recipe, clause, t.head)
        return out

    def _recipe(self, recipe: str, clause: int, head: Head | None = None) -> list[Draft]:
        """The goal of a dish with a clear household reading; what it is served in (the
        mug of coffee, the toast slices, the egg) becomes the antecedent of "it"/"them"."""
        g = self.g
        if recipe == "toast":
            # toast is cooked bread slices: "two slices of toast" are two of them
            bread = g.types_ref(("Bread",), "bread")
            n = head.count if head is not None and head.count and not head.vague_count else 1
            if n > g.count_available("BreadSliced"):
                raise g.fail(f"{g.scene.floor_plan} cannot make {n} slices of toast", "toast")
            slices = Ref("toast", ((ObjectRef(types=("BreadSliced",)), n),), n > 1)
            self.history.append(Mention(slices, Head(text="toast", piece=True), clause, self._group))
            done = cond(P.cooked, ObjectRef(types=("BreadSliced",)), n) if n > 1 else \
                cond(P.cooked, bread.single())
            cooked = self._draft([done], bread)
            cooked.after = [0]
            return [self._draft([cond(P.sliced, bread.single())], bread), cooked]
        dish = DISHES[recipe]
        if dish.each_of:      # a salad: what the scene has of its ingredients
            refs = [g.types_ref((t,), t.lower()) for t in dish.each_of if g.has_type(t)]
            if not refs:
                raise GroundingError(f"{g.scene.floor_plan} has nothing to make a {recipe} with", phrase=recipe)
            return [self._draft(self._dish_goals(dish, ref), ref) for ref in refs]
        assert dish.served_in is not None
        word = split_camel(dish.served_in).lower()
        served = g.types_ref((dish.served_in,), word)
        if dish.needs_type is not None and not g.has_type(dish.needs_type):
            raise GroundingError(f"{g.scene.floor_plan} has no {split_camel(dish.needs_type).lower()}",
                                 phrase=recipe)
        self.history.append(Mention(served, Head(text=word), clause, self._group))
        return [self._draft(self._dish_goals(dish, served), served)]

    @staticmethod
    def _dish_goals(dish: Dish, ref: Ref) -> list[Condition]:
        return [cond(goal.predicate, ref.single(), liquid=goal.liquid) for goal in dish.conditions]

    def _pour(self, frame: Frame, targets: list[Target], clause: int) -> list[Draft]:
        out: list[Draft] = []
        liquid = frame.liquid
        for t in targets:
            liquid = t.head.liquid or t.head.contents or liquid
            for into in t.dest or ([t.head] if t.head.noun is not None else []):
                ref = self.ground(into, "fill", self._group, clause)
                out.append(self._draft([cond(P.filled, r, n, liquid=liquid or "water")
                                        for r, n in ref.groups], ref))
        return out


def then(first: list[Draft], second: list[Draft]) -> list[Draft]:
    """Two draft lists as one, each of the second after all of the first."""
    for d in second:
        d.after = [a + len(first) for a in d.after] + list(range(len(first)))
    return [*first, *second]


def concat(first: list[Draft], second: list[Draft]) -> list[Draft]:
    """Two draft lists as one; ``after`` indices of the second are shifted."""
    for d in second:
        d.after = [a + len(first) for a in d.after]
    return [*first, *second]


def _whole(ref: ObjectRef) -> ObjectRef:
    """A slice type reference as its whole ("toast" is cooked bread)."""
    if ref.id is not None:
        return ref
    cat = load_catalogue()
    return ObjectRef(types=tuple(dict.fromkeys(cat.source_type(t) or t for t in ref.types)))


#: states that "everything" can be brought to: off, closed (the opposite would switch on
#: every faucet and burner, open every cabinet: no household reading)
_ALL_OF = frozenset({(Stat.SWITCH, False), (Stat.OPEN, False)})


def _nothing_asked(frame: Frame, targets: list[Target]) -> bool:
    """"keep the apple", "have the bread": a causative verb with no wish, place, dish or
    drink asks nothing of its objects."""
    return not (frame.wish or frame.ready or frame.recipient or frame.verb == "get") and not any(
        t.dest or t.head.recipe or t.head.contents or (t.head.liquid and t.head.noun is None) for t in targets)


def _is_everything(head: Head) -> bool:
    """"everything", "all the things" without a place ("everything on the table" is the
    things there)."""
    return head.noun is not None and head.noun.concept.kind == "anything" and not head.location
