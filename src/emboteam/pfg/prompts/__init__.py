"""Prompt texts (the ``*.txt`` files beside this module, shipped as package data) and the
renderers that turn a scene, its state and a team into prompt text.

Templates use :class:`string.Template` (``$name``): values are never re-parsed, so an
instruction containing ``$`` or braces cannot alter a template.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Collection, Sequence
from functools import cache
from importlib import resources
from string import Template

from emboteam.world.actions import Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.robots import RobotProfile
from emboteam.world.state import ObjectState, WorldState


@cache
def load_prompt(name: str) -> str:
    """The text of ``<name>.txt`` in this package."""
    return resources.files(__name__).joinpath(f"{name}.txt").read_text(encoding="utf-8")


def render(name: str, **values: str) -> str:
    """``<name>.txt`` with its ``$placeholders`` filled; a missing value is a KeyError (a
    bug in the caller, not user input)."""
    return Template(load_prompt(name)).substitute(**values).strip()


#: the properties a goal's subject may need (world.checker); pickupable covers inside and
#: held. A type with none of them (Floor, Window) can be no goal's subject
GOAL_PROPERTIES = frozenset({"pickupable", "openable", "toggleable", "sliceable", "breakable", "cookable",
                             "dirtyable", "canFillWithLiquid"})

#: property -> the word a prompt uses for it
_ABILITIES = (("pickupable", "pickupable"), ("receptacle", "receptacle"), ("openable", "openable"),
              ("toggleable", "switchable"), ("sliceable", "sliceable"), ("breakable", "breakable"),
              ("cookable", "cookable"), ("canFillWithLiquid", "fillable"), ("dirtyable", "dirtyable"))


def _object_state(o: ObjectState) -> list[str]:
    flags: list[str] = []
    if o.held_by:
        flags.append(f"held by {o.held_by}")
    elif o.parent:
        flags.append(f"in {o.parent}")
    if o.has("pickupable"):
        flags.append(f"{o.mass:g} kg")
    if o.has("openable"):
        flags.append("open" if o.is_open else "closed")
    if o.has("toggleable"):
        flags.append("on" if o.is_on else "off")
    if o.controls:
        flags.append(f"controls {', '.join(o.controls)}")
    for flag, on in (("sliced", o.is_sliced), ("broken", o.is_broken), ("dirty", o.is_dirty),
                     ("cooked", o.is_cooked)):
        if on:
            flags.append(flag)
    if o.liquid:
        flags.append(f"filled with {o.liquid}")
    if o.temperature != "RoomTemp":
        flags.append(o.temperature.lower())
    return flags


def render_scene(state: WorldState, ids: Sequence[str] | None = None,
                 detail: Collection[str] | None = None) -> str:
    """Objects grouped by type, with what they can do and their relevant state::

        Apple (pickupable, sliceable -> AppleSliced): Apple_1 [in Fridge_1]
        Fridge (receptacle, openable): Fridge_1 [closed]

    ``ids`` restricts the listing (few-shot examples show an excerpt). ``detail`` lists
    only those types in full and the others by name on one last line (the prompt stays
    small; an answer may still name those types); that line leaves out the types no goal
    can be about (neither a goal subject, :data:`GOAL_PROPERTIES`, nor a receptacle).
    """
    cat = load_catalogue()
    groups: dict[str, list[ObjectState]] = defaultdict(list)
    chosen = set(ids) if ids is not None else None
    for o in state.objects.values():
        if o.gone or (chosen is not None and o.id not in chosen):
            continue
        groups[o.type].append(o)
    lines = []
    others = sorted(t for t in groups if detail is not None and t not in detail)
    named = [t for t in others
             if any(o.has(prop) for o in groups[t] for prop in (*GOAL_PROPERTIES, "receptacle"))]
    for t in sorted(groups):
        if t in others:
            continue
        abilities = [word for prop, word in _ABILITIES if any(o.has(prop) for o in groups[t])]
        product = cat.slice_product(t)
        if product is not None and "sliceable" in abilities:
            abilities[abilities.index("sliceable")] = f"sliceable -> {product[0]}"
        items = []
        for o in sorted(groups[t], key=lambda x: x.id):
            flags = _object_state(o)
            items.append(f"{o.id} [{'; '.join(flags)}]" if flags else o.id)
        head = f"{t} ({', '.join(abilities)})" if abilities else t
        lines.append(f"{head}: {', '.join(items)}")
    if named:
        lines.append(f"Also here (not listed in detail): {', '.join(named)}")
    return "\n".join(lines)


#: the skills a goal decomposition depends on (the PFG prompts list only these: moving,
#: pushing and dropping concern action lists, not which robot can reach a goal)
GOAL_SKILLS: frozenset[Skill] = frozenset({
    Skill.PickupObject, Skill.PutObject, Skill.OpenObject, Skill.CloseObject, Skill.SwitchOn, Skill.SwitchOff,
    Skill.SliceObject, Skill.BreakObject, Skill.CleanObject})


def render_team(team: Sequence[RobotProfile], skills: Collection[Skill] | None = None) -> str:
    """One line per kind of robot: names, mass capacity, skills (in the canonical skill
    order; only ``skills`` when given). Robots alike share a line ("robot1, robot2: ..."):
    a team of three identical robots costs one line of prompt, not three."""
    lines: dict[str, list[str]] = {}
    for p in team:
        names = ", ".join(s.value for s in Skill if s in p.skills and (skills is None or s in skills)) or "none"
        lines.setdefault(f"lifts up to {p.mass_capacity:g} kg; skills: {names}", []).append(p.name)
    return "\n".join(f"{', '.join(robots)}: {what}" for what, robots in lines.items())
