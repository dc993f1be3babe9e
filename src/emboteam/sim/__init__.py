"""The THOR-like symbolic simulator: action rules, side effects, time, contention, faults."""

from emboteam.sim.faults import Breakdown, FaultConfig, ObjectMove
from emboteam.sim.rules import Failure, apply_action, check_action, piece_ids
from emboteam.sim.simulator import RobotBusyError, SimEvent, Simulator

__all__ = [
    "Breakdown", "Failure", "FaultConfig", "ObjectMove", "RobotBusyError", "SimEvent", "Simulator",
    "apply_action", "check_action", "piece_ids",
]
