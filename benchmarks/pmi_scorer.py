"""The PMI scorer on hand-made ambiguous cases (tests/data/pmi_cases.json): accuracy and
seconds per case, against the raw sum of log-probabilities.

Each case is one scoring call (``LLMClient.score``): the scene's object types and the
instruction, 2-5 end-state sentences; the pick is the sentence with the highest PMI
(log P(sentence | objects + instruction) - log P(sentence | objects only)), compared
with the highest raw log P(sentence | objects + instruction). The live run records a
cassette (``benchmarks/pmi_scorer/cassette``) and the results
(``benchmarks/pmi_scorer/results.json``); ``--replay`` scores again from the cassette,
without the model, and exits 1 unless every pick and both accuracies are the same
(tests/test_pmi_scorer_replay.py does the same in the test suite).

    EMBOTEAM_LLAMACPP_THREADS=1 nice .venv/bin/python benchmarks/pmi_scorer.py     # live, Qwen 0.5B
    .venv/bin/python benchmarks/pmi_scorer.py --replay                             # no model

Seconds: ``wall`` is the scoring call's latency; ``cpu`` the process CPU time during it
(in process only: llama.cpp computes in this process), the better measure on a machine
shared with other jobs, where the wall time mostly measures waiting for a core.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient, make_client
from emboteam.llm.scoring import ScoreRequest
from emboteam.pfg.model_ranker import objects_summary
from emboteam.world.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "tests" / "data" / "pmi_cases.json"
OUT = ROOT / "benchmarks" / "pmi_scorer"
CASSETTE = OUT / "cassette"
RESULTS = OUT / "results.json"


def load_cases(path: Path = CASES) -> list[dict[str, Any]]:
    cases: list[dict[str, Any]] = json.loads(path.read_text(encoding="utf-8"))["cases"]
    return cases


def argmax(values: Sequence[float]) -> int:
    return max(range(len(values)), key=lambda i: (values[i], -i))


def score_case(client: LLMClient, case: dict[str, Any]) -> dict[str, Any]:
    """One case: the scores, both picks, and the time taken."""
    texts = (case["instruction"], *case["candidates"])
    request = ScoreRequest(objects=objects_summary(load_scene(case["floor_plan"]), texts),
                           instruction=case["instruction"], candidates=tuple(case["candidates"]))
    cpu = time.process_time()
    response = client.score(request)
    cpu = time.process_time() - cpu
    pmi = response.pmi
    raw = [s.conditional for s in response.scores]
    return {"id": case["id"], "ambiguous": case["ambiguous"], "answer": case["answer"],
            "pmi_pick": argmax(pmi), "raw_pick": argmax(raw), "pmi": [round(v, 4) for v in pmi],
            "raw": [round(v, 4) for v in raw], "wall": round(response.latency, 3), "cpu": round(cpu, 3),
            "input_tokens": response.input_tokens, "evaluated_tokens": response.evaluated_tokens}


def summary(rows: Sequence[dict[str, Any]]) -> dict[str, Any]:
    def accuracy(pick: str, ambiguous: bool) -> list[int]:
        chosen = [r for r in rows if r["ambiguous"] == ambiguous]
        return [sum(r[pick] == r["answer"] for r in chosen), len(chosen)]

    return {"pmi_ambiguous": accuracy("pmi_pick", True), "pmi_easy": accuracy("pmi_pick", False),
            "raw_ambiguous": accuracy("raw_pick", True), "raw_easy": accuracy("raw_pick", False),
            "chance_ambiguous": round(sum(1 / len(r["pmi"]) for r in rows if r["ambiguous"]), 2),
            "wall_mean": round(statistics.mean(r["wall"] for r in rows), 3),
            "wall_median": round(statistics.median(r["wall"] for r in rows), 3),
            "cpu_mean": round(statistics.mean(r["cpu"] for r in rows), 3),
            "cpu_median": round(statistics.median(r["cpu"] for r in rows), 3),
            "input_tokens": sum(r["input_tokens"] for r in rows),
            "evaluated_tokens": sum(r["evaluated_tokens"] for r in rows)}


def evaluate(client: LLMClient, cases: Sequence[dict[str, Any]]) -> dict[str, Any]:
    rows = []
    for case in cases:
        rows.append(score_case(client, case))
        r = rows[-1]
        print(f"{r['id']:28s} pmi {'ok ' if r['pmi_pick'] == r['answer'] else 'BAD'} "
              f"raw {'ok ' if r['raw_pick'] == r['answer'] else 'BAD'} {r['wall']:6.2f}s wall {r['cpu']:6.2f}s cpu "
              f"{r['evaluated_tokens']}/{r['input_tokens']} tokens", file=sys.stderr, flush=True)
    return {"rows": rows, "summary": summary(rows)}


def differences(recorded: dict[str, Any], replayed: dict[str, Any]) -> list[str]:
    """What a replay must reproduce: every pick and score, and the accuracies."""
    out = []
    for a, b in zip(recorded["rows"], replayed["rows"], strict=True):
        for field in ("pmi_pick", "raw_pick", "pmi", "raw"):
            if a[field] != b[field]:
                out.append(f"{a['id']}: {field} {a[field]} recorded, {b[field]} replayed")
    for field in ("pmi_ambiguous", "pmi_easy", "raw_ambiguous", "raw_easy"):
        if recorded["summary"][field] != replayed["summary"][field]:
            out.append(f"{field}: {recorded['summary'][field]} recorded, {replayed['summary'][field]} replayed")
    return out


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", type=Path, help="GGUF file (default: fetch and verify the Qwen 0.5B model)")
    ap.add_argument("--llm", help="any --llm spec instead (e.g. openai:MODEL@http://127.0.0.1:8080/v1)")
    ap.add_argument("--replay", action="store_true", help="score from the committed cassette and compare")
    ap.add_argument("--out", type=Path, help=f"results file (default {RESULTS.relative_to(ROOT)} for a live run)")
    ap.add_argument("--no-record", action="store_true", help="do not write the cassette")
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--only", nargs="*", default=[], help="case ids (a quick look; implies --no-record)")
    args = ap.parse_args(argv)
    cases = [c for c in load_cases() if not args.only or c["id"] in args.only]
    args.no_record = args.no_record or bool(args.only)
    try:
        if args.replay:
            replayed = evaluate(make_client(f"replay:{CASSETTE}"), cases)
            diffs = differences(json.loads(RESULTS.read_text()), replayed)
            print("\n".join(diffs) or "replay: every pick, score and accuracy reproduced")
            return 1 if diffs else 0
        if args.llm is None:
            from emboteam.llm.local_model import fetch_model

            args.llm = f"llamacpp:{args.model or fetch_model()}"
        record = None
        if not args.no_record:
            shutil.rmtree(CASSETTE, ignore_errors=True)  # a fresh recording holds this run's calls only
            record = CASSETTE
        client = make_client(args.llm, timeout=args.timeout, record_dir=record)
        result = evaluate(client, cases)
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    result["llm"] = args.llm.rsplit("/", 1)[-1] if args.llm.startswith("llamacpp:") else args.llm
    result["date"] = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    out = args.out or RESULTS
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    print(json.dumps(result["summary"], indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
