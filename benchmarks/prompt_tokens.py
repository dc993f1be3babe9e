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

Input tokens are counted three ways, one per API (``--api``), each over what that API
counts as input:

- ``llamacpp`` (exact): the tokenizer of the GGUF model (llama.cpp, vocab only) over the
  prompt as its chat template renders it, which is what ``prompt_tokens`` of a llama.cpp
  call reports (the schema is a grammar there, not prompt text);
- ``openai`` (APPROXIMATE): the messages plus OpenAI's per-message framing (4 tokens a
  message, 3 for the reply's start) plus the strict wire schema
  (``openai_backend.strict_subset``) as compact JSON, which OpenAI also counts as input.
  Counted with tiktoken's ``o200k_base`` when tiktoken and its encoding file are
  available, else with the GGUF model's tokenizer (Qwen2.5's 151k BPE, close to
  o200k_base on English and JSON), and labelled as such; OpenAI renders the schema in its
  own form, so even o200k_base over the JSON is an estimate;
- ``anthropic`` (APPROXIMATE): the system prompt and messages plus the tool definition
  (name and ``input_schema``) as compact JSON, with the same tokenizer; Anthropic's fixed
  tool-use system prompt (a few hundred tokens, per its documentation) is not included.

Without llama-cpp-python or a model, ``--approx`` counts characters / 4 (say so when
quoting it). The script uses only what the LLM front ends had before the prompts were
cut (``LLMFrontend.request``, ``HybridFrontend.request``), so it measures an older
checkout too (``PYTHONPATH=OLD/src``).

    .venv/bin/python benchmarks/prompt_tokens.py                 # fetches the model if needed
    .venv/bin/python benchmarks/prompt_tokens.py --model X.gguf --json --api openai
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
TextCounter = Callable[[str], int]
NO_CLIENT = cast(LLMClient, None)  # requests are only built here, never sent
#: OpenAI's chat framing: tokens per message and for the start of the reply
OPENAI_PER_MESSAGE, OPENAI_REPLY = 4, 3


def _compact(obj: Any) -> str:
    return json.dumps(obj, separators=(",", ":"), ensure_ascii=False)


def llama_tokenizer(model_path: Path) -> tuple[Any, TextCounter]:
    from llama_cpp import Llama

    llama = Llama(model_path=str(model_path), vocab_only=True, verbose=False)
    return llama, lambda text: len(llama.tokenize(text.encode("utf-8"), add_bos=False, special=False))


def llama_counter(llama: Any) -> Counter:
    """Tokens of a request's messages as the model's chat template renders them."""
    from llama_cpp.llama_chat_format import Jinja2ChatFormatter

    template = llama.metadata["tokenizer.chat_template"]
    eos = llama.detokenize([llama.token_eos()]).decode("utf-8", "replace")
    bos = llama.detokenize([llama.token_bos()]).decode("utf-8", "replace") if llama.token_bos() >= 0 else ""
    formatter = Jinja2ChatFormatter(template=template, eos_token=eos, bos_token=bos)

    def count(request: LLMRequest) -> int:
        prompt = formatter(messages=[{"role": m.role, "content": m.content} for m in request.messages]).prompt
        return len(llama.tokenize(prompt.encode("utf-8"), add_bos=False, special=True))
    return count


def o200k_counter() -> TextCounter | None:
    """tiktoken's o200k_base (GPT-4o's encoding), if tiktoken and its encoding file load."""
    try:
        import tiktoken

        enc = tiktoken.get_encoding("o200k_base")
    except Exception:  # not installed, or its encoding file cannot be fetched offline
        return None
    return lambda text: len(enc.encode(text))


def openai_counter(text_tokens: TextCounter) -> Counter:
    """Messages with OpenAI's framing, plus the strict wire schema (approximate)."""
    from emboteam.llm.openai_backend import strict_subset

    def count(request: LLMRequest) -> int:
        n = sum(OPENAI_PER_MESSAGE + text_tokens(m.content) for m in request.messages) + OPENAI_REPLY
        if request.json_schema is not None:
            n += text_tokens(_compact({"name": request.schema_name, "schema": strict_subset(request.json_schema),
                                       "strict": True}))
        return n
    return count


def anthropic_counter(text_tokens: TextCounter) -> Counter:
    """System prompt, messages and the forced tool's definition (approximate)."""
    def count(request: LLMRequest) -> int:
        n = sum(text_tokens(m.content) for m in request.messages)
        if request.json_schema is not None:
            n += text_tokens(_compact({"name": request.schema_name, "input_schema": request.json_schema}))
        return n
    return count


def approx_counter(request: LLMRequest) -> int:
    schema = len(_compact(request.json_schema)) if request.json_schema is not None else 0
    return (sum(len(m.content) for m in request.messages) + schema) // 4


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


def choose_counter(api: str, model: Path | None, approx: bool) -> tuple[Counter, str]:
    if approx:
        return approx_counter, "characters / 4, schema included (APPROXIMATE)"
    from emboteam.llm.local_model import fetch_model

    path = model or fetch_model()
    llama, qwen = llama_tokenizer(path)
    if api == "llamacpp":
        return llama_counter(llama), f"llama.cpp tokenizer of {path.name} over the chat template (exact)"
    o200k = o200k_counter()
    text, name = (o200k, "tiktoken o200k_base") if o200k is not None else (qwen, f"the tokenizer of {path.name}")
    if api == "openai":
        return openai_counter(text), (f"{name}: messages + OpenAI framing + strict wire schema "
                                      "(APPROXIMATE: OpenAI's own count is not available offline)")
    return anthropic_counter(text), (f"{name}: system + messages + tool input_schema (APPROXIMATE; "
                                     "without Anthropic's fixed tool-use system prompt)")


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", type=Path, help="GGUF file whose tokenizer counts (default: fetch the local model)")
    ap.add_argument("--api", choices=("llamacpp", "openai", "anthropic"), default="llamacpp",
                    help="count input as this API does (openai and anthropic: approximate, schema included)")
    ap.add_argument("--approx", action="store_true", help="count characters / 4 instead of tokens")
    ap.add_argument("--json", action="store_true", help="one JSON object on stdout")
    args = ap.parse_args(argv)
    try:
        count, how = choose_counter(args.api, args.model, args.approx)
    except EmboTeamError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    stats = measure(count)
    if args.json:
        print(json.dumps({"api": args.api, "counted_with": how, "suite": "mace-thor", "prompts": stats}))
        return 0
    print(f"PFG input tokens per call on MACE-THOR, as {args.api} counts them ({how}):")
    print(f"{'prompt':<12} {'calls':>5} {'median':>7} {'mean':>7} {'min':>5} {'max':>5}")
    for name, s in stats.items():
        print(f"{name:<12} {s['calls']:>5} {s['median']:>7g} {s['mean']:>7g} {s['min']:>5} {s['max']:>5}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
