"""LLM backends behind one interface: OpenAI-compatible, Anthropic, local llama.cpp, record/replay."""
