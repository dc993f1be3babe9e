"""Build ``src/emboteam/pfg/prompts/fewshot_corpus.json``: the development tasks with
ground truth as worked examples in the answer form, the pool the LLM front ends choose
their examples from by similarity (:func:`emboteam.pfg.fewshot.select_examples`).

One subtask per ground-truth condition (what the oracle front end gives), no robot (the
planner allocates), no dependencies; a description made from the condition. Every
answer is checked with the front end's own conversion (schema limits, scene) before it is
written; a task whose goal the answer form cannot say is left out and counted.

    .venv/bin/python benchmarks/build_fewshot_corpus.py [--data tests/data] [--out PATH]
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import jsonschema

from emboteam.bench.dev_corpus import development_tasks
from emboteam.llm.structured import Rejected
from emboteam.pfg.oracle import OracleFrontend
from emboteam.pfg.schema import (
    DESCRIPTION_MAX,
    SceneVocabulary,
    taskspec_from_answer,
    taskspec_schema,
    taskspec_to_answer,
)
from emboteam.world.goals import Condition, Predicate
from emboteam.world.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]

_VERB = {Predicate.inside: "Put {s} in {r}", Predicate.sliced: "Slice {s}", Predicate.switched_on: "Switch on {s}",
         Predicate.switched_off: "Switch off {s}", Predicate.open: "Open {s}", Predicate.closed: "Close {s}",
         Predicate.hot: "Heat {s}", Predicate.cold: "Chill {s}", Predicate.cooked: "Cook {s}",
         Predicate.clean: "Clean {s}", Predicate.dirty: "Leave {s} dirty", Predicate.filled: "Fill {s}",
         Predicate.broken: "Break {s}", Predicate.held: "Hold {s}"}


def describe(cond: Condition) -> str:
    subject = cond.subject.id or " or ".join(cond.subject.types)
    if cond.count > 1:
        subject = f"{cond.count} {subject}"
    receptacle = "" if cond.receptacle is None else (cond.receptacle.id or cond.receptacle.types[0])
    text = _VERB[cond.predicate].format(s=subject, r=receptacle) + "."
    return text if len(text) <= DESCRIPTION_MAX else text[:DESCRIPTION_MAX - 1] + "."


def build(data: Path) -> tuple[list[dict[str, Any]], int]:
    examples: list[dict[str, Any]] = []
    skipped = 0
    for dev in development_tasks(data):
        task = dev.task
        scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
        spec = OracleFrontend(task.goal).decompose(task.instruction, scene, state, team)
        answer = taskspec_to_answer(spec)
        for sub, raw in zip(spec.subtasks, answer["subtasks"], strict=True):
            raw["description"] = describe(sub.goal[0])
        try:
            jsonschema.validate(answer, taskspec_schema(SceneVocabulary.build(scene, state, team)))
            taskspec_from_answer(answer, task.instruction, scene)
        except (jsonschema.ValidationError, Rejected):
            skipped += 1
            continue
        examples.append({"set": dev.set, "floor_plan": task.floor_plan, "robots": ",".join(task.robots),
                         "instruction": task.instruction, "answer": answer})
    return examples, skipped


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=Path, default=ROOT / "tests" / "data")
    ap.add_argument("--out", type=Path, default=ROOT / "src" / "emboteam" / "pfg" / "prompts" / "fewshot_corpus.json")
    args = ap.parse_args(argv)
    examples, skipped = build(args.data)
    doc = {"about": "development tasks with their ground-truth goals in the answer form; built by "
                    "benchmarks/build_fewshot_corpus.py, do not edit", "examples": examples}
    args.out.write_text(json.dumps(doc, ensure_ascii=False, separators=(",", ":")) + "\n", encoding="utf-8")
    print(f"{len(examples)} examples written to {args.out} ({skipped} left out: not sayable in the answer form)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
