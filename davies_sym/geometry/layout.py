"""What every layout hands on: `Layout`, the geometric constraints, and the
helpers the line, plane and cone layouts share (constraint bookkeeping, eliminating one
radius per constraint)."""

from __future__ import annotations

from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field

import sympy

from davies_sym.algebra.radicals import Radical
from davies_sym.algebra.screws import Vector, vector
from davies_sym.algebra.signs import SignOracle
from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.errors import Problem

Z_AXIS: Vector = vector((0, 0, 1))
X_AXIS: Vector = vector((1, 0, 0))
Y_AXIS: Vector = vector((0, 1, 0))


@dataclass(frozen=True)
class GeometricConstraint:
    """An equation the radii must satisfy, ``lhs = rhs``, and the mesh that closes it."""

    lhs: sympy.Expr
    rhs: sympy.Expr
    coupling: str

    @property
    def expression(self) -> sympy.Expr:
        """``lhs - rhs``, which must vanish."""
        return sympy.expand(self.lhs - self.rhs)

    def __str__(self) -> str:
        return f"{sympy.sstr(self.lhs)} = {sympy.sstr(self.rhs)}"


@dataclass(frozen=True)
class Layout:
    """Positions and directions the coupling kinds need to write their screws."""

    gear_centres: Mapping[str, Vector]
    coupling_points: Mapping[str, Vector]
    mesh_tangents: Mapping[str, Vector]
    mesh_normals: Mapping[str, Vector]
    constraints: tuple[GeometricConstraint, ...]
    #: Expressions known to be positive, e.g. R - r of every internal mesh.
    positive_facts: tuple[sympy.Expr, ...] = ()
    #: Each side of every triangle a 2-D drawing closes shorter than the other two: implied
    #: by the triangle's radicand among ``positive_facts``, written out so that formulas
    #: in fewer symbols can check it where a side's radius cancels (r2 + 2 r6 - r1 > 0).
    side_facts: tuple[sympy.Expr, ...] = ()
    axis: Vector = Z_AXIS
    #: Axis direction of each gear and of each coupling's rotation, where it is not ``axis``
    #: (intersecting-axis trains).
    gear_axes: Mapping[str, Vector] = field(default_factory=dict)
    coupling_axes: Mapping[str, Vector] = field(default_factory=dict)
    #: Square roots the positions use, as symbols with their radicands (tilted axes).
    radicals: tuple[Radical, ...] = ()
    #: The axes are not all parallel and do not meet at one point (a skew mesh): every
    #: screw of space counts, so a spur mesh is a point contact with five freedoms.
    spatial: bool = False
    #: Some mesh is helical: the gears carry axial thrust, so every mesh may slide along
    #: and tilt about its tangent where the screw system holds those motions.
    thrust: bool = False
    #: The unit direction (x, y) the planets of a 2-D drawing are placed along (the
    #: file's `placement`): the drawing is the upright one (planets along +y) turned to
    #: it, and the network solves its equations turned back (`davies_sym.network.null_space`).
    frame: tuple[sympy.Expr, sympy.Expr] = (sympy.Integer(0), sympy.Integer(1))
    #: The meshes whose second gear turns on a planet axis (`.axes`): a constraint they
    #: close is solved for the planet's radius first (`davies_sym.geometry.dependent`).
    planet_second: frozenset[str] = frozenset()


def line_point(y: sympy.Expr) -> Vector:
    """The point at ``y`` on the layout line (x = z = 0)."""
    return vector((0, y, 0))


def constraint_substitutions(constraints: tuple[GeometricConstraint, ...]) -> list[dict[sympy.Symbol, sympy.Expr]]:
    """Every way to eliminate one symbol with one linear constraint: r1 - r3 = r2 - r4
    gives r4 -> r2 + r3 - r1, r1 -> r2 + r3 - r4, ..."""
    out = []
    for c in constraints:
        out += [{s: root} for s, root in linear_roots(polynomial_part(c.expression)).items()]
    return out


def linear_roots(expr: sympy.Expr, kept: Collection[str] = ()) -> dict[sympy.Symbol, sympy.Expr]:
    """Each symbol in which ``expr = 0`` is linear (by name, none of ``kept``) -> its root
    (`solve_linear`), in the order of the symbols."""
    return {
        s: solve_linear(expr, s)
        for s in sorted_symbols(expr.free_symbols)
        if sympy.degree(expr, s) == 1 and str(s) not in kept
    }


def polynomial_part(expr: sympy.Expr) -> sympy.Expr:
    """The numerator of ``expr`` over one denominator, expanded: the same equation ``= 0``
    where the denominator is non-zero.  A dependent module makes radii quotients
    (m2 -> m1 (z1 + z2) / (z4 - z3)), and a polynomial is what degree and solving need."""
    if all(not (p.is_Pow and p.exp.is_negative) for p in sympy.preorder_traversal(expr)):
        return expr
    return sympy.expand(sympy.numer(sympy.together(expr)))


def solve_linear(expr: sympy.Expr, symbol: sympy.Symbol) -> sympy.Expr:
    """The root of ``expr = 0``, linear in ``symbol`` (a coefficient free of it, non-zero
    where the radii are positive): -b / a of a symbol + b, expanded, without sympy's
    general ``solve``."""
    expr = sympy.expand(expr)
    return sympy.expand(-expr.subs(symbol, 0) / expr.coeff(symbol, 1))


def tidy_quotient(expr: sympy.Expr) -> sympy.Expr:
    """``expr`` expanded; a quotient (a module solved before it) over one denominator first,
    so that a relation holds no quotient of quotients."""
    if polynomial_part(expr) is expr:
        return sympy.expand(expr)
    return sympy.expand(sympy.cancel(expr))


def joint_substitution(constraints: tuple[GeometricConstraint, ...]) -> dict[sympy.Symbol, sympy.Expr]:
    """One symbol eliminated per constraint, all at once (r4 -> r2 + r3 - r1, rb -> ...),
    so that a sign needing several constraints together can be decided."""
    eliminated: dict[sympy.Symbol, sympy.Expr] = {}
    for constraint in constraints:
        # Prefer eliminating a symbol that is a positive combination of the others
        # (the annulus: ra -> sa + 2 pa), so that positivity arguments still apply.
        options = sorted(
            constraint_substitutions((constraint,)),
            key=lambda sub: not all(c > 0 for c in sympy.Poly(*sub.values()).coeffs()),
        )
        for substitution in options:
            ((symbol, expr),) = substitution.items()
            expr = sympy.expand(expr.subs(eliminated))
            if symbol not in eliminated and symbol not in expr.free_symbols:
                eliminated = {k: sympy.expand(v.subs(symbol, expr)) for k, v in eliminated.items()}
                eliminated[symbol] = expr
                break
    return eliminated


@dataclass(frozen=True)
class Closures:
    """The geometric constraints a layout collects as its meshes and bearings close loops
    (Laus section 3.4.1.6), and in ``problems`` the loops that cannot close; ``oracle``
    decides the sign of a difference of lengths."""

    oracle: SignOracle
    problems: list[Problem]
    constraints: list[GeometricConstraint] = field(default_factory=list)

    def close(
        self,
        offset: sympy.Expr,
        distance: sympy.Expr,
        coupling: str,
        entry: str | None = None,
        message: str | None = None,
        loop: Sequence[str] = (),
    ) -> None:
        """``offset = distance`` holds, is impossible (a problem naming the ``loop`` of
        couplings that closes here), or is a constraint on the radii."""
        difference = sympy.expand(offset - distance)
        if polynomial_part(difference) == 0:
            return
        if difference.is_number or self.oracle.sign(difference) in (1, -1):
            through = f"the loop of couplings {', '.join(loop)} cannot close: " if len(loop) > 1 else ""
            self.problems.append(
                Problem(
                    entry or f"couplings.{coupling}",
                    message
                    or f"inconsistent geometry: {through}coupling {coupling} needs a centre distance of "
                    f"{distance} where the other couplings give {offset} (difference {difference}); change the sizes "
                    "so that they agree, or write one radius as a symbol and let the constraint give it",
                )
            )
            return
        self.constraints.append(GeometricConstraint(offset, sympy.expand(distance), coupling))


def loop_through(via: Mapping[str, tuple[str, str]], a: str, b: str, closing: str) -> list[str]:
    """The couplings of the loop a mesh ``closing`` between axis classes ``a`` and ``b``
    closes: the placing meshes (``via``: class -> (mesh, class it was placed from)) from
    each end back to their common class, and the closing one."""

    def chain(cls: str) -> tuple[list[str], list[str]]:
        classes, meshes = [cls], []
        while cls in via:
            mesh, cls = via[cls]
            meshes.append(mesh)
            classes.append(cls)
        return classes, meshes

    (classes_a, meshes_a), (classes_b, meshes_b) = chain(a), chain(b)
    common = next((cls for cls in classes_b if cls in classes_a), None)
    if common is None:
        return [closing]
    return sorted({*meshes_a[: classes_a.index(common)], *meshes_b[: classes_b.index(common)], closing})
