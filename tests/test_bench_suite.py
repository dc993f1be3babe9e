"""The MACE-THOR suite as package data: schema, composition, goals, and the suite API."""

from __future__ import annotations

import json
from collections import Counter
from importlib import resources
from typing import Any

import pytest
from pydantic import ValidationError

from emboteam.bench.mace_thor import FLOOR_PLANS, SuiteDataError, load_mace_thor, parse_tasks
from emboteam.bench.suites import Suite, UnknownSuiteError, UnknownTaskError, get_task, load_suite
from emboteam.errors import EmboTeamError
from emboteam.task import BenchTask, InvalidTaskError
from emboteam.world.checker import check_goal, validate_goal
from emboteam.world.scene import load_scene

SUITE = load_suite("mace-thor")
RAW: dict[str, Any] = json.loads(resources.files("emboteam.bench").joinpath("data/mace_thor.json").read_text())


def test_42_tasks_21_per_category() -> None:
    assert SUITE.name == "mace-thor" and SUITE.problems == ()
    assert len(SUITE.tasks) == 42
    assert SUITE.categories() == {"parallel": 21, "temporal": 21}
    assert all(t.suite == "mace-thor" and t.key == f"mace-thor/{t.id}" for t in SUITE.tasks)


def test_the_eight_floor_plans_roughly_balanced_with_both_categories() -> None:
    per_plan = Counter(t.floor_plan for t in SUITE.tasks)
    assert set(per_plan) == set(FLOOR_PLANS) and len(FLOOR_PLANS) == 8
    assert all(5 <= n <= 6 for n in per_plan.values()), per_plan
    for fp in FLOOR_PLANS:
        assert {t.category for t in SUITE.tasks if t.floor_plan == fp} == {"parallel", "temporal"}, fp
    rooms = Counter(load_scene(fp).room for fp in FLOOR_PLANS)
    assert rooms == {"kitchen": 4, "living_room": 2, "bedroom": 1, "bathroom": 1}


def test_ids_unique_and_say_where() -> None:
    ids = [t.id for t in SUITE.tasks]
    assert len(set(ids)) == len(ids)
    for t in SUITE.tasks:
        assert t.id.startswith(f"fp{t.floor_plan.removeprefix('FloorPlan')}-"), t.id


def test_teams_of_two_to_four_different_profiles() -> None:
    for t in SUITE.tasks:
        team = t.team()
        assert 2 <= len(team) <= 4, t.id
        assert all(p.number is not None and 1 <= p.number <= 28 for p in team)
        kinds = {(p.skills, p.mass_capacity) for p in team}
        assert len(kinds) == len(team), f"{t.id}: two members with the same skills and strength"


def test_every_goal_validates_in_its_scene_and_setup_applies() -> None:
    for t in SUITE.tasks:
        t.check()
        validate_goal(t.goal, load_scene(t.floor_plan))
        state = t.initial_state()
        assert state.invariant_violations() == []
        assert set(state.robots) == {p.name for p in t.team()}
        for change in t.setup:
            if change.parent is not None:
                assert state.objects[change.object].parent == change.parent


def test_setup_changes_the_world_the_instruction_talks_about() -> None:
    watch = get_task("mace-thor/fp209-watch-in-drawer").initial_state()
    assert watch.objects["Watch_1"].parent == "Drawer_3"
    assert watch.enclosing_closed("Watch_1") == "Drawer_3"
    wash = get_task("mace-thor/fp1-wash-bowl-pan").initial_state()
    assert wash.objects["Bowl_1"].is_dirty and wash.objects["Pan_1"].is_dirty


def test_instructions_are_written_not_templated() -> None:
    texts = [t.instruction for t in SUITE.tasks]
    assert len(set(texts)) == 42
    openings = Counter(" ".join(x.split()[:3]).lower() for x in texts)
    assert openings.most_common(1)[0][1] == 1, openings.most_common(3)
    lengths = [len(x.split()) for x in texts]
    assert min(lengths) <= 6 and max(lengths) >= 22  # terse requests and long ones
    assert sum(x.endswith("?") for x in texts) >= 3  # questions as well as orders


def test_goals_use_any_instance_counts_and_ids() -> None:
    conds = [c for t in SUITE.tasks for c in t.goal.conditions]
    assert any(c.count > 1 for c in conds)
    assert any(c.subject.id is not None or (c.receptacle and c.receptacle.id) for c in conds)
    assert any(len(c.subject.types) == 0 or (c.receptacle and len(c.receptacle.types) > 1) for c in conds)
    assert len({c.predicate for c in conds}) >= 10


def test_goal_is_not_met_before_anyone_acts() -> None:
    for t in SUITE.tasks:
        assert not check_goal(t.goal, t.initial_state()).success, t.id


def test_task_json_round_trip() -> None:
    for t in SUITE.tasks:
        assert BenchTask.model_validate_json(t.model_dump_json()) == t


# ---- schema: bad data is rejected with the culprit named --------------------------------


def _doc(**override: Any) -> dict[str, Any]:
    task = {"id": "x1", "floor_plan": "FloorPlan1", "category": "parallel", "robots": [1, 24],
            "instruction": "Switch the light off.", "goal": ["switched_off(LightSwitch)"]}
    task.update(override)
    return {"suite": "mace-thor", "version": 1, "tasks": [task]}


def test_a_valid_document_parses() -> None:
    (task,) = parse_tasks(_doc())
    assert task.robots == ("1", "24") and str(task.goal) == "switched_off(LightSwitch)"


@pytest.mark.parametrize(("override", "message"), [
    ({"robot": [1]}, "robot"),  # unknown field (typo)
    ({"category": "sequential"}, "category"),
    ({"goal": ["switched_off(LightSwitch"]}, "goal"),
    ({"goal": ["frobnicated(LightSwitch)"]}, "unknown predicate"),
    ({"goal": ["inside(Sofa, Fridge)"]}, "no Sofa"),  # no sofa in a kitchen
    ({"goal": ["sliced(Mug)"]}, "sliced"),  # mugs do not slice
    ({"robots": [29]}, "29"),
    ({"robots": []}, "robots"),
    ({"floor_plan": "FloorPlan99"}, "FloorPlan99"),
    ({"floor_plan": "6"}, "FloorPlan6"),  # must be written out
    ({"setup": [{"object": "Mug_9", "is_dirty": True}]}, "Mug_9"),
    ({"setup": [{"object": "Mug_1", "dirty": True}]}, "dirty"),  # unknown state field
    ({"suite": "other"}, "suite"),
])
def test_bad_tasks_are_rejected_naming_the_task(override: dict[str, Any], message: str) -> None:
    with pytest.raises(SuiteDataError) as info:
        parse_tasks(_doc(**override))
    assert "x1" in str(info.value) and message in str(info.value)


def test_duplicate_ids_and_unknown_envelope_fields_are_rejected() -> None:
    doc = _doc()
    doc["tasks"].append(dict(doc["tasks"][0]))
    with pytest.raises(SuiteDataError, match="duplicate task id 'x1'"):
        parse_tasks(doc)
    with pytest.raises(SuiteDataError, match="extra"):
        parse_tasks({**_doc(), "extra": 1})
    with pytest.raises(SuiteDataError, match="expected 'mace-thor'"):
        parse_tasks({**_doc(), "suite": "other-suite"})


def test_bench_task_rejects_unknown_fields_directly() -> None:
    with pytest.raises(ValidationError):
        BenchTask.model_validate({**RAW["tasks"][0], "suite": "mace-thor", "difficulty": "hard"})


def test_check_is_a_typed_error() -> None:
    task = BenchTask(id="t", suite="unit", floor_plan="FloorPlan1", robots=("1",), category="parallel",
                     instruction="x", goal=["inside(Pillow, Fridge)"])  # type: ignore[arg-type]
    with pytest.raises(InvalidTaskError, match="unit/t"):
        task.check()
    assert issubclass(InvalidTaskError, EmboTeamError)


# ---- suite API --------------------------------------------------------------------------


def test_get_task_by_key() -> None:
    t = get_task("mace-thor/fp1-toast")
    assert t.floor_plan == "FloorPlan1" and t.category == "temporal"
    assert SUITE.task("fp1-toast") is t


def test_unknown_task_lists_close_matches() -> None:
    with pytest.raises(UnknownTaskError, match="fp1-toast"):
        get_task("mace-thor/fp1-toasts")
    with pytest.raises(UnknownTaskError, match=r"SUITE/ID.*mace-thor/fp1-toast"):
        get_task("fp1-toast")


def test_unknown_suite_suggests_the_known_ones() -> None:
    with pytest.raises(UnknownSuiteError, match="mace-thor"):
        load_suite("mace_thor")
    with pytest.raises(UnknownSuiteError, match="smart-llm:PATH"):
        load_suite("smartllm")
    with pytest.raises(UnknownSuiteError, match="needs a path"):
        load_suite("smart-llm:")
    with pytest.raises(UnknownSuiteError):
        get_task("nope/fp1-toast")


def test_suite_is_cached_and_immutable() -> None:
    assert load_mace_thor() is load_mace_thor()
    with pytest.raises(ValidationError):
        SUITE.tasks[0].id = "changed"  # type: ignore[misc]
    assert isinstance(load_suite(" mace-thor "), Suite)


def test_package_ships_no_peer_data() -> None:
    """SMART-LLM's tasks have no licence: tests read them from ../shared, the package never."""
    bench = resources.files("emboteam.bench")
    shipped = sorted(p.name for p in bench.joinpath("data").iterdir())
    assert shipped == ["congestion.json", "mace_thor.json"]  # both written by this project
    for name in shipped:
        text = bench.joinpath(f"data/{name}").read_text()
        assert "object_states" not in text and "robot list" not in text


def test_docs_table_matches_the_data() -> None:
    """docs/mace_thor.md lists every task; keep it in sync with the data file."""
    from pathlib import Path

    doc = (Path(__file__).resolve().parents[1] / "docs" / "mace_thor.md").read_text()
    rows = [line.strip("|").split("|") for line in doc.splitlines() if line.startswith("| fp")]
    table = [(c[0].strip(), c[1].strip(), c[2].strip(), c[3].strip(), int(c[4])) for c in rows]
    expected = [(t.id, t.floor_plan, t.category, ", ".join(t.robots), len(t.goal.conditions))
                for t in SUITE.tasks]
    assert table == expected
