"""How the train's symbols are typeset: the quantity's letter with the rest of the name
as its subscript, as the references write them (``rp1`` is Laus's `r_{p1}`, not
`r \\cdot p_1`; ``eta_C`` is `\\eta_C`; ``zeta_G1`` is `\\zeta_{G1}`).

sympy alone typesets ``rp1`` as ``rp_{1}``, which a reader takes for a product.  Every
output that shows mathematics (LaTeX documents, the documentation site's MathML, the
notebook representations) uses `latex` and `display_symbol` from here, so a
symbol looks the same everywhere.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import sympy
from sympy.printing.mathml import MathMLPresentationPrinter

#: Greek letters a name may start with (sympy typesets these as letters).
_GREEK = (
    "alpha",
    "beta",
    "gamma",
    "delta",
    "epsilon",
    "zeta",
    "eta",
    "theta",
    "iota",
    "kappa",
    "lambda",
    "mu",
    "nu",
    "xi",
    "omicron",
    "pi",
    "rho",
    "sigma",
    "tau",
    "upsilon",
    "phi",
    "chi",
    "psi",
    "omega",
)


def display_name(name: str) -> str:
    """The name with an underscore between the quantity and its subscript: ``rp1`` ->
    ``r_p1``, ``N4`` -> ``N_4``, ``tau_in`` and ``D_P`` unchanged, ``rs`` -> ``r_s``,
    ``eta_C_1`` -> ``eta_C,1``.

    The quantity is a leading Greek word or else the first letter; a name that already
    has an underscore, or that is that one letter or word alone, is kept."""
    if name.count("_") > 1:
        # eta_C_1 (Buckingham's pinion-driving efficiency of mesh C): one subscript "C,1".
        base, *subscripts = name.split("_")
        return f"{base}_{','.join(subscripts)}"
    if "_" in name or not name[:1].isalpha():
        return name
    if name in _GREEK:
        return name
    for word in sorted(_GREEK, key=len, reverse=True):
        # eta2, etaC: a Greek quantity; pin, mux: not (lower-case letter after the word).
        if name.startswith(word) and len(name) > len(word) and not name[len(word)].islower():
            return f"{word}_{name[len(word) :]}"
    return name if len(name) == 1 else f"{name[0]}_{name[1:]}"


def display_symbol(symbol: sympy.Symbol) -> sympy.Symbol:
    """The symbol under its display name (same assumptions), for printers that split
    names at the underscore themselves (sympy's MathML printer)."""
    return sympy.Symbol(display_name(symbol.name), **symbol.assumptions0)


def symbol_names(symbols: Iterable[sympy.Symbol]) -> dict[sympy.Symbol, str]:
    """``symbol_names`` argument of `sympy.latex`: each symbol's LaTeX (``cos_gamma``, the
    symbol a skew mesh defines as cos(gamma), is `\\cos\\gamma`)."""
    return {s: _function_latex(s.name) or sympy.latex(display_symbol(s)) for s in symbols}


def _function_latex(name: str) -> str | None:
    """``\\cos\\gamma`` for ``cos_gamma``, ``\\sin\\alpha_{n}`` for ``sin_alpha_n``; None otherwise."""
    function, _, rest = name.partition("_")
    if function not in ("cos", "sin") or not rest:
        return None
    inner = sympy.latex(sympy.Symbol(display_name(rest)))
    return f"\\{function}{{{inner}}}"


def latex(expr: sympy.Basic, **settings: object) -> str:
    """`sympy.latex` with every symbol under its display name; the order of the
    terms stays sympy's order of the original names."""
    return str(sympy.latex(expr, symbol_names=symbol_names(expr.free_symbols), **settings))


class _MathML(MathMLPresentationPrinter):  # type: ignore[misc]  # sympy has no type information
    """sympy's presentation MathML with every power of a subscripted symbol as one
    ``msubsup`` (r with 1 below and 2 above), not a superscript on the subscript."""

    def doprint(self, expr: sympy.Basic) -> str:
        node = self._print(expr)
        _join_scripts(node)
        return str(node.toxml().encode("ascii", "xmlcharrefreplace").decode())


def _join_scripts(node: Any) -> None:
    """Each ``<msup><msub>b s</msub> e</msup>`` under ``node`` as ``<msubsup>b s e</msubsup>``."""
    for child in list(node.childNodes):
        _join_scripts(child)
    if node.nodeName == "msup" and node.firstChild is not None and node.firstChild.nodeName == "msub":
        subscripted = node.firstChild
        node.tagName = node.nodeName = "msubsup"
        for part in list(subscripted.childNodes):
            node.insertBefore(part, subscripted)
        node.removeChild(subscripted)


def mathml_body(expr: sympy.Basic) -> str:
    """Presentation MathML of the expression (the content of a ``<math>`` element,
    rendered natively by browsers), symbols under their display names."""
    renamed = expr.xreplace({s: _mathml_symbol(s) for s in expr.free_symbols if isinstance(s, sympy.Symbol)})
    body = str(_MathML({"mul_symbol": None}).doprint(renamed))
    # The printer writes the relations' operators unescaped, which is not XML, and the
    # hyphen where typesetting has the minus sign.
    return (
        body.replace("<mo><</mo>", "<mo>&lt;</mo>")
        .replace("<mo>></mo>", "<mo>&gt;</mo>")
        .replace("<mo>-</mo>", "<mo>&#8722;</mo>")
    )


def _mathml_symbol(symbol: sympy.Symbol) -> sympy.Expr:
    """The symbol under its display name; ``cos_gamma`` as the function cos(gamma) it stands for."""
    function, _, rest = symbol.name.partition("_")
    if function in ("cos", "sin") and rest:
        return getattr(sympy, function)(sympy.Symbol(display_name(rest)), evaluate=False)
    return display_symbol(symbol)


def mathml(expr: sympy.Basic, display: bool = False) -> str:
    """The ``<math>`` element of `mathml_body` (a block when ``display``)."""
    mode = ' display="block"' if display else ""
    return f'<math xmlns="http://www.w3.org/1998/Math/MathML"{mode}>{mathml_body(expr)}</math>'
