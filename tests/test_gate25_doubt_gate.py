"""The doubt gate (emboteam.pfg.doubt_gate): a reading whose own signals say it is in doubt
lets the local model score the top candidates even where the prior is sure; a sure reading
without those signals costs no call. Scores come from a cassette written here (the gate's
one request), so nothing is sent anywhere."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import pytest

from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.llm import make_client
from emboteam.llm.cassette import Cassette
from emboteam.llm.errors import LLMReplayMiss
from emboteam.llm.scoring import CandidateScore, ScoreRequest, ScoreResponse
from emboteam.pfg.doubt_gate import (
    SIGNALS,
    DoubtGate,
    GateRule,
    doubt_signals,
    gate_candidates,
    gate_request,
    only_drops,
)
from emboteam.pfg.hybrid import HybridFrontend
from emboteam.pfg.model_ranker import ModelRankerDataError, load_ranker_settings, objects_summary
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.reading import Reading
from emboteam.world.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]


def _task() -> Any:
    """A development task whose reading has several candidate readings."""
    return next(t for t in import_smart_llm(ROOT / "tests" / "data" / "blind_r6" / "dev").tasks
                if t.instruction.startswith("Heat the egg: crack it into the pan"))


def _sure(reading: Reading, unexplained: tuple[str, ...]) -> Reading:
    """The reading with a sure prior (every other candidate 8 below the first) and the
    given unexplained mentions."""
    first, *others = reading.candidates
    cands = (first, *(replace(c, score=first.score - 8.0 - i) for i, c in enumerate(others)))
    return replace(reading, candidates=cands, unexplained=unexplained)


def _gate() -> DoubtGate:
    return DoubtGate(rules={"mention": GateRule(signal="unexplained_mentions", at_least=1, fit="test")},
                     top_k=2, min_lead=1.0, weight=1.0, max_gap=20.0)


def _cassette(folder: Path, request: ScoreRequest, pmi: list[float]) -> str:
    scores = tuple(CandidateScore(sentence=s, conditional=-10.0 + v, unconditional=-10.0, tokens=8)
                   for s, v in zip(request.candidates, pmi, strict=True))
    store = Cassette(folder)
    store.open_for_recording("test:handmade")
    store.save_score(request, ScoreResponse(scores=scores, input_tokens=100, evaluated_tokens=40, model="m"))
    return f"replay:{folder}"


def _objects(scene: Any, instruction: str, reading: Reading) -> str:
    return objects_summary(scene, (instruction, *(c.sentence for c in reading.candidates)))


def _setup(unexplained: tuple[str, ...]) -> tuple[Any, Any, Any, Any, Reading]:
    task = _task()
    scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
    reading = _sure(OfflineFrontend().parse(task.instruction, scene, state, team), unexplained)
    assert len(gate_candidates(reading.candidates, 2)) == 2
    return task, scene, state, team, reading


def test_an_unexplained_mention_opens_the_gate_and_the_model_may_overturn_a_sure_prior(tmp_path: Path) -> None:
    task, scene, state, team, reading = _setup(("the pan",))
    assert doubt_signals(reading, task.instruction, state)["unexplained_mentions"] == 1.0
    request = gate_request(reading.candidates, _objects(scene, task.instruction, reading), task.instruction, 2)
    assert request is not None
    client = make_client(_cassette(tmp_path, request, [0.0, 9.0]))     # the second leads by 9 > 8 + 1
    hybrid = HybridFrontend(client, lambda *_: reading, when="close")
    hybrid.doubt_gate = _gate()
    got = hybrid.read(task.instruction, scene, state, team)
    assert client.usage.calls == 1
    assert hybrid.last_ranking is not None and hybrid.last_ranking.overturned
    second = gate_candidates(reading.candidates, 2)[1]
    assert got.spec == second.spec
    note = next(n for n in got.notes if n.span == "(model ranking)")
    assert "mention" in note.reason


def test_a_small_lead_does_not_overturn_a_sure_prior(tmp_path: Path) -> None:
    """The gate lets the model speak, not decide alone: prior + weight * PMI still orders,
    and the lead must pass the gate's ``min_lead``."""
    task, scene, state, team, reading = _setup(("the pan",))
    request = gate_request(reading.candidates, _objects(scene, task.instruction, reading), task.instruction, 2)
    assert request is not None
    client = make_client(_cassette(tmp_path, request, [0.0, 5.0]))     # 5 < the prior's 8
    hybrid = HybridFrontend(client, lambda *_: reading, when="close")
    hybrid.doubt_gate = _gate()
    got = hybrid.read(task.instruction, scene, state, team)
    assert client.usage.calls == 1 and got.spec == reading.spec
    assert hybrid.last_ranking is not None and not hybrid.last_ranking.overturned


def test_a_sure_reading_without_doubt_signals_costs_no_call(tmp_path: Path) -> None:
    task, scene, state, team, reading = _setup(())
    Cassette(tmp_path).open_for_recording("test:handmade")
    client = make_client(f"replay:{tmp_path}")          # an empty cassette: any call is a miss
    hybrid = HybridFrontend(client, lambda *_: reading, when="close")
    hybrid.doubt_gate = _gate()
    assert hybrid.read(task.instruction, scene, state, team).spec == reading.spec
    assert client.usage.calls == 0
    # the same reading with a mention left unexplained asks (and the empty cassette misses)
    doubtful = replace(reading, unexplained=("the pan",))
    asks = HybridFrontend(client, lambda *_: doubtful, when="close")
    asks.doubt_gate = _gate()
    with pytest.raises(LLMReplayMiss):
        asks.read(task.instruction, scene, state, team)


def test_gate_settings_are_data_checked_at_load(tmp_path: Path) -> None:
    shipped = load_ranker_settings()
    assert all(r.fit for r in shipped.doubt_gate.rules.values())
    bad = tmp_path / "model_ranker.json"
    bad.write_text('{"fitted": "x", "margin": 1.0, "weight": 1.0, "doubt_gate": {"top_k": 9}}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"entry doubt_gate\.top_k"):
        load_ranker_settings(bad)
    bad.write_text('{"fitted": "x", "margin": 1.0, "weight": 1.0, "doubt_gate": {"rules": {"r": '
                   '{"signal": "nonsense", "fit": "x"}}}}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"signal"):
        load_ranker_settings(bad)


def test_a_reading_that_only_leaves_clauses_out_is_a_drop() -> None:
    first = ("The egg is cooked.", "The egg is in the pan.")
    assert only_drops(first, ("The egg is cooked.",))
    assert not only_drops(first, first)                       # the same clauses: no drop
    assert not only_drops(first, ("The egg is cooked.", "The pan is on the stove."))     # a swap


def test_the_shipped_gate_follows_its_stated_rule_on_the_committed_records() -> None:
    """benchmarks/doubt_gate/records.jsonl holds the development tasks' signals, candidates
    and the model's recorded scores: the rules shipped in pfg/model_ranker.json are exactly
    those the stated rule (doubt_gate_dev.MIN_RIGHT) lets through on them."""
    import sys

    sys.path.insert(0, str(ROOT / "benchmarks"))  # benchmarks/ is no package
    from doubt_gate_dev import RECORDS, THRESHOLDS, merged, rule_outcome

    rows = merged([RECORDS])
    gate = load_ranker_settings().doubt_gate
    assert rows and any(r["pmi"] is not None for r in rows)
    assert {r["round"] for r in rows} <= {"r40", "r41", "r43", "r45", "r47", "r49", "r51", "r53", "r55", "r57"}
    for name, rule in gate.rules.items():
        assert rule_outcome(rows, rule.signal, rule.at_least, gate)["ships"], name
    tried = [rule_outcome(rows, s, t, gate) for s in SIGNALS for t in THRESHOLDS]
    shipped = {f"{r.signal}>={r.at_least:g}" for r in gate.rules.values()}
    assert {o["rule"] for o in tried if o["ships"]} == shipped
