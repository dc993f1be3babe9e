"""Which object types an instruction (and a draft reading of it) is about.

The LLM prompts list these types in full (ids, abilities, state) and only name the
others: a scene has 30-90 object types and the instruction touches a handful, so listing
everything made the PFG prompt 3,500-5,500 tokens, most of it noise for a small model.
The same sets tell the answer checks (:mod:`emboteam.pfg.answer_checks`) what the
instruction mentions, so that a condition copied from a worked example is caught.

Nouns are found with the offline parser's tagger (its lexicon maps words and synonyms,
"TV", "couch", "trash", to catalogue types): that is a dictionary look-up, not a reading,
and it works on any instruction, including the ones the parser cannot read.
"""

from __future__ import annotations

from collections.abc import Iterable

from emboteam.errors import EmboTeamError
from emboteam.pfg.taskspec import TaskSpec
from emboteam.world.catalogue import load_catalogue
from emboteam.world.goals import Condition, ObjectRef
from emboteam.world.state import WorldState


def instruction_types(instruction: str) -> set[str]:
    """Catalogue types the instruction's nouns can name (synonyms and fallbacks included)."""
    from emboteam.pfg.offline.tagger import tag

    try:
        items = tag(instruction)
    except EmboTeamError:  # a tagger that refuses the text names no type
        return set()
    found: set[str] = set()
    for item in items:
        if item.noun is not None:
            found.update(item.noun.concept.types)
            found.update(item.noun.concept.fallback)
    return found


def ref_types(ref: ObjectRef, state: WorldState) -> set[str]:
    """The types an object reference names (an id's type, or its types)."""
    if ref.id is not None:
        obj = state.objects.get(ref.id)
        return {obj.type} if obj is not None else set()
    return set(ref.types)


def condition_types(cond: Condition, state: WorldState) -> set[str]:
    types = ref_types(cond.subject, state)
    if cond.receptacle is not None:
        types |= ref_types(cond.receptacle, state)
    return types


def spec_types(spec: TaskSpec, state: WorldState) -> set[str]:
    return {t for s in spec.subtasks for c in s.goal for t in condition_types(c, state)}


def related_types(types: Iterable[str], state: WorldState) -> set[str]:
    """``types`` closed under what a goal on them needs to know about: slices and what
    they are cut from, the knob that switches a burner (and back), and what holds the
    objects now (to take an apple out of the fridge the model must know the fridge)."""
    cat = load_catalogue()
    out = set(types)
    for t in list(out):
        if (product := cat.slice_product(t)) is not None:
            out.add(product[0])
        if (source := cat.source_type(t)) is not None:
            out.add(source)
    live = [o for o in state.objects.values() if not o.gone]
    by_id = {o.id: o for o in live}
    for o in live:
        controlled = {by_id[c].type for c in o.controls if c in by_id}
        if o.type in out:
            out |= controlled
        elif controlled & out:
            out.add(o.type)
    for o in live:
        if o.type in out and o.parent in by_id:
            out.add(by_id[o.parent].type)
    return out


def focus_types(instruction: str, state: WorldState, draft: TaskSpec | None = None) -> set[str] | None:
    """The types a prompt lists in full, or None (list everything) when the instruction
    names no type present in the scene (a chore like "get breakfast ready": the model
    needs the whole scene to choose from)."""
    present = {o.type for o in state.objects.values() if not o.gone}
    touched = instruction_types(instruction)
    if draft is not None:
        touched |= spec_types(draft, state)
    touched &= present | {p[0] for t in present if (p := load_catalogue().slice_product(t)) is not None}
    if not touched:
        return None
    return related_types(touched, state) & present
