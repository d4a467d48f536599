"""Self-tests of the four-bar friction oracle (tests/oracles/four_bar_statics.py): numpy and scipy only."""

from __future__ import annotations

import numpy as np
import pytest
from oracles.four_bar_statics import FourBarState, _positions, _velocities, four_bar
from scipy.optimize import brentq, fsolve

CRANK_ROCKER = (1.0, 3.0, 2.5, 3.0)  # Grashof: s + l = 4 <= p + q = 5.5, the crank is the shortest link
OTHER = (2.0, 5.0, 4.0, 6.0)  # another Grashof crank-rocker: 8 <= 9
RADII = (0.05, 0.05, 0.05, 0.05)
DRIVERS = ("crank", "rocker")


def _omega4(dims: tuple[float, float, float, float], theta: float) -> float:
    """Rocker rate at crank angle theta (crank rate 1)."""
    return _velocities(*_positions(*dims, theta))[1]


def _dead_points(dims: tuple[float, float, float, float]) -> list[float]:
    """Crank angles in [0, 2 pi) where the rocker rate vanishes (crank and coupler collinear)."""
    grid = np.linspace(0.0, 2.0 * np.pi, 721)
    values = [_omega4(dims, t) for t in grid]
    return [
        float(brentq(lambda t: _omega4(dims, t), grid[i], grid[i + 1], xtol=1e-15, rtol=1e-15))
        for i in range(len(grid) - 1)
        if values[i] * values[i + 1] < 0.0
    ]


def _thetas(dims: tuple[float, float, float, float], count: int, seed: int, margin: float = 0.15) -> list[float]:
    """Random crank angles at least `margin` rad away from the dead points."""
    dead = _dead_points(dims)
    rng = np.random.default_rng(seed)
    out: list[float] = []
    while len(out) < count:
        t = float(rng.uniform(0.0, 2.0 * np.pi))
        if all(abs((t - t0 + np.pi) % (2.0 * np.pi) - np.pi) > margin for t0 in dead):
            out.append(t)
    return out


def _relative_rates(state: FourBarState) -> dict[str, float]:
    """Relative rate (second body minus first) at each joint."""
    w2, w3, w4 = state.omega
    return {"A": w2, "B": w3 - w2, "C": w4 - w3, "D": w4}


def _powers(state: FourBarState, driver: str) -> tuple[float, float]:
    """Input and output port powers."""
    p_crank = state.crank_torque * state.omega[0]
    p_rocker = state.rocker_torque * state.omega[2]
    return (p_crank, p_rocker) if driver == "crank" else (p_rocker, p_crank)


def _cross(u: np.ndarray, v: np.ndarray) -> float:
    """z component of u x v."""
    return float(u[0] * v[1] - u[1] * v[0])


def _reduced(
    z: np.ndarray,
    points: tuple[np.ndarray, np.ndarray, np.ndarray],
    mu: float,
    radii: tuple[float, float, float, float],
    signs: np.ndarray,
    driver: str,
    t_in: float,
) -> list[float]:
    """Crank about A, coupler about C, coupler + rocker about D; z = (force on the coupler at B, output torque)."""
    pb, pc, pd = points
    f, t_out = z[:2], z[2]
    t_crank, t_rocker = (t_in, t_out) if driver == "crank" else (t_out, t_in)
    k = mu * np.array(radii) * np.hypot(*f) * signs  # friction moment on the second body of each joint is -k
    return [
        t_crank + _cross(pb, -f) - k[0] + k[1],
        _cross(pb - pc, f) - k[1] + k[2],
        t_rocker + _cross(pb - pd, f) - k[1] - k[3],
    ]


@pytest.mark.parametrize("dims", [CRANK_ROCKER, OTHER])
def test_positions_close_the_loop(dims: tuple[float, float, float, float]) -> None:
    a, b, c, d = dims
    for theta in np.linspace(0.0, 2.0 * np.pi, 37):
        pb, pc, pd = _positions(a, b, c, d, theta)
        assert np.hypot(*pb) == pytest.approx(a, rel=1e-14)
        assert np.hypot(*(pc - pb)) == pytest.approx(b, rel=1e-13)
        assert np.hypot(*(pc - pd)) == pytest.approx(c, rel=1e-13)
        delta, e = pd - pb, pc - pb
        assert delta[0] * e[1] - delta[1] * e[0] > 0.0


@pytest.mark.parametrize("dims", [CRANK_ROCKER, OTHER])
def test_velocity_loop_matches_finite_differences(dims: tuple[float, float, float, float]) -> None:
    def angles(theta: float) -> np.ndarray:
        pb, pc, pd = _positions(*dims, theta)
        return np.array([np.arctan2(*(pc - pb)[::-1]), np.arctan2(*(pc - pd)[::-1])])

    step = 1e-5
    for theta in _thetas(dims, 20, seed=1):
        diff = (angles(theta + step) - angles(theta - step)) / (2.0 * step)
        diff = (diff + np.pi / step) % (2.0 * np.pi / step) - np.pi / step  # no branch jump of atan2
        w3, w4 = _velocities(*_positions(*dims, theta))
        assert diff == pytest.approx([w3, w4], rel=1e-8, abs=1e-9)


@pytest.mark.parametrize("driver", DRIVERS)
@pytest.mark.parametrize("dims", [CRANK_ROCKER, OTHER])
def test_power_balance_at_random_positions(dims: tuple[float, float, float, float], driver: str) -> None:
    rng = np.random.default_rng(7)
    for theta in _thetas(dims, 40, seed=2):
        mu = float(rng.uniform(0.02, 0.25))
        radii = tuple(float(r) for r in rng.uniform(0.01, 0.06, 4))
        state = four_bar(*dims, theta, mu, radii, driver)
        p_in, p_out = _powers(state, driver)
        assert p_in > 0.0
        rates = _relative_rates(state)
        for i, joint in enumerate("ABCD"):
            expected = -mu * radii[i] * np.hypot(*state.joint_forces[joint]) * abs(rates[joint])
            assert state.friction_power[joint] == pytest.approx(expected, rel=1e-12, abs=1e-15)
            assert state.friction_power[joint] <= 0.0
        assert abs(p_in + p_out + sum(state.friction_power.values())) <= 1e-9 * p_in
        assert state.efficiency == pytest.approx(-p_out / p_in, rel=1e-14)


@pytest.mark.parametrize("driver", DRIVERS)
def test_pin_forces_are_transmitted(driver: str) -> None:
    state = four_bar(*CRANK_ROCKER, 2.0, 0.2, RADII, driver)
    fa, fb, fc, fd = (np.array(state.joint_forces[j]) for j in "ABCD")
    assert fa == pytest.approx(fb, rel=1e-13)
    assert fb == pytest.approx(fc, rel=1e-13)
    assert fd == pytest.approx(-fc, rel=1e-13)


@pytest.mark.parametrize("driver", DRIVERS)
@pytest.mark.parametrize("dims", [CRANK_ROCKER, OTHER])
def test_frictionless_is_virtual_work(dims: tuple[float, float, float, float], driver: str) -> None:
    for theta in _thetas(dims, 30, seed=3, margin=0.02):
        state = four_bar(*dims, theta, 0.0, RADII, driver)
        w2, _, w4 = state.omega
        assert state.efficiency == pytest.approx(1.0, abs=1e-12)
        assert state.rocker_torque / state.crank_torque == pytest.approx(-w2 / w4, rel=1e-12)
        assert all(p == 0.0 for p in state.friction_power.values())
        # the frictionless coupler is a two-force member: its force lies along BC
        pb, pc, _ = _positions(*dims, theta)
        e, f = pc - pb, np.array(state.joint_forces["B"])
        assert abs(e[0] * f[1] - e[1] * f[0]) <= 1e-12 * np.hypot(*e) * np.hypot(*f)


@pytest.mark.parametrize("driver", DRIVERS)
def test_efficiency_tends_to_one_as_mu_vanishes(driver: str) -> None:
    for theta in (0.3, 1.0, 2.5, 5.0):
        losses = [1.0 - four_bar(*CRANK_ROCKER, theta, mu, RADII, driver).efficiency for mu in (1e-2, 1e-3, 1e-4, 1e-5)]
        assert all(x > 0.0 for x in losses)
        assert losses == sorted(losses, reverse=True)
        assert losses[-1] < 1e-4
        # first order in mu: the loss per unit mu settles
        slopes = [x / mu for x, mu in zip(losses, (1e-2, 1e-3, 1e-4, 1e-5), strict=True)]
        assert slopes[-1] == pytest.approx(slopes[-2], rel=1e-3)
        assert slopes[-2] == pytest.approx(slopes[-3], rel=1e-2)


@pytest.mark.parametrize("driver", DRIVERS)
def test_efficiency_below_one_with_friction(driver: str) -> None:
    for theta in _thetas(CRANK_ROCKER, 30, seed=4):
        eta = [four_bar(*CRANK_ROCKER, theta, mu, RADII, driver).efficiency for mu in (0.05, 0.1, 0.2)]
        assert eta[0] < 1.0
        assert eta[0] > eta[1] > eta[2]


@pytest.mark.parametrize("driver", DRIVERS)
@pytest.mark.parametrize("mu", [0.0, 0.15, 0.3])
def test_whole_linkage_equilibrium(driver: str, mu: float) -> None:
    """Ground reactions at A and D (forces and friction moments) and the two port torques balance."""
    a, b, c, d = CRANK_ROCKER
    for theta in _thetas(CRANK_ROCKER, 20, seed=5, margin=0.3):
        state = four_bar(a, b, c, d, theta, mu, RADII, driver)
        w2, _, w4 = state.omega
        fa, fd = np.array(state.joint_forces["A"]), np.array(state.joint_forces["D"])
        m_a = state.friction_power["A"] / w2  # friction moment on the crank from the ground
        m_d = state.friction_power["D"] / w4  # friction moment on the rocker from the ground
        assert m_a == pytest.approx(-mu * RADII[0] * np.hypot(*fa) * np.sign(w2), abs=1e-14)
        assert m_d == pytest.approx(-mu * RADII[3] * np.hypot(*fd) * np.sign(w4), abs=1e-14)
        scale = 1.0 + d * np.hypot(*fd)
        assert np.abs(fa + fd).max() <= 1e-12 * scale
        for point in (np.zeros(2), np.array([d, 0.0]), np.array([-1.3, 2.7])):
            ra, rd = -point, np.array([d, 0.0]) - point
            moment = (
                state.crank_torque
                + state.rocker_torque
                + m_a
                + m_d
                + (ra[0] * fa[1] - ra[1] * fa[0])
                + (rd[0] * fd[1] - rd[1] * fd[0])
            )
            assert abs(moment) <= 1e-12 * (scale + np.hypot(*point) * np.hypot(*fa))


@pytest.mark.parametrize("driver", DRIVERS)
def test_agrees_with_a_reduced_solve(driver: str) -> None:
    """fsolve on another choice of free bodies: crank about A, coupler about C, coupler + rocker about D."""
    mu, radii = 0.25, (0.04, 0.06, 0.05, 0.03)
    for theta in _thetas(CRANK_ROCKER, 15, seed=6, margin=0.3):
        pb, pc, pd = _positions(*CRANK_ROCKER, theta)
        w2 = 1.0
        w3, w4 = _velocities(pb, pc, pd, w2)
        signs = np.sign([w2, w3 - w2, w4 - w3, w4])
        t_in = float(np.sign(w2 if driver == "crank" else w4))
        points = (pb, pc, pd)

        # full_output: the residual is asserted below instead of fsolve's progress warnings
        start = fsolve(_reduced, np.ones(3), args=(points, 0.0, radii, signs, driver, t_in), full_output=True)[0]
        args = (points, mu, radii, signs, driver, t_in)
        z = fsolve(_reduced, start, args=args, xtol=1e-14, full_output=True)[0]
        assert np.abs(_reduced(z, *args)).max() < 1e-12
        state = four_bar(*CRANK_ROCKER, theta, mu, radii, driver)
        t_out = state.rocker_torque if driver == "crank" else state.crank_torque
        assert state.joint_forces["B"] == pytest.approx(tuple(z[:2]), rel=1e-10, abs=1e-12)
        assert t_out == pytest.approx(z[2], rel=1e-10)


@pytest.mark.parametrize("driver", DRIVERS)
@pytest.mark.parametrize("dims", [CRANK_ROCKER, OTHER])
def test_dead_points_raise(dims: tuple[float, float, float, float], driver: str) -> None:
    a, b, _, _ = dims
    dead = _dead_points(dims)
    assert len(dead) == 2  # a crank-rocker has two rocker extremes per turn
    reaches = sorted(float(np.hypot(*_positions(*dims, t)[1])) for t in dead)
    assert reaches == pytest.approx([b - a, a + b], rel=1e-9)  # crank and coupler folded / stretched
    for theta in dead:
        for mu in (0.0, 0.2):
            with pytest.raises(ValueError, match="dead point"):
                four_bar(*dims, theta, mu, RADII, driver)


def test_friction_locks_near_a_dead_point() -> None:
    """Crank input: next to a dead point the friction moments exceed the crank's lever, no equilibrium is unique."""
    theta = _dead_points(CRANK_ROCKER)[0] + 1e-3
    assert four_bar(*CRANK_ROCKER, theta, 0.0, RADII).efficiency == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(ValueError, match="locks"):
        four_bar(*CRANK_ROCKER, theta, 0.2, RADII)
    assert four_bar(*CRANK_ROCKER, theta, 0.2, RADII, "rocker").efficiency < 0.0  # the rocker cannot drive here


def test_invalid_input_raises() -> None:
    with pytest.raises(ValueError, match="assemble"):
        four_bar(1.0, 1.0, 1.0, 3.5, 0.0, 0.1, RADII)
    with pytest.raises(ValueError, match="driver"):
        four_bar(*CRANK_ROCKER, 1.0, 0.1, RADII, "coupler")
    with pytest.raises(ValueError):
        four_bar(*CRANK_ROCKER, 1.0, -0.1, RADII)


def test_example_values_and_a_sweep() -> None:
    crank = four_bar(*CRANK_ROCKER, 1.0, 0.2, RADII, "crank")
    rocker = four_bar(*CRANK_ROCKER, 1.0, 0.2, RADII, "rocker")
    assert crank.omega == pytest.approx((1.0, -0.21295965610830714, 0.1953617393167292), rel=1e-12)
    assert crank.rocker_torque == pytest.approx(-4.7823972670029, rel=1e-11)
    assert crank.efficiency == pytest.approx(0.93429744818526, rel=1e-11)
    assert rocker.crank_torque == pytest.approx(-0.18176346940100, rel=1e-11)
    assert rocker.efficiency == pytest.approx(0.93039440597072, rel=1e-11)
    # A sweep of 200 positions solves everywhere (a finite efficiency in (0, 1) at each).
    sweep = [four_bar(*CRANK_ROCKER, float(theta), 0.2, RADII, "crank") for theta in np.linspace(1.0, 3.0, 200)]
    assert all(0 < state.efficiency < 1 for state in sweep)
