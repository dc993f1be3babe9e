"""EmboTeam: household instructions -> PDDL -> merged multi-robot plan -> reactive behavior trees.

Stages, one package each: ``world`` (objects, scenes, robots, goals), ``sim`` (the
AI2-THOR-like symbolic simulator), ``pddl`` (domain, problems, Fast Downward), ``llm``
(backends), ``pfg`` (instruction -> TaskSpec), ``hp`` (hybrid planner), ``btc`` (behavior
tree compiler), ``exec`` (reactive executor), ``bench`` (MACE-THOR, metrics, runner).
"""

__version__ = "0.1.0"
