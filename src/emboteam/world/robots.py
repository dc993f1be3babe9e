"""Robot profiles: the 28 skill/mass-capacity configurations that SMART-LLM and LaMMA-P
task files index 1-based in their ``robot list``, plus a speed.

The facts (which skills, what mass capacity) are those of SMART-LLM's
``resources/robots.py``; they are restated here as a table rather than shipped as the
peer's file (which carries no licence). ``tests/test_world_robots.py`` checks the table against
``../shared/data/peers/smart-llm/robots.json``.
"""

from __future__ import annotations

from functools import cache

from pydantic import BaseModel, ConfigDict, Field

from emboteam.errors import UnknownRobotError
from emboteam.world.actions import Skill

#: Navigation speed of every profile. SMART-LLM's robots have no speed; AI2-THOR moves
#: 0.25 m per MoveAhead at about 4 actions per second, i.e. 1 m/s.
DEFAULT_SPEED = 1.0

_ALL = "GoTo Open Close Break Slice SwitchOn SwitchOff Pickup Put DropHand Throw Push Pull"
_NAMES = {
    "GoTo": Skill.GoToObject, "Open": Skill.OpenObject, "Close": Skill.CloseObject,
    "Break": Skill.BreakObject, "Slice": Skill.SliceObject, "SwitchOn": Skill.SwitchOn,
    "SwitchOff": Skill.SwitchOff, "Pickup": Skill.PickupObject, "Put": Skill.PutObject,
    "DropHand": Skill.DropHandObject, "Throw": Skill.ThrowObject, "Push": Skill.PushObject,
    "Pull": Skill.PullObject,
}

#: number -> (skills, mass capacity in kg); SMART-LLM's facts.
_TABLE: dict[int, tuple[str, float]] = {
    1: (_ALL, 100), 2: (_ALL, 100), 3: (_ALL, 100), 4: (_ALL, 100),
    5: (_ALL, 1.0), 6: (_ALL, 2.1), 7: (_ALL, 0.08), 8: (_ALL, 0.4), 9: (_ALL, 5),
    10: (_ALL, 0.02),
    11: ("GoTo Break Slice Pickup Put DropHand Throw Push Pull", 100),
    12: ("GoTo Break Slice SwitchOn SwitchOff DropHand Throw Push Pull", 100),
    13: ("GoTo Break SwitchOn SwitchOff Pickup Put DropHand Throw Push Pull", 100),
    14: ("GoTo Break Slice SwitchOn SwitchOff Pickup Put DropHand Push Pull", 100),
    15: ("GoTo Break Slice SwitchOn SwitchOff Pickup Put DropHand Throw Push Pull", 100),
    16: ("GoTo Open Close Break Slice DropHand Throw Push Pull", 100),
    17: ("GoTo Open Close Break Pickup Put DropHand Throw Push Pull", 100),
    18: ("GoTo Open Close Slice Pickup Put DropHand Throw Push Pull", 100),
    19: ("GoTo Open Close Break Slice Pickup Put DropHand Throw Push Pull", 100),
    20: ("GoTo Open Close Break SwitchOn SwitchOff DropHand Throw Push Pull", 100),
    21: ("GoTo Open Close Break Slice SwitchOn SwitchOff DropHand Push Pull", 100),
    22: ("GoTo Open Close Break Slice SwitchOn SwitchOff DropHand Throw Push Pull", 100),
    23: ("GoTo Open Close", 100),
    24: ("GoTo SwitchOn SwitchOff", 100),
    25: ("GoTo Pickup Put", 100),
    26: ("GoTo Slice Pickup", 100),
    27: ("GoTo Break Throw", 100),
    28: (_ALL, 0.9),
}


class RobotProfile(BaseModel):
    """A robot configuration: which skills it has, how much it can lift, how fast it moves."""

    model_config = ConfigDict(frozen=True)

    number: int | None = Field(None, description="SMART-LLM profile number, 1..28")
    name: str
    skills: frozenset[Skill]
    mass_capacity: float = Field(gt=0, description="heaviest object it can pick up, kg")
    speed: float = Field(DEFAULT_SPEED, gt=0, description="navigation speed, m/s")

    def can(self, skill: Skill) -> bool:
        return skill in self.skills

    def describe(self) -> str:
        skills = ", ".join(s.value for s in Skill if s in self.skills)
        return f"{self.name} (max {self.mass_capacity:g} kg): {skills}"


@cache
def robot_profiles() -> tuple[RobotProfile, ...]:
    """The 28 SMART-LLM profiles, numbered 1..28."""
    return tuple(
        RobotProfile(number=n, name=f"robot{n}",
                     skills=frozenset(_NAMES[s] for s in skills.split()), mass_capacity=cap)
        for n, (skills, cap) in sorted(_TABLE.items())
    )


def robot_profile(key: int | str) -> RobotProfile:
    """A profile by number (``5``, ``"5"``) or name (``"robot5"``)."""
    text = str(key).strip().lower()
    if text.isdigit():
        n = int(text)
        if 1 <= n <= len(_TABLE):
            return robot_profiles()[n - 1]
        raise UnknownRobotError(f"robot profile {n} does not exist (profiles are 1..{len(_TABLE)})")
    for p in robot_profiles():
        if p.name == text:
            return p
    raise UnknownRobotError(f"unknown robot {key!r}: use a profile number 1..28 or robot1..robot28")


def parse_team(spec: str | list[int] | list[str]) -> tuple[RobotProfile, ...]:
    """A team from ``"1,2,3"``, ``"robot1,robot5"`` or a list; duplicates get a suffix.

    Team members are named after their profile (``robot5``); a second copy of one profile
    becomes ``robot5b``, so names stay unique within a team.
    """
    items = [s for s in spec.split(",")] if isinstance(spec, str) else [str(s) for s in spec]
    items = [s.strip() for s in items]
    if not any(items):
        raise UnknownRobotError("empty robot list")
    if not all(items):  # "1,,2" is a typo, not a team of two: say so rather than guess
        raise UnknownRobotError(f"robot list {spec!r} has an empty item: write profiles as 1,2,3")
    team: list[RobotProfile] = []
    seen: dict[str, int] = {}
    for item in items:
        profile = robot_profile(item)
        k = seen.get(profile.name, 0)
        seen[profile.name] = k + 1
        if k:
            profile = profile.model_copy(update={"name": f"{profile.name}{chr(ord('a') + k)}"})
        team.append(profile)
    return tuple(team)
