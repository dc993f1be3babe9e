"""The hybrid planner's stages, each a module with one entry point that takes the
planning :class:`~emboteam.hp.stages.context.Context` and returns a typed result; the
:class:`~emboteam.hp.planner.HybridPlanner` only composes them, as
:class:`~emboteam.hp.planner.PlannerConfig` chooses:

- :mod:`.decomposed`: decompose (clusters, allocation, planning units), solve (Fast
  Downward, in rounds; each unit's plan eliminated, replayed, accepted), eliminate over the
  whole sequence and merge (:mod:`.merge`: partial order, validation) -> a
  :class:`.context.Draft`;
- the improvements, each ``(Context, Draft) -> Draft`` and kept only when the simulated
  makespan is shorter: :mod:`.reallocate` (re-allocation from measured plans),
  :mod:`.split` (two or more robots on one long cluster), :mod:`.reorder` (who goes first
  at a shared spot), :mod:`.route` (the jobs on shorter routes, walked as the simulator
  drives, the drives planned again), :mod:`.take_over` (a switch others waited for,
  done by one of them), :mod:`.schedule` (CP-SAT over the whole schedule:
  small plans with ``schedule="fast"``, every plan it can model with ``"optimal"``);
- :mod:`.rebuilt`: what the improvements that rebuild a plan share (replay to the goal,
  merge and simulate, keep when shorter);
- the fallback and the ablation: :mod:`.joint` (one joint problem), :mod:`.concatenate`
  (the no-HP pipeline).
"""
