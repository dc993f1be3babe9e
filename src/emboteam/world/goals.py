"""Goal conditions: a small language over object ids or "any/N instances of these types".

Text form, as written in task files, prompts and logs::

    inside(Apple, Fridge)                 any apple in/on any fridge (transitively);
                                          also in(..), on(.., ..), contains(Fridge, Apple)
    on(2 of Potato|Lettuce|Tomato, CounterTop)   two vegetables on a counter top
    sliced(Lettuce_1)                     that lettuce
    off(LightSwitch)  switched_on(Television)  open(Fridge)  closed(Box)
    hot(Mug) cold(Apple) cooked(Potato) clean(Mug) dirty(Bowl) filled(Mug, coffee)
    held(Pillow)  broken(Vase)

A type reference also matches the slices of objects of that type (a cooked slice of bread
makes ``cooked(Bread)`` true), as AI2-THOR's slices inherit from their whole.
"""

from __future__ import annotations

import re
from enum import Enum

from pydantic import BaseModel, ConfigDict, Field, model_validator

from emboteam.errors import GoalSyntaxError
from emboteam.world.scene import is_object_id


class Predicate(str, Enum):
    inside = "inside"
    sliced = "sliced"
    broken = "broken"
    switched_on = "switched_on"
    switched_off = "switched_off"
    open = "open"
    closed = "closed"
    hot = "hot"
    cold = "cold"
    cooked = "cooked"
    clean = "clean"
    dirty = "dirty"
    filled = "filled"
    held = "held"

    def __str__(self) -> str:
        return self.value


#: Accepted spellings -> (predicate, arity) ; ``on`` is containment with two arguments
#: and "switched on" with one.
_ALIASES: dict[tuple[str, int], Predicate] = {
    ("inside", 2): Predicate.inside, ("in", 2): Predicate.inside, ("on", 2): Predicate.inside,
    ("contains", 2): Predicate.inside,
    ("on", 1): Predicate.switched_on, ("turned_on", 1): Predicate.switched_on,
    ("off", 1): Predicate.switched_off, ("turned_off", 1): Predicate.switched_off,
    ("opened", 1): Predicate.open, ("picked", 1): Predicate.held,
    ("filled", 2): Predicate.filled,
}


def _same_fields(self: BaseModel, other: object) -> bool:
    """Pydantic's ``__eq__`` for a frozen model with no private or extra attributes, in a
    fraction of its time: the reader compares conditions tens of thousands of times per
    instruction (the ranker's candidates), and pydantic's general check (generic origins,
    private and extra attributes, ignored keys) was a tenth of its time."""
    if type(other) is type(self):
        return self.__dict__ == other.__dict__
    return BaseModel.__eq__(self, other)


def _remember_hash(cls: type[BaseModel]) -> None:
    """Pydantic's hash of a frozen model (of its fields' values), worked out once per object
    and kept in its ``_hash`` slot: the ranker hashes the same conditions again and again
    (sets of goals), and the fields of a frozen model never change. A copy
    (``model_copy``) gets an empty slot, so its hash is worked out anew."""
    of_fields = cls.__hash__
    # the slot read directly: an empty slot read as an attribute would go through
    # pydantic's slow ``__getattr__`` before failing
    kept = cls._hash    # type: ignore[attr-defined]

    def __hash__(self: BaseModel) -> int:
        try:
            return kept.__get__(self)    # type: ignore[no-any-return]
        except AttributeError:
            value = of_fields(self)
            kept.__set__(self, value)
            return value
    cls.__hash__ = __hash__    # type: ignore[method-assign, assignment]


class ObjectRef(BaseModel):
    """Either one object (``id``) or any object of some types (``types``)."""

    model_config = ConfigDict(frozen=True)

    id: str | None = None
    types: tuple[str, ...] = ()

    __eq__ = _same_fields
    __slots__ = ("_hash",)

    @model_validator(mode="after")
    def _one_of(self) -> ObjectRef:
        if (self.id is None) == (not self.types):
            raise ValueError("an object reference names an id or one or more types")
        return self

    @classmethod
    def parse(cls, text: str) -> ObjectRef:
        text = text.strip()
        if not text:
            raise GoalSyntaxError("empty object reference")
        if is_object_id(text):
            return cls(id=text)
        types = tuple(t.strip() for t in text.split("|") if t.strip())
        for t in types:
            if not re.fullmatch(r"[A-Za-z]+", t):
                raise GoalSyntaxError(f"not an object id or type: {t!r}")
        return cls(types=types)

    def __str__(self) -> str:
        return self.id if self.id is not None else "|".join(self.types)


_remember_hash(ObjectRef)


class Condition(BaseModel):
    """One goal condition: ``predicate(subject[, receptacle])`` for ``count`` objects."""

    model_config = ConfigDict(frozen=True)

    predicate: Predicate
    subject: ObjectRef
    receptacle: ObjectRef | None = Field(None, description="for inside: where")
    count: int = Field(1, ge=1, description="how many distinct matching objects")
    liquid: str | None = Field(None, description="for filled: water, coffee or wine")

    __eq__ = _same_fields
    __slots__ = ("_hash",)

    @model_validator(mode="after")
    def _shape(self) -> Condition:
        if (self.predicate is Predicate.inside) != (self.receptacle is not None):
            raise ValueError("inside() takes an object and a receptacle; other predicates one object")
        if self.subject.id is not None and self.count != 1:
            raise ValueError("a count applies to a type, not to one object id")
        if self.liquid is not None and self.predicate is not Predicate.filled:
            raise ValueError("a liquid applies only to filled()")
        return self

    def __str__(self) -> str:
        subj = f"{self.count} of {self.subject}" if self.count > 1 else str(self.subject)
        args = [subj]
        if self.receptacle is not None:
            args.append(str(self.receptacle))
        if self.liquid is not None:
            args.append(self.liquid)
        return f"{self.predicate.value}({', '.join(args)})"

    @classmethod
    def parse(cls, text: str) -> Condition:
        m = re.fullmatch(r"\s*([A-Za-z_]+)\s*\((.*)\)\s*", text)
        if not m:
            raise GoalSyntaxError(f"not a condition: {text!r} (expected e.g. inside(Apple, Fridge))")
        name, args = m.group(1).lower(), [a.strip() for a in m.group(2).split(",")]
        key = (name, len(args))
        if key in _ALIASES:
            pred = _ALIASES[key]
        else:
            try:
                pred = Predicate(name)
            except ValueError:
                known = ", ".join(p.value for p in Predicate)
                raise GoalSyntaxError(f"unknown predicate {name!r} in {text!r}; known: {known}") from None
        if name == "contains" and len(args) == 2:
            args.reverse()  # contains(Fridge, Apple) reads "the fridge contains an apple"
        subject_text = args[0]
        count = 1
        cm = re.fullmatch(r"(\d+)\s*(?:of|x|\*)\s*(.+)", subject_text)
        if cm:
            count, subject_text = int(cm.group(1)), cm.group(2)
        try:
            if pred is Predicate.inside:
                if len(args) != 2:
                    raise GoalSyntaxError(f"{name} takes two arguments: {text!r}")
                return cls(predicate=pred, subject=ObjectRef.parse(subject_text),
                           receptacle=ObjectRef.parse(args[1]), count=count)
            if pred is Predicate.filled and len(args) == 2:
                return cls(predicate=pred, subject=ObjectRef.parse(subject_text), count=count,
                           liquid=args[1].lower())
            if len(args) != 1:
                raise GoalSyntaxError(f"{name} takes one argument: {text!r}")
            return cls(predicate=pred, subject=ObjectRef.parse(subject_text), count=count)
        except ValueError as exc:  # pydantic's validation errors
            raise GoalSyntaxError(f"{text!r}: {exc}") from None


_remember_hash(Condition)


class Goal(BaseModel):
    """A conjunction of conditions. SR needs all of them, GCR counts each."""

    model_config = ConfigDict(frozen=True)

    conditions: tuple[Condition, ...]

    @classmethod
    def parse(cls, texts: list[str] | str) -> Goal:
        if isinstance(texts, str):
            texts = [t for t in re.split(r"\s*[;&]\s*", texts) if t.strip()]
        return cls(conditions=tuple(Condition.parse(t) for t in texts))

    def __str__(self) -> str:
        return " & ".join(str(c) for c in self.conditions)
