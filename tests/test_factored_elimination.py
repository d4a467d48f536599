"""Factored elimination (`davies_sym.algebra.factored`) against the expanded one
(`davies_sym.algebra.linalg.gauss_jordan`), which shares none of its arithmetic: on random
sparse systems of products of small polynomials, both give the same solution, the known
factorisation of every solution entry is exactly what flint's ``factor`` gives for the
expanded numerator and denominator (same content, factors and order, so the printed
formulas do not change), and products of rational functions formed factor by factor
equal the expanded products."""

from __future__ import annotations

import random

import pytest
import sympy

from davies_sym.algebra.factored import _reduced_expansion, factored_gauss_jordan, radical_elimination
from davies_sym.algebra.flint_conversion import factor
from davies_sym.algebra.linalg import WorkExceeded, gauss_jordan
from davies_sym.algebra.polynomials import PolynomialRing, RationalFunction
from davies_sym.algebra.radicals import Radical, radicals_form_a_field
from davies_sym.errors import DerivationError
from davies_sym.network.null_space import Swelling, eliminate

SYMBOLS = sympy.symbols("a b c d e", positive=True)


def _random_entry(ring: PolynomialRing, rng: random.Random):
    """A product of one to three small random polynomials (stages multiply), or a number."""
    if rng.random() < 0.4:
        return ring.one * rng.choice([-2, -1, 1, 1, 3])
    out = ring.one * rng.choice([-1, 1, 2])
    for _ in range(rng.randint(1, 3)):
        terms = {}
        for _ in range(rng.randint(1, 3)):
            monom = tuple(rng.randint(0, 1) for _ in SYMBOLS)
            terms[monom] = rng.choice([-3, -1, 1, 2])
        factor_poly = ring.ctx.from_dict(terms)
        if not factor_poly.is_zero():
            out = out * factor_poly
    return out


def _system(seed: int):
    rng = random.Random(seed)
    ring = PolynomialRing(SYMBOLS)
    n = rng.randint(3, 6)
    rows = []
    for _ in range(n - 1):
        row = {}
        for c in rng.sample(range(n), rng.randint(2, min(4, n))):
            row[c] = _random_entry(ring, rng)
        rows.append(row)
    return ring, rows, n


@pytest.mark.parametrize("seed", range(40))
def test_factored_and_expanded_elimination_agree(seed: int) -> None:
    ring, rows, n = _system(seed)
    plain = gauss_jordan([dict(r) for r in rows], n, prefer_free=[0])
    factored = factored_gauss_jordan([dict(r) for r in rows], n, ring.one, prefer_free=[0])
    assert factored.free == plain.free
    expected, got = plain.solution(ring), factored.solution(ring)
    for col in range(n):
        assert got[col].keys() == expected[col].keys(), col
        for j, value in got[col].items():
            assert value == expected[col][j]
            # Lowest terms, positive leading coefficient of the denominator: the same
            # numerator and denominator, and the factorisation flint gives for them.
            assert value.num == expected[col][j].num and value.den == expected[col][j].den
            (cn, fn), (cd, fd) = value.factorisation
            assert (cn, fn) == factor(value.num)
            assert (cd, fd) == factor(value.den)


@pytest.mark.parametrize("seed", range(40))
def test_products_by_factors_equal_expanded_products(seed: int) -> None:
    ring, rows, n = _system(seed)
    solution = factored_gauss_jordan(rows, n, ring.one, prefer_free=[0]).solution(ring)
    # Kept small: the check multiplies out and factors the products the plain way.
    values = [v for col in range(n) for v in solution[col].values() if not v.is_zero() and len(v.num) + len(v.den) < 60]
    if not values:
        pytest.skip("no small entry in this system")
    rng = random.Random(seed)
    small = RationalFunction.make(ring, ring.gen(SYMBOLS[0]) + 2, ring.gen(SYMBOLS[1]) * 3)
    for _ in range(5):
        a = rng.choice(values)
        b = rng.choice([*values, small])
        product = a * b
        plain = RationalFunction.make(ring, a.num * b.num, a.den * b.den)
        assert product.num == plain.num and product.den == plain.den
        assert product.factorisation == (factor(plain.num), factor(plain.den))
        assert product.to_expr() == plain.to_expr()
        assert (a / b) * b == a
        assert (-a).factorisation == (factor(-a.num), factor(a.den))


def _lazy(ring: PolynomialRing, rng: random.Random) -> RationalFunction:
    """A rational function built from factors and never expanded (as a stage product)."""
    num, den = _random_entry(ring, rng), _random_entry(ring, rng)
    if num.is_zero() or den.is_zero():
        num, den = ring.one, ring.one
    (cn, fn), (cd, fd) = factor(num), factor(den)
    out = RationalFunction.from_factors(ring, cn, cd, fn, fd)
    assert "num" not in out.__dict__
    return out


@pytest.mark.parametrize("seed", range(60))
def test_sums_by_factors_equal_expanded_sums_in_lowest_terms(seed: int) -> None:
    """a + b formed over the common denominator of the factors equals the sum of the
    expanded fractions reduced by their gcd (`RationalFunction.make`), with the
    factorisation flint gives for that sum; negation, inverse and evaluation at a point
    work on the factors without expanding them."""
    rng = random.Random(seed)
    ring = PolynomialRing(SYMBOLS)
    a, b = _lazy(ring, rng), _lazy(ring, rng)
    if rng.random() < 0.5:  # shared factors in the numerators and denominators
        c = _lazy(ring, rng)
        a, b = a * c, b * c
    point = {s: sympy.Rational(rng.randint(1, 9), rng.randint(1, 9)) for s in SYMBOLS}
    values = []
    for x in (a, b, -a, a.inverse() if not a.is_zero() else a):
        try:
            values.append(x.evaluate(point))
        except ZeroDivisionError:
            values.append(None)
        assert "num" not in x.__dict__ or x.is_zero()
    total = a + b
    plain = RationalFunction.make(ring, a.num * b.den + b.num * a.den, a.den * b.den)
    assert total.num == plain.num and total.den == plain.den
    if not plain.is_zero():
        assert total.factorisation == (factor(plain.num), factor(plain.den))
    expected = [RationalFunction.make(ring, a.num, a.den), RationalFunction.make(ring, b.num, b.den)]
    for got, want in zip(values, [*expected, -expected[0], expected[0].inverse()], strict=True):
        if got is not None:
            assert got == want.evaluate(point)


def test_a_large_sum_is_divided_by_the_denominator_factors_it_holds() -> None:
    """A numerator sum of more than SMALL_SUM terms stays one factor; where it is divisible
    by a factor of the common denominator, that factor cancels (lowest terms as make)."""
    ring = PolynomialRing(SYMBOLS)
    x = [ring.gen(s) for s in SYMBOLS]
    g = x[0] + 1
    big = (x[0] + x[1] + x[2] + x[3] + x[4] + 1) ** 6 * g  # 462 terms times g
    second = x[1] * x[2] + 3
    first = big - second * g  # first + second * g = big
    a = RationalFunction.from_factors(ring, *_parts(first), *_den(g))
    b = RationalFunction.from_factors(ring, 1, 1, [(second, 1)], [])
    total = a + b
    assert len(first) > 400
    assert total.den == ring.one and total.num == big / g
    assert total == RationalFunction.make(ring, first + second * g, g)


def _parts(p):
    content, factors = factor(p)
    return content, 1, factors


def _den(p):
    content, factors = factor(p)
    assert content == 1
    return ([(f, e) for f, e in factors],)


@pytest.mark.parametrize("seed", range(40))
def test_substitution_by_factors_equals_the_expanded_substitution(seed: int) -> None:
    """x -> n/d in a factored function (each factor f(n/d) d^k factored on its own) equals
    the substitution of the expanded numerator and denominator, reduced (`make`), with
    flint's factorisation of that result."""
    rng = random.Random(seed)
    ring = PolynomialRing(SYMBOLS)
    a = _lazy(ring, rng) * _lazy(ring, rng)
    value = _lazy(ring, rng)
    symbol = rng.choice(SYMBOLS)
    expr = a.to_expr(factored=False).subs(symbol, value.to_expr(factored=False))
    try:
        plain = ring.rational(sympy.together(expr))
    except DerivationError:  # the substitution divides by zero
        with pytest.raises(ZeroDivisionError):
            a.substitute({symbol: value})
        return
    got = a.substitute({symbol: value})
    assert got == plain
    assert got.num == plain.num and got.den == plain.den
    if not plain.is_zero():
        assert got.factorisation == (factor(plain.num), factor(plain.den))


@pytest.mark.parametrize("seed", range(30))
def test_simultaneous_substitution_equals_sympy_substitution(seed: int) -> None:
    """Two symbols replaced at once (each factor substituted in both and factored once)
    equals sympy's simultaneous substitution of the expanded expression, put in lowest
    terms, with flint's factorisation of that result; values free of the replaced
    symbols, as the meshes' zeta forms are."""
    rng = random.Random(1000 + seed)
    ring = PolynomialRing(SYMBOLS)
    x, y = rng.sample(SYMBOLS, 2)
    a = _lazy(ring, rng) * _lazy(ring, rng)
    values = {}
    for symbol in (x, y):
        value = _lazy(ring, rng)
        while value.free_symbols & {x, y}:
            value = value.substitute({x: RationalFunction.polynomial(ring, ring.one * rng.randint(2, 5))})
            value = value.substitute({y: RationalFunction.polynomial(ring, ring.one * rng.randint(2, 5))})
        values[symbol] = value
    expr = a.to_expr(factored=False).subs({s: v.to_expr(factored=False) for s, v in values.items()}, simultaneous=True)
    try:
        plain = ring.rational(sympy.together(expr))
    except DerivationError:  # the substitution divides by zero
        with pytest.raises(ZeroDivisionError):
            a.substitute(values)
        return
    got = a.substitute(values)
    assert got.num == plain.num and got.den == plain.den
    if not plain.is_zero():
        assert got.factorisation == (factor(plain.num), factor(plain.den))


RADICANDS = {"s": SYMBOLS[0] + SYMBOLS[1], "t": SYMBOLS[2] * SYMBOLS[3] + 1}


def _radical_system(seed: int):
    """A random sparse system whose entries hold the square root s^2 = a + b, and for
    seeds 1, 4, 7, 10 also t^2 = c d + 1 (products of small polynomials in a, ..., e, s,
    t; small, as the solution of a system with several roots in its pivots is large in
    lowest terms whichever way it is eliminated)."""
    rng = random.Random(1000 + seed)
    names = ("s", "t") if seed in (1, 4, 7, 10) else ("s",)
    roots = [Radical(sympy.Symbol(name, positive=True), RADICANDS[name]) for name in names]
    ring = PolynomialRing(SYMBOLS, roots)
    gens = [ring.gen(r.symbol) for r in roots]
    letters = [ring.gen(x) for x in SYMBOLS]
    n = rng.randint(3, 6)
    rows = []
    for _ in range(n - 1):
        row = {}
        for c in rng.sample(range(n), rng.randint(2, min(4, n))):
            value = ring.one * rng.choice([-1, 1, 2])
            for _ in range(rng.randint(0, 2)):
                value = value * (rng.choice(letters) + rng.choice(letters) * rng.choice([-1, 1, 3]))
            for g in gens:
                if rng.random() < 0.4:
                    value = value * (g + rng.choice([-1, 1, 2]))
            row[c] = value
        rows.append(row)
    return ring, rows, n


@pytest.mark.parametrize("seed", range(30))
def test_elimination_over_radicals_as_free_symbols_agrees_with_the_reduced_one(seed: int) -> None:
    """Where `radical_elimination` answers, it has the rank of the elimination modulo the
    relations at every step, and each of its null-space vectors (read back modulo
    s^2 = m) satisfies every equation modulo the relations: the same null space. Where
    it does not answer, a pivot vanishes modulo the relations."""
    ring, rows, n = _radical_system(seed)
    reduced = gauss_jordan([dict(r) for r in rows], n, prefer_free=[0], reduce=ring.reduce)
    free = radical_elimination(ring, [dict(r) for r in rows], n, prefer_free=[0])
    if free is None:
        return
    assert free.rank == reduced.rank
    solution = free.solution(ring)
    zero = RationalFunction.polynomial(ring, ring.zero)
    for j in free.free:
        vector = {c: solution[c].get(j, zero) for c in range(n)}
        for row in rows:
            total = zero
            for c, entry in row.items():
                total = total + RationalFunction.polynomial(ring, entry) * vector[c]
            assert total.is_zero(), (j, row)


def test_a_pivot_that_vanishes_modulo_its_radical_refuses_the_free_symbols() -> None:
    """Rows (s, 1) and (a, s) with s^2 = a are dependent: s (s, 1) = (a, s). Taken for a
    free symbol, s leaves the pivot s^2 - a, zero modulo the relation: no answer."""
    a = SYMBOLS[0]
    root = Radical(sympy.Symbol("s", positive=True), a)
    ring = PolynomialRing([a], [root])
    s, x = ring.gen(root.symbol), ring.gen(a)
    assert ring.reduce(s * s - x).is_zero()
    rows = [{0: s, 1: ring.one}, {0: x, 1: s}]
    assert gauss_jordan([dict(r) for r in rows], 2, reduce=ring.reduce).rank == 1
    assert radical_elimination(ring, rows, 2) is None


def test_radicals_form_a_field_unless_a_product_is_a_square() -> None:
    a, b, c = SYMBOLS[:3]
    root = [Radical(sympy.Symbol(f"s{k}", positive=True), m) for k, m in enumerate((a * b, b * c, a * c, a + b))]
    assert radicals_form_a_field(root[:2])
    assert radicals_form_a_field([root[0], root[3]])
    assert not radicals_form_a_field(root[:3])  # (a b)(b c)(a c) = (a b c)^2
    assert not radicals_form_a_field([Radical(sympy.Symbol("s", positive=True), 4 * a**2)])


def test_the_budget_counts_the_terms_formed_before_the_content_is_divided_out() -> None:
    """Eliminating x0 from [1, g] and [f, h] forms h - f g (64 terms here, a multiple of
    the row's content), which the content division leaves as 1: the work is the 64 terms,
    so a budget of 10 is exceeded although the rows kept hold one term each."""
    ring = PolynomialRing(sympy.symbols("a b c d", positive=True))
    a, b, c, d = (ring.gen(s) for s in ring.symbols)
    f = (a + b + c + d + 1) ** 2
    g = (a + 2 * b + 3 * c + 5 * d + 7) ** 2
    h = f * g + (a + b - c) ** 3 * (b + d + 2)
    rows = [{0: ring.one, 1: g}, {0: f, 1: h}]
    combined = h - f * g
    assert len(combined) > 10
    assert gauss_jordan([dict(r) for r in rows], 2).rank == 2
    with pytest.raises(WorkExceeded):
        gauss_jordan([dict(r) for r in rows], 2, budget=10)


def test_a_product_expanded_modulo_the_radicals_factor_by_factor_is_the_whole_reduced() -> None:
    """The read-back of the elimination over the roots as free symbols reduces after
    each factor: the canonical polynomial of the whole expansion reduced, at the pivots
    and entries of random systems with one or two square roots."""
    several = 0
    for seed in range(12):
        ring, rows, n = _radical_system(seed)
        free = radical_elimination(ring, [dict(r) for r in rows], n, prefer_free=[0])
        for p in [v for row in (free.pivots.values() if free else ()) for v in row.values()]:
            several += sum(e for _, e in p.factors) > 1
            assert _reduced_expansion(ring, p) == ring.reduce(p.expand_in(ring.one))
    assert several > 10


@pytest.mark.parametrize("seed", range(12))
def test_a_matrix_known_to_swell_is_solved_alike_by_the_factored_route(seed: int) -> None:
    """Where a sibling state's matrix swelled, `eliminate` goes straight to the
    elimination over the roots as free symbols: the same null space, column by column,
    as the route that tries the reduced elimination first."""
    ring, rows, n = _radical_system(seed)
    key = ("kept", (n - 1, n), 0, False, False)
    first = eliminate(ring, [dict(r) for r in rows], n, [0])
    straight = eliminate(ring, [dict(r) for r in rows], n, [0], swelling=Swelling({key}, key))
    assert first.free == straight.free
    a, b = first.solution(ring), straight.solution(ring)
    for c in range(n):
        assert a[c] == b[c]
