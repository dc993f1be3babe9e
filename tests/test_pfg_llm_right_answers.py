"""No right answer is refused: development tasks of every set (the blind rounds' styles:
corrections, exclusions, rules as facts, narratives, texting, non-native English,
transcripts, rambles, purposes; the offline sets; MACE-THOR) are answered with the RIGHT
TaskSpec, built from each task's ground truth, through a scripted OpenAI-compatible
server on loopback. The LLM front end must accept each first answer (one call, no
repair round), and the HP review must accept the same subtasks given back as a
correction: the checks and the review agree, and none fires on a right answer.

``EMBOTEAM_RIGHT_ANSWERS=all`` runs every development task (about 2,000; 20 minutes on
the shared machine) instead of the 162 chosen ones.
"""

from __future__ import annotations

import os
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from emboteam.bench.dev_corpus import DevTask, development_tasks
from emboteam.errors import EmboTeamError
from emboteam.hp.llm_stages import review_spec
from emboteam.llm import LLMClient, RetryPolicy, make_client
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.pfg.oracle import OracleFrontend
from emboteam.pfg.schema import DESCRIPTION_MAX, taskspec_from_answer, taskspec_to_answer
from emboteam.world.scene import load_scene
from llm_servers import Reply, ScriptedServer

DATA = Path(__file__).parent / "data"
FAST = RetryPolicy(max_attempts=1, base_delay=0.01, max_delay=0.02)
#: tasks taken from each set, in file order (every MACE-THOR task)
PER_SET = {"offline_dev": 12, "offline_dev_natural": 12, "mace-thor": 42}
PER_BLIND_ROUND = 3
@pytest.fixture(autouse=True)
def _key(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("OPENAI_API_KEY", "sk-test")


def chosen_tasks() -> list[DevTask]:
    taken: Counter[str] = Counter()
    out: list[DevTask] = []
    if os.environ.get("EMBOTEAM_RIGHT_ANSWERS") == "all":
        return development_tasks(DATA)
    for dev in development_tasks(DATA):
        if taken[dev.set] < PER_SET.get(dev.set, PER_BLIND_ROUND):
            taken[dev.set] += 1
            out.append(dev)
    return out


def right_answer(dev: DevTask) -> dict[str, Any]:
    """The ground truth in the answer form, as a strong model would write it: one subtask
    per condition, no robot (the planner combines members), a short description."""
    task = dev.task
    spec = OracleFrontend(task.goal).decompose(task.instruction, load_scene(task.floor_plan),
                                               task.initial_state(), task.team())
    answer = taskspec_to_answer(spec)
    for sub in answer["subtasks"]:
        sub["description"] = sub["description"][:DESCRIPTION_MAX]
    return {**answer, "clarification": None}


def answer_task(client: LLMClient, srv: ScriptedServer, dev: DevTask) -> list[str]:
    """What the front end and the review refused of the right answer (empty: nothing)."""
    task = dev.task
    scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
    answer = right_answer(dev)
    before = len(srv.requests)
    srv.push(Reply.answer(answer))
    problems: list[str] = []
    try:
        spec = LLMFrontend(client, avoid_set=dev.set).decompose(task.instruction, scene, state, team)
    except EmboTeamError as exc:
        return [f"pfg: {exc}"]
    if len(srv.requests) - before != 1:
        problems.append(f"pfg: {len(srv.requests) - before} calls")
    # the answer form names one receptacle type where a goal allows several ("Sofa|ArmChair"):
    # the right answer is then one of them
    said = taskspec_from_answer(answer, task.instruction, scene)
    if spec.goal() != said.goal():
        problems.append(f"pfg: got {spec.goal()}, answered {said.goal()}")
    srv.push(Reply.answer({"verdict": "corrected", "reason": "the same subtasks",
                           "subtasks": answer["subtasks"]}))
    review = review_spec(client, spec, task.instruction, scene, state, team, avoid_set=dev.set)
    if review.rejected is not None:
        problems.append(f"hp.validate: {review.rejected}")
    return problems


def test_the_suite_covers_every_development_set_with_at_least_100_tasks() -> None:
    tasks = chosen_tasks()
    sets = {d.set for d in tasks}
    assert len(tasks) >= 100
    assert {"offline_dev", "offline_dev_natural", "mace-thor"} <= sets
    assert sum(s.startswith("blind_r") for s in sets) >= 20


def test_right_answers_are_never_refused() -> None:
    tasks = chosen_tasks()
    refused: dict[str, list[str]] = {}
    with ScriptedServer("openai") as srv:
        client = make_client(srv.spec(), timeout=5, retry=FAST)
        for dev in tasks:
            problems = answer_task(client, srv, dev)
            if problems:
                refused[f"{dev.set}/{dev.task.id}: {dev.task.instruction}"] = problems
    assert refused == {}
    assert client.usage.calls == 2 * len(tasks)

