"""MACE-THOR with a real local model: Qwen2.5-Coder-0.5B-Instruct (GGUF) through llama.cpp.

Runs the full system (``RunConfig(mode="full")``, no faults, seed 0) with

- ``--frontend llm`` (the paper's pure LLM front end) on a fixed subset of
  :data:`LLM_SUBSET` (9 tasks over every floor plan; a call takes about a minute with one
  thread on the shared machine);
- ``--frontend hybrid --llm-when doubt`` on all 42 tasks (the LLM is asked only when the
  offline reading is in doubt);
- ``--frontend offline`` on the same tasks, the reference hybrid must not fall below.

Every LLM call is recorded into ``benchmarks/llm_local/cassettes/<front end>/`` and every
episode's metrics into ``benchmarks/llm_local/results.json``; the table goes into its own
section of docs/results.md. The run is resumable: a task already in results.json is not
run again (``--redo`` runs the chosen tasks again, ``--fresh`` also drops the front end's
cassette first, for when the prompts changed).

``--replay`` runs the recorded tasks again from the cassettes (``--llm replay:DIR``, no
model needed) and exits 1 if any metric differs from results.json.

    .venv/bin/python benchmarks/llm_local.py                          # everything (about an hour)
    .venv/bin/python benchmarks/llm_local.py --frontend llm --tasks fp1-fridge-apple-tomato
    .venv/bin/python benchmarks/llm_local.py --replay                 # seconds, no model
    EMBOTEAM_LLAMACPP_THREADS=1 nice .venv/bin/python benchmarks/llm_local.py --frontend llm

On a machine shared with other busy processes use ONE thread: llama.cpp's threads meet
at a spinning barrier after every operation, so a second thread that is not scheduled
stalls the first (measured on the 2-core machine at load 5-6: 0.03-0.05 s per generated
token with 1 thread, 0.1-0.64 s with 2; prompt 84-139 against 34-62 tokens/s).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import statistics
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from emboteam.bench.mace_thor import load_mace_thor
from emboteam.errors import EmboTeamError
from emboteam.pipeline import RunConfig, run_episode
from emboteam.task import BenchTask

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "llm_local"
RESULTS = OUT / "results.json"
DOC = ROOT / "docs" / "results.md"
START, END = "<!-- llm_local:start -->", "<!-- llm_local:end -->"

#: the fixed subset the pure LLM front end runs on (one to two tasks per floor plan,
#: both categories; the first is the task where this model used to copy the example)
LLM_SUBSET = ("fp1-fridge-apple-tomato", "fp1-coffee-and-light", "fp6-salad-prep", "fp15-set-table",
              "fp21-cup-of-water", "fp201-box-card-pen", "fp209-laptop-sofa", "fp303-desk-clear",
              "fp414-plunger")
FRONTENDS = ("offline", "hybrid", "llm")
#: what must reproduce exactly on replay (of the error: its type; its message may name the backend)
METRICS = ("success", "gcr", "exec", "llm_calls", "tokens", "error")


def cassette_dir(frontend: str) -> Path:
    return OUT / "cassettes" / frontend


def tasks_of(frontend: str, only: Sequence[str]) -> list[BenchTask]:
    tasks = {t.id: t for t in load_mace_thor()}
    unknown = [t for t in only if t not in tasks]
    if unknown:
        raise EmboTeamError(f"no MACE-THOR task {', '.join(unknown)}")
    ids = list(LLM_SUBSET) if frontend == "llm" else list(tasks)
    chosen = [tasks[i] for i in ids if not only or i in only]
    if only:  # in the order given
        return sorted(chosen, key=lambda t: list(only).index(t.id))
    if frontend == "hybrid":  # the tasks that need no call first: a short run still covers them
        chosen.sort(key=needs_llm)
    return chosen


def needs_llm(task: BenchTask) -> bool:
    """Whether the hybrid front end will call the LLM on ``task`` (a doubtful reading or a
    parser error), found by running the offline parser alone (milliseconds)."""
    from emboteam.pfg.doubt import needs_review
    from emboteam.pfg.hybrid import as_reading
    from emboteam.pfg.parser import offline_frontend
    from emboteam.world.scene import load_scene

    state, team = task.initial_state(), task.team()
    try:
        reading = as_reading(offline_frontend().parse(task.instruction, load_scene(task.floor_plan), state, team))
        return needs_review(reading, task.instruction, state)
    except EmboTeamError:
        return True


def config(frontend: str, llm: str | None, record: Path | None, timeout: float) -> RunConfig:
    return RunConfig(mode="full", frontend=frontend, llm=llm if frontend != "offline" else None,
                     llm_record=str(record) if record is not None and frontend != "offline" else None,
                     llm_timeout=timeout, llm_when="doubt")


def row_of(task: BenchTask, cfg: RunConfig) -> dict[str, Any]:
    started = time.perf_counter()
    ep = run_episode(task, cfg)
    return {"task": task.id, "success": ep.success, "gcr": round(ep.gcr, 4), "exec": round(ep.exec, 4),
            "llm_calls": ep.llm_calls, "tokens": ep.tokens, "seconds": round(time.perf_counter() - started, 1),
            "error": ep.error}


def load_results() -> dict[str, Any]:
    if RESULTS.exists():
        data: dict[str, Any] = json.loads(RESULTS.read_text())
        return data
    return {"model": None, "runs": {}}


def write_results(data: dict[str, Any]) -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    tmp = RESULTS.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    tmp.replace(RESULTS)


def save_results(data: dict[str, Any], frontend: str) -> None:
    """Write ``frontend``'s rows into results.json, keeping the other front ends' rows as
    they are on disk (two runs of this script, one per front end, may share the file)."""
    on_disk = load_results()
    on_disk["model"] = data["model"]
    on_disk["runs"].setdefault(frontend, {}).update(data["runs"][frontend])
    write_results(on_disk)


def drop_results(frontend: str) -> None:
    """Remove ``frontend``'s rows from results.json (``--fresh``): a row not run again must
    not stay behind, its calls gone with the old cassette."""
    on_disk = load_results()
    if on_disk["runs"].pop(frontend, None) is not None:
        write_results(on_disk)


def record(frontends: Sequence[str], only: Sequence[str], model: Path, *, redo: bool, fresh: bool,
           timeout: float) -> dict[str, Any]:
    data = load_results()
    data["model"] = model.name
    spec = f"llamacpp:{model}"
    for frontend in frontends:
        if fresh and frontend != "offline":
            shutil.rmtree(cassette_dir(frontend), ignore_errors=True)
            data["runs"].pop(frontend, None)
            drop_results(frontend)
        else:
            data["runs"][frontend] = load_results()["runs"].get(frontend, {})
        rows: dict[str, Any] = data["runs"].setdefault(frontend, {})
        for task in tasks_of(frontend, only):
            if task.id in rows and not redo:
                continue
            print(f"{frontend:8} {task.id} ...", end=" ", flush=True)
            row = row_of(task, config(frontend, spec, cassette_dir(frontend), timeout))
            rows[task.id] = row
            save_results(data, frontend)  # after every task: a killed run loses one task at most
            print(f"success={row['success']} calls={row['llm_calls']} tokens={row['tokens']} "
                  f"{row['seconds']} s {row['error'] or ''}", flush=True)
    return data


def replay(data: dict[str, Any]) -> list[str]:
    """Each recorded episode that used the LLM again from its cassette; the differences,
    one line each (a hybrid task that made no call is the offline reading: not replayed)."""
    diffs: list[str] = []
    tasks = {t.id: t for t in load_mace_thor()}
    for frontend, rows in data["runs"].items():
        if frontend == "offline":
            continue
        for task_id, want in rows.items():
            if frontend == "hybrid" and not want["llm_calls"]:
                continue
            llm = f"replay:{cassette_dir(frontend)}"
            got = row_of(tasks[task_id], config(frontend, llm, None, 60.0))
            for m in METRICS:
                same = (got[m] or "").split(":", 1)[0] == (want[m] or "").split(":", 1)[0] if m == "error" \
                    else got[m] == want[m]
                if not same:
                    diffs.append(f"{frontend} {task_id} {m}: recorded {want[m]!r}, replayed {got[m]!r}")
    return diffs


def summary(rows: Sequence[dict[str, Any]]) -> dict[str, Any]:
    n = len(rows)
    calls = [r["llm_calls"] for r in rows]
    called = [r for r in rows if r["llm_calls"]]
    return {"tasks": n, "sr": sum(r["success"] for r in rows) / n, "gcr": statistics.fmean(r["gcr"] for r in rows),
            "exec": statistics.fmean(r["exec"] for r in rows), "calls_per_task": sum(calls) / n,
            "tokens_per_task": statistics.fmean(r["tokens"] for r in rows),
            "seconds_per_task": statistics.fmean(r["seconds"] for r in rows),
            "seconds_per_called_task": statistics.fmean(r["seconds"] for r in called) if called else 0.0,
            "errors": sum(1 for r in rows if r["error"])}


def table(data: dict[str, Any]) -> str:
    runs = data["runs"]
    lines = ["| front end | tasks | SR | GCR | Exec | LLM calls / task | tokens / task | s / task | "
             "errors |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]

    def add(label: str, rows: list[dict[str, Any]]) -> None:
        if not rows:
            return
        s = summary(rows)
        lines.append(f"| {label} | {s['tasks']} | {s['sr']:.3f} | {s['gcr']:.3f} | {s['exec']:.3f} | "
                     f"{s['calls_per_task']:.2f} | {s['tokens_per_task']:.0f} | {s['seconds_per_task']:.1f} | "
                     f"{s['errors']} |")

    offline = runs.get("offline", {})
    for frontend in ("hybrid", "llm"):
        rows = list(runs.get(frontend, {}).values())
        if not rows:
            continue
        ids = [r["task"] for r in rows]
        add(f"`{frontend}`" + (" (`--llm-when doubt`)" if frontend == "hybrid" else ""), rows)
        add(f"`offline`, same {len(ids)} tasks", [offline[i] for i in ids if i in offline])
    return "\n".join(lines)


#: long phrases of the feedback, shortened so the table shows what the checks found
_SHORTER = ((re.compile(r"no acceptable answer after (\d+) call\(s\); last problems: - "), r"\1 calls, last: "),
            (re.compile(r"the answer is not a JSON object: it was cut off at the (\d+)-token limit; state each "
                        r"condition once, in fewer and shorter items"), r"cut at \1 tokens"),
            (re.compile(r" ?- in the part before the cut: "), "; before the cut: "),
            (re.compile(r": give each subtask once"), ""),
            (re.compile(r", which the instruction does not mention \(it is from the worked example, not this "
                        r"task\): remove it"), " (copied from the example)"))


def short_error(error: str) -> str:
    for pattern, repl in _SHORTER:
        error = pattern.sub(repl, error)
    return error


def per_task(data: dict[str, Any], frontend: str) -> str:
    rows = [r for r in data["runs"].get(frontend, {}).values() if frontend == "llm" or r["llm_calls"]]
    if not rows:
        return ""
    out = ["| task | success | GCR | LLM calls | tokens | s | error |", "|---|---|---:|---:|---:|---:|---|"]
    for r in rows:
        err = short_error(r["error"] or "").replace("|", "/")
        err = err if len(err) <= 240 else err[:240] + "..."
        out.append(f"| {r['task']} | {'yes' if r['success'] else 'no'} | {r['gcr']:.2f} | {r['llm_calls']} | "
                   f"{r['tokens']} | {r['seconds']:.0f} | {err} |")
    return "\n".join(out)


def call_stats(frontend: str) -> str:
    """One line on the recorded calls of ``frontend`` (from its cassette): how long a call
    took and how fast llama.cpp generated, the numbers that decide how big a run fits.
    Scoring calls (the model ranker's PMI, no completion) are counted apart."""
    every = [json.loads(p.read_text()) for p in sorted(cassette_dir(frontend).glob("*.json"))
             if p.name != "cassette.json"]
    scores = [e for e in every if e.get("kind") == "score"]
    entries = [e for e in every if e.get("kind") != "score"]
    answered = [e["response"] for e in entries if "response" in e]
    if not answered:
        return ""
    lat = [r["latency"] for r in answered]
    out_tokens = [r["output_tokens"] for r in answered]
    cut = sum(1 for r in answered if r["finish_reason"] == "length")
    timeouts = len(entries) - len(answered)
    return (f"`{frontend}`: {len(entries)} recorded calls, {timeouts} timed out; per answered call median "
            f"{statistics.median(lat):.0f} s (max {max(lat):.0f} s), prompt median "
            f"{statistics.median(r['input_tokens'] for r in answered):.0f} tokens, completion median "
            f"{statistics.median(out_tokens):.0f} tokens ({cut} cut at the cap), "
            f"{sum(out_tokens) / sum(lat):.1f} completion tokens per second of call"
            + (f"; and {len(scores)} scoring calls." if scores else "."))


def write_doc(data: dict[str, Any]) -> None:
    """Replace this script's section of docs/results.md (between its markers)."""
    missing = {f: [t.id for t in tasks_of(f, ()) if t.id not in data["runs"].get(f, {})] for f in ("hybrid", "llm")}
    gaps = "; ".join(f"`{f}` has not run {', '.join(ids)} yet" for f, ids in missing.items() if ids)
    body = [START, "", "## A real local model: Qwen2.5-Coder-0.5B-Instruct through llama.cpp", "",
            f"Model `{data['model']}` (GGUF, fetched and verified by `python -m emboteam.llm.local_model`), "
            "run in process by llama.cpp on the CPU, `mode=full`, no faults, seed 0. "
            f"`llm` runs the fixed subset of {len(LLM_SUBSET)} tasks in `benchmarks/llm_local.py` "
            "(`LLM_SUBSET`); `hybrid` runs all 42 tasks with `--llm-when doubt`"
            + (f" ({gaps}: the run is resumable)" if gaps else "") + ". Seconds are wall-clock "
            "on a shared, loaded 2-core machine (noisy); tokens are llama.cpp's prompt + completion "
            "counts. A 0.5B model is weak: these numbers say what it does, not what an LLM front end can do.",
            "", "```", ".venv/bin/python benchmarks/llm_local.py          # records what is missing (resumable)",
            ".venv/bin/python benchmarks/llm_local.py --replay # the same numbers from the cassettes", "```",
            "", table(data), ""]
    stats = [line for line in (call_stats(f) for f in ("hybrid", "llm")) if line]
    if stats:
        body += ["Calls (wall-clock as recorded, prompt evaluation included):", "",
                 *(f"- {line}" for line in stats), ""]
    for frontend in ("hybrid", "llm"):
        detail = per_task(data, frontend)
        if detail:
            label = "tasks where `hybrid` called the LLM" if frontend == "hybrid" else "`llm`"
            body += [f"Per task, {label}:", "", detail, ""]
    body.append(END)
    text = DOC.read_text(encoding="utf-8")
    section = "\n".join(body)
    if START in text and END in text:
        head, rest = text.split(START, 1)
        _, tail = rest.split(END, 1)
        text = head + section + tail
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    DOC.write_text(text, encoding="utf-8")


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--frontend", action="append", choices=FRONTENDS, help="repeatable; default all three")
    ap.add_argument("--tasks", nargs="*", default=[], help="task ids (default: each front end's set)")
    ap.add_argument("--model", type=Path, help="GGUF file (default: fetch and verify the Qwen 0.5B model)")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per LLM call")
    ap.add_argument("--redo", action="store_true", help="run tasks already in results.json again")
    ap.add_argument("--fresh", action="store_true", help="drop the front end's cassette and results first")
    ap.add_argument("--replay", action="store_true", help="replay the cassettes and compare with results.json")
    ap.add_argument("--no-doc", action="store_true", help="do not rewrite the docs/results.md section")
    ap.add_argument("--doc-only", action="store_true", help="only rewrite the docs/results.md section")
    args = ap.parse_args(argv)
    if args.doc_only:
        write_doc(load_results())
        print(table(load_results()))
        return 0
    try:
        if args.replay:
            diffs = replay(load_results())
            for d in diffs:
                print(d)
            print("replay: " + ("all recorded metrics reproduced" if not diffs else f"{len(diffs)} difference(s)"))
            return 1 if diffs else 0
        from emboteam.llm.local_model import fetch_model

        model = args.model or fetch_model()
        data = record(args.frontend or FRONTENDS, args.tasks, model, redo=args.redo, fresh=args.fresh,
                      timeout=args.timeout)
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    data = load_results()  # with the rows another run of this script may have added
    if not args.no_doc:
        write_doc(data)
    print(table(data))
    return 0


if __name__ == "__main__":
    sys.exit(main())
