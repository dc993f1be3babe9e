"""PDDL: the domain generated from the catalogue, problems rendered from state + goals, the
Fast Downward runner and plan parsing (docs/planning.md)."""
