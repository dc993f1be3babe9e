"""EXEC: the reactive executor, blackboard protocol, replanning, dynamic team, trace."""
