"""The PMI scorer on the offline reader's close candidates, development rounds only.

For every task of ``tests/data/blind_r*/dev`` (development halves: never the held-out
halves, never the unseen suite) the offline reader gives its ranked candidates
(``Reading.candidates``: sentence, log-prior ``score``, goals). Where at least two are
within ``--margin`` of the first, the leading ones (at most 5) are scored once by the
local model (one ``client.score`` call, PMI) and recorded with which of them meets the
ground truth (``fit_reading_priors.satisfies``). From these records the script reports,
for a grid of margins and weights, what ``prior + weight * pmi`` does: top-1 on the
scored tasks, how often the model overturns the prior's first and how often that was
right, and calls per task. Nothing is tuned here; the grid is the data for choosing
``model_ranker``'s margin and weight.

Per kind of doubt (the kinds two readings settle differently, ``model_ranker.differing_kinds``)
it also counts, where the model's pick and the prior's first disagree, which was right;
with ``--split`` the kinds that meet the stated rule (:func:`kinds_by_rule`) on the rounds
before the split give the grid's second permission axis (``every`` kind or the ``fitted``
ones), reported on the rounds from the split on; the output's ``kinds_entries`` is the
``kinds`` block of ``pfg/model_ranker.json``.

    EMBOTEAM_LLAMACPP_THREADS=1 nice .venv/bin/python benchmarks/pmi_dev_rounds.py --out /tmp/pmi-dev.json
    .venv/bin/python benchmarks/pmi_dev_rounds.py --replay --out /tmp/pmi-dev.json   # from the cassette
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from emboteam.bench.dev_corpus import HELD_OUT_ROUNDS
from emboteam.bench.importers.smart_llm import import_smart_llm
from emboteam.errors import EmboTeamError
from emboteam.llm.backend import Backend
from emboteam.llm.cassette import Cassette, RecordingBackend
from emboteam.llm.client import LLMClient, make_backend, make_client
from emboteam.llm.errors import LLMReplayMiss
from emboteam.llm.messages import LLMRequest, LLMResponse
from emboteam.llm.scoring import ScoreRequest, ScoreResponse
from emboteam.llm.spec import parse_llm_spec
from emboteam.pfg.model_ranker import (
    clause_lead,
    close_count,
    differing_clauses,
    differing_kinds,
    objects_summary,
    rerank_in_scene,
)
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.sentences import clause_sentences

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
OUT = ROOT / "benchmarks" / "pmi_dev"
CASSETTE = OUT / "cassette"
#: candidates within this much of the first are scored (the grid's widest margin)
WIDEST = 2.5
MARGINS = (0.5, 1.0, 1.5, 2.0, 2.5)
WEIGHTS = (0.0, 0.25, 0.5, 1.0, 2.0, 3.0)
#: the PMI lead over the prior's first the model needs to overturn it (0: any)
MIN_LEADS = (0.0, 1.0, 2.0, 3.0)
#: the rule for letting the model judge a kind of doubt: on the fit rounds, at the widest
#: margin and weight 1, where its pick and the prior's first disagree and exactly one is
#: right, the model was right more often than the prior and at least this often
MIN_MODEL_RIGHT = 2
#: how the model's lead over the prior's first is formed: the whole sentences' PMIs
#: (``sentence``), the PMIs of the clauses they do not share with a candidate that only
#: leaves clauses out not judged (``clauses``, ``model_ranker.clause_lead``), or judged with
#: a missing clause counting 0 (``clauses_drops``: what whole-sentence PMI roughly does), or
#: only where each says a clause the other does not (``swaps``); or the whole sentences'
#: PMIs where the other says a clause the first does not (``sentence_nodrop``: a reading
#: that only leaves clauses out is not judged)
CALIBRATIONS = ("sentence", "clauses", "clauses_drops", "swaps", "sentence_nodrop")


class CachedScorer:
    """Scores from the cassette where it holds the request, else from the live backend
    (and recorded): re-running after the reader changed asks only what is new."""

    def __init__(self, live: Backend, folder: Path) -> None:
        self.live = RecordingBackend(live, folder)
        self.cassette = Cassette(folder)
        self.name = live.name

    def send(self, request: LLMRequest) -> LLMResponse:
        return self.live.send(request)

    def score(self, request: ScoreRequest) -> ScoreResponse:
        try:
            return self.cassette.load_score(request)
        except LLMReplayMiss:
            return self.live.score(request)


def dev_folders(since: int, extra: Sequence[Path]) -> list[Path]:
    """The development rounds read: ``blind_r*/dev`` below the first held-out round (from
    ``since`` on) and the ``extra`` development folders; a held-out round is refused."""
    from fit_reading_priors import FIRST_HELD_OUT  # a script beside this one (benchmarks/ is on sys.path)

    rounds = sorted((p for p in DATA.glob("blind_r*/dev")
                     if since <= int(p.parent.name.removeprefix("blind_r")) < FIRST_HELD_OUT),
                    key=lambda p: int(p.parent.name.removeprefix("blind_r")))
    for folder in extra:
        name = folder.resolve().parent.name if folder.name == "dev" else folder.name
        if name in HELD_OUT_ROUNDS or folder.name != "dev":
            raise EmboTeamError(f"{folder} is not a development folder (blind_rNN/dev of a round not held out)")
    return [*rounds, *extra]


def records(client: LLMClient, since: int = 0, extra: Sequence[Path] = (), clauses: bool = False) -> list[dict[str, Any]]:
    """One record per development task the reader read: priors, and for the close ones
    the PMI of each scored candidate and whether it meets the ground truth; with
    ``clauses``, also each candidate's clauses and the PMI of every clause in which a close
    candidate differs from the first (one more call per close task)."""
    from fit_reading_priors import task_case  # a script beside this one (benchmarks/ is on sys.path)

    reader = OfflineFrontend()
    out: list[dict[str, Any]] = []
    for folder in dev_folders(since, extra):
        for task in import_smart_llm(folder).tasks:
            if task.ground_truth is None:
                continue
            case = task_case(folder.parent.name, task)
            scene = case.scene
            try:
                reading = reader.parse(task.instruction, scene, case.state, case.team)
            except EmboTeamError:
                continue
            cands = reading.candidates
            row: dict[str, Any] = {"round": folder.resolve().parent.name, "instruction": task.instruction,
                                   "priors": [round(c.score, 4) for c in cands],
                                   "right": [bool(case.right(c.goals)) for c in cands],
                                   "kinds": [sorted({r.kind for r in c.resolves}) for c in cands],
                                   "resolves": [sorted([r.kind, r.span, r.label] for r in c.resolves)
                                                for c in cands],
                                   "pmi": None}
            if close_count([c.score for c in cands], WIDEST) >= 2:
                start = time.process_time()
                ranking = rerank_in_scene(cands, client=client, scene=scene, instruction=task.instruction,
                                          margin=WIDEST, weight=0.0)
                row["cpu"] = round(time.process_time() - start, 3)
                by_sentence = {r.candidate.sentence: r.pmi for r in ranking.ranked if r.pmi is not None}
                row["pmi"] = [by_sentence.get(c.sentence) for c in cands]
                row["sentences"] = [c.sentence for c in cands]
                if clauses:
                    row.update(clause_scores(client, scene, task.instruction, cands))
                print(f"{row['round']} {len(by_sentence)} scored, right {row['right'][:len(by_sentence)]} "
                      f"{row['cpu']:.2f}s cpu", file=sys.stderr, flush=True)
            out.append(row)
    return out


def clause_scores(client: LLMClient, scene: Any, instruction: str, cands: Sequence[Any]) -> dict[str, Any]:
    """Each candidate's clauses and the PMI of the clauses the close ones (within the
    widest margin) do not share with the first, in the prompt the ranker uses (objects
    summary over every candidate), so the live ranker asks a subset of these."""
    own = [list(clause_sentences(c.goals)) for c in cands]
    close = close_count([c.score for c in cands], WIDEST)
    texts, _ = differing_clauses(own[0], own[1:close], drops=True)
    pmi: dict[str, float] = {}
    if texts:
        objects = objects_summary(scene, (instruction, *(c.sentence for c in cands)))
        response = client.score(ScoreRequest(objects=objects, instruction=instruction, candidates=texts))
        pmi = dict(zip(texts, response.pmi, strict=True))
    return {"clauses": own, "clause_pmi": pmi}


def leads(row: dict[str, Any], calibration: str = "sentence") -> list[float | None]:
    """Each candidate's lead over the prior's first by the model (0 for the first; None:
    not scored, or not judged by this calibration)."""
    pmi = row["pmi"]
    if pmi is None:
        return [0.0] + [None] * (len(row["priors"]) - 1)
    if calibration == "sentence":
        return [None if p is None or pmi[0] is None else p - pmi[0] for p in pmi]
    own, scores = row.get("clauses"), row.get("clause_pmi") or {}
    if own is None:
        raise EmboTeamError(f"{calibration}: the records have no clause scores (record them with --calibration)")
    if calibration == "sentence_nodrop":
        return [None if p is None or pmi[0] is None or (i and set(own[i]) <= set(own[0])) else p - pmi[0]
                for i, p in enumerate(pmi)]
    out: list[float | None] = [0.0]
    for other in own[1:]:
        if calibration == "swaps" and set(own[0]) <= set(other):
            out.append(None)        # only adds clauses: not a swap
            continue
        try:
            out.append(clause_lead(own[0], other, scores, drops=calibration == "clauses_drops"))
        except KeyError:        # a clause past the request's limit: not scored
            out.append(None)
    return out


def _diff(row: dict[str, Any], i: int) -> frozenset[str]:
    res = row["resolves"]
    return differing_kinds(map(tuple, res[0]), map(tuple, res[i]))


def _judged(row: dict[str, Any], margin: float, kinds: frozenset[str] | None, calibration: str = "sentence") -> list[int]:
    """The candidates the ranker scores: the first and the close ones the model may judge
    against it (``kinds`` None: every kind), at most 5, all with recorded scores; with a
    clause calibration, of those the ones it judges (``model_ranker.rerank_by_clauses``)."""
    priors, pmi = row["priors"], row["pmi"]
    if pmi is None:
        return [0]
    others = [i for i in range(1, len(priors)) if priors[0] - priors[i] <= margin
              and (kinds is None or (_diff(row, i) and _diff(row, i) <= kinds))]
    close = [0, *others[:4]]
    if calibration != "sentence":
        lead = leads(row, calibration)
        return [i for i in close if lead[i] is not None]
    return close if all(pmi[i] is not None for i in close) else [0]


def pick(row: dict[str, Any], close: Sequence[int], weight: float, min_lead: float,
         calibration: str = "sentence") -> int:
    """The ranker's first (``model_ranker.rerank``): by ``prior + weight * lead``, the first
    that is the prior's first or leads it by more than ``min_lead`` (for ``sentence``,
    ordering by the lead is ordering by the PMI: they differ by the first's PMI)."""
    priors, lead = row["priors"], leads(row, calibration)
    order = sorted(close, key=lambda i: (-(priors[i] + weight * lead[i]), i))
    return next(i for i in order if i == 0 or lead[i] > min_lead)


def outcome(rows: Sequence[dict[str, Any]], margin: float, weight: float, min_lead: float = 0.0,
            kinds: frozenset[str] | None = None, calibration: str = "sentence") -> dict[str, Any]:
    """What re-ranking with this margin and weight does to the recorded tasks; with
    ``min_lead``, the model overturns the prior's first only when its PMI leads the
    first's by more than that; with ``kinds``, it judges only candidates that differ from
    the first in those kinds of doubt (``model_ranker.rerank_in_scene``'s ``lead_needed``)."""
    calls = overturned = to_right = to_wrong = top1 = prior_top1 = 0
    for r in rows:
        right = r["right"]
        if not r["priors"]:
            continue
        prior_top1 += right[0]
        close = _judged(r, margin, kinds, calibration)
        if len(close) < 2 or len({r["sentences"][i] for i in close}) < 2:
            top1 += right[0]
            continue
        calls += 1
        best = pick(r, close, weight, min_lead, calibration)
        top1 += right[best]
        if best != 0:
            overturned += 1
            to_right += right[best] and not right[0]
            to_wrong += right[0] and not right[best]
    read = sum(1 for r in rows if r["priors"])
    return {"margin": margin, "weight": weight, "min_lead": min_lead, "calibration": calibration,
            "kinds": "every" if kinds is None else "+".join(sorted(kinds)) or "none", "tasks": read,
            "calls": calls, "top1": top1, "prior_top1": prior_top1, "overturned": overturned,
            "overturned_to_right": to_right, "overturned_to_wrong": to_wrong}


def kind_table(rows: Sequence[dict[str, Any]], margin: float = WIDEST, weight: float = 1.0,
               calibration: str = "sentence") -> dict[str, dict[str, int]]:
    """Per kind of doubt, where the model's pick (every kind judged, no lead) differs from
    the prior's first: how often the model was right and the prior wrong (``model``), the
    other way (``prior``), both right or neither. A disagreement counts for every kind
    in which the two readings differ."""
    table: dict[str, dict[str, int]] = {}
    for r in rows:
        close = _judged(r, margin, None, calibration)
        if len(close) < 2:
            continue
        best = pick(r, close, weight, 0.0, calibration)
        if best == 0:
            continue
        a, b = r["right"][best], r["right"][0]
        who = "model" if a and not b else "prior" if b and not a else "both" if a else "neither"
        for kind in _diff(r, best) or {"(none)"}:
            counts = table.setdefault(kind, {"model": 0, "prior": 0, "both": 0, "neither": 0})
            counts[who] += 1
    return dict(sorted(table.items()))


def kinds_by_rule(table: dict[str, dict[str, int]], min_right: int = MIN_MODEL_RIGHT) -> frozenset[str]:
    """The kinds the model may judge: right (where the prior was wrong) at least
    ``min_right`` times and more often than the prior was right where it was wrong."""
    return frozenset(k for k, c in table.items() if c["model"] >= min_right and c["model"] > c["prior"])


def kinds_entries(before: dict[str, dict[str, int]], after: dict[str, dict[str, int]],
                  judged: frozenset[str]) -> dict[str, dict[str, Any]]:
    """``model_ranker.json``'s ``kinds``: each kind seen, whether the rule lets the model
    judge it, and the counts it was chosen on (and the reported ones, not fitted on)."""
    def counts(c: dict[str, int] | None) -> str:
        return (f"model {c['model']}, prior {c['prior']}, both {c['both']}, neither {c['neither']}"
                if c else "no disagreement")

    return {k: {"judge": k in judged, "fit": f"before the split: {counts(before.get(k))}; from the split on "
                f"(reported, not fitted): {counts(after.get(k))}"} for k in sorted({*before, *after})}


def grid(rows: Sequence[dict[str, Any]], fitted: frozenset[str] | None = None,
         calibration: str = "sentence") -> list[dict[str, Any]]:
    axis: list[frozenset[str] | None] = [None] if fitted is None else [None, fitted]
    return [outcome(rows, m, w, lead, k, calibration)
            for k in axis for m in MARGINS for w in WEIGHTS for lead in MIN_LEADS]


def print_kinds(title: str, table: dict[str, dict[str, int]]) -> None:
    print(f"== {title}: where the model's pick and the prior's first disagree (margin {WIDEST}, weight 1)")
    print(f"{'kind':22s} {'model':>5} {'prior':>5} {'both':>5} {'neither':>7}")
    for kind, c in table.items():
        print(f"{kind:22s} {c['model']:5d} {c['prior']:5d} {c['both']:5d} {c['neither']:7d}")


def print_grid(title: str, cells: Sequence[dict[str, Any]]) -> None:
    print(f"== {title}")
    print(f"{'margin':>6} {'weight':>6} {'lead':>5} {'calls':>5} {'top1':>5} {'prior':>5} {'overturned':>10} "
          f"{'to right':>8} {'to wrong':>8}  kinds")
    for g in cells:
        print(f"{g['margin']:6.2f} {g['weight']:6.2f} {g['min_lead']:5.1f} {g['calls']:5d} {g['top1']:5d} "
              f"{g['prior_top1']:5d} {g['overturned']:10d} {g['overturned_to_right']:8d} "
              f"{g['overturned_to_wrong']:8d}  {g['kinds']}   of {g['tasks']} tasks")


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--replay", action="store_true", help="scores from the committed cassette")
    ap.add_argument("--out", type=Path, required=True, help="records and the grid, as JSON")
    ap.add_argument("--model", type=Path, help="GGUF file (default: the Qwen 0.5B model)")
    ap.add_argument("--since", type=int, default=0, help="only development rounds from this number on")
    ap.add_argument("--extra", type=Path, nargs="*", default=[],
                    help="more development rounds (blind_rNN/dev folders past the first held-out round)")
    ap.add_argument("--split", type=int, help="also a grid for the rounds before this number and one from it on")
    ap.add_argument("--calibration", choices=CALIBRATIONS, default="sentence",
                    help="the model's lead over the first (a clause one also records the clauses' scores)")
    args = ap.parse_args(argv)
    try:
        if args.replay:
            client = make_client(f"replay:{CASSETTE}")
        else:
            from emboteam.llm.local_model import fetch_model

            live = make_backend(parse_llm_spec(f"llamacpp:{args.model or fetch_model()}"), timeout=600)
            client = LLMClient(CachedScorer(live, CASSETTE))
        rows = records(client, args.since, args.extra, clauses=args.calibration != "sentence")
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    cal = args.calibration
    out: dict[str, Any] = {"calibration": cal, "rows": rows}
    fitted = None
    if args.split:
        number = lambda r: int(r["round"].removeprefix("blind_r"))  # noqa: E731
        before = [r for r in rows if number(r) < args.split]
        after = [r for r in rows if number(r) >= args.split]
        out["kinds_before_split"], out["kinds_from_split"] = (kind_table(before, calibration=cal),
                                                              kind_table(after, calibration=cal))
        fitted = kinds_by_rule(out["kinds_before_split"])
        out["kinds_fitted"] = sorted(fitted)
        # to paste into pfg/model_ranker.json with the grid cell chosen below
        out["kinds_entries"] = kinds_entries(out["kinds_before_split"], out["kinds_from_split"], fitted)
        out["grid_before_split"] = grid(before, fitted, cal)
        out["grid_from_split"] = grid(after, fitted, cal)
        print_kinds(f"rounds before r{args.split} (to choose on)", out["kinds_before_split"])
        print_kinds(f"rounds from r{args.split} on (to report)", out["kinds_from_split"])
        print(f"kinds the model may judge by the rule (model right >= {MIN_MODEL_RIGHT} and > prior right, "
              f"before r{args.split}): {', '.join(sorted(fitted)) or 'none'}")
        print_grid(f"rounds before r{args.split} (to choose on)", out["grid_before_split"])
        print_grid(f"rounds from r{args.split} on (to report)", out["grid_from_split"])
    out["grid"] = grid(rows, fitted, cal)
    print_grid("all rounds", out["grid"])
    args.out.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
