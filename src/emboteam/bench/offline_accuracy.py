"""Parse accuracy of the offline parser on an instruction set (JSON lines).

Each line: ``{"id", "scene", "instruction", "goal": [conditions]}`` or ``{..., "error":
"GroundingError"}``; optional ``"robots": "1,2"`` and ``"setup": [state changes]`` (the
initial-state changes of a benchmark task, e.g. ``{"object": "RemoteControl_1", "parent":
"Drawer_2"}``: "the remote is in one of the drawers" needs the remote to be there). A parse is correct when its final goal
equals the expected one as a set of conditions, modulo these equivalences (documented in
docs/offline_parser.md):

- a receptacle and its basin are one place (Sink = SinkBasin, Bathtub = BathtubBasin);
- ``cold(X)`` = ``inside(X, Fridge)`` (the fridge is how things get cold);
- an object id = its type when the scene has one object of that type;
- a state of a slice type = that state of its whole (``cooked(BreadSliced)`` =
  ``cooked(Bread)``: type references match slices);
- the order of types in ``A|B`` does not matter;
- ``sliced(X)`` next to a condition that needs X cut (``cooked(Bread)``,
  ``inside(AppleSliced, Bowl)``) adds nothing: both goals hold in the same states.

Run: ``python -m emboteam.bench.offline_accuracy tests/data/offline_dev.jsonl [-v]``
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from emboteam.errors import EmboTeamError
from emboteam.pfg.offline.frontend import OfflineFrontend
from emboteam.sim.setup import StateChange, apply_changes
from emboteam.world.catalogue import load_catalogue, place_types
from emboteam.world.goals import Condition, ObjectRef, Predicate
from emboteam.world.robots import RobotProfile, parse_team
from emboteam.world.scene import Scene, load_scene
from emboteam.world.state import WorldState

Key = tuple[str, frozenset[str], int, frozenset[str], str]


def _ref_key(ref: ObjectRef, scene: Scene, fold_slices: bool) -> frozenset[str]:
    cat = load_catalogue()
    if ref.id is not None:
        t = ref.id.split("_")[0]
        if "_Slice_" not in ref.id and len(scene.of_type(t)) == 1:
            return frozenset({t})
        return frozenset({ref.id})
    types = ref.types
    if fold_slices:
        types = tuple(cat.source_type(t) or t for t in types)
    return frozenset(types)


def condition_key(c: Condition, scene: Scene) -> Key:
    """A canonical form of a condition under the documented equivalences."""
    pred = c.predicate
    receptacle: frozenset[str] = frozenset()
    if pred is Predicate.cold:
        pred = Predicate.inside
        receptacle = frozenset({"Fridge"})
    elif c.receptacle is not None:
        rk = _ref_key(c.receptacle, scene, False)
        receptacle = frozenset(place_types(tuple(rk)))
    subject = _ref_key(c.subject, scene, pred is not Predicate.inside)
    liquid = c.liquid or ""
    if pred is Predicate.filled and not liquid:
        liquid = "water"
    return (pred.value, subject, c.count, receptacle, liquid)


def _implied_slicing(conditions: Sequence[Condition]) -> set[str]:
    """Wholes the goal cannot be met without cutting: a condition on their pieces
    (``inside(AppleSliced, Bowl)``) or cooking what only their pieces can be
    (``cooked(Bread)``)."""
    cat = load_catalogue()
    out: set[str] = set()
    for c in conditions:
        for t in c.subject.types:
            whole = cat.source_type(t)
            if whole is not None:
                out.add(whole)
            product = cat.slice_product(t)
            if c.predicate is Predicate.cooked and product is not None and \
                    not cat.type(t).has("cookable") and cat.type(product[0]).has("cookable"):
                out.add(t)
    return out


def goal_keys(conditions: Iterable[Condition], scene: Scene) -> frozenset[Key]:
    """Canonical keys of a goal; ``sliced(X)`` is left out when the rest of the goal
    already requires X cut (the two goals hold in exactly the same states)."""
    conds = list(conditions)
    implied = _implied_slicing(conds)
    return frozenset(condition_key(c, scene) for c in conds
                     if not (c.predicate is Predicate.sliced and c.subject.id is None
                             and set(c.subject.types) <= implied))


@dataclass
class Outcome:
    id: str
    instruction: str
    correct: bool
    expected: str
    got: str
    seconds: float


def evaluate_record(rec: dict[str, object], frontend: OfflineFrontend | None = None) -> Outcome:
    """Parse one record and compare with its expectation."""
    frontend = frontend or OfflineFrontend()
    scene = load_scene(str(rec["scene"]))
    team = parse_team(str(rec.get("robots", "1,2,3")))
    state = initial_state(rec, scene, team)
    text = str(rec["instruction"])
    expected_error = rec.get("error")
    start = time.perf_counter()
    kinds: set[str] = set()
    try:
        spec = frontend.decompose(text, scene, state, team)
        conditions = spec.goal().conditions
        got_conditions: tuple[Condition, ...] | None = conditions
        got = " & ".join(str(c) for c in conditions)
        error = None
    except EmboTeamError as exc:
        got_conditions = None
        error = type(exc).__name__
        got = f"{error}: {exc}"
        # the expected error names a class: any subclass of it is that error too
        kinds = {k.__name__ for k in type(exc).__mro__}
    seconds = time.perf_counter() - start
    if expected_error is not None:
        ok = error is not None and expected_error in kinds
        return Outcome(str(rec["id"]), text, ok, str(expected_error), got, seconds)
    goal = rec["goal"]
    assert isinstance(goal, list)
    expected = [Condition.parse(str(g)) for g in goal]
    ok = got_conditions is not None and goal_keys(got_conditions, scene) == goal_keys(expected, scene)
    del got_conditions
    return Outcome(str(rec["id"]), text, ok, " & ".join(str(c) for c in expected), got, seconds)


def initial_state(rec: dict[str, object], scene: Scene,
                  team: Sequence[RobotProfile]) -> WorldState:
    """The state a record starts from: the scene's, with the record's ``setup`` applied."""
    state = WorldState.from_scene(scene, team)
    setup = rec.get("setup") or []
    assert isinstance(setup, list)
    apply_changes(state, [StateChange.model_validate(c) for c in setup])
    return state


def load_records(path: Path) -> list[dict[str, object]]:
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def evaluate(records: Sequence[dict[str, object]]) -> list[Outcome]:
    frontend = OfflineFrontend()
    return [evaluate_record(r, frontend) for r in records]


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", type=Path)
    parser.add_argument("-v", "--verbose", action="store_true", help="print every failure")
    args = parser.parse_args(argv)
    for path in args.files:
        outcomes = evaluate(load_records(path))
        n_ok = sum(o.correct for o in outcomes)
        worst = max(o.seconds for o in outcomes)
        mean = sum(o.seconds for o in outcomes) / len(outcomes)
        print(f"{path}: {n_ok}/{len(outcomes)} = {n_ok / len(outcomes):.3f} "
              f"(mean {mean * 1000:.2f} ms, max {worst * 1000:.2f} ms per instruction)")
        if args.verbose:
            for o in outcomes:
                if not o.correct:
                    print(f"  {o.id}: {o.instruction}\n     expected {o.expected}\n     got      {o.got}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
