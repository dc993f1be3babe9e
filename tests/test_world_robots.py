"""The 28 SMART-LLM robot profiles against SMART-LLM's own definitions."""

from __future__ import annotations

from typing import Any

import pytest

from emboteam.errors import UnknownRobotError
from emboteam.world import Skill, parse_team, robot_profile, robot_profiles
from emboteam.world.robots import DEFAULT_SPEED


def test_28_profiles_numbered_like_smart_llm(smart_llm_robots: list[dict[str, Any]]) -> None:
    profiles = robot_profiles()
    assert len(profiles) == len(smart_llm_robots) == 28
    assert [p.number for p in profiles] == list(range(1, 29))
    assert [p.name for p in profiles] == [r["name"] for r in smart_llm_robots]


@pytest.mark.parametrize("number", range(1, 29))
def test_profile_matches_smart_llm(number: int, smart_llm_robots: list[dict[str, Any]]) -> None:
    peer = smart_llm_robots[number - 1]  # task files index this list 1-based
    # SMART-LLM spells the capacity `mass` for some robots and `mass_capacity` for others
    capacity = peer.get("mass_capacity", peer.get("mass"))
    assert capacity is not None
    p = robot_profile(number)
    assert p.mass_capacity == pytest.approx(float(capacity))
    assert {s.value for s in p.skills} == set(peer["skills"])
    assert p.speed == DEFAULT_SPEED


def test_smart_llm_mixes_both_capacity_keys(smart_llm_robots: list[dict[str, Any]]) -> None:
    keys = {k for r in smart_llm_robots for k in r if k in ("mass", "mass_capacity")}
    assert keys == {"mass", "mass_capacity"}, "both spellings must keep being read"


def test_no_smart_llm_robot_can_clean() -> None:
    """Cleaning happens with running water (a faucet over the basin), not a skill."""
    assert not any(p.can(Skill.CleanObject) for p in robot_profiles())


@pytest.mark.parametrize("key", [5, "5", " 5 ", "robot5", "ROBOT5"])
def test_profile_lookup_by_number_or_name(key: int | str) -> None:
    assert robot_profile(key).number == 5
    assert robot_profile(key).mass_capacity == 1.0


@pytest.mark.parametrize("key", [0, 29, "-1", "robot29", "r2d2", ""])
def test_unknown_profiles_are_typed_errors(key: int | str) -> None:
    with pytest.raises(UnknownRobotError):
        robot_profile(key)


def test_parse_team_names_duplicates_apart() -> None:
    team = parse_team("2, 2,robot7,2")
    assert [r.name for r in team] == ["robot2", "robot2b", "robot7", "robot2c"]
    assert [r.number for r in team] == [2, 2, 7, 2]
    assert parse_team([1, 3]) == parse_team("1,3")


@pytest.mark.parametrize("spec", ["", " , ", [], "1,99", "1,x"])
def test_parse_team_rejects_bad_lists(spec: str | list[int]) -> None:
    with pytest.raises(UnknownRobotError):
        parse_team(spec)


def test_describe_lists_skills_and_capacity() -> None:
    text = robot_profile(26).describe()
    assert text.startswith("robot26 (max 100 kg)")
    assert "SliceObject" in text and "PutObject" not in text
