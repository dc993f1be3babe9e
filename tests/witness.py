"""Running what the capability model (emboteam.sim.capability) proposes in the simulator:
a method's steps, bound to robots, each preceded by a GoToObject. Shared by the MACE-THOR
solvability tests and the capability agreement test."""

from __future__ import annotations

from collections.abc import Sequence

from emboteam.sim.capability import Method, Role, Step
from emboteam.sim.simulator import Simulator
from emboteam.world.actions import Action, Skill
from emboteam.world.catalogue import load_catalogue
from emboteam.world.robots import RobotProfile
from emboteam.world.state import WorldState


class WitnessFailed(AssertionError):
    pass


def release(sim: Simulator, robot: str) -> None:
    """Empty a robot's hand: drop what it holds, or put it on a surface it may go on."""
    r = sim.state.robots[robot]
    held = r.holding
    assert held is not None
    if r.profile.can(Skill.DropHandObject):
        act(sim, robot, Action(skill=Skill.DropHandObject, target=held))
        return
    cat = load_catalogue()
    htype = sim.state.objects[held].type
    for o in sim.state.objects.values():
        if (o.has("receptacle") and not o.has("pickupable") and o.type not in cat.must_be_open
                and cat.can_place(htype, o.type) and sim.state.enclosing_closed(o.id) is None):
            act(sim, robot, Action(skill=Skill.GoToObject, target=o.id))
            act(sim, robot, Action(skill=Skill.PutObject, target=held, receptacle=o.id))
            return
    raise WitnessFailed(f"{robot} cannot put {held} down")


def act(sim: Simulator, robot: str, action: Action) -> None:
    outcome = sim.execute(robot, action)
    if not outcome.success:
        raise WitnessFailed(f"{robot}: {action} failed: {outcome.reason} {outcome.message}")


def run_step(sim: Simulator, robot: str, step: Step) -> None:
    r = sim.state.robots[robot]
    if step.action.skill is Skill.PickupObject:
        if r.holding == step.action.target:
            return
        if r.holding is not None:
            release(sim, robot)
    act(sim, robot, Action(skill=Skill.GoToObject, target=step.near))
    act(sim, robot, step.action)


def bind(roles: Sequence[Role], actors: Sequence[RobotProfile], state: WorldState) -> dict[str, str]:
    """A robot for each role, free hands preferred."""
    out: dict[str, str] = {}
    for role in roles:
        able = [a for a in actors if role.covered_by(a)]
        if not able:
            raise WitnessFailed(f"no actor covers {role}")
        able.sort(key=lambda a: state.robots[a.name].holding is not None)
        out[role.name] = able[0].name
    return out


def run_method(sim: Simulator, method: Method, actors: Sequence[RobotProfile]) -> None:
    """Every step of ``method``, each by the robot bound to its role."""
    binding = bind(method.roles, actors, sim.state)
    for step in method.steps:
        run_step(sim, binding[step.role], step)
