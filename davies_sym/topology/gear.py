"""A gear of a train: which link carries it and its pitch circle (read by the couplings
and held by the model)."""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy


@dataclass(frozen=True)
class Gear:
    """A gear fixed to a link, with its pitch radius (number or expression)."""

    name: str
    link: str
    radius: sympy.Expr
    internal: bool = False
    teeth: int | sympy.Expr | None = None
    module: sympy.Expr | None = None
    #: Direction of the gear axis through the common apex (intersecting-axis trains);
    #: None for parallel-axis trains (axes along z).
    axis: tuple[sympy.Expr, sympy.Expr, sympy.Expr] | None = None
    #: The axis is tilted by the cone geometry: derived from the two coaxial gears this
    #: gear meshes (the Humpage planet, Laus eq. (80)).
    tilted: bool = False
    #: The link whose axis the gear is centred on when it is not ``link``'s own (a gear
    #: fixed to a carrier about a pin it holds); None: the axis of ``link``.
    about: str | None = None
    #: The pitch radius as the file writes it where the geometric constraints have put the
    #: independent parameters in ``radius`` in place of a dependent one
    #: (`davies_sym.geometry.dependent`); None: ``radius`` is as written.
    written: sympy.Expr | None = field(default=None, compare=False)

    @property
    def written_radius(self) -> sympy.Expr:
        """The pitch radius in the file's own symbols (``rp1``, not ``rr1/2 - rs/2``)."""
        return self.radius if self.written is None else self.written

    @property
    def axis_link(self) -> str:
        """The link whose axis the gear turns about (for the layout)."""
        return self.about or self.link
