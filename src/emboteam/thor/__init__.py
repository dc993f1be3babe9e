"""Execution in a real AI2-THOR (``--env ai2thor``): an Environment on ``ai2thor.controller``.

One module per concern: :mod:`.launch` probes for a usable AI2-THOR build and starts the
controller, :mod:`.ids` maps our stable ids to AI2-THOR objectIds, :mod:`.convert` turns
``event.metadata`` into a :class:`~emboteam.world.state.WorldState`, :mod:`.skills` turns
each skill into controller actions, :mod:`.failures` reads ``errorMessage`` into typed
failure reasons, :mod:`.setup` applies a task's initial-state changes, and
:mod:`.environment` is the adapter the executor drives.

The ``ai2thor`` package is optional (``pip install 'emboteam[ai2thor]'``) and imported
lazily: nothing here imports it at module level, so the default install never needs it.
"""
