"""The reading's own doubt signals against the model's overturns, development rounds only.

The hybrid front end asks the local model only where the top candidates' priors are close;
on fresh rounds the prior is often sure and wrong and the model is never asked. This script
records, per development task, the doubt signals of the offline reading
(:func:`emboteam.pfg.doubt_gate.doubt_signals`), its candidates' priors and which of them
meet the ground truth, and, with ``--score``, the model's PMI of the top candidates (one
``client.score`` call, the request :func:`emboteam.pfg.doubt_gate` makes, recorded in a
cassette so a re-run asks only what is new). From the records it reports, per signal, how
often the gate would open and, where the model would overturn the prior's first, how often
that was right: the data ``pfg/model_ranker.json``'s ``doubt_gate`` block is chosen on.

Development rounds only (``blind_rNN/dev`` of a round not held out, never the unseen suite).

    PYTHONPATH=src:benchmarks python benchmarks/doubt_gate_dev.py --out /tmp/gate.jsonl r57 r55
    EMBOTEAM_LLAMACPP_THREADS=1 PYTHONPATH=src:benchmarks python benchmarks/doubt_gate_dev.py \
        --score --out /tmp/gate.jsonl r57
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
from emboteam.llm.client import LLMClient, make_backend, make_client
from emboteam.llm.spec import parse_llm_spec
from emboteam.pfg.doubt_gate import SIGNALS, DoubtGate, doubt_signals, gate_request, only_drops
from emboteam.pfg.model_ranker import MAX_SCORED, differing_kinds, load_ranker_settings, objects_summary
from emboteam.pfg.offline import OfflineFrontend
from emboteam.pfg.sentences import clause_sentences

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
CASSETTE = ROOT / "benchmarks" / "doubt_gate" / "cassette"
#: the committed records (signals and candidates of every development task read, with the
#: model's scores where recorded): what ``doubt_gate`` in pfg/model_ranker.json was chosen on
RECORDS = ROOT / "benchmarks" / "doubt_gate" / "records.jsonl"


def dev_folder(name: str) -> Path:
    """``r57`` -> tests/data/blind_r57/dev; a held-out round is refused."""
    round_ = f"blind_{name}"
    if round_ in HELD_OUT_ROUNDS:
        raise EmboTeamError(f"{round_} is held out")
    return DATA / round_ / "dev"


def record(rounds: Sequence[str], client: LLMClient | None, out: Path, only: frozenset[str] = frozenset()) -> None:
    """Append one JSON line per task of ``rounds`` to ``out`` (tasks already there are
    skipped; with ``only``, just the tasks named ``round:id`` there)."""
    from fit_reading_priors import task_case  # a script beside this one (benchmarks/ is on sys.path)

    done = {(r["round"], r["id"]) for r in load(out)} if out.exists() else set()
    gate = load_ranker_settings().doubt_gate
    reader = OfflineFrontend()
    with out.open("a", encoding="utf-8") as sink:
        for name in rounds:
            folder = dev_folder(name)
            for task in import_smart_llm(folder).tasks:
                if task.ground_truth is None or (name, task.id) in done or (only and f"{name}:{task.id}" not in only):
                    continue
                case = task_case(folder.parent.name, task)
                try:
                    reading = reader.parse(task.instruction, case.scene, case.state, case.team)
                except EmboTeamError:
                    continue
                cands = reading.candidates
                row: dict[str, Any] = {
                    "round": name, "id": task.id, "instruction": task.instruction,
                    "signals": doubt_signals(reading, task.instruction, case.state),
                    "priors": [round(c.score, 4) for c in cands],
                    "right": [bool(case.right(c.goals)) for c in cands],
                    "resolves": [sorted([r.kind, r.span, r.label] for r in c.resolves) for c in cands],
                    "sentences": [c.sentence for c in cands],
                    "clauses": [list(clause_sentences(c.goals)) for c in cands], "pmi": None}
                # every top candidate, drops too: the records then serve either setting of judge_drops
                objects = objects_summary(case.scene, (task.instruction, *(c.sentence for c in cands)))
                request = gate_request(cands, objects, task.instruction, gate.top_k, gate.max_gap)
                if client is not None and request is not None:
                    start = time.monotonic()
                    response = client.score(request)
                    row["seconds"] = round(time.monotonic() - start, 3)
                    row["pmi"] = list(response.pmi)
                print(f"{name} {task.id} {row['signals']} right {row['right'][:5]} pmi {row['pmi']}",
                      file=sys.stderr, flush=True)
                sink.write(json.dumps(row) + "\n")
                sink.flush()


def load(path: Path) -> list[dict[str, Any]]:
    return [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines() if line.strip()]


def merged(paths: Sequence[Path]) -> list[dict[str, Any]]:
    """The records of several files, one per task (the last file's reading); the model's
    scores of a record with the same candidate sentences are kept from any file."""
    by_task: dict[tuple[str, str], dict[str, Any]] = {}
    scores: dict[tuple[str, str, tuple[str, ...]], list[float]] = {}
    for path in paths:
        for row in load(path) if path.exists() else []:
            key = (row["round"], row["id"])
            by_task[key] = row
            if row["pmi"] is not None:
                scores[(*key, tuple(row["sentences"]))] = row["pmi"]
    return [{**row, "pmi": row["pmi"] or scores.get((*key, tuple(row["sentences"])))} for key, row in by_task.items()]


#: the rules tried: every signal at these thresholds
THRESHOLDS = (1.0, 2.0, 3.0)
#: a rule is shipped only when, on the scored development tasks where it opens the gate,
#: the model's overturns were right (the prior's first wrong, the pick right) at least this
#: often and more often than wrong (the prior's first right, the pick wrong)
MIN_RIGHT = 2


def top(row: dict[str, Any], top_k: int, max_gap: float) -> list[int]:
    """The indices of the candidates a signal-opened gate scores (``doubt_gate.gate_candidates``)."""
    out: list[int] = []
    for i, sentence in enumerate(row["sentences"]):
        if len(out) == top_k:
            break
        if sentence in {row["sentences"][j] for j in out} or (out and row["priors"][0] - row["priors"][i] > max_gap):
            continue
        out.append(i)
    return out if len(out) >= 2 else []


def scored_today(row: dict[str, Any]) -> bool:
    """Whether the close-prior ranker (``model_ranker.json``'s margin and kinds) asks the
    model already: the gate is only tried where it does not."""
    settings = load_ranker_settings()
    priors, res = row["priors"], [[tuple(x) for x in r] for r in row["resolves"]]
    judged = [i for i in range(1, len(priors)) if priors[0] - priors[i] <= settings.margin
              and settings.lead_for(differing_kinds(res[0], res[i])) is not None][:MAX_SCORED - 1]
    return len({row["sentences"][i] for i in [0, *judged]}) >= 2


def gate_pick(row: dict[str, Any], chosen: Sequence[int], weight: float, min_lead: float) -> int:
    """The ranker's first among ``chosen`` (``model_ranker.rerank``): by prior + weight *
    PMI, the first that is the prior's first or leads its PMI by more than ``min_lead``."""
    priors, pmi = row["priors"], row["pmi"]
    order = sorted(range(len(chosen)), key=lambda j: (-(priors[chosen[j]] + weight * pmi[j]), j))
    return chosen[next(j for j in order if j == 0 or pmi[j] - pmi[0] > min_lead)]


def judged(row: dict[str, Any], chosen: Sequence[int], judge_drops: bool) -> list[int]:
    """The positions in ``chosen`` the gate lets the model pick (``gate_candidates``'s drop rule)."""
    if judge_drops:
        return list(range(len(chosen)))
    first = row["clauses"][chosen[0]]
    return [0, *(j for j in range(1, len(chosen)) if not only_drops(first, row["clauses"][chosen[j]]))]


def rule_outcome(rows: Sequence[dict[str, Any]], signal: str, at_least: float, gate: DoubtGate) -> dict[str, Any]:
    """What a rule does where today's ranker asks nothing: tasks it opens the gate on, of
    those scored how often the model overturned the prior and whether rightly, and the
    opened tasks not scored whose outcome could change (``unscored_*``: first wrong with a
    right one among the scored candidates, or first right)."""
    out = {"rule": f"{signal}>={at_least:g}", "opens": 0, "scored": 0, "overturned": 0, "right": 0, "wrong": 0,
           "neutral": 0, "unscored_could_win": 0, "unscored_could_lose": 0}
    for row in rows:
        listed = top(row, gate.top_k, gate.max_gap)         # what the recorder scored
        keep = judged(row, listed, gate.judge_drops) if listed else []
        if len(keep) < 2 or row["signals"].get(signal, 0.0) < at_least or scored_today(row):
            continue
        chosen = [listed[j] for j in keep]
        out["opens"] += 1
        right = row["right"]
        if row["pmi"] is None:
            out["unscored_could_win"] += not right[0] and any(right[i] for i in chosen)
            out["unscored_could_lose"] += right[0]
            continue
        out["scored"] += 1
        best = gate_pick({**row, "pmi": [row["pmi"][j] for j in keep]}, chosen, gate.weight, gate.min_lead)
        if best != chosen[0]:
            out["overturned"] += 1
            key = "right" if right[best] and not right[0] else "wrong" if right[0] and not right[best] else "neutral"
            out[key] += 1
    out["ships"] = out["right"] >= MIN_RIGHT and out["right"] > out["wrong"]
    return out


def report(rows: Sequence[dict[str, Any]], **override: Any) -> list[dict[str, Any]]:
    gate = load_ranker_settings().doubt_gate.model_copy(update=override)
    table = [rule_outcome(rows, s, t, gate) for s in SIGNALS for t in THRESHOLDS]
    print(f"{len(rows)} tasks, {sum(r['pmi'] is not None for r in rows)} scored; gate top_k {gate.top_k}, "
          f"weight {gate.weight:g}, min_lead {gate.min_lead:g}")
    for o in table:
        if o["opens"]:
            print(f"{o['rule']:26s} opens {o['opens']:3d} scored {o['scored']:3d} overturned {o['overturned']:2d} "
                  f"(right {o['right']}, wrong {o['wrong']}, neutral {o['neutral']}); unscored could win "
                  f"{o['unscored_could_win']}, lose {o['unscored_could_lose']}{'  SHIPS' if o['ships'] else ''}")
    return table


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("rounds", nargs="*", help="development rounds to record: r40 r41 r43 r45 r47 ... r57")
    ap.add_argument("--out", type=Path, required=True, help="records, one JSON line per task (appended)")
    ap.add_argument("--report", type=Path, nargs="*", help="report the rules on these record files (no reading)")
    ap.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE",
                    help="report with these doubt_gate settings instead of the file's (weight=2 judge_drops=true)")
    ap.add_argument("--by-round", metavar="SIGNAL>=N", help="with --report: this rule per round too")
    ap.add_argument("--merge-into", type=Path, help="with --report: also write the merged records there")
    ap.add_argument("--score", action="store_true", help="also the model's PMI of the top candidates")
    ap.add_argument("--replay", action="store_true", help="scores from the cassette only")
    ap.add_argument("--only", type=Path, help="a file of round:id lines: record just those tasks")
    ap.add_argument("--model", type=Path, help="GGUF file (default: the Qwen 0.5B model)")
    args = ap.parse_args(argv)
    if args.report is not None:
        rows = merged([*args.report, args.out])
        if args.merge_into:
            args.merge_into.write_text("".join(json.dumps(r) + "\n" for r in rows), encoding="utf-8")
        override = {k: json.loads(v) for k, v in (kv.split("=", 1) for kv in args.set)}
        table = report(rows, **override)
        if args.by_round:
            signal, at_least = args.by_round.split(">=")
            gate = load_ranker_settings().doubt_gate.model_copy(update=override)
            for name in sorted({r["round"] for r in rows}, key=lambda n: int(n[1:])):
                o = rule_outcome([r for r in rows if r["round"] == name], signal, float(at_least), gate)
                n = sum(r["round"] == name for r in rows)
                print(f"{name}: {n} tasks, opens {o['opens']} ({o['opens'] / n:.2f} calls/task), scored "
                      f"{o['scored']}, overturned {o['overturned']} (right {o['right']}, wrong {o['wrong']}, "
                      f"neutral {o['neutral']}); unscored could win {o['unscored_could_win']}, "
                      f"lose {o['unscored_could_lose']}")
        args.out.with_suffix(".report.json").write_text(json.dumps(table, indent=1) + "\n", encoding="utf-8")
        return 0
    client: LLMClient | None = None
    try:
        if args.replay:
            client = make_client(f"replay:{CASSETTE}")
        elif args.score:
            from pmi_dev_rounds import CachedScorer  # a script beside this one

            from emboteam.llm.local_model import fetch_model

            CASSETTE.mkdir(parents=True, exist_ok=True)
            live = make_backend(parse_llm_spec(f"llamacpp:{args.model or fetch_model()}"), timeout=600)
            client = LLMClient(CachedScorer(live, CASSETTE))
        only = frozenset(args.only.read_text().split()) if args.only else frozenset()
        record(args.rounds, client, args.out, only)
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
