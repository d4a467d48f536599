"""The friction laws of Laus Table 2 as types: each writes its own constitutive row of the
augmented action matrix D_A (eqs. (21)-(22), (40)) or its source term (eqs. (50)-(53)).

- `CoulombLaw`: ``T = -zeta |U| sign(t)``, loaded by a transmitted action ``U`` (the
  tooth force of a mesh, the reaction of a bearing); its sign is decided per design.
- `LinearLaw`: ``T = zeta U`` as written (the signed form of a mesh law).
- `ViscousLaw`: ``T = -b t``, a dependent source.
- `DragLaw`: ``T = -D sign(t)``, a constant torque opposing the motion, a source too.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from enum import Enum
from typing import ClassVar

import sympy


@dataclass(frozen=True)
class FrictionLaw:
    """One friction element: its torque variable, law and coefficient.

    ``transmitted`` is the action whose magnitude loads a load-dependent law (the tooth
    force of a mesh, the reaction of a bearing); ``motion`` the relative motion the
    friction opposes.
    """

    coupling: str
    variable: str
    coefficient: sympy.Expr
    motion: str
    transmitted: str | None

    #: The law's name as the topology file writes it (``friction: {coulomb: ...}``).
    name: ClassVar[str] = ""
    #: The unit of its coefficient.
    unit: ClassVar[str] = ""
    #: The role of its action variable in the network.
    role: ClassVar[str] = "friction"
    #: Loaded by a transmitted action (Coulomb, linear): a row of D_A in two unknowns.
    load_dependent: ClassVar[bool] = False
    #: A dependent source (viscous, drag): its torque follows from the motion (eq. (51)).
    source: ClassVar[bool] = False

    def row(self, sign: sympy.Expr) -> dict[str, sympy.Expr]:
        """The constitutive row of D_A by action name; ``sign`` is the Coulomb law's
        sign(U) sign(t) (unused by the other laws)."""
        return {self.variable: sympy.Integer(1)}

    def source_term(self, speed: Callable[[], sympy.Expr], direction: Callable[[], int]) -> sympy.Expr:
        """The right-hand side of a source row (``nu``, eq. (53)): each law asks for what it
        needs, the relative ``speed`` or the ``direction`` it turns in (deciding one may
        fail: a drag whose sense the geometry leaves open); 0 for a law that is no source."""
        return sympy.Integer(0)


@dataclass(frozen=True)
class CoulombLaw(FrictionLaw):
    name: ClassVar[str] = "coulomb"
    unit: ClassVar[str] = "length"
    load_dependent: ClassVar[bool] = True

    def row(self, sign: sympy.Expr) -> dict[str, sympy.Expr]:
        """``T + sign zeta U = 0`` (eq. (21) with the signs multiplied out)."""
        assert self.transmitted is not None
        return {self.variable: sympy.Integer(1), self.transmitted: sign * self.coefficient}


@dataclass(frozen=True)
class LinearLaw(FrictionLaw):
    name: ClassVar[str] = "linear"
    unit: ClassVar[str] = "length"
    load_dependent: ClassVar[bool] = True

    def row(self, sign: sympy.Expr) -> dict[str, sympy.Expr]:
        """``T - zeta U = 0``."""
        assert self.transmitted is not None
        return {self.variable: sympy.Integer(1), self.transmitted: -self.coefficient}


@dataclass(frozen=True)
class ViscousLaw(FrictionLaw):
    name: ClassVar[str] = "viscous"
    unit: ClassVar[str] = "torque / angular speed"
    role: ClassVar[str] = "viscous"
    source: ClassVar[bool] = True

    def source_term(self, speed: Callable[[], sympy.Expr], direction: Callable[[], int]) -> sympy.Expr:
        """``T = -b t`` (eqs. (50)-(51))."""
        return -self.coefficient * speed()


@dataclass(frozen=True)
class DragLaw(FrictionLaw):
    name: ClassVar[str] = "drag"
    unit: ClassVar[str] = "torque"
    role: ClassVar[str] = "drag"
    source: ClassVar[bool] = True

    def source_term(self, speed: Callable[[], sympy.Expr], direction: Callable[[], int]) -> sympy.Expr:
        """``T = -D sign(t)``: a constant torque against the motion."""
        return -self.coefficient * direction()


#: Roles of the action variables a lossless network leaves out.
LOSS_ROLES = tuple(dict.fromkeys(law.role for law in (CoulombLaw, ViscousLaw, DragLaw)))


class CoulombSigns(Enum):
    """How `Analysis` treats the sign of each Coulomb law (see `davies_sym.network.analysis.Analysis`)."""

    RESOLVE = "resolve"
    SYMBOLIC = "symbolic"
    MESH_LINEAR = "mesh-linear"


def coulomb_mode(value: CoulombSigns | str) -> CoulombSigns:
    """``value`` as a `CoulombSigns` (its name as text is accepted, as the API always has)."""
    try:
        return CoulombSigns(value)
    except ValueError:
        raise ValueError("coulomb_signs must be 'resolve', 'symbolic' or 'mesh-linear'") from None
