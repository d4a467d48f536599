"""Turning conditions: which gear drives in every mesh (Laus Tables 5 and 6).

The sign of a mesh's lossless virtual power (per unit input power) is factored; the
factors that are provably positive under the symbols' assumptions and the train's
geometric facts are removed, and what remains is the mesh's turning condition
(eq. (86): "the expression ... might be used in place of the fraction").  Meshes whose
conditions agree up to sign share one condition: Tuplin's two meshes both turn with
r1 r4 - r2 r3 (r1 < r2 on the constraint r1 - r3 = r2 - r4).
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import sympy

from davies_sym.efficiency.virtual_power import MeshPowerFlow, mesh_power_flow
from davies_sym.topology.coupling_kinds import toothed_meshes
from davies_sym.topology.symbol_display import latex

if TYPE_CHECKING:
    from davies_sym.network.analysis import Analysis
    from davies_sym.topology.toothed_mesh import ToothedMesh


@dataclass(frozen=True)
class TurningCondition:
    """A sign that the geometry decides: ``expression`` is the factor product as
    derived, ``simplified`` the same sign on the geometric constraints."""

    name: str
    expression: sympy.Expr
    simplified: sympy.Expr

    def _repr_latex_(self) -> str:
        """``$$c_{1} = r_{2} - r_{1}$$``: its name and the expression whose sign it is."""
        return rf"$${latex(sympy.Symbol(self.name))} = {latex(self.simplified)}$$"

    def _repr_html_(self) -> str:
        expression = html.escape(latex(self.simplified))
        return (
            f"<p>turning condition <b>{html.escape(self.name)}</b>: the sign of \\({expression}\\) "
            "decides which gear drives</p>"
        )


@dataclass(frozen=True, eq=False)
class MeshRole:
    """One mesh: its carrier, its flow and what decides its direction.

    With the declared input, the first gear drives when ``fixed`` is +1, or when
    ``orientation * sign(condition) > 0``; swapping input and output reverses it.
    """

    coupling: str
    flow: MeshPowerFlow
    fixed: int | None
    condition: str | None
    orientation: int
    efficiencies: tuple[sympy.Expr, sympy.Expr]
    #: No virtual power crosses the mesh in this train or state (its set is locked by a
    #: clutch or unloaded): no gear drives and the mesh loses nothing.
    idle: bool = False

    def first_drives(self, signs: dict[str, int], declared_input: bool) -> bool:
        """Whether the first gear drives for the given condition signs and input side."""
        base = self.fixed if self.condition is None else self.orientation * signs[self.condition]
        assert base is not None
        return (base > 0) == declared_input


def _shorter(analysis: Analysis, expr: sympy.Expr) -> sympy.Expr:
    """The condition on each geometric constraint, if it is simpler there."""
    best = expr
    for substitution in analysis.oracle.substitutions:
        replaced = sympy.expand(expr.subs(substitution))
        if replaced == 0:
            continue
        sign, factors = sympy.factor_list(replaced)
        s, undecided = analysis.oracle.classify(1 if sign > 0 else -1, factors)
        candidate = undecided if s is None else sympy.Integer(s)
        if sympy.count_ops(candidate) < sympy.count_ops(best):
            best = candidate
    return best


def _normalised(expr: sympy.Expr) -> tuple[int, sympy.Expr]:
    """(sign, expr') with expr = sign * expr' and expr' free of a leading minus."""
    sign, rest = sympy.Integer(1), expr
    coeff, body = expr.as_coeff_Mul()
    if coeff < 0:
        sign, rest = sympy.Integer(-1), -coeff * body if coeff != -1 else body
    return int(sign), rest


def mesh_roles(analysis: Analysis) -> tuple[list[MeshRole], list[TurningCondition]]:
    """Roles of every mesh with a load-dependent friction law, and the distinct
    turning conditions (named c1, c2, ... in mesh order)."""
    roles: list[MeshRole] = []
    conditions: list[TurningCondition] = []
    for c in toothed_meshes(analysis.train.couplings):
        if c.efficiencies is None:
            continue
        if c.friction.coulomb is None and c.friction.linear is None:
            continue
        roles.append(_mesh_role(analysis, c, c.efficiencies, conditions))
    return roles, conditions


def _mesh_role(
    analysis: Analysis,
    c: ToothedMesh,
    efficiencies: tuple[sympy.Expr, sympy.Expr],
    conditions: list[TurningCondition],
) -> MeshRole:
    """The role of mesh ``c`` (with its ordinary ``efficiencies``): idle, decided by the
    geometry, or decided by a turning condition, which is added to ``conditions`` unless
    one there agrees with it up to sign."""
    flow = mesh_power_flow(analysis, c)
    if flow.flow_ratio.is_zero():
        # No virtual power crosses the mesh (unloaded or locked set): no loss either way.
        return MeshRole(c.name, flow, fixed=1, condition=None, orientation=1, efficiencies=efficiencies, idle=True)
    content, factors = flow.flow_ratio.factor_list()
    sign, undecided = analysis.oracle.classify(content, factors)
    if sign in (1, -1):
        return MeshRole(c.name, flow, fixed=sign, condition=None, orientation=1, efficiencies=efficiencies)
    orientation, general = _normalised(sympy.expand(undecided))
    shorter = _shorter(analysis, general)
    if shorter.is_number:
        # Decided on the geometric constraints only.
        fixed = orientation * (1 if shorter > 0 else -1)
        return MeshRole(c.name, flow, fixed=fixed, condition=None, orientation=1, efficiencies=efficiencies)
    simple_sign, simplified = _normalised(shorter)
    orientation *= simple_sign
    for existing in conditions:
        same = sympy.expand(existing.simplified - simplified) == 0
        opposite = sympy.expand(existing.simplified + simplified) == 0
        if same or opposite:
            oriented = orientation * (1 if same else -1)
            return MeshRole(
                c.name, flow, fixed=None, condition=existing.name, orientation=oriented, efficiencies=efficiencies
            )
    name = f"c{len(conditions) + 1}"
    conditions.append(TurningCondition(name, simple_sign * general, simplified))
    return MeshRole(c.name, flow, fixed=None, condition=name, orientation=orientation, efficiencies=efficiencies)


def condition_signs(conditions: Sequence[TurningCondition]) -> list[dict[str, int]]:
    """Every combination of condition signs, + before -, in condition order."""
    combos: list[dict[str, int]] = [{}]
    for cond in conditions:
        combos = [{**combo, cond.name: s} for combo in combos for s in (1, -1)]
    return combos
