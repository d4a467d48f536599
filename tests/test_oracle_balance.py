"""The independent oracle (tests/oracle/balance.py) checked by hand on textbook cases,
by the power balance and by the lossless limit.  Nothing here uses the engine."""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from oracle.balance import Gear, Member, Mesh, SelfLocking, TrainSpec, in_state, solve, with_efficiencies
from oracle.random_trains import FAMILIES, generate


def pair(r1: F, r2: F, eta: F, internal: bool = False) -> TrainSpec:
    d = r2 - r1 if internal else r1 + r2
    return TrainSpec(
        "pair",
        (Member("0"), Member("a"), Member("b", None, (F(0), d))),
        (Gear("G1", "a", r1), Gear("G2", "b", r2, internal)),
        (Mesh("C", ("G1", "G2"), eta),),
        "0",
        {"A": "a", "B": "b"},
        "A",
        "B",
    )


def planetary(rs: F, rp: F, eta_sp: F, eta_rp: F) -> TrainSpec:
    """Ring fixed (on the housing), sun input A, carrier output B."""
    rr = rs + 2 * rp
    return TrainSpec(
        "planetary",
        (Member("0"), Member("s"), Member("p", "c", (F(0), rs + rp)), Member("c")),
        (Gear("S", "s", rs), Gear("P", "p", rp), Gear("R", "0", rr, True)),
        (Mesh("C", ("S", "P"), eta_sp), Mesh("D", ("R", "P"), eta_rp)),
        "0",
        {"A": "s", "B": "c"},
        "A",
        "B",
    )


def tuplin(r1: F, r2: F, r3: F, r4: F, eta: F) -> TrainSpec:
    """Laus 2011 Fig. 7: annulus 1 fixed, carrier 5 (port A), annulus 2 (port B)."""
    return TrainSpec(
        "tuplin",
        (Member("1"), Member("2"), Member("3/4", "5", (F(0), r1 - r3)), Member("5")),
        (Gear("1", "1", r1, True), Gear("2", "2", r2, True), Gear("3", "3/4", r3), Gear("4", "3/4", r4)),
        (Mesh("C", ("1", "3"), eta), Mesh("D", ("2", "4"), eta)),
        "1",
        {"A": "5", "B": "2"},
        "A",
        "B",
    )


@pytest.mark.parametrize("internal", [False, True])
@pytest.mark.parametrize("port", ["A", "B"])
def test_fixed_axis_pair(internal: bool, port: str) -> None:
    """A fixed-axis pair: the housing is the carrier, so the overall efficiency is the
    ordinary efficiency itself (Laus eq. (36): P_B = -eta T_A t_A), in both directions; the
    ratio is -r2/r1 (external) or +r2/r1 (internal)."""
    r = solve(pair(F(20), F(50), F(98, 100), internal), port)
    assert r.efficiency == F(98, 100)
    ratio = F(50, 20) * (1 if internal else -1)
    assert r.speed_ratio == (ratio if port == "A" else 1 / ratio)


def test_simple_planetary_ring_fixed() -> None:
    """Ring R fixed, sun S input, carrier output; eta0 = eta_SP * eta_RP is the efficiency
    of the basic train (carrier held, sun to ring).

    Kinematics (Willis): w_S - w_c = -(R/S)(w_R - w_c) with w_R = 0, so
    w_S / w_c = 1 + R/S.  Statics: the whole train gives T_S + T_R + T_c = 0.  In the
    carrier frame the sun drives (power T_S (w_S - w_c) > 0 enters at the sun) and the
    ring receives eta0 of it: T_R (w_R - w_c) = -eta0 T_S (w_S - w_c), so
    T_R = eta0 (R/S) T_S.  Then eta = -T_c w_c / (T_S w_S) = (T_S + T_R) / (T_S (1 + R/S))
    = (1 + eta0 R/S) / (1 + R/S).

    Driven backwards (carrier input, sun output) the ring drives in the carrier frame:
    T_S (w_S - w_c) = -eta0 T_R (w_R - w_c) gives T_R = T_S R / (S eta0) and
    eta = (1 + R/S) / (1 + R / (S eta0))."""
    rs, rp, e1, e2 = F(20), F(15), F(98, 100), F(97, 100)
    rr, e0 = rs + 2 * rp, e1 * e2
    train = planetary(rs, rp, e1, e2)
    forward = solve(train, "A")
    assert forward.speed_ratio == 1 + rr / rs
    assert forward.efficiency == (1 + e0 * rr / rs) / (1 + rr / rs)
    backward = solve(train, "B")
    assert backward.efficiency == (1 + rr / rs) / (1 + rr / (rs * e0))
    assert backward.first_drives == {"C": False, "D": True}


def test_tuplin_laus():
    """Laus 2011, section 3.4.1.6: z = 80, 60, 30, 35 with modules 1 and 2 mm (r1 = 40,
    r2 = 60, r3 = 15, r4 = 35), eta = 0.99 for both meshes: eq. (76) gives 0.9462 with the
    carrier (A) as input; eq. (78), 0.9443, holds with B as input."""
    train = tuplin(F(40), F(60), F(15), F(35), F(99, 100))
    a = solve(train, "A")
    assert round(float(a.efficiency), 4) == 0.9462
    assert a.speed_ratio == F(-9, 5)  # w5 / w2 = r2 r3 / ((r1 - r2)(r1 - r3)), Laus eq. (59)
    b = solve(train, "B")
    assert round(float(b.efficiency), 4) == 0.9443


def test_compound_chain_is_the_product() -> None:
    """On fixed axes every mesh passes eta_k of its power on: eta = prod eta_k."""
    for seed in range(10):
        t = generate("chain", seed)
        spec = t.oracle()
        expected = F(1)
        for m in spec.meshes:
            expected *= m.eta
        for port in ("A", "B"):
            assert solve(spec, port, "run").efficiency == expected


def test_wolfrom_ratio_textbook() -> None:
    """Wolfrom (ring 1 fixed, sun in, ring 2 out, carrier free):
    i = (1 + R1/S) / (1 - R1 P2 / (P1 R2)) (catalog/wolfrom.yaml's textbook source)."""
    n = 0
    for seed in range(40):
        t = generate("wolfrom", seed)
        if (t.held, t.ports["A"], t.ports["B"]) != ("r1", "s", "r2"):
            continue
        r = {g.name: g.radius for g in t.gears}
        spec = t.oracle()
        assert solve(spec, "A", "run", lossless=True).speed_ratio == (1 + r["R1"] / r["S"]) / (
            1 - r["R1"] * r["P2"] / (r["P1"] * r["R2"])
        )
        n += 1
    assert n > 3


def test_simpson_ratios_textbook() -> None:
    """Simpson set (catalog/simpson.yaml's textbook source): 1st (R1 + R2 + S)/R1,
    2nd 1 + S/R1, 3rd 1 (and no loss), reverse -R2/S."""
    t = generate("simpson", 3)
    r = {g.name: g.radius for g in t.gears}
    spec = t.oracle()
    ratio = {s: solve(spec, i, s, lossless=True).speed_ratio for s, i, _ in t.cases()[::2]}
    assert ratio == {
        "first": (r["R1"] + r["R2"] + r["S"]) / r["R1"],
        "second": 1 + r["S"] / r["R1"],
        "third": 1,
        "reverse": -r["R2"] / r["S"],
    }
    assert solve(spec, "A", "third").efficiency == 1


@pytest.mark.parametrize("family", FAMILIES)
def test_power_balance_and_lossless_limit(family: str) -> None:
    """P_in + P_out = sum of mesh losses M_k (w_a - w_b) >= 0 (the tooth forces do no net
    work when the geometry agrees with the kinematics); eta = 1 exactly without losses and
    1 - efficiency -> 0 as the losses vanish."""
    for seed in range(6):
        t = generate(family, seed)
        spec = t.oracle()
        for state, port, _ in t.cases():
            try:
                r = solve(spec, port, state)
            except SelfLocking:
                continue
            assert r.power_in + r.power_out == sum(r.losses.values())
            assert all(v >= 0 for v in r.losses.values())
            assert 0 < r.efficiency <= 1
            ideal = solve(with_efficiencies(spec, F(1)), port, state)
            assert ideal.efficiency == 1
            gaps = [1 - solve(with_efficiencies(spec, 1 - F(1, 10**k)), port, state).efficiency for k in (2, 4, 6)]
            assert gaps[0] >= gaps[1] >= gaps[2] >= 0
            assert gaps[2] < F(1, 10**4)


def test_states_merge_members() -> None:
    """A brake joins a member to the housing, a clutch two members, free members vanish
    with their meshes."""
    spec = generate("simpson", 0).oracle()
    reverse = in_state(spec, "reverse")
    assert {m.name for m in reverse.members} == {"0", "s", "o", "p2"}
    assert [m.name for m in reverse.meshes] == ["E", "F"]
    third = in_state(spec, "third")
    assert len(third.members) == len(spec.members) - 1
