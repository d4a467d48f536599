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
axes meet at one apex (:func:`_conical_balance`: a planet's speed is its spin about its
own axis relative to its carrier, and the Willis equation of a mesh equates the
carrier-frame speeds of the pitch point, ``s_p (u_p x P).t = s_q (u_q x P).t``);
other trains get a clear error.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import sympy

from davies_sym.algebra.screws import cross
from davies_sym.errors import DerivationError
from davies_sym.geometry import train_layout
from davies_sym.geometry.cone import conical_layout
from davies_sym.geometry.layout import Layout
from davies_sym.topology.couplings import GearMesh, Prismatic, Revolute
from davies_sym.topology.model import Train

Values = Mapping[sympy.Symbol, sympy.Expr]
Point2 = tuple[sympy.Expr, sympy.Expr]


def _exact(x: object) -> sympy.Expr:
    """Canonical form of an exact number with square roots: a + b sqrt(m) expanded."""
    return sympy.expand(sympy.radsimp(sympy.sympify(x)))


def _numbers(layout: Layout, values: Values) -> Callable[[object], sympy.Expr]:
    """Exact value of a layout expression at ``values``, its square roots evaluated by sympy."""
    roots = {r.symbol: sympy.sqrt(r.radicand.subs(values)) for r in layout.radicals}
    return lambda expr: _exact(sympy.sympify(expr).subs(values).subs(roots))


def _same(p: Point2, q: Point2) -> bool:
    return all(_exact(a - b) == 0 for a, b in zip(p, q, strict=True))


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


class _Members:
    """Axes of the members and which carrier holds which planet."""

    def __init__(self, train: Train, values: Values):
        self.train = train
        layout = train_layout(train)
        number = _numbers(layout, values)

        def pt(point: object) -> Point2:
            return (number(point[0]), number(point[1]))  # type: ignore[index]

        self.gear_axis = {g.name: pt(layout.gear_centres[g.name]) for g in train.gears}
        self.pitch = {c.name: pt(layout.coupling_points[c.name]) for c in train.couplings if isinstance(c, GearMesh)}
        self.tangent = {c.name: pt(layout.mesh_tangents[c.name]) for c in train.couplings
                        if isinstance(c, GearMesh)}
        self.revolutes = [c for c in train.couplings if isinstance(c, Revolute)]
        self.bearing_axis = {c.name: pt(layout.coupling_points[c.name]) for c in self.revolutes}
        # A geared link turns about its gears' axis; any other link about the bearing by
        # which it is first reached from the reference.
        self.axis: dict[str, Point2] = {}
        for g in train.gears:
            self.axis.setdefault(g.link, self.gear_axis[g.name])
        self.axis.setdefault(train.reference, (sympy.Integer(0), sympy.Integer(0)))
        frontier, reached = [train.reference], {train.reference}
        while frontier:
            nxt = []
            for link in frontier:
                for c in self.revolutes:
                    if link in c.links:
                        other = c.links[1] if c.links[0] == link else c.links[0]
                        if other not in reached:
                            reached.add(other)
                            self.axis.setdefault(other, self.bearing_axis[c.name])
                            nxt.append(other)
            frontier = nxt
        missing = [link for link in train.link_names if link not in reached]
        if missing:
            raise DerivationError(f"virtual-power balance: links {missing} hang on no bearing chain from the "
                                  f"reference {train.reference!r}")

    def arm(self, mesh: str, gear: str) -> sympy.Expr:
        """(z x (P - C)) . t: the pitch-point speed per unit carrier-frame speed of
        ``gear`` along the tooth-force direction (a signed distance on a line layout)."""
        (px, py), (cx, cy), (tx, ty) = self.pitch[mesh], self.gear_axis[gear], self.tangent[mesh]
        return _exact(-(py - cy) * tx + (px - cx) * ty)

    def coaxial_group(self, link: str, axis: Point2) -> set[str]:
        """Links joined to ``link`` by bearings on ``axis``: they hold that axis."""
        group, frontier = {link}, [link]
        while frontier:
            current = frontier.pop()
            for c in self.revolutes:
                if current in c.links and _same(self.bearing_axis[c.name], axis):
                    other = c.links[1] if c.links[0] == current else c.links[0]
                    if other not in group:
                        group.add(other)
                        frontier.append(other)
        return group

    def carrier(self, mesh: GearMesh) -> str:
        """The link holding both gear axes of ``mesh``."""
        groups = [self.coaxial_group(link, self.gear_axis[gear]) - set(mesh.links)
                  for gear, link in zip(mesh.gears, mesh.links, strict=True)]
        common = [link for link in self.train.link_names if link in groups[0] and link in groups[1]]
        if not common:
            raise DerivationError(f"virtual-power balance: no carrier found for mesh {mesh.name}")
        return common[0]

    def carries(self, carrier: str, planet: str) -> bool:
        """Whether ``planet`` turns in a bearing of ``carrier`` off the carrier's axis."""
        return not _same(self.axis[planet], self.axis[carrier]) and any(
            set(c.links) == {carrier, planet} and _same(self.bearing_axis[c.name], self.axis[planet])
            for c in self.revolutes)


def virtual_power_balance(train: Train, values: Values, input: str | None = None,
                          layout: Layout | None = None) -> BalanceResult:
    """Efficiency of ``train`` at ``values`` with ``input`` (default: the declared one);
    ``layout`` replaces the derived geometry of a bevel train (to study a published one)."""
    port_in = input or train.ports.input
    port_out = train.ports.output if port_in == train.ports.input else train.ports.input
    if any(g.axis is not None or g.tilted for g in train.gears):
        return _conical_balance(train, values, port_in, port_out, layout or conical_layout(train))
    members = _Members(train, values)
    meshes = [c for c in train.couplings if isinstance(c, GearMesh)]
    # A lossless prismatic pair in a planar train (an Oldham coupling) keeps its two
    # links at one angular speed and passes a couple between them.
    sliders = [c for c in train.couplings if isinstance(c, Prismatic)]
    lossy = [c.name for c in sliders if not c.friction.lossless]
    others = [c.name for c in train.couplings if not isinstance(c, (GearMesh, Prismatic, Revolute))]
    if lossy or others:
        raise DerivationError(f"virtual-power balance: couplings {lossy + others} are outside its scope "
                              "(lossy sliders, explicit screws)")
    carriers = {m.name: members.carrier(m) for m in meshes}
    # Signed distance from each gear's axis to the pitch point: s_p a_p = s_q a_q (Willis).
    arms = {m.name: tuple(members.arm(m.name, g) for g in m.gears) for m in meshes}
    links = [link for link in train.link_names if link != train.reference]
    col = {link: i for i, link in enumerate(links)}

    # (i) kinematics: Willis equations and the input speed set to 1.
    rows = []
    for m in meshes:
        row = [sympy.Integer(0)] * len(links)
        c = carriers[m.name]
        for sign, arm, link in zip((1, -1), arms[m.name], m.links, strict=True):
            if link in col:
                row[col[link]] += sign * arm
            if c in col:
                row[col[c]] -= sign * arm
        rows.append(row)
    for k in sliders:
        row = [sympy.Integer(0)] * len(links)
        for link, sign in zip(k.links, (-1, 1), strict=True):
            if link in col:
                row[col[link]] += sign
        rows.append(row)
    w = _speeds(train, port_in, links, rows)

    def rel(link: str, carrier: str) -> sympy.Expr:
        return w[link] - w[carrier]

    def solve(first_drives: Mapping[str, bool] | None) -> tuple[Torques, sympy.Expr]:
        # Unknowns: (M_p, M_q) per mesh, a couple per slider, then the output torque;
        # the input torque is 1.
        n = 2 * len(meshes) + len(sliders) + 1
        eqs = [_loss_row(m, k, n, arms[m.name], rel, carriers[m.name], first_drives, values)
               for k, m in enumerate(meshes)]
        rhs: list[sympy.Expr] = [sympy.Integer(0)] * len(meshes)
        for link in links:  # (vi) torque balance of every member about its axis
            row = [sympy.Integer(0)] * n
            for k, m in enumerate(meshes):
                for side in (0, 1):
                    if m.links[side] == link:
                        if not _same(members.gear_axis[m.gears[side]], members.axis[link]):
                            raise DerivationError(f"virtual-power balance: gear {m.gears[side]} is not on the "
                                                  f"axis of its link {link}")
                        row[2 * k + side] += 1
                    planet = m.links[side]
                    partner = 1 - side
                    # A planet-planet mesh of one carrier acts on it with equal and opposite
                    # wrenches: nothing reaches the carrier.
                    if (planet != link and m.links[partner] != link and members.carries(link, planet)
                            and not members.carries(link, m.links[partner])):
                        if not _same(members.gear_axis[m.gears[partner]], members.axis[link]):
                            raise DerivationError(f"virtual-power balance: planet {planet} meshes gear "
                                                  f"{m.gears[partner]}, which is not coaxial with its carrier {link}")
                        row[2 * k + partner] -= 1
            for j, k in enumerate(sliders):
                slider_col = 2 * len(meshes) + j
                for end, sign in zip(k.links, (-1, 1), strict=True):
                    if end == link:
                        row[slider_col] += sign
                    elif link not in k.links and members.carries(link, end):
                        row[slider_col] += sign  # the couple on a planet reaches its carrier
            const, row[n - 1] = _port_terms(train, link, port_in, port_out)
            eqs.append(row)
            rhs.append(-const)
        x = _solve_exact(eqs, rhs, "the torque balances do not determine the torques")
        return {m.name: (x[2 * k], x[2 * k + 1]) for k, m in enumerate(meshes)}, x[n - 1]

    return _balance_result(train, meshes, carriers, w, rel, solve, port_in, port_out)


Torques = dict[str, tuple[sympy.Expr, sympy.Expr]]


def _is_zero(x: object) -> bool:
    return bool(_exact(x) == 0)


def _solve_exact(rows: list[list[sympy.Expr]], rhs: list[sympy.Expr], failure: str) -> list[sympy.Expr]:
    """The unique solution of ``rows x = rhs`` (exact, square roots allowed), or an error."""
    A = sympy.Matrix(rows)
    if A.rank(iszerofunc=_is_zero) != A.cols:
        raise DerivationError(f"virtual-power balance: {failure}")
    return [_exact(v) for v in A.LUsolve(sympy.Matrix(rhs), iszerofunc=_is_zero)]


def _speeds(train: Train, port_in: str, links: list[str], rows: list[list[sympy.Expr]]) -> dict[str, sympy.Expr]:
    """(i) Speeds from the Willis rows and the input speed set to 1 (reference at rest)."""
    a, b = train.coupling(port_in).links
    col = {link: i for i, link in enumerate(links)}
    row = [sympy.Integer(0)] * len(links)
    for end, sign in ((b, 1), (a, -1)):
        if end in col:
            row[col[end]] += sign
    values = _solve_exact([*rows, row], [sympy.Integer(0)] * len(rows) + [sympy.Integer(1)],
                          "the kinematics do not have one degree of freedom")
    w = dict(zip(links, values, strict=True))
    w[train.reference] = sympy.Integer(0)
    return w


def _loss_row(mesh: GearMesh, k: int, n: int, arms: tuple[sympy.Expr, sympy.Expr],
              rel: Callable[[str, str], sympy.Expr], carrier: str, first_drives: Mapping[str, bool] | None,
              values: Values) -> list[sympy.Expr]:
    """(iv-v) Loss formula of mesh ``k``: M_q s_q + eta M_p s_p = 0 (driver p) divided by the
    carrier-frame speed through Willis (s_p a_p = s_q a_q): eta M_p a_q + M_q a_p = 0, which
    stays regular in a locked set (where the mesh does not turn and loses nothing)."""
    a_p, a_q = arms
    turning = rel(mesh.links[0], carrier) != 0 or rel(mesh.links[1], carrier) != 0
    row = [sympy.Integer(0)] * n
    row[2 * k], row[2 * k + 1] = a_q, a_p
    if first_drives is not None and turning:
        if first_drives[mesh.name]:
            row[2 * k] = _efficiency(mesh, 0, values) * a_q
        else:
            row[2 * k + 1] = _efficiency(mesh, 1, values) * a_p
    return row


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


def _balance_result(train: Train, meshes: list[GearMesh], carriers: Mapping[str, str], w: Mapping[str, sympy.Expr],
                    rel: Callable[[str, str], sympy.Expr],
                    solve: Callable[[Mapping[str, bool] | None], tuple[Torques, sympy.Expr]],
                    port_in: str, port_out: str) -> BalanceResult:
    """Steps (ii)-(viii): lossless flow and drivers, the lossy solve, losses, efficiency."""
    # (ii-iii) lossless flow: the side delivering virtual power drives.
    lossless, _ = solve(None)
    first = {m.name: bool(-lossless[m.name][0] * rel(m.links[0], carriers[m.name]) >= 0) for m in meshes}
    # (vii) with losses
    torques, t_out = solve(first)
    pa, pb = train.coupling(port_in).links
    p_in = _exact(w[pb] - w[pa])
    qa, qb = train.coupling(port_out).links
    p_out = _exact(t_out * (w[qb] - w[qa]))
    losses = {m.name: sympy.Rational(_exact(-(torques[m.name][0] * rel(m.links[0], carriers[m.name])
                                             + torques[m.name][1] * rel(m.links[1], carriers[m.name]))))
              for m in meshes}
    # (viii) efficiency, with the power balance (4.3b) as a check.
    total_loss = sum(losses.values(), sympy.Integer(0))
    if _exact(p_in + p_out - total_loss) != 0:
        # The net power entering the train is what its meshes dissipate.
        raise DerivationError("virtual-power balance: P_in + P_out differs from the losses")  # pragma: no cover
    efficiency = sympy.Rational(_exact((p_in - total_loss) / p_in))
    if _exact(efficiency + p_out / p_in) != 0:
        raise DerivationError("virtual-power balance: the two efficiency forms differ")  # pragma: no cover
    return BalanceResult(efficiency, sympy.Rational(p_in), sympy.Rational(p_out), losses, first,
                         {k: _exact(v) for k, v in w.items()})


def _efficiency(mesh: GearMesh, index: int, values: Values) -> sympy.Expr:
    if mesh.efficiencies is None or (mesh.friction.coulomb is None and mesh.friction.linear is None):
        return sympy.Integer(1)
    return sympy.sympify(mesh.efficiencies[index]).subs(values)


def _conical_balance(train: Train, values: Values, port_in: str, port_out: str, layout: Layout) -> BalanceResult:
    """Chen's eight steps for a train whose axes meet at one apex (bevel, face gears).

    Members on the main axis turn at w about it; a planet spins at s about its own axis
    relative to the carrier whose bearing holds it.  Moments are taken about each
    member's axis.  Square roots of the geometry are evaluated exactly (sympy numbers).
    """
    number = _numbers(layout, values)

    def vec(v: object) -> tuple[sympy.Expr, ...]:
        return tuple(number(x) for x in v)  # type: ignore[attr-defined]

    main = vec(layout.axis)
    meshes = [c for c in train.couplings if isinstance(c, GearMesh)]
    others = [c.name for c in train.couplings if not isinstance(c, (GearMesh, Revolute))]
    if others:
        raise DerivationError(f"virtual-power balance: couplings {others} are outside its scope in a bevel train")
    axis = {g.link: vec(layout.gear_axes[g.name]) for g in train.gears}
    carrier_of: dict[str, str] = {}
    for c in train.couplings:
        if isinstance(c, Revolute):
            bearing = vec(layout.coupling_axes[c.name])
            for planet, holder in (c.links, c.links[::-1]):
                if planet in axis and not _parallel(axis[planet], main) and _parallel(bearing, axis[planet]):
                    carrier_of[planet] = holder
    planets = set(carrier_of)
    links = [link for link in train.link_names if link != train.reference]
    col = {link: i for i, link in enumerate(links)}
    arms, carriers = {}, {}
    for m in meshes:
        point, tangent = vec(layout.coupling_points[m.name]), vec(layout.mesh_tangents[m.name])
        held = {carrier_of[link] for link in m.links if link in planets}
        if len(held) != 1:
            raise DerivationError(f"virtual-power balance: mesh {m.name} needs exactly one carrier in a bevel train")
        carriers[m.name] = held.pop()
        arms[m.name] = tuple(_exact(sum(x * t for x, t in zip(cross(axis[link] if link in planets else main, point),
                                                              tangent, strict=True)))
                             for link in m.links)

    def speed_row(link: str, carrier: str, factor: sympy.Expr, row: list[sympy.Expr]) -> None:
        # Carrier-frame speed: a planet's spin, or w - w_c about the main axis.
        if link in planets:
            if carrier_of[link] != carrier:
                raise DerivationError(f"virtual-power balance: planet {link} meshes in a frame other than its carrier")
            row[col[link]] += factor
            return
        if link in col:
            row[col[link]] += factor
        if carrier in col:
            row[col[carrier]] -= factor

    rows = []
    for m in meshes:
        row = [sympy.Integer(0)] * len(links)
        for sign, arm, link in zip((1, -1), arms[m.name], m.links, strict=True):
            speed_row(link, carriers[m.name], sign * arm, row)
        rows.append(row)
    w = _speeds(train, port_in, links, rows)

    def rel(link: str, carrier: str) -> sympy.Expr:
        return w[link] if link in planets else w[link] - w[carrier]

    def solve(first_drives: Mapping[str, bool] | None) -> tuple[Torques, sympy.Expr]:
        n = 2 * len(meshes) + 1
        eqs = [_loss_row(m, k, n, arms[m.name], rel, carriers[m.name], first_drives, values)
               for k, m in enumerate(meshes)]
        rhs: list[sympy.Expr] = [sympy.Integer(0)] * len(meshes)
        for link in links:
            row = [sympy.Integer(0)] * n
            for k, m in enumerate(meshes):
                for side in (0, 1):
                    if m.links[side] == link:
                        row[2 * k + side] += 1
                    partner = m.links[1 - side]
                    # The planet's bearing passes to its carrier the mesh's moment about the
                    # main axis: minus the moment on the partner gear, which turns about it.
                    if (m.links[side] in planets and carrier_of[m.links[side]] == link and partner != link
                            and partner not in planets):
                        row[2 * k + 1 - side] -= 1
            const, row[n - 1] = _port_terms(train, link, port_in, port_out)
            eqs.append(row)
            rhs.append(-const)
        x = _solve_exact(eqs, rhs, "the torque balances do not determine the torques")
        return {m.name: (x[2 * k], x[2 * k + 1]) for k, m in enumerate(meshes)}, x[n - 1]

    return _balance_result(train, meshes, carriers, w, rel, solve, port_in, port_out)


def _parallel(a: tuple[sympy.Expr, ...], b: tuple[sympy.Expr, ...]) -> bool:
    return all(_is_zero(x) for x in cross(a, b))  # type: ignore[arg-type]
