"""Independent numerical oracle: quasi-static planar four-bar linkage with Coulomb friction in its pins.

Bodies: 1 ground, 2 crank AB, 3 coupler BC, 4 rocker DC.  Ground pivots A = (0, 0) and D = (d, 0).
The crank turns at omega_2 = 1 rad/s; the coupler and rocker rates come from the velocity loop.
Each revolute joint j carries a friction moment of magnitude mu * r_j * |F_j| (friction circle) opposing the
relative rotation of its two bodies.  The 9 equilibrium equations (forces x, y and moment for crank, coupler and
rocker) are written out here; the unknowns are the 4 pin forces and the output torque.  Only numpy and scipy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

JOINTS: tuple[str, str, str, str] = ("A", "B", "C", "D")
_FIXED_POINT_TOL = 1e-13
_MAX_FIXED_POINT = 200
_POWER_TOL = 1e-9


@dataclass(frozen=True)
class FourBarState:
    """Torques, rates, pin forces, friction powers and efficiency of the linkage at one position."""

    crank_torque: float
    rocker_torque: float
    omega: tuple[float, float, float]  # crank, coupler, rocker angular velocities (crank = 1)
    joint_forces: dict[str, tuple[float, float]]  # force on the second-named body from the first
    friction_power: dict[str, float]  # A..D, each <= 0
    efficiency: float


def _positions(a: float, b: float, c: float, d: float, theta: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points B, C, D; C on the left of the directed line B -> D.  ValueError when it cannot be assembled."""
    pb = np.array([a * np.cos(theta), a * np.sin(theta)])
    pd = np.array([d, 0.0])
    delta = pd - pb
    length = float(np.hypot(delta[0], delta[1]))
    if length == 0.0:
        raise ValueError("cannot assemble: B coincides with D")
    s = (b * b - c * c + length * length) / (2.0 * length)
    h2 = b * b - s * s
    if h2 < 0.0:
        raise ValueError(f"cannot assemble at theta={theta}: h^2 = {h2} < 0")
    h = float(np.sqrt(h2))
    pc = pb + (s / length) * delta + (h / length) * np.array([-delta[1], delta[0]])
    return pb, pc, pd


def _velocities(pb: np.ndarray, pc: np.ndarray, pd: np.ndarray, omega2: float = 1.0) -> tuple[float, float]:
    """Coupler and rocker rates from the loop v_B + w3 k x (C - B) = w4 k x (C - D)."""
    e = pc - pb
    g = pc - pd
    # [-e_y  g_y] [w3]   [ w2 B_y]
    # [ e_x -g_x] [w4] = [-w2 B_x]
    det = e[1] * g[0] - g[1] * e[0]
    if abs(det) <= 1e-12 * float(np.hypot(*e) * np.hypot(*g)):
        raise ValueError("coupler and rocker are collinear: the crank cannot turn (singular velocity loop)")
    r0, r1 = omega2 * pb[1], -omega2 * pb[0]
    w3 = (r0 * (-g[0]) - g[1] * r1) / det
    w4 = (-e[1] * r1 - e[0] * r0) / det
    return float(w3), float(w4)


def _equations(
    pb: np.ndarray, pc: np.ndarray, pd: np.ndarray, driver: str, t_in: float
) -> tuple[np.ndarray, np.ndarray]:
    """Matrix and frictionless right-hand side of the 9 equilibrium equations.

    Unknowns x = [FAx, FAy, FBx, FBy, FCx, FCy, FDx, FDy, T_out].  Rows: crank Fx, Fy, moment about A;
    coupler Fx, Fy, moment about B; rocker Fx, Fy, moment about D.
    """
    e = pc - pb
    g = pc - pd
    m = np.zeros((9, 9))
    # crank: F_A from ground, -F_B from coupler, moment about A of -F_B at B
    m[0, [0, 2]] = (1.0, -1.0)
    m[1, [1, 3]] = (1.0, -1.0)
    m[2, [2, 3]] = (pb[1], -pb[0])
    # coupler: F_B from crank, -F_C from rocker, moment about B of -F_C at C
    m[3, [2, 4]] = (1.0, -1.0)
    m[4, [3, 5]] = (1.0, -1.0)
    m[5, [4, 5]] = (e[1], -e[0])
    # rocker: F_C from coupler, F_D from ground, moment about D of F_C at C
    m[6, [4, 6]] = (1.0, 1.0)
    m[7, [5, 7]] = (1.0, 1.0)
    m[8, [4, 5]] = (-g[1], g[0])
    rhs = np.zeros(9)
    if driver == "crank":
        m[8, 8] = 1.0  # T_rocker unknown
        rhs[2] = -t_in
    else:
        m[2, 8] = 1.0  # T_crank unknown
        rhs[8] = -t_in
    return m, rhs


def _friction_rhs(n: np.ndarray, mu: float, radii: np.ndarray, sig: np.ndarray) -> np.ndarray:
    """Right-hand-side contribution of the friction moments (moved to the right), given |F_j| = n[j].

    sig[j] is the sign of the relative rate (second body minus first) at joint j.
    """
    k = mu * radii * n * sig  # friction moment on the second body is -k[j]
    f = np.zeros(9)
    # crank: -k_A (joint A, crank second) + k_B (joint B, crank first)
    f[2] = -(-k[0] + k[1])
    # coupler: -k_B (second at B) + k_C (first at C)
    f[5] = -(-k[1] + k[2])
    # rocker: -k_C (second at C) - k_D (second at D)
    f[8] = -(-k[2] - k[3])
    return f


def _magnitudes(x: np.ndarray) -> np.ndarray:
    """|F_A|, |F_B|, |F_C|, |F_D| from the unknown vector."""
    return np.hypot(x[0:8:2], x[1:8:2])


def _solve(m: np.ndarray, rhs0: np.ndarray, mu: float, radii: np.ndarray, sig: np.ndarray) -> np.ndarray:
    """Solve the 9 equations with friction: exact start from the common magnitude, then fixed-point polishing.

    The force rows make F_A = F_B = F_C = -F_D, so with all magnitudes equal to n the solution is x0 + n xg
    (x0 frictionless, xg the response to unit friction magnitudes) and n = |F0 + n G| is a quadratic in n.
    With |G| < 1 it has exactly one positive root and the fixed-point map on the magnitudes contracts (factor
    |G|); with |G| >= 1 there are two equilibria or none (friction locks the linkage near a dead point).
    """
    inv = np.linalg.inv(m)
    x0 = inv @ rhs0
    if mu == 0.0 or float(np.max(radii)) == 0.0:
        return x0
    xg = inv @ _friction_rhs(np.ones(4), mu, radii, sig)
    f0, g = x0[0:2], xg[0:2]
    gg = float(g @ g)
    if gg >= 1.0 - 1e-12:
        raise ValueError(
            f"friction locks the linkage here (|G| = {np.sqrt(gg):.6g} >= 1): no unique quasi-static equilibrium"
        )
    fg = float(f0 @ g)
    n = (fg + np.sqrt(fg * fg + (1.0 - gg) * float(f0 @ f0))) / (1.0 - gg)
    x = x0 + n * xg
    mags = _magnitudes(x)
    for _ in range(_MAX_FIXED_POINT):
        x = inv @ (rhs0 + _friction_rhs(mags, mu, radii, sig))
        new = _magnitudes(x)
        done = np.max(np.abs(new - mags)) <= _FIXED_POINT_TOL * float(np.max(new))
        mags = new
        if done:
            break
    else:
        raise RuntimeError("fixed-point iteration on the pin-force magnitudes did not converge")
    residual = m @ x - rhs0 - _friction_rhs(_magnitudes(x), mu, radii, sig)
    if float(np.max(np.abs(residual))) > 1e-12 * max(1.0, float(np.max(np.abs(x)))):
        raise RuntimeError(f"friction statics residual too large: {residual}")
    return x


def four_bar(
    a: float,
    b: float,
    c: float,
    d: float,
    theta: float,
    mu: float,
    radii: tuple[float, float, float, float],
    driver: str = "crank",
) -> FourBarState:
    """Quasi-static torques, pin forces and efficiency of the four-bar at crank angle theta (omega_2 = 1).

    The input port (``driver``) carries a torque of magnitude 1 with the sign of its body's rate.  ValueError when
    the linkage cannot be assembled, at a dead point (omega_4 = 0, or coupler and rocker collinear), and where the
    friction moments exceed the lever of the transmitted force (no unique equilibrium, next to a crank-input dead
    point).  A negative efficiency means the output port must assist (self-locking in that direction).
    """
    if driver not in ("crank", "rocker"):
        raise ValueError(f"driver must be 'crank' or 'rocker', not {driver!r}")
    if min(a, b, c, d) <= 0.0:
        raise ValueError("link lengths must be positive")
    if len(radii) != 4 or mu < 0.0 or min(radii) < 0.0:
        raise ValueError("mu and the four pin radii must be non-negative")
    pb, pc, pd = _positions(a, b, c, d, theta)
    w2 = 1.0
    w3, w4 = _velocities(pb, pc, pd, w2)
    if abs(w4) <= 1e-12 * (1.0 + abs(w3)):
        raise ValueError(f"dead point at theta={theta}: the rocker does not move (omega_4 = {w4})")
    omega = (w2, w3, w4)
    rel = np.array([w2 - 0.0, w3 - w2, w4 - w3, w4 - 0.0])  # second body minus first, joints A..D
    sig = np.sign(rel)

    t_in = float(np.sign(w2 if driver == "crank" else w4))
    m, rhs0 = _equations(pb, pc, pd, driver, t_in)
    r = np.asarray(radii, dtype=float)
    x = _solve(m, rhs0, float(mu), r, sig)
    t_out = float(x[8])
    t_crank, t_rocker = (t_in, t_out) if driver == "crank" else (t_out, t_in)

    n = _magnitudes(x)
    fric = -mu * r * n * np.abs(rel)
    p_crank, p_rocker = t_crank * w2, t_rocker * w4
    p_in, p_out = (p_crank, p_rocker) if driver == "crank" else (p_rocker, p_crank)
    balance = p_in + p_out + float(np.sum(fric))
    if abs(balance) > _POWER_TOL * abs(p_in):
        raise RuntimeError(f"power balance fails: {balance} (P_in = {p_in})")

    forces = {j: (float(x[2 * i]), float(x[2 * i + 1])) for i, j in enumerate(JOINTS)}
    return FourBarState(
        crank_torque=t_crank,
        rocker_torque=t_rocker,
        omega=omega,
        joint_forces=forces,
        friction_power={j: float(fric[i]) for i, j in enumerate(JOINTS)},
        efficiency=-p_out / p_in,
    )
