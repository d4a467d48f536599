"""The lossy oracle (tests/oracle/lossy_balance.py) checked against closed forms derived by hand
(in the docstrings), with the power balance ``P_in + P_out = sum of losses`` in every case.
Nothing here uses the package.

Notation: pitch radii r, mesh efficiency eta_C, Buckingham's force-line offset for an external
mesh with driver i and driven j (Mantriota & Pennestri 2003, eq. 9a)
``delta = (1 - eta_C) r_i r_j / (eta_C r_j + r_i)``: the tangential tooth force F has the lever
``r_i + delta`` on the driver and ``r_j - delta`` on the driven gear, so that the torque ratio
times the speed ratio is eta_C; the bearing of a gear on a fixed axis takes the force F.
"""

from __future__ import annotations

from fractions import Fraction as F

import pytest
from oracle.balance import DescriptionError, Gear, Member, Mesh, MobilityProblem
from oracle.lossy_balance import (
    AmbiguousSolution,
    Bearing,
    LossyResult,
    LossyTrain,
    NoConsistentSolution,
    solve,
    sr20,
    sr20_at_row,
)

R1, R2 = F(3), F(5)
ETA = F(97, 100)


def balanced(r: LossyResult) -> LossyResult:
    """Every case: P_in + P_out = sum of losses (exactly), and every loss is >= 0."""
    assert r.power_in + r.power_out == r.total_loss
    assert all(v >= 0 for v in r.losses.values())
    assert r.efficiency == -r.power_out / r.power_in
    return r


def delta(eta: F, ri: F, rj: F) -> F:
    return (1 - eta) * ri * rj / (eta * rj + ri)


def pair(eta: F = ETA, *bearings: Bearing, reverse: bool = False) -> LossyTrain:
    """Gear 1 (r1) on g1 at y = 0, gear 2 (r2) on g2 at y = r1 + r2, both on the housing."""
    members = (Member("0"), Member("g1"), Member("g2", None, (F(0), R1 + R2)))
    mesh = Mesh("C", ("2", "1") if reverse else ("1", "2"), eta)
    return LossyTrain(
        "pair", members, (Gear("1", "g1", R1), Gear("2", "g2", R2)), (mesh,), "0", {"in": "g1", "out": "g2"}, bearings
    )


@pytest.mark.parametrize("reverse", [False, True])
@pytest.mark.parametrize(("w1", "load"), [(100, 7), (100, 70), (-40, -7)])
def test_pair_coulomb_on_input_bearing(reverse: bool, w1: int, load: int) -> None:
    """Fixed-axis pair, input gear 1 at w1, resisting load T_out on gear 2 (T_out w2 < 0, with
    w2 = -(r1/r2) w1), Coulomb friction circle rho1 on gear 1's bearing.

    Gear 2: (r2 - delta) F = |T_out|, so F = |T_out| / (r2 - delta).  Gear 1 is pushed back by F at
    the lever r1 + delta, and its bearing takes the reaction F (force balance of gear 1), hence the
    friction couple rho1 F against its motion: T_in = (r1 + delta + rho1) F.  Then
    P_in = T_in |w1|, P_out = -|T_out| (r1/r2) |w1| and

        eta = (r2 - delta) r1 / (r2 (r1 + delta + rho1)) = eta_C (r1 + delta) / (r1 + delta + rho1),

    using eta_C = (r2 - delta) r1 / (r2 (r1 + delta)) (eq. 7a).  Independent of the load."""
    rho1 = F(1, 10)
    r = balanced(solve(pair(ETA, Bearing("g1", rho=rho1), reverse=reverse), {"in": w1}, "out", load))
    d = delta(ETA, R1, R2)
    force = abs(F(load)) / (R2 - d)
    assert r.speeds["g2"] == -R1 / R2 * w1
    assert abs(r.reactions["g1"]) == force
    assert abs(r.torques["in"]) == (R1 + d + rho1) * force
    assert r.efficiency == ETA * (R1 + d) / (R1 + d + rho1)
    assert r.losses["coulomb g1"] == rho1 * force * abs(w1)
    assert r.iterations >= 1


def test_pair_coulomb_without_mesh_loss() -> None:
    """eta_C = 1 (delta = 0): eta = r1 / (r1 + rho1)."""
    r = balanced(solve(pair(F(1), Bearing("g1", rho=F(1, 4))), {"in": 50}, "out", 3))
    assert r.efficiency == R1 / (R1 + F(1, 4))


@pytest.mark.parametrize("reverse", [False, True])
def test_pair_constant_drag_on_output(reverse: bool) -> None:
    """Constant drag D on gear 2 (resisting its motion), input gear 1 at w1 > 0, load T_out > 0
    (w2 < 0).  Gear 2's mesh torque takes T_out + D, so the mesh delivers P2 = (T_out + D)|w2| and
    P_in = P2 / eta_C; P_out = -T_out |w2|:

        eta = eta_C T_out / (T_out + D) = eta_C - D |w2| / P_in,

    which rises with the load towards eta_C."""
    drag, w1 = F(1, 2), 60
    w2 = R1 / R2 * w1
    values = []
    for load in (F(1), F(2), F(5), F(20), F(100)):
        r = balanced(solve(pair(ETA, Bearing("g2", drag=drag), reverse=reverse), {"in": w1}, "out", load))
        assert r.efficiency == ETA * load / (load + drag)
        assert r.efficiency == ETA - drag * w2 / r.power_in
        assert r.losses["drag g2"] == drag * w2
        values.append(r.efficiency)
    assert values == sorted(values) and len(set(values)) == len(values)
    assert values[-1] < ETA


def test_pair_viscous_on_both_bearings() -> None:
    """Viscous b1, b2 on both bearings.  Gear 2: mesh torque T_out + b2 |w2|, so the mesh delivers
    P2 = L + b2 w2^2 with L = T_out |w2| = -P_out; gear 1: P_in = P2 / eta_C + b1 w1^2:

        eta = eta_C L / (L + b2 w2^2 + eta_C b1 w1^2)."""
    b1, b2, w1, load = F(1, 200), F(1, 100), 40, F(9)
    w2 = R1 / R2 * w1
    r = balanced(solve(pair(ETA, Bearing("g1", viscous=b1), Bearing("g2", viscous=b2)), {"in": w1}, "out", load))
    big_l = load * w2
    assert r.efficiency == ETA * big_l / (big_l + b2 * w2**2 + ETA * b1 * w1**2)
    assert r.losses["viscous g1"] == b1 * w1**2 and r.losses["viscous g2"] == b2 * w2**2
    assert r.losses["mesh C"] == (1 - ETA) * (big_l + b2 * w2**2) / ETA


def planetary(eta1: F, eta2: F, rho: F, rs: F = F(3), rp: F = F(2), ring_first: bool = True) -> LossyTrain:
    """Sun s (rs) on the main axis, planet p (rp) on carrier c at y = rs + rp, ring (rs + 2 rp) fixed."""
    members = (Member("0"), Member("s"), Member("c"), Member("p", "c", (F(0), rs + rp)))
    gears = (Gear("S", "s", rs), Gear("P", "p", rp), Gear("R", "0", rs + 2 * rp, True))
    meshes = (Mesh("SP", ("S", "P"), eta1), Mesh("RP", ("R", "P") if ring_first else ("P", "R"), eta2))
    return LossyTrain("planetary", members, gears, meshes, "0", {"in": "s", "out": "c"}, (Bearing("p", rho=rho),))


@pytest.mark.parametrize("ring_first", [True, False])
@pytest.mark.parametrize(
    ("eta1", "eta2", "rho"),
    [
        (F(97, 100), F(98, 100), F(0)),
        (F(97, 100), F(98, 100), F(1, 5)),
        (F(1), F(1), F(1, 10)),
        (F(9, 10), F(8, 10), F(1, 3)),
    ],
)
def test_planetary_with_planet_bearing_friction(ring_first: bool, eta1: F, eta2: F, rho: F) -> None:
    """Sun input (w_s > 0), ring fixed, carrier output.  Kinematics: w_c = w_s rs / (2e), e = rs + rp,
    rr = rs + 2 rp; in the carrier frame the planet turns backwards (w_p - w_c < 0).

    Carrier frame: the sun drives the planet (delta1 = (1-eta1) rs rp / (eta1 rp + rs), eq. 9a), the
    planet drives the ring (internal, delta2 = (1-eta2) rp rr / (eta2 rr - rp), from eq. 9c).  Tooth
    forces on the planet f1 (sun side) and f2 (ring side) point the same way; the planet bearing
    takes |R| = f1 + f2 (= 2F without losses) and its friction couple rho |R| opposes the planet.
    Planet: (rp - delta1) f1 = (rp + delta2) f2 + rho (f1 + f2), so f2 = q f1 with
    q = (rp - delta1 - rho) / (rp + delta2 + rho).  Sun: T_s = (rs + delta1) f1.  Carrier: it
    takes f1 + f2 at the lever e, less the bearing couple: |T_c| = (e - rho)(f1 + f2).  Hence

        eta = (e - rho)(1 + q) rs / (2 e (rs + delta1)),

    and with rho = 0 the textbook (1 + eta1 eta2 k) / (1 + k), k = rr / rs."""
    rs, rp, w_s, load = F(3), F(2), 120, F(-50)
    rr, e = rs + 2 * rp, rs + rp
    r = balanced(solve(planetary(eta1, eta2, rho, rs, rp, ring_first), {"in": w_s}, "out", load))
    assert r.speeds["c"] == w_s * rs / (2 * e)
    d1, d2 = delta(eta1, rs, rp), (1 - eta2) * rp * rr / (eta2 * rr - rp)
    ratio = (rp - d1 - rho) / (rp + d2 + rho)
    assert r.efficiency == (e - rho) * (1 + ratio) * rs / (2 * e * (rs + d1))
    f1 = r.torques["in"] / (rs + d1)
    assert abs(r.reactions["p"]) == (1 + ratio) * f1
    assert -r.torques["out"] == (e - rho) * (1 + ratio) * f1
    if rho == 0:
        k = rr / rs
        assert r.efficiency == (1 + eta1 * eta2 * k) / (1 + k)
    if eta1 == eta2 == 1:
        assert r.losses["coulomb p"] == r.power_in + r.power_out


SPEEDS = [(309, 51), (658, 146), (327, 143), (100, 300)]


@pytest.mark.parametrize(("w_a", "w_k"), SPEEDS)
def test_sr20_lossless(w_a: int, w_k: int) -> None:
    """Tooth ratio z1 z3 / (z2 z4) = 36 20 / (32 45) = 1/2: in the carrier frame the output turns at
    half the sun speed, w_O - w_K = (w_A - w_K)/2, so w_O = (w_A + w_K)/2; the planet turns at
    w_p - w_K = -(36/32)(w_A - w_K).  Lossless virtual power T_A w_A + T_K w_K + T_O w_O = 0 for
    every (w_A, w_K) gives T_A = T_K = -T_O / 2."""
    r = balanced(solve(sr20(), {"A": w_a, "K": w_k}, "O", -30))
    assert r.speeds["o"] == F(w_a + w_k, 2)
    assert r.speeds["p"] - w_k == -F(36, 32) * (w_a - w_k)
    assert r.torques["A"] == r.torques["K"] == 15
    assert r.efficiency == 1 and r.total_loss == 0


@pytest.mark.parametrize(("w_a", "w_k"), SPEEDS[:3])
def test_sr20_mesh_losses_and_drag(w_a: int, w_k: int) -> None:
    """Both inputs driving, w_A > w_K > 0, load T_O < 0.  Drag D_X on d1, c, o (against the
    housing) and D_p on the planet (against the carrier).  Carrier frame: d1 drives the planet
    (eta1), the planet drives o (eta2); the planet (an idler) loses D_p |w_p - w_K| with
    |w_p - w_K| = (9/8)(w_A - w_K).  With T_A' = T_A - D_A and T_O' = T_O - D_O (the torques the
    meshes see), the carrier-frame powers give -T_O' (w_A - w_K)/2 = eta1 eta2 T_A' (w_A - w_K)
    - eta2 (9/8) D_p (w_A - w_K), so

        T_A = D_A - (T_O - D_O) / (2 eta1 eta2) + (9/8) D_p / eta1,

    and the housing takes only the drags: T_K = -T_A - T_O + D_A + D_K + D_O.  Without drag,
    eta = (w_A + w_K) / (2 w_K + (w_A - w_K) / (eta1 eta2)) whatever the load."""
    e1, e2, t_o = F(98, 100), F(97, 100), F(-30)
    drags = {"d1": F(1, 10), "c": F(2, 10), "o": F(15, 100), "p": F(5, 100)}
    r = balanced(solve(sr20(e1, e2, drag=drags), {"A": w_a, "K": w_k}, "O", t_o))
    t_a = drags["d1"] - (t_o - drags["o"]) / (2 * e1 * e2) + F(9, 8) * drags["p"] / e1
    assert r.torques["A"] == t_a
    assert r.torques["K"] == -t_a - t_o + drags["d1"] + drags["c"] + drags["o"]
    assert r.losses["drag p"] == drags["p"] * F(9, 8) * (w_a - w_k)
    assert r.first_drives == {"M1": True, "M2": False}  # gear 1 drives 2; gear 3 (second of M2) drives 4
    for load in (F(-5), F(-50)):
        plain = balanced(solve(sr20(e1, e2), {"A": w_a, "K": w_k}, "O", load))
        assert plain.efficiency == F(w_a + w_k) / (2 * w_k + (w_a - w_k) / (e1 * e2))


@pytest.mark.parametrize("load", [F(-3), F(-30)])
def test_sr20_carrier_faster_than_sun(load: F) -> None:
    """w_K > w_A: in the carrier frame the output gear o turns backwards against a resisting load,
    so o feeds power into the carrier-frame train and d1 takes it (gear 4 drives 3, gear 2 drives
    1): T_A (w_A - w_K) = -eta1 eta2 T_O (w_A - w_K)/2, i.e. T_A = -eta1 eta2 T_O / 2 and
    T_K = -T_A - T_O, hence eta = (w_A + w_K) / (eta1 eta2 w_A + (2 - eta1 eta2) w_K)."""
    e1, e2, w_a, w_k = F(98, 100), F(97, 100), 100, 300
    r = balanced(solve(sr20(e1, e2), {"A": w_a, "K": w_k}, "O", load))
    assert r.first_drives == {"M1": False, "M2": True}
    assert r.torques["A"] == -e1 * e2 * load / 2 and r.torques["K"] == -r.torques["A"] - load
    assert r.efficiency == F(w_a + w_k) / (e1 * e2 * w_a + (2 - e1 * e2) * w_k)


def test_sr20_at_csv_row_and_coulomb() -> None:
    """A row as read by the csv module (strings, Table I row 1); Coulomb friction everywhere only
    checked by the power balance, and it lowers the efficiency."""
    row = {"w_A": "309", "w_K": "51", "w_O": "180", "T_O": "-5.08"}
    p = sr20_at_row(row)
    assert (p.T_A, p.T_K, p.eta) == (F(254, 100), F(254, 100), 1)
    meshes = sr20_at_row(row, eta_1=F(98, 100), eta_2=F(98, 100))
    lossy = sr20_at_row(row, eta_1=F(98, 100), eta_2=F(98, 100), rho=F(1, 1000), drag={"p": F(1, 100)})
    balanced(lossy.result)
    assert lossy.result.losses["coulomb p"] > 0
    assert lossy.eta < meshes.eta < 1


@pytest.mark.parametrize(
    "train",
    [pair(F(1), Bearing("g1"), Bearing("g2")), planetary(F(1), F(1), F(0)), sr20(1, 1, drag=0, viscous=0, rho=0)],
    ids=["pair", "planetary", "sr20"],
)
def test_lossless_limit(train: LossyTrain) -> None:
    """All losses zero: eta = 1 and nothing is dissipated."""
    inputs = {"A": 309, "K": 51} if "A" in train.ports else {"in": 100}
    out = "O" if "O" in train.ports else "out"
    for lossless in (False, True):
        r = balanced(solve(train, inputs, out, -7 if out == "O" or train.name == "planetary" else 7, lossless))
        assert r.efficiency == 1 and r.total_loss == 0


def test_lossless_flag_ignores_losses() -> None:
    lossy = sr20(F(9, 10), F(9, 10), drag=1, viscous=F(1, 100), rho=F(1, 100))
    r = balanced(solve(lossy, {"A": 309, "K": 51}, "O", -30, lossless=True))
    assert r.efficiency == 1 and r.torques["A"] == 15


def test_jammed_and_indeterminate_trains() -> None:
    """Friction circle on gear 2 larger than its lever (rho2 = 2 r2): with a resisting load no sign
    assignment is consistent (the pair jams); with an aiding load both drivers are consistent and
    give different torques (statically indeterminate)."""
    jam = pair(ETA, Bearing("g2", rho=2 * R2))
    with pytest.raises(NoConsistentSolution):
        solve(jam, {"in": 100}, "out", 7)
    with pytest.raises(AmbiguousSolution):
        solve(jam, {"in": 100}, "out", -7)


def test_wrong_number_of_inputs() -> None:
    with pytest.raises(MobilityProblem):
        solve(sr20(), {"A": 309}, "O", -30)
    loose = pair()
    loose = LossyTrain("loose", (*loose.members, Member("x")), loose.gears, loose.meshes, "0", loose.ports)
    with pytest.raises(MobilityProblem):  # 3 moving members, 1 mesh: two degrees of freedom
        solve(loose, {"in": 1}, "out", 1)
    with pytest.raises(DescriptionError):
        solve(pair(), {"in": 1}, "in", 1)
    with pytest.raises(DescriptionError):
        solve(pair(), {"nowhere": 1}, "out", 1)
