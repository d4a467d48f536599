"""Generated Python module of a train's efficiency (``derive FILE --python OUT``).

The module depends on numpy only and is meant for design code (sweeps, optimisers):

- ``efficiency(input=..., errors=..., **params)`` on scalars or arrays (broadcast
  together) picks the variant element by element from the turning conditions, and gives
  NaN with a warning (or raises, ``errors='raise'``) where the design lies outside the
  admissible parameters or the train self-locks (efficiency outside (0, 1]);
- one function per variant named by its ports and condition signs, one per turning
  condition, ``speed_ratio`` and ``losses`` (power lost in each friction element over the
  input power, adding up to 1 - efficiency);
- ``PARAMETERS`` (name, meaning, unit, admissible range), ``RELATIONS`` (expressions
  positive on an admissible design), ``CONDITIONS`` and ``VARIANTS`` (conditions and
  formula as text and as LaTeX), the source in the module docstring.

Each function's common subexpressions are computed once (sympy ``cse``).  The text is
deterministic (the same train gives the same bytes) and passes ``ruff`` and
``mypy --strict``.
"""

from __future__ import annotations

import keyword
import os
import textwrap
from collections.abc import Sequence

import sympy
from sympy.printing.numpy import NumPyPrinter

from davies_sym.algebra.radicals import restore
from davies_sym.efficiency.parameters import Parameter, admissible_relations, eliminated_symbols, parameter_table
from davies_sym.efficiency.power_losses import all_loss_fractions, lossy_couplings
from davies_sym.efficiency.variants import Variant, VariantSet
from davies_sym.emit.variant_report import condition_text, mesh_text
from davies_sym.errors import DerivationError

WIDTH = 110
#: Names the module itself uses; a parameter may not take them.
RESERVED = frozenset({"input", "errors", "np", "warnings", "values", "annotations", "Any", "ArrayLike", "NDArray",
                      "Array", "Callable", "Final", "TypedDict"})
_TEMPORARY = "_t"


def _code(expr: sympy.Expr) -> str:
    return str(NumPyPrinter({"fully_qualified_modules": True}).doprint(expr)).replace("numpy.", "np.")


def _wrapped(head: str, code: str, indent: str) -> list[str]:
    """``head + code`` on one line, or ``head + (`` with the code broken at spaces (the
    printed expressions hold no strings, so any space is a safe break)."""
    if len(indent + head + code) <= WIDTH:
        return [indent + head + code]
    body = textwrap.wrap(code, WIDTH - len(indent) - 4, break_long_words=False, break_on_hyphens=False)
    return [indent + head + "("] + [indent + "    " + line for line in body] + [indent + ")"]


def _string(head: str, text: str, indent: str, suffix: str = ",") -> list[str]:
    """``head`` and a string literal, split into adjacent literals when long."""
    if len(indent + head + repr(text) + suffix) <= WIDTH:
        return [indent + head + repr(text) + suffix]
    step = WIDTH - len(indent) - 12
    chunks = [indent + "    " + repr(text[i:i + step]) for i in range(0, len(text), step)]
    return [indent + head + "(", *chunks, indent + ")" + suffix]


def _strings(head: str, texts: Sequence[str], indent: str) -> list[str]:
    """``head`` and a tuple of string literals."""
    one = head + _tuple(texts) + ","
    if len(indent + one) <= WIDTH:
        return [indent + one]
    out = [indent + head + "("]
    for t in texts:
        out += _string("", t, indent + "    ")
    return [*out, indent + "),"]


def _doc_text(text: str) -> str:
    """``text`` safe inside a triple-quoted docstring: backslashes and quotes escaped, one line."""
    text = "".join(ch if ch.isprintable() else " " for ch in text)
    return text.replace("\\", "\\\\").replace('"', '\\"')


def _docstring(text: str, indent: str) -> list[str]:
    lines = textwrap.wrap(_doc_text(text), WIDTH - len(indent) - 6)
    if len(lines) == 1:
        return [f'{indent}"""{lines[0]}"""']
    return [f'{indent}"""{lines[0]}'] + [indent + line for line in lines[1:]] + [f'{indent}"""']


def _signature(name: str, params: Sequence[str], returns: str) -> list[str]:
    line = f"def {name}(*, {', '.join(params)}) -> {returns}:" if params else f"def {name}() -> {returns}:"
    if len(line) <= WIDTH:
        return [line]
    return [f"def {name}(", "    *,"] + [f"    {p}," for p in params] + [f") -> {returns}:"]


def _names(exprs: Sequence[sympy.Expr]) -> list[str]:
    symbols: set[sympy.Basic] = set()
    for e in exprs:
        symbols |= e.free_symbols
    return sorted(str(s) for s in symbols)


def _function(name: str, doc: str, exprs: Sequence[sympy.Expr], returns: str = "Array",
              relations: bool = False) -> tuple[list[str], list[str]]:
    """A function of the symbols of ``exprs`` returning them (one: an array, several: a
    tuple; ``relations``: whether every expression is positive), common subexpressions
    shared; also the argument names."""
    args = _names(exprs)
    lines = _signature(name, [f"{a}: ArrayLike" for a in args], returns)
    lines += _docstring(doc, "    ")
    lines += [f"    {a} = _array({a})" for a in args]
    temporaries = sympy.numbered_symbols(_TEMPORARY)
    replacements, reduced = sympy.cse(list(exprs), symbols=temporaries, order="canonical")
    for symbol, value in replacements:
        lines += _wrapped(f"{symbol} = ", _code(value), "    ")
    if relations:
        lines += _wrapped("return ", f"np.asarray({_code(reduced[0])} > 0)", "    ")
    elif len(reduced) == 1:
        lines += _wrapped("return ", f"_array({_code(reduced[0])})", "    ")
    else:
        lines += _wrapped("return ", "(" + ", ".join(f"_array({_code(e)})" for e in reduced) + ")", "    ")
    return [*lines, "", ""], args


def _check_names(variants: VariantSet, names: Sequence[str]) -> None:
    for n in names:
        if n in RESERVED or keyword.iskeyword(n) or n.startswith(_TEMPORARY):
            raise DerivationError(f"{variants.train.path or variants.train.name}: the symbol {n!r} clashes with a "
                                  "name of the generated module; rename it in the topology file")


def _where(variants: VariantSet, variant: Variant) -> str:
    conditions = condition_text(variants, variant)
    return f"input {variant.input}, output {variant.output}" + (f", where {' and '.join(conditions)}"
                                                                  if conditions else "")


def _region(variants: VariantSet, variant: Variant) -> int:
    """Bit k set where condition k is negative (the code ``_region`` computes)."""
    return sum(1 << k for k, c in enumerate(variants.conditions) if variant.signs[c.name] < 0)


def _header(variants: VariantSet) -> list[str]:
    train = variants.train
    origin = os.path.basename(train.path) if train.path else "a topology file"
    lines = textwrap.wrap(f'"""Efficiency of {_doc_text(train.name)}: every turning-condition variant.', WIDTH)
    lines += ["", *textwrap.wrap(f"Source: {_doc_text(train.source or 'not given')}.", WIDTH),
              *textwrap.wrap(f"Generated by davies_sym from {_doc_text(origin)}; do not edit.", WIDTH), ""]
    eliminated = eliminated_symbols(variants)
    if eliminated:
        given = ", ".join(f"{k} = {sympy.sstr(v)}" for k, v in sorted(eliminated.items(), key=lambda kv: str(kv[0])))
        lines += [*textwrap.wrap(f"The geometric constraints give {given}; the formulas use the other radii.", WIDTH),
                  ""]
    lines += textwrap.wrap(
        "efficiency(**params) takes the parameters of PARAMETERS (scalars or numpy arrays, broadcast together), "
        "picks the variant element by element from the turning conditions and the input port, and gives NaN "
        "with a DesignWarning (errors='raise': a DesignError) where the design is outside the admissible "
        "parameters or self-locks.  speed_ratio and losses work the same way.", WIDTH)
    return [*lines, '"""', "", "from __future__ import annotations", "", "import warnings",
            "from collections.abc import Callable", "from typing import Any, Final, TypedDict", "",
            "import numpy as np", "from numpy.typing import ArrayLike, NDArray", "",
            "Array = NDArray[np.float64]", "", ""]


_TYPES = '''class Parameter(TypedDict):
    """A parameter of the formulas and its admissible range (low excluded unless closed_low)."""

    name: str
    meaning: str
    unit: str
    low: float
    high: float
    closed_low: bool


class Variant(TypedDict):
    """One formula of the efficiency and where it holds."""

    name: str
    number: int
    input: str
    output: str
    region: int
    conditions: tuple[str, ...]
    conditions_latex: tuple[str, ...]
    meshes: tuple[str, ...]
    formula: str
    latex: str
    feasible: bool


class DesignWarning(RuntimeWarning):
    """Some design points are outside the admissible parameters or self-lock (NaN there)."""


class DesignError(ValueError):
    """Raised instead of DesignWarning with errors='raise'."""
'''

_SELECTION = '''def _array(value: ArrayLike) -> Array:
    return np.asarray(value, dtype=np.float64)


def _region(values: dict[str, Array], shape: tuple[int, ...]) -> NDArray[np.int64]:
    """Bit k set where turning condition k is negative."""
    code = np.zeros(shape, dtype=np.int64)
    for bit, (function, names) in enumerate(_CONDITIONS.values()):
        code |= np.asarray(function(**{n: values[n] for n in names}) < 0, dtype=np.int64) << bit
    return code


def _select(input: str, values: dict[str, Array], table: _Table, width: int) -> Array:
    """The function of the variant that holds, evaluated element by element (each
    variant only on its own points); shape (width, *broadcast shape)."""
    if input not in PORTS:
        raise ValueError(f"input must be one of {PORTS}, got {input!r}")
    shape = np.broadcast_shapes(*(v.shape for v in values.values()))
    result = np.full((width, *shape), np.nan)
    with np.errstate(all="ignore"):
        code = _region(values, shape)
        for variant in VARIANTS:
            if variant["input"] != input:
                continue
            function, names = table[variant["name"]]
            mask = code == variant["region"]
            if mask.all():
                parts = function(**{n: values[n] for n in names})
                for k, part in enumerate(parts if isinstance(parts, tuple) else (parts,)):
                    result[k, ...] = part
            elif mask.any():
                chosen = {n: values[n] if values[n].ndim == 0 else np.broadcast_to(values[n], shape)[mask]
                          for n in names}
                parts = function(**chosen)
                for k, part in enumerate(parts if isinstance(parts, tuple) else (parts,)):
                    result[k, mask] = part
    return result


def _consistent(given: dict[str, ArrayLike | None], values: dict[str, Array]) -> None:
    """Refuse a dependent parameter (DEPENDENT) whose value breaks its relation."""
    for name, value in given.items():
        if value is None:
            continue
        function, names = _DEPENDENT[name]
        implied = np.broadcast_to(function(**{n: values[n] for n in names}), np.shape(value))
        bad = ~np.isclose(_array(value), implied, rtol=1e-9, atol=0.0)
        if bad.any():
            k = np.flatnonzero(bad)[0]
            actual = np.ravel(_array(value))[k]
            expected = np.ravel(implied)[k]
            raise DesignError(f"{name} = {actual} breaks the relation {DEPENDENT[name]}, which gives {expected}; "
                              f"the difference is {actual - expected}")


def _admissible(values: dict[str, Array]) -> NDArray[np.bool_]:
    """Where every parameter is in its range and every relation positive."""
    shape = np.broadcast_shapes(*(v.shape for v in values.values()))
    ok = np.ones(shape, dtype=bool)
    with np.errstate(all="ignore"):
        for p in PARAMETERS:
            if p["name"] not in values:
                continue
            v = values[p["name"]]
            ok &= ((v >= p["low"]) if p["closed_low"] else (v > p["low"])) & (v <= p["high"])
        for function, names in _RELATIONS.values():
            if all(n in values for n in names):
                ok &= function(**{n: values[n] for n in names})
    return ok


def _screened(result: Array, values: dict[str, Array], errors: str) -> Array:
    """NaN (with a warning, or an error) where the design is not admissible or self-locks."""
    if errors not in ("warn", "raise", "ignore"):
        raise ValueError(f"errors must be 'warn', 'raise' or 'ignore', got {errors!r}")
    outside = ~_admissible(values)
    with np.errstate(invalid="ignore"):
        locked = ~((result > 0) & (result <= 1 + 1e-12)) & ~outside
    if not (outside.any() or locked.any()):
        return result
    message = (f"{int(np.count_nonzero(outside))} design point(s) outside the admissible parameters "
               f"(PARAMETERS, RELATIONS) and {int(np.count_nonzero(locked))} where the train self-locks "
               "(efficiency outside (0, 1]): NaN there")
    if errors == "raise":
        raise DesignError(message)
    if errors == "warn":
        warnings.warn(message, DesignWarning, stacklevel=3)
    return np.where(outside | locked, np.nan, result)


'''


def _constants(variants: VariantSet, parameters: Sequence[Parameter],
               relations: Sequence[sympy.Expr], lossy: Sequence[str]) -> list[str]:
    train = variants.train
    lines = [f"PORTS: Final[tuple[str, str]] = ({train.ports.input!r}, {train.ports.output!r})",
             f"LOSSY: Final[tuple[str, ...]] = {_tuple(lossy)}",
             "PARAMETERS: Final[tuple[Parameter, ...]] = ("]
    for p in parameters:
        lines += ["    {", f"        'name': {p.name!r},", *_string("'meaning': ", p.meaning, "        "),
                  f"        'unit': {p.unit!r},", f"        'low': {_float(p.low)},",
                  f"        'high': {_float(p.high)},", f"        'closed_low': {p.closed_low!r},", "    },"]
    lines += [")"]
    lines += _strings("RELATIONS: Final[tuple[str, ...]] = ", [f"{sympy.sstr(r)} > 0" for r in relations], "")
    lines[-1] = lines[-1].rstrip(",")
    lines.append("DEPENDENT: Final[dict[str, str]] = {")
    for r in train.dependent or ():
        lines += _wrapped(f"{str(r.symbol)!r}: ", f"{str(r)!r},", "    ")
    lines.append("}")
    lines.append("CONDITIONS: Final[dict[str, tuple[str, str]]] = {")
    for c in variants.conditions:
        lines += _strings(f"{c.name!r}: ", (sympy.sstr(c.simplified), sympy.latex(c.simplified)), "    ")
    lines += ["}", "VARIANTS: Final[tuple[Variant, ...]] = ("]
    for v in variants.variants:
        latex = tuple(f"{sympy.latex(c.simplified)} {'>' if v.signs[c.name] > 0 else '<'} 0"
                      for c in variants.conditions)
        lines += ["    {", f"        'name': {v.name!r},", f"        'number': {v.number},",
                  f"        'input': {v.input!r},", f"        'output': {v.output!r},",
                  f"        'region': {_region(variants, v)},",
                  *_strings("'conditions': ", condition_text(variants, v), "        "),
                  *_strings("'conditions_latex': ", latex, "        "),
                  *_strings("'meshes': ", mesh_text(variants, v), "        "),
                  *_string("'formula': ", sympy.sstr(v.efficiency), "        "),
                  *_string("'latex': ", sympy.latex(v.efficiency), "        "),
                  f"        'feasible': {v.feasible!r},", "    },"]
    return [*lines, ")", "", ""]


def _tuple(items: Sequence[object]) -> str:
    return "(" + ", ".join(repr(i) for i in items) + ("," if len(items) == 1 else "") + ")"


def _float(value: float) -> str:
    return repr(value) if abs(value) != float("inf") else ("float('inf')" if value > 0 else "float('-inf')")


def _table(name: str, entries: Sequence[tuple[str, str, Sequence[str]]]) -> list[str]:
    lines = [f"{name}: Final[_Table] = {{"]
    for key, function, args in entries:
        lines += _wrapped(f"{key!r}: ", f"({function}, {_tuple(args)}),", "    ")
    return [*lines, "}"]


def _entry_point(name: str, doc: str, symbols: Sequence[str], returns: str, body: Sequence[str],
                 default_input: str, screened: bool = True,
                 dependent: Sequence[tuple[str, Sequence[str]]] = ()) -> list[str]:
    """An entry point taking ``symbols``, and the ``dependent`` parameters (name, the
    symbols their relation needs) optionally, checked against their relations."""
    params = [f"input: str = {default_input!r}"] + (["errors: str = 'warn'"] if screened else [])
    params += [f"{s}: ArrayLike" for s in symbols]
    checked = [d for d, needs in dependent if set(needs) <= set(symbols)]
    params += [f"{d}: ArrayLike | None = None" for d in checked]
    lines = _signature(name, params, returns) + _docstring(doc, "    ")
    arrays = ", ".join(f"{s!r}: _array({s})" for s in symbols)
    lines += _wrapped("values: dict[str, Array] = ", "{" + arrays + "}", "    ")
    if checked:
        lines += _wrapped("_consistent(", "{" + ", ".join(f"{d!r}: {d}" for d in checked) + "}, values)", "    ")
    return [*lines, *body, "", ""]


def python_module(variants: VariantSet) -> str:
    """Source text of the module."""
    train = variants.train
    symbols = [str(s) for s in variants.symbols]
    _check_names(variants, symbols)
    parameters = parameter_table(variants)
    relations = admissible_relations(variants)
    lossy = lossy_couplings(variants)
    radicals = variants.analysis.network.layout.radicals
    lines = [*_header(variants), _TYPES, ""]
    lines += ["_Table = dict[str, tuple[Callable[..., Any], tuple[str, ...]]]", "", ""]
    lines += _constants(variants, parameters, relations, lossy)
    conditions = []
    for c in variants.conditions:
        code, args = _function(f"condition_{c.name}", f"Turning condition {c.name}: {sympy.sstr(c.simplified)}.",
                               [restore(c.expression, radicals)])
        lines += code
        conditions.append((c.name, f"condition_{c.name}", args))
    relation_table = []
    for k, r in enumerate(relations, start=1):
        code, args = _function(f"_relation_{k}", f"Whether {sympy.sstr(r)} > 0.", [r], "NDArray[np.bool_]",
                               relations=True)
        lines += code
        relation_table.append((f"{sympy.sstr(r)} > 0", f"_relation_{k}", args))
    efficiency, losses = [], []
    fractions_of = all_loss_fractions(variants)
    for v in variants.variants:
        doc = f"Variant ({v.number}): {_where(variants, v)}.  " + "; ".join(mesh_text(variants, v)) + "."
        code, args = _function(v.name, doc, [restore(v.efficiency, radicals)])
        lines += code
        efficiency.append((v.name, v.name, args))
        fractions = fractions_of[v.name]
        code, args = _function(f"_losses_{v.name}", f"Losses over the input power in variant ({v.number}).",
                               [restore(fractions[n].to_expr(), radicals) for n in lossy],
                               "tuple[Array, ...]" if len(lossy) > 1 else "Array")
        lines += code
        losses.append((v.name, f"_losses_{v.name}", args))
    dependent = []
    for r in train.dependent or ():
        code, args = _function(f"_dependent_{r.symbol}", f"{r} (the geometric constraint {r.constraint}).",
                               [restore(r.expression, radicals)])
        lines += code
        dependent.append((str(r.symbol), f"_dependent_{r.symbol}", args))
    ratio = restore(variants.analysis.speed_ratio().to_expr(), radicals)
    code, ratio_args = _function("_speed_ratio", f"Speed ratio with {train.ports.input} as input.", [ratio])
    lines += code
    lines += _table("_CONDITIONS", conditions) + _table("_RELATIONS", relation_table) + _table("_DEPENDENT", dependent)
    lines += _table("_EFFICIENCY", efficiency) + _table("_LOSSES", losses) + ["", "", _SELECTION.rstrip("\n"), "", ""]
    lines += _entry_point(
        "efficiency", "Overall efficiency -P_out/P_in with `input` as the input port, the variant chosen element "
        "by element; NaN where the design is not admissible or self-locks (errors: 'warn', 'raise', 'ignore').",
        symbols, "Array", ["    (result,) = _select(input, values, _EFFICIENCY, 1)",
                           "    return _screened(result, values, errors)"], train.ports.input,
        dependent=[(d, args) for d, _, args in dependent])
    lines += _entry_point(
        "losses", "Power lost in each element of LOSSY over the input power (they add up to 1 - efficiency), "
        "the variant chosen element by element; NaN where efficiency is.", symbols, "dict[str, Array]",
        ["    (result,) = _select(input, values, _EFFICIENCY, 1)",
         "    bad = np.isnan(_screened(result, values, errors))",
         "    parts = _select(input, values, _LOSSES, len(LOSSY))",
         "    return {name: np.where(bad, np.nan, part) for name, part in zip(LOSSY, parts, strict=True)}"],
        train.ports.input, dependent=[(d, args) for d, _, args in dependent])
    lines += _entry_point(
        "speed_ratio", f"Input speed over output speed with `input` as the input port ({sympy.sstr(ratio)} with "
        f"{train.ports.input} as input).", ratio_args, "Array",
        ["    if input not in PORTS:",
         "        raise ValueError(f'input must be one of {PORTS}, got {input!r}')",
         "    ratio = _speed_ratio(**values)",
         f"    return ratio if input == {train.ports.input!r} else _array(1 / ratio)"],
        train.ports.input, screened=False, dependent=[(d, args) for d, _, args in dependent])
    while lines[-1] == "":
        lines.pop()
    return "\n".join(lines) + "\n"
