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
from emboteam.pfg.model_ranker import close_count, rerank_in_scene
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.offline.doubts.priors import load_priors

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


def records(client: LLMClient, since: int = 0, extra: Sequence[Path] = ()) -> list[dict[str, Any]]:
    """One record per development task the reader read: priors, and for the close ones
    the PMI of each scored candidate and whether it meets the ground truth."""
    from fit_reading_priors import task_case  # a script beside this one (benchmarks/ is on sys.path)

    reader = OfflineFrontend()
    kinds = frozenset(load_priors().prior_only_kinds)
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
                                   "prior_only": [any(r.kind in kinds for r in c.resolves) for c in cands],
                                   "kinds": [sorted({r.kind for r in c.resolves}) for c in cands],
                                   "pmi": None}
            if close_count([c.score for c in cands], WIDEST) >= 2:
                start = time.process_time()
                ranking = rerank_in_scene(cands, client=client, scene=scene, instruction=task.instruction,
                                          margin=WIDEST, weight=0.0)
                row["cpu"] = round(time.process_time() - start, 3)
                by_sentence = {r.candidate.sentence: r.pmi for r in ranking.ranked if r.pmi is not None}
                row["pmi"] = [by_sentence.get(c.sentence) for c in cands]
                row["sentences"] = [c.sentence for c in cands]
                print(f"{row['round']} {len(by_sentence)} scored, right {row['right'][:len(by_sentence)]} "
                      f"{row['cpu']:.2f}s cpu", file=sys.stderr, flush=True)
            out.append(row)
    return out


def outcome(rows: Sequence[dict[str, Any]], margin: float, weight: float, min_lead: float = 0.0) -> dict[str, Any]:
    """What re-ranking with this margin and weight does to the recorded tasks; with
    ``min_lead``, the model overturns the prior's first only when its PMI leads the
    first's by more than that (``model_ranker.rerank``'s ``min_lead``)."""
    calls = overturned = to_right = to_wrong = top1 = prior_top1 = 0
    for r in rows:
        priors, right = r["priors"], r["right"]
        if not priors:
            continue
        prior_top1 += right[0]
        only = r.get("prior_only") or [False] * len(priors)
        # as the hybrid front end does: readings settling a prior-only doubt are never
        # scored, and none is when the first is one
        close = [i for i in range(len(priors)) if priors[0] - priors[i] <= margin and not only[i]][:5]
        if only[0] or len(close) < 2 or r["pmi"] is None or any(r["pmi"][i] is None for i in close):
            top1 += right[0]
            continue
        calls += 1
        scored = [(priors[i] + weight * r["pmi"][i], -i) for i in close]
        best = -max(scored)[1]
        if best != 0 and r["pmi"][best] - r["pmi"][0] <= min_lead:
            best = 0
        top1 += right[best]
        if best != 0:
            overturned += 1
            to_right += right[best] and not right[0]
            to_wrong += right[0] and not right[best]
    read = sum(1 for r in rows if r["priors"])
    return {"margin": margin, "weight": weight, "min_lead": min_lead, "tasks": read, "calls": calls, "top1": top1,
            "prior_top1": prior_top1, "overturned": overturned, "overturned_to_right": to_right,
            "overturned_to_wrong": to_wrong}


def grid(rows: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    return [outcome(rows, m, w, lead) for m in MARGINS for w in WEIGHTS for lead in MIN_LEADS]


def print_grid(title: str, cells: Sequence[dict[str, Any]]) -> None:
    print(f"== {title}")
    print(f"{'margin':>6} {'weight':>6} {'lead':>5} {'calls':>5} {'top1':>5} {'prior':>5} {'overturned':>10} "
          f"{'to right':>8} {'to wrong':>8}")
    for g in cells:
        print(f"{g['margin']:6.2f} {g['weight']:6.2f} {g['min_lead']:5.1f} {g['calls']:5d} {g['top1']:5d} "
              f"{g['prior_top1']:5d} {g['overturned']:10d} {g['overturned_to_right']:8d} "
              f"{g['overturned_to_wrong']:8d}   of {g['tasks']} tasks")


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--replay", action="store_true", help="scores from the committed cassette")
    ap.add_argument("--out", type=Path, required=True, help="records and the grid, as JSON")
    ap.add_argument("--model", type=Path, help="GGUF file (default: the Qwen 0.5B model)")
    ap.add_argument("--since", type=int, default=0, help="only development rounds from this number on")
    ap.add_argument("--extra", type=Path, nargs="*", default=[],
                    help="more development rounds (blind_rNN/dev folders past the first held-out round)")
    ap.add_argument("--split", type=int, help="also a grid for the rounds before this number and one from it on")
    args = ap.parse_args(argv)
    try:
        if args.replay:
            client = make_client(f"replay:{CASSETTE}")
        else:
            from emboteam.llm.local_model import fetch_model

            live = make_backend(parse_llm_spec(f"llamacpp:{args.model or fetch_model()}"), timeout=600)
            client = LLMClient(CachedScorer(live, CASSETTE))
        rows = records(client, args.since, args.extra)
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    out: dict[str, Any] = {"rows": rows, "grid": grid(rows)}
    if args.split:
        number = lambda r: int(r["round"].removeprefix("blind_r"))  # noqa: E731
        out["grid_before_split"] = grid([r for r in rows if number(r) < args.split])
        out["grid_from_split"] = grid([r for r in rows if number(r) >= args.split])
        print_grid(f"rounds before r{args.split} (to choose on)", out["grid_before_split"])
        print_grid(f"rounds from r{args.split} on (to report)", out["grid_from_split"])
    print_grid("all rounds", out["grid"])
    args.out.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
