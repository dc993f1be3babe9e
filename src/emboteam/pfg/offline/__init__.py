"""The offline parser: the PFG's embedded default front end (rule-based, no LLM).

``OfflineFrontend().decompose(instruction, scene, state, team) -> TaskSpec``;
``OfflineFrontend().parse(...) -> Reading`` also gives a note per unread span and the
conditions chosen with doubt.
Errors are :class:`OfflineParseError` and its subclass :class:`GroundingError`. See
docs/offline_parser.md.
"""

from emboteam.pfg.offline.errors import GroundingError, OfflineParseError
from emboteam.pfg.offline.frontend import OfflineFrontend

__all__ = ["GroundingError", "OfflineFrontend", "OfflineParseError"]
