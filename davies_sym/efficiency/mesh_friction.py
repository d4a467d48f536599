"""What the variants need of each mesh's friction, checked before they are derived.

The variants replace each mesh's friction coefficient by the solution of its
ordinary-efficiency equation (Laus eqs. (74)-(75)).  So each mesh needs a
load-dependent law (Coulomb or signed linear) whose coefficient is a symbol used
nowhere else: a number cannot be solved for, and a symbol shared with a radius, an
efficiency or another mesh would be replaced in the wrong places.  The friction form of
`davies_sym.analyse` has no such need and keeps accepting these trains.
"""

from __future__ import annotations

from collections.abc import Collection, Iterator

import sympy

from davies_sym.errors import Problem, TopologyError
from davies_sym.network.friction_laws import FrictionLaw
from davies_sym.topology.coupling_kinds import toothed_meshes
from davies_sym.topology.couplings import Coupling
from davies_sym.topology.model import Train
from davies_sym.topology.toothed_mesh import ToothedMesh


def is_mesh_law(law: FrictionLaw, meshes: Collection[str]) -> bool:
    """Whether ``law`` is the own friction law of one of ``meshes`` (the Coulomb or linear
    law its ordinary efficiency replaces); a viscous law or drag on a mesh is not."""
    return law.coupling in meshes and law.load_dependent


def only_mesh_laws(laws: Collection[FrictionLaw], meshes: Collection[str]) -> bool:
    """Whether every loss is a mesh's own law, so every force scales with the load and the
    reversed input is the declared one inverted."""
    return all(is_mesh_law(law, meshes) for law in laws)


def check_mesh_friction(train: Train) -> None:
    """Raise `TopologyError` (every problem, located) unless each mesh of ``train``
    has a load-dependent friction law with a symbol of its own."""
    problems = [p for c in toothed_meshes(train.couplings) for p in _problems(train, c)]
    if problems:
        raise TopologyError(problems, train.file_lines)


def _problems(train: Train, mesh: ToothedMesh) -> list[Problem]:
    entry = f"couplings.{mesh.name}.friction"
    if mesh.friction.loaded is None:
        return [
            Problem(
                entry,
                f"a mesh needs a coulomb or linear friction law, from which its ordinary "
                f"efficiency is derived; remove `friction:` (the default is coulomb: zeta_{mesh.name})",
            )
        ]
    law, coefficient = mesh.friction.loaded
    if not isinstance(coefficient, sympy.Symbol):
        return [
            Problem(
                f"{entry}.{law}",
                f"the coefficient is solved from the mesh's ordinary efficiency, so "
                f"it must be a symbol, not {sympy.sstr(coefficient)[:40]}; write {law}: "
                f"zeta_{mesh.name} and give the efficiency (`efficiency:`) instead",
            )
        ]
    if any(coefficient in q.free_symbols for q in _other_quantities(train, mesh)):
        return [
            Problem(
                f"{entry}.{law}",
                f"{coefficient} is also used elsewhere in the train; give each mesh "
                f"a friction symbol of its own, e.g. zeta_{mesh.name}",
            )
        ]
    return []


def _other_quantities(train: Train, mesh: ToothedMesh) -> Iterator[sympy.Expr]:
    """Every quantity of ``train`` but the load-dependent friction coefficient of ``mesh``."""
    for g in train.gears:
        yield g.radius
    for c in train.couplings:
        yield from _coupling_quantities(c, own=c.name == mesh.name)


def _coupling_quantities(c: Coupling, own: bool) -> Iterator[sympy.Expr]:
    laws = (c.friction.viscous,) if own else (c.friction.coulomb, c.friction.linear, c.friction.viscous)
    yield from (x for x in laws if x is not None)
    yield from c.written_quantities
