"""The model ranker (emboteam.pfg.model_ranker): the model is asked only where the prior is
unsure, re-ranks only the close candidates, and its scores come back through the client
(budget, ledger, cassettes). Scores are served by the replay backend from a cassette
written here, so the numbers are known; a backend without log-probabilities (Anthropic,
on a loopback server) is refused before anything is sent."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from emboteam.llm import make_client
from emboteam.llm.cassette import Cassette
from emboteam.llm.errors import LLMScoringUnsupported
from emboteam.llm.scoring import CandidateScore, ScoreRequest, ScoreResponse
from emboteam.pfg.model_ranker import close_count, objects_summary, rerank, rerank_in_scene
from emboteam.world.scene import load_scene
from llm_servers import ScriptedServer


@dataclass(frozen=True)
class Reading:
    """Anything with a sentence and a prior satisfies the ranker's protocol."""

    sentence: str
    score: float


INSTRUCTION = "put the tomato in the microwave, no wait, the fridge"
OBJECTS = "fridge, microwave, tomato"
MICROWAVE = Reading("The tomato is in the microwave.", -0.2)
FRIDGE = Reading("The tomato is in the fridge.", -0.5)
BOTH = Reading("The tomato is in the microwave and the fridge is open.", -0.9)
FAR = Reading("The fridge is open.", -4.0)


def cassette(folder: Path, pmi: dict[str, float], objects: str = OBJECTS) -> str:
    """A cassette answering the one request the ranker should make, with these PMIs."""
    request = ScoreRequest(objects=objects, instruction=INSTRUCTION, candidates=tuple(pmi))
    scores = tuple(CandidateScore(sentence=s, conditional=-10.0 + v, unconditional=-10.0, tokens=8)
                   for s, v in pmi.items())
    store = Cassette(folder)
    store.open_for_recording("test:handmade")
    store.save_score(request, ScoreResponse(scores=scores, input_tokens=100, evaluated_tokens=40, model="m"))
    return f"replay:{folder}"


def test_close_candidates_are_reranked_by_prior_plus_weighted_pmi(tmp_path: Path) -> None:
    client = make_client(cassette(tmp_path, {MICROWAVE.sentence: 1.0, FRIDGE.sentence: 3.0, BOTH.sentence: 0.5}))
    result = rerank([MICROWAVE, FRIDGE, BOTH, FAR], client=client, objects=OBJECTS, instruction=INSTRUCTION,
                    margin=1.0, weight=0.5)
    assert result.scored and result.overturned
    assert result.candidates == (FRIDGE, MICROWAVE, BOTH, FAR)
    assert [r.combined for r in result.ranked] == pytest.approx([-0.5 + 1.5, -0.2 + 0.5, -0.9 + 0.25, -4.0])
    assert result.ranked[-1].pmi is None  # beyond the margin: not scored, stays last
    assert client.usage.calls == 1 and client.usage.input_tokens == 100


def test_a_small_weight_keeps_the_prior_and_records_the_model(tmp_path: Path) -> None:
    client = make_client(cassette(tmp_path, {MICROWAVE.sentence: 1.0, FRIDGE.sentence: 3.0, BOTH.sentence: 0.5}))
    result = rerank([MICROWAVE, FRIDGE, BOTH, FAR], client=client, objects=OBJECTS, instruction=INSTRUCTION,
                    margin=1.0, weight=0.1)
    assert result.scored and not result.overturned
    assert result.candidates == (MICROWAVE, FRIDGE, BOTH, FAR)
    assert [r.pmi for r in result.ranked[:3]] == pytest.approx([1.0, 3.0, 0.5])
    assert result.ranked[0].to_json() == {"sentence": MICROWAVE.sentence, "prior": -0.2, "pmi": 1.0,
                                          "combined": 1.0 * 0.1 - 0.2}


def test_a_sure_prior_costs_no_call(tmp_path: Path) -> None:
    # an empty cassette: any call would be a replay miss
    Cassette(tmp_path).open_for_recording("test:handmade")
    client = make_client(f"replay:{tmp_path}")
    result = rerank([MICROWAVE, FAR], client=client, objects=OBJECTS, instruction=INSTRUCTION, margin=1.0,
                    weight=1.0)
    assert not result.scored and result.candidates == (MICROWAVE, FAR)
    assert client.usage.calls == 0
    one = rerank([MICROWAVE], client=client, objects=OBJECTS, instruction=INSTRUCTION, margin=9.0, weight=1.0)
    assert not one.scored and client.usage.calls == 0
    # close, but said the same way: the model cannot tell them apart
    same = Reading(MICROWAVE.sentence, -0.3)
    twins = rerank([MICROWAVE, same], client=client, objects=OBJECTS, instruction=INSTRUCTION, margin=1.0,
                   weight=1.0)
    assert not twins.scored and twins.candidates == (MICROWAVE, same) and client.usage.calls == 0


def test_close_count_is_measured_from_the_first() -> None:
    assert close_count([-0.2, -0.5, -0.9, -4.0], 1.0) == 3
    assert close_count([-0.2, -1.5], 1.0) == 1
    assert close_count([], 1.0) == 0


def test_a_backend_without_logprobs_is_refused_before_sending() -> None:
    with ScriptedServer("anthropic") as server:
        client = make_client(server.spec("claude-test"), timeout=5)
        with pytest.raises(LLMScoringUnsupported, match="no token log-probabilities"):
            rerank([MICROWAVE, FRIDGE], client=client, objects=OBJECTS, instruction=INSTRUCTION, margin=1.0,
                   weight=1.0)
        assert server.requests == [] and client.usage.calls == 0


def test_the_objects_summary_names_the_scene_types_the_texts_mention() -> None:
    scene = load_scene("FloorPlan1")
    assert objects_summary(scene, ("put the tomato in the fridge", "The tomato is in the microwave.")) == \
        "fridge, microwave, tomato"
    everything = objects_summary(scene)
    assert "coffee machine" in everything and "floor" not in everything.split(", ")
    assert objects_summary(scene, ("do the thing",)) == everything  # nothing named: all of them


# ---- wired into the hybrid front end ----------------------------------------------------

def _dev_task(round_: str, start: str) -> Any:
    from emboteam.bench.importers.smart_llm import import_smart_llm

    root = Path(__file__).resolve().parents[1]
    return next(t for t in import_smart_llm(root / "tests" / "data" / round_ / "dev").tasks
                if t.instruction.startswith(start))


def _satisfies() -> Any:
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # benchmarks/ is no package
    from fit_reading_priors import satisfies

    return satisfies


def test_hybrid_lets_the_model_settle_close_readings() -> None:
    """A development task whose reading as read is wrong and a close candidate right: with
    the recorded Qwen 0.5B scores (benchmarks/pmi_dev) the hybrid front end takes the right
    one, in one scoring call and no review; with the model's weight at 0, or a backend
    without log-probabilities, the reading as read stands."""
    from emboteam.bench.offline_accuracy import goal_keys
    from emboteam.pfg.hybrid import HybridFrontend
    from emboteam.pfg.offline import OfflineFrontend

    task = _dev_task("blind_r6", "Heat the egg: crack it into the pan")
    scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
    truth = goal_keys(task.ground_truth.conditions, scene)
    satisfies = _satisfies()
    reader = OfflineFrontend()
    draft = reader.parse(task.instruction, scene, state, team)
    assert not satisfies(goal_keys(draft.spec.goal().conditions, scene), truth)

    root = Path(__file__).resolve().parents[1]
    client = make_client(f"replay:{root / 'benchmarks' / 'pmi_dev' / 'cassette'}")
    # the right reading's prior is 0.93 below the first: within a margin of 2 (the fitted
    # margin, pfg/model_ranker.json, is narrower and leaves this task to the prior)
    hybrid = HybridFrontend(client, reader.parse, rank_margin=2.0)
    reading = hybrid.read(task.instruction, scene, state, team)
    assert satisfies(goal_keys(reading.spec.goal().conditions, scene), truth)
    assert hybrid.last_ranking is not None and hybrid.last_ranking.overturned
    assert reading.candidates[0].spec == reading.spec
    assert any(n.span == "(model ranking)" for n in reading.notes)
    assert client.usage.calls == 1 and "pfg.score" in client.usage.by_stage()

    off = HybridFrontend(client, reader.parse, rank_margin=2.0, rank_weight=0.0)
    assert off.read(task.instruction, scene, state, team).spec == draft.spec
    with ScriptedServer("anthropic") as server:
        anthropic = HybridFrontend(make_client(server.spec("claude-test"), timeout=5), reader.parse, rank_margin=2.0)
        assert anthropic.read(task.instruction, scene, state, team).spec == draft.spec
        assert server.requests == []


def test_a_scoring_time_out_leaves_the_prior_reading_and_says_so(monkeypatch: pytest.MonkeyPatch) -> None:
    """The model only settles close calls: when its scoring times out (a loaded machine)
    the task goes on with the prior's first reading, marked unsure with the reason; a
    replay miss stays loud (the cassette does not cover the run)."""
    from emboteam.llm.errors import LLMReplayMiss, LLMTimeout
    from emboteam.pfg.hybrid import HybridFrontend
    from emboteam.pfg.offline import OfflineFrontend

    task = _dev_task("blind_r6", "Heat the egg: crack it into the pan")
    scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
    reader = OfflineFrontend()
    draft = reader.parse(task.instruction, scene, state, team)
    root = Path(__file__).resolve().parents[1]
    client = make_client(f"replay:{root / 'benchmarks' / 'pmi_dev' / 'cassette'}")

    def time_out(request: object) -> None:
        raise LLMTimeout("scoring outlived the 5 s time-out", stage="pfg.score")

    monkeypatch.setattr(client, "score", time_out)
    reading = HybridFrontend(client, reader.parse, rank_margin=2.0).read(task.instruction, scene, state, team)
    assert reading.spec == draft.spec
    note = next(n for n in reading.notes if n.span == "(model ranking)")
    assert note.kind == "unsure" and "LLMTimeout" in note.reason

    def miss(request: object) -> None:
        raise LLMReplayMiss("no recorded score", stage="pfg.score")

    monkeypatch.setattr(client, "score", miss)
    with pytest.raises(LLMReplayMiss):
        HybridFrontend(client, reader.parse, rank_margin=2.0).read(task.instruction, scene, state, team)


def test_ranker_settings_load_and_a_bad_file_is_named(tmp_path: Path) -> None:
    """The hybrid front end's margin, weight and PMI lead are data: the shipped file loads,
    and a misspelt entry or a negative weight is a ModelRankerDataError naming the file
    and the entry (not a traceback from deep inside a run)."""
    from emboteam.errors import EmboTeamError
    from emboteam.pfg.model_ranker import ModelRankerDataError, load_ranker_settings

    shipped = load_ranker_settings()
    assert shipped.margin >= 0 and shipped.weight >= 0 and shipped.fitted
    bad = tmp_path / "model_ranker.json"
    bad.write_text('{"fitted": "x", "margin": 1.0, "weight": -1.0}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"model_ranker\.json: entry weight"):
        load_ranker_settings(bad)
    bad.write_text('{"fitted": "x", "margin": 1.0, "weight": 1.0, "min_led": 2.0}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"entry min_led"):
        load_ranker_settings(bad)
    bad.write_text("{", encoding="utf-8")
    with pytest.raises(EmboTeamError, match=r"cannot read the model ranker's settings"):
        load_ranker_settings(bad)


def test_min_lead_keeps_the_priors_first_unless_the_model_leads_clearly(tmp_path: Path) -> None:
    """With a PMI lead required, a close candidate the model prefers by less than the lead
    does not overturn the prior's first; one it prefers by more does."""
    client = make_client(cassette(tmp_path, {MICROWAVE.sentence: 1.0, FRIDGE.sentence: 3.0, BOTH.sentence: 0.5}))
    args: dict[str, Any] = {"client": client, "objects": OBJECTS, "instruction": INSTRUCTION, "margin": 1.0,
                            "weight": 0.5}
    held = rerank([MICROWAVE, FRIDGE, BOTH, FAR], **args, min_lead=2.5)   # FRIDGE leads by 2.0
    assert held.scored and not held.overturned
    assert held.candidates[0] == MICROWAVE and held.ranked[0].pmi == pytest.approx(1.0)
    taken = rerank([MICROWAVE, FRIDGE, BOTH, FAR], **args, min_lead=1.5)
    assert taken.overturned and taken.candidates == (FRIDGE, MICROWAVE, BOTH, FAR)


# ---- which kinds of doubt the model may judge (pfg/model_ranker.json "kinds") -----------

@dataclass(frozen=True)
class Settled:
    """A reading with the kinds of doubt it settles other than as read."""

    sentence: str
    score: float
    kinds: frozenset[str] = frozenset()


def _settings(**kinds: dict[str, Any]) -> Any:
    from emboteam.pfg.model_ranker import RankerSettings

    return RankerSettings.model_validate({"fitted": "test", "margin": 1.0, "weight": 1.0, "min_lead": 1.0,
                                          "kinds": {k: {"fit": "test", **v} for k, v in kinds.items()}})


def test_a_kind_the_model_may_not_judge_is_left_to_the_prior_without_a_call(tmp_path: Path) -> None:
    """A close reading that differs from the prior's first only in a kind of doubt the
    model lost on (here a correction) is not scored: with no other close reading the
    model is not asked at all, and the prior's first stands even though the recorded
    PMI would have overturned it; a kind it may judge is scored and can overturn."""
    settings = _settings(correction={"judge": False}, means={"judge": True})

    def lead_needed(first: Settled, other: Settled) -> float | None:
        return settings.lead_for(first.kinds ^ other.kinds)

    first = Settled(MICROWAVE.sentence, -0.2)
    corrected = Settled(FRIDGE.sentence, -0.5, frozenset({"correction"}))
    scene = load_scene("FloorPlan1")
    Cassette(tmp_path / "empty").open_for_recording("test:handmade")
    silent = make_client(f"replay:{tmp_path / 'empty'}")  # any call would be a replay miss
    held = rerank_in_scene([first, corrected], client=silent, scene=scene, instruction=INSTRUCTION,
                           margin=1.0, weight=1.0, lead_needed=lead_needed)
    assert not held.scored and held.candidates == (first, corrected) and silent.usage.calls == 0

    # the same two readings, the other one now differing by a means the model may judge
    meant = Settled(FRIDGE.sentence, -0.5, frozenset({"means"}))
    client = make_client(cassette(tmp_path / "scores", {MICROWAVE.sentence: 1.0, FRIDGE.sentence: 3.0}))
    taken = rerank_in_scene([first, meant, corrected], client=client, scene=scene, instruction=INSTRUCTION,
                            margin=1.0, weight=1.0, lead_needed=lead_needed)
    assert taken.overturned and taken.candidates == (meant, first, corrected)
    assert taken.ranked[-1].pmi is None and client.usage.calls == 1  # the correction: never scored


def test_a_per_kind_lead_and_a_reading_differing_in_two_kinds() -> None:
    """A kind's own ``min_lead`` replaces the file's; a reading differing in two kinds
    needs both allowed and the larger lead; a kind not listed, or no differing kind,
    leaves the call to the prior."""
    settings = _settings(means={"judge": True, "min_lead": 4.0}, next_place={"judge": True},
                         exclusion={"judge": False})
    assert settings.lead_for({"next_place"}) == 1.0         # the file's min_lead
    assert settings.lead_for({"means"}) == 4.0
    assert settings.lead_for({"means", "next_place"}) == 4.0
    assert settings.lead_for({"means", "exclusion"}) is None
    assert settings.lead_for({"a_kind_not_listed"}) is None
    assert settings.lead_for(()) is None
    assert _settings().lead_for({"anything"}) == 1.0         # no kinds listed: every kind


def test_per_kind_settings_are_checked_at_load(tmp_path: Path) -> None:
    """A misspelt or mistyped per-kind entry is a ModelRankerDataError naming the file and
    the entry, and every kind the shipped file names is a kind of doubt the reader has
    priors for (a renamed kind would silently stop being judged)."""
    from emboteam.pfg.model_ranker import ModelRankerDataError, load_ranker_settings
    from emboteam.pfg.offline.doubts.priors import load_priors

    head = '{"fitted": "x", "margin": 1.0, "weight": 1.0, "kinds": '
    bad = tmp_path / "model_ranker.json"
    bad.write_text(head + '{"means": {"jugde": true, "fit": "x"}}}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"model_ranker\.json: entry kinds\.means\.judge"):
        load_ranker_settings(bad)
    bad.write_text(head + '{"means": {"judge": "often", "fit": "x"}}}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"entry kinds\.means\.judge"):
        load_ranker_settings(bad)
    bad.write_text(head + '{"means": {"judge": true, "min_lead": -1, "fit": "x"}}}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"entry kinds\.means\.min_lead"):
        load_ranker_settings(bad)
    shipped = load_ranker_settings()
    assert shipped.kinds and shipped.kinds_rule
    assert set(shipped.kinds) <= set(load_priors().priors)
    assert not shipped.kinds["correction"].judge and not shipped.kinds["exclusion"].judge


def test_hybrid_obeys_the_fitted_kinds_on_recorded_scores() -> None:
    """Two development tasks with the recorded Qwen 0.5B scores (benchmarks/pmi_dev): on a
    self-correction the model prefers the rejected desk (PMI lead 5.5), but corrections are
    not a kind it may judge, so it is not asked and the right reading stands (with every
    kind allowed it would have overturned it); on a means ("in the microwave") it may
    judge, and it overturns the wrong reading as read to the right one."""
    from emboteam.bench.offline_accuracy import goal_keys
    from emboteam.pfg.hybrid import HybridFrontend
    from emboteam.pfg.offline import OfflineFrontend

    root = Path(__file__).resolve().parents[1]
    satisfies, reader = _satisfies(), OfflineFrontend()

    def read(round_: str, start: str, every_kind: bool = False) -> tuple[bool, Any]:
        task = _dev_task(round_, start)
        scene, state, team = load_scene(task.floor_plan), task.initial_state(), task.team()
        client = make_client(f"replay:{root / 'benchmarks' / 'pmi_dev' / 'cassette'}")
        hybrid = HybridFrontend(client, reader.parse, rank_margin=2.5)   # the recorded margin
        if every_kind:
            hybrid.rank_kinds = hybrid.rank_kinds.model_copy(update={"kinds": {}, "min_lead": 0.0})
        reading = hybrid.read(task.instruction, scene, state, team)
        truth = goal_keys(task.ground_truth.conditions, scene)
        return satisfies(goal_keys(reading.spec.goal().conditions, scene), truth), client

    right, client = read("blind_r31", "The teddy bear goes on the desk, no wait")
    assert right and client.usage.calls == 0
    right, client = read("blind_r31", "The teddy bear goes on the desk, no wait", every_kind=True)
    assert not right and client.usage.calls == 1
    right, client = read("blind_r39", "Heat the mug in the microwave")
    assert right and client.usage.calls == 1


def test_the_shipped_kinds_follow_the_stated_rule_on_the_committed_records() -> None:
    """pfg/model_ranker.json's judged kinds are what the rule of benchmarks/pmi_dev_rounds.py
    gives on the committed records of the fit rounds (r30-r45), and with them the shipped
    margin, weight and lead never overturn a right reading on those rounds: a hand edit
    of the file that breaks either shows here."""
    import json
    import sys

    from emboteam.pfg.model_ranker import load_ranker_settings

    root = Path(__file__).resolve().parents[1]
    sys.path.insert(0, str(root / "benchmarks"))  # benchmarks/ is no package
    from pmi_dev_rounds import kind_table, kinds_by_rule, outcome

    rows = json.loads((root / "benchmarks" / "pmi_dev" / "results_r30_r51.json").read_text())["rows"]
    fit = [r for r in rows if int(r["round"].removeprefix("blind_r")) < 46]
    shipped = load_ranker_settings()
    judged = frozenset(k for k, v in shipped.kinds.items() if v.judge)
    assert judged == kinds_by_rule(kind_table(fit))
    cell = outcome(fit, shipped.margin, shipped.weight, shipped.min_lead, judged)
    assert cell["overturned_to_right"] > 0 and cell["overturned_to_wrong"] == 0
    assert cell["top1"] > cell["prior_top1"]


# ---- the clauses calibration: leaving a clause out is no gain --------------------------

@dataclass(frozen=True)
class Clausal:
    """A reading with its end state as one sentence per condition."""

    sentence: str
    score: float
    clauses: tuple[str, ...]


IN_FRIDGE, IN_MICROWAVE = "The tomato is in the fridge.", "The tomato is in the microwave."
LIGHT_OFF, DOOR_OPEN = "The light switch is off.", "The fridge is open."
AS_READ = Clausal("The tomato is in the microwave and the light switch is off.", -0.2, (IN_MICROWAVE, LIGHT_OFF))
SWAPPED = Clausal("The tomato is in the fridge and the light switch is off.", -0.6, (IN_FRIDGE, LIGHT_OFF))
DROPPED = Clausal("The tomato is in the microwave.", -0.4, (IN_MICROWAVE,))
ADDED = Clausal("The tomato is in the microwave, the light switch is off and the fridge is open.", -0.9,
                (IN_MICROWAVE, LIGHT_OFF, DOOR_OPEN))


def test_clause_lead_cancels_shared_clauses_and_gives_no_gain_for_a_missing_one() -> None:
    """Only the clauses two readings do not share count, each side by its mean PMI; a
    reading that only leaves a clause out is not judged (its lead would be minus that
    clause's PMI, a gain whenever the instruction does not strongly predict the clause),
    unless drops are asked for; one that adds a clause leads by that clause's PMI."""
    from emboteam.pfg.model_ranker import clause_lead, differing_clauses

    pmi = {IN_MICROWAVE: 1.0, IN_FRIDGE: 4.0, LIGHT_OFF: -3.0, DOOR_OPEN: 0.5}
    assert clause_lead(AS_READ.clauses, SWAPPED.clauses, pmi) == pytest.approx(3.0)
    assert clause_lead(AS_READ.clauses, DROPPED.clauses, pmi) is None
    assert clause_lead(AS_READ.clauses, DROPPED.clauses, pmi, drops=True) == pytest.approx(3.0)
    assert clause_lead(AS_READ.clauses, ADDED.clauses, pmi) == pytest.approx(0.5)
    assert clause_lead(AS_READ.clauses, AS_READ.clauses[::-1], pmi) is None      # the same end state
    others = [SWAPPED.clauses, DROPPED.clauses, ADDED.clauses]
    assert differing_clauses(AS_READ.clauses, others) == ((IN_FRIDGE, IN_MICROWAVE, DOOR_OPEN), (0, 2))
    assert differing_clauses(AS_READ.clauses, others, drops=True)[1] == (0, 1, 2)
    assert differing_clauses(AS_READ.clauses, others, limit=2) == ((IN_FRIDGE, IN_MICROWAVE), (0,))


def test_rerank_by_clauses_asks_only_the_differing_clauses_and_never_rewards_a_drop(tmp_path: Path) -> None:
    """The one request holds the clauses the judged readings do not share with the first
    (the cassette holds only that request: any other would be a replay miss); the reading
    that leaves the light out is not scored although its missing clause's PMI is -3 (a
    whole-sentence PMI would have favoured it); the swap overturns when it leads by more
    than the lead, not otherwise; when every close reading only drops clauses, nothing is
    asked."""
    from emboteam.pfg.model_ranker import rerank_by_clauses

    def clauses_of(c: Clausal) -> tuple[str, ...]:
        return c.clauses

    client = make_client(cassette(tmp_path / "a", {IN_FRIDGE: 4.0, IN_MICROWAVE: 1.0, DOOR_OPEN: 0.5},
                                          OBJECTS))
    args: dict[str, Any] = {"client": client, "objects": OBJECTS, "instruction": INSTRUCTION, "margin": 1.0,
                            "weight": 1.0, "clauses_of": clauses_of}
    taken = rerank_by_clauses([AS_READ, DROPPED, SWAPPED, ADDED], **args, min_lead=2.0)
    assert taken.overturned and taken.candidates == (SWAPPED, AS_READ, ADDED, DROPPED)
    assert [r.pmi for r in taken.ranked] == pytest.approx([3.0, 0.0, 0.5, None])
    assert taken.ranked[0].combined == pytest.approx(-0.6 + 3.0)
    held = rerank_by_clauses([AS_READ, DROPPED, SWAPPED, ADDED], **args, min_lead=3.5)
    assert held.scored and not held.overturned and held.candidates[0] == AS_READ
    assert client.usage.calls == 2

    Cassette(tmp_path / "empty").open_for_recording("test:handmade")
    silent = make_client(f"replay:{tmp_path / 'empty'}")
    quiet = rerank_by_clauses([AS_READ, DROPPED], **{**args, "client": silent})
    assert not quiet.scored and quiet.candidates == (AS_READ, DROPPED) and silent.usage.calls == 0


def test_the_calibration_is_data_checked_at_load(tmp_path: Path) -> None:
    """``calibration`` is one of the two forms; anything else names the file and entry."""
    from emboteam.pfg.model_ranker import ModelRankerDataError, load_ranker_settings

    bad = tmp_path / "model_ranker.json"
    bad.write_text('{"fitted": "x", "margin": 1.0, "weight": 1.0, "calibration": "clause"}', encoding="utf-8")
    with pytest.raises(ModelRankerDataError, match=r"model_ranker\.json: entry calibration"):
        load_ranker_settings(bad)
    assert load_ranker_settings().calibration in ("sentence", "clauses")


def test_the_benchmark_forms_each_calibrations_lead_from_the_records() -> None:
    """benchmarks/pmi_dev_rounds.py's leads: the whole sentences' PMI difference; the clause
    lead (a drop not judged, or judged with a missing clause counting 0); swaps only; and
    the sentences' PMI with drops not judged. A clause past the request's limit (no
    recorded score) is not judged."""
    import sys

    root = Path(__file__).resolve().parents[1]
    sys.path.insert(0, str(root / "benchmarks"))  # benchmarks/ is no package
    from pmi_dev_rounds import leads

    row: dict[str, Any] = {
        "priors": [-0.2, -0.4, -0.6, -0.9, -1.0], "pmi": [5.0, 9.0, 6.0, 4.0, None],
        "clauses": [list(AS_READ.clauses), list(DROPPED.clauses), list(SWAPPED.clauses), list(ADDED.clauses),
                    [IN_FRIDGE]],
        "clause_pmi": {IN_MICROWAVE: 1.0, IN_FRIDGE: 4.0, LIGHT_OFF: -3.0, DOOR_OPEN: 0.5}}
    assert leads(row) == [0.0, 4.0, 1.0, -1.0, None]
    assert leads(row, "clauses") == pytest.approx([0.0, None, 3.0, 0.5, 5.0])
    assert leads(row, "clauses_drops") == pytest.approx([0.0, 3.0, 3.0, 0.5, 5.0])
    assert leads(row, "swaps") == pytest.approx([0.0, None, 3.0, None, 5.0])
    assert leads(row, "sentence_nodrop") == [0.0, None, 1.0, -1.0, None]
    assert leads({**row, "clause_pmi": {}}, "clauses")[1:] == [None, None, None, None]
