"""The offline front end: the PFG's default, rule-based, no LLM calls."""

from __future__ import annotations

import logging
import re
from collections.abc import Sequence
from dataclasses import replace

from pydantic import ValidationError

from emboteam.pfg.candidates import Doubt
from emboteam.pfg.offline import lexicon
from emboteam.pfg.offline.adjuncts import drop_time_adjuncts
from emboteam.pfg.offline.clause_passes import (
    again_sequence,
    attach_means,
    drop_conditions,
    elided_participle,
    elided_place,
    elided_state,
    fix_up_complaints,
    gapped_objects,
    known_objects,
    labelled_lists,
    own_future,
    pointing_question,
    purpose_acts,
    reasons,
    repeat_for_also,
    share_objects,
    small_talk,
    told_ahead,
    whereabouts,
)
from emboteam.pfg.offline.clauses import AND, THEN, Clause, segment
from emboteam.pfg.offline.consistency import (
    ContradictoryInstruction,
    check_consistent,
    narrow_choices,
    narrow_contrasts,
)
from emboteam.pfg.offline.constructions import (
    commaless_lists,
    object_first,
    parts_as_places,
    places_to_locations,
)
from emboteam.pfg.offline.corrections import Corrected, correct
from emboteam.pfg.offline.cues import cue_mentions, is_statement, read_cues
from emboteam.pfg.offline.decompose import assemble
from emboteam.pfg.offline.described import name_described, warm_described
from emboteam.pfg.offline.doubts.choose import choices, from_mentions_choices
from emboteam.pfg.offline.doubts.contradiction import settle as settle_contradictions
from emboteam.pfg.offline.doubts.contradiction import settle_placements
from emboteam.pfg.offline.doubts.mention_words import being
from emboteam.pfg.offline.doubts.priors import Priors
from emboteam.pfg.offline.doubts.sound_alike import warm_sound_alike
from emboteam.pfg.offline.draft_passes import (
    drop_fulfilled_wishes,
    drop_guessed_water,
    drop_holds_before_placing,
    drop_impossible,
    drop_self_placements,
    drop_superseded_placements,
)
from emboteam.pfg.offline.errors import GroundingError, IncapableError, OfflineParseError
from emboteam.pfg.offline.force import warm_force
from emboteam.pfg.offline.frames import parse_clause
from emboteam.pfg.offline.grounding import Grounder
from emboteam.pfg.offline.idioms import warm_idioms
from emboteam.pfg.offline.knowledge import word_tables
from emboteam.pfg.offline.list_positions import (
    EARLIER_LIST,
    earlier_list_reading,
    has_references,
    resolve_list_positions,
)
from emboteam.pfg.offline.morphology import warm_spelling
from emboteam.pfg.offline.page import warm_page
from emboteam.pfg.offline.patterns import pattern_tables
from emboteam.pfg.offline.phrases import ParsedClause, np_start
from emboteam.pfg.offline.retractions import retract
from emboteam.pfg.offline.semantics import Draft, Semantics, concat
from emboteam.pfg.offline.start_conditions import conditionals
from emboteam.pfg.offline.start_conditions import settle as settle_start_conditions
from emboteam.pfg.offline.surface import KIND as SURFACE
from emboteam.pfg.offline.surface import Surface, read_surface, warm_surface
from emboteam.pfg.offline.tagger import Item, tag
from emboteam.pfg.offline.text import normalize
from emboteam.pfg.reading import Reading, ReadingNote
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.goals import Condition, ObjectRef
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

_MAX_CHARS = 2000
log = logging.getLogger(__name__)


_W = word_tables("frontend")
_PRONOUN_SUBJECT, _SUBJECT_PRONOUN, _REJECTED = (pattern_tables("frontend").pattern(name) for name in (
    "pronoun_subject", "subject_pronoun", "rejected"))
#: a prefix of only these is the person's own words ("(when) you have got the egg out"),
#: nothing left unread
_PERSON_WORDS = _W.set("person_words")


def _tag(text: str) -> list[Item]:
    """The words tagged, a position in the speaker's own list read as the items it picks."""
    return resolve_list_positions(tag(text))


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
    if _REJECTED.at(items):
        return False     # "not the apple", "instead of the cup": a rejected alternative
    if known_objects(items):
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


def _with_candidates(reading: Reading, items: list[Item], scene: Scene, state: WorldState,
                     team: Sequence[RobotProfile], semantics: Semantics, priors: Priors | None,
                     surface: Sequence[tuple[str, str, tuple[Condition, ...]]] = (),
                     corrections: Sequence[tuple[str, str, tuple[Condition, ...]]] = (),
                     extra: Sequence[Doubt] = ()) -> Reading:
    """The reading with its ranked candidates (:mod:`.doubts`): the best one's spec, an
    list of the mentions nothing explains, and the conditions a close
    alternative would change marked unsure."""
    found = choices(reading.spec, items, scene, state, team, semantics.history, priors, surface, corrections,
                    extra)
    best = found.candidates[0]
    notes = reading.notes
    unsure = reading.unsure
    if not best.as_read:
        notes += (ReadingNote(", ".join(r.span for r in best.resolves), "read as: " + "; ".join(
            r.how for r in best.resolves), "assumed"),)
        unsure += tuple(str(c) for c in best.goals if str(c) not in unsure and c not in reading.spec.goal().conditions)
    noted = " ".join(n.span for n in notes if n.kind == "vague")    # "make the bed": the bed is the chore's
    unexplained = tuple(w for w in found.unexplained if w not in noted)
    return replace(reading, spec=best.spec, notes=notes, unsure=unsure, candidates=found.candidates,
                   unexplained=unexplained, doubts=found.doubts)


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

    def __init__(self, priors: Priors | None = None) -> None:
        #: the ranker's priors (None: the shipped ``doubts/priors.json``)
        self.priors = priors
        # build the lexicon, the spelling index and the rule tables now (about 0.3 s, once
        # per process), so that every instruction parses in milliseconds, the first too
        lexicon.nouns()
        lexicon.vocabulary()
        warm_spelling()
        warm_surface()
        warm_force()
        warm_page()
        warm_idioms()
        warm_sound_alike()
        warm_described()

    def decompose(self, instruction: str, scene: Scene, state: WorldState,
                  team: Sequence[RobotProfile]) -> TaskSpec:
        return self.parse(instruction, scene, state, team).spec

    def parse(self, instruction: str, scene: Scene, state: WorldState,
              team: Sequence[RobotProfile]) -> Reading:
        """The TaskSpec, a note per span that was skipped (also logged at INFO) and the
        conditions chosen with doubt."""
        try:
            return self._parse(instruction, scene, state, team)
        except ValidationError as exc:
            # a condition the reader put together that no goal can hold (a count of zero):
            # the reader's own error, typed, never a crash of the caller's run
            raise OfflineParseError(f"the instruction reads as a goal that cannot hold: "
                                    f"{exc.errors()[0].get('msg', exc)}") from exc

    def _parse(self, instruction: str, scene: Scene, state: WorldState,
               team: Sequence[RobotProfile]) -> Reading:
        text = instruction.strip()
        if not text:
            raise OfflineParseError("empty instruction")
        if len(text) > _MAX_CHARS:
            raise OfflineParseError(f"instruction too long ({len(text)} characters, at most "
                                    f"{_MAX_CHARS})")
        # "the thing you boil water in": named for this scene's types before anything reads it
        surface = read_surface(name_described(text, scene.types()), scene.types())
        said = tag(surface.text)
        # the other list a position may refer to is read only when a word may be one: the
        # second tagging and reading cost a millisecond an instruction
        positions = has_references(said)
        # as said, self-corrections and all: what the points of doubt read; a request undone
        # whole ("... [beep] undo") was taken back, not said (:mod:`.retractions`)
        tagged = retract(resolve_list_positions(said))
        try:
            alternatives = self._surface_readings(text, surface, scene, state, team)
            if positions:
                alternatives |= self._earlier_list_reading(text, surface.text, scene, state, team)
            return self._surfaced(self._read(text, tagged, scene, state, team, alternatives), alternatives)
        except ContradictoryInstruction:
            raise
        except OfflineParseError as exc:
            if surface.alternative is not None:
                try:
                    return self._read(text, _tag(surface.alternative), scene, state, team)
                except OfflineParseError:
                    pass
            if surface.text != text:
                try:
                    return self._read(text, _tag(text), scene, state, team)
                except OfflineParseError:
                    pass
            # "the pineapple", "two bottles" (only one): what the scene lacks stands, unless
            # the words' structure reads it ("everything on the dresser except ..."); a person
            # or an animal a ramble names ("my brother") is chatter, not a missing thing
            words_only = isinstance(exc, GroundingError) and not isinstance(exc, IncapableError) \
                and not being(exc.phrase)
            found = from_mentions_choices(text, tagged, scene, state, team, self.priors, words_only)
            if found is None:
                raise
            spec, made = found
            note = ReadingNote(text, f"read from the things it names ({exc.message})", "assumed")
            unsure = tuple(str(c) for c in spec.goal().conditions)
            return Reading(spec, (note,), unsure, candidates=made.candidates, doubts=made.doubts)

    def _surface_readings(self, text: str, surface: Surface, scene: Scene, state: WorldState,
                          team: Sequence[RobotProfile]) -> dict[str, tuple[str, Reading]]:
        """The reading of the surface's alternative text (:mod:`.surface`: a misheard
        "in", a split name that only sounds like a thing, a transcript's clause breaks),
        read only when a guess fired (a re-read costs a reading)."""
        if surface.alternative is None:
            return {}
        try:
            read = self._read(text, _tag(surface.alternative), scene, state, team, candidates=False)
        except OfflineParseError:
            return {}
        return {surface.label: (surface.alternative, read)}

    def _earlier_list_reading(self, text: str, said: str, scene: Scene, state: WorldState,
                              team: Sequence[RobotProfile]) -> dict[str, tuple[str, Reading]]:
        """The reading with a position in a list ("the first") resolved to the list named
        before the latest one, when it fits both (:mod:`.list_positions`): a point of doubt."""
        items = earlier_list_reading(tag(said))
        if items is None:
            return {}
        try:
            read = self._read(text, items, scene, state, team, candidates=False)
        except OfflineParseError:
            return {}
        return {EARLIER_LIST: (" ".join(i.text for i in items), read)}

    @staticmethod
    def _surfaced(reading: Reading, alternatives: dict[str, tuple[str, Reading]]) -> Reading:
        """The reading, its spec the alternative text's own when the ranker put that first
        (its subtasks keep their order and dependencies)."""
        best = reading.candidates[0] if reading.candidates else None
        if best is None or not any(r.kind == SURFACE for r in best.resolves):
            return reading
        for _, alt in alternatives.values():
            if set(alt.spec.goal().conditions) == set(best.goals):
                return replace(reading, spec=alt.spec)
        return reading

    def _read(self, text: str, tagged: list[Item], scene: Scene, state: WorldState,
              team: Sequence[RobotProfile], alternatives: dict[str, tuple[str, Reading]] | None = None,
              candidates: bool = True) -> Reading:
        """The grammar's reading of the words as corrected (:mod:`.corrections`), with the
        other readings of a correction whose slot is in doubt among its candidates; when
        the first reading finds nothing to act on, the first other reading that does."""
        fixed = correct(tagged, alternatives=True)
        try:
            reading = self._read_items(text, tagged, fixed.items, scene, state, team, alternatives, candidates,
                                       self._corrections(text, tagged, fixed, scene, state, team, candidates))
        except ContradictoryInstruction:
            raise
        except OfflineParseError:
            for _, _, items in fixed.alternatives:
                try:
                    return self._read_items(text, tagged, items, scene, state, team, alternatives, candidates)
                except OfflineParseError:
                    continue
            raise
        return reading

    def _corrections(self, text: str, tagged: list[Item], fixed: Corrected, scene: Scene, state: WorldState,
                     team: Sequence[RobotProfile], candidates: bool) -> list[tuple[str, str, tuple[Condition, ...]]]:
        """The goal of each other reading of a self-correction (label, how, goal)."""
        out: list[tuple[str, str, tuple[Condition, ...]]] = []
        for label, how, items in fixed.alternatives if candidates else ():
            try:
                read = self._read_items(text, tagged, items, scene, state, team, candidates=False)
            except OfflineParseError:
                continue
            out.append((label, how, tuple(read.spec.goal().conditions)))
        return out

    def _read_items(self, text: str, tagged: list[Item], corrected: list[Item], scene: Scene, state: WorldState,
                    team: Sequence[RobotProfile], alternatives: dict[str, tuple[str, Reading]] | None = None,
                    candidates: bool = True,
                    corrections: Sequence[tuple[str, str, tuple[Condition, ...]]] = ()) -> Reading:
        """The grammar's reading of ``corrected`` (raises when it finds nothing to act on);
        with its ranked candidates, the ``alternatives`` (readings of the surface's guesses)
        and ``corrections`` among them, unless ``candidates`` is False."""
        items = object_first(commaless_lists(parts_as_places(drop_time_adjuncts(corrected))))
        clauses = segment(items)
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
            if small_talk(c):
                parsed = replace(parsed, frames=[])
                chat.add(k)
            elif not parsed.frames and (elided := elided_participle(c, before) or elided_state(c, before)
                                        or elided_place(c, before)):
                parsed = replace(parsed, frames=elided)
            elif not parsed.frames and _unread(c, parsed) and not own_future(c) and not (
                    k > 0 and clauses[k - 1].extra.get("colon") and c.items and c.items[0].prep is not None):
                # (a place after a label's colon is the label's: clause_passes.labelled_lists)
                # "I reckon you should chuck the egg in the bin", "swap the TV off": read
                # from the first place the grammar can read, the words before it are a note
                # and what it gives is unsure
                reread = _reread_after_prefix(c, inherit)
                if reread is not None:
                    parsed, dropped = reread
            if pointing_question(c, parsed) or whereabouts(c, parsed):
                # "(do you) see the box on the coffee table?": where the box is, for what
                # follows, not a request
                for f in parsed.frames:
                    places_to_locations(f)
                parsed = replace(parsed, frames=[])
                chat.add(k)
            elif dropped is not None and not set(dropped.split()) <= _PERSON_WORDS:
                guessed.add(k)
                unread.append(ReadingNote(dropped, "not understood; read the rest of the clause without it"))
            purpose_acts(c, parsed)
            again_sequence(c, parsed)
            parsed_clauses.append(parsed)
        start_conds = conditionals(clauses, parsed_clauses)
        silent = drop_conditions(clauses, parsed_clauses) | chat
        silent |= labelled_lists(clauses, parsed_clauses)
        silent |= fix_up_complaints(parsed_clauses)
        silent |= reasons(clauses, parsed_clauses)
        silent |= told_ahead(items, clauses, parsed_clauses)
        attach_means(parsed_clauses)
        share_objects(clauses, parsed_clauses)
        gapped_objects(clauses, parsed_clauses)
        repeat_for_also(parsed_clauses)
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
                    cued = read_cues(clause, semantics, ci)
                    if cued:
                        drafts[ci] = cued
                        guessed.add(ci)
                        unread.append(ReadingNote(clause.text, "read from its key words: the "
                                                  "sentence's structure was not understood", "assumed"))
                        continue
                    unread.append(ReadingNote(clause.text, "no act or wished state found in it"))
                # "keys, watch and the credit card - pop all three in the box": a clause of
                # noun phrases names every one of them ("watch" is no verb here)
                # ("they're both on the desk next to the laptop": after a pronoun subject the
                # nouns are where it is, places, as the grammar read them)
                pronoun_subject = _PRONOUN_SUBJECT.at(clause.items)
                named = known_objects(clause.items) or parsed.mentions or cue_mentions(clause)
                for h in named:
                    semantics.note(h, ci, "place" if pronoun_subject else None)
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
            if not out and (len(failed) > failed_before or not any(
                    f.report or f.negated or f.past for f in parsed.frames)):
                # the grammar's reading failed (a misread phrase often grounds nothing):
                # read the clause from its cue words
                out = read_cues(clause, semantics, ci)
                if out:
                    guessed.add(ci)
                    unread.append(ReadingNote(clause.text, "read from its key words: the "
                                              "sentence's structure was not understood", "assumed"))
            if out:
                drafts[ci] = out
                continue
            # "the book doesn't belong on the sofa; it ..."; after a pronoun subject ("they're
            # on the desk next to the laptop") the nouns are where it is
            subject_pronoun = _SUBJECT_PRONOUN.at(clause.items)
            for h in parsed.mentions:
                semantics.note(h, ci, "place" if subject_pronoun else None)
            if not any(f.act is not None or f.state is not None for f in parsed.frames):
                unknown.extend(parsed.unknown)
        settle_start_conditions(start_conds, drafts, semantics.g)
        drop_fulfilled_wishes(drafts)
        drop_guessed_water(drafts)
        drop_holds_before_placing(drafts)
        drop_self_placements(drafts)
        superseded = drop_superseded_placements(drafts, semantics.g)
        # one object in two places: an error when asked at once, else the later one wins
        # a self-correction between two places of one object: the later, the earlier a candidate
        sides: list[Doubt] = []
        unread += [ReadingNote(span, why, "assumed") for span, why in
                   settle_placements(clauses, superseded, tagged, sides, text)]
        for what, why in drop_impossible(drafts, scene, state):
            unread.append(ReadingNote(what, f"left out, the scene cannot have it: {why}"))
        if not drafts:
            if failed:
                raise failed[0]
            self._nothing_actionable(text, scene.floor_plan, semantics, unknown, skipped,
                                     verbs_seen)
        notes = (*(_note(e) for e in [*skipped, *failed, *semantics.skipped]), *unread)
        for note in notes:
            log.info("offline parser: %s", note)
        narrow_contrasts(drafts)
        narrow_choices(drafts)
        settled = settle_contradictions(clauses, drafts, check_consistent, tagged, sides)
        notes = (*notes, *(ReadingNote(span, why, "assumed") for span, why in settled))
        spec = assemble(text, clauses, drafts, team)
        unsure = _unsure(spec, semantics.g.doubts)
        unsure += tuple(dict.fromkeys(str(c) for ci in sorted(guessed) for d in drafts.get(ci, [])
                                      for c in d.conditions if str(c) not in unsure))
        # the later side of a settled contradiction is a choice made with doubt
        unsure += tuple(dict.fromkeys(str(c) for d in sides for c in d.choices[1].drop if str(c) not in unsure))
        if not candidates:
            return Reading(spec, notes, unsure)
        surface = [(label, how, tuple(r.spec.goal().conditions)) for label, (how, r) in (alternatives or {}).items()]
        return _with_candidates(Reading(spec, notes, unsure), tagged, scene, state, team, semantics,
                                self.priors, surface, corrections, sides)

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
