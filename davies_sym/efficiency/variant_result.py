"""One formula of a train's overall efficiency and where it holds: the input port, the
sign of every turning condition (Laus Tables 5 and 6), each mesh's driving gear, and the
loaded forces the losses reverse."""

from __future__ import annotations

import html
from collections.abc import Mapping
from dataclasses import dataclass, field

import sympy

from davies_sym.algebra.linear_regions import Requirement
from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.light_load import LoadedForces
from davies_sym.efficiency.parameter_domain import Point
from davies_sym.topology.symbol_display import latex


@dataclass(frozen=True, eq=False)
class Variant:
    """One formula of the overall efficiency and where it holds."""

    number: int
    input: str
    output: str
    #: Required sign of each turning condition (condition name -> +1 or -1).
    signs: Mapping[str, int]
    #: Mesh -> True when its first gear drives.
    first_drives: Mapping[str, bool]
    efficiency_rf: RationalFunction = field(repr=False)
    #: Whether a sampled admissible geometry lies in the region.
    feasible: bool = True
    #: "positive", "failed: <symbols>" or "not checked" (no sample in the region).
    derivative_check: str = "not checked"
    #: A sampled point of the region where the efficiency is outside (0, 1] (the train
    #: self-locks there), if any was found.
    self_locking_point: Point | None = None
    #: Product whose sign is that of the efficiency (positive factors removed); the
    #: variant self-locks where it is <= 0.  None when provably positive.
    locking_expression: sympy.Expr | None = None
    #: Couplings whose loaded force (mesh power, bearing reaction) the losses reverse in this
    #: variant: empty for the lossless directions.
    reversed_forces: frozenset[str] = frozenset()
    #: Each loaded force at the operating point with the sign it needs where the variant
    #: holds: the power through each mesh whose direction the losses can turn, each
    #: bearing's reaction.
    loaded_forces: LoadedForces = field(default_factory=dict, repr=False)

    @property
    def efficiency(self) -> sympy.Expr:
        """The formula, numerator and denominator factored."""
        return self.efficiency_rf.to_expr()

    def where_latex(self, expressions: Mapping[str, str] | None = None) -> list[str]:
        """Where the variant holds, as LaTeX: each turning condition's sign (``c_{1} > 0``,
        or the condition's expression given in ``expressions`` by name) and the loaded
        forces the losses reverse."""
        shown = expressions or {}
        out = [f"{shown.get(c) or latex(sympy.Symbol(c))} {'>' if s > 0 else '<'} 0" for c, s in self.signs.items()]
        if self.reversed_forces:
            out.append(r"\text{the losses reverse " + ", ".join(sorted(self.reversed_forces)) + "}")
        return out

    def equation_latex(self, expressions: Mapping[str, str] | None = None) -> str:
        """``$$\\eta_{(n)} = ... \\qquad (A \\to B,\\ c_1 > 0)$$``: the formula, its ports
        and `where_latex`."""
        escaped = [p.replace("_", r"\_") for p in (self.input, self.output)]  # port names are identifiers
        where = [rf"\text{{{escaped[0]}}} \to \text{{{escaped[1]}}}", *self.where_latex(expressions)]
        joined = r",\ ".join(where)
        return rf"$$\eta_{{({self.number})}} = {latex(self.efficiency)} \qquad ({joined})$$"

    def __repr__(self) -> str:
        where = ", ".join(f"{c} {'>' if s > 0 else '<'} 0" for c, s in self.signs.items()) or "always"
        if self.reversed_forces:
            where += f" (the losses reverse {', '.join(sorted(self.reversed_forces))})"
        ports = f"input {self.input}, output {self.output}"
        return f"<Variant ({self.number}): {ports}, where {where}: eta = {self.efficiency}>"

    def _repr_latex_(self) -> str:
        """The equation for a notebook, conditions by name (the variant set shows their
        expressions)."""
        return self.equation_latex()

    def _repr_html_(self) -> str:
        where = html.escape(r",\ ".join(self.where_latex()) or r"\text{always}")
        ports = f"{html.escape(self.input)} &rarr; {html.escape(self.output)}"
        formula = html.escape(latex(self.efficiency))
        return f"<p>variant ({self.number}), {ports}, where \\({where}\\): \\(\\eta = {formula}\\)</p>"

    @property
    def name(self) -> str:
        """An identifier naming the ports and the condition signs, e.g. ``A_to_B_c1_pos``."""
        return variant_name(self.input, self.output, self.signs, self.reversed_forces)


def variant_name(input: str, output: str, signs: Mapping[str, int], reversed_forces: frozenset[str]) -> str:
    """An identifier naming the ports, the condition signs and the reversed forces."""
    parts = [f"{input}_to_{output}"]
    parts += [f"{c}_{'pos' if s > 0 else 'neg'}" for c, s in signs.items()]
    if reversed_forces:
        parts += ["reversed", *sorted(reversed_forces)]
    name = "_".join(_identifier(p) for p in parts)
    # A port named by a number would start the function name with a digit.
    return name if name[0].isalpha() else f"from_{name}"


@dataclass(frozen=True, eq=False)
class ExcludedVariant:
    """A combination of input port and turning-condition signs that no admissible
    geometry reaches, proved so before its formula is built (`davies_sym.algebra.linear_regions`):
    it keeps its number in the table (Laus Tables 5 and 6 list every combination) and has
    no formula."""

    number: int
    input: str
    output: str
    signs: Mapping[str, int]
    first_drives: Mapping[str, bool]
    #: The requirements the proof needs: the variant's conditions and the facts of the
    #: admissible geometry they contradict (``rr - rs1 > 0``).
    conditions: tuple[Requirement, ...]
    facts: tuple[Requirement, ...]

    @property
    def name(self) -> str:
        return variant_name(self.input, self.output, self.signs, frozenset())

    @property
    def reason(self) -> str:
        """Why the variant never holds, in one sentence."""
        against = f"with {_listed(self.facts)} (admissible geometry)" if self.facts else "for any values"
        return f"{_listed(self.conditions)} cannot hold {against}, so no design reaches it; not derived"


def _listed(requirements: tuple[Requirement, ...]) -> str:
    items = [str(r) for r in requirements]
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _identifier(text: str) -> str:
    return "".join(ch if ch.isalnum() or ch == "_" else "_" for ch in text)
