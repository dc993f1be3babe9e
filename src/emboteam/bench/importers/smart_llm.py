"""Import tasks in the SMART-LLM / MAT-THOR format (``emboteam ... --suite smart-llm:PATH``).

Every ``FloorPlanN*.json`` file beneath PATH holds one task per line::

    {"task": "Put apple in fridge and switch off the light", "robot list": [1, 2, 3],
     "object_states": [{"name": "Fridge", "contains": ["Apple"], "state": None},
                       {"name": "LightSwitch", "contains": [], "state": "OFF"}],
     "trans": 1, "max_trans": 1}

The floor plan comes from the file name, ``robot list`` indexes the 28 SMART-LLM profiles
(1-based, as :mod:`emboteam.world.robots` numbers them), and each ``object_states`` entry
becomes goal conditions: its ``state`` one condition (``OFF`` -> ``switched_off(LightSwitch)``),
each item type it ``contains`` one ``inside(Item, Name)`` (one condition per item type, so GCR
stays a share; see docs/metrics.md); an item listed twice is counted, ``["Egg", "Egg"]`` ->
``inside(2 of Egg, Fridge)``.

The files are hand-written: a line that is strict JSON is read as JSON, any other is repaired
leniently (:mod:`.lenient`); names are resolved against the scene's types first ("lamp" is the
DeskLamp of a room without a FloorLamp), then normalised ("CoffeeTable," -> CoffeeTable,
"cabinet" -> Cabinet, "trash" -> GarbageCan, "Labtop" -> Laptop). What cannot be used is
reported in :attr:`Suite.problems` as ``FILE:LINE: why`` and left out, never fatal: a line
without ground truth, or whose conditions all hold already at the start (a free success),
drops its task; an unusable entry drops its condition. A task with a condition the
simulator's rules or its team cannot achieve is kept as the peers wrote it and flagged
("kept: ...").
"""

from __future__ import annotations

import difflib
import re
from collections import Counter
from pathlib import Path
from typing import Any

from emboteam.bench.suite import Suite, UnknownSuiteError
from emboteam.errors import EmboTeamError
from emboteam.sim.capability import analyse_goal
from emboteam.task import BenchTask
from emboteam.world.catalogue import load_catalogue
from emboteam.world.checker import GoalValidationError, check_goal, validate_goal
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import robot_profile
from emboteam.world.scene import Scene, load_scene, normalize_floor_plan

from .lenient import RecordSyntaxError, read_record

_FILE = re.compile(r"^FloorPlan(\d+)\D.*\.json$|^FloorPlan(\d+)\.json$", re.IGNORECASE)

#: Names the peers use for AI2-THOR types (lower-case, letters only -> type).
NAME_ALIASES: dict[str, str] = {
    "trash": "GarbageCan", "trashcan": "GarbageCan", "garbage": "GarbageCan", "bin": "GarbageCan",
    "dustbin": "GarbageCan", "labtop": "Laptop", "tv": "Television", "phone": "CellPhone",
    "mobilephone": "CellPhone", "fridge": "Fridge", "refrigerator": "Fridge", "lamp": "FloorLamp",
    "sofa": "Sofa", "couch": "Sofa", "breadloaf": "Bread", "soap": "SoapBar", "remote": "RemoteControl",
}

#: SMART-LLM ground-truth states -> our predicates (upper-case, letters only).
STATE_PREDICATES: dict[str, Predicate] = {
    "ON": Predicate.switched_on, "TOGGLED": Predicate.switched_on, "TURNEDON": Predicate.switched_on,
    "OFF": Predicate.switched_off, "TURNEDOFF": Predicate.switched_off,
    "SLICED": Predicate.sliced, "BROKEN": Predicate.broken,
    "OPENED": Predicate.open, "OPEN": Predicate.open, "CLOSED": Predicate.closed,
    "COOKED": Predicate.cooked, "HOT": Predicate.hot, "COLD": Predicate.cold,
    "PICKED": Predicate.held, "PICKEDUP": Predicate.held, "HELD": Predicate.held,
    "CLEAN": Predicate.clean, "CLEANED": Predicate.clean, "WASHED": Predicate.clean,
    "DIRTY": Predicate.dirty, "FILLED": Predicate.filled,
}
_NO_STATE = {"", "NONE", "NULL"}
_KNOWN_KEYS = {"task", "robot list", "object_states", "trans", "max_trans"}


def task_files(path: Path) -> list[Path]:
    """The FloorPlanN*.json files at or beneath ``path``, in floor-plan order."""
    if not path.exists():
        raise UnknownSuiteError(f"smart-llm: {path} does not exist")
    files = [path] if path.is_file() else [p for p in path.rglob("*.json") if p.is_file()]
    files = [p for p in files if _FILE.match(p.name)]
    if not files:
        raise UnknownSuiteError(f"smart-llm: no FloorPlanN*.json task files at or beneath {path}")
    return sorted(files, key=lambda p: (_floor_number(p), str(p)))


def _floor_number(p: Path) -> int:
    m = _FILE.match(p.name)
    assert m is not None
    return int(m.group(1) or m.group(2))


def resolve_type(raw: object, scene: Scene) -> tuple[str | None, str | None]:
    """(AI2-THOR type, note on the repair) for a peer's name, or (None, why not).

    The scene's own types are tried first, so a generic name means what the floor plan
    holds: "lamp" is the DeskLamp of a room that has a DeskLamp and no FloorLamp. Only a
    name the scene cannot explain falls back to the aliases and the whole catalogue (and
    then :func:`validate_goal` says the scene lacks it)."""
    if not isinstance(raw, str) or not raw.strip():
        return None, f"not a name: {raw!r}"
    letters = re.sub(r"[^A-Za-z]", "", raw)
    key = letters.lower()
    if not key:
        return None, f"not a name: {raw!r}"
    present = sorted(scene.types())
    by_lower = {t.lower(): t for t in present}
    by_lower_all = {t.lower(): t for t in load_catalogue().types}
    alias = NAME_ALIASES.get(key)
    # a generic word the scene's types end with ("lamp" -> DeskLamp, "table" -> SideTable)
    endings = [t for t in present if t.lower().endswith(key)]
    found = (by_lower.get(key)
             or (alias if alias in by_lower.values() else None)
             or (endings[0] if len(endings) == 1 else None)
             or (alias if alias in endings else None)
             or alias or by_lower_all.get(key))
    if found is None:
        close = difflib.get_close_matches(key, list(by_lower), n=1, cutoff=0.8)
        found = by_lower[close[0]] if close else None
    if found is None:
        return None, f"unknown object name {raw!r}"
    return found, (None if found == raw else f"{raw!r} -> {found}")


def _conditions(entry: object, scene: Scene, where: str, problems: list[str],
                notes: list[str]) -> list[Condition]:
    """One object_states entry -> its conditions; what it cannot use goes to problems."""
    if not isinstance(entry, dict):
        problems.append(f"{where}: object_states entry {entry!r} is not an object; ignored")
        return []
    name, note = resolve_type(entry.get("name"), scene)
    if name is None:
        problems.append(f"{where}: {note}; entry ignored")
        return []
    if note:
        notes.append(note)
    out: list[Condition] = []
    raw_state = entry.get("state")
    state = re.sub(r"[^A-Za-z]", "", str(raw_state)).upper() if raw_state is not None else ""
    if state not in _NO_STATE:
        pred = STATE_PREDICATES.get(state)
        if pred is None:
            problems.append(f"{where}: {name}: unknown state {raw_state!r}; condition ignored")
        else:
            out.append(Condition(predicate=pred, subject=ObjectRef(types=(name,))))
    contains = entry.get("contains") or []
    if not isinstance(contains, list):
        problems.append(f"{where}: {name}: 'contains' is not a list ({contains!r}); ignored")
        contains = []
    wanted: Counter[str] = Counter()  # a repeated item means that many of it: ["Egg", "Egg"]
    for item in contains:
        item_type, item_note = resolve_type(item, scene)
        if item_type is None:
            problems.append(f"{where}: {name} contains {item_note}; condition ignored")
            continue
        if item_note:
            notes.append(item_note)
        wanted[item_type] += 1
    for item_type, count in wanted.items():
        out.append(Condition(predicate=Predicate.inside, subject=ObjectRef(types=(item_type,)),
                             receptacle=ObjectRef(types=(name,)), count=count))
    if not out and state in _NO_STATE and not contains:
        problems.append(f"{where}: {name}: no state and contains nothing: nothing to check; entry ignored")
    usable: list[Condition] = []
    for cond in out:
        try:
            validate_goal(Goal(conditions=(cond,)), scene)
        except GoalValidationError as exc:
            problems.append(f"{where}: {exc}; condition ignored")
            continue
        if str(cond) not in {str(c) for c in usable}:
            usable.append(cond)
    return usable


def _task(record: Any, *, task_id: str, suite: str, scene: Scene, where: str,
          problems: list[str], repairs: list[str]) -> BenchTask | None:
    if not isinstance(record, dict):
        problems.append(f"{where}: not a task record ({type(record).__name__}); line skipped")
        return None
    instruction = record.get("task")
    if not isinstance(instruction, str) or not instruction.strip():
        problems.append(f"{where}: no 'task' instruction; line skipped")
        return None
    unknown = sorted(set(record) - _KNOWN_KEYS)
    notes: list[str] = [f"repaired: {'; '.join(repairs)}"] if repairs else []
    if unknown:
        notes.append(f"ignored fields {unknown}")
    robots = record.get("robot list")
    if not isinstance(robots, list) or not robots:
        problems.append(f"{where}: no 'robot list'; task skipped")
        return None
    try:
        team = tuple(str(robot_profile(r).number) for r in robots)
    except EmboTeamError as exc:
        problems.append(f"{where}: robot list {robots}: {exc}; task skipped")
        return None
    states = record.get("object_states")
    if not isinstance(states, list) or not states:
        why = "no 'object_states'" if states is None else "empty 'object_states'"
        problems.append(f"{where}: {why}: no ground truth to score; task skipped")
        return None
    name_notes: list[str] = []
    conditions: list[Condition] = []
    for entry in states:
        for c in _conditions(entry, scene, where, problems, name_notes):
            if str(c) not in {str(k) for k in conditions}:
                conditions.append(c)
    if not conditions:
        problems.append(f"{where}: no usable goal condition; task skipped")
        return None
    if name_notes:
        notes.append("names: " + ", ".join(dict.fromkeys(name_notes)))
    if "trans" in record or "max_trans" in record:
        notes.append(f"peer transfers: trans={record.get('trans')} max_trans={record.get('max_trans')}")
    task = BenchTask(id=task_id, suite=suite, floor_plan=scene.floor_plan, robots=team,
                     category="imported", instruction=instruction.strip(),
                     goal=Goal(conditions=tuple(conditions)), notes="; ".join(notes))
    if check_goal(task.goal, task.initial_state()).success:
        problems.append(f"{where}: every goal condition already holds at the start in {task.floor_plan} "
                        f"({', '.join(str(c) for c in conditions)}): it would score as a free success; "
                        "task skipped")
        return None
    _flag_unachievable(task, where, problems)
    return task


def _flag_unachievable(task: BenchTask, where: str, problems: list[str]) -> None:
    """Keep the peers' ground truth, but say when the rules or the team rule it out."""
    analysis = analyse_goal(task.goal, task.initial_state())
    team = task.team()
    for c in analysis.conditions:
        if not c.methods:
            problems.append(f"{where}: kept: {c.condition} cannot be achieved under AI2-THOR's rules "
                            f"in {task.floor_plan}")
        elif c.team_method(team) is None:
            gaps = "; ".join(c.gap(r) for r in team)
            problems.append(f"{where}: kept: team {','.join(task.robots)} cannot achieve {c.condition} ({gaps})")


def import_smart_llm(path: Path, *, suite: str | None = None) -> Suite:
    """Every task of every FloorPlanN*.json file at or beneath ``path``."""
    suite_name = suite or f"smart-llm:{path}"
    root = path if path.is_dir() else path.parent
    tasks: list[BenchTask] = []
    problems: list[str] = []
    stems = [p.stem for p in task_files(path)]
    for file in task_files(path):
        rel = file.relative_to(root).as_posix()
        try:
            scene = load_scene(normalize_floor_plan(_floor_number(file)))
        except EmboTeamError as exc:
            problems.append(f"{rel}: {exc}; file skipped")
            continue
        prefix = file.stem if stems.count(file.stem) == 1 else rel.removesuffix(".json").replace("/", ".")
        for lineno, line in enumerate(file.read_text(encoding="utf-8", errors="replace").splitlines(), start=1):
            if not line.strip():
                continue
            where = f"{rel}:{lineno}"
            try:
                record, repairs = read_record(line)
            except RecordSyntaxError as exc:
                problems.append(f"{where}: {exc}; line skipped")
                continue
            task = _task(record, task_id=f"{prefix}-{lineno}", suite=suite_name, scene=scene,
                         where=where, problems=problems, repairs=repairs)
            if task is not None:
                tasks.append(task)
    return Suite(name=suite_name, tasks=tuple(tasks), problems=tuple(problems))
