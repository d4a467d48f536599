"""Independent numeric oracle for gear trains with real losses (mesh efficiencies; bearing
Coulomb friction, viscous friction, constant drag) and one or more inputs, in exact rational
arithmetic.  Nothing comes from ``davies_sym``; only types of :mod:`oracle.balance` are reused.

Geometry: member X turns about the axis through ``(0, y_X)`` (``Member.axis``; all axes on the
y-axis), in a bearing on the housing (``carrier`` None) or, for a planet, on its carrier (which
turns about ``y = 0``).  Tooth forces are tangential (pressure angle zero): along x at the pitch
point ``(0, y_P)``; a force ``f`` at height ``y`` has the torque ``-(y - y_X) f`` about X's axis.
Kinematics: a mesh's two pitch points move together; the point ``(0, y)`` of X moves with
``v = -w_X (y - y_X) - w_H y_X`` (H the carrier holding X).  The input speeds (one per degree of
freedom) fix every speed.

Statics (steady state), unknowns: per mesh the tooth force ``F`` (``+F`` on the second gear,
``-F`` on the first) and friction couple ``M`` (``+M`` on the second, ``-M`` on the first: the
offset force line of Buckingham's model, ``M = -delta F`` when the first gear of an external mesh
drives, Mantriota & Pennestri 2003 eq. 9a); per moving member its bearing reaction ``R`` (force
of the holder on it); per input port its torque.  Equations: torque and force balance of every
moving member; per mesh the carrier-frame rule of :mod:`oracle.balance` (the mesh's power on gear
X in the frame of the mesh's carrier c is ``tau_X (w_X - w_c)``; the driver's is negative and
``P_driven = -eta P_driver``).  Bearing of X on its holder H, ``dw = w_X - w_H``: couple on X
``C = -rho |R| sign(dw) - b dw - D sign(dw)`` (friction circle rho, viscous b, drag D), ``-C`` on
H (lost in the housing); none when ``dw = 0``.

The signs (driver of each lossy mesh, sign of each slipping Coulomb reaction) make the problem
piecewise linear: they are found by fixed-point iteration from the lossless solution, the final
assignment is verified against its own solution, and all assignments are enumerated:
:class:`AmbiguousSolution` when several consistent ones give different solutions,
:class:`NoConsistentSolution` when none is consistent (a jammed, self-locking train).

Powers: ``P = T w`` at a port is the power into the train (``T`` applied by the outside); losses
are dissipated powers (mesh ``M (w_a - w_b)``: the tooth forces do no net work; bearing
``rho |R| |dw|``, ``b dw^2``, ``D |dw|``), so ``P_in + P_out = sum of losses``.  Efficiency
(eq. 6 of the paper): ``eta = -P_out / P_in``, ``P_in`` summed over the declared input ports.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, NamedTuple

from .balance import DescriptionError, Gear, Member, Mesh, MobilityProblem, OracleError

Number = int | Fraction | float | str


class NoConsistentSolution(OracleError):
    """No assignment of mesh drivers and bearing-reaction signs agrees with its own solution."""


class AmbiguousSolution(OracleError):
    """Several consistent sign assignments give different solutions (statically indeterminate)."""


def q(x: Number) -> Fraction:
    """An exact rational (a float is read by its shortest decimal repr: 0.1 -> 1/10)."""
    return Fraction(repr(x)) if isinstance(x, float) else Fraction(x)


def sign(x: Fraction) -> int:
    return (x > 0) - (x < 0)


# -- description -------------------------------------------------------------------------


@dataclass(frozen=True)
class Bearing:
    """The bearing of ``member`` on its holder: Coulomb friction-circle radius ``rho`` (length,
    same unit as the radii), viscous coefficient ``viscous`` (torque per unit speed) and
    constant drag torque ``drag``."""

    member: str
    rho: Fraction = Fraction(0)
    viscous: Fraction = Fraction(0)
    drag: Fraction = Fraction(0)


@dataclass(frozen=True)
class LossyTrain:
    """A train: members with axes ``(0, y)``, gears, meshes, the fixed member (housing), ports
    (port name -> member; the other side of every port is the housing) and bearings (a member
    without one has a frictionless bearing)."""

    name: str
    members: tuple[Member, ...]
    gears: tuple[Gear, ...]
    meshes: tuple[Mesh, ...]
    fixed: str
    ports: Mapping[str, str]
    bearings: tuple[Bearing, ...] = ()


@dataclass(frozen=True)
class LossyResult:
    """The solved train.  ``torques``/``powers`` per port: the torque the outside applies and
    ``T w`` (power into the train); ``forces``/``couples`` per mesh: on its second gear;
    ``reactions`` per moving member: the bearing force on the member (along x); ``losses``:
    ``"mesh <name>"``, ``"coulomb <member>"``, ``"viscous <member>"``, ``"drag <member>"`` ->
    dissipated power (>= 0).  ``efficiency = -power_out / power_in``."""

    inputs: tuple[str, ...]
    output: str
    speeds: dict[str, Fraction]
    torques: dict[str, Fraction]
    powers: dict[str, Fraction]
    forces: dict[str, Fraction]
    couples: dict[str, Fraction]
    reactions: dict[str, Fraction]
    losses: dict[str, Fraction]
    first_drives: dict[str, bool]
    power_in: Fraction
    power_out: Fraction
    efficiency: Fraction
    iterations: int

    @property
    def total_loss(self) -> Fraction:
        return sum(self.losses.values(), Fraction(0))


# -- exact linear algebra ----------------------------------------------------------------


def solve_linear(rows: Sequence[Sequence[Fraction]], rhs: Sequence[Fraction], n: int) -> list[Fraction] | None:
    """The unique solution of ``rows x = rhs`` (Gauss-Jordan), or None (singular/inconsistent)."""
    a = [[*row, b] for row, b in zip(rows, rhs, strict=True)]
    for col in range(n):
        piv = next((i for i in range(col, len(a)) if a[i][col] != 0), None)
        if piv is None:
            return None
        a[col], a[piv] = a[piv], a[col]
        p = a[col][col]
        a[col] = [v / p for v in a[col]]
        for i in range(len(a)):
            if i != col and a[i][col] != 0:
                f = a[i][col]
                a[i] = [x - f * y for x, y in zip(a[i], a[col], strict=True)]
    if any(row[-1] != 0 for row in a[n:]):
        return None
    return [a[i][-1] for i in range(n)]


# -- the model ---------------------------------------------------------------------------


@dataclass(frozen=True)
class _Geo:
    mesh: Mesh
    a: str  # member of the first gear
    b: str  # member of the second gear
    carrier: str | None  # None: the housing
    y_pitch: Fraction
    arm_a: Fraction  # torque of a unit +x force at the pitch point about a's axis
    arm_b: Fraction


class LossyBalance:
    """The oracle for one train; :meth:`solve` for one operating point."""

    def __init__(self, train: LossyTrain):
        self.train = train
        self.members = {m.name: m for m in train.members}
        if train.fixed not in self.members:
            raise DescriptionError(f"fixed member {train.fixed!r} is not a member")
        self.moving = [m.name for m in train.members if m.name != train.fixed]
        for m in train.members:
            if m.axis[0] != 0:
                raise DescriptionError(f"member {m.name}: its axis must lie on the y-axis (x = 0)")
            if self.holder(m.name) is not None:
                c = self.members.get(m.carrier or "")
                if c is None or c.carrier not in (None, train.fixed) or c.axis[1] != 0:
                    raise DescriptionError(f"planet {m.name}: its carrier must turn about the main axis")
        self.bearings = {b.member: Bearing(b.member, q(b.rho), q(b.viscous), q(b.drag)) for b in train.bearings}
        if not {*self.bearings, *train.ports.values()} <= set(self.moving):
            raise DescriptionError("bearings and ports must be on moving members")
        self.gears = {g.name: Gear(g.name, g.member, q(g.radius), g.internal) for g in train.gears}
        self.geometry = [self._geometry(Mesh(m.name, m.gears, q(m.eta))) for m in train.meshes]

    def holder(self, name: str) -> str | None:
        """The moving member (a carrier) holding ``name``'s bearing; None: the housing."""
        c = self.members[name].carrier
        return None if name == self.train.fixed or c in (None, self.train.fixed) else c

    def y(self, name: str) -> Fraction:
        return q(self.members[name].axis[1])

    def _geometry(self, mesh: Mesh) -> _Geo:
        try:
            g, h = (self.gears[n] for n in mesh.gears)
        except KeyError as exc:
            raise DescriptionError(f"mesh {mesh.name}: unknown gear {exc}") from None
        if g.internal and h.internal:
            raise DescriptionError(f"mesh {mesh.name}: two internal gears")
        if min(g.radius, h.radius) <= 0 or g.member == h.member:
            raise DescriptionError(f"mesh {mesh.name}: radii must be positive, members different")
        ya, yb = self.y(g.member), self.y(h.member)
        d = yb - ya
        expected = abs(g.radius - h.radius) if (g.internal or h.internal) else g.radius + h.radius
        if abs(d) != expected or d == 0:
            raise DescriptionError(f"mesh {mesh.name}: centre distance {abs(d)}, the radii need {expected}")
        u = sign(d)
        y_pitch = yb - h.radius * u if h.internal else ya + g.radius * u
        fa, fb = self.holder(g.member), self.holder(h.member)
        if fa == fb:
            carrier = fa
        elif fa is None and ya == 0:
            carrier = fb
        elif fb is None and yb == 0:
            carrier = fa
        else:
            raise DescriptionError(f"mesh {mesh.name}: no member holds both gear axes")
        return _Geo(mesh, g.member, h.member, carrier, y_pitch, -(y_pitch - ya), -(y_pitch - yb))

    # kinematics -------------------------------------------------------------------------
    def speeds(self, inputs: Mapping[str, Fraction]) -> dict[str, Fraction]:
        """Member speeds (housing frame) from the input port speeds."""
        n, idx = len(self.moving), {name: i for i, name in enumerate(self.moving)}
        if len(self.geometry) + len(inputs) != n:
            raise MobilityProblem(
                f"{self.train.name}: {n} moving members and {len(self.geometry)} meshes "
                f"need {n - len(self.geometry)} input speeds, got {len(inputs)}"
            )
        rows, rhs = [], []
        for geo in self.geometry:
            row = [Fraction(0)] * n
            for member, s in ((geo.a, 1), (geo.b, -1)):  # v_a - v_b = 0 at the pitch point
                if member in idx:
                    row[idx[member]] += -s * (geo.y_pitch - self.y(member))
                h = self.holder(member)
                if h is not None:
                    row[idx[h]] += -s * self.y(member)
            rows.append(row)
            rhs.append(Fraction(0))
        for port, w in inputs.items():
            rows.append([Fraction(i == idx[self.train.ports[port]]) for i in range(n)])
            rhs.append(w)
        x = solve_linear(rows, rhs, n)
        if x is None:
            raise MobilityProblem(f"{self.train.name}: the input speeds do not determine the motion")
        return {**{name: x[i] for name, i in idx.items()}, self.train.fixed: Fraction(0)}

    def rel(self, w: Mapping[str, Fraction], name: str) -> Fraction:
        """Speed of ``name`` relative to its holder."""
        h = self.holder(name)
        return w[name] - (w[h] if h is not None else 0)

    def carrier_frame(self, w: Mapping[str, Fraction], geo: _Geo) -> tuple[Fraction, Fraction]:
        wc = w[geo.carrier] if geo.carrier is not None else Fraction(0)
        return w[geo.a] - wc, w[geo.b] - wc

    # statics ----------------------------------------------------------------------------
    def _statics(
        self,
        w: Mapping[str, Fraction],
        inputs: Sequence[str],
        output: str,
        t_out: Fraction,
        first: Mapping[str, bool] | None,
        sigma: Mapping[str, int],
    ) -> list[Fraction] | None:
        """Solve for x = [F_k, M_k, R_m, T_i].  ``first`` None: lossless."""
        k, n = len(self.geometry), len(self.moving)
        ncols = 2 * k + n + len(inputs)
        col_r = {name: 2 * k + i for i, name in enumerate(self.moving)}
        torque = {name: [Fraction(0)] * ncols for name in self.moving}
        force = {name: [Fraction(0)] * ncols for name in self.moving}
        t_rhs = dict.fromkeys(self.moving, Fraction(0))
        for j, geo in enumerate(self.geometry):  # +F, +M on the second gear; -F, -M on the first
            for member, s, arm in ((geo.b, 1, geo.arm_b), (geo.a, -1, geo.arm_a)):
                if member in torque:
                    torque[member][j] += s * arm
                    torque[member][k + j] += s
                    force[member][j] += s
        for x in self.moving:
            force[x][col_r[x]] += 1
            h = self.holder(x)
            if h is not None:  # the planet's bearing: -R at the planet axis on the carrier
                force[h][col_r[x]] -= 1
                torque[h][col_r[x]] += self.y(x) - self.y(h)
            if first is None or x not in self.bearings or self.rel(w, x) == 0:
                continue
            b, dw = self.bearings[x], self.rel(w, x)
            coulomb = -sign(dw) * b.rho * sigma.get(x, 1)  # C = coulomb * R + const
            const = -b.viscous * dw - b.drag * sign(dw)
            torque[x][col_r[x]] += coulomb
            t_rhs[x] -= const
            if h is not None:
                torque[h][col_r[x]] -= coulomb
                t_rhs[h] += const
        for i, port in enumerate(inputs):
            torque[self.train.ports[port]][2 * k + n + i] += 1
        t_rhs[self.train.ports[output]] -= t_out
        rows = [torque[x] for x in self.moving] + [force[x] for x in self.moving]
        rhs = [t_rhs[x] for x in self.moving] + [Fraction(0)] * n
        for j, geo in enumerate(self.geometry):
            row = [Fraction(0)] * ncols
            da, db = self.carrier_frame(w, geo)
            if first is None or geo.mesh.eta == 1 or (da == 0 and db == 0):
                row[k + j] = Fraction(1)  # no mesh loss: M = 0
            else:  # carrier-frame powers P_a = (-arm_a F - M) da, P_b = (arm_b F + M) db
                pa, pb = (-geo.arm_a * da, -da), (geo.arm_b * db, db)
                drv, drn = (pa, pb) if first[geo.mesh.name] else (pb, pa)
                row[j], row[k + j] = drn[0] + geo.mesh.eta * drv[0], drn[1] + geo.mesh.eta * drv[1]
            rows.append(row)
            rhs.append(Fraction(0))
        return solve_linear(rows, rhs, ncols)

    def _powers(self, w: Mapping[str, Fraction], x: Sequence[Fraction]) -> dict[str, tuple[Fraction, Fraction]]:
        """Carrier-frame power of each mesh on its first and second gear."""
        k = len(self.geometry)
        return {
            geo.mesh.name: ((-geo.arm_a * x[j] - x[k + j]) * da, (geo.arm_b * x[j] + x[k + j]) * db)
            for j, geo in enumerate(self.geometry)
            for da, db in [self.carrier_frame(w, geo)]
        }

    def _signs(
        self,
        w: Mapping[str, Fraction],
        x: Sequence[Fraction],
        first: Mapping[str, bool] | None,
        sigma: Mapping[str, int] | None,
    ) -> tuple[dict[str, bool], dict[str, int]]:
        """The drivers and reaction signs that the solution ``x`` implies (ties: keep the old)."""
        new_first = {}
        for name, (pa, pb) in self._powers(w, x).items():
            flow = sign(pb) or -sign(pa)  # > 0: the first gear drives
            new_first[name] = flow > 0 if flow else (first or {}).get(name, True)
        k = len(self.geometry)
        new_sigma = {m: sign(x[2 * k + i]) or (sigma or {}).get(m, 1) for i, m in enumerate(self.moving)}
        return new_first, new_sigma

    def _consistent(
        self, w: Mapping[str, Fraction], x: Sequence[Fraction], first: Mapping[str, bool], sigma: Mapping[str, int]
    ) -> bool:
        """Only the signs that matter: lossy meshes that turn in their carrier's frame, Coulomb
        bearings that slip."""
        meshes, bearings = self._sign_variables(w)
        powers, k = self._powers(w, x), len(self.geometry)
        r = {m: x[2 * k + i] for i, m in enumerate(self.moving)}
        return all((powers[n][0] <= 0) if first[n] else (powers[n][1] <= 0) for n in meshes) and all(
            sigma.get(m, 1) * r[m] >= 0 for m in bearings
        )

    def _sign_variables(self, w: Mapping[str, Fraction]) -> tuple[list[str], list[str]]:
        meshes = [g.mesh.name for g in self.geometry if g.mesh.eta != 1 and any(self.carrier_frame(w, g))]
        bearings = [m for m, b in self.bearings.items() if b.rho != 0 and self.rel(w, m) != 0]
        return meshes, bearings

    def solve(
        self, inputs: Mapping[str, Number], output: str, load: Number, lossless: bool = False, max_iterations: int = 30
    ) -> LossyResult:
        """Input port speeds ``inputs`` (port -> speed), output port ``output`` with the external
        torque ``load`` (a resisting load has ``load * w_out < 0``)."""
        win = {p: q(v) for p, v in inputs.items()}
        ports = [*win, output]
        if not set(ports) <= set(self.train.ports):
            raise DescriptionError(f"unknown port(s) {sorted(set(ports) - set(self.train.ports))}")
        if len(set(ports)) != len(ports) or len({self.train.ports[p] for p in ports}) != len(ports):
            raise DescriptionError("the input and output ports must be distinct members")
        t_out, names = q(load), list(win)
        w = self.speeds(win)
        x = self._statics(w, names, output, t_out, None, {})
        if x is None:
            raise MobilityProblem(f"{self.train.name}: the lossless statics have no unique solution")
        first, sigma = self._signs(w, x, None, None)
        if lossless:
            return self._result(w, names, output, t_out, x, first, sigma, 0, lossless=True)
        solution, iterations, seen = None, 0, []
        while solution is None and iterations < max_iterations and (first, sigma) not in seen:
            iterations += 1  # fixed point: signs -> solution -> signs
            seen.append((first, sigma))
            x = self._statics(w, names, output, t_out, first, sigma)
            if x is None:
                break
            if self._consistent(w, x, first, sigma):
                solution = (x, first, sigma)
            else:
                first, sigma = self._signs(w, x, first, sigma)
        found = self._enumerate(w, names, output, t_out)
        if not found:
            raise NoConsistentSolution(
                f"{self.train.name}: no consistent assignment of mesh drivers and "
                f"bearing-reaction signs (a jammed, self-locking train)"
            )
        if len(found) > 1:
            values = sorted(float(self._result(w, names, output, t_out, *s, -1).efficiency) for s in found)
            raise AmbiguousSolution(
                f"{self.train.name}: {len(found)} consistent sign assignments give "
                f"different solutions (efficiencies {values})"
            )
        if solution is None:  # the iteration cycled: take the unique consistent assignment
            solution, iterations = found[0], -1
        elif found[0][0] != solution[0]:
            raise OracleError(f"{self.train.name}: iteration and enumeration disagree (internal error)")
        return self._result(w, names, output, t_out, *solution, iterations)

    def _enumerate(
        self, w: Mapping[str, Fraction], names: Sequence[str], output: str, t_out: Fraction
    ) -> list[tuple[list[Fraction], dict[str, bool], dict[str, int]]]:
        """Every consistent sign assignment (one per distinct solution)."""
        meshes, bearings = self._sign_variables(w)
        base_first = {g.mesh.name: True for g in self.geometry}
        found: dict[tuple[Fraction, ...], tuple[list[Fraction], dict[str, bool], dict[str, int]]] = {}
        for choice in itertools.product((True, False), repeat=len(meshes) + len(bearings)):
            first = {**base_first, **dict(zip(meshes, choice, strict=False))}
            sigma = {m: 1 if c else -1 for m, c in zip(bearings, choice[len(meshes) :], strict=True)}
            x = self._statics(w, names, output, t_out, first, sigma)
            if x is not None and self._consistent(w, x, first, sigma):
                found.setdefault(tuple(x), (x, first, sigma))
        return list(found.values())

    def _result(
        self,
        w: Mapping[str, Fraction],
        names: Sequence[str],
        output: str,
        t_out: Fraction,
        x: Sequence[Fraction],
        first: Mapping[str, bool],
        sigma: Mapping[str, int],
        iterations: int,
        lossless: bool = False,
    ) -> LossyResult:
        k, n = len(self.geometry), len(self.moving)
        torques = {p: x[2 * k + n + i] for i, p in enumerate(names)} | {output: t_out}
        powers = {p: t * w[self.train.ports[p]] for p, t in torques.items()}
        reactions = {m: x[2 * k + i] for i, m in enumerate(self.moving)}
        losses: dict[str, Fraction] = {}
        for j, geo in enumerate(self.geometry):
            losses[f"mesh {geo.mesh.name}"] = x[k + j] * (w[geo.a] - w[geo.b])
        if not lossless:
            for m, b in self.bearings.items():
                dw = self.rel(w, m)
                losses[f"coulomb {m}"] = b.rho * abs(reactions[m]) * abs(dw)
                losses[f"viscous {m}"] = b.viscous * dw * dw
                losses[f"drag {m}"] = b.drag * abs(dw)
        p_in, p_out = sum((powers[p] for p in names), Fraction(0)), powers[output]
        if p_in == 0:
            raise MobilityProblem(f"{self.train.name}: no power enters through the inputs")
        return LossyResult(
            tuple(names),
            output,
            dict(w),
            torques,
            powers,
            {g.mesh.name: x[j] for j, g in enumerate(self.geometry)},
            {g.mesh.name: x[k + j] for j, g in enumerate(self.geometry)},
            reactions,
            losses,
            dict(first),
            p_in,
            p_out,
            -p_out / p_in,
            iterations,
        )


def solve(
    train: LossyTrain, inputs: Mapping[str, Number], output: str, load: Number, lossless: bool = False
) -> LossyResult:
    """Solve ``train`` with input port speeds ``inputs`` and the external torque ``load`` at ``output``."""
    return LossyBalance(train).solve(inputs, output, load, lossless)


# -- the Andantex SR20 (Mantriota & Pennestri 2003, Fig. 7) -------------------------------

#: Pitch radii in metres from the paper's diametral pitches (425 and 406.25 per metre):
#: r = z / (2 P); both meshes have the centre distance 0.08 m (module ratio 65 : 68).
SR20_RADII = {"1": Fraction(36, 850), "2": Fraction(32, 850), "3": Fraction(40, 1625), "4": Fraction(90, 1625)}
SR20_MEMBERS = ("d1", "c", "p", "o")


def _per_member(value: Number | Mapping[str, Number]) -> dict[str, Fraction]:
    if isinstance(value, Mapping):
        unknown = set(value) - set(SR20_MEMBERS)
        if unknown:
            raise DescriptionError(f"SR20 has no member {sorted(unknown)} (members: {SR20_MEMBERS})")
        return {m: q(value.get(m, 0)) for m in SR20_MEMBERS}
    return dict.fromkeys(SR20_MEMBERS, q(value))


def sr20(
    eta_1: Number = 1,
    eta_2: Number = 1,
    drag: Number | Mapping[str, Number] = 0,
    viscous: Number | Mapping[str, Number] = 0,
    rho: Number | Mapping[str, Number] = 0,
) -> LossyTrain:
    """The SR20 differential: sun gear 1 (z 36) on shaft d1 (port A), compound planet p = gears
    2/3 (z 32, 20) on the carrier c (port K), output gear 4 (z 45) on o (port O); meshes M1 = (1, 2)
    with ``eta_1`` and M2 = (4, 3) with ``eta_2``.  ``drag``, ``viscous``, ``rho``: one value for
    every bearing (d1, c, o on the housing; p on the carrier) or a mapping member -> value.
    Radii in metres (:data:`SR20_RADII`), so ``rho`` is in metres."""
    e = SR20_RADII["1"] + SR20_RADII["2"]
    members = (Member("0"), Member("d1"), Member("c"), Member("p", "c", (Fraction(0), e)), Member("o"))
    gears = tuple(Gear(n, m, SR20_RADII[n]) for n, m in (("1", "d1"), ("2", "p"), ("3", "p"), ("4", "o")))
    meshes = (Mesh("M1", ("1", "2"), q(eta_1)), Mesh("M2", ("4", "3"), q(eta_2)))
    d, b, r = _per_member(drag), _per_member(viscous), _per_member(rho)
    bearings = tuple(Bearing(m, r[m], b[m], d[m]) for m in SR20_MEMBERS)
    return LossyTrain("Andantex SR20", members, gears, meshes, "0", {"A": "d1", "K": "c", "O": "o"}, bearings)


class SR20Point(NamedTuple):
    """The SR20 model at one operating point: input torques, efficiency and the full result."""

    T_A: Fraction
    T_K: Fraction
    eta: Fraction
    result: LossyResult


def sr20_at_row(row: Mapping[str, Number], train: LossyTrain | None = None, **losses: Any) -> SR20Point:
    """Evaluate the SR20 model at a CSV row of catalog/data/sr20_table*.csv: the speeds ``w_A``,
    ``w_K`` (any unit, e.g. rpm; ``viscous`` is then per that unit) and the output torque ``T_O``
    are prescribed, ``T_A``, ``T_K`` and ``eta`` (eq. 6) computed.  ``train`` or the keyword
    arguments of :func:`sr20`."""
    train = train if train is not None else sr20(**losses)
    result = solve(train, {"A": row["w_A"], "K": row["w_K"]}, "O", row["T_O"])
    return SR20Point(result.torques["A"], result.torques["K"], result.efficiency, result)
