"""HP (Hybrid Planner): validation, allocation, Fast Downward per subtask, merge into one plan."""
