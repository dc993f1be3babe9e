"""The offline front end: the PFG's default, rule-based, no LLM calls."""

from __future__ import annotations

import re
from collections.abc import Sequence

from emboteam.pfg.offline import lexicon
from emboteam.pfg.offline.clauses import segment
from emboteam.pfg.offline.decompose import assemble
from emboteam.pfg.offline.errors import GroundingError, OfflineParseError
from emboteam.pfg.offline.frames import parse_clause
from emboteam.pfg.offline.grounding import Grounder
from emboteam.pfg.offline.morphology import warm_spelling
from emboteam.pfg.offline.semantics import Draft, Semantics, concat
from emboteam.pfg.offline.tagger import tag
from emboteam.pfg.offline.text import normalize
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.robots import RobotProfile
from emboteam.world.scene import Scene
from emboteam.world.state import WorldState

_MAX_CHARS = 2000


class OfflineFrontend:
    """Rule-based semantic parser: instruction -> TaskSpec, deterministic and offline.

    Pipeline: :func:`~emboteam.pfg.offline.tagger.tag` (normalise, correct typos, find
    multi-word nouns) -> :func:`~emboteam.pfg.offline.clauses.segment` (clauses and how
    they are ordered) -> :func:`~emboteam.pfg.offline.frames.parse_clause` (act, objects,
    places, states) -> :class:`~emboteam.pfg.offline.semantics.Semantics` (grounded goal
    conditions, pronouns) -> :func:`~emboteam.pfg.offline.decompose.assemble`
    (dependencies, robots, intermediate steps).
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
        text = instruction.strip()
        if not text:
            raise OfflineParseError("empty instruction")
        if len(text) > _MAX_CHARS:
            raise OfflineParseError(f"instruction too long ({len(text)} characters, at most "
                                    f"{_MAX_CHARS})")
        normal = normalize(text)
        for pattern in lexicon.VAGUE_PHRASES:
            m = re.search(pattern, normal)
            if m:
                raise OfflineParseError(
                    f"{m.group(0)!r} is too vague for the offline parser: say which objects go "
                    "where or what to do with them (e.g. 'put the plate on the table')",
                    phrase=m.group(0))
        clauses = segment(tag(text))
        semantics = Semantics(Grounder(scene, state))
        drafts: dict[int, list[Draft]] = {}
        unknown: list[str] = []
        skipped: list[OfflineParseError] = []
        verbs_seen = False
        for ci, clause in enumerate(clauses):
            parsed = parse_clause(clause)
            if not parsed.frames:
                for h in parsed.mentions:
                    semantics.note(h, ci)
                unknown.extend(parsed.unknown)
                continue
            out: list[Draft] = []
            for frame in parsed.frames:
                verbs_seen = True
                try:
                    out = concat(out, semantics.frame(frame, ci))
                except OfflineParseError as exc:
                    # "when you get a chance": small talk; "dim things": too vague, maybe
                    # said better by another clause ("... by switching off the lamp")
                    if frame.weak or getattr(exc, "vague", False):
                        skipped.append(exc)
                        continue
                    raise
            if out:
                drafts[ci] = out
                continue
            for h in parsed.mentions:      # "the book doesn't belong on the sofa; it ..."
                semantics.note(h, ci)
            if not any(f.act is not None or f.state is not None for f in parsed.frames):
                unknown.extend(parsed.unknown)
        if not drafts:
            vague = [w for w in normalize(text).split() if w in lexicon.VAGUE_NOUNS]
            if vague and not unknown:
                raise OfflineParseError(
                    f"{text!r} is too vague for the offline parser ({vague[0]!r} has no single "
                    "household reading): say which objects to act on, e.g. 'cook the potato'",
                    phrase=vague[0])
            if skipped and any(getattr(e, "vague", False) for e in skipped):
                raise next(e for e in skipped if getattr(e, "vague", False))
            if unknown and verbs_seen:
                word = unknown[0]
                grounder = semantics.g
                raise GroundingError(f"{word!r} names nothing in {scene.floor_plan}", phrase=word,
                                     suggestions=grounder.suggestions(word))
            what = "no goal could be read from it" if verbs_seen else "no action found in it"
            raise OfflineParseError(
                f"cannot understand {text!r}: {what} (try e.g. 'put the apple in the fridge', "
                "'slice the bread', 'turn off the lights')", phrase=text)
        return assemble(text, clauses, drafts, team)
