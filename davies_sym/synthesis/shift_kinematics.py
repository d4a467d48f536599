"""The speeds of the members of a transmission about its main axis, before any shift
element is engaged: every member that runs in a bearing of the reference, as an exact
linear form in the train's free shaft speeds (Laus eq. (1) for a train of several
degrees of freedom: the motions are the null space of M_N, with the bearings' speeds
chosen as its free variables).

Engaging a brake or a clutch adds one linear equation; a gear is a set of engaged
elements that leaves exactly one degree of freedom, and its speed ratio is the input
member's speed over the output member's in that one motion.  Everything is exact
(rationals): the tooth numbers are numbers here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

import flint
import sympy

from davies_sym.caches import IdentityCache
from davies_sym.errors import InputError
from davies_sym.network.analysis import Analysis
from davies_sym.topology.coupling_kinds import bearings
from davies_sym.topology.model import Train

#: A linear form in the free speeds: one coefficient per free speed.
Form = tuple[Fraction, ...]


@dataclass(frozen=True)
class MemberSpeeds:
    """The speed of every main-axis member (by link name, in the order of the links) as
    a linear form in the free speeds; ``shaft`` names the bearing each member runs in."""

    free: tuple[str, ...]
    forms: Mapping[str, Form]
    shaft: Mapping[str, str]

    @property
    def degrees_of_freedom(self) -> int:
        return len(self.free)

    def members(self) -> tuple[str, ...]:
        return tuple(self.forms)


#: The member speeds of each train asked (the command checks them, the search uses them).
_SPEEDS: IdentityCache[Train, MemberSpeeds] = IdentityCache()


def member_speeds(train: Train) -> MemberSpeeds:
    """The speeds of the members that run in a bearing of ``train``'s reference (its
    main-axis members), from the null space of M_N; a train of one degree of freedom
    (nothing to shift) and a member whose speed is not a number multiple of the free
    speeds (a symbolic tooth number) are refused."""
    return _SPEEDS.get(train, lambda: _member_speeds(train))


@dataclass(frozen=True)
class MemberForms:
    """The main-axis members' speeds as written by the analysis: per member one
    coefficient (a sympy expression, in the tooth numbers where they are symbols) per
    free speed, and the bearing each member runs in."""

    free: tuple[str, ...]
    forms: Mapping[str, tuple[sympy.Expr, ...]]
    shaft: Mapping[str, str]


def member_forms(train: Train) -> MemberForms:
    """The speeds of the members in a bearing of the reference from the null space of
    M_N, the bearings' speeds as its free variables; a train of one degree of freedom
    (nothing to shift) is refused."""
    analysis = Analysis(train)
    net = analysis.network
    on_reference = [c for c in bearings(train.couplings) if train.reference in c.links]
    motions = {c.name: net.coupling_motions(c.name)[0].name for c in on_reference}
    solution = analysis.motions_in(list(motions.values()))
    free = tuple(dict.fromkeys(name for c in on_reference for name in solution[motions[c.name]]))
    if len(free) < 2:
        why = (
            f"the train has {len(free)} degree of freedom: nothing to shift (give the gearsets and their "
            "permanent connections, every main-axis member in a bearing of the reference)"
        )
        raise InputError([train.problem("", why)], train.path)
    forms: dict[str, tuple[sympy.Expr, ...]] = {}
    shaft: dict[str, str] = {}
    for c in on_reference:
        member = c.links[1] if c.links[0] == train.reference else c.links[0]
        # The bearing's motion is its second link's relative to its first.
        sign = 1 if c.links[0] == train.reference else -1
        combination = solution[motions[c.name]]
        zero = sympy.Integer(0)
        forms[member] = tuple(sign * (combination[f].to_expr() if f in combination else zero) for f in free)
        shaft[member] = c.name
    order = {name: k for k, name in enumerate(train.link_names)}
    ordered = sorted(forms, key=order.__getitem__)
    return MemberForms(free, {m: forms[m] for m in ordered}, {m: shaft[m] for m in ordered})


def _member_speeds(train: Train) -> MemberSpeeds:
    written = member_forms(train)
    forms = {m: tuple(_number(train, written.shaft[m], x) for x in form) for m, form in written.forms.items()}
    return MemberSpeeds(written.free, forms, dict(written.shaft))


def _number(train: Train, coupling: str, value: sympy.Expr) -> Fraction:
    if not value.is_Rational:
        why = (
            f"the speed of this bearing's member is {value} times a free speed: write the tooth numbers as "
            "numbers, or search them with --teeth (the shift search needs exact speed ratios)"
        )
        raise InputError([train.problem(f"couplings.{coupling}", why)], train.path)
    return Fraction(int(value.p), int(value.q))


def null_basis(rows: Sequence[Form], columns: int) -> list[Form]:
    """A basis of the vectors every row annihilates (exact, from the reduced row echelon
    form): one vector per column without a pivot."""
    if not rows:
        return [tuple(Fraction(int(i == j)) for i in range(columns)) for j in range(columns)]
    matrix = flint.fmpq_mat(len(rows), columns, [flint.fmpq(x.numerator, x.denominator) for r in rows for x in r])
    reduced, rank = matrix.rref()
    pivots = [next(j for j in range(columns) if reduced[i, j] != 0) for i in range(rank)]
    basis = []
    for loose in (j for j in range(columns) if j not in pivots):
        vector = [Fraction(0)] * columns
        vector[loose] = Fraction(1)
        for i, j in enumerate(pivots):
            entry = reduced[i, loose]
            vector[j] = -Fraction(int(entry.p), int(entry.q))
        basis.append(tuple(vector))
    return basis


def one_motion(rows: Sequence[Form], free: int) -> Form | None:
    """The motion left by the engaged elements' equations ``rows`` (each a form that
    must vanish): a basis vector of their null space when ``rows`` are independent and
    leave exactly one degree of freedom, else None (a redundant element, or too few)."""
    if len(rows) != free - 1:
        return None
    basis = null_basis(rows, free)
    return basis[0] if len(basis) == 1 else None


def speed(form: Form, motion: Form) -> Fraction:
    """A member's speed in ``motion``."""
    return sum((a * b for a, b in zip(form, motion, strict=True)), Fraction(0))
