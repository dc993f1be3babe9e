"""Parse accuracy of the offline parser on its instruction sets, goal validity and the
oracle front end (parse speed is measured by benchmarks/offline_speed.py).

- tests/data/offline_dev.jsonl: the development set (tuned against);
- tests/data/offline_heldout.jsonl: written in other styles (terse, chatty, indirect,
  typos) and never tuned against;
- SMART-LLM's 36 test tasks, read from ../shared (never shipped): the final held-out check.

Run with ``-s`` to see the numbers; docs/offline_parser.md records them.
"""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path
from typing import Any

import pytest

import shared_data
from emboteam.bench.offline_accuracy import Outcome, evaluate, goal_keys, initial_state, load_records
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline import lexicon as lx
from emboteam.pfg.oracle import OracleFrontend, OracleGoalError
from emboteam.world.catalogue import load_catalogue
from emboteam.world.checker import validate_goal
from emboteam.world.goals import Condition, Goal, ObjectRef, Predicate
from emboteam.world.robots import parse_team
from emboteam.world.scene import load_scene
from emboteam.world.state import WorldState

DATA = Path(__file__).parent / "data"
SMART_LLM = shared_data.SMART_LLM / "final_test"


def _report(name: str, outcomes: list[Outcome]) -> float:
    ok = sum(o.correct for o in outcomes)
    print(f"\n{name}: {ok}/{len(outcomes)} = {ok / len(outcomes):.3f}")
    for o in outcomes:
        if not o.correct:
            print(f"  MISS {o.id}: {o.instruction}\n       expected {o.expected}\n       got      {o.got}")
    return ok / len(outcomes)


#: the phenomena of round 2 (docs/offline_parser.md), each with its own dev examples
PHENOMENA = ("locative-modifier", "motion-predicate", "vague-umbrella", "verbless-states",
             "desire-result", "discourse-reference", "universal-quantifier", "dark-light",
             "measure-noun", "instrument", "light-verb", "verb-particle",
             "politeness-justification")


def test_dev_set_accuracy() -> None:
    records = load_records(DATA / "offline_dev.jsonl")
    assert len(records) >= 450
    assert len({r["scene"] for r in records}) >= 40
    tags = [r.get("phenomenon") for r in records]
    assert all(tags.count(p) >= 5 for p in PHENOMENA)
    assert _report("dev", evaluate(records)) >= 0.97


def test_heldout_set_accuracy() -> None:
    records = load_records(DATA / "offline_heldout.jsonl")
    assert len(records) >= 60
    # floor below the measured accuracy (docs/offline_parser.md): a regression guard, not a target
    assert _report("held-out", evaluate(records)) >= 0.85


def test_every_parsed_goal_is_valid_in_its_scene() -> None:
    """Whatever the parser grounds, the goal checker accepts: types the scene has, with the
    properties the predicates need, counts it can meet."""
    frontend = OfflineFrontend()
    checked = 0
    for path in ("offline_dev.jsonl", "offline_heldout.jsonl"):
        for rec in load_records(DATA / path):
            if "error" in rec:
                continue
            scene = load_scene(str(rec["scene"]))
            team = parse_team(str(rec.get("robots", "1,2,3")))
            try:
                spec = frontend.decompose(str(rec["instruction"]), scene,
                                          initial_state(rec, scene, team), team)
            except Exception:   # accuracy tests report misses; validity is about what parses
                continue
            for sub in spec.subtasks:
                validate_goal(Goal(conditions=sub.goal), scene)
            checked += 1
    assert checked >= 150


# ---- SMART-LLM's test set (peer data, read from ../shared) --------------------------------
_STATES = {"SLICED": Predicate.sliced, "ON": Predicate.switched_on, "OFF": Predicate.switched_off,
           "HOT": Predicate.hot, "COOKED": Predicate.cooked, "OPENED": Predicate.open,
           "OPEN": Predicate.open, "CLOSED": Predicate.closed, "PICKED": Predicate.held,
           "BROKEN": Predicate.broken, "COLD": Predicate.cold, "CLEAN": Predicate.clean,
           "DIRTY": Predicate.dirty, "FILLED": Predicate.filled}


def _load_line(line: str) -> dict[str, Any] | None:
    """One record of the peer's files, which are not all valid JSON (Python None, trailing
    commas, missing closing brackets)."""
    text = line.strip().rstrip(",")
    if not text:
        return None
    text = text.replace(": None", ": null")
    # a list of object states left open before the next key
    closed = re.sub(r'\}\s*,\s*"(trans|max_trans)"', r'}], "\1"', text)
    candidates = [text, closed, re.sub(r",\s*([}\]])", r"\1", text)]
    for extra in ("", "]", "}", "]}", "}]", "}]}", "]}]", "}]}}"):
        for c in list(candidates):
            candidates.append(c + extra)
    for c in candidates:
        for loader in (json.loads, ast.literal_eval):
            try:
                fixed = c.replace("None", "null") if loader is json.loads else c.replace("null", "None")
                value = loader(fixed)
            except (ValueError, SyntaxError):
                continue
            if isinstance(value, dict):
                return value
    raise AssertionError(f"unreadable SMART-LLM record: {text[:60]}...")


def _type_name(raw: str) -> str:
    """The peer's object names, typos and lower case included ("Labtop", "CoffeeTable,",
    "trash")."""
    name = re.sub(r"[^A-Za-z]", "", raw)
    cat = load_catalogue()
    if name in cat.types:
        return name
    for t in cat.types:
        if t.lower() == name.lower():
            return t
    concept = lx.nouns().get(name.lower())
    if concept is not None and concept.types:
        return concept.types[0]
    import difflib
    close = difflib.get_close_matches(name, list(cat.types), n=1, cutoff=0.7)
    assert close, raw
    return close[0]


def smart_llm_records() -> list[dict[str, Any]]:
    if not SMART_LLM.exists():
        pytest.skip(f"SMART-LLM peer data not available at {SMART_LLM}")
    out = []
    for path in sorted(SMART_LLM.glob("FloorPlan*.json")):
        fp = path.stem
        for k, line in enumerate(path.read_text().splitlines()):
            rec = _load_line(line)
            if rec is None:
                continue
            conds: list[Condition] = []
            for st in rec.get("object_states") or []:
                name = _type_name(str(st["name"]))
                contains = st.get("contains") or []
                counts: dict[str, int] = {}
                for item in contains:
                    counts[_type_name(str(item))] = counts.get(_type_name(str(item)), 0) + 1
                for item, n in counts.items():
                    conds.append(Condition(predicate=Predicate.inside, subject=ObjectRef(types=(item,)),
                                           receptacle=ObjectRef(types=(name,)), count=n))
                state = str(st.get("state") or "None").strip().upper()
                if state in _STATES:
                    conds.append(Condition(predicate=_STATES[state], subject=ObjectRef(types=(name,))))
            robots = rec.get("robot list") or [1, 2]
            out.append({"id": f"{fp}#{k + 1}", "scene": fp, "instruction": rec["task"],
                        "goal": [str(c) for c in conds],
                        "robots": ",".join(str(int(r)) for r in robots)})
    return out


def test_smart_llm_test_set_accuracy() -> None:
    records = smart_llm_records()
    assert len(records) == 36
    outcomes = evaluate(records)
    acc = _report("SMART-LLM", outcomes)
    # condition-level recall: how many ground-truth conditions the parse contains
    frontend = OfflineFrontend()
    found = total = 0
    for rec in records:
        scene = load_scene(rec["scene"])
        team = parse_team(rec["robots"])
        expected = goal_keys([Condition.parse(g) for g in rec["goal"]], scene)
        total += len(expected)
        try:
            spec = frontend.decompose(rec["instruction"], scene, WorldState.from_scene(scene, team), team)
        except Exception:
            continue
        found += len(expected & goal_keys(spec.goal().conditions, scene))
    print(f"SMART-LLM condition recall: {found}/{total} = {found / total:.3f}")
    # measured 0.750 (docs/offline_parser.md; 0.778 before "dark" also closed the blinds,
    # which its ground truth for "Make the kitchen dark" does not): a regression guard
    assert acc >= 0.7


# ---- the oracle front end -----------------------------------------------------------------
def test_oracle_returns_one_subtask_per_condition() -> None:
    goal = Goal.parse("inside(Apple, Fridge) & sliced(Bread) & off(LightSwitch) & sliced(Bread)")
    scene = load_scene(1)
    team = parse_team("1,2")
    spec = OracleFrontend(goal).decompose("whatever the text", scene, WorldState.from_scene(scene, team), team)
    assert [str(s.goal[0]) for s in spec.subtasks] == ["inside(Apple, Fridge)", "sliced(Bread)",
                                                       "switched_off(LightSwitch)"]
    assert all(s.robot is None and not s.depends_on and s.final for s in spec.subtasks)
    assert spec.goal() == Goal.parse("inside(Apple, Fridge) & sliced(Bread) & off(LightSwitch)")
    with pytest.raises(OracleGoalError):
        OracleFrontend(Goal(conditions=()))
