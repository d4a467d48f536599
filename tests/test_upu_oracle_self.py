"""Self-tests of the 3-UPU friction oracle (tests/oracles/upu_statics.py; Laus 2011, sec. 4.3).

The frictionless reference is written here again, independently: the platform's balance under the
three axial limb forces ``f_i ê2_i`` and the three constraint couples ``c_i ê5_i`` (a frictionless
U-P-U limb transmits nothing else), a direct 6x6 solve of eqs. 124-125 geometry.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np
import pytest
from oracles import upu_statics
from oracles.upu_statics import UpuConvergenceError, UpuSingularityError, UpuStep, simulate, statics
from scipy.integrate import trapezoid
from scipy.optimize import brentq

TASKS = ("lift", "lift_half", "ellipse")
WEIGHT = np.array([0.0, 0.0, -10_000.0])
ALPHAS = (0.0, 2.0 * math.pi / 3.0, -2.0 * math.pi / 3.0)


@pytest.fixture(scope="module")
def runs() -> dict[str, upu_statics.UpuTask]:
    """The three tasks at the data of sec. 4.3.4 (5 ms steps, mu = 0.11)."""
    return {task: simulate(task) for task in TASKS}


def lift_path(t: float) -> tuple[np.ndarray, np.ndarray]:
    """Eq. 130."""
    return np.array([0.1, 0.2, 0.5 + 0.4 * t]), np.array([0.0, 0.0, 0.4])


def ellipse_path(t: float) -> tuple[np.ndarray, np.ndarray]:
    """Eqs. 131-132."""
    w = 2.0 * math.pi
    return (
        np.array([0.2 * math.cos(w * t), 0.2 * math.sin(w * t), 0.2 * math.sin(w * t) + 0.7]),
        0.2 * w * np.array([-math.sin(w * t), math.cos(w * t), math.cos(w * t)]),
    )


def direct_frictionless(m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Axial forces ``f`` and couples ``c``: ``sum f_i ê2_i + W = 0``, ``sum (D_i - M) x f_i ê2_i + c_i ê5_i = 0``."""
    a = np.zeros((6, 6))
    for i, alpha in enumerate(ALPHAS):
        radial = np.array([math.cos(alpha), math.sin(alpha), 0.0])
        axis = m + (0.5 - 1.0) * radial  # e2: from the base joint to the platform joint
        axis /= np.linalg.norm(axis)
        third = np.cross(radial, axis)
        third /= np.linalg.norm(third)
        fifth = np.cross(radial, third)
        arm = 0.5 * radial  # D - M
        a[:3, i] = axis
        a[3:, i] = np.cross(arm, axis)
        a[3:, 3 + i] = fifth
    x = np.linalg.solve(a, np.concatenate([-WEIGHT, np.zeros(3)]))  # moments about M: W passes through M
    return x[:3], x[3:]


def balance_terms(step: UpuStep) -> list[float]:
    """Every power of one sample: actuators, payload, friction."""
    return [*step.actuator_power, step.payload_power, *step.friction_power.values()]


@pytest.mark.parametrize("task", TASKS)
def test_power_balance_every_step(runs: dict[str, upu_statics.UpuTask], task: str) -> None:
    """Actuator + payload + friction powers add up to zero at every sample (1e-6 relative)."""
    steps = runs[task].steps
    assert len(steps) == (101 if task == "lift_half" else 201)
    for step in steps:
        terms = balance_terms(step)
        assert abs(sum(terms)) <= 1e-6 * sum(abs(t) for t in terms), step.time
        for force, speed, power in zip(step.actuator_force, step.actuator_speed, step.actuator_power, strict=True):
            assert power == pytest.approx(force * speed, rel=1e-12, abs=1e-9)


@pytest.mark.parametrize("task", TASKS)
def test_friction_dissipates(runs: dict[str, upu_statics.UpuTask], task: str) -> None:
    """Every friction power is <= 0, every friction energy >= 0; the twelve joints A..L all appear."""
    run = runs[task]
    assert sorted(run.friction_energy) == list("ABCDEFGHIJKL")
    for step in run.steps:
        assert sorted(step.friction_power) == list("ABCDEFGHIJKL")
        assert all(p <= 0.0 for p in step.friction_power.values()), step.time
    assert all(e >= 0.0 for e in run.friction_energy.values())


@pytest.mark.parametrize("task", TASKS)
def test_energies_are_trapezoids(runs: dict[str, upu_statics.UpuTask], task: str) -> None:
    """The energies are scipy's trapezoid rule over the samples; supplied = payload + friction."""
    run = runs[task]
    times = [s.time for s in run.steps]
    assert times[1] - times[0] == pytest.approx(0.005)
    supplied = trapezoid([sum(s.actuator_power) for s in run.steps], times)
    payload = trapezoid([-s.payload_power for s in run.steps], times)
    assert run.supplied_energy == pytest.approx(supplied, rel=1e-9, abs=1e-9)
    assert run.payload_energy == pytest.approx(payload, rel=1e-9, abs=1e-9)
    lost = sum(run.friction_energy.values())
    assert run.supplied_energy == pytest.approx(run.payload_energy + lost, rel=1e-6)
    if task != "ellipse":
        assert run.efficiency == pytest.approx(run.payload_energy / run.supplied_energy)


def test_lift_payload_energy(runs: dict[str, upu_statics.UpuTask]) -> None:
    """Lifting 10 kN by 0.4 m (0.2 m for the half task) takes 4000 J (2000 J); the machine loses energy."""
    assert runs["lift"].payload_energy == pytest.approx(4000.0, rel=1e-12)
    assert runs["lift_half"].payload_energy == pytest.approx(2000.0, rel=1e-12)
    assert 0.0 < runs["lift"].efficiency < runs["lift_half"].efficiency < 1.0
    assert runs["ellipse"].payload_energy == pytest.approx(0.0, abs=1e-6)  # a closed path


@pytest.mark.parametrize("task", TASKS)
def test_frictionless_energy_balance(task: str) -> None:
    """With mu = 0 the actuators supply exactly the payload's energy, and no friction power appears."""
    run = simulate(task, mu=0.0)
    assert run.supplied_energy == pytest.approx(run.payload_energy, rel=1e-9, abs=1e-6)
    assert all(p == 0.0 for s in run.steps for p in s.friction_power.values())
    if task == "lift":
        assert run.supplied_energy == pytest.approx(4000.0, rel=1e-9)
        assert run.efficiency == pytest.approx(1.0, rel=1e-12)


def test_frictionless_forces_match_direct_solve() -> None:
    """With mu = 0 the actuator forces are the axial forces of the direct 6x6 platform balance."""
    rng = np.random.default_rng(7)
    configurations = [lift_path(t) for t in (0.0, 0.37, 1.0)] + [ellipse_path(t) for t in (0.0, 0.21, 0.66)]
    for _ in range(10):
        m = np.array([rng.uniform(-0.25, 0.25), rng.uniform(-0.25, 0.25), rng.uniform(0.4, 1.0)])
        configurations.append((m, rng.normal(size=3)))
    for m, m_dot in configurations:
        forces, _ = direct_frictionless(m)
        step = statics(m, m_dot, mu=0.0)
        assert np.allclose(step.actuator_force, forces, rtol=1e-9, atol=1e-6), m
        # the actuators alone lift the payload: power in = power out
        assert sum(step.actuator_power) == pytest.approx(-step.payload_power, rel=1e-9, abs=1e-9)


def test_frictionless_limb_actions_match_direct_solve() -> None:
    """With mu = 0 every limb carries its axial force and the couple c_i ê5_i unchanged from A to D."""
    m, m_dot = lift_path(0.37)
    forces, couples = direct_frictionless(m)
    system = upu_statics._assemble(m, m_dot)
    x = upu_statics._solve(system, 0.0, 0.0)
    for i in range(3):
        row = dict(zip(upu_statics.UNKNOWNS, x[14 * i : 14 * i + 14], strict=True))
        assert row["P_D"] == pytest.approx(couples[i], rel=1e-9, abs=1e-6)
        assert row["P_A"] == pytest.approx(couples[i], rel=1e-9, abs=1e-6)
        assert row["Q_CA"] == pytest.approx(forces[i], rel=1e-9, abs=1e-6)


def test_efficiency_tends_to_one() -> None:
    """As mu -> 0 the efficiency tends to 1 and the losses shrink in proportion to mu."""
    tiny = simulate("lift", mu=1e-6)
    assert tiny.efficiency == pytest.approx(1.0, abs=1e-4)
    assert tiny.efficiency < 1.0
    small = simulate("lift", mu=1e-4)
    loss_tiny, loss_small = tiny.supplied_energy - 4000.0, small.supplied_energy - 4000.0
    assert loss_small / loss_tiny == pytest.approx(100.0, rel=1e-2)


def test_efficiency_decreases_with_mu() -> None:
    """More friction, less efficiency."""
    etas = [simulate("lift_half", mu=mu).efficiency for mu in (0.0, 0.03, 0.07, 0.11)]
    assert all(a > b for a, b in itertools.pairwise(etas))


def test_mirror_symmetric_configuration() -> None:
    """M and Ṁ in the xz-plane (limb 1's plane): limbs 2 and 3 are mirror images, with equal actions."""
    step = statics((0.15, 0.0, 0.8), (0.1, 0.0, 0.3))
    assert step.actuator_force[1] == pytest.approx(step.actuator_force[2], rel=1e-9)
    assert step.actuator_speed[1] == pytest.approx(step.actuator_speed[2], rel=1e-12)
    for limb2, limb3 in zip("EFGH", "IJKL", strict=True):
        assert step.friction_power[limb2] == pytest.approx(step.friction_power[limb3], rel=1e-9, abs=1e-9)
    assert all(p < 0.0 for p in step.friction_power.values())


def test_constraint_singularity_is_refused() -> None:
    """M on the z-axis: every ê5 is vertical, the constraint couples cannot hold the tilt of the platform."""
    with pytest.raises(UpuSingularityError, match="singular"):
        statics((0.0, 0.0, 0.8), (0.0, 0.0, 0.3))
    statics((0.01, 0.0, 0.8), (0.0, 0.0, 0.3))  # near it, still solvable


def test_coulomb_friction_is_rate_independent() -> None:
    """Doubling the speed leaves the forces unchanged and doubles every power."""
    m, m_dot = ellipse_path(0.13)
    slow, fast = statics(m, m_dot), statics(m, 2.0 * m_dot)
    assert np.allclose(fast.actuator_force, slow.actuator_force, rtol=1e-9)
    assert np.allclose(fast.actuator_power, 2.0 * np.array(slow.actuator_power), rtol=1e-9)
    for joint, power in slow.friction_power.items():
        assert fast.friction_power[joint] == pytest.approx(2.0 * power, rel=1e-9, abs=1e-9)


def test_lowering_needs_less_force_than_lifting() -> None:
    """Friction opposes the motion: the actuators push harder lifting, less lowering, than without it."""
    m = np.array([0.1, 0.2, 0.7])
    up, down = statics(m, (0.0, 0.0, 0.4)), statics(m, (0.0, 0.0, -0.4))
    free = statics(m, (0.0, 0.0, 0.4), mu=0.0)
    assert sum(up.actuator_power) > -up.payload_power > 0.0
    assert 0.0 < -sum(down.actuator_power) < down.payload_power
    assert sum(up.actuator_force) > sum(free.actuator_force) > sum(down.actuator_force)


def test_stationary_platform_has_no_friction() -> None:
    """Zero speed: every rate is zero, so no friction acts and the forces are the frictionless ones."""
    m = np.array([0.05, -0.1, 0.75])
    step = statics(m, (0.0, 0.0, 0.0))
    assert all(p == 0.0 for p in step.friction_power.values())
    assert np.allclose(step.actuator_force, direct_frictionless(m)[0], rtol=1e-9)


def test_extension_rate_is_limb_length_rate() -> None:
    """q_i = d|D_i - A_i|/dt (central differences along the ellipse)."""
    for t in (0.1, 0.4, 0.8):
        step = statics(*ellipse_path(t))
        for i, alpha in enumerate(ALPHAS):
            radial = np.array([math.cos(alpha), math.sin(alpha), 0.0])

            def length(s: float, radial: np.ndarray = radial) -> float:
                return float(np.linalg.norm(ellipse_path(s)[0] - 0.5 * radial))

            h = 1e-6
            assert step.actuator_speed[i] == pytest.approx((length(t + h) - length(t - h)) / (2 * h), rel=1e-6)


def test_motion_reversals_of_laus() -> None:
    """Ellipse: p_E1 reverses at 43.54 ms, p_I2 at 47.57 ms, p_A2 at 66.43 ms, q of limb 1 at 0.33275 s."""

    def rate(limb: int, which: str) -> float:
        def f(t: float) -> float:
            geometry = upu_statics._limb(ALPHAS[limb], *ellipse_path(t))
            return {"p1": geometry.p_a[0], "p2": geometry.p_a[1], "q": geometry.q}[which]

        return f

    assert brentq(rate(1, "p1"), 0.03, 0.05) == pytest.approx(0.04354, abs=2e-5)
    assert brentq(rate(2, "p2"), 0.04, 0.055) == pytest.approx(0.04757, abs=2e-5)
    assert brentq(rate(0, "p2"), 0.06, 0.07) == pytest.approx(0.06643, abs=2e-5)
    assert brentq(rate(0, "q"), 0.3, 0.35) == pytest.approx(0.33275, abs=2e-5)
    before, after = statics(*ellipse_path(0.3327)), statics(*ellipse_path(0.3328))
    assert before.actuator_speed[0] > 0.0 > after.actuator_speed[0]
    assert before.actuator_force[0] > after.actuator_force[0] + 10_000.0  # the friction of B and C reverses


def test_limb_angular_velocity_reproduces_platform_velocity() -> None:
    """omega = p_A1 ê1 + p_A2 ê3 satisfies omega x e2 + q ê2 = Ṁ; D's rates are the negatives."""
    rng = np.random.default_rng(3)
    for _ in range(10):
        m = np.array([rng.uniform(-0.25, 0.25), rng.uniform(-0.25, 0.25), rng.uniform(0.4, 1.0)])
        m_dot = rng.normal(size=3)
        for alpha in ALPHAS:
            g = upu_statics._limb(alpha, m, m_dot)
            omega = g.p_a[0] * g.e[0] + g.p_a[1] * g.e[2]
            assert np.allclose(np.cross(omega, g.d - g.a) + g.q * g.e[1], m_dot, atol=1e-12)
            assert g.p_d == (-g.p_a[0], -g.p_a[1])
            basis = np.array([g.e[0], g.e[2], g.e[4]])
            assert np.allclose(basis @ basis.T, np.eye(3), atol=1e-12)


def test_continuation_in_mu_gives_the_same_solution(monkeypatch: pytest.MonkeyPatch) -> None:
    """When the direct sign iteration fails, the continuation in mu reaches the same solution."""
    m, m_dot = ellipse_path(0.3)
    expected = statics(m, m_dot)
    real = upu_statics._solve_signs
    calls = {"n": 0}

    def fail_first(system: Any, mu: float, signs: np.ndarray) -> Any:
        calls["n"] += 1
        return None if calls["n"] == 1 else real(system, mu, signs)

    monkeypatch.setattr(upu_statics, "_solve_signs", fail_first)
    got = statics(m, m_dot)
    assert calls["n"] > 2
    assert np.allclose(got.actuator_force, expected.actuator_force, rtol=1e-9)


def test_non_convergence_names_the_time(monkeypatch: pytest.MonkeyPatch) -> None:
    """A sign iteration that never settles raises UpuConvergenceError naming the time."""
    monkeypatch.setattr(upu_statics, "MAX_SIGN_ITERATIONS", 0)
    with pytest.raises(UpuConvergenceError, match=r"t = 0\.123 s"):
        upu_statics._statics(*ellipse_path(0.123), 0.11, 0.123)


def test_bad_arguments() -> None:
    """Unknown task, a step that does not divide the duration."""
    with pytest.raises(ValueError, match="unknown task"):
        simulate("circle")
    with pytest.raises(ValueError, match="does not divide"):
        simulate("lift", step=0.003)


def test_a_task_settles_every_step() -> None:
    """The ellipse task's 200 steps each settle their friction signs within the bounded
    iteration (UpuConvergenceError otherwise): work bounded by a count, not by seconds
    (the timing is benchmarks/three_upu_task.py's)."""
    task = simulate("ellipse")
    assert len(task.steps) in (200, 201)  # t = 0, 0.005, ..., 1 s
    assert task.supplied_energy > 0 and all(e >= 0 for e in task.friction_energy.values())
