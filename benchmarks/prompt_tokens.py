"""Input tokens of the PFG prompts on MACE-THOR, before and after they were cut.

For every MACE-THOR task this builds, without calling any model, the first request each
front end would send:

- ``llm-before``: the LLM front end as it was (three worked examples, the whole scene
  listed with ids and state): ``LLMFrontend(fewshot=3, focus=False)``;
- ``llm``: the LLM front end now (one example, only the types the instruction touches in
  full, the rest by name);
- ``hybrid``: the hybrid front end's review request (draft, notes, focused scene; no
  example), or its writing request when the offline parser fails on the task. With
  ``--llm-when doubt`` only doubtful readings send it; this counts it for every task
  (what ``--llm-when always`` sends).

Tokens are counted with the tokenizer of the GGUF model (llama.cpp, vocab only) over the
prompt as its chat template renders it, which is what ``prompt_tokens`` of a llama.cpp
call reports. Without llama-cpp-python or a model, ``--approx`` counts characters / 4
(say so when quoting it).

    .venv/bin/python benchmarks/prompt_tokens.py                 # fetches the model if needed
    .venv/bin/python benchmarks/prompt_tokens.py --model X.gguf --json
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, cast

from emboteam.bench.mace_thor import load_mace_thor
from emboteam.errors import EmboTeamError
from emboteam.llm.client import LLMClient
from emboteam.llm.messages import LLMRequest
from emboteam.pfg.hybrid import HybridFrontend, as_reading
from emboteam.pfg.llm_frontend import LLMFrontend
from emboteam.pfg.offline import OfflineFrontend
from emboteam.world.scene import load_scene

Counter = Callable[[LLMRequest], int]
NO_CLIENT = cast(LLMClient, None)  # requests are only built here, never sent


def llama_counter(model_path: Path) -> Counter:
    """Tokens of a request's messages as the model's chat template renders them."""
    from llama_cpp import Llama
    from llama_cpp.llama_chat_format import Jinja2ChatFormatter

    llama = Llama(model_path=str(model_path), vocab_only=True, verbose=False)
    template = llama.metadata["tokenizer.chat_template"]
    eos = llama.detokenize([llama.token_eos()]).decode("utf-8", "replace")
    bos = llama.detokenize([llama.token_bos()]).decode("utf-8", "replace") if llama.token_bos() >= 0 else ""
    formatter = Jinja2ChatFormatter(template=template, eos_token=eos, bos_token=bos)

    def count(request: LLMRequest) -> int:
        prompt = formatter(messages=[{"role": m.role, "content": m.content} for m in request.messages]).prompt
        return len(llama.tokenize(prompt.encode("utf-8"), add_bos=False, special=True))
    return count


def approx_counter(request: LLMRequest) -> int:
    return sum(len(m.content) for m in request.messages) // 4


def requests_of_task(task: Any, parser: OfflineFrontend) -> dict[str, LLMRequest]:
    scene = load_scene(task.floor_plan)
    state, team = task.initial_state(), task.team()
    before = LLMFrontend(NO_CLIENT, fewshot=3, focus=False)
    now = LLMFrontend(NO_CLIENT)
    out = {"llm-3ex-full": before.request(task.instruction, scene, state, team),
           "llm": now.request(task.instruction, scene, state, team)}
    hybrid = HybridFrontend(NO_CLIENT, parser.parse, llm=now)
    try:
        draft = as_reading(parser.parse(task.instruction, scene, state, team))
    except EmboTeamError as exc:
        out["hybrid"] = now.request(task.instruction, scene, state, team, hint=f"An offline parser could not "
                                    f"read this instruction: {exc}. Decompose what the user asks for.")
    else:
        out["hybrid"] = hybrid.request(draft, task.instruction, scene, state, team)
    return out


def measure(count: Counter) -> dict[str, dict[str, Any]]:
    parser = OfflineFrontend()
    per: dict[str, list[int]] = {}
    for task in load_mace_thor():
        for name, request in requests_of_task(task, parser).items():
            per.setdefault(name, []).append(count(request))
    return {name: {"calls": len(v), "median": statistics.median(v), "mean": round(statistics.fmean(v), 1),
                   "min": min(v), "max": max(v)} for name, v in per.items()}


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", type=Path, help="GGUF file whose tokenizer counts (default: fetch the local model)")
    ap.add_argument("--approx", action="store_true", help="count characters / 4 instead of tokens")
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout")
    args = ap.parse_args(argv)
    count: Counter
    if args.approx:
        count, how = approx_counter, "characters / 4"
    else:
        from emboteam.llm.local_model import fetch_model

        try:
            model = args.model or fetch_model()
        except EmboTeamError as exc:
            print(f"error: {exc}", file=sys.stderr)
            return 2
        count, how = llama_counter(model), f"llama.cpp tokenizer of {model.name}"
    stats = measure(count)
    if args.json:
        print(json.dumps({"counted_with": how, "suite": "mace-thor", "prompts": stats}))
        return 0
    print(f"PFG input tokens per call on MACE-THOR ({how}):")
    print(f"{'prompt':<12} {'calls':>5} {'median':>7} {'mean':>7} {'min':>5} {'max':>5}")
    for name, s in stats.items():
        print(f"{name:<12} {s['calls']:>5} {s['median']:>7g} {s['mean']:>7g} {s['min']:>5} {s['max']:>5}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
