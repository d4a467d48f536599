"""Independent numeric oracle: speed ratio and efficiency of a planar parallel-axis
gear train by per-member torque and force balance, in exact rational arithmetic.

Nothing here comes from ``davies_sym``: the train is a plain description (members with
an axis position and, for a planet, the member that carries it; gears; meshes with an
ordinary efficiency; a fixed member; ports) and the balance is written from first
principles:

* Kinematics (Willis, in the frame of the mesh's carrier c): the pitch points of the two
  gears have the same velocity, so for an external mesh
  ``r_g (w_g - w_c) = -r_h (w_h - w_c)`` and for an internal one
  ``r_g (w_g - w_c) = +r_h (w_h - w_c)``; the fixed member has ``w = 0`` and the input
  ``w = 1``.  A mesh whose gears both turn about axes fixed in the housing has the
  housing as carrier; a mesh with a planet has the planet's carrier.
* Statics (pressure angle zero, frictionless bearings): each mesh k carries a tangential
  tooth force ``F_k`` along the common tangent at the pitch point P (on the second gear
  ``+F t``, on the first ``-F t``, Newton's third law) and a friction couple ``M_k``
  (``+M`` on the second gear, ``-M`` on the first), as in the Coulomb model where the
  friction moment acts about the relative-motion axis through the pitch point.
  Every moving member is in torque equilibrium about its own axis.  A planet's bearing
  takes the resultant of its tooth forces (force balance of the planet, sum F + R = 0);
  the carrier receives ``-R`` at the planet centre, i.e. a torque ``(O_p x sum F)_z``
  about the main axis.  Members turning about an axis fixed in the housing need only the
  torque balance about that axis (the housing bearing takes the force).
* Friction: in the carrier frame the power of the mesh on gear X is ``tau_X (w_X - w_c)``
  (``tau_X`` its torque about X's axis); when gear g drives, ``P_h = -eta P_g``
  (power delivered to the driven gear = eta x power taken from the driver).  The driver is
  the gear whose carrier-frame power is negative; starting from the lossless solution the
  balance is solved again until the driver of every mesh stops changing.

Overall efficiency = -P_out / P_in with ``P = T_ext w`` at each port member.  The dissipated
power of mesh k is ``M_k (w_a - w_b)`` (the tooth forces do no net work because the pitch
points move together), so ``P_in + P_out = sum of losses`` is a check of the geometry
against the kinematics.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from fractions import Fraction

Number = Fraction
Vec = tuple[Fraction, Fraction]
ORIGIN: Vec = (Fraction(0), Fraction(0))


class OracleError(Exception):
    """The oracle cannot give a result for this train."""


class DescriptionError(OracleError):
    """The description is inconsistent (unknown names, mesh centre distances, ...)."""


class MobilityProblem(OracleError):
    """The kinematics do not leave exactly one degree of freedom driven by the input."""


class SelfLocking(OracleError):
    """No consistent assignment of driving gears with positive efficiency exists.
    ``value``: the efficiency (<= 0) of the consistent assignment when there is exactly one."""

    def __init__(self, message: str, value: Fraction | None = None):
        super().__init__(message)
        self.value = value


# -- description -------------------------------------------------------------------------


@dataclass(frozen=True)
class Member:
    """A rigid member.  ``carrier``: the member whose bearing holds this one's axis
    (a planet); None when the axis is fixed in the housing (the main axis at the origin,
    or another fixed axis).  ``axis``: position of the axis (for a planet, at the instant
    considered, in the housing frame)."""

    name: str
    carrier: str | None = None
    axis: Vec = ORIGIN


@dataclass(frozen=True)
class Gear:
    """A gear on ``member`` with pitch radius ``radius``; ``internal`` for an annulus."""

    name: str
    member: str
    radius: Fraction
    internal: bool = False


@dataclass(frozen=True)
class Mesh:
    """A mesh between two gears with ordinary efficiency ``eta`` (carrier held)."""

    name: str
    gears: tuple[str, str]
    eta: Fraction


@dataclass(frozen=True)
class State:
    """An operating state: ports, members braked to the fixed member, pairs of members
    clutched together, members running free (removed with their meshes)."""

    name: str
    input: str
    output: str
    brake: tuple[str, ...] = ()
    clutch: tuple[tuple[str, str], ...] = ()
    free: tuple[str, ...] = ()


@dataclass(frozen=True)
class TrainSpec:
    """A train: ``ports`` maps a port name to the member whose rotation it carries (the
    other side of every port is the fixed member)."""

    name: str
    members: tuple[Member, ...]
    gears: tuple[Gear, ...]
    meshes: tuple[Mesh, ...]
    fixed: str
    ports: Mapping[str, str]
    input: str
    output: str
    states: tuple[State, ...] = ()

    def member(self, name: str) -> Member:
        for m in self.members:
            if m.name == name:
                return m
        raise DescriptionError(f"unknown member {name!r}")

    def gear(self, name: str) -> Gear:
        for g in self.gears:
            if g.name == name:
                return g
        raise DescriptionError(f"unknown gear {name!r}")

    def state(self, name: str) -> State:
        for s in self.states:
            if s.name == name:
                return s
        raise DescriptionError(f"unknown state {name!r}")


@dataclass
class BalanceResult:
    """The solved train for one input port."""

    input: str
    output: str
    #: w_in / w_out (speeds relative to the fixed member).
    speed_ratio: Fraction
    #: -P_out / P_in.
    efficiency: Fraction
    speeds: dict[str, Fraction]
    #: External torque on each port member (input torque 1).
    torques: dict[str, Fraction]
    forces: dict[str, Fraction]
    couples: dict[str, Fraction]
    #: Mesh -> True when its first gear drives (carrier frame).
    first_drives: dict[str, bool]
    losses: dict[str, Fraction]
    power_in: Fraction
    power_out: Fraction
    iterations: int = 0
    notes: list[str] = field(default_factory=list)


# -- exact linear algebra ----------------------------------------------------------------


def solve_linear(rows: Sequence[Sequence[Fraction]], rhs: Sequence[Fraction], ncols: int) -> list[Fraction] | None:
    """The unique solution of ``rows x = rhs`` (Gauss-Jordan over the rationals), or None
    when the system is inconsistent or has a null space."""
    a = [[Fraction(v) for v in row] + [Fraction(b)] for row, b in zip(rows, rhs, strict=True)]
    pivots: list[int] = []
    r = 0
    for col in range(ncols):
        piv = next((i for i in range(r, len(a)) if a[i][col] != 0), None)
        if piv is None:
            continue
        a[r], a[piv] = a[piv], a[r]
        inv = 1 / a[r][col]
        a[r] = [v * inv for v in a[r]]
        for i in range(len(a)):
            if i != r and a[i][col] != 0:
                f = a[i][col]
                a[i] = [vi - f * vr for vi, vr in zip(a[i], a[r], strict=True)]
        pivots.append(col)
        r += 1
    if len(pivots) < ncols:
        return None
    if any(row[-1] != 0 for row in a[r:]):
        return None
    x = [Fraction(0)] * ncols
    for i, col in enumerate(pivots):
        x[col] = a[i][-1]
    return x


def exact_sqrt(value: Fraction) -> Fraction:
    """Square root of a rational that is a perfect square (else DescriptionError)."""
    if value < 0:
        raise DescriptionError(f"negative square {value}")
    n, d = value.numerator, value.denominator
    rn, rd = math.isqrt(n), math.isqrt(d)
    if rn * rn != n or rd * rd != d:
        raise DescriptionError(f"centre distance sqrt({value}) is not rational; use a rational layout")
    return Fraction(rn, rd)


def cross(p: Vec, q: Vec) -> Fraction:
    """z component of the planar cross product p x q."""
    return p[0] * q[1] - p[1] * q[0]


def sub(p: Vec, q: Vec) -> Vec:
    return (p[0] - q[0], p[1] - q[1])


# -- states ------------------------------------------------------------------------------


def in_state(train: TrainSpec, state: State | str) -> TrainSpec:
    """``train`` with a state applied: braked members join the fixed member, clutched
    members join each other (one rigid member), free members are removed with their meshes;
    a mesh whose gears end up on one member carries no motion and is dropped."""
    if isinstance(state, str):
        state = train.state(state)
    parent = {m.name: m.name for m in train.members}

    def find(x: str) -> str:
        while parent[x] != x:
            x = parent[x]
        return x

    def union(a: str, b: str, root: str | None = None) -> None:
        ra, rb = find(a), find(b)
        if ra == rb:
            return
        if root is not None and find(root) == rb:
            ra, rb = rb, ra
        parent[rb] = ra

    for b in state.brake:
        union(train.fixed, b, root=train.fixed)
    for a, b in state.clutch:
        union(a, b, root=train.fixed)
    fixed = find(train.fixed)
    free = set(state.free)
    groups: dict[str, list[Member]] = {}
    for m in train.members:
        if m.name not in free:
            groups.setdefault(find(m.name), []).append(m)
    members = []
    for root, group in groups.items():
        planets = [m for m in group if m.carrier is not None]
        if len(group) > 1 and planets:
            raise DescriptionError(f"state {state.name}: a planet ({planets[0].name}) cannot be braked or clutched")
        axes = {m.axis for m in group}
        if len(axes) > 1:
            raise DescriptionError(f"state {state.name}: members of {root} are not coaxial")
        base = group[0]
        carrier = None if base.carrier is None else find(base.carrier)
        if carrier is not None and carrier in free:
            raise DescriptionError(f"state {state.name}: carrier of {base.name} is free")
        members.append(Member(root, carrier, base.axis))
    gears = tuple(replace(g, member=find(g.member)) for g in train.gears if g.member not in free)
    kept = {g.name for g in gears}
    by_name = {g.name: g for g in gears}
    meshes = tuple(
        m
        for m in train.meshes
        if m.gears[0] in kept and m.gears[1] in kept and by_name[m.gears[0]].member != by_name[m.gears[1]].member
    )
    ports = {p: find(mem) for p, mem in train.ports.items() if mem not in free}
    return TrainSpec(
        f"{train.name}[{state.name}]", tuple(members), gears, meshes, fixed, ports, state.input, state.output
    )


# -- the balance -------------------------------------------------------------------------


@dataclass(frozen=True)
class _MeshGeometry:
    mesh: Mesh
    a: str  # member of the first gear
    b: str  # member of the second gear
    carrier: str | None  # None: the housing (fixed member)
    pitch: Vec
    tangent: Vec
    #: Lever arms: torque of a unit force +t at the pitch point about each member's axis.
    arm_a: Fraction
    arm_b: Fraction


class Balance:
    """The oracle for one train (apply a state first with :func:`in_state`)."""

    def __init__(self, train: TrainSpec):
        self.train = train
        self.members = {m.name: m for m in train.members}
        if train.fixed not in self.members:
            raise DescriptionError(f"fixed member {train.fixed!r} is not a member")
        for g in train.gears:
            if g.member not in self.members:
                raise DescriptionError(f"gear {g.name}: unknown member {g.member!r}")
            if g.radius <= 0:
                raise DescriptionError(f"gear {g.name}: radius must be positive")
        for m in train.members:
            if m.carrier is not None:
                c = self.members.get(m.carrier)
                if c is None:
                    raise DescriptionError(f"planet {m.name}: unknown carrier {m.carrier!r}")
                if c.carrier is not None or c.axis != ORIGIN:
                    raise DescriptionError(f"planet {m.name}: its carrier must turn about the main axis")
        self.moving = [m.name for m in train.members if m.name != train.fixed]
        self.geometry = [self._mesh_geometry(mesh) for mesh in train.meshes]

    # geometry ---------------------------------------------------------------------------
    def _frame(self, member: str) -> str | None:
        """The member in whose frame ``member``'s axis is fixed (None: the housing)."""
        m = self.members[member]
        if member == self.train.fixed or m.carrier == self.train.fixed:
            return None
        return m.carrier

    def _mesh_geometry(self, mesh: Mesh) -> _MeshGeometry:
        g, h = (self.train.gear(n) for n in mesh.gears)
        if g.internal and h.internal:
            raise DescriptionError(f"mesh {mesh.name}: two internal gears")
        ma, mb = self.members[g.member], self.members[h.member]
        fa, fb = self._frame(ma.name), self._frame(mb.name)
        if fa == fb:
            carrier = fa
        elif fa is None and ma.axis == ORIGIN:
            carrier = fb
        elif fb is None and mb.axis == ORIGIN:
            carrier = fa
        else:
            raise DescriptionError(f"mesh {mesh.name}: no member holds both gear axes")
        if carrier == self.train.fixed:
            carrier = None
        oa, ob = ma.axis, mb.axis
        d2 = (ob[0] - oa[0]) ** 2 + (ob[1] - oa[1]) ** 2
        d = exact_sqrt(d2)
        expected = abs(g.radius - h.radius) if (g.internal or h.internal) else g.radius + h.radius
        if d != expected or d == 0:
            raise DescriptionError(f"mesh {mesh.name}: centre distance {d}, the radii need {expected}")
        u = ((ob[0] - oa[0]) / d, (ob[1] - oa[1]) / d)  # from the first gear's axis to the second's
        if h.internal:  # pinion g inside annulus h: pitch point on h's circle beyond g
            pitch = (ob[0] - h.radius * u[0], ob[1] - h.radius * u[1])
        else:  # external, or annulus g: pitch point at r_g from g's axis towards h
            pitch = (oa[0] + g.radius * u[0], oa[1] + g.radius * u[1])
        tangent = (-u[1], u[0])
        return _MeshGeometry(
            mesh,
            ma.name,
            mb.name,
            carrier,
            pitch,
            tangent,
            cross(sub(pitch, oa), tangent),
            cross(sub(pitch, ob), tangent),
        )

    # kinematics -------------------------------------------------------------------------
    def speeds(self, input_member: str) -> dict[str, Fraction]:
        """Absolute speeds (housing frame) with the input member at speed 1 (Willis)."""
        index = {name: i for i, name in enumerate(self.moving)}
        n = len(self.moving)
        rows: list[list[Fraction]] = []
        rhs: list[Fraction] = []

        def add(row: list[Fraction], member: str | None, coef: Fraction) -> None:
            if member is not None and member != self.train.fixed:
                row[index[member]] += coef

        for geo in self.geometry:
            g, h = (self.train.gear(x) for x in geo.mesh.gears)
            sign = -1 if (g.internal or h.internal) else 1
            row = [Fraction(0)] * n
            # r_g (w_a - w_c) + sign * r_h (w_b - w_c) = 0
            add(row, geo.a, g.radius)
            add(row, geo.b, sign * h.radius)
            add(row, geo.carrier, -g.radius - sign * h.radius)
            rows.append(row)
            rhs.append(Fraction(0))
        row = [Fraction(0)] * n
        if input_member == self.train.fixed:
            raise MobilityProblem("the input member is the fixed member")
        row[index[input_member]] = Fraction(1)
        rows.append(row)
        rhs.append(Fraction(1))
        x = solve_linear(rows, rhs, n)
        if x is None:
            raise MobilityProblem(f"{self.train.name}: the kinematics do not give one degree of freedom")
        out = {name: x[i] for name, i in index.items()}
        out[self.train.fixed] = Fraction(0)
        return out

    # statics ----------------------------------------------------------------------------
    def _statics(
        self, w: Mapping[str, Fraction], inp: str, out: str, first_drives: Mapping[str, bool] | None
    ) -> list[Fraction] | None:
        """Solve for (F_k, M_k) of every mesh and T_out, with T_in = 1.  ``first_drives``
        None: lossless (M_k = 0)."""
        m = len(self.geometry)
        ncols = 2 * m + 1
        t_out = 2 * m
        rows: list[list[Fraction]] = []
        rhs: list[Fraction] = []
        rows_of = {name: [Fraction(0)] * ncols for name in self.moving}
        rhs_of = {name: Fraction(0) for name in self.moving}
        for k, geo in enumerate(self.geometry):
            f, c = 2 * k, 2 * k + 1
            # Torque balance about each gear's own axis: on b +F t and +M, on a -F t and -M.
            if geo.b in rows_of:
                rows_of[geo.b][f] += geo.arm_b
                rows_of[geo.b][c] += 1
            if geo.a in rows_of:
                rows_of[geo.a][f] -= geo.arm_a
                rows_of[geo.a][c] -= 1
            # A planet's bearing passes its tooth force to the carrier at the planet centre.
            for member, sign in ((geo.a, -1), (geo.b, 1)):
                carrier = self.members[member].carrier
                if carrier is not None and carrier in rows_of and member != self.train.fixed:
                    centre = self.members[member].axis
                    rows_of[carrier][f] += sign * cross(centre, geo.tangent)
        rhs_of[inp] -= 1  # T_in = 1 on the input member
        rows_of[out][t_out] += 1
        for name in self.moving:
            rows.append(rows_of[name])
            rhs.append(rhs_of[name])
        for k, geo in enumerate(self.geometry):
            f, c = 2 * k, 2 * k + 1
            row = [Fraction(0)] * ncols
            wc = w[geo.carrier] if geo.carrier is not None else Fraction(0)
            wa, wb = w[geo.a] - wc, w[geo.b] - wc
            if first_drives is None or (wa == 0 and wb == 0):
                row[c] = Fraction(1)  # lossless, or no motion in the carrier frame: M = 0
            else:
                eta = geo.mesh.eta
                # carrier-frame powers: P_a = (-arm_a F - M) wa, P_b = (arm_b F + M) wb
                pa = (-geo.arm_a * wa, -wa)
                pb = (geo.arm_b * wb, wb)
                if first_drives[geo.mesh.name]:  # P_b + eta P_a = 0
                    row[f], row[c] = pb[0] + eta * pa[0], pb[1] + eta * pa[1]
                else:  # P_a + eta P_b = 0
                    row[f], row[c] = pa[0] + eta * pb[0], pa[1] + eta * pb[1]
            rows.append(row)
            rhs.append(Fraction(0))
        return solve_linear(rows, rhs, ncols)

    def _result(
        self,
        w: Mapping[str, Fraction],
        inp: str,
        out: str,
        port_in: str,
        port_out: str,
        x: Sequence[Fraction],
        first: Mapping[str, bool],
        iterations: int,
    ) -> BalanceResult:
        m = len(self.geometry)
        forces = {g.mesh.name: x[2 * k] for k, g in enumerate(self.geometry)}
        couples = {g.mesh.name: x[2 * k + 1] for k, g in enumerate(self.geometry)}
        losses = {g.mesh.name: couples[g.mesh.name] * (w[g.a] - w[g.b]) for g in self.geometry}
        t_out = x[2 * m]
        p_in, p_out = w[inp], t_out * w[out]
        if p_in == 0:
            raise MobilityProblem("the input does not turn")
        if w[out] == 0:
            raise MobilityProblem("the output does not turn")
        return BalanceResult(
            port_in,
            port_out,
            w[inp] / w[out],
            -p_out / p_in,
            dict(w),
            {port_in: Fraction(1), port_out: t_out},
            forces,
            couples,
            dict(first),
            losses,
            p_in,
            p_out,
            iterations,
        )

    def carrier_frame_powers(
        self, w: Mapping[str, Fraction], x: Sequence[Fraction]
    ) -> dict[str, tuple[Fraction, Fraction]]:
        """Power of each mesh on its first and second gear, in the mesh carrier's frame."""
        out = {}
        for k, geo in enumerate(self.geometry):
            f, c = x[2 * k], x[2 * k + 1]
            wc = w[geo.carrier] if geo.carrier is not None else Fraction(0)
            out[geo.mesh.name] = ((-geo.arm_a * f - c) * (w[geo.a] - wc), (geo.arm_b * f + c) * (w[geo.b] - wc))
        return out

    def _drivers(
        self, powers: Mapping[str, tuple[Fraction, Fraction]], previous: Mapping[str, bool] | None
    ) -> dict[str, bool]:
        out = {}
        for name, (pa, pb) in powers.items():
            if pa < 0 or pb > 0:
                out[name] = True
            elif pa > 0 or pb < 0:
                out[name] = False
            else:  # no power through this mesh: keep the previous choice
                out[name] = True if previous is None else previous[name]
        return out

    def _consistent(self, powers: Mapping[str, tuple[Fraction, Fraction]], first: Mapping[str, bool]) -> bool:
        return all((pa <= 0) if first[n] else (pb <= 0) for n, (pa, pb) in powers.items())

    def solve(
        self, port_in: str | None = None, port_out: str | None = None, lossless: bool = False, max_iterations: int = 20
    ) -> BalanceResult:
        """Speed ratio and efficiency with ``port_in`` as input (default: the train's)."""
        port_in = port_in or self.train.input
        if port_out is None:
            port_out = self.train.output if port_in == self.train.input else self.train.input
        inp, out = self.train.ports[port_in], self.train.ports[port_out]
        if inp == out:
            raise DescriptionError("input and output are the same member")
        w = self.speeds(inp)
        x0 = self._statics(w, inp, out, None)
        if x0 is None:
            raise MobilityProblem(f"{self.train.name}: the lossless statics have no unique solution")
        powers = self.carrier_frame_powers(w, x0)
        first = self._drivers(powers, None)
        if lossless:
            return self._result(w, inp, out, port_in, port_out, x0, first, 0)
        seen: list[dict[str, bool]] = []
        for iteration in range(1, max_iterations + 1):
            x = self._statics(w, inp, out, first)
            if x is None:
                raise SelfLocking(f"{self.train.name}: singular statics for drivers {first}")
            powers = self.carrier_frame_powers(w, x)
            if self._consistent(powers, first):
                result = self._result(w, inp, out, port_in, port_out, x, first, iteration)
                if result.efficiency <= 0:
                    raise SelfLocking(
                        f"{self.train.name}: efficiency {float(result.efficiency):.6g} <= 0 "
                        f"with input {port_in} (self-locking)",
                        result.efficiency,
                    )
                return result
            seen.append(dict(first))
            first = self._drivers(powers, first)
            if first in seen:
                break
        return self._enumerate(w, inp, out, port_in, port_out)

    def _enumerate(self, w: Mapping[str, Fraction], inp: str, out: str, port_in: str, port_out: str) -> BalanceResult:
        """Every driver assignment; the one consistent with its own power flow and positive
        efficiency (several or none: self-locking / inconsistency)."""
        names = [g.mesh.name for g in self.geometry]
        found = []
        for choice in itertools.product((True, False), repeat=len(names)):
            first = dict(zip(names, choice, strict=True))
            x = self._statics(w, inp, out, first)
            if x is None:
                continue
            if self._consistent(self.carrier_frame_powers(w, x), first):
                r = self._result(w, inp, out, port_in, port_out, x, first, -1)
                if r.efficiency > 0:
                    found.append(r)
        values = {r.efficiency for r in found}
        if len(values) == 1:
            return found[0]
        if not found:
            raise SelfLocking(
                f"{self.train.name}: no consistent driver assignment with positive efficiency (input {port_in})"
            )
        raise SelfLocking(
            f"{self.train.name}: several consistent driver assignments ({sorted(float(v) for v in values)})"
        )


def solve(
    train: TrainSpec, port_in: str | None = None, state: State | str | None = None, lossless: bool = False
) -> BalanceResult:
    """Speed ratio and efficiency of ``train`` (in ``state``) with ``port_in`` as input."""
    if state is not None:
        train = in_state(train, state)
    return Balance(train).solve(port_in, lossless=lossless)


def with_efficiencies(train: TrainSpec, etas: Mapping[str, Fraction] | Fraction) -> TrainSpec:
    """``train`` with other mesh efficiencies (one value for all, or per mesh)."""

    def eta(m: Mesh) -> Fraction:
        return etas if isinstance(etas, Fraction) else etas.get(m.name, m.eta)

    return replace(train, meshes=tuple(replace(m, eta=eta(m)) for m in train.meshes))


def mesh_names(train: TrainSpec) -> Iterable[str]:
    return (m.name for m in train.meshes)
