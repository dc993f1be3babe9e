"""A goal said as one plain-English sentence about the end state.

"The apple is in the fridge, the bread is sliced and the light switch is off." This is
what the person chooses from (``emboteam run --clarify``) and what a language model
scores (PMI of the sentence given the instruction): a reading said as a state of the
room, in everyday words, not as predicates.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from functools import lru_cache

from emboteam.world.goals import Condition, ObjectRef, Predicate

P = Predicate

#: how each one-place predicate reads after "is" / "are"
_STATE_WORDS: dict[Predicate, str] = {
    P.sliced: "sliced", P.broken: "broken", P.switched_on: "on", P.switched_off: "off",
    P.open: "open", P.closed: "closed", P.hot: "hot", P.cold: "cold", P.cooked: "cooked",
    P.clean: "clean", P.dirty: "dirty", P.held: "held by a robot",
}

#: object types whose everyday name is not their split CamelCase name
_PLAIN_NAMES: dict[str, str] = {
    "SinkBasin": "sink", "BathtubBasin": "bathtub", "GarbageCan": "bin", "CounterTop": "counter",
    "LightSwitch": "light switch", "TVStand": "TV stand", "Television": "TV", "CellPhone": "phone",
    "RemoteControl": "remote", "CD": "CD", "StoveBurner": "stove burner", "StoveKnob": "stove knob",
    "DiningTable": "dining table", "SoapBar": "soap bar", "HousePlant": "house plant",
}


@lru_cache(maxsize=1024)     # a type's name is asked per clause of every candidate sentence
def type_name(type_: str) -> str:
    """An AI2-THOR type in everyday lower-case words: ``AppleSliced`` -> "apple slice"."""
    if type_ in _PLAIN_NAMES:
        return _PLAIN_NAMES[type_]
    if type_.endswith("Sliced"):
        return f"{type_name(type_.removesuffix('Sliced'))} slice"
    if type_.endswith("Cracked"):
        return f"cracked {type_name(type_.removesuffix('Cracked'))}"
    return re.sub(r"(?<=[a-z])(?=[A-Z])", " ", type_).lower()


def ref_phrase(ref: ObjectRef, count: int = 1) -> str:
    """"the apple", "two apple slices", "the mug or the cup", "the apple (Apple_1)"."""
    if ref.id is not None:
        t = ref.id.split("_")[0]
        return f"the {type_name(t)}"
    names = [type_name(t) for t in ref.types]
    if count > 1:
        word = _NUMBERS.get(count, str(count))
        return f"{word} " + " or ".join(_plural(n) for n in names)
    return " or ".join(f"the {n}" for n in names)


#: places things go on, not in
_SURFACES = ("Top", "Table", "Shelf", "Desk", "Sofa", "Bed", "Chair", "Stand", "Dresser", "Plate", "Pan",
             "Burner", "Ottoman", "Cart", "Board", "Stool", "Holder", "Bar", "Tray", "Floor", "Counter")

_NUMBERS = {2: "two", 3: "three", 4: "four", 5: "five", 6: "six"}


def _plural(noun: str) -> str:
    if noun.endswith(("s", "sh", "ch", "x")):
        return noun + "es"
    if noun.endswith("y") and noun[-2:-1] not in "aeiou":
        return noun[:-1] + "ies"
    return noun + "s"


@lru_cache(maxsize=4096)     # conditions are frozen; the candidates of one reading share most
def clause(c: Condition) -> str:
    """One condition as a clause: "the apple is in the fridge"."""
    subject = ref_phrase(c.subject, c.count)
    verb = "are" if c.count > 1 else "is"
    if c.predicate is P.inside:
        assert c.receptacle is not None
        types = c.receptacle.types or (str(c.receptacle.id).split("_")[0],)
        prep = "on" if types[0].endswith(_SURFACES) else "in"
        return f"{subject} {verb} {prep} {ref_phrase(c.receptacle)}"
    if c.predicate is P.filled:
        return f"{subject} {verb} filled with {c.liquid or 'water'}"
    return f"{subject} {verb} {_STATE_WORDS[c.predicate]}"


def sentence(conditions: Sequence[Condition]) -> str:
    """The goal as one sentence, capitalised, with a full stop."""
    parts = [clause(c) for c in conditions]
    if not parts:
        return "Nothing changes."
    text = parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]
    return text[0].upper() + text[1:] + "."


def clause_sentences(conditions: Sequence[Condition]) -> tuple[str, ...]:
    """Each condition as a sentence of its own ("The apple is in the fridge."): what the
    model scores clause by clause (``model_ranker.clause_lead``)."""
    return tuple(sentence([c]) for c in conditions)
