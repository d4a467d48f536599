"""Efficiency by virtual-power balance (Chen 2006, chapter 4): an independent route.

No screws, no coupling-graph matrices, no friction coefficients: members, angular
speeds and torques about their axes, and Chen's loss formula, evaluated exactly at one
parameter point.  The eight steps of Chen section 4.6:

(i)    kinematics: one Willis equation per mesh, the pitch-point speeds of both gears
       equal when seen from the mesh's carrier, ``(w_p - w_c) a_p = (w_q - w_c) a_q``
       with ``a`` the signed distance from the gear axis to the pitch point;
(ii)   power flow without loss: the torques of the lossless train;
(iii)  virtual-power flow without loss in each carrier frame: the virtual power a
       member delivers to a mesh is ``-M (w - w_c)`` (eq. (4.6): a member's virtual
       power is its torque times its speed relative to the carrier); the side that
       delivers power drives;
(iv-v) losses added: the driven side receives ``eta`` times the virtual power the
       driver delivers, ``L = (1 - eta) P^v`` (eq. (4.4) with lambda = 1 - eta);
(vi)   balances: each member's torques about its axis sum to zero, which is its
       virtual-power balance (4.5) divided by its carrier-frame speed; a carrier
       receives from each planet the moments that the planet's meshes exert on it
       (about the carrier axis: minus the moment on the partner gear, which is coaxial);
(vii)  the linear system is solved for the mesh torques and the output torque;
(viii) ``eta = (P_0 - L) / P_0``, checked against ``-P_out / P_in`` and the power
       balance (4.3b).

Applies to 1-DOF trains with parallel axes drawn on a line (planets on carriers whose
partner gears are coaxial with the carrier), and to bevel and face-gear trains whose
axes meet at one apex; `.balance_frames` gives both geometries one interface,
so the eight steps are written once.  Other trains get a clear error.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.balance_frames import ConicalFrames, Frames, PlanarFrames, Row, Values, exact, is_zero
from davies_sym.efficiency.design_point import check_working, turning_ratio
from davies_sym.efficiency.design_values import design_values
from davies_sym.efficiency.empty_regions import check_facts, geometry_facts
from davies_sym.efficiency.parameter_domain import efficiency_symbols
from davies_sym.errors import DerivationError, InputError, MissingValuesError, Problem, shortened
from davies_sym.geometry import train_layout
from davies_sym.geometry.dependent import resolved_train, with_dependent
from davies_sym.geometry.layout import Layout
from davies_sym.losses.definitions import completed, parameters_of
from davies_sym.topology.gear_mesh import GearMesh
from davies_sym.topology.model import Train

Torques = dict[str, tuple[sympy.Expr, sympy.Expr]]


@dataclass(frozen=True)
class BalanceResult:
    """Outcome of the virtual-power balance at one point."""

    efficiency: sympy.Rational
    input_power: sympy.Rational
    output_power: sympy.Rational
    #: Power lost in each mesh (frame-invariant, eq. (4.4)).
    losses: Mapping[str, sympy.Rational]
    #: Mesh -> True when its first gear drives.
    first_drives: Mapping[str, bool]
    speeds: Mapping[str, sympy.Rational]


def virtual_power_balance(
    train: Train, values: Mapping[sympy.Symbol | str, object], input: str | None = None, layout: Layout | None = None
) -> BalanceResult:
    """Efficiency of ``train`` at ``values`` (keyed by symbol or name, read as every entry
    point reads them: `design_values`) with ``input`` (default: the declared one);
    ``layout`` replaces the derived geometry (to study a published one).  A design where
    the train self-locks is refused as `VariantSet.design_point` refuses it
    (`NotCoveredError`); `balance_at` gives the balance there too."""
    result = balance_at(train, values, input, layout)
    check_working(result.efficiency, input or train.ports.input, "the virtual-power balance")
    return result


def balance_at(
    train: Train, values: Mapping[sympy.Symbol | str, object], input: str | None = None, layout: Layout | None = None
) -> BalanceResult:
    """The balance of `virtual_power_balance` at any design, a self-locking one included
    (its efficiency then is not in (0, 1])."""
    ports = (train.ports.input, train.ports.output)
    if input is not None and input not in ports:  # refused as --input refuses it
        raise InputError(
            [Problem("--input", f"{shortened(input)} is not a port (ports: {', '.join(ports)})")], train.path
        )
    given = design_values(train, values)
    if layout is None:
        train = resolved_train(train)
        given = with_dependent(train, given)
        layout = train_layout(train)
        # The derived geometry admits the designs every entry point admits (a ring larger than its sun).
        check_facts(geometry_facts(train, layout, ()), given, train.path)
    _check_given(train, given)
    values = completed(given, train.definitions)  # a mesh efficiency from its tooth geometry
    port_in = input or train.ports.input
    port_out = train.ports.output if port_in == train.ports.input else train.ports.input
    conical = any(g.axis is not None or g.tilted for g in train.gears)
    # The frames refuse a coupling outside the balance's scope first: that is the reason to give.
    frames: Frames = (ConicalFrames if conical else PlanarFrames)(train, values, layout)
    _check_algebraic(values)
    links = tuple(link for link in train.link_names if link != train.reference)
    w = _kinematics(train, frames, links, port_in)
    out_a, out_b = train.coupling(port_out).links
    out_speed = exact(w[out_b] - w[out_a])
    # A port that does not turn is refused as every entry point refuses it (the input turns at 1).
    turning_ratio(sympy.zoo if is_zero(out_speed) else 1 / out_speed, {}, port_in, port_out, True)
    return _Balance(train, frames, values, links, w, (port_in, port_out)).result()


def _kinematics(train: Train, frames: Frames, links: tuple[str, ...], port_in: str) -> dict[str, sympy.Expr]:
    """(i) kinematics: the speed of every link, from one Willis equation per mesh (and the
    geometry's own rows) and the input speed set to 1."""
    col = {link: i for i, link in enumerate(links)}
    rows = []
    for m in frames.meshes:
        row: Row = [sympy.Integer(0)] * len(links)
        for sign, arm, link in zip((1, -1), frames.arms[m.name], m.links, strict=True):
            frames.speed(row, col, link, frames.carriers[m.name], sign * arm)
        rows.append(row)
    return _speeds(train, port_in, list(links), [*rows, *frames.extra_kinematics(col)])


def _check_given(train: Train, given: Mapping[sympy.Symbol, sympy.Expr]) -> None:
    """Refuse (`MissingValuesError`, as `VariantSet.design_point` words it) a design that
    leaves out a radius or a mesh efficiency (or a parameter of one defined by the teeth)."""
    needed: set[sympy.Basic] = set(efficiency_symbols(train))
    for g in train.gears:
        needed |= g.radius.free_symbols
    missing = [str(s) for s in sorted_symbols(parameters_of(needed, train.definitions)) if s not in given]
    if missing:
        raise MissingValuesError([Problem("values", f"missing values for {', '.join(missing)}")], train.path)


def _check_algebraic(values: Mapping[sympy.Symbol, sympy.Expr]) -> None:
    """The balance works in exact numbers with square roots: a value with a logarithm or
    a trigonometric function of a number (an efficiency from the tooth geometry) is
    outside its scope, said as its other limits are (`DerivationError`)."""
    for symbol, value in values.items():
        functions = sorted({type(f).__name__ for f in sympy.sympify(value).atoms(sympy.Function)})
        if functions:
            raise DerivationError(
                f"virtual-power balance: {symbol} is not an algebraic number at these values (it holds "
                f"{', '.join(functions)}); the balance works in exact numbers with square roots"
            )


def _solve_exact(rows: list[list[sympy.Expr]], rhs: list[sympy.Expr], failure: str) -> list[sympy.Expr]:
    """The unique solution of ``rows x = rhs`` (exact, square roots allowed), or an error."""
    A = sympy.Matrix(rows)
    if A.rank(iszerofunc=is_zero) != A.cols:
        raise DerivationError(f"virtual-power balance: {failure}")
    return [exact(v) for v in A.LUsolve(sympy.Matrix(rhs), iszerofunc=is_zero)]


def _speeds(train: Train, port_in: str, links: list[str], rows: list[list[sympy.Expr]]) -> dict[str, sympy.Expr]:
    """(i) Speeds from the Willis rows and the input speed set to 1 (reference at rest)."""
    a, b = train.coupling(port_in).links
    col = {link: i for i, link in enumerate(links)}
    row = [sympy.Integer(0)] * len(links)
    for end, sign in ((b, 1), (a, -1)):
        if end in col:
            row[col[end]] += sign
    values = _solve_exact(
        [*rows, row],
        [sympy.Integer(0)] * len(rows) + [sympy.Integer(1)],
        "the kinematics do not have one degree of freedom",
    )
    w = dict(zip(links, values, strict=True))
    w[train.reference] = sympy.Integer(0)
    return w


def _port_terms(train: Train, link: str, port_in: str, port_out: str) -> tuple[sympy.Expr, sympy.Expr]:
    """Torque-balance terms of the ports on ``link``: the unit input torque (a constant) and
    the coefficient of the unknown output torque."""
    const, out = sympy.Integer(0), sympy.Integer(0)
    for port, is_output in ((port_in, False), (port_out, True)):
        pa, pb = train.coupling(port).links
        for end, sign in ((pb, 1), (pa, -1)):
            if end == link:
                if is_output:
                    out += sign
                else:
                    const += sign
    return const, out


@dataclass(frozen=True)
class _Balance:
    """The balance of one train at one design point once its link speeds ``w`` are known
    (input speed 1): what Chen's steps (ii)-(viii) share.  ``ports``: the input port,
    then the output port."""

    train: Train
    frames: Frames
    values: Values
    links: tuple[str, ...]
    w: Mapping[str, sympy.Expr]
    ports: tuple[str, str]

    def rel(self, link: str, carrier: str) -> sympy.Expr:
        """The speed of ``link`` relative to ``carrier``."""
        return self.frames.relative(self.w, link, carrier)

    def solve(self, first_drives: Mapping[str, bool] | None) -> tuple[Torques, sympy.Expr]:
        """(vi-vii) the mesh torques and the output torque, the input torque 1: lossless
        (``first_drives`` None) or with the losses of the given drivers."""
        # Unknowns: (M_p, M_q) per mesh, the extra ones of the geometry, then the output
        # torque; the input torque is 1.
        frames, meshes = self.frames, self.frames.meshes
        n = 2 * len(meshes) + frames.extra_unknowns + 1
        eqs = [self.loss_row(m, k, n, first_drives) for k, m in enumerate(meshes)]
        rhs: list[sympy.Expr] = [sympy.Integer(0)] * len(meshes)
        for link in self.links:  # (vi) torque balance of every member about its axis
            row = [sympy.Integer(0)] * n
            for k, m in enumerate(meshes):
                frames.reactions(row, link, k, m)
            frames.extra_reactions(row, link, 2 * len(meshes))
            const, row[n - 1] = _port_terms(self.train, link, *self.ports)
            eqs.append(row)
            rhs.append(-const)
        x = _solve_exact(eqs, rhs, "the torque balances do not determine the torques")
        return {m.name: (x[2 * k], x[2 * k + 1]) for k, m in enumerate(meshes)}, x[n - 1]

    def loss_row(self, mesh: GearMesh, k: int, n: int, first_drives: Mapping[str, bool] | None) -> list[sympy.Expr]:
        """(iv-v) Loss formula of mesh ``k`` (of ``n`` unknowns): M_q s_q + eta M_p s_p = 0
        (driver p) divided by the carrier-frame speed through Willis (s_p a_p = s_q a_q):
        eta M_p a_q + M_q a_p = 0, which stays regular in a locked set (where the mesh
        does not turn and loses nothing)."""
        a_p, a_q = self.frames.arms[mesh.name]
        carrier = self.frames.carriers[mesh.name]
        turning = self.rel(mesh.links[0], carrier) != 0 or self.rel(mesh.links[1], carrier) != 0
        row = [sympy.Integer(0)] * n
        row[2 * k], row[2 * k + 1] = a_q, a_p
        if first_drives is not None and turning:
            if first_drives[mesh.name]:
                row[2 * k] = _efficiency(mesh, 0, self.values) * a_q
            else:
                row[2 * k + 1] = _efficiency(mesh, 1, self.values) * a_p
        return row

    def delivered(self, torques: Torques, mesh: GearMesh, side: int) -> sympy.Expr:
        """The virtual power gear ``side`` of ``mesh`` delivers in its carrier's frame."""
        return exact(-torques[mesh.name][side] * self.rel(mesh.links[side], self.frames.carriers[mesh.name]))

    def agrees(self, torques: Torques, first: Mapping[str, bool]) -> bool:
        """Whether every mesh's driver delivers virtual power in the solution ``torques``."""
        # The driven side receives eta times what the driver delivers: one side decides.
        return all(self.delivered(torques, m, 0 if first[m.name] else 1) >= 0 for m in self.frames.meshes)

    def loss(self, torques: Torques, mesh: GearMesh) -> sympy.Rational:
        """The power lost in ``mesh`` (frame-invariant, eq. (4.4))."""
        carrier = self.frames.carriers[mesh.name]
        t_p, t_q = torques[mesh.name]
        return sympy.Rational(exact(-(t_p * self.rel(mesh.links[0], carrier) + t_q * self.rel(mesh.links[1], carrier))))

    def result(self) -> BalanceResult:
        """Steps (ii)-(viii): lossless flow and drivers, the lossy solve, losses, efficiency.

        The lossless drivers (Chen's steps (ii)-(iii)) hold while the lossy solution keeps
        every mesh's power crossing the way they assume.  Near a turning point the losses can
        reverse a small mesh power: then every assignment of drivers is tried and the one
        that agrees with its own solution is taken (a working one, with positive efficiency,
        before a self-locking one); none or several different ones are refused."""
        train, w, meshes = self.train, self.w, self.frames.meshes
        pa, pb = train.coupling(self.ports[0]).links
        p_in = exact(w[pb] - w[pa])
        qa, qb = train.coupling(self.ports[1]).links
        out_speed = w[qb] - w[qa]
        # (ii-iii) lossless flow: the side delivering virtual power drives.
        lossless, _ = self.solve(None)
        first = {m.name: bool(self.delivered(lossless, m, 0) >= 0) for m in meshes}
        # (vii) with losses
        torques, t_out = self.solve(first)
        if not self.agrees(torques, first):
            first, torques, t_out = _agreeing_drivers(
                meshes, self.solve, self.agrees, lambda t: exact(-t * out_speed / p_in)
            )
        p_out = exact(t_out * out_speed)
        losses = {m.name: self.loss(torques, m) for m in meshes}
        # (viii) efficiency, with the power balance (4.3b) as a check.
        total_loss = sum(losses.values(), sympy.Integer(0))
        if exact(p_in + p_out - total_loss) != 0:
            # The net power entering the train is what its meshes dissipate.
            raise DerivationError("virtual-power balance: P_in + P_out differs from the losses")  # pragma: no cover
        efficiency = sympy.Rational(exact((p_in - total_loss) / p_in))
        if exact(efficiency + p_out / p_in) != 0:
            raise DerivationError("virtual-power balance: the two efficiency forms differ")  # pragma: no cover
        return BalanceResult(
            efficiency, sympy.Rational(p_in), sympy.Rational(p_out), losses, first, {k: exact(v) for k, v in w.items()}
        )


def _agreeing_drivers(
    meshes: list[GearMesh],
    solve: Callable[[Mapping[str, bool] | None], tuple[Torques, sympy.Expr]],
    agrees: Callable[[Torques, Mapping[str, bool]], bool],
    efficiency: Callable[[sympy.Expr], sympy.Expr],
) -> tuple[dict[str, bool], Torques, sympy.Expr]:
    """The assignment of drivers that agrees with its own lossy solution (working first);
    ``efficiency`` of the output torque."""
    found: list[tuple[sympy.Expr, dict[str, bool], Torques, sympy.Expr]] = []
    for choice in itertools.product((True, False), repeat=len(meshes)):
        first = {m.name: c for m, c in zip(meshes, choice, strict=True)}
        try:
            torques, t_out = solve(first)
        except DerivationError:
            continue  # this assignment leaves the torques undetermined
        if agrees(torques, first):
            found.append((efficiency(t_out), first, torques, t_out))
    working = [f for f in found if f[0] > 0] or found
    if not working or len({f[0] for f in working}) > 1:
        raise DerivationError(
            "virtual-power balance: "
            + ("no assignment of driving gears agrees" if not working else "several assignments agree")
            + " with its own power flow"
        )
    _, first, torques, t_out = working[0]
    return first, torques, t_out


def _efficiency(mesh: GearMesh, index: int, values: Values) -> sympy.Expr:
    if mesh.efficiencies is None or (mesh.friction.coulomb is None and mesh.friction.linear is None):
        return sympy.Integer(1)
    return sympy.sympify(mesh.efficiencies[index]).subs(values)
