"""Independent numeric oracle for the friction losses of the 3-UPU of Laus (2011, thesis sec. 4.3).

Nothing comes from ``davies_sym``: the equations are written here from free-body diagrams, in
numpy, and solved with numpy's dense LU.

Geometry (eqs. 124-126), limb ``i`` at ``alpha_i = 0, 2pi/3, -2pi/3``; ``M`` the platform centre:
``e1 = r_b (cos a, sin a, 0)`` is the base joint centre A, ``e2 = M + (r_t - r_b)(cos a, sin a, 0)``
points from A to the platform joint centre ``D = e1 + e2``; ``ê1 = e1/|e1|``, ``ê2 = e2/|e2|``,
``ê3 = unit(ê1 x ê2)``, ``ê4 = ê2 x ê3``, ``ê5 = ê1 x ê3`` (``ê1, ê3, ê5`` orthonormal);
``B = e1 + l_B ê2`` (mouth of the lower tube, link 1), ``C = e1 + e2 - l_C ê2`` (foot of the upper
rod, link 2).  Limb 1 has the joints A, B, C, D; limb 2 E, F, G, H; limb 3 I, J, K, L.

Kinematics: the platform translates with ``Ṁ``; links 1 and 2 turn together with
``omega = p_A1 ê1 + p_A2 ê3`` (what the universal joint A allows), fixed by
``omega x e2 = Ṁ - (ê2·Ṁ) ê2``; since ``ê1 x ê2 = s ê3`` (``s = |ê1 x ê2|``) and ``ê3 x ê2 = -ê4``:
``p_A1 = ê3·Ṁ / (s |e2|)``, ``p_A2 = -ê4·Ṁ / |e2|``.  The extension rate is ``q = ê2·Ṁ``.  At D the
platform turns relative to link 2 with ``-omega``: ``p_D1 = -p_A1``, ``p_D2 = -p_A2``.  All
relative point velocities at A and D vanish; at B and C link 2 slides along ``ê2`` at ``q``
relative to link 1.

Actions (Laus Table 10).  Every joint action is the action of the first body named on the second:
- A, base -> link 1, at A: torque ``P_A ê5``; forces ``Q_A1 ê1 + Q_A2 ê3 + Q_A3 ê5``; friction
  torques ``P_AF1 ê1 + P_AF2 ê3``, signs from ``p_A1, p_A2`` (link 1 relative to the base);
- B, link 1 -> link 2, at B: torque ``P_B ê2``; forces ``Q_B1 ê3 + Q_B2 ê4``; friction ``Q_BF ê2``;
- C, link 1 -> link 2, at C: forces ``Q_C1 ê3 + Q_C2 ê4``; actuation ``Q_CA ê2`` (positive pushes
  link 2 out of link 1, i.e. extends the limb); friction ``Q_CF ê2``;
- D, link 2 -> platform, at D: as A with ``P_D, Q_D1..3, P_DF1, P_DF2``, signs from ``p_D1, p_D2``
  (the platform relative to link 2);
- payload: ``W = (0, 0, -10 000) N`` on the platform at M.
The reaction (the negative) acts on the first body (none on the fixed base).

Friction (Coulomb, worn surfaces; eqs. 127-129), with ``mu`` everywhere and the pin radius ``r``:
``P_AF1 = -mu r sign(p_A1) (|Q_A1| + 4/pi |Q_A2| + 4/pi |Q_A3|)``,
``P_AF2 = -mu r sign(p_A2) (4/pi |Q_A1| + |Q_A2| + 4/pi |Q_A3|)`` (the same for D with ``p_D1,
p_D2``), ``Q_BF = -mu sign(q) (|Q_B1| + |Q_B2|)``, ``Q_CF = -mu sign(q) (|Q_C1| + |Q_C2|)``.  Every
friction action opposes the relative motion of the body it acts on, so each friction power
(action times the relative rate of that body) is ``<= 0``: ``P_AF1 p_A1 + P_AF2 p_A2`` at A,
``Q_BF q`` at B, ``Q_CF q`` at C, ``P_DF1 p_D1 + P_DF2 p_D2`` at D.  The transmitted torques
``P_A``, ``P_B``, ``P_D`` do not enter the friction laws (as in eqs. 127-129).

Statics (quasi-static): force and moment balance (about the origin) of the 7 moving bodies, 42
equations ``K x + mu G |x| = b`` in the 42 unknowns ``x`` (per limb ``P_A, Q_A1..3, P_B, Q_B1, Q_B2,
Q_C1, Q_C2, Q_CA, P_D, Q_D1..3``); ``mu G |x|`` holds the friction actions, ``b`` the payload.  With
the signs ``s`` of the unknowns frozen the system is linear, ``(K + mu G diag(s)) x = b``: from the
frictionless solution the signs are updated until they agree with the solution (a semismooth
Newton iteration of the piecewise-linear system); if that cycles, ``mu`` is raised from 0 in
steps, each from the previous signs (homotopy continuation, as Laus did, sec. 4.3.3.4).

Powers: actuator ``Q_CA q``, payload ``W·Ṁ``, friction as above; their sum vanishes (power
balance, checked at every solve).  Energies: trapezoid rule over the samples.

A configuration where ``K`` is singular raises :class:`UpuSingularityError`: e.g. ``M`` on the
z-axis, where all three ``ê5`` are vertical and the limbs' constraint couples cannot hold the
platform's tilt (the constraint singularity of the 3-UPU); the tasks stay far from it.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Vector = NDArray[np.float64]

#: Dimensions of sec. 4.3.4.1 (m) and the payload of sec. 4.3.4.2 (N).
R_BASE = 1.0
R_TOP = 0.5
L_B = 0.6
L_C = 0.6
PIN_RADIUS = 0.015
MU = 0.11
PAYLOAD = np.array([0.0, 0.0, -10_000.0])
ALPHAS = (0.0, 2.0 * math.pi / 3.0, -2.0 * math.pi / 3.0)
#: Joint names per limb: (base universal, square annulus, round annulus, platform universal).
JOINTS = (("A", "B", "C", "D"), ("E", "F", "G", "H"), ("I", "J", "K", "L"))
#: Unknowns per limb, in this order (offset 14 i for limb i).
UNKNOWNS = ("P_A", "Q_A1", "Q_A2", "Q_A3", "P_B", "Q_B1", "Q_B2", "Q_C1", "Q_C2", "Q_CA", "P_D", "Q_D1", "Q_D2", "Q_D3")
N_LIMB = len(UNKNOWNS)
N = 3 * N_LIMB
CYL = 4.0 / math.pi  # worn cylindrical contact, half-circle (Laus Table 16)
RATE_TOL = 1e-12  # relative rates below this (rad/s, m/s) are taken as zero: no friction
BALANCE_TOL = 1e-6
MAX_SIGN_ITERATIONS = 60
MAX_CONDITION = 1e8  # of K; the tasks stay below 2e3, the constraint singularity (M on the z-axis) is ~1e18


class UpuConvergenceError(RuntimeError):
    """The sign iteration and the continuation in mu found no consistent solution."""


class UpuSingularityError(ValueError):
    """The frictionless statics is singular (e.g. M on the z-axis: every ê5 is vertical, a constraint singularity)."""


class PowerBalanceError(RuntimeError):
    """Actuator + payload + friction powers do not add up to zero."""


@dataclass(frozen=True)
class UpuStep:
    """One time sample of a task."""

    time: float
    actuator_force: tuple[float, float, float]  # Q_CA, Q_GA, Q_KA
    actuator_speed: tuple[float, float, float]  # q of each limb
    actuator_power: tuple[float, float, float]
    payload_power: float
    friction_power: dict[str, float]  # per joint name A..L, each <= 0


@dataclass(frozen=True)
class UpuTask:
    """A whole task: its samples and the energies integrated over them."""

    steps: tuple[UpuStep, ...]
    supplied_energy: float  # integral of the actuator powers (J)
    payload_energy: float  # integral of -payload_power (J)
    friction_energy: dict[str, float]  # per joint, integral of -friction power (J, >= 0)
    efficiency: float  # payload_energy / supplied_energy


@dataclass(frozen=True)
class _Limb:
    """Geometry (eqs. 124-126) and kinematics of one limb."""

    e: tuple[Vector, Vector, Vector, Vector, Vector]  # unit vectors ê1..ê5
    a: Vector
    b: Vector
    c: Vector
    d: Vector
    p_a: tuple[float, float]  # link 1 relative to the base, on ê1, ê3
    p_d: tuple[float, float]  # platform relative to link 2, on ê1, ê3
    q: float  # extension rate, link 2 relative to link 1 along ê2


def _unit(v: Vector) -> Vector:
    """``v / |v|``; refuses a zero vector."""
    n = float(np.linalg.norm(v))
    if n < 1e-12:
        raise ValueError("degenerate geometry: zero vector")
    return v / n


def _limb(alpha: float, m: Vector, m_dot: Vector) -> _Limb:
    """Eqs. 124-126 and the limb kinematics (module docstring) for the limb at ``alpha``."""
    radial = np.array([math.cos(alpha), math.sin(alpha), 0.0])
    e1 = R_BASE * radial
    e2 = m + (R_TOP - R_BASE) * radial
    u1, u2 = _unit(e1), _unit(e2)
    cross12 = _cross(u1, u2)
    s = float(np.linalg.norm(cross12))
    if s < 1e-9:
        raise ValueError("singular limb: its axis is parallel to the first axis of the universal joints")
    u3 = cross12 / s
    u4 = _cross(u2, u3)
    u5 = _cross(u1, u3)
    length = float(np.linalg.norm(e2))
    p1 = float(u3 @ m_dot) / (s * length)
    p2 = -float(u4 @ m_dot) / length
    return _Limb(
        e=(u1, u2, u3, u4, u5),
        a=e1,
        b=e1 + L_B * u2,
        c=e1 + e2 - L_C * u2,
        d=e1 + e2,
        p_a=(p1, p2),
        p_d=(-p1, -p2),
        q=float(u2 @ m_dot),
    )


def _cross(u: Vector, v: Vector) -> Vector:
    """``u x v`` of two 3-vectors (np.cross is slow on single vectors)."""
    return np.array([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]])


def _force(direction: Vector, point: Vector) -> Vector:
    """Wrench ``(f, X x f)`` (moment about the origin) of a unit force along ``direction`` at ``point``."""
    return np.concatenate([direction, _cross(point, direction)])


def _torque(direction: Vector) -> Vector:
    """Wrench ``(0, t)`` of a unit couple along ``direction``."""
    return np.concatenate([np.zeros(3), direction])


def _sign(rate: float) -> float:
    """Sign of a relative rate; zero below ``RATE_TOL`` (no friction)."""
    return 0.0 if abs(rate) < RATE_TOL else math.copysign(1.0, rate)


@dataclass(frozen=True)
class _System:
    """``K x + mu G |x| = b`` with ``G = sum_f outer(w_f, g_f)``; friction magnitudes ``mu g_f · |x|``."""

    k: NDArray[np.float64]
    b: Vector
    friction_wrench: NDArray[np.float64]  # (42, 18): columns w_f (placed on both bodies)
    friction_coeff: NDArray[np.float64]  # (18, 42): rows g_f, per unit mu
    g: NDArray[np.float64]  # (42, 42): G
    friction_rate: Vector  # (18,): rate each friction action works on
    friction_joint: tuple[str, ...]  # (18,): joint name of each friction action
    limbs: tuple[_Limb, ...]


def _rows(body: str, limb: int) -> slice | None:
    """Equation rows (6) of a body: ``link1``/``link2`` of a limb, ``platform``, ``base`` (none)."""
    if body == "base":
        return None
    if body == "platform":
        return slice(36, 42)
    return slice(12 * limb + (0 if body == "link1" else 6), 12 * limb + (6 if body == "link1" else 12))


def _place(column: Vector, wrench: Vector, source: str, target: str, limb: int) -> None:
    """Add ``wrench`` (action of ``source`` on ``target``) to ``target``'s rows, its reaction to ``source``'s."""
    rows_t, rows_s = _rows(target, limb), _rows(source, limb)
    if rows_t is not None:
        column[rows_t] += wrench
    if rows_s is not None:
        column[rows_s] -= wrench


def _assemble(position: Sequence[float], velocity: Sequence[float]) -> _System:
    """Balance of the 7 bodies (module docstring): ``K``, ``b`` and the friction terms per unit mu."""
    m = np.asarray(position, dtype=float)
    m_dot = np.asarray(velocity, dtype=float)
    k = np.zeros((N, N))
    f_wrench: list[Vector] = []
    f_coeff: list[Vector] = []
    f_rate: list[float] = []
    f_joint: list[str] = []
    limbs = tuple(_limb(alpha, m, m_dot) for alpha in ALPHAS)
    for i, lb in enumerate(limbs):
        u1, u2, u3, u4, u5 = lb.e
        o = N_LIMB * i
        # (unknown index, wrench, source body, target body)
        actions = [
            (0, _torque(u5), "base", "link1"),
            (1, _force(u1, lb.a), "base", "link1"),
            (2, _force(u3, lb.a), "base", "link1"),
            (3, _force(u5, lb.a), "base", "link1"),
            (4, _torque(u2), "link1", "link2"),
            (5, _force(u3, lb.b), "link1", "link2"),
            (6, _force(u4, lb.b), "link1", "link2"),
            (7, _force(u3, lb.c), "link1", "link2"),
            (8, _force(u4, lb.c), "link1", "link2"),
            (9, _force(u2, lb.c), "link1", "link2"),
            (10, _torque(u5), "link2", "platform"),
            (11, _force(u1, lb.d), "link2", "platform"),
            (12, _force(u3, lb.d), "link2", "platform"),
            (13, _force(u5, lb.d), "link2", "platform"),
        ]
        for j, wrench, source, target in actions:
            _place(k[:, o + j], wrench, source, target, i)
        name_a, name_b, name_c, name_d = JOINTS[i]
        r, rc = PIN_RADIUS, CYL * PIN_RADIUS  # flat face, worn half-cylinder
        # (joint, wrench, source, target, rate, {unknown: weight}) -- eqs. 127-129
        frictions = [
            (name_a, _torque(u1), "base", "link1", lb.p_a[0], {1: r, 2: rc, 3: rc}),
            (name_a, _torque(u3), "base", "link1", lb.p_a[1], {1: rc, 2: r, 3: rc}),
            (name_b, _force(u2, lb.b), "link1", "link2", lb.q, {5: 1.0, 6: 1.0}),
            (name_c, _force(u2, lb.c), "link1", "link2", lb.q, {7: 1.0, 8: 1.0}),
            (name_d, _torque(u1), "link2", "platform", lb.p_d[0], {11: r, 12: rc, 13: rc}),
            (name_d, _torque(u3), "link2", "platform", lb.p_d[1], {11: rc, 12: r, 13: rc}),
        ]
        for joint, wrench, source, target, rate, weights in frictions:
            column = np.zeros(N)
            _place(column, wrench, source, target, i)
            coeff = np.zeros(N)
            for j, w in weights.items():
                coeff[o + j] = -_sign(rate) * w
            f_wrench.append(column)
            f_coeff.append(coeff)
            f_rate.append(rate)
            f_joint.append(joint)
    b = np.zeros(N)
    b[36:42] = -_force(PAYLOAD, m)
    wrenches, coeffs = np.array(f_wrench).T, np.array(f_coeff)
    return _System(
        k=k,
        b=b,
        friction_wrench=wrenches,
        friction_coeff=coeffs,
        g=wrenches @ coeffs,
        friction_rate=np.array(f_rate),
        friction_joint=tuple(f_joint),
        limbs=limbs,
    )


def _solve_signs(system: _System, mu: float, signs: Vector) -> tuple[Vector, Vector] | None:
    """Sign iteration at ``mu`` from ``signs``: the consistent ``(x, signs)``, or None if it cycles or stalls."""
    g = mu * system.g
    tol = 1e-10 * float(np.abs(system.b).max())
    seen: set[bytes] = set()
    for _ in range(MAX_SIGN_ITERATIONS):
        key = signs.tobytes()
        if key in seen:
            return None
        seen.add(key)
        x = np.linalg.solve(system.k + g * signs, system.b)  # (K + mu G diag(s)) x = b
        # the assumed |x| = s x holds where s x >= 0 or x is negligible (then |x| ~ 0 either way)
        wrong = (signs * x < -tol) | ((signs == 0) & (np.abs(x) > tol))
        if not wrong.any():
            return x, signs
        signs = signs.copy()
        signs[wrong] = np.sign(x[wrong])
    return None


def _solve(system: _System, mu: float, time: float) -> Vector:
    """Solve ``K x + mu G |x| = b``: signs from the frictionless solution, else continuation in mu."""
    if np.linalg.cond(system.k) > MAX_CONDITION:
        raise UpuSingularityError(f"singular configuration at t = {time:g} s: the constraint couples are dependent")
    x0 = np.linalg.solve(system.k, system.b)
    signs0 = np.sign(x0) * (np.abs(x0) > 1e-10 * float(np.abs(system.b).max()))
    if mu == 0.0:
        return x0
    found = _solve_signs(system, mu, signs0)
    if found is not None:
        return found[0]
    # homotopy (Laus sec. 4.3.3.4): raise mu in steps from 0, each from the previous signs; halve a failing step
    level, signs, step = 0.0, signs0, mu / 20.0
    while level < mu:
        target = min(mu, level + step)
        found = _solve_signs(system, target, signs)
        if found is None:
            step /= 2.0
            if step < mu * 1e-6:
                raise UpuConvergenceError(f"no consistent friction signs at t = {time:g} s (stuck at mu = {level:g})")
            continue
        level, signs = target, found[1]
    return found[0]


def _statics(position: Sequence[float], velocity: Sequence[float], mu: float, time: float) -> UpuStep:
    """One configuration: solve the statics, compute the powers and check their balance."""
    system = _assemble(position, velocity)
    x = _solve(system, mu, time)
    friction = mu * (system.friction_coeff @ np.abs(x))  # the 18 friction magnitudes, eqs. 127-129
    powers = friction * system.friction_rate
    friction_power = {name: 0.0 for limb in JOINTS for name in limb}
    for joint, p in zip(system.friction_joint, powers, strict=True):
        friction_power[joint] += float(p)
    force = tuple(float(x[N_LIMB * i + 9]) for i in range(3))
    speed = tuple(lb.q for lb in system.limbs)
    actuator_power = tuple(f * v for f, v in zip(force, speed, strict=True))
    payload_power = float(PAYLOAD @ np.asarray(velocity, dtype=float))
    terms = [*actuator_power, payload_power, *friction_power.values()]
    scale = max(sum(abs(t) for t in terms), 1e-12)
    if abs(sum(terms)) > BALANCE_TOL * scale:
        raise PowerBalanceError(f"power balance fails at t = {time:g} s: residual {sum(terms):.3e} W")
    if max(friction_power.values()) > 1e-12 * scale:
        raise PowerBalanceError(f"positive friction power at t = {time:g} s")
    return UpuStep(
        time=time,
        actuator_force=(force[0], force[1], force[2]),
        actuator_speed=(speed[0], speed[1], speed[2]),
        actuator_power=(actuator_power[0], actuator_power[1], actuator_power[2]),
        payload_power=payload_power,
        friction_power=friction_power,
    )


def statics(position: Sequence[float], velocity: Sequence[float], mu: float = MU) -> UpuStep:
    """Actions and powers of one configuration: platform centre ``position``, its ``velocity`` (time 0.0)."""
    return _statics(position, velocity, mu, 0.0)


def _lift(t: float) -> tuple[Vector, Vector]:
    """Eq. 130: ``M = (0.1, 0.2, 0.5 + 0.4 t)``."""
    return np.array([0.1, 0.2, 0.5 + 0.4 * t]), np.array([0.0, 0.0, 0.4])


def _ellipse(t: float) -> tuple[Vector, Vector]:
    """Eqs. 131-132: ``M = (0.2 cos 2pi t, 0.2 sin 2pi t, 0.2 sin 2pi t + 0.7)``."""
    w = 2.0 * math.pi
    c, s = math.cos(w * t), math.sin(w * t)
    return np.array([0.2 * c, 0.2 * s, 0.2 * s + 0.7]), np.array([-0.2 * w * s, 0.2 * w * c, 0.2 * w * c])


TASKS: dict[str, tuple[Callable[[float], tuple[Vector, Vector]], float]] = {
    "lift": (_lift, 1.0),
    "lift_half": (_lift, 0.5),
    "ellipse": (_ellipse, 1.0),
}


def _trapezoid(values: Sequence[float], h: float) -> float:
    """Trapezoid rule over equally spaced samples."""
    v = np.asarray(values, dtype=float)
    return float(h * (v.sum() - 0.5 * (v[0] + v[-1])))


def simulate(task: str, step: float = 0.005, mu: float = MU) -> UpuTask:
    """Run ``task`` (``lift``, eq. 130, 1 s; ``lift_half``, 0.5 s; ``ellipse``, eq. 131, 1 s) at ``t_k = k step``."""
    if task not in TASKS:
        raise ValueError(f"unknown task {task!r}; known: {', '.join(TASKS)}")
    path, duration = TASKS[task]
    n = round(duration / step)
    if n < 1 or abs(n * step - duration) > 1e-9 * duration:
        raise ValueError(f"the step {step} does not divide the duration {duration} s")
    steps = []
    for k in range(n + 1):
        t = k * step
        m, m_dot = path(t)
        steps.append(_statics(m, m_dot, mu, t))
    supplied = _trapezoid([sum(s.actuator_power) for s in steps], step)
    payload = _trapezoid([-s.payload_power for s in steps], step)
    friction = {name: _trapezoid([-s.friction_power[name] for s in steps], step) for name in steps[0].friction_power}
    return UpuTask(
        steps=tuple(steps),
        supplied_energy=supplied,
        payload_energy=payload,
        friction_energy=friction,
        efficiency=payload / supplied,
    )
