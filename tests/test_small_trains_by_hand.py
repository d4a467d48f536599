"""Small trains written here (not from the references: an idler chain, a simple planetary,
a rack in the low-level screw form, gears sized by teeth and modules), each checked by an
independent route: hand-derived classic formulas, the power balance, the ideal limit, the
sign of the partial derivatives, relabelling and the low-level screw form."""

from __future__ import annotations

import sympy

import davies_sym

from conftest import S, catalog_path, equal, read_text

zC, zD = S("zeta_C", "friction"), S("zeta_D", "friction")

IDLER = """
name: idler chain on a frame
links: [0, 1, 2, 3]
gears:
  1: {link: 1, radius: r1}
  2: {link: 2, radius: r2}
  3: {link: 3, radius: r3}
couplings:
  A: {type: revolute, links: [0, 1]}
  B: {type: revolute, links: [0, 3]}
  I: {type: revolute, links: [0, 2]}
  C: {type: mesh, gears: [1, 2]}
  D: {type: mesh, gears: [2, 3]}
ports: {input: A, output: B}
"""

PLANETARY = """
name: simple planetary, ring fixed, sun in, carrier out
links: [0, s, p, c]
reference: 0
gears:
  R: {link: 0, radius: rr, internal: true}
  S: {link: s, radius: rs}
  P: {link: p, radius: rp}
couplings:
  A: {type: revolute, links: [0, s]}
  B: {type: revolute, links: [0, c]}
  C: {type: mesh, gears: [S, P]}
  D: {type: mesh, gears: [R, P]}
  E: {type: revolute, links: [p, c]}
ports: {input: A, output: B}
"""

RACK = """
name: rack and pinion in the low-level screw form
links: [0, 1, 2]
couplings:
  A: {type: revolute, links: [0, 1], at: 0}
  B: {type: prismatic, links: [0, 2], direction: x}
  C:
    type: screws
    links: [1, 2]
    motions: {t_C: {t: 1, u: r1}}
    actions: {U_C: {T: -r1, U: 1}}
    friction: {coulomb: zeta_C}
ports: {input: A, output: B}
"""


def mesh_external(r_driver, r_driven, zeta):
    """Ordinary efficiency of an external mesh, Laus eq. (32)."""
    return r_driver * (r_driven - zeta) / (r_driven * (r_driver + zeta))


def test_idler_chain_is_product_of_mesh_efficiencies():
    r1, r2, r3 = S("r1"), S("r2"), S("r3")
    a = davies_sym.analyse(davies_sym.loads(IDLER, "idler"))
    assert a.sign_conditions == []
    assert equal(a.efficiency, mesh_external(r1, r2, zC) * mesh_external(r2, r3, zD))


def test_planetary_matches_the_classic_formula():
    """Ring fixed, sun drives carrier: eta = (1 + g eta0) / (1 + g), g = R / r_s, with
    eta0 = eta_SP eta_PR the efficiency of the train with the carrier held (the sun
    drives the planet, the planet drives the ring, in the carrier frame)."""
    rs, rp, rr = S("rs"), S("rp"), S("rr")
    a = davies_sym.analyse(davies_sym.loads(PLANETARY, "planetary"))
    # The loop sun-planet-ring gives rr = rs + 2 rp, applied to the gears (no constraint left).
    (relation,) = a.train.dependent or ()
    assert relation.symbol == rr and equal(relation.expression, rs + 2 * rp)
    assert a.network.layout.constraints == ()
    assert a.sign_conditions == []
    # Speed ratio: w_carrier / w_sun = rs / (rs + rr).
    ratio = a.motion_magnitudes["t_B"].to_expr() / a.motion_magnitudes["t_A"].to_expr()
    assert equal(ratio, rs / (rs + rr), {rr: rs + 2 * rp})
    eta_sp = mesh_external(rs, rp, zC)
    # Internal mesh, planet drives ring: Laus eq. (73) written for a positive Coulomb
    # coefficient (the linear law of eqs. (63)-(64) has zeta_D -> -zeta_D here).
    eta_pr = rp * (rr + zD) / (rr * (rp + zD))
    g = rr / rs
    assert equal(a.efficiency, (1 + g * eta_sp * eta_pr) / (1 + g), {rr: rs + 2 * rp})


def test_invariants_on_every_train():
    """B Q^T = 0, powers sum to zero (Tellegen), eta -> 1 without friction and
    d eta / d zeta < 0 at a nominal point."""
    trains = [
        davies_sym.loads(IDLER, "idler"),
        davies_sym.loads(PLANETARY, "planetary"),
        davies_sym.load(catalog_path("simple_pair")),
        davies_sym.load(catalog_path("tuplin")),
        davies_sym.loads(RACK, "rack"),
    ]
    for train in trains:
        a = davies_sym.analyse(train)
        net = a.network
        B = net.circuit_matrix()
        assert sympy.zeros(B.rows, len(net.tree)) == B * net.cutset_matrix().T
        total = sum((a.power_rf(c.name) for c in train.couplings[1:]), a.power_rf(train.couplings[0].name))
        assert total.is_zero(), train.name
        zetas = [s for s in a.efficiency.free_symbols if s.name.startswith("zeta")]
        assert equal(a.efficiency.subs({z: 0 for z in zetas}), 1), train.name
        nominal = {
            s: sympy.Rational(10 + 7 * i, 1)
            for i, s in enumerate(sorted(a.ring.symbols, key=str))
            if s.name.startswith("r")
        }
        if "rr" in {s.name for s in nominal}:
            nominal[S("rr")] = nominal[S("rs")] + 2 * nominal[S("rp")]
        if "r4" in {s.name for s in nominal}:
            nominal[S("r4")] = nominal[S("r2")] - nominal[S("r1")] + nominal[S("r3")]
        nominal.update({z: sympy.Rational(1, 10) for z in zetas})
        signs = {c.symbol: sympy.sign(c.expression.subs(nominal)) for c in a.sign_conditions}
        eta = a.efficiency.subs(signs)
        for z in zetas:
            assert sympy.diff(eta, z).subs(nominal) < 0, (train.name, z)


def test_relabelling_links_and_reordering_couplings_changes_nothing():
    text = read_text(catalog_path("tuplin"))
    renamed = text
    for old, new in (
        ("3/4", "planet"),
        ("link: 1,", "link: housing,"),
        ("[1, 5]", "[housing, 5]"),
        ("[1, 2]", "[housing, 2]"),
        ("reference: 1", "reference: housing"),
        ("  1: {desc", "  housing: {desc"),
    ):
        renamed = renamed.replace(old, new)
    lines = renamed.splitlines()
    start = lines.index("couplings:")
    block = lines[start + 1 : start + 6]
    reordered = "\n".join(lines[: start + 1] + block[::-1] + lines[start + 6 :]) + "\n"
    base = davies_sym.analyse(davies_sym.load(catalog_path("tuplin"))).efficiency
    other = davies_sym.analyse(davies_sym.loads(reordered, "renamed"))
    assert other.train.reference == "housing"
    # Reordered couplings place the planet through mesh D (at r2 - r4) instead of C: the two
    # results agree on the geometric constraint r1 - r3 = r2 - r4.
    assert equal(other.efficiency, base, {S("r3"): S("r1") - S("r2") + S("r4")})


def test_rack_and_pinion_in_low_level_form():
    """A prismatic rack driven by a pinion, contact written as explicit screws (as in
    Laus App. B): the simple-pair formula with r2 -> infinity, eta = r1 / (r1 + zeta)."""
    r1 = S("r1")
    a = davies_sym.analyse(davies_sym.loads(RACK, "rack"))
    assert a.network.order == 2 and a.network.system.twist_names == ("t", "u")
    assert equal(a.efficiency, r1 / (r1 + zC))
    assert equal(a.motion_magnitudes["u_B"].to_expr() / a.motion_magnitudes["t_A"].to_expr(), -r1)


def test_teeth_and_modules_give_radii_and_decide_the_signs():
    """Laus section 3.4.1.6: z = 80, 60, 30, 35 with modules 1 and 2 mm give r = 40, 60,
    15, 35 mm, which close the loop (no constraint left) and decide r1 < r2."""
    text = read_text(catalog_path("tuplin"))
    for g, z, m in (("1", 80, 1), ("2", 60, 2), ("3", 30, 1), ("4", 35, 2)):
        radius = f"r{g}"
        text = text.replace(f"radius: {radius}", f"teeth: {z}, module: {m}")
    a = davies_sym.analyse(davies_sym.loads(text, "tuplin-teeth"))
    assert [g.radius for g in a.train.gears] == [40, 60, 15, 35]
    assert a.network.layout.constraints == ()
    assert a.sign_conditions == []
    assert a.coulomb_sign_values == {"C": -1, "D": 1}
