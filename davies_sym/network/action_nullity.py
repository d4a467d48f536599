"""The check of the action network's null space: the input torque is free, and it alone
determines every action (Laus eqs. (2), (23))."""

from __future__ import annotations

from collections.abc import Sequence

from davies_sym.errors import Problem
from davies_sym.network.matrices import ActionVariable
from davies_sym.topology.model import Train


def action_nullity_problems(
    train: Train, free: Sequence[int], index: int, columns: Sequence[ActionVariable]
) -> list[Problem]:
    """What is wrong with the free actions ``free`` (indices into ``columns``; ``index``
    is the input torque's), empty when nothing is: the first problem found only."""
    if index not in free:
        return [
            Problem(
                "ports.input",
                f"the input torque on {train.ports.input!r} is determined by the other actions: the input does no work",
            )
        ]
    others = [columns[j].name for j in free if j != index]
    if others:
        first = next(columns[j].coupling for j in free if j != index)
        return [
            Problem(
                f"couplings.{first}",
                f"the actions are not determined by the input: {', '.join(others)} stay free "
                "(the network is overconstrained in this screw system, or a port is missing)",
            )
        ]
    return []
