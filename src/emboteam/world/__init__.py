"""World model: object catalogue, scenes, robot profiles, symbolic state, goals and checker."""

from emboteam.world.actions import Action, ActionOutcome, FailureReason, Skill
from emboteam.world.catalogue import Catalogue, load_catalogue
from emboteam.world.checker import GoalReport, GoalValidationError, check_goal, validate_goal
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile, parse_team, robot_profile, robot_profiles
from emboteam.world.scene import Scene, SceneObject, load_scene, scene_ids
from emboteam.world.state import ObjectState, RobotState, WorldState

__all__ = [
    "Action", "ActionOutcome", "Catalogue", "Condition", "FailureReason", "Goal", "GoalReport",
    "GoalValidationError", "ObjectRef", "ObjectState", "Predicate", "RobotProfile", "RobotState",
    "Scene", "SceneObject", "Skill", "WorldState", "check_goal", "load_catalogue", "load_scene",
    "parse_team", "robot_profile", "robot_profiles", "scene_ids", "validate_goal",
]
