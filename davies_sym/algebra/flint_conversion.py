"""Between sympy expressions and python-flint polynomials, without sympy's polynomial
machinery: an expression is read off its tree (sums, products, integer powers, symbols,
rationals) with flint arithmetic, and a polynomial is written back one term at a time.
Also the factoring of a sympy polynomial by flint, for the sign reasoning that works on
expressions (`davies_sym.algebra.signs`)."""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Hashable, Mapping, Sequence
from math import gcd, lcm

import sympy
from flint import fmpz_mpoly, fmpz_mpoly_ctx

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.errors import DerivationError

#: Factorisations already found, by context and polynomial terms (most recent last): the
#: turning conditions, loaded forces and sums of one derivation factor the same
#: polynomials again and again (some ten times each on a 7-link planetary train).
_FACTORED: OrderedDict[tuple[fmpz_mpoly_ctx, Hashable], tuple[int, tuple[tuple[fmpz_mpoly, int], ...]]] = OrderedDict()
_FACTORED_LIMIT = 4096


def polynomial_key(p: fmpz_mpoly) -> tuple[tuple[tuple[int, ...], ...], tuple[int, ...]]:
    """``p``'s terms (exponents, coefficients) as a hashable value.  Not its text:
    python-flint 0.9 keeps the buffer of every polynomial it writes as text (some 5 kB
    each), which a process deriving thousands of files never gets back."""
    return tuple(p.monoms()), tuple(map(int, p.coeffs()))


def factor(p: fmpz_mpoly) -> tuple[int, list[tuple[fmpz_mpoly, int]]]:
    """Content and irreducible factors of ``p`` (flint); a polynomial factored before is
    looked up (a pure function's memo, bounded: flint polynomials are immutable)."""
    key = (p.context(), polynomial_key(p))
    found = _FACTORED.get(key)
    if found is None:
        found = _FACTORED[key] = _factored(p)
        if len(_FACTORED) > _FACTORED_LIMIT:
            _FACTORED.popitem(last=False)
    else:
        _FACTORED.move_to_end(key)
    return found[0], list(found[1])


def _factored(p: fmpz_mpoly) -> tuple[int, tuple[tuple[fmpz_mpoly, int], ...]]:
    """Content and irreducible factors of ``p`` (flint), also where python-flint 0.9 cannot
    order factors whose coefficients exceed a C long (OverflowError in its sort key):
    then sympy factors the same polynomial, a rare and slower path.  A polynomial of
    degree at most one is its content times its primitive part, which is irreducible (the
    sign put in the content so that the factor leads positively, as flint writes it)."""
    if p.total_degree() <= 1:
        coefficients = [int(c) for c in p.coeffs()]
        if not coefficients:
            return 0, ()
        content = gcd(*coefficients) * (1 if coefficients[0] > 0 else -1)
        return (content, ()) if p.is_constant() else (content, ((p / content, 1),))
    try:
        whole, factors = p.factor()
    except OverflowError:
        ctx = p.context()
        gens = sympy.symbols([f"x{i}" for i in range(len(ctx.names()))])
        poly = sympy.Poly.from_dict({m: int(c) for m, c in zip(p.monoms(), p.coeffs(), strict=True)}, gens, domain="ZZ")
        whole, parts = poly.factor_list()
        return int(whole), tuple((ctx.from_dict({m: int(c) for m, c in f.as_dict().items()}), int(e)) for f, e in parts)
    return int(whole), tuple((f, int(e)) for f, e in factors)


def expanded_expr(p: fmpz_mpoly, symbols: Sequence[sympy.Expr]) -> sympy.Expr:
    """``p`` as an expanded sympy expression in ``symbols`` (the generators' order)."""
    # One Mul per term and one Add in all: repeated ``*=`` re-flattens every product.
    terms = [
        sympy.Mul(
            sympy.Integer(int(coeff)),
            *(sym ** int(exp) for sym, exp in zip(symbols, monom, strict=False) if exp),
        )
        for monom, coeff in zip(p.monoms(), p.coeffs(), strict=True)
    ]
    return sympy.Add(*terms)


class ExpressionConverter:
    """Sympy rational expressions as pairs of integer polynomials of one flint context."""

    def __init__(self, ctx: fmpz_mpoly_ctx, gens: Mapping[sympy.Symbol, fmpz_mpoly]):
        self.ctx = ctx
        self._gens = gens
        #: Expressions already converted (matrix entries repeat: +-1, radii, sums of radii).
        self._converted: dict[sympy.Expr, tuple[fmpz_mpoly, fmpz_mpoly]] = {}

    def fraction(self, expr: sympy.Expr) -> tuple[fmpz_mpoly, fmpz_mpoly]:
        """``expr`` as integer polynomials ``(num, den)``, read off its tree (sums,
        products, integer powers, symbols, rationals) with flint arithmetic: no sympy
        ``Poly``, ``together`` or ``expand``, whose cost grows with the number of symbols.
        The pair is not reduced; `RationalFunction.make` divides by the gcd."""
        known = self._converted.get(expr)
        if known is not None:
            return known
        one = self.ctx.constant(1)
        if expr.is_Symbol:
            gen = self._gens.get(expr)
            if gen is None:
                raise DerivationError(f"symbols [{str(expr)!r}] are not in the polynomial ring")
            out = (gen, one)
        elif expr.is_Rational or expr.is_Float:
            value = sympy.Rational(expr)
            out = (self.ctx.constant(int(value.p)), self.ctx.constant(int(value.q)))
        elif expr.is_Add:
            num, den = self.fraction(expr.args[0])
            for term in expr.args[1:]:
                n, d = self.fraction(term)
                if d == den:
                    num = num + n
                elif d.is_constant() and den.is_constant():
                    a, b = int(den.leading_coefficient()), int(d.leading_coefficient())
                    common = lcm(a, b)
                    num, den = num * (common // a) + n * (common // b), self.ctx.constant(common)
                else:
                    num, den = num * d + n * den, den * d
            out = (num, den)
        elif expr.is_Mul:
            num, den = one, one
            for factor_ in expr.args:
                n, d = self.fraction(factor_)
                num, den = num * n, den * d
            out = (num, den)
        elif expr.is_Pow and expr.exp.is_Integer:
            n, d = self.fraction(expr.base)
            k = int(expr.exp)
            out = (n**k, d**k) if k >= 0 else (d ** (-k), n ** (-k))
            if out[1].is_zero():
                raise DerivationError(f"{expr} divides by zero")
        else:
            raise DerivationError(f"{expr} is not a rational function of the train's symbols")
        self._converted[expr] = out
        return out


def factor_expression(expr: sympy.Expr) -> tuple[int, list[tuple[sympy.Expr, int]]]:
    """The sign of the content and the irreducible factors of the rational expression
    ``expr`` (the denominator's with negative exponents), factored by flint: sympy's
    ``factor_list`` gives the same factors up to sign, many times slower in several
    symbols."""
    expr = sympy.sympify(expr)
    symbols = sorted_symbols(expr.free_symbols)
    if not symbols:
        value = sympy.Rational(expr)
        return (1 if value > 0 else -1 if value < 0 else 0), []
    ctx = fmpz_mpoly_ctx.get(tuple(f"x{i}" for i in range(len(symbols))), "degrevlex")
    num, den = ExpressionConverter(ctx, dict(zip(symbols, ctx.gens(), strict=True))).fraction(expr)
    if num.is_zero():
        return 0, []
    sign, out = 1, []
    for part, direction in ((num, 1), (den, -1)):
        content, factors = factor(part)
        sign *= 1 if content > 0 else -1
        out += [(expanded_expr(f, symbols), direction * e) for f, e in factors]
    return sign, out
