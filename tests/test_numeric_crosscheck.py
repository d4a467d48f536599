"""Independent numeric route: the same network solved with numpy at random parameters.

The matrices M_N and D_A are evaluated numerically; motions and actions come from
numpy's least-squares null-space solve (no symbolic elimination), and the efficiency
-P_out / P_in is compared with the symbolic one to 1e-12.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy

import davies_sym

from conftest import catalog_path, variant


def numeric_efficiency(a: davies_sym.Analysis, values: dict[sympy.Symbol, float]) -> float:
    net = a.network
    sigma = {s: 1.0 for s in a.sign_symbols.values()}
    subs = {**values, **sigma}
    MN = np.array(net.network_motion_matrix().subs(subs), dtype=float)
    k = net.motions.index(a.input_motion)
    # psi with the input speed fixed to 1: solve M_N[:, others] psi_others = -M_N[:, k].
    others = [j for j in range(MN.shape[1]) if j != k]
    psi_o, *_ = np.linalg.lstsq(MN[:, others], -MN[:, k], rcond=None)
    psi = np.insert(psi_o, k, 1.0)
    D = np.array(a.augmented_action_matrix.subs(subs), dtype=float)
    i = net.actions.index(a.input_action)
    others = [j for j in range(D.shape[1]) if j != i]
    Psi_o, *_ = np.linalg.lstsq(D[:, others], -D[:, i], rcond=None)
    Psi = np.insert(Psi_o, i, 1.0)

    def port_power(coupling: str) -> float:
        act = net.port_action(coupling)
        mot = net.coupling_motions(coupling)[0]
        pairing = float(sum(sympy.sympify(w * t).subs(subs) for w, t in zip(act.wrench, mot.twist, strict=True)))
        return Psi[net.actions.index(act)] * psi[net.motions.index(mot)] * pairing

    return -port_power(a.train.ports.output) / port_power(a.train.ports.input)


@pytest.mark.parametrize(
    "train",
    [
        davies_sym.load(catalog_path("simple_pair")),
        davies_sym.load(catalog_path("tuplin")),
        variant("tuplin", {"coulomb: zeta_C": "linear: zeta_C", "coulomb: zeta_D": "linear: zeta_D"}),
        variant(
            "simple_pair",
            {"A: {type: revolute, links: [0, 1]}": "A: {type: revolute, links: [0, 1], friction: {coulomb: zeta_A}}"},
        ),
    ],
    ids=["simple_pair", "tuplin_coulomb", "tuplin_linear", "simple_pair_bearing"],
)
def test_symbolic_equals_numeric(train, rng):
    a = davies_sym.analyse(train)
    eta = a.efficiency
    for _ in range(5):
        values = {}
        for s in sorted(a.ring.symbols, key=str):
            if s.name.startswith(("zeta", "b_")):
                values[s] = rng.uniform(0.01, 0.5)
            elif s.name.startswith("r"):
                values[s] = rng.uniform(5.0, 60.0)
        # Keep the planar constraint when there is one (r4 follows from the others).
        for c in a.network.layout.constraints:
            r = sympy.Symbol("r4", positive=True)
            if r in c.expression.free_symbols:
                values[r] = float(sympy.solve(c.expression, r)[0].subs(values))
        symbolic = float(eta.subs({**values, **{s: 1 for s in a.sign_symbols.values()}}))
        numeric = numeric_efficiency(a, values)
        assert abs(symbolic - numeric) <= 1e-12 * max(1.0, abs(symbolic))
