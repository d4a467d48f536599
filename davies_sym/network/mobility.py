"""The mobility check of a train: its net degree of freedom F_N (the nullity of M_N,
Laus eq. (1)) against the input ports and the file's ``degrees_of_freedom``."""

from __future__ import annotations

from collections.abc import Sequence

from davies_sym.errors import Problem
from davies_sym.network.matrices import Network
from davies_sym.topology.model import Train


def mobility_problems(train: Train, network: Network, free: Sequence[int], input_index: int) -> list[Problem]:
    """What is wrong with the free motions ``free`` of Null(M_N) (indices into the
    network's motions; ``input_index`` is the input speed's), empty when nothing is."""
    dof = len(free)
    problems = []
    if dof == 0 and train.degrees_of_freedom is None:
        # One cause, one problem: the input cannot move because nothing can.
        port = train.ports.input
        return [
            Problem(
                "ports", f"the train has no degree of freedom (it is locked): the input coupling {port!r} cannot move"
            )
        ]
    if input_index not in free:
        problems.append(
            Problem("ports.input", f"the input coupling {train.ports.input!r} cannot move: the train is locked")
        )
    if train.degrees_of_freedom is not None and dof != train.degrees_of_freedom:
        problems.append(
            Problem(
                "degrees_of_freedom",
                f"the train has {dof} degree(s) of freedom, the file says {train.degrees_of_freedom}",
            )
        )
    elif train.degrees_of_freedom is None and dof != len(train.ports.inputs):
        # Without a stated mobility, one degree of freedom per input port is expected.
        driven = {m.name for p in train.ports.inputs for m in network.coupling_motions(p)[:1]}
        extra = [network.motions[j].name for j in free if network.motions[j].name not in driven]
        inputs = len(train.ports.inputs)
        count = "one input port drives" if inputs == 1 else f"{inputs} input ports drive"
        text = f"the train has {dof} degrees of freedom but {count} it"
        if extra:
            text += f"; also free: {', '.join(extra)}"
        if dof == 0:
            text = "the train has no degree of freedom"
        problems.append(Problem("ports", text))
    return problems
