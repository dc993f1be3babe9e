"""The offline front end: the PFG's default, rule-based, no LLM calls."""

from __future__ import annotations

import logging
import re
from collections.abc import Callable, Sequence
from dataclasses import replace

from emboteam.pfg.offline import lexicon
from emboteam.pfg.offline.adjuncts import drop_time_adjuncts
from emboteam.pfg.offline.clauses import AND, THEN, Clause, segment
from emboteam.pfg.offline.consistency import check_consistent
from emboteam.pfg.offline.constructions import places_to_locations
from emboteam.pfg.offline.corrections import apply_corrections
from emboteam.pfg.offline.cues import candidate_frames, collect, is_statement
from emboteam.pfg.offline.decompose import assemble, refs_overlap
from emboteam.pfg.offline.errors import GroundingError, OfflineParseError
from emboteam.pfg.offline.frames import parse_clause
from emboteam.pfg.offline.grounding import Grounder
from emboteam.pfg.offline.morphology import warm_spelling
from emboteam.pfg.offline.phrases import Frame, Head, ParsedClause, Target, np_list, np_start
from emboteam.pfg.offline.semantics import Draft, Semantics, concat
from emboteam.pfg.offline.tagger import Item, tag
from emboteam.pfg.offline.text import normalize
from emboteam.pfg.reading import Reading, ReadingNote
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import ObjectRef, Predicate
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

_MAX_CHARS = 2000
log = logging.getLogger(__name__)


#: the offline parser's parse is a :class:`~emboteam.pfg.reading.Reading` (kept under
#: its old name for callers that import it)
ParseResult = Reading


def _note(exc: OfflineParseError) -> ReadingNote:
    """A skipped clause as the note the user sees: the span and why."""
    return ReadingNote(exc.phrase or "", exc.message, "vague" if exc.vague else "unread")


def _reread_after_prefix(clause: Clause, directive: bool) -> tuple[ParsedClause, str] | None:
    """The clause read from the first word after which the grammar finds an act or a
    state (a verb, or a noun phrase with its state: "the TV off"), and the words skipped;
    None when no suffix reads or the words to skip name an object (they are a statement
    about it, kept for pronouns, not noise)."""
    items = clause.items
    for k in range(1, len(items)):
        if items[k - 1].noun is not None and items[k - 1].corrected_from is None:
            return None    # "the remote, my watch and my keys keep going missing": objects
        if items[k].verb is None and not np_start(items[k]):
            continue
        rest = replace(clause, items=items[k:])
        parsed = parse_clause(rest, directive=directive)
        if any(f.act is not None or f.state is not None for f in parsed.frames):
            return parsed, " ".join(i.corrected_from or i.text for i in items[:k] if i.punct is None)
    return None


def _known_objects(items: list[Item]) -> list[Head] | None:
    """The noun phrases of a clause that is only noun phrases of known words ("the
    bread", "then the tomato"; not "wibble the tomato"), else None."""
    words = [i for i in items if i.punct is None]
    if not all(i.noun is not None or i.det or i.quant is not None or i.pron
               or i.number is not None or i.text in lexicon.COMMON_WORDS for i in words):
        return None
    # commas stay: they separate the phrases of a list ("keys, watch and the card")
    return np_list([i for i in items if i.punct in (None, ",")]) or np_list(words)


def _unread(clause: Clause, parsed: ParsedClause) -> bool:
    """Did a clause that gave no act say something the parser could not read? A statement
    ("my phone is on the bed", "there's a potato on the counter") introduces objects, and
    thanks and small talk carry no content words; "then wibble the tomato" does."""
    items = clause.items
    stated = is_statement(items)
    if parsed.means is not None or parsed.also or stated:
        return False
    if clause.link not in (AND, THEN) and not any(i.noun is not None for i in items):
        return False     # "if you have time", "before you leave": a circumstance
    if items and items[0].text in ("not", "instead", "rather", "except"):
        return False     # "not the apple", "instead of the cup": a rejected alternative
    if _known_objects(items):
        return False     # "The bread. Slice it.": a topic for what follows
    return bool(parsed.unknown) or any(i.verb is not None or i.noun is not None for i in clause.items)


def _unsure(spec: TaskSpec, doubts: set[ObjectRef]) -> tuple[str, ...]:
    """The spec's conditions that name a reference chosen with doubt."""
    out: list[str] = []
    for c in spec.goal().conditions:
        if (c.subject in doubts or c.receptacle in doubts) and str(c) not in out:
            out.append(str(c))
    return tuple(out)


def _vague_phrase(clause: Clause) -> str | None:
    """The chore of a clause that has no single household reading ("tidy up the
    kitchen", "set the table"), if any."""
    text = " ".join(i.text for i in clause.items)
    for pattern in lexicon.VAGUE_PHRASES:
        m = re.search(pattern, text)
        if m:
            return m.group(0)
    return None


#: acts that ask for nothing on their own ("I'd love it if ...", "when I get home")
_NO_REQUEST = frozenset({None, lexicon.Act.CAUSE, lexicon.Act.GO, lexicon.Act.MAKE})
#: a person's own doings under "when", "before", "if": "when I get home", "before you go"
#: are a time, not a request
_PERSON = frozenset({"i", "we", "you"})


#: verbs of a question that points something out ("see the box on the table?")
_POINTING = frozenset({"see", "notice", "spot", "remember", "know"})


#: acts a purpose infinitive asks of what was just placed ("put it on the hob to boil")
_PURPOSE_ACTS = frozenset({lexicon.Act.HEAT, lexicon.Act.COOK, lexicon.Act.COOL, lexicon.Act.CLEAN,
                           lexicon.Act.MICROWAVE, lexicon.Act.TOAST})


def _purpose_acts(clause: Clause, parsed: ParsedClause) -> None:
    """"put the kettle on the hob to boil", "pop the wine in the fridge to chill": the
    placement is for the act after "to", which is asked of the same objects."""
    items = clause.items
    placing = [f for f in parsed.frames if f.act in (lexicon.Act.PLACE, lexicon.Act.GO)]
    if not placing:
        return
    for k in range(len(items) - 1):
        verb = items[k + 1].verb
        if items[k].text == "to" and verb is not None and verb.sense.act in _PURPOSE_ACTS \
                and items[k + 1].noun is None and (k + 2 >= len(items) or not np_start(items[k + 2])
                                                   or items[k + 2].pron in ("it", "them")):
            heads = [t.head for f in placing for t in f.targets]
            parsed.frames.append(Frame(verb.sense.act, verb.lemma, [Target(h) for h in heads],
                                       text=clause.text))
            return


#: words that make "X should be in Y" a guess about where X is, not a wish
_WHEREABOUTS = frozenset({"somewhere", "probably", "presumably", "somewhere in", "anywhere"})


def _whereabouts(clause: Clause, parsed: ParsedClause) -> bool:
    """"The mug should be in a cabinet somewhere", "the remote must be on the sofa
    somewhere": a verbless placement with a word of guessing says where something is."""
    return any(i.text in _WHEREABOUTS for i in clause.items) and bool(parsed.frames) and all(
        f.act is lexicon.Act.PLACE and not f.verb for f in parsed.frames)


def _again_sequence(clause: Clause, parsed: ParsedClause) -> None:
    """"turn the tap on and off again": with "again" after it, "on and off" is a sequence
    that ends in the second state, not both at once."""
    words = [i.text for i in clause.items if i.punct is None]
    if not words or words[-1] != "again":
        return
    for f in parsed.frames:
        last: dict[int, Target] = {}
        for t in f.targets:
            last[id(t.head)] = t
        if len(last) < len(f.targets):
            f.targets = [t for t in f.targets if last[id(t.head)] is t]
            f.state = f.targets[-1].state or f.state
            if f.state is not None and f.state[0] is lexicon.Stat.SWITCH:
                f.act = lexicon.Act.SWITCH_ON if f.state[1] else lexicon.Act.SWITCH_OFF


def _pointing_question(clause: Clause, parsed: ParsedClause) -> bool:
    """Is the clause a question pointing at an object and where it is?"""
    words = [i.text for i in clause.items if i.punct is None]
    while words and words[0] in ("do", "did", "can", "you", "could"):
        words = words[1:]
    return bool(clause.extra.get("question")) and bool(words) and words[0] in _POINTING and \
        bool(parsed.frames) and all(f.act is lexicon.Act.PLACE for f in parsed.frames)


def _small_talk(clause: Clause) -> bool:
    """"Cheers love", "love you!", "you're a star": no object, no state, no pronoun to
    act on, and only verbs that ask for nothing by themselves."""
    items = clause.items
    if any(i.noun is not None or i.state is not None or i.pron is not None or i.liquid is not None
           or i.recipe is not None for i in items):
        return False
    verbs = [i.verb for i in items if i.verb is not None]
    return bool(verbs) and all(v.sense.act in _NO_REQUEST for v in verbs)


def _requests(p: ParsedClause) -> bool:
    return any(f.act not in _NO_REQUEST and not f.report and not f.wish for f in p.frames)


def condition_groups(clauses: list[Clause]) -> list[list[int]]:
    """The clauses of each "if": the "if" clause and the clauses it coordinates ("if the
    laptop were shut and the pillow were on the armchair")."""
    groups: list[list[int]] = []
    for k, c in enumerate(clauses):
        if c.link == "if":
            groups.append([k])
        elif groups and groups[-1][-1] == k - 1 and c.link == AND and c.sentence == clauses[k - 1].sentence \
                and not (c.items and c.items[0].verb is not None):
            groups[-1].append(k)
    return groups


def _drop_conditions(clauses: list[Clause], parsed: list[ParsedClause]) -> set[int]:
    """"If the fridge is open, close it": a state under "if" is the condition of an act
    of its sentence, not a goal (its objects stay for the pronouns). Without such an act
    the "if" clauses are what is wished ("I'd appreciate it if the laptop were closed").
    "When I get home": the speaker's own doings under a subordinator are a time. Returns
    the clauses that were read this way (no note for them)."""
    silent: set[int] = set()
    for k, (c, p) in enumerate(zip(clauses, parsed, strict=True)):
        if c.link not in (AND, THEN, "purpose") and c.items and c.items[0].text in _PERSON \
                and all(f.act in _NO_REQUEST and f.state is None for f in p.frames) \
                and not any(h.noun is not None and h.noun.concept.kind not in ("room", "anything")
                            for h in p.mentions):
            parsed[k] = replace(p, frames=[])
            silent.add(k)
    for group in condition_groups(clauses):
        if any(_requests(parsed[k]) for k in group):
            continue
        sentence = clauses[group[0]].sentence
        acted = any(clauses[j].sentence == sentence and j not in group and _requests(parsed[j])
                    for j in range(len(clauses)))
        for k in group:
            if acted:
                parsed[k] = replace(parsed[k], frames=[])
            elif any(f.report for f in parsed[k].frames):
                # "... and the pillow were on the armchair": wished, as the "if" is
                parsed[k] = parse_clause(clauses[k], directive=True)
        if not acted:
            for j, c in enumerate(clauses):
                # "I'd love it if ...": the "it" is what the "if" says, nothing of its own
                if c.sentence == sentence and j not in group and parsed[j].frames and all(
                        f.act in _NO_REQUEST and all(t.head.pron is not None for t in f.targets)
                        for f in parsed[j].frames):
                    parsed[j] = replace(parsed[j], frames=[], mentions=[])
                    silent.add(j)
    return silent


def _labelled_lists(clauses: list[Clause], parsed: list[ParsedClause]) -> set[int]:
    """"Bed: pillow and teddy. Desk: book and laptop.", "Things for the box: the pen and
    the pencil.": a place before a colon, then only objects, puts them there. Returns the
    label clauses (read, no note)."""
    labels: set[int] = set()
    for k in range(len(clauses) - 1):
        c, nxt = clauses[k], clauses[k + 1]
        # "things for the desk" reads as a placement that lacks its place
        placing = all(f.act is lexicon.Act.PLACE and not any(t.dest for t in f.targets)
                      for f in parsed[k].frames)
        if not c.extra.get("colon") or not placing or parsed[k + 1].frames \
                or nxt.sentence != c.sentence + 1:
            continue
        label = [h for h in parsed[k].mentions if h.noun is not None] or _known_objects(c.items)
        if not label:
            continue
        place = label[-1]
        heads = _known_objects(nxt.items)
        if place.noun is None or not heads or any(h.noun is None for h in heads):
            continue
        place.role = "dest"
        parsed[k].frames = []
        parsed[k + 1].frames = [Frame(lexicon.Act.PLACE, "put", [Target(h, [place], "in") for h in heads],
                                      text=nxt.text)]
        labels.add(k)
    return labels


def _attach_means(parsed: list[ParsedClause]) -> None:
    """"cook the potato, the microwave is fine", "the stove is fine - fry the egg": a
    clause that only names an appliance gives the means of the act next to it (the one
    before, else the one after)."""
    for k, p in enumerate(parsed):
        if p.means is None:
            continue
        for other in (parsed[k - 1] if k > 0 else None, parsed[k + 1] if k + 1 < len(parsed) else None):
            if other is not None and other.frames:
                for f in other.frames:
                    f.means = f.means or p.means
                break


#: acts whose object may be left out on purpose ("dim", "water" the plants, "go")
_NO_OBJECT_ACTS = frozenset({lexicon.Act.DIM, lexicon.Act.BRIGHTEN, lexicon.Act.WATER,
                             lexicon.Act.GO, lexicon.Act.MAKE, lexicon.Act.VAGUE})


def _share_objects(clauses: list[Clause], parsed: list[ParsedClause]) -> None:
    """"open and close the fridge", "wash and dry the mug": a verb without an object,
    coordinated with the next clause of its sentence, shares that clause's objects."""
    for k in range(len(parsed) - 1):
        p, nxt = parsed[k], parsed[k + 1]
        if clauses[k + 1].sentence != clauses[k].sentence or clauses[k + 1].link != "and" \
                or len(p.frames) != 1 or not nxt.frames or not nxt.frames[0].targets:
            continue
        frame = p.frames[0]
        if frame.targets or frame.act is None or frame.act in _NO_OBJECT_ACTS or frame.report:
            continue
        frame.targets = [Target(t.head, [], None) for t in nxt.frames[0].targets]


def _elided_participle(clause: Clause, before: ParsedClause | None) -> list[Frame]:
    """"I'd like my mug washed and then filled with water": a clause that is only a
    state participle asks that state of the objects of the clause before it."""
    words = [i for i in clause.items if i.punct is None and i.text not in lexicon.FILLER_WORDS]
    if before is None or not before.frames or not words or words[0].state is None \
            or words[0].verb is None or words[0].verb.form != "ed" or words[0].noun is not None or before.clause.sentence != clause.sentence \
            or any(np_start(i) and i.liquid is None for i in words[1:]):
        return []
    targets = [t for f in before.frames for t in f.targets if t.head.noun is not None or t.head.pron]
    if not targets:
        return []
    liquid = next((i.liquid for i in words if i.liquid is not None), None)
    return [Frame(lexicon.Act.CAUSE, "get", [Target(t.head) for t in targets], state=words[0].state,
                  liquid=liquid, text=clause.text)]


def _gapped_objects(clauses: list[Clause], parsed: list[ParsedClause]) -> None:
    """"Put the apple in the fridge, then the tomato" (". Then the tomato."): a clause that
    is only objects, sequenced right after an act, has that act (gapping)."""
    for k in range(1, len(parsed)):
        p, c = parsed[k], clauses[k]
        if p.frames or p.also or c.link != THEN or not parsed[k - 1].frames:
            continue
        heads = _known_objects(p.clause.items)
        if heads and all(h.noun is not None for h in heads):
            p.also = heads


def _repeat_for_also(parsed: list[ParsedClause]) -> None:
    """"Put the apple in the fridge. Oh, and the tomato too.": the act of the clause
    before, with its place, on the new objects."""
    for k, p in enumerate(parsed):
        if not p.also or p.frames or k == 0:
            continue
        before = next((q for q in reversed(parsed[:k]) if q.frames), None)
        if before is None:
            continue
        last = before.frames[-1]
        model = last.targets[-1] if last.targets else Target(Head())
        p.frames = [replace(last, targets=[Target(h, list(model.dest), model.prep) for h in p.also],
                            instruments=list(last.instruments), room_states=[])]


#: what a later act brings about: a wished state it makes true needs no subtask of its own
_FULFILS: dict[Predicate, frozenset[Predicate]] = {
    Predicate.hot: frozenset({Predicate.hot, Predicate.cooked}),
    Predicate.cold: frozenset({Predicate.cold}),
    Predicate.cooked: frozenset({Predicate.cooked}),
    Predicate.clean: frozenset({Predicate.clean}),
    Predicate.filled: frozenset({Predicate.filled}),
}


def _drop_drafts(drafts: dict[int, list[Draft]], gone_of: Callable[[int, Draft], bool]) -> None:
    """Remove the drafts ``gone_of(clause, draft)`` picks, keeping the others' order
    (their ``after`` indices renumbered)."""
    for ci in sorted(drafts):
        gone = {k for k, d in enumerate(drafts[ci]) if gone_of(ci, d)}
        if not gone:
            continue
        kept = [k for k in range(len(drafts[ci])) if k not in gone]
        index = {old: new for new, old in enumerate(kept)}
        out = []
        for k in kept:
            d = drafts[ci][k]
            d.after = [index[a] for a in d.after if a in index]
            out.append(d)
        if out:
            drafts[ci] = out
        else:
            del drafts[ci]


def _drop_fulfilled_wishes(drafts: dict[int, list[Draft]]) -> None:
    """"I'd love a warm slice of bread - toast some for me": the wish introduces what a
    later clause says how to make; toasting makes it warm (cooking heats), so the wish adds
    no subtask of its own."""
    def fulfilled(ci: int, d: Draft) -> bool:
        later = [c for cj, ds in drafts.items() if cj > ci for e in ds if not e.wished
                 for c in e.conditions]
        return d.wished and all(any(c2.predicate in _FULFILS.get(c.predicate, frozenset())
                                    and refs_overlap(c.subject, c2.subject) for c2 in later)
                                for c in d.conditions)
    _drop_drafts(drafts, fulfilled)


def _drop_superseded_placements(drafts: dict[int, list[Draft]], grounder: Grounder) -> None:
    """"Pick the pillow and the paper up - pillow on the sofa, paper on the coffee table":
    an object placed twice ends where it is placed last; the earlier placement of one
    object (an id, or a kind the scene has one of) is no goal (both cannot hold at the
    end). "The toilet paper on the holder, the spare roll on the shelf" is two rolls."""
    order = [(ci, k, d) for ci in sorted(drafts) for k, d in enumerate(drafts[ci])]

    def one_object(ref: ObjectRef) -> bool:
        return ref.id is not None or sum(len(grounder.instances(t)) for t in ref.types) == 1

    def superseded(ci: int, d: Draft) -> bool:
        if d.intermediate or not d.conditions or any(
                c.predicate is not Predicate.inside or c.count != 1 or not one_object(c.subject)
                for c in d.conditions):
            return False
        at = next(i for i, (_, _, e) in enumerate(order) if e is d)
        later = [c for _, _, e in order[at + 1:] if not e.intermediate for c in e.conditions
                 if c.predicate is Predicate.inside]
        return all(any(refs_overlap(c.subject, c2.subject) and c2.receptacle != c.receptacle
                       for c2 in later) for c in d.conditions)
    _drop_drafts(drafts, superseded)


def _drop_holds_before_placing(drafts: dict[int, list[Draft]]) -> None:
    """"Take the sponge and the towels out of the cupboard and put them on the counter":
    holding is how they get there, not a goal of its own (and two things held "at once"
    would ask for two free hands)."""
    placed = [(ci, k, c) for ci, ds in drafts.items() for k, d in enumerate(ds) for c in d.conditions
              if c.predicate is Predicate.inside]

    def before_placing(ci: int, d: Draft) -> bool:
        return bool(d.conditions) and all(
            c.predicate is Predicate.held and any(
                cj >= ci and refs_overlap(c.subject, p.subject) for cj, _, p in placed)
            for c in d.conditions)
    _drop_drafts(drafts, before_placing)


def _cue_mentions(clause: Clause) -> list[Head]:
    """The noun phrases of a clause the grammar found none in ("where's the pot?")."""
    cues = collect(clause.items)
    return [*cues.objects, *(h for _, h in cues.places)]


def _read_cues(clause: Clause, semantics: Semantics, ci: int) -> list[Draft]:
    """The drafts of a clause read from its cue words (:mod:`~emboteam.pfg.offline.cues`):
    the first candidate of each kind that the scene grounds, no placement beside an act
    that already places."""
    out: list[Draft] = []
    kinds: set[str] = set()
    for kind, frame in candidate_frames(clause):
        if kind in kinds or (kind == "place" and "places" in kinds):
            continue
        try:
            got = semantics.frame(frame, ci)
        except OfflineParseError:
            continue
        if got:
            out = concat(out, got)
            kinds.add(kind)
            if frame.act in (lexicon.Act.PLACE, lexicon.Act.TRASH):
                kinds.add("places")
    return out


class OfflineFrontend:
    """Rule-based semantic parser: instruction -> TaskSpec, deterministic and offline.

    Pipeline: :func:`~emboteam.pfg.offline.tagger.tag` (normalise, correct typos, find
    multi-word nouns) -> :func:`~emboteam.pfg.offline.clauses.segment` (clauses and how
    they are ordered) -> :func:`~emboteam.pfg.offline.frames.parse_clause` (act, objects,
    places, states) -> :class:`~emboteam.pfg.offline.semantics.Semantics` (grounded goal
    conditions, pronouns) -> :func:`~emboteam.pfg.offline.decompose.assemble`
    (dependencies, robots, intermediate steps).

    What cannot be read never sinks the instruction: a clause too vague to act on ("tidy
    up the kitchen"), an object that names nothing in the scene, an act or a clause the
    grammar cannot read is skipped with a note (:class:`~emboteam.pfg.reading.ReadingNote`)
    when something else can be read; only an instruction with nothing actionable is an
    :class:`OfflineParseError`. Opposite states asked at once ("open and close the
    fridge") are a :class:`~emboteam.pfg.offline.consistency.ContradictoryInstruction`.
    """

    name = "offline"

    def __init__(self) -> None:
        # build the lexicon and the spelling index now (about 0.1 s, once per process), so
        # that every instruction parses in milliseconds
        lexicon.nouns()
        lexicon.vocabulary()
        warm_spelling()

    def decompose(self, instruction: str, scene: Scene, state: WorldState,
                  team: Sequence[RobotProfile]) -> TaskSpec:
        return self.parse(instruction, scene, state, team).spec

    def parse(self, instruction: str, scene: Scene, state: WorldState,
              team: Sequence[RobotProfile]) -> Reading:
        """The TaskSpec, a note per span that was skipped (also logged at INFO) and the
        conditions chosen with doubt."""
        text = instruction.strip()
        if not text:
            raise OfflineParseError("empty instruction")
        if len(text) > _MAX_CHARS:
            raise OfflineParseError(f"instruction too long ({len(text)} characters, at most "
                                    f"{_MAX_CHARS})")
        clauses = segment(drop_time_adjuncts(apply_corrections(tag(text))))
        semantics = Semantics(Grounder(scene, state))
        drafts: dict[int, list[Draft]] = {}
        unknown: list[str] = []
        skipped: list[OfflineParseError] = []
        failed: list[OfflineParseError] = []
        unread: list[ReadingNote] = []
        guessed: set[int] = set()       # clauses read without their unreadable first words
        verbs_seen = False
        parsed_clauses: list[ParsedClause] = []
        chat: set[int] = set()          # small talk: no note
        for k, c in enumerate(clauses):
            # "make sure the fridge is closed, the stove is off": the wish reaches over the
            # comma to the next statement of the same sentence
            before = parsed_clauses[-1] if parsed_clauses else None
            inherit = before is not None and before.directive and clauses[k - 1].sentence == \
                c.sentence and c.link == "and"
            parsed = parse_clause(c, directive=inherit)
            dropped: str | None = None
            if _small_talk(c):
                parsed = replace(parsed, frames=[])
                chat.add(k)
            elif not parsed.frames and (elided := _elided_participle(c, before)):
                parsed = replace(parsed, frames=elided)
            elif not parsed.frames and _unread(c, parsed):
                # "I reckon you should chuck the egg in the bin", "swap the TV off": read
                # from the first place the grammar can read, the words before it are a note
                # and what it gives is unsure
                reread = _reread_after_prefix(c, inherit)
                if reread is not None:
                    parsed, dropped = reread
            if _pointing_question(c, parsed) or _whereabouts(c, parsed):
                # "(do you) see the box on the coffee table?": where the box is, for what
                # follows, not a request
                for f in parsed.frames:
                    places_to_locations(f)
                parsed = replace(parsed, frames=[])
                chat.add(k)
            elif dropped is not None:
                guessed.add(k)
                unread.append(ReadingNote(dropped, "not understood; read the rest of the clause without it"))
            _purpose_acts(c, parsed)
            _again_sequence(c, parsed)
            parsed_clauses.append(parsed)
        silent = _drop_conditions(clauses, parsed_clauses) | chat
        silent |= _labelled_lists(clauses, parsed_clauses)
        _attach_means(parsed_clauses)
        _share_objects(clauses, parsed_clauses)
        _gapped_objects(clauses, parsed_clauses)
        _repeat_for_also(parsed_clauses)
        for ci, (clause, parsed) in enumerate(zip(clauses, parsed_clauses, strict=True)):
            chore = _vague_phrase(clause)
            if chore is not None:
                for h in parsed.mentions:
                    semantics.note(h, ci)
                skipped.append(OfflineParseError(
                    f"{chore!r} is too vague for the offline parser: say which objects go "
                    "where or what to do with them (e.g. 'put the plate on the table')",
                    phrase=chore, vague=True))
                continue
            if not parsed.frames:
                if ci not in silent and _unread(clause, parsed):
                    cued = _read_cues(clause, semantics, ci)
                    if cued:
                        drafts[ci] = cued
                        guessed.add(ci)
                        unread.append(ReadingNote(clause.text, "read from its key words: the "
                                                  "sentence's structure was not understood", "assumed"))
                        continue
                    unread.append(ReadingNote(clause.text, "no act or wished state found in it"))
                # "keys, watch and the credit card - pop all three in the box": a clause of
                # noun phrases names every one of them ("watch" is no verb here)
                for h in _known_objects(clause.items) or parsed.mentions or _cue_mentions(clause):
                    semantics.note(h, ci)
                unknown.extend(parsed.unknown)
                continue
            out: list[Draft] = []
            failed_before = len(failed)
            for frame in parsed.frames:
                verbs_seen = True
                try:
                    out = concat(out, semantics.frame(frame, ci))
                except OfflineParseError as exc:
                    # "when you get a chance": small talk; "dim things", "tidy up": too
                    # vague, maybe said better by another clause; anything else that cannot
                    # be read is skipped with a note when another act can be
                    (skipped if frame.weak or exc.vague else failed).append(exc)
                    continue
            grounding = [e for e in failed[failed_before:] if isinstance(e, GroundingError) and not e.vague]
            if not out and not grounding and (len(failed) > failed_before or not any(
                    f.report or f.negated or f.past for f in parsed.frames)):
                # the clause's shape was not understood (an object that is not in the
                # scene is no reason to read it another way)
                out = _read_cues(clause, semantics, ci)
                if out:
                    guessed.add(ci)
                    unread.append(ReadingNote(clause.text, "read from its key words: the "
                                              "sentence's structure was not understood", "assumed"))
            if out:
                drafts[ci] = out
                continue
            for h in parsed.mentions:      # "the book doesn't belong on the sofa; it ..."
                semantics.note(h, ci)
            if not any(f.act is not None or f.state is not None for f in parsed.frames):
                unknown.extend(parsed.unknown)
        _drop_fulfilled_wishes(drafts)
        _drop_holds_before_placing(drafts)
        _drop_superseded_placements(drafts, semantics.g)
        if not drafts:
            if failed:
                raise failed[0]
            self._nothing_actionable(text, scene.floor_plan, semantics, unknown, skipped,
                                     verbs_seen)
        notes = (*(_note(e) for e in [*skipped, *failed, *semantics.skipped]), *unread)
        for note in notes:
            log.info("offline parser: %s", note)
        check_consistent(clauses, drafts)
        spec = assemble(text, clauses, drafts, team)
        unsure = _unsure(spec, semantics.g.doubts)
        unsure += tuple(dict.fromkeys(str(c) for ci in sorted(guessed) for d in drafts.get(ci, [])
                                      for c in d.conditions if str(c) not in unsure))
        return Reading(spec, notes, unsure)

    @staticmethod
    def _nothing_actionable(text: str, floor_plan: str, semantics: Semantics,
                            unknown: list[str], skipped: list[OfflineParseError],
                            verbs_seen: bool) -> None:
        """Raise the error that best explains why no clause gave a goal."""
        vague = [w for w in normalize(text).split() if w in lexicon.VAGUE_NOUNS]
        if skipped and any(e.vague for e in skipped):
            raise next(e for e in skipped if e.vague)
        if vague and not unknown:
            raise OfflineParseError(
                f"{text!r} is too vague for the offline parser ({vague[0]!r} has no single "
                "household reading): say which objects to act on, e.g. 'cook the potato'",
                phrase=vague[0], vague=True)
        if skipped:
            raise skipped[0]     # "I'd love five slices of toast": why the wish failed
        if unknown and verbs_seen:
            word = unknown[0]
            raise GroundingError(f"{word!r} names nothing in {floor_plan}", phrase=word,
                                 suggestions=lambda: semantics.g.suggestions(word))
        what = "no goal could be read from it" if verbs_seen else "no action found in it"
        raise OfflineParseError(
            f"cannot understand {text!r}: {what} (try e.g. 'put the apple in the fridge', "
            "'slice the bread', 'turn off the lights')", phrase=text)
