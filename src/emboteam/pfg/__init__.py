"""PFG (PDDL File Generator): instruction -> TaskSpec, by an LLM, the offline parser or the oracle."""
