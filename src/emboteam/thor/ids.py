"""Our stable ids (``Apple_1``) <-> AI2-THOR objectIds (``Apple|-00.47|+01.15|+00.48``).

The scene data keeps each object's objectId (``SceneObject.thor_id``). AI2-THOR's
objectIds encode the object's position when the scene loads, so they stay the same while
the object moves; the pieces of a sliced (or cracked) object get AI2-THOR's id
``<whole objectId>|<PieceType>_<n>`` counted from 0, which we name ``<whole>_Slice_<n+1>``
as the symbolic simulator does.
"""

from __future__ import annotations

import re

from emboteam.errors import UnknownObjectError
from emboteam.world.scene import Scene

_PIECE = re.compile(r"^(?P<whole>.+)\|(?P<type>[A-Za-z]+)_(?P<n>\d+)$")
_OUR_PIECE = re.compile(r"^(?P<whole>[A-Za-z]+_\d+)_Slice_(?P<k>\d+)$")


class ThorIds:
    """The id mapping of one floor plan, both ways."""

    def __init__(self, scene: Scene) -> None:
        self.floor_plan = scene.floor_plan
        self._thor = {o.id: o.thor_id for o in scene.objects}
        self._ours = {o.thor_id: o.id for o in scene.objects}
        #: piece objectIds seen in metadata: our piece id -> AI2-THOR objectId
        self._pieces: dict[str, str] = {}

    def thor(self, object_id: str) -> str:
        """The objectId of one of our ids (a slice piece once AI2-THOR has spawned it)."""
        if object_id in self._thor:
            return self._thor[object_id]
        if object_id in self._pieces:
            return self._pieces[object_id]
        raise UnknownObjectError(f"{object_id!r} has no AI2-THOR objectId in {self.floor_plan}"
                                 + (" (not sliced yet)" if _OUR_PIECE.match(object_id) else ""))

    def ours(self, thor_id: str) -> str | None:
        """Our id of an objectId, or None for an object the scene data does not know."""
        if thor_id in self._ours:
            return self._ours[thor_id]
        m = _PIECE.match(thor_id)
        if m is None:
            return None
        whole = self._ours.get(m["whole"])
        if whole is None or not m["type"].startswith(whole.rsplit("_", 1)[0]):
            return None
        piece = f"{whole}_Slice_{int(m['n']) + 1}"
        self._pieces[piece] = thor_id
        return piece

    def __contains__(self, object_id: object) -> bool:
        return object_id in self._thor or object_id in self._pieces
