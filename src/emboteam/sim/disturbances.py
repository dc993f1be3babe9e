"""Benchmark disturbances: a robot breaking down, a robot joining, someone moving an object,
and the blackboard losing or delaying messages (``emboteam bench --breakdown/--join/--moves/
--msg-loss/--msg-delay``).

A :class:`Disturbances` is what the user asked for, independent of any task
(``random@0.3``: a robot drawn by the seed, at 30 % of the task's nominal makespan). It is
part of a benchmark job's key, so its text form (:attr:`Disturbances.label`) is canonical.
:func:`resolve` turns it into concrete simulator faults and joins for one task and seed;
every random choice is drawn from a generator seeded by ``(seed, task, what, index)``, so
every mode of one task and seed gets the same disturbance (side-by-side comparison) and a
rerun gets the same one again.

Time grammar (``WHEN``): ``0.3`` is a fraction of the nominal makespan (in [0, 1]), ``30%``
the same in percent, ``12s`` absolute simulated seconds. ``--join`` keeps ``run``'s
``PROFILE@SECONDS``: a bare number there is seconds.
"""

from __future__ import annotations

import random
import re
from collections.abc import Sequence
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from emboteam.errors import EmboTeamError
from emboteam.sim.faults import Breakdown, MessageFaults, ObjectMove
from emboteam.world.robots import RobotProfile, robot_profile

RANDOM = "random"


class DisturbanceSpecError(EmboTeamError):
    """A disturbance option that cannot be parsed or resolved."""


class When(BaseModel):
    """A point of the run: a fraction of the nominal makespan, or simulated seconds."""

    model_config = ConfigDict(frozen=True)

    value: float = Field(ge=0)
    unit: Literal["fraction", "seconds"]

    def seconds(self, nominal_makespan: float) -> float:
        return self.value if self.unit == "seconds" else self.value * nominal_makespan

    def __str__(self) -> str:
        return f"{self.value:g}s" if self.unit == "seconds" else f"{self.value:g}"


_NUMBER = r"\d+(?:\.\d*)?|\.\d+"


def parse_when(text: str, *, bare: Literal["fraction", "seconds"], option: str) -> When:
    """``0.3`` / ``30%`` / ``12s`` (a bare number is ``bare``)."""
    t = text.strip().lower()
    m = re.fullmatch(rf"({_NUMBER})\s*(%|s|)", t)
    if m is None:
        raise DisturbanceSpecError(f"{option}: {text!r} is not a time; use a fraction of the nominal "
                                   "makespan (0.3), a percentage (30%) or seconds (12s)")
    value, suffix = float(m.group(1)), m.group(2)
    unit: Literal["fraction", "seconds"]
    if suffix == "%":
        value, unit = value / 100, "fraction"
    elif suffix == "s":
        unit = "seconds"
    else:
        unit = bare
    if unit == "fraction" and value > 1:
        raise DisturbanceSpecError(f"{option}: {text!r} is past the end of the run (a fraction is in [0, 1]; "
                                   "write seconds as 12s)")
    return When(value=value, unit=unit)


def _split(text: str, option: str) -> tuple[str, str]:
    who, sep, when = text.strip().rpartition("@")
    if not sep or not who.strip() or not when.strip():
        raise DisturbanceSpecError(f"{option} takes WHO@WHEN, e.g. random@0.3, not {text!r}")
    return who.strip(), when


class BreakdownSpec(BaseModel):
    """``random@0.3``: a robot of the team drawn by the seed stops for good at 30 % of the
    nominal makespan; ``robot2@12s``: that robot, at 12 s."""

    model_config = ConfigDict(frozen=True)

    robot: str
    at: When

    @classmethod
    def parse(cls, text: str) -> BreakdownSpec:
        who, when = _split(text, "--breakdown")
        if who.lower() != RANDOM:
            robot_profile(who)  # an unknown robot is a typed error now, not mid-run
        return cls(robot=who.lower(), at=parse_when(when, bare="fraction", option="--breakdown"))

    def __str__(self) -> str:
        return f"{self.robot}@{self.at}"


class JoinSpec(BaseModel):
    """``5@30``: profile 5 joins after 30 s (as ``run --join``); ``random@0.3``: a second
    unit of a team member's profile, drawn by the seed, joins at 30 % of the nominal
    makespan (``30%`` works too)."""

    model_config = ConfigDict(frozen=True)

    profile: str
    at: When

    @classmethod
    def parse(cls, text: str) -> JoinSpec:
        who, when = _split(text, "--join")
        if who.lower() != RANDOM:
            robot_profile(who)  # an unknown profile is a typed error now, not mid-run
        return cls(profile=who.lower(), at=parse_when(when, bare="seconds", option="--join"))

    def __str__(self) -> str:
        # a bare number means seconds here, so a fraction is written as a percentage
        at = f"{100 * self.at.value:g}%" if self.at.unit == "fraction" else str(self.at)
        return f"{self.profile}@{at}"


class MoveSpec(BaseModel):
    """``random@0.5``: at half the nominal makespan someone moves an object the plan uses
    (drawn by the seed among those not held at that moment) to a random valid place the team
    left can get it back from (closed receptacles only when a working robot can open them); ``Apple_1@20s``: that object, at 20 s."""

    model_config = ConfigDict(frozen=True)

    object: str
    at: When

    @classmethod
    def parse(cls, text: str) -> MoveSpec:
        who, when = _split(text, "--moves")
        return cls(object=RANDOM if who.lower() == RANDOM else who,
                   at=parse_when(when, bare="fraction", option="--moves"))

    def __str__(self) -> str:
        return f"{self.object}@{self.at}"


class Disturbances(BaseModel):
    """The disturbances of a benchmark run (all optional; the default disturbs nothing)."""

    model_config = ConfigDict(frozen=True)

    breakdowns: tuple[BreakdownSpec, ...] = ()
    joins: tuple[JoinSpec, ...] = ()
    moves: tuple[MoveSpec, ...] = ()
    messages: MessageFaults = MessageFaults()

    @classmethod
    def parse(cls, *, breakdown: Sequence[str] = (), join: Sequence[str] = (), moves: Sequence[str] = (),
              msg_loss: float = 0.0, msg_delay: float = 0.0) -> Disturbances:
        """From the CLI options; each may be repeated or hold a comma-separated list."""
        def items(values: Sequence[str]) -> list[str]:
            return [p for v in values for p in v.split(",") if p.strip()]
        if not 0.0 <= msg_loss <= 1.0:
            raise DisturbanceSpecError(f"--msg-loss {msg_loss:g} is not a probability in [0, 1]")
        if msg_delay < 0:
            raise DisturbanceSpecError(f"--msg-delay {msg_delay:g} must be >= 0 seconds")
        return cls(breakdowns=tuple(BreakdownSpec.parse(t) for t in items(breakdown)),
                   joins=tuple(JoinSpec.parse(t) for t in items(join)),
                   moves=tuple(MoveSpec.parse(t) for t in items(moves)),
                   messages=MessageFaults(release_loss=msg_loss, flag_delay=msg_delay))

    @property
    def any(self) -> bool:
        return bool(self.breakdowns or self.joins or self.moves or self.messages.any)

    @property
    def needs_nominal(self) -> bool:
        """Whether resolving needs the task's nominal makespan (a time given as a fraction)."""
        specs: list[BreakdownSpec | JoinSpec | MoveSpec] = [*self.breakdowns, *self.joins, *self.moves]
        whens = [s.at for s in specs]
        return any(w.unit == "fraction" for w in whens)

    @property
    def label(self) -> str:
        """Canonical text, e.g. ``breakdown=random@0.3;msg-loss=0.5`` ('' when nothing is
        disturbed): part of a job's key and the tables' row label."""
        parts = []
        for name, specs in (("breakdown", self.breakdowns), ("join", self.joins), ("moves", self.moves)):
            if specs:
                parts.append(f"{name}=" + ",".join(map(str, specs)))
        if self.messages.release_loss:
            parts.append(f"msg-loss={self.messages.release_loss:g}")
        if self.messages.flag_delay:
            parts.append(f"msg-delay={self.messages.flag_delay:g}")
        return ";".join(parts)


class Resolved(BaseModel):
    """A disturbance made concrete for one task and seed."""

    model_config = ConfigDict(frozen=True)

    breakdowns: tuple[Breakdown, ...] = ()
    moves: tuple[ObjectMove, ...] = ()
    joins: tuple[tuple[RobotProfile, float], ...] = ()
    messages: MessageFaults = MessageFaults()
    nominal_makespan: float = 0.0


def _rng(seed: int, task: str, *key: object) -> random.Random:
    return random.Random("|".join(map(str, ("disturb", seed, task, *key))))


def resolve(spec: Disturbances, *, team: Sequence[RobotProfile], seed: int, task: str,
            nominal_makespan: float, plan_objects: Sequence[str] = ()) -> Resolved:
    """Concrete breakdowns, moves and joins for one task (``task`` is its key) and seed.

    ``plan_objects``: the pickupable objects the reference plan uses, the candidates of a
    ``random`` move (the simulator draws among those not held when the move happens)."""
    names = [p.name for p in team]
    breakdowns = []
    for i, b in enumerate(spec.breakdowns):
        if b.robot == RANDOM:
            robot = _rng(seed, task, "breakdown", i).choice(sorted(names))
        else:
            robot = b.robot if b.robot in names else robot_profile(b.robot).name
            if robot not in names:
                raise DisturbanceSpecError(f"--breakdown {b}: {robot} is not in the team ({', '.join(names)})")
        breakdowns.append(Breakdown(robot=robot, at=round(b.at.seconds(nominal_makespan), 6)))
    moves = []
    for i, m in enumerate(spec.moves):
        at = round(m.at.seconds(nominal_makespan), 6)
        if m.object == RANDOM:
            if not plan_objects:
                continue  # nothing the plan uses can be moved: nothing is disturbed
            moves.append(ObjectMove(object=None, candidates=tuple(sorted(set(plan_objects))), at=at,
                                    into_closed=True, draw=f"{task}|{i}"))
        else:
            moves.append(ObjectMove(object=m.object, at=at, into_closed=True, draw=f"{task}|{i}"))
    joins = []
    taken = set(names)
    for i, j in enumerate(spec.joins):
        if j.profile == RANDOM:
            base = _rng(seed, task, "join", i).choice(sorted(team, key=lambda p: p.name))
            profile = robot_profile(base.number) if base.number else base
        else:
            profile = robot_profile(j.profile)
        name, k = profile.name, 0
        while name in taken:
            k += 1
            name = f"{profile.name}{chr(ord('a') + k)}"
        taken.add(name)
        if name != profile.name:
            profile = profile.model_copy(update={"name": name})
        joins.append((profile, round(j.at.seconds(nominal_makespan), 6)))
    return Resolved(breakdowns=tuple(breakdowns), moves=tuple(moves), joins=tuple(joins),
                    messages=spec.messages, nominal_makespan=nominal_makespan)
