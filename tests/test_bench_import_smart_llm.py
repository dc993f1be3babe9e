"""Importing SMART-LLM / MAT-THOR task files: tolerant parsing, name and state mapping,
problems reported (not fatal). Reads the peers' test set from ../shared (never shipped)."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SMART_LLM
from emboteam.bench.importers.lenient import RecordSyntaxError, read_record, repair
from emboteam.bench.importers.smart_llm import import_smart_llm, resolve_type, task_files
from emboteam.bench.suites import UnknownSuiteError, get_task, load_suite
from emboteam.world.goals import Goal
from emboteam.world.scene import load_scene


@pytest.fixture(scope="module")
def peers() -> Path:
    if not (SMART_LLM / "final_test").is_dir():
        pytest.skip(f"SMART-LLM peer data not available at {SMART_LLM}")
    return SMART_LLM


def goal_text(task_goal: Goal) -> list[str]:
    return [str(c) for c in task_goal.conditions]


# ---- the peers' test set ------------------------------------------------------------------


def test_imports_34_of_36_tasks_and_reports_the_rest(peers: Path) -> None:
    suite = load_suite(f"smart-llm:{peers}")
    assert suite.name == f"smart-llm:{peers}"
    assert len(suite.tasks) == 34  # 36 lines, 2 without ground truth
    assert {t.category for t in suite.tasks} == {"imported"}
    assert len({t.id for t in suite.tasks}) == 34
    assert sorted({t.floor_plan for t in suite.tasks}) == sorted(
        ["FloorPlan6", "FloorPlan15", "FloorPlan21", "FloorPlan201", "FloorPlan209", "FloorPlan303", "FloorPlan414"])
    problems = suite.problems
    # lines and conditions left out, each with FILE:LINE and why
    assert any(p.startswith("final_test/FloorPlan209.json:1: no 'object_states'") for p in problems)
    assert any(p.startswith("final_test/FloorPlan414.json:1: empty 'object_states'") for p in problems)
    assert any(p.startswith("final_test/FloorPlan414.json:4: Cabinet: no state and contains nothing")
               for p in problems)
    # kept as the peers wrote them, flagged: AI2-THOR's rules or the team rule them out
    assert any(p.startswith("final_test/FloorPlan209.json:5: kept: inside(Vase, Sofa) cannot be achieved")
               for p in problems)
    assert any(p.startswith("final_test/FloorPlan201.json:3: kept: inside(Bowl, Box)") for p in problems)
    assert any(p.startswith("final_test/FloorPlan6.json:3: kept: team 27,25 cannot achieve inside(Spatula, GarbageCan)")
               and "robot27 lacks PickupObject" in p for p in problems)
    assert len(problems) == 6, problems


def test_exact_conversions(peers: Path) -> None:
    s = load_suite(f"smart-llm:{peers}")
    t = s.task("FloorPlan15-2")
    assert t.instruction == "Put apple in fridge and switch off the light"
    assert t.robots == ("1", "2", "3") and t.floor_plan == "FloorPlan15"
    assert goal_text(t.goal) == ["inside(Apple, Fridge)", "switched_off(LightSwitch)"]
    # one condition per contained item: GCR is a share of items, not of entries
    assert goal_text(s.task("FloorPlan21-3").goal) == ["inside(Potato, Fridge)", "inside(Lettuce, Fridge)"]
    assert goal_text(s.task("FloorPlan201-2").goal) == ["held(Pillow)"]  # PICKED
    assert goal_text(s.task("FloorPlan201-5").goal) == ["open(Laptop)", "switched_on(Laptop)"]  # OPENED, ON
    assert goal_text(s.task("FloorPlan209-2").goal) == ["broken(Vase)", "switched_on(Television)"]  # BROKEN
    assert goal_text(s.task("FloorPlan21-5").goal) == ["cooked(Bread)"]  # COOKED
    assert goal_text(s.task("FloorPlan15-6").goal) == ["inside(Mug, CoffeeMachine)", "hot(Mug)"]  # HOT
    assert goal_text(s.task("FloorPlan303-5").goal) == ["broken(CellPhone)", "closed(Blinds)"]  # CLOSED
    # names: trailing comma, trailing space, lower case, "trash"
    assert goal_text(s.task("FloorPlan209-3").goal) == ["inside(Watch, Box)", "inside(WateringCan, CoffeeTable)"]
    assert "'CoffeeTable,' -> CoffeeTable" in s.task("FloorPlan209-3").notes
    assert goal_text(s.task("FloorPlan303-3").goal) == ["inside(Book, Box)", "switched_on(CellPhone)"]
    assert goal_text(s.task("FloorPlan414-2").goal) == ["inside(Cloth, GarbageCan)"]
    assert goal_text(s.task("FloorPlan414-5").goal) == ["switched_on(Faucet)", "inside(ToiletPaper, GarbageCan)"]
    # "state": "None" (a string) is no state
    assert goal_text(s.task("FloorPlan6-2").goal) == ["inside(Lettuce, CounterTop)"]
    # a record missing its ']' mid-line was repaired, and says so
    assert "inserted a missing ']'" in s.task("FloorPlan303-6").notes
    assert goal_text(s.task("FloorPlan303-6").goal) == ["inside(Laptop, Bed)"]


def test_every_imported_goal_validates(peers: Path) -> None:
    for t in load_suite(f"smart-llm:{peers}").tasks:
        t.check()


def test_get_task_through_a_path_with_slashes(peers: Path) -> None:
    t = get_task(f"smart-llm:{peers}/FloorPlan21-1")
    assert goal_text(t.goal) == ["inside(Mug, CoffeeMachine)"] and t.robots == ("1",)
    assert t.key == f"smart-llm:{peers}/FloorPlan21-1"


def test_one_file_can_be_imported_on_its_own(peers: Path) -> None:
    suite = import_smart_llm(peers / "final_test" / "FloorPlan6.json")
    assert [t.id for t in suite.tasks] == ["FloorPlan6-1", "FloorPlan6-2", "FloorPlan6-3"]


# ---- tolerance, on files written for the test ----------------------------------------------


BROKEN_FILE = "\n".join([
    '{"task": "Turn off the light", "robot list": [24], "object_states": [{"name": "LightSwitch", '
    '"contains": [], "state": "OFF"}],}',  # trailing comma
    '{"task": "Fridge open", "robot list": [1], "object_states": [{"name": "Fride", "contains": [], '
    '"state": "OPENED"}',  # typo and two missing closing brackets
    '{"task": "Cold apple", "robot list": [1, 2], "object_states": [{"name": "fridge", "contains": ["apple"], '
    '"state": null}], "trans": 0}',  # JSON null, lower case
    'this is not a record',
    '{"task": "Robots from elsewhere", "robot list": [1, 31], "object_states": [{"name": "Fridge", '
    '"contains": ["Apple"], "state": None}]}',
    '{"task": "Odd states", "robot list": [1], "object_states": [{"name": "Fridge", "contains": [], '
    '"state": "FROZEN"}, {"name": "Sofa", "contains": ["Apple"], "state": None}, '
    '{"name": "Apple", "contains": [], "state": "SLICED"}]}',
    '',
    '__import__("os").system("echo pwned")',
])


def test_tolerant_import_reports_problems_with_file_and_line(tmp_path: Path) -> None:
    folder = tmp_path / "tasks" / "kitchen"
    folder.mkdir(parents=True)
    (folder / "FloorPlan1_mine.json").write_text(BROKEN_FILE)
    (folder / "notes.json").write_text("{}")  # not a FloorPlanN*.json file: ignored
    suite = import_smart_llm(tmp_path / "tasks")
    ids = {t.id: t for t in suite.tasks}
    assert sorted(ids) == ["FloorPlan1_mine-1", "FloorPlan1_mine-2", "FloorPlan1_mine-3", "FloorPlan1_mine-6"]
    assert goal_text(ids["FloorPlan1_mine-2"].goal) == ["open(Fridge)"]
    assert "inserted a missing '}' at the end" in ids["FloorPlan1_mine-2"].notes
    assert goal_text(ids["FloorPlan1_mine-3"].goal) == ["inside(Apple, Fridge)"]
    assert goal_text(ids["FloorPlan1_mine-6"].goal) == ["sliced(Apple)"]
    where = "kitchen/FloorPlan1_mine.json"
    problems = "\n".join(suite.problems)
    assert f"{where}:4: not a record" in problems
    assert f"{where}:5: robot list [1, 31]" in problems and "1..28" in problems
    assert f"{where}:6: Fridge: unknown state 'FROZEN'" in problems
    assert f"{where}:6: inside(Apple, Sofa): FloorPlan1 has no Sofa" in problems
    assert f"{where}:8: not a record" in problems  # never evaluated as code
    assert len(suite.problems) == 5, suite.problems


def test_no_task_files_is_a_typed_error(tmp_path: Path) -> None:
    with pytest.raises(UnknownSuiteError, match="no FloorPlanN"):
        load_suite(f"smart-llm:{tmp_path}")
    with pytest.raises(UnknownSuiteError, match="does not exist"):
        load_suite(f"smart-llm:{tmp_path / 'missing'}")
    (tmp_path / "FloorPlan999.json").write_text('{"task": "x", "robot list": [1], "object_states": []}')
    suite = load_suite(f"smart-llm:{tmp_path}")
    assert suite.tasks == () and "FloorPlan999" in suite.problems[0]


def test_task_files_in_floor_plan_order(tmp_path: Path) -> None:
    for name in ("FloorPlan201.json", "FloorPlan15.json", "FloorPlan6.json", "floorplan2_b.json", "x.json"):
        (tmp_path / name).write_text("")
    assert [p.name for p in task_files(tmp_path)] == [
        "floorplan2_b.json", "FloorPlan6.json", "FloorPlan15.json", "FloorPlan201.json"]


# ---- the lenient record reader ------------------------------------------------------------


@pytest.mark.parametrize(("line", "value"), [
    ('{"a": None, "b": [1, 2,],}', {"a": None, "b": [1, 2]}),
    ('{"a": Null, "b": True, "c": false}', {"a": None, "b": True, "c": False}),
    ('{"a": [{"x": 1}, {"y": 2}', {"a": [{"x": 1}, {"y": 2}]}),
    ('{"s": [{"n": "Box"},{"n": "Sofa"}, "trans":0, "max_trans":0}', {"s": [{"n": "Box"}, {"n": "Sofa"}],
                                                                       "trans": 0, "max_trans": 0}),
    ('{"state": OFF}', {"state": "OFF"}),
    ('{"task": "unterminated', {"task": "unterminated"}),
    ('{"a": 1}},', {"a": 1}),
])
def test_repairs(line: str, value: object) -> None:
    parsed, repairs = read_record(line)
    assert parsed == value
    assert repairs or line.startswith('{"a": None')


def test_repairs_are_described() -> None:
    fixed, repairs = repair('{"s": [{"n": 1}, "t": 0')
    assert fixed == '{ "s" : [ { "n" : 1 } ] , "t" : 0 }'
    assert repairs == ["inserted a missing ']' before key \"t\"", "inserted a missing '}' at the end"]


@pytest.mark.parametrize("line", ['__import__("os")', '{"a": open("x")}', "[1, 2] + [3]", "{1: lambda: 2}"])
def test_code_is_never_evaluated(line: str) -> None:
    with pytest.raises(RecordSyntaxError):
        read_record(line)


def test_name_resolution() -> None:
    scene = load_scene("FloorPlan303")
    assert resolve_type("CellPhone ", scene) == ("CellPhone", "'CellPhone ' -> CellPhone")
    assert resolve_type("trash", scene)[0] == "GarbageCan"
    assert resolve_type("Labtop", scene)[0] == "Laptop"
    assert resolve_type("baseballbat", scene)[0] == "BaseballBat"
    assert resolve_type("TenisRacket", scene)[0] == "TennisRacket"  # close match in the scene
    assert resolve_type("Laptop", scene) == ("Laptop", None)
    assert resolve_type("Spaceship", scene)[0] is None
    assert resolve_type(None, scene)[0] is None


# ---- valid files read faithfully ------------------------------------------------------------


def _line(task: str, states: list[dict[str, object]], robots: tuple[int, ...] = (1, 2)) -> str:
    import json

    return json.dumps({"task": task, "robot list": list(robots), "object_states": states})


def test_strict_json_is_read_as_json_without_repairs() -> None:
    value, repairs = read_record('{"task": "wipe the table and\\/or the sink", "state": null, "ok": true}')
    assert value == {"task": "wipe the table and/or the sink", "state": None, "ok": True}
    assert repairs == []  # a valid null is not a repair


def test_a_valid_file_imports_without_repair_notes_and_unescapes(tmp_path: Path) -> None:
    (tmp_path / "FloorPlan1.json").write_text(
        '{"task": "Put the apple in the fridge and\\/or turn off the light", "robot list": [1, 2], '
        '"object_states": [{"name": "Fridge", "contains": ["Apple"], "state": null}, '
        '{"name": "LightSwitch", "contains": [], "state": "OFF"}]}\n')
    suite = import_smart_llm(tmp_path)
    (task,) = suite.tasks
    assert task.instruction == "Put the apple in the fridge and/or turn off the light"
    assert "repaired" not in task.notes and suite.problems == ()


def test_repeated_contained_items_are_counted(tmp_path: Path) -> None:
    # FloorPlan1 has two vases and one egg
    (tmp_path / "FloorPlan1.json").write_text("\n".join([
        _line("two vases and an apple in the fridge",
              [{"name": "Fridge", "contains": ["Vase", "Apple", "vase"], "state": None}]),
        _line("two eggs in the fridge, and the tomato",
              [{"name": "Fridge", "contains": ["Egg", "Egg", "Tomato"], "state": None}]),
    ]) + "\n")
    suite = import_smart_llm(tmp_path)
    tasks = {t.id: t for t in suite.tasks}
    assert goal_text(tasks["FloorPlan1-1"].goal) == ["inside(2 of Vase, Fridge)", "inside(Apple, Fridge)"]
    # the scene has one egg: asking for two is reported, not quietly made one
    assert goal_text(tasks["FloorPlan1-2"].goal) == ["inside(Tomato, Fridge)"]
    assert any(p.startswith("FloorPlan1.json:2: inside(2 of Egg, Fridge): FloorPlan1 has only 1 Egg")
               for p in suite.problems), suite.problems


def test_a_line_whose_goal_already_holds_is_a_problem_line(tmp_path: Path) -> None:
    # in FloorPlan1 the egg starts in the fridge and the light starts on
    (tmp_path / "FloorPlan1.json").write_text("\n".join([
        _line("keep the egg in the fridge with the light on",
              [{"name": "Fridge", "contains": ["Egg"], "state": None},
               {"name": "LightSwitch", "contains": [], "state": "ON"}]),
        _line("keep the egg in the fridge and turn off the light",
              [{"name": "Fridge", "contains": ["Egg"], "state": None},
               {"name": "LightSwitch", "contains": [], "state": "OFF"}]),
    ]) + "\n")
    suite = import_smart_llm(tmp_path)
    assert [t.id for t in suite.tasks] == ["FloorPlan1-2"]  # one condition left to do is a task
    (problem,) = suite.problems
    assert problem.startswith("FloorPlan1.json:1: every goal condition already holds at the start")
    assert "free success" in problem and "task skipped" in problem


def test_names_resolve_against_the_scene_first(tmp_path: Path) -> None:
    # FloorPlan301 (a bedroom) has a DeskLamp and no FloorLamp; FloorPlan1 has neither
    assert resolve_type("lamp", load_scene("FloorPlan301")) == ("DeskLamp", "'lamp' -> DeskLamp")
    assert resolve_type("Lamp", load_scene("FloorPlan1"))[0] == "FloorLamp"  # the alias, then validation
    (tmp_path / "FloorPlan301.json").write_text(
        _line("turn off the lamp", [{"name": "lamp", "contains": [], "state": "OFF"}], robots=(1,)) + "\n")
    suite = import_smart_llm(tmp_path)
    (task,) = suite.tasks
    assert goal_text(task.goal) == ["switched_off(DeskLamp)"]
    assert "'lamp' -> DeskLamp" in task.notes
