"""The ZF 8HP70 eight-speed automatic transmission of benchmarks/eight_speed.yaml.

Published ratios of the 8HP70 (2008 pilot series; Wikipedia, "ZF 8HP transmission",
gear-ratio table): 1st 4.696, 2nd 3.130, 3rd 2.104, 4th 1.667, 5th 1.285, 6th 1.000,
7th 0.839, 8th 0.667, reverse -3.297, for the tooth numbers S1/R1 48/96, S2/R2 48/96,
S3/R3 69/111, S4/R4 23/85 of the article's in-depth table; the connections of the sets are
those of the 8HP service information (see the header of the file).

Checked per gear: the engine's speed ratio is the published one (to its rounding); every
variant is exactly 1 when every mesh efficiency is 1; and an independent model written here
(Willis's equation per set, shaft torque balances, each set's carrier-frame power direction
from its lossless torques) gives the same speed ratio, a lossless torque ratio equal to the
speed ratio, and the engine's efficiency exactly.
"""

from __future__ import annotations

import functools
import os

import pytest
import sympy

import davies_sym

from conftest import ROOT

PATH = os.path.join(ROOT, "benchmarks", "eight_speed.yaml")

PUBLISHED = {
    "first": 4.696,
    "second": 3.130,
    "third": 2.104,
    "fourth": 1.667,
    "fifth": 1.285,
    "sixth": 1.000,
    "seventh": 0.839,
    "eighth": 0.667,
    "reverse": -3.297,
}

#: (sun, ring) teeth of sets 1 to 4, and the shaft each set member is on.
TEETH = {1: (48, 96), 2: (48, 96), 3: (69, 111), 4: (23, 85)}
SHAFT = {
    "C2": "in",
    "S1": "s12",
    "S2": "s12",
    "R1": "r1",
    "C1": "c1r4",
    "R4": "c1r4",
    "R2": "r2s3",
    "S3": "r2s3",
    "R3": "r3s4",
    "S4": "r3s4",
    "C3": "c3",
    "C4": "out",
}
ETAS = sorted(f"eta_{m}{k}" for m in "sr" for k in TEETH)


def mesh_efficiencies(k: int) -> dict[str, sympy.Rational]:
    """Different lossy values for every mesh: eta_s<k> = 1 - k/100, eta_r<k> = 1 - k/300."""
    return {f"eta_s{k}": 1 - sympy.Rational(k, 100), f"eta_r{k}": 1 - sympy.Rational(k, 300)}


LOSSY = {name: value for k in TEETH for name, value in mesh_efficiencies(k).items()}


@functools.cache
def train() -> davies_sym.Train:
    return davies_sym.load(PATH)


@functools.cache
def derived(state: str) -> davies_sym.VariantSet:
    """Every variant of one gear, derived once per process (each xdist worker derives only
    the gears of its own tests)."""
    return davies_sym.derive(davies_sym.train_in_state(train(), train().state(state)))


def independent_model(state: davies_sym.State) -> tuple[sympy.Rational, sympy.Rational, sympy.Rational]:
    """(speed ratio, -output torque / input torque without losses, efficiency at LOSSY) of
    one gear, from the shift elements alone: no code of the engine."""
    parent = {s: s for s in [*SHAFT.values(), "0"]}

    def find(s: str) -> str:
        while parent[s] != s:
            s = parent[s]
        return s

    for link in state.brake:
        parent[find(link)] = find("0")
    for a, b in state.clutch:
        parent[find(b)] = find(a)
    shafts = sorted({find(s) for s in parent} - {find("0")})
    speed = {s: sympy.Symbol(f"w_{s}") for s in shafts} | {find("0"): sympy.Integer(0)}
    willis = [zs * speed[find(SHAFT[f"S{k}"])] + zr * speed[find(SHAFT[f"R{k}"])] for k, (zs, zr) in TEETH.items()]
    willis = [w - sum(TEETH[k]) * speed[find(SHAFT[f"C{k}"])] for k, w in zip(TEETH, willis, strict=True)]
    solved = sympy.solve([*willis, speed[find("in")] - 1], [speed[s] for s in shafts], dict=True)[0]
    w = {m: speed[find(s)].subs(solved) for m, s in SHAFT.items()}

    def torques(gain: dict[int, sympy.Expr]) -> tuple[list[sympy.Expr], sympy.Expr]:
        """Set k takes t_k on its sun, t_k z_R/z_S gain_k on its ring and the rest on its
        carrier; each shaft's torques balance its external torque (1 in, T_out out)."""
        t, t_out = sympy.symbols("t1:5"), sympy.Symbol("t_out")
        on = {}
        for k, (zs, zr) in TEETH.items():
            on[f"S{k}"], on[f"R{k}"] = t[k - 1], t[k - 1] * sympy.Rational(zr, zs) * gain[k]
            on[f"C{k}"] = -on[f"S{k}"] - on[f"R{k}"]
        external = {find("in"): 1, find("out"): t_out}
        balance = [sum(on[m] for m in SHAFT if find(SHAFT[m]) == s) - external.get(s, 0) for s in shafts]
        result = sympy.solve(balance, [*t, t_out], dict=True)[0]
        return [result.get(x, sympy.Integer(0)) for x in t], result[t_out]

    lossless, t_out = torques(dict.fromkeys(TEETH, sympy.Integer(1)))
    gain = {}
    for k in TEETH:
        # Power of the sun in the carrier frame: > 0, the sun drives (sun -> planet -> ring).
        sun_power = lossless[k - 1] * (w[f"S{k}"] - w[f"C{k}"])
        eta = LOSSY[f"eta_s{k}"] * LOSSY[f"eta_r{k}"]
        gain[k] = sympy.Integer(1) if sun_power == 0 else eta if sun_power > 0 else 1 / eta
    lossy, t_out_lossy = torques(gain)
    for k in TEETH:  # the losses do not turn any set's power round
        assert sympy.sign(lossy[k - 1]) == sympy.sign(lossless[k - 1])
    return 1 / w["C4"], -t_out, -t_out_lossy * w["C4"]


def test_the_file_has_every_published_gear():
    assert [s.name for s in train().states] == list(PUBLISHED)


@pytest.mark.parametrize("state", list(PUBLISHED))
def test_speed_ratio_is_the_published_one(state):
    ratio = derived(state).analysis.speed_ratio().to_expr()
    assert ratio.is_Rational
    assert abs(float(ratio) - PUBLISHED[state]) < 0.0015, (state, ratio)


@pytest.mark.parametrize("state", list(PUBLISHED))
def test_lossless_meshes_give_efficiency_one(state):
    vs = derived(state)
    ones = dict.fromkeys(ETAS, 1)
    assert vs.evaluate(ones, "IN") == 1
    assert vs.evaluate(ones, "OUT") == 1
    for v in vs.variants:
        assert v.efficiency.subs({s: 1 for s in v.efficiency.free_symbols}) == 1, (state, v.number)


@pytest.mark.parametrize("state", list(PUBLISHED))
def test_independent_torque_balance(state):
    vs = derived(state)
    ratio, torque_ratio, efficiency = independent_model(train().state(state))
    assert ratio == vs.analysis.speed_ratio().to_expr()
    assert torque_ratio == ratio  # lossless: output power = input power
    assert vs.evaluate(LOSSY, "IN") == efficiency
    assert 0 < efficiency <= 1
