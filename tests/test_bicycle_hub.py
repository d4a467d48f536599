"""The bicycle drivetrain of the catalog (catalog/bicycle_hub.yaml) against its hand
derivation, at random rational points, exactly.

Chain (chainring F, z_F teeth, on the crank; sprocket Q, z_Q teeth, on the hub's
driver; both axes held by the frame): omega_c z_F = omega_d z_Q, the same sense, and the
chain passes eta_K of the power (it is its ordinary efficiency, the frame being the link
that holds both axes).

Hub (Willis): sun S on the axle (the frame), planets P on the carrier k, ring R, with
R = S + 2P in teeth.  Seen from the carrier the ring and the sun turn in opposite senses,
(omega_r - omega_k) R = -(omega_s - omega_k) S, and omega_s = 0:

* low (driver to ring, carrier to hub): omega_k / omega_r = R / (R + S).  Seen from the
  carrier the ring drives (its torque and relative speed agree) and the sun is driven, so
  with eta_0 = eta_C eta_D (ring-planet and planet-sun meshes) the torque on the sun is
  T_s = eta_0 T_r (omega_r - omega_k) / omega_k and the hub delivers
  (T_r + T_s) omega_k: eta_hub = (R + eta_0 S) / (R + S) (Laus section 3.1, Table 5: the
  sun-planet mesh is driven by the planet, the ring drives the planet).
* normal (driver, ring and hub clutched): the planetary set runs idle, eta_hub = 1, ratio 1.
* high (driver to carrier, ring to hub): omega_r / omega_k = (R + S) / R; seen from the
  carrier the sun drives, the ring is driven: T_r (omega_r - omega_k) = eta_0 T_s omega_k
  and eta_hub = eta_0 (R + S) / (eta_0 R + S).

The train (crank in, hub shell out): speed ratio omega_c / omega_h = (z_Q / z_F) times the
driver's speed over the hub's, R+S over R (low), 1, R over R+S (high); efficiency
eta_K eta_hub.  Driven backwards (the wheel driving the crank) every member's role turns
over: low gives eta_K eta_0 (R + S) / (eta_0 R + S), high eta_K (R + eta_0 S) / (R + S).
As every loss goes (eta_K, eta_C, eta_D -> 1) the efficiency tends to 1.
"""

from __future__ import annotations

import random

import pytest
import sympy

import davies_sym
from davies_sym.topology.states import train_in_state

from conftest import catalog_path

zF, zQ, zS, zP = (sympy.Symbol(n, positive=True) for n in ("zF", "zQ", "zS", "zP"))
eta_K, eta_C, eta_D = (sympy.Symbol(n, positive=True) for n in ("eta_K", "eta_C", "eta_D"))
R, S = zS + 2 * zP, zS
ETA_0 = eta_C * eta_D
LOW = eta_K * (R + ETA_0 * S) / (R + S)
HIGH = eta_K * ETA_0 * (R + S) / (ETA_0 * R + S)

#: state -> (speed ratio crank over hub, efficiency crank driving, efficiency hub driving)
HAND = {
    "low": ((zQ / zF) * (R + S) / R, LOW, HIGH),
    "normal": (zQ / zF, eta_K, eta_K),
    "high": ((zQ / zF) * R / (R + S), HIGH, LOW),
}


def _points(count: int = 6, seed: int = 11) -> list[dict[sympy.Symbol, sympy.Rational]]:
    rng = random.Random(seed)
    return [
        {
            zF: sympy.Integer(rng.randint(28, 53)),
            zQ: sympy.Integer(rng.randint(11, 28)),
            zS: sympy.Integer(rng.randint(12, 40)),
            zP: sympy.Integer(rng.randint(10, 30)),
            eta_K: sympy.Rational(rng.randint(80, 99), 100),
            eta_C: sympy.Rational(rng.randint(80, 99), 100),
            eta_D: sympy.Rational(rng.randint(80, 99), 100),
        }
        for _ in range(count)
    ]


def _variants(state: str) -> davies_sym.VariantSet:
    train = davies_sym.load(catalog_path("bicycle_hub"))
    return davies_sym.derive(train_in_state(train, train.state(state)))


def _by_name(values: dict[sympy.Symbol, sympy.Rational], names: list[sympy.Symbol]) -> dict:
    """``values`` keyed by the derived set's own symbols (matched by name)."""
    given = {str(k): v for k, v in values.items()}
    return {s: given[str(s)] for s in names if str(s) in given}


@pytest.mark.parametrize("state", sorted(HAND))
def test_each_gear_is_the_hand_derivation_exactly(state: str) -> None:
    variants = _variants(state)
    ratio, forward, backward = HAND[state]
    derived_ratio = variants.analysis.speed_ratio().to_expr()
    symbols = sorted(set(variants.parameters) | derived_ratio.free_symbols, key=str)
    for values in _points():
        point = _by_name(values, list(symbols))
        assert sympy.simplify(derived_ratio.subs(point) - ratio.subs(values)) == 0
        for port, hand in (("A", forward), ("H", backward)):
            variant = next(v for v in variants.variants if v.input == port)
            assert sympy.simplify(variant.efficiency.subs(point) - hand.subs(values)) == 0, (state, port)


@pytest.mark.parametrize("state", sorted(HAND))
def test_lossless_limit_is_one(state: str) -> None:
    variants = _variants(state)
    for variant in variants.variants:
        lossless = {s: 1 for s in variant.efficiency.free_symbols if str(s).startswith("eta")}
        assert sympy.simplify(variant.efficiency.subs(lossless)) == 1


def test_chain_centre_distance_enters_no_formula() -> None:
    for state in HAND:
        variants = _variants(state)
        assert "L_K" not in {str(s) for s in variants.parameters}
        assert all("L_K" not in {str(s) for s in v.efficiency.free_symbols} for v in variants.variants)
